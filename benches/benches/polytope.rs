//! Criterion benchmarks of cdpr-polytope, one group per method:
//! - `capacity_margin/hyperplane_shifting_8_spatial`: capacity margin of a gravity-centred box
//!   for the 8-cable spatial robot, per pose (W given; target ≤ 10 µs);
//! - `isotropic_force/seed001_point2`: the maximum isotropic force of Krut, Company & Pierrot's (2004) 3-motor robot,
//!   per pose, inverse kinematics and W included (target ≤ 200 ns);
//! - `available_wrench_set/*`: full facet lists by both methods, for reference;
//!   `hyperplane_shifting_10_spatial` (10 cables, 6 DOF, 504 half-spaces): target ≤ 100 µs.

use cdpr_benches::{
    ipanema_like_8, krut_poses, krut_three_motor, spatial_poses, ten_cable_spatial,
};
use cdpr_polytope::{
    CapacityMargin, CapacityMarginEvaluator, IsotropicForce, RequiredWrenchSet,
    hyperplane_shifting, krut_vertex_projection,
};
use cdpr_tension::TensionBounds;
use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::{DMatrix, DVector};
use std::hint::black_box;

fn capacity_margin(c: &mut Criterion) {
    let robot = ipanema_like_8();
    let poses = spatial_poses(64);
    let ws: Vec<DMatrix<f64>> = poses
        .iter()
        .map(|p| robot.inverse_kinematics(p).unwrap().wrench_matrix())
        .collect();
    let bounds = TensionBounds::uniform(8, 1.0, 1000.0).unwrap();
    // 10 kg platform under gravity, ±20 N / ±2 N·m of disturbance.
    let required = RequiredWrenchSet::boxed(
        DVector::from_vec(vec![0.0, 0.0, -98.1, 0.0, 0.0, 0.0]),
        DVector::from_vec(vec![20.0, 20.0, 20.0, 2.0, 2.0, 2.0]),
    )
    .unwrap();
    let cm = CapacityMarginEvaluator::new(&bounds, &required).unwrap();
    let mut g = c.benchmark_group("capacity_margin");
    let mut i = 0;
    g.bench_function("hyperplane_shifting_8_spatial", |b| {
        b.iter(|| {
            i = (i + 1) % ws.len();
            black_box(cm.margin(black_box(&ws[i])).unwrap())
        })
    });
    // The same through the per-call-checked API (bounds and required set passed each time).
    let mut legacy = CapacityMargin::new(6, 8);
    g.bench_function("hyperplane_shifting_8_spatial_unprepared", |b| {
        b.iter(|| {
            i = (i + 1) % ws.len();
            black_box(
                legacy
                    .margin(black_box(&ws[i]), &bounds, &required)
                    .unwrap(),
            )
        })
    });
    g.finish();
}

fn isotropic_force(c: &mut Criterion) {
    let robot = krut_three_motor();
    let poses = krut_poses(64);
    let bounds = TensionBounds::uniform(3, 50.0, 500.0).unwrap();
    let mut index = IsotropicForce::new(&robot, &bounds).unwrap();
    let mut g = c.benchmark_group("isotropic_force");
    let mut i = 0;
    g.bench_function("seed001_point2", |b| {
        b.iter(|| {
            i = (i + 1) % poses.len();
            black_box(index.force_at_pose(black_box(&poses[i])).unwrap())
        })
    });
    g.finish();
}

fn available_wrench_set(c: &mut Criterion) {
    let robot = krut_three_motor();
    let w = robot
        .inverse_kinematics(&krut_poses(1)[0])
        .unwrap()
        .wrench_matrix();
    let bounds = TensionBounds::uniform(3, 50.0, 500.0).unwrap();
    let mut g = c.benchmark_group("available_wrench_set");
    g.bench_function("krut_vertex_projection_seed001", |b| {
        b.iter(|| krut_vertex_projection::available_wrench_set(black_box(&w), &bounds).unwrap())
    });
    g.bench_function("hyperplane_shifting_seed001", |b| {
        b.iter(|| hyperplane_shifting::available_wrench_set(black_box(&w), &bounds).unwrap())
    });
    let robot = ipanema_like_8();
    let w8 = robot
        .inverse_kinematics(&spatial_poses(1)[0])
        .unwrap()
        .wrench_matrix();
    let b8 = TensionBounds::uniform(8, 1.0, 1000.0).unwrap();
    g.bench_function("hyperplane_shifting_8_spatial", |b| {
        b.iter(|| hyperplane_shifting::available_wrench_set(black_box(&w8), &b8).unwrap())
    });
    // Issue 13 §7: 504 half-spaces merged into facets (target ≤ 100 µs for the whole call).
    let w10 = ten_cable_spatial()
        .inverse_kinematics(&spatial_poses(1)[0])
        .unwrap()
        .wrench_matrix();
    let b10 = TensionBounds::uniform(10, 1.0, 1000.0).unwrap();
    g.bench_function("hyperplane_shifting_10_spatial", |b| {
        b.iter(|| hyperplane_shifting::available_wrench_set(black_box(&w10), &b10).unwrap())
    });
    g.finish();
}

criterion_group!(
    benches,
    capacity_margin,
    isotropic_force,
    available_wrench_set
);
criterion_main!(benches);
