//! # Robot model: the data behind `cdpr.Robot`
//!
//! The `cdpr.Robot` class's Rust struct: a shared [`RobotDescription`] (geometry, tension bounds,
//! limits, platform mass, axial stiffness) and what every analysis module reads from it. Its
//! Python methods are in module `robot`, which calls the analysis modules; the analysis modules
//! read this struct only, so no two files import each other in a loop.

use cdpr_io::RobotDescription;
use cdpr_kinematics::{MotionPattern, Robot as Geometry};
use pyo3::prelude::*;
use std::sync::Arc;

/// A cable-driven parallel robot: geometry, tension bounds, workspace limits and platform mass.
///
/// Build one with :meth:`Robot.load` (a robot file) or :meth:`Robot.from_anchors` (arrays).
/// Poses are rows of motion-pattern coordinates: ``(x, y)`` for ``point2``, ``(x, y, φ)`` for
/// ``planar``, ``(x, y, z)`` for ``point3``, ``(x, y, z, rx, ry, rz)`` (XYZ Euler angles, rad)
/// for ``spatial``. Every analysis method takes one pose, shape ``(DOF,)``, or a batch,
/// shape ``(N, DOF)``; batches run in parallel with the GIL released.
#[pyclass(module = "cdpr", frozen)]
pub struct Robot {
    pub desc: Arc<RobotDescription>,
}

impl Robot {
    pub fn geometry(&self) -> &Geometry {
        &self.desc.robot
    }

    pub fn motion_pattern(&self) -> MotionPattern {
        self.desc.robot.motion()
    }

    /// Pose-coordinate hint for error messages.
    pub fn pose_hint(&self) -> &'static str {
        match self.motion_pattern() {
            MotionPattern::Point2 => "poses (x, y) of a point2 robot",
            MotionPattern::Planar => "poses (x, y, φ) of a planar robot",
            MotionPattern::Point3 => "poses (x, y, z) of a point3 robot",
            MotionPattern::Spatial => "poses (x, y, z, rx, ry, rz) of a spatial robot",
        }
    }
}
