//! Forward kinematics: IK → FK round trips (straight and pulley models), the least-squares pose
//! of noisy lengths, outcomes that are not errors, multi-start and the path (batch) API.

use cdpr_kinematics::reference_robots::{
    ipanema_like_8, ipanema_like_8_pulleys, thesis_four_cable,
};
use cdpr_kinematics::strategies::{arb_pulley_robot_and_pose, arb_robot_and_pose};
use cdpr_kinematics::{
    Cable, ForwardKinematics, ForwardSettings, ForwardStatus, KinematicsError, MotionPattern, Pose,
    Robot,
};
use nalgebra::{Rotation3, Vector3};
use proptest::prelude::*;

/// ‖R₁ − R₂‖_F ≈ √2 × the angle between them (acos of the trace loses half the digits).
fn rotation_distance(a: &Rotation3<f64>, b: &Rotation3<f64>) -> f64 {
    (a.matrix() - b.matrix()).norm()
}

/// `pose` moved by 2 cm and 0.02 rad along fixed directions (only the pattern's components).
fn nearby(motion: MotionPattern, pose: &Pose, sign: f64) -> Pose {
    let dp = Vector3::new(0.02, -0.015, 0.01) * sign;
    let dp = if motion.space_dim() == 2 {
        Vector3::new(dp.x, dp.y, 0.0)
    } else {
        dp
    };
    let rotation = match motion {
        MotionPattern::Planar => {
            Rotation3::new(Vector3::new(0.0, 0.0, 0.02 * sign)) * pose.rotation
        }
        MotionPattern::Spatial => {
            Rotation3::new(Vector3::new(0.012, -0.01, 0.012) * sign) * pose.rotation
        }
        _ => pose.rotation,
    };
    Pose::new(pose.position + dp, rotation)
}

fn round_trip(robot: &Robot, pose: &Pose, sign: f64) -> Result<(), TestCaseError> {
    let lengths: Vec<f64> = robot.inverse_kinematics(pose).unwrap().lengths().collect();
    // Started at the answer, the solver only certifies it: σ_min of J at the true pose.
    let at_truth = robot
        .forward_kinematics(&lengths, pose, ForwardSettings::default())
        .unwrap();
    prop_assert_eq!(at_truth.pose, *pose);
    // Well-conditioned poses only: pose error ≈ length error / σ_min, and a random robot near a
    // singularity has other solutions within centimetres of the true pose.
    prop_assume!(at_truth.min_singular_value > 0.05);
    let guess = nearby(robot.motion(), pose, 0.2 * sign);
    let Ok(sol) = robot.forward_kinematics(&lengths, &guess, ForwardSettings::default()) else {
        // The guess itself is degenerate: nothing to test.
        return Ok(());
    };
    if sol.status == ForwardStatus::AboveAnchors {
        // A random robot whose anchors span little height, posed above them: the flag of the
        // mirror pose, honest here too (every cable descends from the platform).
        prop_assert!(robot.is_suspended());
        let kin = robot.inverse_kinematics(&sol.pose).unwrap();
        prop_assert!(kin.cables().iter().all(|c| c.unit.z <= 1e-9));
        return Ok(());
    }
    prop_assert_eq!(sol.status, ForwardStatus::Solved, "{:?}", sol);
    prop_assert!(sol.converged && sol.residual <= 1e-12, "{:?}", sol);
    prop_assert!(
        (sol.pose.position - pose.position).norm() < 1e-9,
        "{:?} vs {:?}",
        sol.pose,
        pose
    );
    prop_assert!(rotation_distance(&sol.pose.rotation, &pose.rotation) < 1e-9);
    // The certificate is honest: the residual is the one at the returned pose.
    let back: Vec<f64> = robot
        .inverse_kinematics(&sol.pose)
        .unwrap()
        .lengths()
        .collect();
    let residual = back
        .iter()
        .zip(&lengths)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    prop_assert_eq!(residual, sol.residual);
    Ok(())
}

