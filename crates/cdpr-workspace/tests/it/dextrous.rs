//! Dextrous workspace, eq. (6.28), and the §6.5 check of the two-extremes shortcut.
use crate::common;

use cdpr_tension::{Method, TensionBounds};
use cdpr_workspace::{
    Criterion, Grid, GridWorkspace, OrientationRange, PoseEvaluator, Region,
    constant_orientation_workspace, dextrous_workspace, dextrous_workspace_about_axis,
    dextrous_workspace_over, euler_box, planar_workspace,
};
use common::*;
use nalgebra::{Rotation3, Vector3};
use proptest::prelude::*;

/// The dextrous workspace is exactly the intersection of the slices, and the central check is
/// (extremes ∩) ⊆ central, both recomputed here from constant-orientation workspaces.
fn check_against_slices(
    eval: &PoseEvaluator,
    range: &OrientationRange,
    grid: &Grid,
) -> GridWorkspace {
    let dex = dextrous_workspace(eval, range, grid).unwrap();
    let slices: Vec<GridWorkspace> = range
        .angles()
        .iter()
        .map(|&phi| planar_workspace(eval, phi, grid).unwrap())
        .collect();
    for s in &slices {
        assert!(dex.workspace.is_subset_of(s));
    }
    for i in 0..dex.workspace.total_points {
        assert_eq!(
            dex.workspace.feasible[i],
            slices.iter().all(|s| s.feasible[i])
        );
    }
    let lo = &slices[0];
    let hi = &slices[slices.len() - 1];
    let mid = planar_workspace(eval, range.central(), grid).unwrap();
    let ext: Vec<bool> = lo
        .feasible
        .iter()
        .zip(&hi.feasible)
        .map(|(a, b)| *a && *b)
        .collect();
    let violations = ext
        .iter()
        .zip(&mid.feasible)
        .filter(|(e, m)| **e && !**m)
        .count();
    assert_eq!(dex.central_check.violations, violations);
    assert_eq!(dex.central_check.holds, violations == 0);
    assert_eq!(
        dex.central_check.extremes_points,
        ext.iter().filter(|e| **e).count()
    );
    dex.workspace
}

#[test]
fn three_cable_dextrous_is_the_intersection_of_slices() {
    let g = Grid::over_frame(&three_cable(), 50);
    for load_case in 0..3 {
        let eval = three_cable_eval(load_case);
        for range in [
            OrientationRange {
                min: 0.0,
                max: 0.1,
                slices: 3,
            },
            OrientationRange {
                min: 0.0,
                max: 0.1,
                slices: 6,
            },
            OrientationRange {
                min: 0.05,
                max: 0.05,
                slices: 1,
            },
        ] {
            check_against_slices(&eval, &range, &g);
        }
    }
}

#[test]
fn four_cable_dextrous_is_the_intersection_of_slices() {
    let g = Grid::over_frame(&four_cable(), 40);
    for load_case in 0..3 {
        let eval = four_cable_eval(load_case, Method::L1);
        let dex = check_against_slices(
            &eval,
            &OrientationRange {
                min: -0.2,
                max: 0.2,
                slices: 5,
            },
            &g,
        );
        assert!(dex.feasible_points > 0, "L{}", load_case + 1);
    }
}

