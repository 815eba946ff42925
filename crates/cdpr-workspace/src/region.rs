//! # Search regions
//!
//! The axis-aligned box a workspace is searched in. Algorithm 6.2 step 2 of the thesis chapter on planar tendon-driven manipulators uses the
//! bounding box of the frame anchors c^i; any other box may be given.
//!
//! ## References
//! - Thesis Algorithm 6.2, step 2.

use crate::WorkspaceError;
use cdpr_kinematics::Robot;
use nalgebra::Vector3;

/// An axis-aligned box `min ≤ u ≤ max` of platform positions (z ignored for 2-D robots).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Region {
    /// Lower corner (x_min, y_min, z_min).
    pub min: Vector3<f64>,
    /// Upper corner (x_max, y_max, z_max).
    pub max: Vector3<f64>,
}

impl Region {
    /// The bounding box of the frame anchors, Algorithm 6.2 step 2:
    /// x_min = min_i c_x^i, x_max = max_i c_x^i, and likewise for y (and z).
    ///
    /// ```
    /// use cdpr_kinematics::{Cable, MotionPattern, Robot};
    /// use cdpr_workspace::Region;
    /// use nalgebra::Vector3;
    /// let c = |x: f64, y: f64| Cable { frame: Vector3::new(x, y, 0.0), platform: Vector3::zeros(), pulley: None };
    /// let robot = Robot::new(MotionPattern::Point2, vec![c(1.0, 0.5), c(-1.0, 0.5), c(0.0, -1.0)]).unwrap();
    /// let r = Region::frame_bounding_box(&robot);
    /// assert_eq!((r.min.x, r.max.x, r.min.y, r.max.y), (-1.0, 1.0, -1.0, 0.5));
    /// ```
    pub fn frame_bounding_box(robot: &Robot) -> Self {
        let (min, max) = robot.frame_bounding_box();
        Self { min, max }
    }

    /// The default region of every front end (CLI, Python, gallery):
    /// [`Robot::default_region`], the frame anchors' bounding box extended below anchors that
    /// span little height (suspended robots).
    ///
    /// ```
    /// use cdpr_kinematics::{Cable, MotionPattern, Robot};
    /// use cdpr_workspace::Region;
    /// use nalgebra::Vector3;
    /// let c = |x: f64, y: f64| Cable { frame: Vector3::new(x, y, 3.0), platform: Vector3::zeros(), pulley: None };
    /// let robot = Robot::new(MotionPattern::Point3, vec![c(1.0, 1.0), c(-1.0, 1.0), c(0.0, -1.0)]).unwrap();
    /// let r = Region::default_for(&robot);
    /// assert_eq!((r.min.z, r.max.z), (2.0, 3.0));
    /// assert!(r.validate(3).is_ok());
    /// ```
    pub fn default_for(robot: &Robot) -> Self {
        let (min, max) = robot.default_region();
        Self { min, max }
    }

    /// A planar box [x_min, x_max] × [y_min, y_max] (z = 0).
    pub fn planar(xmin: f64, xmax: f64, ymin: f64, ymax: f64) -> Self {
        Self {
            min: Vector3::new(xmin, ymin, 0.0),
            max: Vector3::new(xmax, ymax, 0.0),
        }
    }

    /// A box in space.
    pub fn cuboid(min: Vector3<f64>, max: Vector3<f64>) -> Self {
        Self { min, max }
    }

    /// Whether `p` lies in the box (its first `dim` coordinates, boundary included).
    #[inline]
    pub fn contains(&self, p: &Vector3<f64>, dim: usize) -> bool {
        (0..dim).all(|k| p[k] >= self.min[k] && p[k] <= self.max[k])
    }

    /// Extent max − min along each axis.
    pub fn extent(&self) -> Vector3<f64> {
        self.max - self.min
    }

    /// Checks the first `dim` axes: finite corners with min < max.
    pub fn validate(&self, dim: usize) -> Result<(), WorkspaceError> {
        for k in 0..dim {
            for v in [self.min[k], self.max[k]] {
                if !v.is_finite() {
                    return Err(WorkspaceError::NotFinite {
                        what: "region corner",
                        value: v,
                    });
                }
            }
            if self.min[k] >= self.max[k] {
                return Err(WorkspaceError::EmptyRegion {
                    axis: k,
                    min: self.min[k],
                    max: self.max[k],
                });
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validation_rejects_empty_and_non_finite_boxes() {
        assert!(Region::planar(-1.0, 1.0, -1.0, 1.0).validate(2).is_ok());
        assert!(matches!(
            Region::planar(1.0, 1.0, -1.0, 1.0).validate(2),
            Err(WorkspaceError::EmptyRegion { axis: 0, .. })
        ));
        assert!(matches!(
            Region::planar(-1.0, 1.0, f64::NAN, 1.0).validate(2),
            Err(WorkspaceError::NotFinite { .. })
        ));
        // z is ignored in 2-D but checked in 3-D.
        assert!(Region::planar(-1.0, 1.0, -1.0, 1.0).validate(3).is_err());
        assert!(Region::planar(0.0, 1.0, 0.0, 1.0).contains(&Vector3::new(1.0, 0.0, 5.0), 2));
        assert!(!Region::planar(0.0, 1.0, 0.0, 1.0).contains(&Vector3::new(1.1, 0.0, 0.0), 2));
    }
}
