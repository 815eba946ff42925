//! K = Kp + Ka against physics: the finite-difference derivative of the restoring wrench of
//! elastic cables (t_i(X) = t_i + k_i (l_i(X) − l_i(X₀)), k_i = E S / l_i(X₀)) at a perturbed pose.

use cdpr_kinematics::strategies::{arb_pulley_robot_and_pose, arb_robot_and_pose};
use cdpr_kinematics::{Pose, Robot};
use cdpr_wrench::{stiffness_matrix, wrench_components};
use nalgebra::{DMatrix, DVector, Rotation3, Vector3};
use proptest::prelude::*;

/// Pose displaced by the 6-D screw `dx` = [δp; δφ] (δφ applied in base coordinates).
fn displaced(pose: &Pose, dx: &[f64; 6]) -> Pose {
    let dp = Vector3::new(dx[0], dx[1], dx[2]);
    let dphi = Vector3::new(dx[3], dx[4], dx[5]);
    Pose::new(pose.position + dp, Rotation3::new(dphi) * pose.rotation)
}

/// −(wrench the cables apply to the platform), i.e. the external wrench balancing them.
fn balancing_wrench(robot: &Robot, pose: &Pose, t0: &[f64], l0: &[f64], k: &[f64]) -> DVector<f64> {
    let kin = robot.inverse_kinematics(pose).unwrap();
    let w = kin.wrench_matrix();
    let t = DVector::from_iterator(
        t0.len(),
        kin.lengths()
            .enumerate()
            .map(|(i, l)| t0[i] + k[i] * (l - l0[i])),
    );
    -(w * t)
}

proptest! {
    #[test]
    fn stiffness_equals_finite_difference_of_restoring_wrench(
        (robot, pose) in arb_robot_and_pose(0..=3),
        tensions in prop::collection::vec(1.0f64..200.0, 9),
        es in prop::collection::vec(1.0e3f64..1.0e5, 9),
    ) {
        check(&robot, &pose, &tensions, &es)?;
    }

    /// The same physics with swivel pulleys (Pott 2018 model): the lengths are the total ones
    /// and W uses the free-segment directions.
    #[test]
    fn pulley_stiffness_equals_finite_difference_of_restoring_wrench(
        (robot, pose) in arb_pulley_robot_and_pose(0..=3),
        tensions in prop::collection::vec(1.0f64..200.0, 9),
        es in prop::collection::vec(1.0e3f64..1.0e5, 9),
    ) {
        check(&robot, &pose, &tensions, &es)?;
    }
}

fn check(robot: &Robot, pose: &Pose, tensions: &[f64], es: &[f64]) -> Result<(), TestCaseError> {
    let (robot, pose) = (robot.clone(), *pose);
    {
        let n = robot.cable_count();
        let (t0, es) = (&tensions[..n], &es[..n]);
        let kin = robot.inverse_kinematics(&pose).unwrap();
        let l0: Vec<f64> = kin.lengths().collect();
        let k: Vec<f64> = es.iter().zip(&l0).map(|(e, l)| e / l).collect();
        let analytic = stiffness_matrix(&kin, t0, es).unwrap();
        let idx = wrench_components(robot.motion());
        let h = 1e-6;
        let mut fd = DMatrix::zeros(idx.len(), idx.len());
        for (col, &j) in idx.iter().enumerate() {
            let mut dx = [0.0; 6];
            dx[j] = h;
            let plus = balancing_wrench(&robot, &displaced(&pose, &dx), t0, &l0, &k);
            dx[j] = -h;
            let minus = balancing_wrench(&robot, &displaced(&pose, &dx), t0, &l0, &k);
            fd.set_column(col, &((plus - minus) / (2.0 * h)));
        }
        let scale = analytic.amax().max(1.0);
        let err = (&analytic - &fd).amax();
        prop_assert!(
            err <= 1e-5 * scale,
            "max |K − K_fd| = {err:e} (scale {scale:e})\nK = {analytic}\nK_fd = {fd}"
        );
    }
    Ok(())
}
