//! # Stiffness matrix K = Kp + Ka
//!
//! The stiffness of the platform, K = δw_e / δX (Picard, Caro, Plestan & Claveau 2020, eq. (3)), for a small displacement
//! screw δX = [δp; δφ] (δφ: small rotation vector in base coordinates, applied as
//! R ← exp([δφ]×) R), with linear elastic cables of stiffness k_i = E S / l_i.
//!
//! Per cable, with unit vector u (from the platform attachment towards the frame anchor),
//! attachment b = R b̄ (relative to the platform origin), length l, tension t,
//! P = I − u uᵀ, G = [u; b × u] and H = [I₃; b̂] (b̂: cross-product matrix of b):
//!
//! ```text
//!   K_p = Σ k_i G_i G_iᵀ                                  (Picard, Caro, Plestan & Claveau 2020, eq. (4), passive part)
//!   K_a = Σ (t_i / l_i) H_i P_i H_iᵀ − t_i [0 0; 0 û_i b̂_i]   (Picard, Caro, Plestan & Claveau 2020, eq. (4), active part)
//! ```
//!
//! This is Picard, Caro, Plestan & Claveau's (2020) eq. (4) rewritten with b̂ᵀ = −b̂; `tests/it/stiffness_printed_eq4.rs` checks it
//! against the printed blocks assembled literally. We derived it independently from the
//! restoring wrench of elastic cables (see `docs/algorithms.md`) and the property test
//! `tests/it/stiffness_finite_difference.rs` checks it against the finite-difference derivative of
//! that wrench: the printed formula and the physics agree. K is not symmetric when cables are
//! tensioned and attachments are off the platform origin (the û b̂ term).
//!
//! Reduced motion patterns use the rows/columns of their wrench components: planar (x, y, φ_z),
//! point2 (x, y), point3 (x, y, z); these are exactly the sub-blocks of the 6 × 6 matrix for
//! motions confined to the pattern.
//!
//! **Pulley cables** (swivel-pulley model of Pott 2018, `cdpr_kinematics` module `pulley`):
//! k_i = E S / L_i with the total length L_i = ρ β + l_f (the wrapped arc stretches too), u the
//! free-segment direction, and in K_a
//!
//! ```text
//!   t_i / l_i → t_i / l_f,i,    P_i → P̃_i = I − u uᵀ − (s_C / s) e_n e_nᵀ
//! ```
//!
//! because the free segment's direction varies as δu = −(1/l_f) P̃ δB: an attachment motion δB
//! along u leaves u unchanged; one in the pulley plane normal to u turns the tangent line while
//! the tangent point slides along it (tangency), as for a straight cable of length l_f; one along
//! the plane normal e_n swivels the pulley by δB·e_n / s, which carries the tangent point by
//! (s_C / s) δB·e_n along e_n (s, s_C: distances of the attachment and of the tangent point from
//! the swivel axis). This is exact, not an approximation: the finite-difference property test
//! runs on pulley robots too. Straight cables use the straight-cable formula unchanged.
//!
//! ## References
//! - Picard, Caro, Plestan & Claveau 2020, eqs. (3)–(4); Behzadipour & Khajepour (2006).
//! - Pott, *Cable-Driven Parallel Robots*, Springer 2018 (pulley kinematics).

use crate::WrenchError;
use crate::error::check_slice;
use cdpr_kinematics::{MotionPattern, PoseKinematics};
use nalgebra::{DMatrix, Matrix3, Matrix6};

/// Which rows/columns of the 6 × 6 spatial matrix a motion pattern keeps.
pub fn wrench_components(motion: MotionPattern) -> &'static [usize] {
    match motion {
        MotionPattern::Point2 => &[0, 1],
        MotionPattern::Planar => &[0, 1, 5],
        MotionPattern::Point3 => &[0, 1, 2],
        MotionPattern::Spatial => &[0, 1, 2, 3, 4, 5],
    }
}

fn hat(v: &nalgebra::Vector3<f64>) -> Matrix3<f64> {
    v.cross_matrix()
}

