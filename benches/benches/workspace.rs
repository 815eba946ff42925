//! Workspace analysis (thesis §§6.4–6.5): the discretisation method (Algorithm 6.2) on the
//! thesis robots at m = 50 (thesis, Fortran 2002: 3-cable 0.03 s, 4-cable with l2 29.3 s), the
//! chord method (§6.4.3, thesis 4-cable l2: 30.12 s) and a spatial constant-orientation grid of
//! the 8-cable robot (`ipanema_like_8`, 25³ = 15 625 poses over the frame's bounding box: about
//! CASPR's IPAnema 2 benchmark size of 14 823) for wrench closure and l2 tension feasibility,
//! and the boundary mesh of the same robot's wrench-feasible workspace with gravity (l2 tensions
//! in [10, 1000] N, 5 kg platform, cables ≥ 0.05 m, `examples/robots/ipanema-like-8.toml`) at
//! M = 60 over its frame, vertices refined to 1e-8 of the box (issue 16: ≤ 1 s on 2 cores).
//! `dextrous/table_6_10_run_1_m400_l1_21_slices` is the setting of the issue-13 `cdpr dextrous`
//! timing against numpy (401² points × 21 orientations, l1).

use cdpr_benches::ipanema_like_8;
use cdpr_kinematics::{Cable, MotionPattern, Robot};
use cdpr_tension::{Method, TensionBounds};
use cdpr_workspace::{
    ChordSettings, Criterion as Cr, Grid, MeshSettings, OrientationRange, PoseEvaluator, Region,
    boundary_mesh, chord_workspace, constant_orientation_workspace, dextrous_workspace,
    planar_workspace,
};
use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::{DVector, Rotation3, Vector3};
use std::hint::black_box;

fn planar(c: &[[f64; 2]], a: &[[f64; 2]]) -> Robot {
    let cables = c
        .iter()
        .zip(a)
        .map(|(c, a)| Cable {
            frame: Vector3::new(c[0], c[1], 0.0),
            platform: Vector3::new(a[0], a[1], 0.0),
            pulley: None,
        })
        .collect();
    Robot::new(MotionPattern::Planar, cables).unwrap()
}

/// Tables 6.1, 6.2, 6.4 with load L1 = (0, −10, 0).
fn three_cable() -> PoseEvaluator {
    let s = 0.1 / 2f64.sqrt();
    let robot = planar(
        &[[1.0, 1.0], [-1.0, 1.0], [0.0, -1.0]],
        &[[s, s], [-s, s], [0.0, -0.1]],
    );
    PoseEvaluator::new(
        robot,
        TensionBounds::uniform(3, 5.0, 100.0).unwrap(),
        vec![
            Cr::TensionFeasible {
                method: Method::Exact,
                wrench: DVector::from_vec(vec![0.0, -10.0, 0.0]),
            },
            Cr::MinCableLength(0.1),
            Cr::MinJacobianDeterminant(1e-3),
        ],
    )
    .unwrap()
}

fn four_cable(method: Method) -> PoseEvaluator {
    let s = 0.1 / 2f64.sqrt();
    let robot = planar(
        &[[1.0, 0.5], [-1.0, 0.5], [-1.0, -0.5], [1.0, -0.5]],
        &[[s, s], [-s, s], [-0.1, -0.1], [0.1, -0.1]],
    );
    PoseEvaluator::new(
        robot,
        TensionBounds::uniform(4, 5.0, 100.0).unwrap(),
        vec![
            Cr::TensionFeasible {
                method,
                wrench: DVector::from_vec(vec![0.0, -10.0, 0.0]),
            },
            Cr::MinCableLength(0.1),
        ],
    )
    .unwrap()
}

fn discretisation(c: &mut Criterion) {
    let mut g = c.benchmark_group("discretisation");
    let three = three_cable();
    let grid3 = Grid::over_frame(three.robot(), 50);
    g.bench_function("three_cable_m50", |b| {
        b.iter(|| planar_workspace(black_box(&three), 0.0, &grid3).unwrap())
    });
    for method in [Method::L2, Method::L1] {
        let four = four_cable(method);
        let grid4 = Grid::over_frame(four.robot(), 50);
        g.bench_function(format!("four_cable_m50_{}", method.name()), |b| {
            b.iter(|| planar_workspace(black_box(&four), 0.0, &grid4).unwrap())
        });
    }
    g.finish();
}