proptest! {
    /// IK → FK recovers the pose to 1e-9 from 4 mm / 4 mrad away (the bench's 2 cm / 0.02 rad
    /// on the 8-cable robots below), straight cables, every motion pattern.
    #[test]
    fn round_trip_straight((robot, pose) in arb_robot_and_pose(0..=3), sign in prop::sample::select(vec![-1.0, 1.0])) {
        round_trip(&robot, &pose, sign)?;
    }

    /// IK → FK recovers the pose to 1e-9 with swivel pulleys, every motion pattern.
    #[test]
    fn round_trip_pulley((robot, pose) in arb_pulley_robot_and_pose(0..=3), sign in prop::sample::select(vec![-1.0, 1.0])) {
        round_trip(&robot, &pose, sign)?;
    }
}

#[test]
fn ipanema_round_trips_from_the_bench_guess() {
    for robot in [ipanema_like_8(), ipanema_like_8_pulleys()] {
        let truth = Pose::spatial(Vector3::new(0.4, -0.3, 1.2), 0.05, -0.08, 0.1);
        let lengths: Vec<f64> = robot
            .inverse_kinematics(&truth)
            .unwrap()
            .lengths()
            .collect();
        let sol = robot
            .forward_kinematics(
                &lengths,
                &nearby(MotionPattern::Spatial, &truth, 1.0),
                ForwardSettings::default(),
            )
            .unwrap();
        assert_eq!(sol.status, ForwardStatus::Solved);
        assert!((sol.pose.position - truth.position).norm() < 1e-12);
        assert!(rotation_distance(&sol.pose.rotation, &truth.rotation) < 1e-12);
        assert!(sol.iterations <= 8, "{} iterations", sol.iterations);
    }
}

/// Four cables on a point from (±1, 0) and (0, ±1) with the x cables' lengths perturbed by
/// e₁, e₂: by symmetry y = 0, and x minimises (x + e₁)² + (x − e₂)² + 2(√(1 + x²) − 1)², whose
/// stationarity condition 2(x + e₁) + 2(x − e₂) + 4x(1 − 1/√(1 + x²)) = 0 we solve by scalar
/// Newton independently of the solver.
#[test]
fn noisy_lengths_give_the_least_squares_pose() {
    let cable = |x: f64, y: f64| Cable {
        frame: Vector3::new(x, y, 0.0),
        platform: Vector3::zeros(),
        pulley: None,
    };
    let robot = Robot::new(
        MotionPattern::Point2,
        vec![
            cable(1.0, 0.0),
            cable(-1.0, 0.0),
            cable(0.0, 1.0),
            cable(0.0, -1.0),
        ],
    )
    .unwrap();
    let (e1, e2) = (0.013, -0.007);
    let lengths = [1.0 + e1, 1.0 + e2, 1.0, 1.0];
    let f = |x: f64| 2.0 * (x + e1) + 2.0 * (x - e2) + 4.0 * x * (1.0 - 1.0 / (1.0 + x * x).sqrt());
    let mut x = 0.0;
    for _ in 0..50 {
        let h = 1e-7;
        x -= f(x) / ((f(x + h) - f(x - h)) / (2.0 * h));
    }
    assert!(f(x).abs() < 1e-15);
    let sol = robot
        .forward_kinematics(
            &lengths,
            &Pose::point(0.1, 0.1, 0.0),
            ForwardSettings::default(),
        )
        .unwrap();
    assert!(sol.converged);
    // Residuals of about 1 cm are inconsistent with the default length noise of 0.1 mm …
    assert_eq!(sol.status, ForwardStatus::Inconsistent);
    // … and consistent with a noise of 1 cm: ‖r‖² / σ² below χ²(2) at 99.9 % (13.8).
    let loose = ForwardSettings {
        length_sigma: 0.01,
        ..Default::default()
    };
    let fitted = robot
        .forward_kinematics(&lengths, &Pose::point(0.1, 0.1, 0.0), loose)
        .unwrap();
    assert_eq!(fitted.status, ForwardStatus::Fitted);
    assert_eq!(fitted.pose, sol.pose);
    assert!(
        (sol.pose.position.x - x).abs() < 1e-12,
        "{} vs {x}",
        sol.pose.position.x
    );
    assert!(sol.pose.position.y.abs() < 1e-12);
    // The residual is that of the least-squares pose, not zero.
    assert!((sol.residual - (x + e1).abs().max((x - e2).abs())).abs() < 1e-12);
}

