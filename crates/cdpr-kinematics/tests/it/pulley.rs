//! The swivel-pulley model (Pott 2018): W = Jᵀ against finite differences of the total length,
//! the geometry of the tangent point, degenerate poses, and straight cables left bit-identical.

use cdpr_kinematics::strategies::{arb_pose, arb_pulley_robot_and_pose, arb_robot_and_pose};
use cdpr_kinematics::{
    Cable, KinematicsError, MotionPattern, Pose, Pulley, PulleyDegeneracy, Robot,
};
use nalgebra::{Rotation3, Vector3};
use proptest::prelude::*;

/// Pose displaced by the twist `dx` = [δp; δφ] given in the motion pattern's coordinates.
fn displaced(motion: MotionPattern, pose: &Pose, dx: &[f64]) -> Pose {
    let (dp, dphi) = match motion {
        MotionPattern::Point2 => (Vector3::new(dx[0], dx[1], 0.0), Vector3::zeros()),
        MotionPattern::Planar => (
            Vector3::new(dx[0], dx[1], 0.0),
            Vector3::new(0.0, 0.0, dx[2]),
        ),
        MotionPattern::Point3 => (Vector3::new(dx[0], dx[1], dx[2]), Vector3::zeros()),
        MotionPattern::Spatial => (
            Vector3::new(dx[0], dx[1], dx[2]),
            Vector3::new(dx[3], dx[4], dx[5]),
        ),
    };
    Pose::new(pose.position + dp, Rotation3::new(dphi) * pose.rotation)
}

/// The 8-cable IPAnema-like robot with 0.1 m pulleys whose axes point up (as in the `.wcrfx`
/// IPAnema file).
fn ipanema_with_pulleys() -> Robot {
    let base = cdpr_kinematics::reference_robots::ipanema_like_8();
    let cables = base
        .cables()
        .iter()
        .map(|c| Cable {
            pulley: Some(Pulley::from_axis(0.1, Vector3::z())),
            ..*c
        })
        .collect();
    Robot::new(MotionPattern::Spatial, cables).unwrap()
}

