//! Tension distribution: per-pose cost of each method on 1000 feasible poses of the 8-cable
//! spatial robot (`ipanema_like_8`, t ∈ [1, 1000] N, 10 kg platform under gravity), and of the
//! closed form (Algorithm 6.1) on the thesis' planar 4-cable robot, and of the exact solution
//! (6.12) on the thesis' planar 3-cable robot (the workspace-grid hot path), and of the dense
//! active-set path (redundancy 5) against Clarabel on an 8-cable planar robot. Each iteration
//! solves all poses; criterion's throughput gives the per-pose cost.

use cdpr_benches::goals::{Goal, SaggingStatics, feasible_poses};
use cdpr_benches::{ipanema_like_8, twelve_cable_spatial};
use cdpr_kinematics::reference_robots::thesis_four_cable;
use cdpr_kinematics::{Cable, MotionPattern, Pose, PoseKinematics, Robot};
use cdpr_tension::{
    Method, Objective, SotdaSettings, SotdaVariant, StiffnessData, TensionBounds, TensionProblem,
    TensionSolver, interior_point,
};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::{DMatrix, DVector, Vector3};
use std::hint::black_box;

type Feasible = (
    Vec<(PoseKinematics, DMatrix<f64>)>,
    DVector<f64>,
    TensionBounds,
    Vec<f64>,
);

fn feasible_spatial(count: usize) -> Feasible {
    let (out, we, b) = feasible_poses(&ipanema_like_8(), count);
    (out, we, b, vec![80e9 * 0.75e-6; 8])
}

fn bench_spatial(c: &mut Criterion) {
    const N: usize = 1000;
    let (poses, we, b, es) = feasible_spatial(N);
    let mut g = c.benchmark_group("tension_8_cable");
    g.throughput(Throughput::Elements(N as u64));
    let mut run = |name: &str, mut solver: TensionSolver, stiff: bool| {
        let mut t = DVector::zeros(8);
        g.bench_function(name, |bch| {
            bch.iter(|| {
                let mut ok = 0;
                for p in &poses {
                    let problem = TensionProblem {
                        stiffness: stiff.then_some(StiffnessData {
                            kinematics: &p.0,
                            axial_stiffness: &es,
                        }),
                        ..TensionProblem::new(&p.1, &we, &b)
                    };
                    ok += solver.solve_into(&problem, &mut t).unwrap().is_ok() as usize;
                }
                black_box(ok)
            })
        });
    };
    run("l2", TensionSolver::new(Method::L2), false);
    run("l1", TensionSolver::new(Method::L1), false);
    run("linf", TensionSolver::new(Method::Linf), false);
    run("barycenter", TensionSolver::new(Method::Barycenter), false);
    run(
        "improved_closed_form",
        TensionSolver::new(Method::ImprovedClosedForm),
        false,
    );
    run("pinv", TensionSolver::new(Method::Pinv), false);
    run(
        "sotda_corners",
        TensionSolver::sotda(SotdaSettings {
            variant: SotdaVariant::Corners,
            ..SotdaSettings::default()
        }),
        true,
    );
    g.finish();
}

fn bench_planar(c: &mut Criterion) {
    let robot = thesis_four_cable();
    let we = DVector::from_vec(vec![0.0, -10.0, 0.0]);
    let b = TensionBounds::uniform(4, 5.0, 100.0).unwrap();
    let mut ws = Vec::new();
    for i in 0..=20 {
        for j in 0..=20 {
            let pose = Pose::planar(-0.5 + 0.05 * i as f64, -0.25 + 0.025 * j as f64, 0.0);
            ws.push(robot.inverse_kinematics(&pose).unwrap().wrench_matrix());
        }
    }
    let mut g = c.benchmark_group("tension_planar_4_cable");
    g.throughput(Throughput::Elements(ws.len() as u64));
    for (name, method) in [("closed_form", Method::ClosedForm), ("l1", Method::L1)] {
        let mut solver = TensionSolver::new(method);
        let mut t = DVector::zeros(4);
        g.bench_function(name, |bch| {
            bch.iter(|| {
                let mut ok = 0;
                for w in &ws {
                    let p = TensionProblem::new(w, &we, &b);
                    ok += solver.solve_into(&p, &mut t).unwrap().is_ok() as usize;
                }
                black_box(ok)
            })
        });
    }
    g.finish();
}

fn bench_planar_exact(c: &mut Criterion) {
    let robot = cdpr_kinematics::reference_robots::thesis_three_cable();
    let we = DVector::from_vec(vec![0.0, -10.0, 0.0]);
    let b = TensionBounds::uniform(3, 5.0, 100.0).unwrap();
    let mut ws = Vec::new();
    for i in 0..=20 {
        for j in 0..=20 {
            let pose = Pose::planar(-0.5 + 0.05 * i as f64, -0.5 + 0.05 * j as f64, 0.0);
            ws.push(robot.inverse_kinematics(&pose).unwrap().wrench_matrix());
        }
    }
    let mut g = c.benchmark_group("tension_planar_3_cable");
    g.throughput(Throughput::Elements(ws.len() as u64));
    let mut solver = TensionSolver::new(Method::Exact);
    let mut t = DVector::zeros(3);
    g.bench_function("exact", |bch| {
        bch.iter(|| {
            let mut ok = 0;
            for w in &ws {
                let p = TensionProblem::new(w, &we, &b);
                ok += solver.solve_into(&p, &mut t).unwrap().is_ok() as usize;
            }
            black_box(ok)
        })
    });
    g.bench_function("exact_is_feasible", |bch| {
        bch.iter(|| {
            let mut ok = 0;
            for w in &ws {
                let p = TensionProblem::new(w, &we, &b);
                ok += solver.is_feasible(&p).unwrap() as usize;
            }
            black_box(ok)
        })
    });
    g.finish();
}

