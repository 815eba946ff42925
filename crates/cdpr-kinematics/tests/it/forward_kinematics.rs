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
    assert_eq!(sol.status, ForwardStatus::NoPoseWithinTolerance);
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
        Err(KinematicsError::WrongDimension {
            expected: 4,
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
