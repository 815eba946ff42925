//! Properties of the inverse kinematics and the wrench matrix W = Jᵀ.

use cdpr_kinematics::strategies::{arb_pose, arb_robot, arb_robot_and_pose};
use cdpr_kinematics::{MotionPattern, Pose, Robot};
use nalgebra::{DMatrix, Rotation3, Vector3};
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

proptest! {
    /// Eq. (6.7): l̇ = −J q̇, checked by central finite differences of the lengths.
    #[test]
    fn jacobian_is_minus_derivative_of_lengths((robot, pose) in arb_robot_and_pose(0..=3)) {
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

    /// Reordering the cables reorders the columns of W and nothing else.
    #[test]
    fn wrench_matrix_is_invariant_to_cable_order(
        robot in arb_robot(MotionPattern::Spatial, 6..=9),
        pose in arb_pose(MotionPattern::Spatial),
        seed in any::<u64>(),
    ) {
        let n = robot.cable_count();
        let mut order: Vec<usize> = (0..n).collect();
        // Fisher–Yates with a tiny LCG so that the permutation comes from the seed.
        let mut s = seed;
        for i in (1..n).rev() {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            order.swap(i, (s >> 33) as usize % (i + 1));
        }
        let w = robot.inverse_kinematics(&pose).unwrap().wrench_matrix();
        let wp = robot.permuted(&order).unwrap().inverse_kinematics(&pose).unwrap().wrench_matrix();
        for (k, &i) in order.iter().enumerate() {
            prop_assert_eq!(wp.column(k), w.column(i));
        }
    }

    /// A spatial robot whose anchors lie in z = 0, at a planar pose, has the planar W as its
    /// (f_x, f_y, τ_z) rows, and zero f_z, τ_x, τ_y rows.
    #[test]
    fn spatial_reduces_to_planar(robot in arb_robot(MotionPattern::Planar, 3..=8), pose in arb_pose(MotionPattern::Planar)) {
        let spatial = Robot::new(MotionPattern::Spatial, robot.cables().to_vec()).unwrap();
        let wp = robot.inverse_kinematics(&pose).unwrap().wrench_matrix();
        let ws = spatial.inverse_kinematics(&pose).unwrap().wrench_matrix();
        let reduced = DMatrix::from_rows(&[ws.row(0).into_owned(), ws.row(1).into_owned(), ws.row(5).into_owned()]);
        prop_assert!((&reduced - &wp).amax() < 1e-15);
        prop_assert!(ws.row(2).amax() < 1e-15 && ws.row(3).amax() < 1e-15 && ws.row(4).amax() < 1e-15);
    }

    /// The buffer-reusing path gives the same answer as the allocating one.
    #[test]
    fn update_kinematics_matches_inverse_kinematics((robot, pose) in arb_robot_and_pose(0..=2), (r2, p2) in arb_robot_and_pose(0..=2)) {
        let mut kin = r2.inverse_kinematics(&p2).unwrap();
        robot.update_kinematics(&pose, &mut kin).unwrap();
        prop_assert_eq!(kin, robot.inverse_kinematics(&pose).unwrap());
    }
}