/// A planar robot with 8 cables (redundancy 5): two cables from each corner of a 4 m × 2 m frame,
/// crossed onto the corners of a 0.2 m × 0.1 m platform.
fn planar_eight_cable() -> Robot {
    let mut cables = Vec::new();
    for (x, y) in [(2.0f64, 1.0f64), (-2.0, 1.0), (-2.0, -1.0), (2.0, -1.0)] {
        for (px, py) in [
            (0.1f64.copysign(x), 0.05f64.copysign(-y)),
            (0.1f64.copysign(-x), 0.05f64.copysign(y)),
        ] {
            cables.push(Cable {
                frame: Vector3::new(x, y, 0.0),
                platform: Vector3::new(px, py, 0.0),
                pulley: None,
            });
        }
    }
    Robot::new(MotionPattern::Planar, cables).expect("valid robot")
}

/// l2 and l1 at r = 5 on 121 poses of the 8-cable planar robot (all feasible), by the dense
/// active-set path of `TensionSolver` and by Clarabel (`interior_point`, the former path).
fn bench_planar_redundant(c: &mut Criterion) {
    let robot = planar_eight_cable();
    let we = DVector::from_vec(vec![0.0, -50.0, 0.5]);
    let b = TensionBounds::uniform(8, 5.0, 200.0).unwrap();
    let mut ws = Vec::new();
    for i in 0..=10 {
        for j in 0..=10 {
            let pose = Pose::planar(-1.0 + 0.2 * i as f64, -0.5 + 0.1 * j as f64, 0.05);
            ws.push(robot.inverse_kinematics(&pose).unwrap().wrench_matrix());
        }
    }
    for w in &ws {
        let p = TensionProblem::new(w, &we, &b);
        assert!(TensionSolver::new(Method::L2).is_feasible(&p).unwrap());
    }
    let mut g = c.benchmark_group("tension_planar_8_cable");
    g.throughput(Throughput::Elements(ws.len() as u64));
    for (name, method, objective) in [
        ("l2", Method::L2, Objective::L2),
        ("l1", Method::L1, Objective::L1),
    ] {
        let mut solver = TensionSolver::new(method);
        let mut t = DVector::zeros(8);
        g.bench_function(name, |bch| {
            bch.iter(|| {
                let mut ok = 0;
                for w in &ws {
                    let p = TensionProblem::new(w, &we, &b);
                    ok += solver.solve_into(&p, &mut t).unwrap().is_ok() as usize;
                }
                black_box(ok)
            })
        });
        assert_eq!(solver.clarabel_fallbacks(), 0);
        g.bench_function(format!("{name}_clarabel"), |bch| {
            bch.iter(|| {
                let mut ok = 0;
                for w in &ws {
                    let p = TensionProblem::new(w, &we, &b);
                    ok += interior_point(&p, objective).unwrap().is_ok() as usize;
                }
                black_box(ok)
            })
        });
    }
    g.finish();
}

/// l2-max at redundancy 6: 100 feasible poses of the 12-cable spatial robot
/// (`twelve_cable_spatial`, t ∈ [1, 1000] N, 10 kg platform under gravity). The former candidate
/// enumeration solved C(12, 6)·2⁶ = 59 136 systems per pose; the pivoting search visits only
/// the feasible bases (issue 13 §1, goal ≤ 100 µs per pose).
fn bench_twelve_cable_l2_max(c: &mut Criterion) {
    const N: usize = 100;
    let (poses, we, b) = feasible_poses(&twelve_cable_spatial(), N);
    let ws: Vec<DMatrix<f64>> = poses.into_iter().map(|p| p.1).collect();
    let mut g = c.benchmark_group("tension_12_cable");
    g.throughput(Throughput::Elements(N as u64));
    let mut solver = TensionSolver::new(Method::L2Max);
    let mut t = DVector::zeros(12);
    g.bench_function("l2_max", |bch| {
        bch.iter(|| {
            let mut ok = 0;
            for w in &ws {
                let p = TensionProblem::new(w, &we, &b);
                ok += solver.solve_into(&p, &mut t).unwrap().is_ok() as usize;
            }
            black_box(ok)
        })
    });
    g.finish();
}

/// Statics with sagging cables (issue 29 budget: ≤ 20 µs per pose): [`SaggingStatics`], the
/// fixed point with l2 on 100 of the feasible poses above, cables of 0.02 kg/m and E·S = 60 kN.
fn bench_sagging_statics(c: &mut Criterion) {
    let mut goal = SaggingStatics::new();
    let mut g = c.benchmark_group("sagging_statics");
    g.throughput(Throughput::Elements(SaggingStatics::UNITS));
    g.bench_function("l2_spatial_8", |b| b.iter(|| black_box(goal.run())));
    g.finish();
}

criterion_group!(
    benches,
    bench_sagging_statics,
    bench_spatial,
    bench_twelve_cable_l2_max,
    bench_planar,
    bench_planar_exact,
    bench_planar_redundant
);
criterion_main!(benches);