#[test]
fn unreachable_lengths_are_an_outcome_not_an_error() {
    let cable = |x: f64| Cable {
        frame: Vector3::new(x, 0.0, 0.0),
        platform: Vector3::zeros(),
        pulley: None,
    };
    let robot = Robot::new(MotionPattern::Point2, vec![cable(-1.0), cable(1.0)]).unwrap();
    // Two circles of radius 0.5 two apart do not meet.
    let sol = robot
        .forward_kinematics(
            &[0.5, 0.5],
            &Pose::point(0.1, 0.3, 0.0),
            ForwardSettings::default(),
        )
        .unwrap();
    assert_eq!(sol.status, ForwardStatus::NoPoseWithinTolerance);
    assert!(sol.residual >= 0.5 - 1e-9);
    // One iteration from far away: did not converge, and says so.
    let lengths: Vec<f64> = robot
        .inverse_kinematics(&Pose::point(0.2, 0.9, 0.0))
        .unwrap()
        .lengths()
        .collect();
    let sol = robot
        .forward_kinematics(
            &lengths,
            &Pose::point(0.5, 0.1, 0.0),
            ForwardSettings {
                max_iterations: 1,
                ..Default::default()
            },
        )
        .unwrap();
    assert_eq!(sol.status, ForwardStatus::NotConverged);
    assert!(!sol.converged && sol.residual > 1e-3 && sol.iterations == 1);
}

#[test]
fn bad_input_is_an_error() {
    let robot = thesis_four_cable();
    let guess = Pose::planar(0.0, 0.0, 0.0);
    let s = ForwardSettings::default();
    assert!(matches!(
        robot.forward_kinematics(&[1.0; 3], &guess, s),
        Err(KinematicsError::WrongCableCount {
            cables: 4,
            found: 3,
            ..
        })
    ));
    assert!(matches!(
        robot.forward_kinematics(&[1.0, f64::NAN, 1.0, 1.0], &guess, s),
        Err(KinematicsError::NotFinite { .. })
    ));
    let two = robot.permuted(&[0, 1]).unwrap();
    assert!(matches!(
        ForwardKinematics::new(&two, s),
        Err(KinematicsError::TooFewCables { cables: 2, dof: 3 })
    ));
}

#[test]
fn multistart_finds_the_pose_and_only_distinct_solutions() {
    let robot = thesis_four_cable();
    let truth = Pose::planar(0.2, -0.1, 0.3);
    let lengths: Vec<f64> = robot
        .inverse_kinematics(&truth)
        .unwrap()
        .lengths()
        .collect();
    let mut fk = ForwardKinematics::new(&robot, ForwardSettings::default()).unwrap();
    let solutions = fk.solve_multistart(&lengths).unwrap();
    assert!(!solutions.is_empty());
    assert!(solutions.iter().all(|s| s.status == ForwardStatus::Solved));
    assert!(solutions.iter().any(|s| {
        (s.pose.position - truth.position).norm() < 1e-9
            && rotation_distance(&s.pose.rotation, &truth.rotation) < 1e-9
    }));
    for (i, a) in solutions.iter().enumerate() {
        for b in &solutions[i + 1..] {
            let d = (a.pose.position - b.pose.position).norm()
                + rotation_distance(&a.pose.rotation, &b.pose.rotation);
            assert!(d > 1e-6);
        }
    }
    // The spatial pulley robot, too.
    let robot = ipanema_like_8_pulleys();
    let truth = Pose::spatial(Vector3::new(-0.5, 0.3, 0.8), 0.1, 0.0, -0.2);
    let lengths: Vec<f64> = robot
        .inverse_kinematics(&truth)
        .unwrap()
        .lengths()
        .collect();
    let mut fk = ForwardKinematics::new(&robot, ForwardSettings::default()).unwrap();
    let solutions = fk.solve_multistart(&lengths).unwrap();
    assert!(
        solutions
            .iter()
            .any(|s| (s.pose.position - truth.position).norm() < 1e-9)
    );
    // Distinct: before the fix, equal rotations compared by `angle_to` (NaN) counted as new.
    for (i, a) in solutions.iter().enumerate() {
        for b in &solutions[i + 1..] {
            let d = (a.pose.position - b.pose.position).norm()
                + rotation_distance(&a.pose.rotation, &b.pose.rotation);
            assert!(d > 1e-6, "{a:?} and {b:?} are the same pose");
        }
    }
}

