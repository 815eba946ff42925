//! Picard, Caro, Plestan & Claveau 2020, eq. (4) exactly as printed, block by block, against `passive_stiffness` and
//! `active_stiffness` (which implement a rearranged form, see the `stiffness` module docs):
//!
//! ```text
//!   K_p =  Σ k_i [ u uᵀ        u uᵀ b̂ᵀ       ]
//!                [ b̂ u uᵀ      b̂ u uᵀ b̂ᵀ     ]
//!   K_a = −Σ t_i [ −P/l        P b̂ / l        ]      P = I₃ − u uᵀ
//!                [ −b̂ P / l    (û + b̂ P / l) b̂ ]
//! ```
//!
//! with k_i = E S / l_i, u the unit cable vector, b the attachment R b̄ and x̂ the cross-product
//! matrix of x (all in the base frame). The physics of the same K is checked separately by
//! `stiffness_finite_difference.rs`.

use cdpr_kinematics::strategies::arb_robot_and_pose;
use cdpr_wrench::{active_stiffness, passive_stiffness, wrench_components};
use nalgebra::{DMatrix, Matrix3, Matrix6};
use proptest::prelude::*;

/// Writes the 3 × 3 blocks [a b; c d] into a 6 × 6 matrix.
fn blocks(a: Matrix3<f64>, b: Matrix3<f64>, c: Matrix3<f64>, d: Matrix3<f64>) -> Matrix6<f64> {
    let mut m = Matrix6::zeros();
    m.fixed_view_mut::<3, 3>(0, 0).copy_from(&a);
    m.fixed_view_mut::<3, 3>(0, 3).copy_from(&b);
    m.fixed_view_mut::<3, 3>(3, 0).copy_from(&c);
    m.fixed_view_mut::<3, 3>(3, 3).copy_from(&d);
    m
}

/// The rows and columns of a 6 × 6 matrix that a motion pattern keeps.
fn restricted(m: &Matrix6<f64>, idx: &[usize]) -> DMatrix<f64> {
    DMatrix::from_fn(idx.len(), idx.len(), |r, c| m[(idx[r], idx[c])])
}

proptest! {
    #[test]
    fn kp_and_ka_match_the_printed_blocks(
        (robot, pose) in arb_robot_and_pose(0..=3),
        tensions in prop::collection::vec(1.0f64..200.0, 9),
        es in prop::collection::vec(1.0e3f64..1.0e5, 9),
    ) {
        let n = robot.cable_count();
        let (t, es) = (&tensions[..n], &es[..n]);
        let kin = robot.inverse_kinematics(&pose).unwrap();
        let (mut kp, mut ka) = (Matrix6::zeros(), Matrix6::zeros());
        for (i, c) in kin.cables().iter().enumerate() {
            let (u, b, l) = (c.unit, c.attachment, c.length);
            let k = es[i] / l;
            let uu = u * u.transpose();
            let (bh, uh) = (b.cross_matrix(), u.cross_matrix());
            let p = Matrix3::identity() - uu;
            kp += k * blocks(uu, uu * bh.transpose(), bh * uu, bh * uu * bh.transpose());
            ka -= t[i]
                * blocks(
                    -p / l,
                    p * bh / l,
                    -bh * p / l,
                    (uh + bh * p / l) * bh,
                );
        }
        let idx = wrench_components(robot.motion());
        let (kp, ka) = (restricted(&kp, idx), restricted(&ka, idx));
        let ours_p = passive_stiffness(&kin, es).unwrap();
        let ours_a = active_stiffness(&kin, t).unwrap();
        let scale_p = kp.amax().max(1.0);
        let scale_a = ka.amax().max(1.0);
        prop_assert!((&ours_p - &kp).amax() <= 1e-12 * scale_p, "Kp\n{ours_p}\nprinted\n{kp}");
        prop_assert!((&ours_a - &ka).amax() <= 1e-12 * scale_a, "Ka\n{ours_a}\nprinted\n{ka}");
    }
}

/// One hand-derived case: a single cable along +x attached at b = (0, 1, 0), l = 2, t = 10,
/// E S = 400 (k = 200). u uᵀ = e_x e_xᵀ, b × u = (0, 0, −1): K_p = 200 [e_x; −e_z][e_x; −e_z]ᵀ,
/// so K_p(0,0) = 200, K_p(0,5) = K_p(5,0) = −200, K_p(5,5) = 200. K_a(1,1) = K_a(2,2) = t/l = 5.
#[test]
fn single_cable_by_hand() {
    use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
    use nalgebra::Vector3;
    let robot = Robot::new(
        MotionPattern::Spatial,
        vec![Cable {
            frame: Vector3::new(2.0, 1.0, 0.0),
            platform: Vector3::new(0.0, 1.0, 0.0),
            pulley: None,
        }],
    )
    .unwrap();
    let kin = robot
        .inverse_kinematics(&Pose::new(
            Vector3::zeros(),
            nalgebra::Rotation3::identity(),
        ))
        .unwrap();
    let kp = passive_stiffness(&kin, &[400.0]).unwrap();
    assert!((kp[(0, 0)] - 200.0).abs() < 1e-12);
    assert!((kp[(0, 5)] + 200.0).abs() < 1e-12 && (kp[(5, 0)] + 200.0).abs() < 1e-12);
    assert!((kp[(5, 5)] - 200.0).abs() < 1e-12);
    assert!(kp[(1, 1)].abs() < 1e-12);
    let ka = active_stiffness(&kin, &[10.0]).unwrap();
    assert!(ka[(0, 0)].abs() < 1e-12);
    assert!((ka[(1, 1)] - 5.0).abs() < 1e-12 && (ka[(2, 2)] - 5.0).abs() < 1e-12);
}
