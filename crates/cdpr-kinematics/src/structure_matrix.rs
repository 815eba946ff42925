//! # Structure (wrench) matrix and Jacobian
//!
//! Static equilibrium of the platform under cable tensions **t** and an external wrench
//! **w**_ext (the thesis chapter: **f**^P) is
//!
//! ```text
//!     W t + w_ext = 0                      (thesis eq. (6.11): f^P = −S t; Picard, Caro, Plestan & Claveau 2020, eq. (1))
//! ```
//!
//! with the DOF × n wrench matrix W (the thesis' *structure matrix* S), whose column i is
//! `[u_i ; a_i × u_i]` restricted to the motion pattern's wrench components (Picard, Caro, Plestan & Claveau 2020, eq. (2)).
//! The Jacobian of eq. (6.7) is J = Wᵀ (n × DOF) and relates cable and platform velocities by
//! l̇ = −J q̇ for a twist q̇ = [u̇; ω] (ω: angular velocity in base coordinates).
//!
//! ## References
//! - Thesis eqs. (6.6), (6.7), (6.11). Picard, Caro, Plestan & Claveau 2020, eqs. (1)–(2).

use crate::MotionPattern;
use crate::PoseKinematics;
use nalgebra::DMatrix;

impl PoseKinematics {
    /// The DOF × n wrench (structure) matrix W, eq. (6.11) / Picard, Caro, Plestan & Claveau 2020, eq. (2).
    ///
    /// ```
    /// use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
    /// use nalgebra::Vector3;
    /// let robot = Robot::new(MotionPattern::Point2, vec![
    ///     Cable { frame: Vector3::new(2.0, 0.0, 0.0), platform: Vector3::zeros(), pulley: None },
    ///     Cable { frame: Vector3::new(0.0, 3.0, 0.0), platform: Vector3::zeros(), pulley: None },
    /// ]).unwrap();
    /// let w = robot.inverse_kinematics(&Pose::point(0.0, 0.0, 0.0)).unwrap().wrench_matrix();
    /// assert_eq!(w[(0, 0)], 1.0);
    /// assert_eq!(w[(1, 1)], 1.0);
    /// ```
    pub fn wrench_matrix(&self) -> DMatrix<f64> {
        let mut w = DMatrix::zeros(self.motion().dof(), self.cable_count());
        self.write_wrench_matrix(&mut w);
        w
    }

    /// W into an existing matrix (resized only if its shape differs: no allocation in loops).
    pub fn write_wrench_matrix(&self, w: &mut DMatrix<f64>) {
        let (dof, n) = (self.motion().dof(), self.cable_count());
        if w.shape() != (dof, n) {
            *w = DMatrix::zeros(dof, n);
        }
        // One loop per motion pattern (the match outside the loop, the column length a
        // constant): column i is [u_i; a_i × u_i] restricted to the pattern's wrench components.
        let (w, cables) = (w.as_mut_slice(), self.cables());
        match self.motion() {
            MotionPattern::Point2 => {
                for (col, c) in w.chunks_exact_mut(2).zip(cables) {
                    (col[0], col[1]) = (c.unit.x, c.unit.y);
                }
            }
            MotionPattern::Planar => {
                for (col, c) in w.chunks_exact_mut(3).zip(cables) {
                    let (u, a) = (&c.unit, &c.attachment);
                    (col[0], col[1], col[2]) = (u.x, u.y, a.x * u.y - a.y * u.x);
                }
            }
            MotionPattern::Point3 => {
                for (col, c) in w.chunks_exact_mut(3).zip(cables) {
                    (col[0], col[1], col[2]) = (c.unit.x, c.unit.y, c.unit.z);
                }
            }
            MotionPattern::Spatial => {
                for (col, c) in w.chunks_exact_mut(6).zip(cables) {
                    let (u, m) = (&c.unit, c.attachment.cross(&c.unit));
                    (col[0], col[1], col[2]) = (u.x, u.y, u.z);
                    (col[3], col[4], col[5]) = (m.x, m.y, m.z);
                }
            }
        }
    }

    /// The Jacobian J = Wᵀ (n × DOF) of eq. (6.7): l̇ = −J q̇.
    pub fn jacobian(&self) -> DMatrix<f64> {
        self.wrench_matrix().transpose()
    }

    /// det J for a fully determined robot (n = DOF), else `None`; criterion (6.24).
    pub fn jacobian_determinant(&self) -> Option<f64> {
        (self.cable_count() == self.motion().dof()).then(|| self.wrench_matrix().determinant())
    }
}

#[cfg(test)]
mod tests {
    use crate::Pose;
    use crate::reference_robots::thesis_four_cable;
    use approx::assert_relative_eq;

