//! Algorithm 6.2 (thesis §6.4.2): grids, areas, determinism and independent cross-checks.
use crate::common;

use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
use cdpr_tension::{Method, TensionBounds};
use cdpr_workspace::{
    Criterion, CustomCriterion, Grid, PoseEvaluator, Region, WorkspaceError,
    constant_orientation_workspace, planar_workspace,
};
use common::*;
use nalgebra::{DVector, Matrix3, Rotation3, Vector3};

#[test]
fn grid_points_follow_algorithm_6_2_step_3() {
    let robot = three_cable();
    let g = Grid::over_frame(&robot, 4);
    assert_eq!(g.point_count(2), 25);
    assert_eq!(g.point(2, 0), Vector3::new(-1.0, -1.0, 0.0));
    assert_eq!(g.point(2, 24), Vector3::new(1.0, 1.0, 0.0));
    // i = 1, j = 2: u = [x_min + (1/4)·2, y_min + (2/4)·2].
    assert_eq!(g.point(2, 2 * 5 + 1), Vector3::new(-0.5, 0.0, 0.0));
    assert_eq!(g.cell_measure(2), 0.25);
    // A 3-D box given to a 2-D grid: z stays 0.
    let g3 = Grid::new(
        2,
        Region::cuboid(Vector3::new(0.0, 0.0, 1.0), Vector3::new(1.0, 1.0, 2.0)),
    );
    assert_eq!(g3.point(2, 8), Vector3::new(1.0, 1.0, 0.0));
    assert_eq!(g3.point(3, 26), Vector3::new(1.0, 1.0, 2.0));
}

#[test]
fn disc_area_counts_exactly_the_grid_points_inside() {
    let r = 0.5;
    let eval = shape_eval(move |x, y| x * x + y * y <= r * r);
    for m in [10, 37, 200] {
        let g = Grid::new(m, unit_box());
        let ws = planar_workspace(&eval, 0.0, &g).unwrap();
        // Independent count of grid points in the disc.
        let h = 2.0 / m as f64;
        let mut count = 0;
        for j in 0..=m {
            for i in 0..=m {
                let (x, y) = (-1.0 + i as f64 * h, -1.0 + j as f64 * h);
                if x * x + y * y <= r * r {
                    count += 1;
                }
            }
        }
        // Points exactly on the circle may round either way.
        assert!(
            (ws.feasible_points as i64 - count as i64).abs() <= 4,
            "m = {m}"
        );
        assert_eq!(ws.total_points, (m + 1) * (m + 1));
        assert!((ws.area - ws.feasible_points as f64 * h * h).abs() < 1e-12);
    }
    let ws = planar_workspace(&eval, 0.0, &Grid::new(400, unit_box())).unwrap();
    let exact = std::f64::consts::PI * r * r;
    assert!((ws.area - exact).abs() / exact < 0.01, "{}", ws.area);
}

#[test]
fn sphere_volume_on_a_3d_grid() {
    let c = |x: f64, y: f64, z: f64| Cable {
        frame: Vector3::new(x, y, z),
        platform: Vector3::zeros(),
        pulley: None,
    };
    let robot = Robot::new(
        MotionPattern::Point3,
        vec![
            c(5.0, 0.0, 0.0),
            c(-5.0, 5.0, 0.0),
            c(-5.0, -5.0, 0.0),
            c(0.0, 0.0, 5.0),
        ],
    )
    .unwrap();
    let eval = PoseEvaluator::new(
        robot,
        TensionBounds::uniform(4, 0.0, 1.0).unwrap(),
        vec![Criterion::Custom(CustomCriterion::new("ball", |ctx| {
            ctx.pose.position.norm() <= 0.8
        }))],
    )
    .unwrap();
    let g = Grid::new(
        60,
        Region::cuboid(Vector3::repeat(-1.0), Vector3::repeat(1.0)),
    );
    let ws = constant_orientation_workspace(&eval, &Rotation3::identity(), &g).unwrap();
    assert_eq!(ws.dim, 3);
    assert_eq!(ws.total_points, 61 * 61 * 61);
    let exact = 4.0 / 3.0 * std::f64::consts::PI * 0.8f64.powi(3);
    assert!(
        (ws.area - exact).abs() / exact < 0.02,
        "{} vs {exact}",
        ws.area
    );
}

#[test]
fn same_result_with_one_and_two_threads() {
    let run = |threads: usize, eval: &PoseEvaluator, phi: f64| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| planar_workspace(eval, phi, &Grid::over_frame(eval.robot(), 60)).unwrap())
    };
    for (eval, phi) in [
        (four_cable_eval(0, Method::L2), 0.0),
        (four_cable_eval(2, Method::L1), 0.1),
        (three_cable_eval(1), 0.05),
    ] {
        let a = run(1, &eval, phi);
        let b = run(2, &eval, phi);
        assert_eq!(a, b);
        assert!(a.feasible_points > 0);
    }
}

