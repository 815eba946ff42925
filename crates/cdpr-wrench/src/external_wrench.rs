//! # External wrenches
//!
//! The wrench **w**_ext acting on the platform (the thesis chapter: **f**^P = [f_x, f_y, τ]; Picard, Caro, Plestan & Claveau 2020:
//! **w**_e + **w**_g), expressed in base coordinates about the platform origin, with the
//! motion pattern's components (see [`MotionPattern`]).
//!
//! ## References
//! - Thesis eq. (6.8), Table 6.3. Picard, Caro, Plestan & Claveau 2020, eq. (1).

use crate::WrenchError;
use crate::error::check_slice;
use cdpr_kinematics::{MotionPattern, Pose};
use nalgebra::{DVector, Vector3};

/// Standard gravity vector (m/s²), −z.
pub const STANDARD_GRAVITY: Vector3<f64> = Vector3::new(0.0, 0.0, -9.80665);

/// Mass properties of the platform (Picard, Caro, Plestan & Claveau's (2020) w_g).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Platform {
    /// Mass m (kg).
    pub mass: f64,
    /// Centre of mass in platform coordinates (m).
    pub centre_of_mass: Vector3<f64>,
    /// Gravity vector **g** in base coordinates (m/s²).
    pub gravity: Vector3<f64>,
}

impl Default for Platform {
    fn default() -> Self {
        Self {
            mass: 0.0,
            centre_of_mass: Vector3::zeros(),
            gravity: STANDARD_GRAVITY,
        }
    }
}

impl Platform {
    /// The gravity wrench w_g = [m g; (T c) × m g] restricted to the motion pattern, at `pose`.
    ///
    /// ```
    /// use cdpr_kinematics::{MotionPattern, Pose};
    /// use cdpr_wrench::Platform;
    /// use nalgebra::Vector3;
    /// let p = Platform { mass: 2.0, centre_of_mass: Vector3::new(0.1, 0.0, 0.0), gravity: Vector3::new(0.0, -10.0, 0.0) };
    /// let w = p.gravity_wrench(MotionPattern::Planar, &Pose::planar(0.0, 0.0, 0.0));
    /// assert_eq!(w.as_slice(), &[0.0, -20.0, -2.0]);   // τ_z = 0.1 · (−20)
    /// ```
    pub fn gravity_wrench(&self, motion: MotionPattern, pose: &Pose) -> DVector<f64> {
        let f = self.gravity * self.mass;
        let r = pose.rotation * self.centre_of_mass;
        let m = r.cross(&f);
        DVector::from_vec(match motion {
            MotionPattern::Point2 => vec![f.x, f.y],
            MotionPattern::Planar => vec![f.x, f.y, m.z],
            MotionPattern::Point3 => vec![f.x, f.y, f.z],
            MotionPattern::Spatial => vec![f.x, f.y, f.z, m.x, m.y, m.z],
        })
    }
}

/// A wrench given component by component (length DOF), checked for size and finiteness.
pub fn wrench_from_slice(motion: MotionPattern, w: &[f64]) -> Result<DVector<f64>, WrenchError> {
    check_slice("wrench component", w, motion.dof())?;
    Ok(DVector::from_column_slice(w))
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn spatial_gravity_moment_of_offset_mass() {
        let p = Platform {
            mass: 1.0,
            centre_of_mass: Vector3::new(0.0, 0.0, 0.2),
            gravity: STANDARD_GRAVITY,
        };
        // Platform rotated 90° about x: the COM (0,0,0.2) moves to (0,−0.2,0).
        let pose = Pose::spatial(Vector3::zeros(), std::f64::consts::FRAC_PI_2, 0.0, 0.0);
        let w = p.gravity_wrench(MotionPattern::Spatial, &pose);
        // m = (0,−0.2,0) × (0,0,−9.80665) = (0.2·9.80665, 0, 0).
        assert_relative_eq!(w[3], 0.2 * 9.80665, epsilon = 1e-12);
        assert_relative_eq!(w[2], -9.80665, epsilon = 1e-15);
    }

    #[test]
    fn wrench_size_is_checked() {
        assert!(wrench_from_slice(MotionPattern::Planar, &[0.0, -10.0]).is_err());
        assert!(wrench_from_slice(MotionPattern::Planar, &[0.0, f64::INFINITY, 0.0]).is_err());
        assert_eq!(
            wrench_from_slice(MotionPattern::Point2, &[1.0, 2.0])
                .unwrap()
                .len(),
            2
        );
    }
}