#[test]
fn path_solves_start_from_the_previous_pose() {
    let robot = ipanema_like_8_pulleys();
    let poses: Vec<Pose> = (0..20)
        .map(|k| {
            let t = k as f64 / 19.0;
            Pose::spatial(
                Vector3::new(-0.5 + t, 0.2 * t, 1.0),
                0.05 * t,
                0.0,
                -0.1 * t,
            )
        })
        .collect();
    let lengths: Vec<f64> = poses
        .iter()
        .flat_map(|p| {
            robot
                .inverse_kinematics(p)
                .unwrap()
                .lengths()
                .collect::<Vec<_>>()
        })
        .collect();
    let mut fk = ForwardKinematics::new(&robot, ForwardSettings::default()).unwrap();
    let solutions = fk.solve_path(&lengths, &poses[0]).unwrap();
    assert_eq!(solutions.len(), 20);
    for (s, p) in solutions.iter().zip(&poses) {
        assert_eq!(s.status, ForwardStatus::Solved);
        assert!((s.pose.position - p.position).norm() < 1e-9);
    }
    assert!(fk.solve_path(&lengths[..7], &poses[0]).is_err());
}

/// The step rule comes before the trial pose: from a guess 3·10⁻¹⁴ m from the pose of the
/// lengths (residual within the tolerance, Gauss–Newton step below 10⁻¹³ × the length scale)
/// the solver stops at the guess itself, without moving it by that step, for both cable models.
#[test]
fn a_step_below_the_tolerance_leaves_a_solving_pose_unmoved() {
    for robot in [ipanema_like_8(), ipanema_like_8_pulleys()] {
        let mut fk = ForwardKinematics::new(&robot, ForwardSettings::default()).unwrap();
        let mut unmoved = 0;
        for k in 0..20 {
            let t = k as f64;
            let pose = Pose::spatial(
                Vector3::new(0.3 * t.sin(), 0.2 * t.cos(), 1.0 + 0.1 * (0.7 * t).sin()),
                0.05 * t.cos(),
                -0.04 * t.sin(),
                0.03 * (1.3 * t).cos(),
            );
            let lengths: Vec<f64> = robot.inverse_kinematics(&pose).unwrap().lengths().collect();
            let guess = Pose::new(pose.position + Vector3::new(3e-14, 0.0, 0.0), pose.rotation);
            let sol = fk.solve(&lengths, &guess).unwrap();
            assert_eq!(sol.status, ForwardStatus::Solved);
            assert!(sol.converged && sol.iterations <= 1, "{sol:?}");
            if sol.pose == guess {
                unmoved += 1;
            }
        }
        assert_eq!(unmoved, 20);
    }
}