/// Grids are cut into a few tasks per thread, so task boundaries move with the thread count
/// (mid-row, mid-layer): the verdicts must not. 2-D exact (3 cables) and 3-D wrench closure
/// (8 cables), each also checked point by point against a sequential evaluation.
#[test]
fn same_result_whatever_the_thread_count() {
    let in_pool = |threads: usize, f: &(dyn Fn() -> cdpr_workspace::GridWorkspace + Sync)| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(f)
    };
    let mut three = three_cable_eval(0);
    let g2 = Grid::over_frame(three.robot(), 53);
    let planar = || planar_workspace(&three, 0.05, &g2).unwrap();
    let mut eight = PoseEvaluator::new(
        eight_cable_spatial(),
        TensionBounds::uniform(8, 1.0, 100.0).unwrap(),
        vec![Criterion::WrenchClosure],
    )
    .unwrap();
    let g3 = Grid::new(
        9,
        Region::cuboid(Vector3::repeat(-0.8), Vector3::new(0.8, 0.7, 0.75)),
    );
    let spatial = || constant_orientation_workspace(&eight, &Rotation3::identity(), &g3).unwrap();
    let (a2, a3) = (in_pool(1, &planar), in_pool(1, &spatial));
    for threads in [2, 3, 5] {
        assert_eq!(in_pool(threads, &planar), a2, "{threads} threads");
        assert_eq!(in_pool(threads, &spatial), a3, "{threads} threads");
    }
    assert!(0 < a2.feasible_points && a2.feasible_points < a2.total_points);
    assert!(0 < a3.feasible_points && a3.feasible_points < a3.total_points);
    let rotation = Rotation3::from_axis_angle(&Vector3::z_axis(), 0.05);
    for (i, &f) in a2.feasible.iter().enumerate() {
        assert_eq!(f, three.is_feasible(&Pose::new(g2.point(2, i), rotation)));
    }
    for (i, &f) in a3.feasible.iter().enumerate() {
        assert_eq!(
            f,
            eight.is_feasible(&Pose::new(g3.point(3, i), Rotation3::identity()))
        );
    }
}

/// Independent check of the 3-cable workspace: t = −W⁻¹ w_ext by a fixed-size inverse, eqs.
/// (6.12), (6.21), (6.22), (6.24), evaluated by hand at every grid point.
#[test]
fn three_cable_grid_matches_a_direct_evaluation() {
    let robot = three_cable();
    for (load_case, phi) in [(0, 0.0), (1, 0.05), (2, 0.1), (2, 0.0)] {
        let eval = three_cable_eval(load_case);
        let g = Grid::over_frame(&robot, 50);
        let ws = planar_workspace(&eval, phi, &g).unwrap();
        let w_ext = nalgebra::Vector3::from_row_slice(&LOADS[load_case]);
        let mut disagreements = 0;
        for idx in 0..ws.total_points {
            let u = g.point(2, idx);
            let expected = match robot.inverse_kinematics(&Pose::planar(u.x, u.y, phi)) {
                Err(_) => false,
                Ok(kin) => {
                    let w = Matrix3::from_column_slice(kin.wrench_matrix().as_slice());
                    let det = w.determinant();
                    let t = w.try_inverse().map(|inv| -(inv * w_ext));
                    kin.min_length() >= L_MIN
                        && det.abs() >= D_MIN
                        && t.is_some_and(|t| t.iter().all(|&ti| (T_MIN..=T_MAX).contains(&ti)))
                }
            };
            if expected != ws.feasible[idx] {
                disagreements += 1;
            }
        }
        assert_eq!(disagreements, 0, "load {load_case}, φ = {phi}");
        assert!(ws.feasible_points > 0);
    }
}

/// The feasible set's non-emptiness does not depend on the objective: l1, l2 and linf decide
/// alike; the minimum-norm (pinv) tensions only underestimate (thesis Fig. 6.3).
#[test]
fn four_cable_methods_agree_and_pinv_underestimates() {
    let g = Grid::over_frame(&four_cable(), 40);
    for load_case in 0..3 {
        for phi in [-0.2, 0.0, 0.2] {
            let l2 = planar_workspace(&four_cable_eval(load_case, Method::L2), phi, &g).unwrap();
            let l1 = planar_workspace(&four_cable_eval(load_case, Method::L1), phi, &g).unwrap();
            let linf =
                planar_workspace(&four_cable_eval(load_case, Method::Linf), phi, &g).unwrap();
            let pinv =
                planar_workspace(&four_cable_eval(load_case, Method::Pinv), phi, &g).unwrap();
            assert_eq!(l1.feasible, l2.feasible, "L{} φ = {phi}", load_case + 1);
            assert_eq!(linf.feasible, l2.feasible, "L{} φ = {phi}", load_case + 1);
            assert!(pinv.is_subset_of(&l2));
            assert!(pinv.feasible_points < l2.feasible_points);
        }
    }
}

