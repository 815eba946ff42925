//! # Platform poses
//!
//! A pose is the position **u** of the platform frame origin and its orientation, both in base
//! coordinates. Planar poses rotate about z by φ (thesis eq. (6.3)).
//!
//! **Spatial orientation convention.** Six-number spatial poses are `x, y, z, r_x, r_y, r_z` with
//! XYZ Euler angles in radians, as CASPR uses them: intrinsic rotations about x, then the new y,
//! then the new z, i.e. `R = R_x(r_x) · R_y(r_y) · R_z(r_z)`. A rotation matrix can be given
//! directly with [`Pose::new`].

use crate::{KinematicsError, MotionPattern};
use nalgebra::{Matrix3, Rotation3, Vector3};

/// Position and orientation of the platform frame in base coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Position **u** of the platform frame origin (z = 0 for 2-D motion patterns).
    pub position: Vector3<f64>,
    /// Orientation **T**(φ) of the platform frame (identity for point motion patterns).
    pub rotation: Rotation3<f64>,
}

impl Pose {
    /// A pose from a position and a rotation matrix.
    pub fn new(position: Vector3<f64>, rotation: Rotation3<f64>) -> Self {
        Self { position, rotation }
    }

    /// A planar pose (x, y, φ): rotation by φ radians about z, eq. (6.3).
    pub fn planar(x: f64, y: f64, phi: f64) -> Self {
        Self::new(
            Vector3::new(x, y, 0.0),
            Rotation3::from_axis_angle(&Vector3::z_axis(), phi),
        )
    }

    /// A point pose in the plane or in space (no orientation).
    pub fn point(x: f64, y: f64, z: f64) -> Self {
        Self::new(Vector3::new(x, y, z), Rotation3::identity())
    }

    /// A spatial pose from XYZ Euler angles (radians): `R = R_x(rx) R_y(ry) R_z(rz)`.
    pub fn spatial(position: Vector3<f64>, rx: f64, ry: f64, rz: f64) -> Self {
        let r = Rotation3::from_axis_angle(&Vector3::x_axis(), rx)
            * Rotation3::from_axis_angle(&Vector3::y_axis(), ry)
            * Rotation3::from_axis_angle(&Vector3::z_axis(), rz);
        Self::new(position, r)
    }

    /// A pose from the coordinates of a motion pattern (see [`MotionPattern`] for their order).
    ///
    /// ```
    /// use cdpr_kinematics::{MotionPattern, Pose};
    /// let p = Pose::from_coordinates(MotionPattern::Planar, &[-0.5, 0.2, 0.1]).unwrap();
    /// assert_eq!(p.position.x, -0.5);
    /// assert!(Pose::from_coordinates(MotionPattern::Planar, &[0.0, 0.0]).is_err());
    /// ```
    pub fn from_coordinates(motion: MotionPattern, q: &[f64]) -> Result<Self, KinematicsError> {
        if q.len() != motion.dof() {
            return Err(KinematicsError::WrongDimension {
                what: "pose".into(),
                motion: motion.name(),
                expected: motion.dof(),
                found: q.len(),
            });
        }
        if let Some((i, &v)) = q.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(KinematicsError::NotFinite {
                what: format!("pose coordinate {}", i + 1),
                value: v,
            });
        }
        Ok(match motion {
            MotionPattern::Point2 => Self::point(q[0], q[1], 0.0),
            MotionPattern::Planar => Self::planar(q[0], q[1], q[2]),
            MotionPattern::Point3 => Self::point(q[0], q[1], q[2]),
            MotionPattern::Spatial => {
                Self::spatial(Vector3::new(q[0], q[1], q[2]), q[3], q[4], q[5])
            }
        })
    }

    /// The coordinates of this pose for a motion pattern (inverse of [`Pose::from_coordinates`]).
    ///
    /// Spatial angles are recovered in `(-π, π]` for r_x and r_z and `[-π/2, π/2]` for r_y.
    pub fn coordinates(&self, motion: MotionPattern) -> Vec<f64> {
        let p = &self.position;
        match motion {
            MotionPattern::Point2 => vec![p.x, p.y],
            MotionPattern::Planar => {
                let m = self.rotation.matrix();
                vec![p.x, p.y, m[(1, 0)].atan2(m[(0, 0)])]
            }
            MotionPattern::Point3 => vec![p.x, p.y, p.z],
            MotionPattern::Spatial => {
                let [rx, ry, rz] = xyz_euler_angles(self.rotation.matrix());
                vec![p.x, p.y, p.z, rx, ry, rz]
            }
        }
    }
}

/// XYZ Euler angles of `R = R_x(a) R_y(b) R_z(c)`.
fn xyz_euler_angles(m: &Matrix3<f64>) -> [f64; 3] {
    // R[0,2] = sin b, R[1,2] = -sin a cos b, R[2,2] = cos a cos b,
    // R[0,1] = -cos b sin c, R[0,0] = cos b cos c.
    let b = m[(0, 2)].clamp(-1.0, 1.0).asin();
    let a = (-m[(1, 2)]).atan2(m[(2, 2)]);
    let c = (-m[(0, 1)]).atan2(m[(0, 0)]);
    [a, b, c]
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn planar_rotation_matches_eq_6_3() {
        let p = Pose::planar(0.0, 0.0, 0.3);
        let a = p.rotation * Vector3::new(1.0, 0.0, 0.0);
        assert_relative_eq!(
            a,
            Vector3::new(0.3f64.cos(), 0.3f64.sin(), 0.0),
            epsilon = 1e-15
        );
    }

    #[test]
    fn spatial_euler_convention_is_intrinsic_xyz() {
        // R_x(π/2) R_y(π/2): the platform x axis ends up along ... computed by hand:
        // R_y(π/2) e_x = -e_z; R_x(π/2)(-e_z) = e_y.
        let p = Pose::spatial(
            Vector3::zeros(),
            std::f64::consts::FRAC_PI_2,
            std::f64::consts::FRAC_PI_2,
            0.0,
        );
        assert_relative_eq!(p.rotation * Vector3::x(), Vector3::y(), epsilon = 1e-15);
    }

    #[test]
    fn coordinates_round_trip() {
        let q = [0.1, -0.2, 0.3, 0.4, -0.5, 0.6];
        let p = Pose::from_coordinates(MotionPattern::Spatial, &q).unwrap();
        let back = p.coordinates(MotionPattern::Spatial);
        for (a, b) in q.iter().zip(&back) {
            assert_relative_eq!(a, b, epsilon = 1e-12);
        }
        let p = Pose::from_coordinates(MotionPattern::Planar, &[-0.5, 0.2, -0.1]).unwrap();
        assert_relative_eq!(
            p.coordinates(MotionPattern::Planar)[2],
            -0.1,
            epsilon = 1e-15
        );
    }

    #[test]
    fn bad_coordinates_are_errors() {
        assert!(matches!(
            Pose::from_coordinates(MotionPattern::Spatial, &[0.0; 3]),
            Err(KinematicsError::WrongDimension {
                expected: 6,
                found: 3,
                ..
            })
        ));
        assert!(matches!(
            Pose::from_coordinates(MotionPattern::Point2, &[0.0, f64::NAN]),
            Err(KinematicsError::NotFinite { .. })
        ));
    }
}