/// The spidercam-like stadium robot of `examples/robots/spidercam-like-4.toml`.
fn spidercam() -> Robot {
    let c = |x: f64, y: f64| Cable::point3(Vector3::new(x, y, 30.0));
    Robot::new(
        MotionPattern::Point3,
        vec![
            c(50.0, 35.0),
            c(-50.0, 35.0),
            c(-50.0, -35.0),
            c(50.0, -35.0),
        ],
    )
    .unwrap()
}

/// The NIST RoboCrane of `examples/robots/caspr-nist-robocrane.toml` (CASPR model).
fn robocrane() -> Robot {
    let f = [
        [-3.0, -1.7321, 3.0],
        [-3.0, -1.7321, 3.0],
        [3.0, -1.7321, 3.0],
        [3.0, -1.7321, 3.0],
        [0.0, 3.4642, 3.0],
        [0.0, 3.4642, 3.0],
    ];
    let a = [
        [0.0, -0.866, 0.0],
        [-0.75, 0.433, 0.0],
        [0.0, -0.866, 0.0],
        [0.75, 0.433, 0.0],
        [-0.75, 0.433, 0.0],
        [0.75, 0.433, 0.0],
    ];
    let cables = f
        .iter()
        .zip(&a)
        .map(|(f, a)| Cable::spatial(Vector3::from(*f), Vector3::from(*a)))
        .collect();
    Robot::new(MotionPattern::Spatial, cables).unwrap()
}

/// Issue 27: exact lengths at (0, 0, 10) under four anchors at z = 30: the multi-start finds
/// the hanging pose without a guess (it answered (0, 0, 30) with a residual of 3.2 m), and the
/// mirror pose above the anchors is flagged, not solved.
#[test]
fn a_suspended_robot_is_found_hanging_without_a_guess() {
    let robot = spidercam();
    let truth = Pose::point(0.0, 0.0, 10.0);
    let lengths: Vec<f64> = robot
        .inverse_kinematics(&truth)
        .unwrap()
        .lengths()
        .collect();
    let mut fk = ForwardKinematics::new(&robot, ForwardSettings::default()).unwrap();
    let sols = fk.solve_multistart(&lengths).unwrap();
    assert_eq!(sols[0].status, ForwardStatus::Solved, "{sols:?}");
    assert!(
        (sols[0].pose.position - truth.position).norm() < 1e-9,
        "{sols:?}"
    );
    assert!(sols.iter().all(|s| s.pose.position.z < 30.0), "{sols:?}");
    // The mirror image (0, 0, 50) solves the lengths too, but hangs above the anchors.
    let mirror = fk.solve(&lengths, &Pose::point(0.0, 0.0, 45.0)).unwrap();
    assert!((mirror.pose.position.z - 50.0).abs() < 1e-6, "{mirror:?}");
    assert_eq!(mirror.status, ForwardStatus::AboveAnchors);
    assert!(!mirror.status.is_solution());
}

/// Issue 27: the RoboCrane's multi-start finds its home pose (0, 0, 1.5, 0, 0, 0) without a
/// guess (it returned four solved poses, none the home pose).
#[test]
fn the_robocrane_home_pose_is_found_without_a_guess() {
    let robot = robocrane();
    let home = Pose::spatial(Vector3::new(0.0, 0.0, 1.5), 0.0, 0.0, 0.0);
    let lengths: Vec<f64> = robot.inverse_kinematics(&home).unwrap().lengths().collect();
    let mut fk = ForwardKinematics::new(&robot, ForwardSettings::default()).unwrap();
    let sols = fk.solve_multistart(&lengths).unwrap();
    let found = sols.iter().find(|s| {
        (s.pose.position - home.position).norm() < 1e-8
            && rotation_distance(&s.pose.rotation, &home.rotation) < 1e-8
    });
    assert!(found.is_some(), "{sols:?}");
    assert!(sols.iter().all(|s| s.status == ForwardStatus::Solved));
    // None of the answers hangs above the anchors.
    assert!(sols.iter().all(|s| s.pose.position.z < 3.0), "{sols:?}");
}