/// The two parts of K at one pose, 6 × 6 (before restriction to the motion pattern).
fn spatial_parts(
    kin: &PoseKinematics,
    tensions: &[f64],
    axial_stiffness: &[f64],
) -> Result<(Matrix6<f64>, Matrix6<f64>), WrenchError> {
    let n = kin.cable_count();
    check_slice("tension", tensions, n)?;
    check_slice("axial stiffness", axial_stiffness, n)?;
    if let Some((cable, &value)) = axial_stiffness.iter().enumerate().find(|(_, v)| **v <= 0.0) {
        return Err(WrenchError::NonPositiveStiffness { cable, value });
    }
    let mut kp = Matrix6::zeros();
    let mut ka = Matrix6::zeros();
    for (i, ((c, &t), &es)) in kin
        .cables()
        .iter()
        .zip(tensions)
        .zip(axial_stiffness)
        .enumerate()
    {
        let k = es / c.length;
        let (u, b) = (c.unit, c.attachment);
        let bh = hat(&b);
        let g =
            nalgebra::Vector6::from_iterator(u.iter().copied().chain(b.cross(&u).iter().copied()));
        kp += k * g * g.transpose();
        let mut p = Matrix3::identity() - u * u.transpose();
        let mut s = t / c.length;
        if let Some(pulley) = kin.pulley(i) {
            // The swivel carries the tangent point along e_n (module docs).
            let e = pulley.plane_normal;
            p -= pulley.swivel_ratio * e * e.transpose();
            s = t / pulley.free_length;
        }
        let pbt = p * bh.transpose();
        let mut blk = Matrix6::zeros();
        blk.fixed_view_mut::<3, 3>(0, 0).copy_from(&(s * p));
        blk.fixed_view_mut::<3, 3>(0, 3).copy_from(&(s * pbt));
        blk.fixed_view_mut::<3, 3>(3, 0).copy_from(&(s * bh * p));
        blk.fixed_view_mut::<3, 3>(3, 3)
            .copy_from(&(s * bh * pbt - t * hat(&u) * bh));
        ka += blk;
    }
    Ok((kp, ka))
}

fn restrict(motion: MotionPattern, m: &Matrix6<f64>, out: &mut DMatrix<f64>) {
    let idx = wrench_components(motion);
    if out.shape() != (idx.len(), idx.len()) {
        *out = DMatrix::zeros(idx.len(), idx.len());
    }
    for (r, &i) in idx.iter().enumerate() {
        for (c, &j) in idx.iter().enumerate() {
            out[(r, c)] = m[(i, j)];
        }
    }
}

/// The stiffness matrix K = Kp + Ka (DOF × DOF) at the pose of `kin` under `tensions`, with
/// per-cable axial stiffness E·S (N) so that k_i = E S / l_i. Picard, Caro, Plestan & Claveau 2020, eqs. (3)–(4).
///
/// ```
/// use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
/// use cdpr_wrench::stiffness_matrix;
/// use nalgebra::Vector3;
/// // Two opposed horizontal cables of length 1 on a point: K_xx = 2 E S / l, K_yy = 2 t / l.
/// let robot = Robot::new(MotionPattern::Point2, vec![
///     Cable { frame: Vector3::new(1.0, 0.0, 0.0), platform: Vector3::zeros(), pulley: None },
///     Cable { frame: Vector3::new(-1.0, 0.0, 0.0), platform: Vector3::zeros(), pulley: None },
/// ]).unwrap();
/// let kin = robot.inverse_kinematics(&Pose::point(0.0, 0.0, 0.0)).unwrap();
/// let k = stiffness_matrix(&kin, &[10.0, 10.0], &[1000.0, 1000.0]).unwrap();
/// assert!((k[(0, 0)] - 2000.0).abs() < 1e-9 && (k[(1, 1)] - 20.0).abs() < 1e-12);
/// ```
pub fn stiffness_matrix(
    kin: &PoseKinematics,
    tensions: &[f64],
    axial_stiffness: &[f64],
) -> Result<DMatrix<f64>, WrenchError> {
    let mut out = DMatrix::zeros(0, 0);
    write_stiffness_matrix(kin, tensions, axial_stiffness, &mut out)?;
    Ok(out)
}

