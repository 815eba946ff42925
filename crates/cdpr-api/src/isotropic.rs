//! # Maximum isotropic force and the force polytope at a pose
//!
//! The largest force the platform resists in every direction with tensions in [t_min, t_max]:
//! the radius of the largest ball centred at −w_ext inside the available force polytope {W t}
//! (Krut, Company & Pierrot 2004, eq. 19); for planar and spatial robots the force at zero
//! moment. With it the polytope itself (facets, vertices) and, for point2 robots, the largest
//! centred ellipse (Krut, Company & Pierrot 2004, §IV-C).
//!
//! ## References
//! - Krut, Company & Pierrot 2004, *Force performance indexes for parallel mechanisms with
//!   actuation redundancy* (eq. 19, §IV-C).

use cdpr_kinematics::MotionPattern;
use cdpr_polytope::{
    AvailableWrenchSet, hyperplane_shifting, isotropic_force_under_load, largest_inscribed_ellipse,
};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::inputs::{external_wrench, pose};
use crate::{ApiError, Robot};

/// What the index means for this motion pattern (JSON `definition`).
pub fn definition(motion: MotionPattern) -> &'static str {
    if motion.has_orientation() {
        "force at zero moment: radius of the largest force ball centred at -w_ext (the origin \
         without load) inside the moment = 0 slice of the available wrench set \
         {W t : t_min <= t <= t_max}; negative when -w_ext is outside"
    } else {
        "radius of the largest force ball centred at -w_ext (the origin without load) inside the \
         available force polytope {W t : t_min <= t <= t_max} (Krut, Company & Pierrot 2004, \
         eq. 19); negative when -w_ext is outside"
    }
}

/// The isotropic force and the force polytope at one pose (`cdpr isotropic --pose`).
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
pub struct IsotropicRequest {
    /// The robot.
    pub robot: Robot,
    /// Platform pose (m, rad).
    pub pose: Vec<f64>,
    /// External wrench w_e (N, N·m; default zero), added to the robot file's load.
    #[serde(default)]
    pub wrench: Option<Vec<f64>>,
    /// Also the largest-area centred ellipse (point2 robots only).
    #[serde(default)]
    pub ellipse: bool,
}

/// The largest centred ellipse inside the force polygon (no load).
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct EllipseReport {
    /// Semi-axes, major first (N).
    pub semi_axes: [f64; 2],
    /// Angle of the major axis from x (rad).
    pub angle: f64,
    /// The same in degrees.
    pub angle_deg: f64,
    /// Area π a b (N²).
    pub area: f64,
}

/// The JSON of `cdpr isotropic --pose --json`.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct IsotropicReport {
    /// Robot name.
    pub robot: String,
    /// The pose (m, rad).
    pub pose: Vec<f64>,
    /// The maximum isotropic force on top of w_ext (N; negative: w_ext cannot be held).
    pub isotropic_force: f64,
    /// The ball in the full wrench space (N and N·m combined).
    pub wrench_radius: f64,
    /// w_ext = w_e + the robot file's load (N, N·m).
    pub external_wrench: Vec<f64>,
    /// What the index means for this motion pattern.
    pub definition: String,
    /// Number of facets of the available wrench set.
    pub facets: usize,
    /// Vertices of the available wrench set (N, N·m; wrench spaces of dimension 2 and 3).
    pub vertices: Option<Vec<Vec<f64>>>,
    /// Faces of a bounded set of dimension 2 or 3: vertex indices into `vertices`,
    /// counter-clockwise seen from outside (DOF 2: edges).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub faces: Option<Vec<Vec<usize>>>,
    /// The faces' outward unit normals n (one per face).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub normals: Option<Vec<Vec<f64>>>,
    /// The faces' offsets d (n · w ≤ d; N, or N·m for moment directions).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub offsets: Option<Vec<f64>>,
    /// With `ellipse`: the largest centred ellipse, null when the origin is not strictly inside.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ellipse: Option<Option<EllipseReport>>,
}

impl IsotropicRequest {
    /// Checks the request.
    pub fn validate(&self) -> Result<(), ApiError> {
        let robot = &self.robot;
        cdpr_wrench::require_enough_cables(&robot.robot, "the isotropic force (wrench closure)")?;
        let motion = robot.robot.motion();
        if self.ellipse && motion != MotionPattern::Point2 {
            return Err(ApiError::invalid(format!(
                "--ellipse needs a 2-D force polygon (a point2 robot); this robot is {}",
                motion.name()
            )));
        }
        let p = pose(robot, &self.pose)?;
        external_wrench(robot, &p, self.wrench.as_deref())?;
        Ok(())
    }

    /// The available wrench set {W t : t_min ≤ t ≤ t_max} at the pose (no load).
    pub fn wrench_set(&self) -> Result<AvailableWrenchSet, ApiError> {
        let p = pose(&self.robot, &self.pose)?;
        let w = self.robot.robot.inverse_kinematics(&p)?.wrench_matrix();
        Ok(hyperplane_shifting::available_wrench_set(
            &w,
            &self.robot.bounds,
        )?)
    }

    /// The isotropic force, the polytope and the ellipse.
    pub fn run(&self) -> Result<IsotropicReport, ApiError> {
        self.validate()?;
        let robot = &self.robot;
        let motion = robot.robot.motion();
        let aws = self.wrench_set()?;
        let w_ext = external_wrench(robot, &pose(robot, &self.pose)?, self.wrench.as_deref())?;
        let force = isotropic_force_under_load(&aws, motion, &w_ext)?;
        let radius = aws
            .supporting_halfspaces()
            .iter()
            .map(|f| f.offset + f.normal.dot(&w_ext))
            .fold(f64::INFINITY, f64::min);
        let ellipse = if self.ellipse {
            Some(largest_inscribed_ellipse(&aws)?.map(|e| EllipseReport {
                semi_axes: e.semi_axes,
                angle: e.angle,
                angle_deg: e.angle.to_degrees(),
                area: e.area(),
            }))
        } else {
            None
        };
        let faces = aws.faces();
        let facet = |f: &cdpr_polytope::Face| &aws.facets()[f.facet];
        Ok(IsotropicReport {
            faces: faces.map(|fs| fs.iter().map(|f| f.vertices.clone()).collect()),
            normals: faces.map(|fs| {
                fs.iter()
                    .map(|f| facet(f).normal.as_slice().to_vec())
                    .collect()
            }),
            offsets: faces.map(|fs| fs.iter().map(|f| facet(f).offset).collect()),
            robot: robot.name.clone(),
            pose: self.pose.clone(),
            isotropic_force: force,
            wrench_radius: radius,
            external_wrench: w_ext.as_slice().to_vec(),
            definition: definition(motion).to_string(),
            facets: aws.facets().len(),
            vertices: aws
                .vertices()
                .map(|v| v.iter().map(|p| p.as_slice().to_vec()).collect()),
            ellipse,
        })
    }
}