/// Issue 27: lengths rounded to 0.1 mm (4 cables, 3 DOF) are `fitted`, not "no pose within
/// tolerance", with the right pose, and the reported standard deviations are those of
/// σ² (JᵀJ)⁻¹ (checked against nalgebra's inverse).
#[test]
fn rounded_lengths_are_fitted_with_the_right_pose() {
    let robot = spidercam();
    let truth = Pose::point(3.0, -7.0, 10.0);
    let exact: Vec<f64> = robot
        .inverse_kinematics(&truth)
        .unwrap()
        .lengths()
        .collect();
    let rounded: Vec<f64> = exact.iter().map(|l| (l * 1e4).round() / 1e4).collect();
    let mut fk = ForwardKinematics::new(&robot, ForwardSettings::default()).unwrap();
    let sols = fk.solve_multistart(&rounded).unwrap();
    let s = sols[0];
    assert_eq!(s.status, ForwardStatus::Fitted, "{s:?}");
    assert!((s.pose.position - truth.position).norm() < 1e-3, "{s:?}");
    let rms = (rounded
        .iter()
        .zip(robot.inverse_kinematics(&s.pose).unwrap().lengths())
        .map(|(a, b)| (a - b) * (a - b))
        .sum::<f64>()
        / 4.0)
        .sqrt();
    assert!(
        (s.residual_rms - rms).abs() < 1e-15,
        "{} vs {rms}",
        s.residual_rms
    );
    let w = robot.inverse_kinematics(&s.pose).unwrap().wrench_matrix();
    let cov = (&w * w.transpose()).try_inverse().unwrap() * 1e-8;
    for k in 0..3 {
        let expected = cov[(k, k)].sqrt();
        assert!(
            (s.pose_std(3)[k] - expected).abs() < 1e-12 * expected,
            "{k}: {} vs {expected}",
            s.pose_std(3)[k]
        );
    }
    // Lengths off by 5 cm are inconsistent.
    let mut bad = exact.clone();
    bad[0] += 0.05;
    assert_eq!(
        fk.solve_multistart(&bad).unwrap()[0].status,
        ForwardStatus::Inconsistent
    );
}

/// Issue 25: the cable count, not the motion pattern, is blamed; negative lengths are errors.
#[test]
fn wrong_count_and_negative_lengths_are_named() {
    let robot = spidercam();
    let mut fk = ForwardKinematics::new(&robot, ForwardSettings::default()).unwrap();
    let e = fk.solve_multistart(&[1.0, 1.0, 1.0]).unwrap_err();
    assert!(matches!(
        e,
        KinematicsError::WrongCableCount {
            cables: 4,
            found: 3,
            ..
        }
    ));
    assert!(e.to_string().contains("4 cables"), "{e}");
    assert!(!e.to_string().contains("motion pattern"), "{e}");
    let e = fk.solve_multistart(&[30.0, -1.0, 30.0, 30.0]).unwrap_err();
    assert_eq!(
        e,
        KinematicsError::NegativeLength {
            cable: 1,
            value: -1.0
        }
    );
    assert!(e.to_string().contains("cable 2"), "{e}");
    let bad = ForwardSettings {
        length_sigma: -1.0,
        ..Default::default()
    };
    assert!(bad.validate().is_err());
}

/// The χ² quantile of the `fitted` test against tabulated values (Abramowitz & Stegun 1964,
/// Table 26.8, 0.999 column): at most 3.1 % above.
#[test]
fn chi_square_quantiles_are_close_to_the_table() {
    for (k, exact) in [
        (1, 10.828),
        (2, 13.816),
        (5, 20.515),
        (10, 29.588),
        (30, 59.703),
    ] {
        let q = cdpr_kinematics::chi_square_quantile_999(k);
        assert!(q >= exact && q <= 1.031 * exact, "{k}: {q} vs {exact}");
    }
    assert_eq!(cdpr_kinematics::chi_square_quantile_999(0), 0.0);
}