proptest! {
    /// l̇ = −J q̇ with J = Wᵀ and l the *total* length (arc + free segment), by central finite
    /// differences, for every motion pattern (planar and spatial included).
    #[test]
    fn jacobian_is_minus_derivative_of_total_lengths((robot, pose) in arb_pulley_robot_and_pose(0..=3)) {
        let m = robot.motion();
        let kin = robot.inverse_kinematics(&pose).unwrap();
        let j = kin.jacobian();
        let h = 1e-6;
        for k in 0..m.dof() {
            let mut dx = vec![0.0; m.dof()];
            dx[k] = h;
            let lp: Vec<f64> = robot.inverse_kinematics(&displaced(m, &pose, &dx)).unwrap().lengths().collect();
            dx[k] = -h;
            let lm: Vec<f64> = robot.inverse_kinematics(&displaced(m, &pose, &dx)).unwrap().lengths().collect();
            for i in 0..robot.cable_count() {
                let fd = (lp[i] - lm[i]) / (2.0 * h);
                prop_assert!((fd + j[(i, k)]).abs() < 1e-7, "cable {i}, coordinate {k}: fd {fd}, J {}", j[(i, k)]);
            }
        }
    }

    /// The tangent point lies on the pulley circle in the plane of the axis and the attachment,
    /// the free segment is tangent there, and the cable is never shorter than the straight line.
    #[test]
    fn tangent_point_geometry((robot, pose) in arb_pulley_robot_and_pose(0..=2)) {
        let kin = robot.inverse_kinematics(&pose).unwrap();
        for (i, (c, s)) in robot.cables().iter().zip(kin.cables()).enumerate() {
            let p = c.pulley.unwrap();
            let ps = kin.pulley(i).unwrap();
            let (exit_point, free_length, wrap_angle) = (ps.exit_point, ps.free_length, ps.wrap_angle);
            let q = p.orientation;
            let d = q.transpose() * (s.attachment_point - c.frame);
            let radial = q * Vector3::new(d.x, d.y, 0.0).normalize();
            let centre = c.frame + p.radius * radial;
            prop_assert!(((exit_point - centre).norm() - p.radius).abs() < 1e-12);
            prop_assert!((exit_point - centre).dot(&s.unit).abs() < 1e-12);
            // In the pulley plane: normal k × radial.
            let normal = p.axis().cross(&radial);
            prop_assert!((exit_point - c.frame).dot(&normal).abs() < 1e-12);
            prop_assert!(((exit_point - s.attachment_point).norm() - free_length).abs() < 1e-12);
            prop_assert!((s.length - (p.radius * wrap_angle + free_length)).abs() < 1e-15);
            prop_assert!(s.length >= (s.attachment_point - c.frame).norm() - 1e-12);
            prop_assert!(wrap_angle > 0.0 && wrap_angle < std::f64::consts::TAU);
            prop_assert!((s.unit.norm() - 1.0).abs() < 1e-14);
        }
    }

    /// Shrinking every pulley to nothing gives the straight-cable lengths and directions.
    #[test]
    fn tiny_pulleys_tend_to_straight_cables((robot, pose) in arb_pulley_robot_and_pose(0..=1)) {
        let tiny: Vec<Cable> = robot.cables().iter().map(|c| Cable {
            pulley: c.pulley.map(|p| Pulley { radius: 1e-9, ..p }),
            ..*c
        }).collect();
        let tiny = Robot::new(robot.motion(), tiny).unwrap();
        let a = tiny.inverse_kinematics(&pose).unwrap();
        let b = robot.without_pulleys().inverse_kinematics(&pose).unwrap();
        for (s, t) in a.cables().iter().zip(b.cables()) {
            prop_assert!((s.length - t.length).abs() < 1e-8);
            prop_assert!((s.unit - t.unit).norm() < 1e-8);
        }
    }

    /// Cables without a pulley are computed exactly as before pulleys existed: bit for bit the
    /// straight-cable equations (6.2)–(6.4).
    #[test]
    fn straight_cables_are_bit_identical((robot, pose) in arb_robot_and_pose(0..=3)) {
        let kin = robot.inverse_kinematics(&pose).unwrap();
        let r = pose.rotation.matrix();
        for (i, (c, s)) in robot.cables().iter().zip(kin.cables()).enumerate() {
            let attachment = r * c.platform;
            let attachment_point = pose.position + attachment;
            let vector = c.frame - attachment_point;
            let length = vector.norm();
            prop_assert_eq!(s.vector, vector);
            prop_assert_eq!(s.length.to_bits(), length.to_bits());
            prop_assert_eq!(s.unit, vector / length);
            prop_assert_eq!(s.attachment, attachment);
            prop_assert_eq!(s.attachment_point, attachment_point);
            prop_assert!(kin.pulley(i).is_none());
            prop_assert_eq!(kin.free_length(i).to_bits(), length.to_bits());
            prop_assert_eq!((kin.swivel_angle(i), kin.wrap_angle(i)), (0.0, 0.0));
        }
    }

    /// The planar model keeps its cables in the plane.
    #[test]
    fn planar_pulley_cables_stay_in_the_plane(
        robot in cdpr_kinematics::strategies::arb_pulley_robot(MotionPattern::Planar, 3..=6),
        pose in arb_pose(MotionPattern::Planar),
    ) {
        let kin = robot.inverse_kinematics(&pose).unwrap();
        for (i, s) in kin.cables().iter().enumerate() {
            prop_assert!(s.unit.z.abs() < 1e-14 && kin.exit_point(i).z.abs() < 1e-14);
        }
    }
}

#[test]
fn ipanema_with_pulleys_at_the_centre_by_hand() {
    // Cable 1: a = (2, 1.5, 2), attachment (0.1, 0.1, −0.05) at the pose (0, 0, 1):
    // d = (−1.9, −1.4, −1.05), s = √(1.9² + 1.4²), h = −1.05, ρ = 0.1.
    let robot = ipanema_with_pulleys();
    let kin = robot
        .inverse_kinematics(&Pose::spatial(Vector3::new(0.0, 0.0, 1.0), 0.0, 0.0, 0.0))
        .unwrap();
    let (c, pc) = (kin.cables()[0], *kin.pulley(0).unwrap());
    let (s, h, rho) = ((1.9f64 * 1.9 + 1.4 * 1.4).sqrt(), -1.05f64, 0.1);
    let bm = ((s - rho).powi(2) + h * h).sqrt();
    let lf = (bm * bm - rho * rho).sqrt();
    // s ≥ ρ: the form of β applies.
    let beta = (lf / bm).acos() + (h / bm).acos();
    assert!((pc.wrap_angle - beta).abs() < 1e-14);
    assert!((pc.free_length - lf).abs() < 1e-14);
    assert!((c.length - (rho * beta + lf)).abs() < 1e-14);
    assert!((pc.swivel_angle() - (-1.4f64).atan2(-1.9)).abs() < 1e-15);
    // The top cables wrap more than a quarter turn (the cable arrives going up).
    assert!(pc.wrap_angle > std::f64::consts::FRAC_PI_2);
}

