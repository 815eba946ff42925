//! # Regions of a request
//!
//! The platform orientation, the search box and the grid resolution of a region analysis, read
//! from the numbers a request gives (the command line's `--orientation`, `--box`, `--grid`),
//! with the messages the command line prints.
//!
//! ## References
//! - Thesis Algorithm 6.2, step 2 (the default box: the frame anchors' bounding box).

use cdpr_kinematics::{MotionPattern, Pose, Robot};
use cdpr_workspace::Region;
use nalgebra::{Rotation3, Vector3};

use crate::ApiError;

/// The platform orientation from command-line numbers: φ (planar), rx,ry,rz (spatial), none
/// (point robots; zeros are accepted).
pub fn rotation(motion: MotionPattern, q: Option<&[f64]>) -> Result<Rotation3<f64>, ApiError> {
    let q = q.unwrap_or(&[]);
    if let Some(v) = q.iter().find(|v| !v.is_finite()) {
        return Err(ApiError::invalid(format!(
            "--orientation: {v} is not a finite number"
        )));
    }
    match motion {
        MotionPattern::Point2 | MotionPattern::Point3 => {
            if q.iter().any(|&v| v != 0.0) {
                return Err(ApiError::invalid(format!(
                    "a `{}` robot has no orientation: omit --orientation",
                    motion.name()
                )));
            }
            Ok(Rotation3::identity())
        }
        MotionPattern::Planar => match q {
            [] => Ok(Rotation3::identity()),
            [phi] => Ok(Rotation3::from_axis_angle(&Vector3::z_axis(), *phi)),
            _ => Err(ApiError::invalid(format!(
                "--orientation needs 1 number (φ) for a planar robot, got {}",
                q.len()
            ))),
        },
        MotionPattern::Spatial => match q {
            [] => Ok(Rotation3::identity()),
            [rx, ry, rz] => Ok(Pose::spatial(Vector3::zeros(), *rx, *ry, *rz).rotation),
            _ => Err(ApiError::invalid(format!(
                "--orientation needs 3 numbers (rx,ry,rz) for a spatial robot, got {}",
                q.len()
            ))),
        },
    }
}

/// The search box: 4 numbers in the plane, 6 in space; default [`Region::default_for`] (the
/// frame anchors' bounding box, extended below anchors that span little height).
pub fn region(robot: &Robot, q: Option<&[f64]>, option: &str) -> Result<Region, ApiError> {
    let dim = robot.motion().space_dim();
    let r = match q {
        None => Region::default_for(robot),
        Some(b) if dim == 2 && b.len() == 4 => Region::planar(b[0], b[1], b[2], b[3]),
        Some(b) if dim == 3 && b.len() == 6 => Region::cuboid(
            Vector3::new(b[0], b[2], b[4]),
            Vector3::new(b[1], b[3], b[5]),
        ),
        Some(b) => {
            return Err(ApiError::invalid(format!(
                "{option} needs {} numbers ({}) for a `{}` robot, got {}",
                2 * dim,
                if dim == 2 {
                    "XMIN,XMAX,YMIN,YMAX"
                } else {
                    "XMIN,XMAX,YMIN,YMAX,ZMIN,ZMAX"
                },
                robot.motion().name(),
                b.len()
            )));
        }
    };
    if q.is_some() {
        for (k, axis) in ["x", "y", "z"].iter().enumerate().take(dim) {
            let (lo, hi) = (r.min[k], r.max[k]);
            let (a, b) = (axis.to_uppercase(), axis.to_uppercase());
            if !(lo.is_finite() && hi.is_finite()) {
                return Err(ApiError::invalid(format!(
                    "{option}: the {axis} bounds {a}MIN = {lo}, {b}MAX = {hi} must be finite numbers (m)"
                )));
            }
            if lo >= hi {
                return Err(ApiError::invalid(format!(
                    "{option}: along {axis}, {a}MIN = {lo} m must be less than {b}MAX = {hi} m"
                )));
            }
        }
    }
    r.validate(dim)?;
    Ok(r)
}

/// Grid resolution: default 50 in the plane (the thesis), 20 in space; bounded to keep the
/// point count reasonable.
pub fn resolution(m: Option<usize>, dim: usize, default_2d: usize) -> Result<usize, ApiError> {
    let max = if dim == 2 { 4000 } else { 300 };
    let m = m.unwrap_or(if dim == 2 { default_2d } else { 20 });
    if !(1..=max).contains(&m) {
        return Err(ApiError::invalid(format!(
            "--grid M must lie in [1, {max}] for a {dim}-D grid"
        )));
    }
    Ok(m)
}
