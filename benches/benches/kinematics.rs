//! Inverse kinematics and wrench matrix (cdpr-kinematics).

use cdpr_benches::goals::{CatenarySolve, ElasticForward, Goal, NoisyForward, forward_problems};
use cdpr_benches::{ipanema_like_8, ipanema_like_8_pulleys, spatial_poses};
use cdpr_kinematics::{ForwardKinematics, ForwardSettings, MotionPattern, Pose, PoseKinematics};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::DMatrix;
use std::hint::black_box;

fn inverse_kinematics(c: &mut Criterion) {
    let robot = ipanema_like_8();
    let poses = spatial_poses(1000);
    let mut kin = PoseKinematics::for_robot(&robot);
    let mut w = DMatrix::zeros(6, 8);
    let mut g = c.benchmark_group("kinematics");
    // One iteration = one pose: IK of 8 cables + the 6 × 8 wrench matrix, no allocation.
    let mut k = 0;
    g.bench_function("ik_and_wrench_matrix/spatial_8", |b| {
        b.iter(|| {
            k = (k + 1) % poses.len();
            robot
                .update_kinematics(black_box(&poses[k]), &mut kin)
                .unwrap();
            kin.write_wrench_matrix(&mut w);
            black_box(w[(5, 7)])
        })
    });
    // The same with a 0.05 m swivel pulley at every anchor (Pott 2018 model, issue budget 150 ns).
    let robot = ipanema_like_8_pulleys();
    let mut k = 0;
    g.bench_function("ik_w_8_spatial_pulley", |b| {
        b.iter(|| {
            k = (k + 1) % poses.len();
            robot
                .update_kinematics(black_box(&poses[k]), &mut kin)
                .unwrap();
            kin.write_wrench_matrix(&mut w);
            black_box(w[(5, 7)])
        })
    });
    g.finish();
}

fn forward_kinematics(c: &mut Criterion) {
    let poses = spatial_poses(1000);
    let mut g = c.benchmark_group("kinematics");
    // One iteration = one Levenberg–Marquardt solve (issue budget 2 µs) with its certificate.
    for (name, robot) in [
        ("fk_8_spatial_standard", ipanema_like_8()),
        ("fk_8_spatial_pulley", ipanema_like_8_pulleys()),
    ] {
        let problems = forward_problems(&robot, &poses);
        let mut fk = ForwardKinematics::new(&robot, ForwardSettings::default()).unwrap();
        let mut k = 0;
        g.bench_function(name, |b| {
            b.iter(|| {
                k = (k + 1) % problems.len();
                let (l, guess) = &problems[k];
                black_box(fk.solve(black_box(l), guess).unwrap().residual)
            })
        });
    }
    // Issue 27: measured lengths (noise of about 0.1 mm, deterministic): the least-squares pose
    // with its `fitted` test, residual_rms and pose standard deviations (budget 5 µs).
    let mut noisy = NoisyForward::new();
    g.bench_function("fk_8_spatial_noisy", |b| b.iter(|| black_box(noisy.run())));
    g.finish();
}