#[test]
fn degenerate_poses_are_errors_naming_the_cable() {
    let pulley = Some(Pulley::from_axis(0.2, Vector3::z()));
    let robot = Robot::new(
        MotionPattern::Point3,
        vec![
            Cable {
                frame: Vector3::new(2.0, 0.0, 0.0),
                platform: Vector3::zeros(),
                pulley: None,
            },
            Cable {
                frame: Vector3::new(0.0, 0.0, 2.0),
                platform: Vector3::zeros(),
                pulley,
            },
        ],
    )
    .unwrap();
    assert!(matches!(
        robot.inverse_kinematics(&Pose::point(0.0, 0.0, 0.0)),
        Err(KinematicsError::DegeneratePulley {
            cable: 1,
            reason: PulleyDegeneracy::OnSwivelAxis,
            ..
        })
    ));
    // 0.05 from the pulley centre (0.2, 0, 2).
    assert!(matches!(
        robot.inverse_kinematics(&Pose::point(0.25, 0.0, 2.0)),
        Err(KinematicsError::DegeneratePulley {
            cable: 1,
            reason: PulleyDegeneracy::InsidePulley,
            ..
        })
    ));
    assert!(
        robot
            .inverse_kinematics(&Pose::point(0.5, 0.0, 0.0))
            .is_ok()
    );
}

#[test]
fn invalid_pulleys_are_rejected_by_robot_new() {
    let cable = |p: Pulley| Cable {
        frame: Vector3::new(1.0, 0.0, 0.0),
        platform: Vector3::zeros(),
        pulley: Some(p),
    };
    for bad in [
        Pulley::from_axis(-0.1, Vector3::z()),
        Pulley::from_axis(f64::NAN, Vector3::z()),
        Pulley {
            radius: 0.1,
            orientation: nalgebra::Matrix3::zeros(),
        },
        Pulley {
            radius: 0.1,
            orientation: nalgebra::Matrix3::identity() * 2.0,
        },
    ] {
        assert!(matches!(
            Robot::new(MotionPattern::Point3, vec![cable(bad)]),
            Err(KinematicsError::InvalidPulley { cable: 0, .. })
        ));
    }
    // A 2-D robot's pulley must swivel about an in-plane axis.
    assert!(
        Robot::new(
            MotionPattern::Point2,
            vec![cable(Pulley::from_axis(0.1, Vector3::z()))]
        )
        .is_err()
    );
    assert!(
        Robot::new(
            MotionPattern::Point2,
            vec![cable(Pulley::from_axis(0.1, Vector3::y()))]
        )
        .is_ok()
    );
}

proptest! {
    /// δu = −(1/l_f) (I − u uᵀ − (s_C/s) e_n e_nᵀ) δB, the variation the pulley stiffness uses,
    /// against central differences of u under translations of a point platform.
    #[test]
    fn free_segment_direction_varies_as_documented(
        robot in cdpr_kinematics::strategies::arb_pulley_robot(MotionPattern::Point3, 3..=5),
        pose in arb_pose(MotionPattern::Point3),
    ) {
        let kin = robot.inverse_kinematics(&pose).unwrap();
        let h = 1e-6;
        for j in 0..3 {
            let mut e = Vector3::zeros();
            e[j] = h;
            let plus = robot.inverse_kinematics(&Pose::new(pose.position + e, pose.rotation)).unwrap();
            let minus = robot.inverse_kinematics(&Pose::new(pose.position - e, pose.rotation)).unwrap();
            for (i, s) in kin.cables().iter().enumerate() {
                let fd = (plus.cables()[i].unit - minus.cables()[i].unit) / (2.0 * h);
                let ps = kin.pulley(i).unwrap();
                let p = nalgebra::Matrix3::identity() - s.unit * s.unit.transpose()
                    - ps.swivel_ratio * ps.plane_normal * ps.plane_normal.transpose();
                let analytic = -(p * e / h) / ps.free_length;
                prop_assert!((fd - analytic).norm() < 1e-7, "cable {i}, axis {j}: {fd} vs {analytic}");
            }
        }
    }
}