    #[test]
    fn thesis_four_cable_at_origin_by_hand() {
        let w = thesis_four_cable()
            .inverse_kinematics(&Pose::planar(0.0, 0.0, 0.0))
            .unwrap()
            .wrench_matrix();
        let s = 0.1 / 2f64.sqrt();
        // Cable 1: ℓ = (1 − s, 0.5 − s); moment = s·ℓ_y − s·ℓ_x = s(0.5 − 1) = −0.5 s, divided by l.
        let l1 = ((1.0 - s).powi(2) + (0.5 - s).powi(2)).sqrt();
        assert_relative_eq!(w[(0, 0)], (1.0 - s) / l1, epsilon = 1e-15);
        assert_relative_eq!(w[(1, 0)], (0.5 - s) / l1, epsilon = 1e-15);
        assert_relative_eq!(w[(2, 0)], -0.5 * s / l1, epsilon = 1e-15);
        // Cable 3: ℓ = (−0.9, −0.4), a = (−0.1, −0.1): moment = (−0.1)(−0.4) − (−0.1)(−0.9) = −0.05.
        let l3 = (0.81f64 + 0.16).sqrt();
        assert_relative_eq!(w[(0, 2)], -0.9 / l3, epsilon = 1e-15);
        assert_relative_eq!(w[(1, 2)], -0.4 / l3, epsilon = 1e-15);
        assert_relative_eq!(w[(2, 2)], -0.05 / l3, epsilon = 1e-15);
        // Cable 4: ℓ = (0.9, −0.4), a = (0.1, −0.1): moment = 0.1(−0.4) − (−0.1)(0.9) = 0.05.
        assert_relative_eq!(w[(2, 3)], 0.05 / l3, epsilon = 1e-15);
    }

    /// Every motion pattern's column is [u; b × u] restricted to its wrench components, bit for
    /// bit, also when the output matrix has to be resized.
    #[test]
    fn columns_of_every_motion_pattern() {
        use crate::{Cable, MotionPattern, Robot};
        use nalgebra::{DMatrix, Rotation3, Vector3};
        let cables: Vec<Cable> = (0..7)
            .map(|i| {
                let t = i as f64;
                Cable {
                    frame: Vector3::new(
                        2.0 * (1.1 * t).cos(),
                        2.0 * (1.1 * t).sin(),
                        1.0 + 0.1 * t,
                    ),
                    platform: Vector3::new(0.1 * (2.3 * t).cos(), 0.1 * (2.3 * t).sin(), 0.05),
                    pulley: None,
                }
            })
            .collect();
        let spatial = Pose::new(
            Vector3::new(0.1, -0.2, 0.3),
            Rotation3::new(Vector3::new(0.1, 0.2, -0.3)),
        );
        for (motion, pose) in [
            (MotionPattern::Point2, Pose::point(0.1, -0.2, 0.0)),
            (MotionPattern::Planar, Pose::planar(0.1, -0.2, 0.3)),
            (MotionPattern::Point3, Pose::point(0.1, -0.2, 0.3)),
            (MotionPattern::Spatial, spatial),
        ] {
            let planar = matches!(motion, MotionPattern::Point2 | MotionPattern::Planar);
            let cables = cables
                .iter()
                .map(|c| {
                    let flat =
                        |v: Vector3<f64>| Vector3::new(v.x, v.y, if planar { 0.0 } else { v.z });
                    let point = matches!(motion, MotionPattern::Point2 | MotionPattern::Point3);
                    Cable {
                        frame: flat(c.frame),
                        platform: if point {
                            Vector3::zeros()
                        } else {
                            flat(c.platform)
                        },
                        pulley: None,
                    }
                })
                .collect();
            let kin = Robot::new(motion, cables)
                .unwrap()
                .inverse_kinematics(&pose)
                .unwrap();
            let mut w = DMatrix::zeros(1, 1);
            kin.write_wrench_matrix(&mut w);
            assert_eq!(w.shape(), (motion.dof(), 7));
            for (i, c) in kin.cables().iter().enumerate() {
                let (u, m) = (c.unit, c.attachment.cross(&c.unit));
                let full = [u.x, u.y, u.z, m.x, m.y, m.z];
                let expected: Vec<f64> = match motion {
                    MotionPattern::Point2 => vec![u.x, u.y],
                    MotionPattern::Planar => vec![u.x, u.y, m.z],
                    MotionPattern::Point3 => vec![u.x, u.y, u.z],
                    MotionPattern::Spatial => full.to_vec(),
                };
                assert_eq!(
                    w.column(i).as_slice(),
                    &expected[..],
                    "{motion:?} cable {i}"
                );
            }
        }
    }

    #[test]
    fn determinant_only_when_square() {
        let r = thesis_four_cable();
        let kin = r.inverse_kinematics(&Pose::planar(0.0, 0.0, 0.0)).unwrap();
        assert!(kin.jacobian_determinant().is_none());
        let three = r.permuted(&[0, 1, 2]).unwrap();
        let kin = three
            .inverse_kinematics(&Pose::planar(0.0, 0.0, 0.0))
            .unwrap();
        assert!(kin.jacobian_determinant().unwrap().abs() > 1e-3);
    }
}