fn chord(c: &mut Criterion) {
    let mut g = c.benchmark_group("chord");
    let settings = ChordSettings::default(); // d = 0.05, ε = 1e-8
    let four = four_cable(Method::L2);
    let region = Region::frame_bounding_box(four.robot());
    g.bench_function("four_cable_l2_d0.05", |b| {
        b.iter(|| chord_workspace(black_box(&four), 0.05, &region, &settings).unwrap())
    });
    let three = three_cable();
    let region3 = Region::frame_bounding_box(three.robot());
    g.bench_function("three_cable_d0.05", |b| {
        b.iter(|| chord_workspace(black_box(&three), 0.1, &region3, &settings).unwrap())
    });
    g.finish();
}

fn dextrous(c: &mut Criterion) {
    let mut g = c.benchmark_group("dextrous");
    let four = four_cable(Method::L1);
    let grid = Grid::over_frame(four.robot(), 50);
    let range = OrientationRange {
        min: -0.2,
        max: 0.2,
        slices: 5,
    };
    g.bench_function("four_cable_m50_l1_5_slices", |b| {
        b.iter(|| dextrous_workspace(black_box(&four), &range, &grid).unwrap())
    });
    // The issue-13 timing setting (Table 6.10 run 1 of the thesis chapter on planar
    // tendon-driven manipulators, 401² points × 21 orientations): the lean path in lanes.
    let anchors: Vec<[f64; 2]> = [0.7572f64, 2.922, 3.097, 5.449]
        .iter()
        .map(|&b| {
            let rho = 1.0 / b.cos().abs().max(b.sin().abs());
            [rho * b.cos(), rho * b.sin()]
        })
        .collect();
    let table = PoseEvaluator::new(
        cdpr_kinematics::reference_robots::thesis_manipulator(&anchors),
        TensionBounds::uniform(4, 5.0, 100.0).unwrap(),
        vec![
            Cr::TensionFeasible {
                method: Method::L1,
                wrench: DVector::from_row_slice(&[5.0, -10.0, 1.0]),
            },
            Cr::MinCableLength(0.1),
        ],
    )
    .unwrap();
    let range21 = OrientationRange {
        min: -0.2,
        max: 0.2,
        slices: 21,
    };
    let grid400 = Grid::new(400, Region::planar(-1.0, 1.0, -1.0, 1.0));
    g.bench_function("table_6_10_run_1_m400_l1_21_slices", |b| {
        b.iter(|| dextrous_workspace(black_box(&table), &range21, &grid400).unwrap())
    });
    g.finish();
}

fn spatial(c: &mut Criterion) {
    let mut g = c.benchmark_group("spatial_grid");
    g.sample_size(20);
    let robot = ipanema_like_8();
    let bounds = TensionBounds::uniform(8, 1.0, 1000.0).unwrap();
    let grid = Grid::over_frame(&robot, 24); // 25³ = 15 625 poses
    let closure =
        PoseEvaluator::new(robot.clone(), bounds.clone(), vec![Cr::WrenchClosure]).unwrap();
    let gravity = DVector::from_vec(vec![0.0, 0.0, -9.80665 * 10.0, 0.0, 0.0, 0.0]);
    let l2 = PoseEvaluator::new(
        robot,
        bounds,
        vec![Cr::TensionFeasible {
            method: Method::L2,
            wrench: gravity,
        }],
    )
    .unwrap();
    let id = Rotation3::identity();
    g.bench_function("eight_cable_wrench_closure_15625", |b| {
        b.iter(|| constant_orientation_workspace(black_box(&closure), &id, &grid).unwrap())
    });
    g.bench_function("eight_cable_l2_15625", |b| {
        b.iter(|| constant_orientation_workspace(black_box(&l2), &id, &grid).unwrap())
    });
    g.finish();
}

fn mesh(c: &mut Criterion) {
    let mut g = c.benchmark_group("workspace");
    g.sample_size(10);
    let robot = ipanema_like_8();
    let grid = Grid::over_frame(&robot, 60);
    let eval = PoseEvaluator::new(
        robot,
        TensionBounds::uniform(8, 10.0, 1000.0).unwrap(),
        vec![
            Cr::TensionFeasible {
                method: Method::L2,
                wrench: DVector::from_vec(vec![0.0, 0.0, -9.80665 * 5.0, 0.0, 0.0, 0.0]),
            },
            Cr::MinCableLength(0.05),
        ],
    )
    .unwrap();
    let id = Rotation3::identity();
    g.bench_function("boundary_mesh_8_spatial_m60", |b| {
        b.iter(|| boundary_mesh(black_box(&eval), &id, &grid, &MeshSettings::default()).unwrap())
    });
    g.finish();
}

criterion_group!(benches, discretisation, chord, dextrous, spatial, mesh);
criterion_main!(benches);