/// A case where the shortcut fails: feasible at both extremes but not in between. A custom
/// criterion rejects |φ| < 0.05 in a disc (a platform feature in the way, say).
#[test]
fn central_check_detects_a_failing_shortcut() {
    use cdpr_workspace::CustomCriterion;
    let eval = PoseEvaluator::new(
        four_cable(),
        TensionBounds::uniform(4, T_MIN, T_MAX).unwrap(),
        vec![Criterion::Custom(CustomCriterion::new("notch", |ctx| {
            let phi = ctx.pose.rotation.angle();
            let u = ctx.pose.position;
            !(phi < 0.05 && u.x * u.x + u.y * u.y < 0.04)
        }))],
    )
    .unwrap();
    let g = Grid::new(40, Region::planar(-0.5, 0.5, -0.5, 0.5));
    let dex = dextrous_workspace(
        &eval,
        &OrientationRange {
            min: -0.2,
            max: 0.2,
            slices: 2,
        },
        &g,
    )
    .unwrap();
    assert!(!dex.central_check.holds);
    assert!(dex.central_check.violations > 0);
    // With three slices the central orientation is part of the intersection.
    let dex3 = check_against_slices(
        &eval,
        &OrientationRange {
            min: -0.2,
            max: 0.2,
            slices: 3,
        },
        &g,
    );
    assert!(dex3.is_subset_of(&dex.workspace));
    assert_eq!(
        dex.workspace.feasible_points - dex3.feasible_points,
        dex.central_check.violations
    );
}

#[test]
fn spatial_dextrous_about_an_axis_and_over_an_euler_box() {
    // A cube frame with 8 cables to the corners of a small platform (IPAnema-like layout).
    let robot = common::eight_cable_spatial();
    let eval = PoseEvaluator::new(
        robot,
        TensionBounds::uniform(8, 1.0, 100.0).unwrap(),
        vec![Criterion::WrenchClosure],
    )
    .unwrap();
    let g = Grid::new(
        8,
        Region::cuboid(Vector3::repeat(-0.6), Vector3::repeat(0.6)),
    );
    let range = OrientationRange {
        min: -0.1,
        max: 0.1,
        slices: 3,
    };
    let dex = dextrous_workspace_about_axis(
        &eval,
        &Vector3::x_axis(),
        &Rotation3::identity(),
        &range,
        &g,
    )
    .unwrap();
    assert!(dex.workspace.feasible_points > 0);
    for a in range.angles() {
        let r = Rotation3::from_axis_angle(&Vector3::x_axis(), a);
        let slice = constant_orientation_workspace(&eval, &r, &g).unwrap();
        assert!(dex.workspace.is_subset_of(&slice));
    }
    let box_rots = euler_box([-0.1, 0.0, -0.1], [0.1, 0.0, 0.1], 2).unwrap();
    assert_eq!(box_rots.len(), 4);
    let over = dextrous_workspace_over(&eval, &box_rots, &g).unwrap();
    for r in &box_rots {
        assert!(over.is_subset_of(&constant_orientation_workspace(&eval, r, &g).unwrap()));
    }
}

#[test]
fn bad_ranges_are_errors() {
    let eval = four_cable_eval(0, Method::L2);
    let g = Grid::over_frame(eval.robot(), 10);
    for range in [
        OrientationRange {
            min: 0.1,
            max: 0.0,
            slices: 3,
        },
        OrientationRange {
            min: 0.0,
            max: 0.1,
            slices: 1,
        },
        OrientationRange {
            min: f64::NAN,
            max: 0.1,
            slices: 3,
        },
    ] {
        assert!(dextrous_workspace(&eval, &range, &g).is_err());
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]
    #[test]
    fn dextrous_is_inside_every_slice(lo in -0.3f64..0.1, width in 0.0f64..0.3, slices in 2usize..6, load_case in 0usize..3) {
        let eval = four_cable_eval(load_case, Method::L1);
        let g = Grid::over_frame(eval.robot(), 16);
        let range = OrientationRange { min: lo, max: lo + width, slices };
        let dex = dextrous_workspace(&eval, &range, &g).unwrap();
        for phi in range.angles() {
            prop_assert!(dex.workspace.is_subset_of(&planar_workspace(&eval, phi, &g).unwrap()));
        }
    }
}