#[test]
fn zero_length_cable_is_infeasible_not_an_error() {
    let mut eval = four_cable_eval(0, Method::L2);
    let s = 0.1 / 2f64.sqrt();
    // Cable 1's attachment on its anchor: u = c¹ − ā¹ at φ = 0.
    let pose = Pose::planar(1.0 - s, 0.5 - s, 0.0);
    assert_eq!(eval.check(&pose), Ok(false));
    assert!(!eval.is_feasible(&pose));
}

#[test]
fn bad_input_is_an_error() {
    let eval = four_cable_eval(0, Method::L2);
    let region = Region::frame_bounding_box(eval.robot());
    assert!(matches!(
        planar_workspace(&eval, 0.0, &Grid::new(0, region)),
        Err(WorkspaceError::InvalidSetting { .. })
    ));
    assert!(matches!(
        planar_workspace(&eval, f64::NAN, &Grid::new(10, region)),
        Err(WorkspaceError::NotFinite { .. })
    ));
    assert!(matches!(
        planar_workspace(
            &eval,
            0.0,
            &Grid::new(10, Region::planar(0.0, 0.0, 0.0, 1.0))
        ),
        Err(WorkspaceError::EmptyRegion { axis: 0, .. })
    ));
    let tilted = Rotation3::from_axis_angle(&Vector3::x_axis(), 0.1);
    assert!(matches!(
        constant_orientation_workspace(&eval, &tilted, &Grid::new(10, region)),
        Err(WorkspaceError::NotPlanarRotation)
    ));
    let bounds = TensionBounds::uniform(4, 5.0, 100.0).unwrap();
    let wrong_wrench = vec![Criterion::TensionFeasible {
        method: Method::L2,
        wrench: DVector::from_vec(vec![0.0, -10.0]),
    }];
    assert!(matches!(
        PoseEvaluator::new(four_cable(), bounds.clone(), wrong_wrench),
        Err(WorkspaceError::DimensionMismatch { .. })
    ));
    assert!(matches!(
        PoseEvaluator::new(three_cable(), bounds.clone(), vec![]),
        Err(WorkspaceError::DimensionMismatch { .. })
    ));
    assert!(matches!(
        PoseEvaluator::new(
            four_cable(),
            bounds.clone(),
            vec![Criterion::MinCableLength(f64::NAN)]
        ),
        Err(WorkspaceError::InvalidSetting { .. })
    ));
    let mut ev =
        PoseEvaluator::new(four_cable(), bounds, vec![Criterion::MinCableLength(0.1)]).unwrap();
    let nan_pose = Pose::planar(f64::NAN, 0.0, 0.0);
    assert!(ev.check(&nan_pose).is_err());
    assert!(!ev.is_feasible(&nan_pose));
}

#[test]
fn no_criteria_accepts_every_pose_with_proper_cables() {
    let eval = PoseEvaluator::new(
        four_cable(),
        TensionBounds::uniform(4, 5.0, 100.0).unwrap(),
        vec![],
    )
    .unwrap();
    // The grid over the anchors' box hits no anchor exactly once attachments are subtracted
    // except where u = c − a: count those by hand (none lie on this 10 × 10 grid).
    let ws = planar_workspace(
        &eval,
        0.0,
        &Grid::new(10, Region::frame_bounding_box(eval.robot())),
    )
    .unwrap();
    assert_eq!(ws.feasible_points, ws.total_points);
    assert!((ws.area - 2.0 * 1.0 * (11.0 * 11.0) / 100.0).abs() < 1e-12);
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(16))]
    /// Random robots: the parallel grid equals a sequential evaluation point by point, with one
    /// or two threads.
    #[test]
    fn parallel_grid_is_the_pointwise_verdict(
        robot in cdpr_kinematics::strategies::arb_robot(MotionPattern::Planar, 4..=6),
        phi in -0.3f64..0.3,
    ) {
        let n = robot.cable_count();
        let mut eval = PoseEvaluator::new(
            robot,
            TensionBounds::uniform(n, 1.0, 50.0).unwrap(),
            vec![
                Criterion::TensionFeasible { method: Method::L1, wrench: DVector::from_vec(vec![0.0, -5.0, 0.1]) },
                Criterion::MinCableLength(0.2),
            ],
        )
        .unwrap();
        let g = Grid::new(14, Region::planar(-1.0, 1.0, -1.0, 1.0));
        let run = |threads: usize| {
            rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap()
                .install(|| planar_workspace(&eval, phi, &g).unwrap())
        };
        let (one, two) = (run(1), run(2));
        proptest::prop_assert_eq!(&one, &two);
        for i in 0..one.total_points {
            let u = g.point(2, i);
            proptest::prop_assert_eq!(one.feasible[i], eval.is_feasible(&Pose::planar(u.x, u.y, phi)));
        }
    }
}