/// The loop behind the Python package's `Robot.inverse_kinematics` for a batch (python/), on one
/// thread: pose coordinates → pose → IK → W, written into flat row-major buffers (lengths, unit
/// vectors, W, attachment points). `python/benchmarks/bench.py` compares the package with it.
fn batch_from_coordinates(c: &mut Criterion) {
    const N: usize = 100_000;
    let robot = ipanema_like_8();
    let n = robot.cable_count();
    let q: Vec<f64> = spatial_poses(N)
        .iter()
        .flat_map(|p| p.coordinates(MotionPattern::Spatial))
        .collect();
    let (mut l, mut u, mut wm, mut a) = (
        vec![0.0; N * n],
        vec![0.0; N * 3 * n],
        vec![0.0; N * 6 * n],
        vec![0.0; N * 3 * n],
    );
    let mut kin = PoseKinematics::for_robot(&robot);
    let mut w = DMatrix::zeros(6, n);
    let mut g = c.benchmark_group("kinematics_batch");
    g.throughput(Throughput::Elements(N as u64));
    g.sample_size(20);
    g.bench_function("ik_and_wrench_matrix_from_coordinates/spatial_8", |b| {
        b.iter(|| {
            for k in 0..N {
                let pose =
                    Pose::from_coordinates(MotionPattern::Spatial, &q[6 * k..6 * k + 6]).unwrap();
                robot.update_kinematics(&pose, &mut kin).unwrap();
                kin.write_wrench_matrix(&mut w);
                for (i, s) in kin.cables().iter().enumerate() {
                    l[k * n + i] = s.length;
                    u[3 * (k * n + i)..3 * (k * n + i) + 3].copy_from_slice(s.unit.as_slice());
                    a[3 * (k * n + i)..3 * (k * n + i) + 3]
                        .copy_from_slice(s.attachment_point.as_slice());
                }
                for r in 0..6 {
                    for j in 0..n {
                        wm[k * 6 * n + r * n + j] = w[(r, j)];
                    }
                }
            }
            black_box((l[0], u[0], wm[0], a[0]))
        })
    });
    g.finish();
}

/// The interference criterion's two tests at one pose of the 8-cable robot: the 28 cable-pair
/// segment distances, and 8 cable segments against a box platform (6 faces).
fn interference(c: &mut Criterion) {
    let robot = ipanema_like_8();
    let poses = spatial_poses(1000);
    let kins: Vec<PoseKinematics> = poses
        .iter()
        .map(|p| robot.inverse_kinematics(p).unwrap())
        .collect();
    let shape = cdpr_kinematics::ConvexPolyhedron::cuboid(
        nalgebra::Vector3::new(0.2, 0.2, 0.1),
        nalgebra::Vector3::zeros(),
    )
    .unwrap();
    let mut g = c.benchmark_group("interference");
    let mut k = 0;
    g.bench_function("min_cable_distance/spatial_8", |b| {
        b.iter(|| {
            k = (k + 1) % kins.len();
            black_box(cdpr_kinematics::min_cable_distance(black_box(&kins[k])))
        })
    });
    g.bench_function("platform_penetration/spatial_8_box", |b| {
        b.iter(|| {
            k = (k + 1) % kins.len();
            black_box(cdpr_kinematics::platform_interference(
                black_box(&kins[k]),
                &shape,
                &poses[k].position,
                &poses[k].rotation,
            ))
        })
    });
    g.finish();
}

/// Issue 29 budget: one catenary solve (span, platform-end tension → L0 and forces) ≤ 1 µs
/// ([`CatenarySolve`]: the example cable at 100 spans around its span).
fn elastic_catenary(c: &mut Criterion) {
    let mut goal = CatenarySolve::new();
    let mut g = c.benchmark_group("elastic_catenary");
    g.throughput(Throughput::Elements(CatenarySolve::UNITS));
    g.bench_function("solve_for_tension", |b| b.iter(|| black_box(goal.run())));
    g.bench_function("solve_for_length", |b| {
        b.iter(|| black_box(goal.run_for_length()))
    });
    g.finish();
}

/// Issue 29 budget: elastic forward kinematics ≤ 10 µs ([`ElasticForward`]: 100 poses,
/// weightless `elastic` and 0.02 kg/m `catenary` cables).
fn elasto_geometric_forward(c: &mut Criterion) {
    let mut g = c.benchmark_group("elasto_geometric_forward");
    g.throughput(Throughput::Elements(ElasticForward::UNITS));
    for (name, mut goal) in [
        ("elastic_spatial_8", ElasticForward::elastic()),
        ("catenary_spatial_8", ElasticForward::catenary()),
    ] {
        g.bench_function(name, |b| b.iter(|| black_box(goal.run())));
    }
    g.finish();
}

criterion_group!(
    benches,
    inverse_kinematics,
    forward_kinematics,
    batch_from_coordinates,
    interference,
    elastic_catenary,
    elasto_geometric_forward
);
criterion_main!(benches);