/// SplitMix64 in [a, b).
struct Rng(u64);
impl Rng {
    fn range(&mut self, a: f64, b: f64) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        a + (b - a) * (((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64)
    }
}

/// The lean planar r = 1 path gives the evaluator's verdict at every pose: random 4-cable planar
/// robots, loads, bounds (some fixed, some infinite t_max), length floors, the three methods
/// of Algorithm 6.1, poses on a grid and at the frame anchors (a zero-length cable).
#[test]
fn planar_slice_agrees_with_the_evaluator() {
    use cdpr_kinematics::{Cable, MotionPattern, Robot};
    use cdpr_workspace::PlanarSlice;
    let mut g = Rng(20261122);
    let (mut feasible, mut infeasible, mut deferred) = (0, 0, 0);
    for robot_index in 0..60 {
        let cables: Vec<Cable> = (0..4)
            .map(|i| {
                let a = std::f64::consts::FRAC_PI_2 * i as f64 + g.range(0.0, 1.4);
                let b = std::f64::consts::FRAC_PI_2 * i as f64 + g.range(0.0, 1.4);
                Cable {
                    frame: Vector3::new(a.cos(), a.sin(), 0.0),
                    platform: Vector3::new(0.1 * b.cos(), 0.1 * b.sin(), 0.0),
                    pulley: None,
                }
            })
            .collect();
        let robot = Robot::new(MotionPattern::Planar, cables).unwrap();
        let lo = g.range(0.0, 10.0);
        let mut hi = vec![lo + g.range(5.0, 200.0); 4];
        match robot_index % 4 {
            1 => hi[robot_index % 3] = lo,            // a fixed cable
            2 => hi[robot_index % 4] = f64::INFINITY, // no upper bound
            _ => {}
        }
        let bounds = TensionBounds::new(vec![lo; 4], hi).unwrap();
        let wrench = nalgebra::DVector::from_fn(3, |_, _| g.range(-10.0, 10.0));
        let method = [Method::L1, Method::L1Max, Method::ClosedForm][robot_index % 3];
        let mut criteria = vec![Criterion::TensionFeasible { method, wrench }];
        if robot_index % 2 == 0 {
            criteria.push(Criterion::MinCableLength(g.range(0.0, 0.3)));
        }
        let mut eval = PoseEvaluator::new(robot.clone(), bounds, criteria).unwrap();
        for phi in [-0.3, 0.0, 0.17] {
            let r = Rotation3::from_axis_angle(&Vector3::z_axis(), phi);
            let lean = PlanarSlice::new(&eval, &r).expect("the lean path applies");
            let mut positions: Vec<Vector3<f64>> = (0..=20)
                .flat_map(|i| (0..=20).map(move |j| (i, j)))
                .map(|(i, j)| Vector3::new(-1.0 + 0.1 * i as f64, -1.0 + 0.1 * j as f64, 0.0))
                .collect();
            // A cable of zero length: the attachment point on its frame anchor.
            let c = &robot.cables()[0];
            positions.push(c.frame - r * c.platform);
            check_lanes(&lean, &positions);
            for u in positions {
                let expected = eval.is_feasible(&cdpr_kinematics::Pose::new(u, r));
                match lean.is_feasible(&u) {
                    Some(got) => assert_eq!(got, expected, "robot {robot_index}, φ {phi}, u {u:?}"),
                    None => deferred += 1,
                }
                if expected {
                    feasible += 1;
                } else {
                    infeasible += 1;
                }
            }
        }
    }
    // Both verdicts occur; only the zero-length cables go to the evaluator.
    assert!(
        feasible > 1000 && infeasible > 1000,
        "{feasible} / {infeasible}"
    );
    assert!(deferred <= 60 * 3, "{deferred}");
}

/// [`PlanarSlice::is_feasible_lanes`] in both builds (portable, and AVX2 on a CPU with it) gives
/// [`PlanarSlice::is_feasible`] lane by lane (verdict, or deferred for `None`), for the
/// positions four at a time in several lane orders.
fn check_lanes(lean: &cdpr_workspace::PlanarSlice, positions: &[Vector3<f64>]) {
    use cdpr_tension::lanes::{F64x4, Portable};
    fn check<V: F64x4>(v: V, lean: &cdpr_workspace::PlanarSlice, u: [Vector3<f64>; 4]) {
        let (verdicts, deferred) =
            lean.is_feasible_lanes(v.load(u.map(|u| u.x)), v.load(u.map(|u| u.y)));
        for (l, u) in u.iter().enumerate() {
            match lean.is_feasible(u) {
                Some(ok) => {
                    assert_eq!(deferred >> l & 1, 0, "lane {l}, u {u:?}");
                    assert_eq!(verdicts >> l & 1 == 1, ok, "lane {l}, u {u:?}");
                }
                None => assert_eq!(deferred >> l & 1, 1, "lane {l}, u {u:?}"),
            }
        }
    }
    for shift in [0, 1, 3] {
        for j in 0..positions.len() {
            let u = std::array::from_fn(|l| positions[(j + shift * l) % positions.len()]);
            check(Portable([0.0; 4]), lean, u);
            #[cfg(target_arch = "x86_64")]
            if let Some(v) = cdpr_tension::lanes::Avx2::detect() {
                check(v, lean, u);
            }
        }
    }
}

/// The lean path applies only where it is the evaluator's path: another method or criterion,
/// a robot that is not planar with 4 cables, pulleys.
#[test]
fn planar_slice_declines_other_settings() {
    use cdpr_workspace::PlanarSlice;
    let r = Rotation3::identity();
    assert!(PlanarSlice::new(&four_cable_eval(0, Method::L1), &r).is_some());
    assert!(PlanarSlice::new(&four_cable_eval(0, Method::L2), &r).is_none());
    assert!(PlanarSlice::new(&four_cable_eval(0, Method::Pinv), &r).is_none());
    assert!(PlanarSlice::new(&three_cable_eval(0), &r).is_none());
    let closure = PoseEvaluator::new(
        four_cable(),
        TensionBounds::uniform(4, T_MIN, T_MAX).unwrap(),
        vec![Criterion::WrenchClosure],
    )
    .unwrap();
    assert!(PlanarSlice::new(&closure, &r).is_none());
}

/// The thesis' Table 6.10 run-1 design (the `cdpr dextrous` timing of issue 13): the dextrous
/// workspace by the lean path equals the intersection of the constant-orientation workspaces
/// of the general evaluator, slice by slice.
#[test]
fn table_6_10_run_1_dextrous_matches_the_general_slices() {
    use cdpr_kinematics::reference_robots::thesis_manipulator;
    let anchors: Vec<[f64; 2]> = [0.7572f64, 2.922, 3.097, 5.449]
        .iter()
        .map(|&b| {
            let rho = 1.0 / b.cos().abs().max(b.sin().abs());
            [rho * b.cos(), rho * b.sin()]
        })
        .collect();
    let eval = PoseEvaluator::new(
        thesis_manipulator(&anchors),
        TensionBounds::uniform(4, 5.0, 100.0).unwrap(),
        vec![
            Criterion::TensionFeasible {
                method: Method::L1,
                wrench: nalgebra::DVector::from_row_slice(&[5.0, -10.0, 1.0]),
            },
            Criterion::MinCableLength(0.1),
        ],
    )
    .unwrap();
    let range = OrientationRange {
        min: -0.2,
        max: 0.2,
        slices: 21,
    };
    let g = Grid::new(60, Region::planar(-1.0, 1.0, -1.0, 1.0));
    let dex = check_against_slices(&eval, &range, &g);
    assert!(dex.feasible_points > 100 && dex.feasible_points < dex.total_points / 2);
}

/// The lean driver [`dextrous_verdicts_lean`] (orientation by orientation, four points at a
/// time, deferred points through the evaluator) gives the per-point order of tests of the
/// scalar path: (dextrous, both extremes, central violated), with slices of different loads so
/// that the central orientation (sampled, or not sampled) fails where the others pass.
#[test]
fn dextrous_verdicts_lean_follow_the_scalar_order_of_tests() {
    use cdpr_kinematics::Pose;
    use cdpr_kinematics::reference_robots::thesis_manipulator;
    use cdpr_workspace::{LeanScratch, PlanarSlice, dextrous_verdicts_lean};
    let robot = thesis_manipulator(&[
        [1.0, 0.9451],
        [-1.0, 0.2232],
        [-1.0, 0.0446],
        [0.9069, -1.0],
    ]);
    let evaluator = |fy: f64| {
        PoseEvaluator::new(
            robot.clone(),
            TensionBounds::uniform(4, 5.0, 100.0).unwrap(),
            vec![
                Criterion::TensionFeasible {
                    method: Method::L1,
                    wrench: nalgebra::DVector::from_row_slice(&[5.0, fy, 1.0]),
                },
                Criterion::MinCableLength(0.1),
            ],
        )
        .unwrap()
    };
    let rot = |phi: f64| Rotation3::from_axis_angle(&Vector3::z_axis(), phi);
    // Positions on a grid (442 points: the last group of four is padded) and on a frame anchor.
    let mut points: Vec<Vector3<f64>> = (0..21)
        .flat_map(|i| {
            (0..21).map(move |j| Vector3::new(-1.0 + 0.1 * j as f64, -1.0 + 0.1 * i as f64, 0.0))
        })
        .collect();
    let c = &robot.cables()[1];
    points.push(c.frame - rot(-0.2) * c.platform);
    // (load, angle) of each sampled orientation; the heavy load at index `heavy`.
    for (loads, central_sampled) in [
        (vec![-10.0, -40.0, -10.0], true),
        (vec![-10.0, -10.0, -10.0, -40.0, -10.0], true),
        (vec![-10.0, -10.0, -40.0, -10.0], false),
    ] {
        let n = loads.len();
        let angles: Vec<f64> = (0..n)
            .map(|k| -0.2 + 0.4 * k as f64 / (n - 1) as f64)
            .collect();
        let mut evals: Vec<PoseEvaluator> = loads.iter().map(|&f| evaluator(f)).collect();
        let slices: Vec<PlanarSlice> = evals
            .iter()
            .zip(&angles)
            .map(|(e, &a)| PlanarSlice::new(e, &rot(a)).unwrap())
            .collect();
        let mut central_eval = evaluator(-40.0);
        let central_slice = PlanarSlice::new(&central_eval, &rot(0.0)).unwrap();
        let central_index = central_sampled.then_some(n / 2);
        let central = central_index.ok_or(&central_slice);
        let mut ok = |k: Option<usize>, u: &Vector3<f64>| match k {
            Some(k) => evals[k].is_feasible(&Pose::new(*u, rot(angles[k]))),
            None => central_eval.is_feasible(&Pose::new(*u, rot(0.0))),
        };
        let expected: Vec<(bool, bool, bool)> = points
            .iter()
            .map(|u| {
                if !ok(Some(0), u) || !ok(Some(n - 1), u) {
                    return (false, false, false);
                }
                let central_ok = ok(central_index, u);
                let others = (1..n - 1)
                    .filter(|&k| Some(k) != central_index)
                    .all(|k| ok(Some(k), u));
                (
                    (central_ok || central_index.is_none()) && others,
                    true,
                    !central_ok,
                )
            })
            .collect();
        let mut got = vec![(false, false, false); points.len()];
        let mut deferred = 0;
        dextrous_verdicts_lean(
            &slices,
            central,
            &points,
            &mut got,
            &mut LeanScratch::default(),
            |k, u| {
                deferred += 1;
                ok(k, u)
            },
        );
        assert_eq!(got, expected, "loads {loads:?}");
        assert!(deferred >= 1, "the anchor point is deferred");
        let count = |f: fn(&(bool, bool, bool)) -> bool| expected.iter().filter(|v| f(v)).count();
        assert!(
            count(|v| v.0) > 20 && count(|v| v.1) > count(|v| v.0) + 10,
            "{loads:?}: {} {} {}",
            count(|v| v.0),
            count(|v| v.1),
            count(|v| v.2)
        );
    }
}