/// Issue 17: `PoseEvaluator::feasible_batch` (W from the SIMD batch inverse kinematics when the
/// criteria need W only) gives the pose-by-pose verdicts, for criteria that take the batch
/// path and for ones that do not, on random spatial poses (lists of any length, poses with a
/// zero-length cable or a non-finite position among them); and the grid, which goes through
/// it, gives the per-point verdicts.
mod batch_equals_per_pose {
    use cdpr_kinematics::reference_robots::ipanema_like_8;
    use cdpr_kinematics::{Pose, Robot};
    use cdpr_tension::{Method, TensionBounds};
    use cdpr_workspace::{Criterion, Grid, PoseEvaluator, constant_orientation_workspace};
    use nalgebra::{DVector, Rotation3, Vector3};
    use proptest::prelude::*;

    fn evaluators(robot: &Robot) -> Vec<PoseEvaluator> {
        let bounds = TensionBounds::uniform(8, 1.0, 1000.0).unwrap();
        let gravity = DVector::from_vec(vec![0.0, 0.0, -245.25, 0.0, 0.0, 0.0]);
        let make = |criteria| PoseEvaluator::new(robot.clone(), bounds.clone(), criteria).unwrap();
        vec![
            make(vec![Criterion::WrenchClosure]),
            make(vec![Criterion::TensionFeasible {
                method: Method::L2,
                wrench: gravity.clone(),
            }]),
            // The four-pose tension path: null spaces in lanes (l1, barycentre), and pose by
            // pose (linf).
            make(vec![Criterion::TensionFeasible {
                method: Method::L1,
                wrench: gravity.clone(),
            }]),
            make(vec![Criterion::TensionFeasible {
                method: Method::Barycenter,
                wrench: gravity.clone(),
            }]),
            make(vec![Criterion::TensionFeasible {
                method: Method::Linf,
                wrench: gravity.clone(),
            }]),
            // Not W-only: the pose-by-pose fallback.
            make(vec![
                Criterion::WrenchClosure,
                Criterion::MinCableLength(1.5),
            ]),
        ]
    }

    proptest! {
        #[test]
        fn batch_verdicts_equal_per_pose_verdicts(
            coords in prop::collection::vec(
                (-1.0f64..1.0, -1.0f64..1.0, 0.0f64..2.0, -0.3f64..0.3, -0.3f64..0.3, -0.3f64..0.3),
                0..150,
            ),
            special in prop::collection::vec((0usize..150, 0usize..9), 0..4),
        ) {
            let robot = ipanema_like_8();
            let mut poses: Vec<Pose> = coords
                .iter()
                .map(|&(x, y, z, a, b, c)| Pose::spatial(Vector3::new(x, y, z), a, b, c))
                .collect();
            for (k, i) in special {
                if poses.is_empty() {
                    break;
                }
                let k = k % poses.len();
                if i == 8 {
                    poses[k].position.x = f64::NAN;
                } else {
                    let cable = &robot.cables()[i];
                    poses[k].position = cable.frame - poses[k].rotation * cable.platform;
                }
            }
            for mut eval in evaluators(&robot) {
                let mut batch = vec![false; poses.len()];
                eval.feasible_batch(&poses, &mut batch);
                for (k, pose) in poses.iter().enumerate() {
                    prop_assert_eq!(batch[k], eval.is_feasible(pose), "pose {}", k);
                }
            }
        }
    }

    #[test]
    fn grid_verdicts_equal_per_point_verdicts() {
        let robot = ipanema_like_8();
        let grid = Grid::over_frame(&robot, 9);
        let rotation = Rotation3::from_euler_angles(0.01, -0.02, 0.03);
        for mut eval in evaluators(&robot) {
            let ws = constant_orientation_workspace(&eval, &rotation, &grid).unwrap();
            assert!(ws.feasible_points > 0 && ws.feasible_points < ws.total_points);
            for (idx, &f) in ws.feasible.iter().enumerate() {
                assert_eq!(
                    f,
                    eval.is_feasible(&Pose::new(ws.point(idx), rotation)),
                    "{idx}"
                );
            }
        }
    }
}
