//! Issue 26's throughput table (issue 17's operations plus the peers' methods) on issue 26's
//! fixture, WireLib's own robot: `CIPAnema1Design` (Pott et al. 2013; 8 cables, 6 DOF), bounds
//! t ∈ [1, 1000] N, w = (0, 0, −245.25 N, 0, 0, 0), 20 000 poses with x, y ∈ [−1, 1] m,
//! z ∈ [0.3, 1.7] m, XYZ angles in [−0.1, 0.1] rad (`cdpr_benches::issue_26`). Every tension
//! answer is certified (as in every `TensionSolver` call).
//!
//! One iteration runs all 20 000 poses (criterion's throughput gives the rate; CPU time per call
//! = time / 20 000). IDs: `throughput_ipanema_1/{ik_w, ik_w_batch, ik_w_batch_portable,
//! improved_closed_form, barycenter, l2, l1, linf, pott_closed_form, pott_closed_form_ee,
//! puncture, dykstra, dykstra_alternating, l2_mid, vertex_centroid, p_norm, optimally_safe}`;
//! run with `cargo bench -p cdpr-benches --bench throughput`.

use cdpr_benches::issue_26::{POSES, fixture};
use cdpr_kinematics::{KinematicsError, Pose, PoseKinematics, Robot};
use cdpr_tension::{Method, MethodOptions, TensionProblem, TensionSolver};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::{DMatrix, DVector};
use std::hint::black_box;

fn ik_w(c: &mut Criterion) {
    let f = fixture();
    let mut g = c.benchmark_group("throughput_ipanema_1");
    g.throughput(Throughput::Elements(POSES as u64));
    g.sample_size(30);
    let mut kin = PoseKinematics::for_robot(&f.robot);
    let mut w = DMatrix::zeros(6, 8);
    g.bench_function("ik_w", |b| {
        b.iter(|| {
            let mut s = 0.0;
            for pose in &f.poses {
                f.robot
                    .update_kinematics(black_box(pose), &mut kin)
                    .unwrap();
                kin.write_wrench_matrix(&mut w);
                s += w[(5, 7)];
            }
            black_box(s)
        })
    });
    // The batch API: W of all 20 000 poses into one flat buffer; and the same API through the
    // portable (SSE2) build of its structure-of-arrays kernel, which CPUs without AVX2 run.
    let mut out = vec![0.0; POSES * 48];
    let mut valid = vec![false; POSES];
    type Batch = fn(&Robot, &[Pose], &mut [f64], &mut [bool]) -> Result<usize, KinematicsError>;
    let batches: [(&str, Batch); 2] = [
        ("ik_w_batch", Robot::wrench_matrices),
        ("ik_w_batch_portable", Robot::wrench_matrices_portable),
    ];
    for (name, batch) in batches {
        g.bench_function(name, |b| {
            b.iter(|| {
                let count = batch(&f.robot, black_box(&f.poses), &mut out, &mut valid).unwrap();
                black_box((count, out[POSES * 48 - 1]))
            })
        });
    }
    g.finish();
}

fn tension(c: &mut Criterion) {
    let f = fixture();
    let ws: Vec<DMatrix<f64>> = f
        .poses
        .iter()
        .map(|p| f.robot.inverse_kinematics(p).unwrap().wrench_matrix())
        .collect();
    let mut g = c.benchmark_group("throughput_ipanema_1");
    g.throughput(Throughput::Elements(POSES as u64));
    g.sample_size(20);
    let alternating = MethodOptions {
        alternating: true,
        ..MethodOptions::default()
    };
    let only = std::env::var("THROUGHPUT_ONLY").ok();
    for (name, method, options) in [
        ("improved_closed_form", Method::ImprovedClosedForm, None),
        ("barycenter", Method::Barycenter, None),
        ("l2", Method::L2, None),
        ("l1", Method::L1, None),
        ("linf", Method::Linf, None),
        ("pott_closed_form", Method::PottClosedForm, None),
        ("pott_closed_form_ee", Method::PottClosedFormEe, None),
        ("puncture", Method::Puncture, None),
        ("dykstra", Method::Dykstra, None),
        ("dykstra_alternating", Method::Dykstra, Some(alternating)),
        ("l2_mid", Method::L2Mid, None),
        ("vertex_centroid", Method::VertexCentroid, None),
        ("p_norm", Method::PNorm, None),
        ("optimally_safe", Method::OptimallySafe, None),
    ] {
        // THROUGHPUT_ONLY=a,b: skip the other methods' feasibility pass too.
        if only
            .as_deref()
            .is_some_and(|o| !o.split(',').any(|x| x == name))
        {
            continue;
        }
        let mut solver = TensionSolver::new(method)
            .with_options(options.unwrap_or_default())
            .unwrap();
        let mut t = DVector::zeros(8);
        let mut run = |solver: &mut TensionSolver| {
            let mut ok = 0usize;
            for w in &ws {
                let p = TensionProblem::new(w, &f.load, &f.bounds);
                ok += solver.solve_into(&p, &mut t).unwrap().is_ok() as usize;
            }
            ok
        };
        eprintln!("{name}: {} of {POSES} poses feasible", run(&mut solver));
        g.bench_function(name, |b| b.iter(|| black_box(run(&mut solver))));
    }
    g.finish();
}

criterion_group!(benches, ik_w, tension);
criterion_main!(benches);