/// [`stiffness_matrix`] into an existing matrix (no allocation when it is DOF × DOF already).
pub fn write_stiffness_matrix(
    kin: &PoseKinematics,
    tensions: &[f64],
    axial_stiffness: &[f64],
    out: &mut DMatrix<f64>,
) -> Result<(), WrenchError> {
    let (kp, ka) = spatial_parts(kin, tensions, axial_stiffness)?;
    restrict(kin.motion(), &(kp + ka), out);
    Ok(())
}

/// The passive part Kp (cable elasticity only), DOF × DOF.
pub fn passive_stiffness(
    kin: &PoseKinematics,
    axial_stiffness: &[f64],
) -> Result<DMatrix<f64>, WrenchError> {
    let zeros = vec![0.0; kin.cable_count()];
    let (kp, _) = spatial_parts(kin, &zeros, axial_stiffness)?;
    let mut out = DMatrix::zeros(0, 0);
    restrict(kin.motion(), &kp, &mut out);
    Ok(out)
}

/// The active part Ka (tension-dependent only), DOF × DOF.
pub fn active_stiffness(
    kin: &PoseKinematics,
    tensions: &[f64],
) -> Result<DMatrix<f64>, WrenchError> {
    let ones = vec![1.0; kin.cable_count()];
    let (_, ka) = spatial_parts(kin, tensions, &ones)?;
    let mut out = DMatrix::zeros(0, 0);
    restrict(kin.motion(), &ka, &mut out);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use cdpr_kinematics::{Cable, Pose, Robot};
    use nalgebra::Vector3;

    #[test]
    fn planar_is_the_xy_phi_block_of_spatial() {
        let c = |f: [f64; 2], a: [f64; 2]| Cable {
            frame: Vector3::new(f[0], f[1], 0.0),
            platform: Vector3::new(a[0], a[1], 0.0),
            pulley: None,
        };
        let cables = vec![
            c([1.0, 1.0], [0.1, 0.1]),
            c([-1.0, 1.0], [-0.1, 0.1]),
            c([0.0, -1.0], [0.0, -0.1]),
        ];
        let planar = Robot::new(MotionPattern::Planar, cables.clone()).unwrap();
        let spatial = Robot::new(MotionPattern::Spatial, cables).unwrap();
        let t = [20.0, 30.0, 40.0];
        let es = [1e4; 3];
        let kp = stiffness_matrix(
            &planar
                .inverse_kinematics(&Pose::planar(0.1, 0.2, 0.3))
                .unwrap(),
            &t,
            &es,
        )
        .unwrap();
        let pose = Pose::spatial(Vector3::new(0.1, 0.2, 0.0), 0.0, 0.0, 0.3);
        let ks = stiffness_matrix(&spatial.inverse_kinematics(&pose).unwrap(), &t, &es).unwrap();
        for (r, &i) in [0usize, 1, 5].iter().enumerate() {
            for (cc, &j) in [0usize, 1, 5].iter().enumerate() {
                assert!((kp[(r, cc)] - ks[(i, j)]).abs() < 1e-9);
            }
        }
    }

    #[test]
    fn bad_inputs_are_errors() {
        let r = Robot::new(
            MotionPattern::Point2,
            vec![Cable {
                frame: Vector3::new(1.0, 0.0, 0.0),
                platform: Vector3::zeros(),
                pulley: None,
            }],
        )
        .unwrap();
        let kin = r.inverse_kinematics(&Pose::point(0.0, 0.0, 0.0)).unwrap();
        assert!(stiffness_matrix(&kin, &[1.0, 2.0], &[1.0]).is_err());
        assert!(stiffness_matrix(&kin, &[f64::NAN], &[1.0]).is_err());
        assert!(matches!(
            stiffness_matrix(&kin, &[1.0], &[0.0]),
            Err(WrenchError::NonPositiveStiffness { .. })
        ));
    }
}
