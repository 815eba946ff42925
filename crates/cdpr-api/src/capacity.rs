//! # Capacity margin at a pose
//!
//! The capacity margin (Guay, Cardou, Cruz-Ruiz & Caro 2014) of a required set of external
//! wrenches R: min over the facets n_k·w ≤ d_k of the available wrench set {W t} of
//! d_k − max_{w∈R}(−n_k·w). Positive iff every wrench of R can be balanced with tensions in
//! bounds; R is a point, a box, a Euclidean ball, or force and moment balls, centred on w_e plus
//! the robot file's load.
//!
//! ## References
//! - Guay, Cardou, Cruz-Ruiz & Caro 2014 (capacity margin, hyperplane shifting).

use cdpr_polytope::{RequiredWrenchSet, hyperplane_shifting, limiting_facet};
use nalgebra::DVector;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::inputs::{external_wrench, pose};
use crate::{ApiError, Robot};

/// The capacity margin of a required wrench set at one pose (`cdpr capacity`).
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
pub struct CapacityRequest {
    /// The robot.
    pub robot: Robot,
    /// Platform pose (m, rad).
    pub pose: Vec<f64>,
    /// Centre of the required set before the robot file's load (N, N·m; default zero).
    #[serde(default)]
    pub wrench: Option<Vec<f64>>,
    /// A box: half-widths per wrench component (N, N·m).
    #[serde(default)]
    pub wrench_box: Option<Vec<f64>>,
    /// A Euclidean ball of this radius in the wrench space (N and N·m as plain numbers).
    #[serde(default)]
    pub wrench_ball: Option<f64>,
    /// Every force of magnitude ≤ F (N).
    #[serde(default)]
    pub force_radius: Option<f64>,
    /// Every moment of magnitude ≤ M (N·m), with the forces of `force_radius`.
    #[serde(default)]
    pub moment_radius: Option<f64>,
}

/// The required set as analysed.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct RequiredReport {
    /// `point`, `box`, `ball` or `force-moment-balls`.
    pub shape: String,
    /// Its centre (N, N·m): w_e plus the robot file's load.
    pub centre: Vec<f64>,
    /// box: half-widths (N, N·m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub half_widths: Option<Vec<f64>>,
    /// ball (and point: 0): radius.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub radius: Option<f64>,
    /// force-moment-balls: F (N).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub force_radius: Option<f64>,
    /// force-moment-balls: M (N·m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub moment_radius: Option<f64>,
}

/// A facet n·w ≤ d of the available wrench set.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct FacetReport {
    /// Its index among `facets` (0-based).
    pub index: usize,
    /// Unit normal n.
    pub normal: Vec<f64>,
    /// Offset d.
    pub offset: f64,
}

/// The JSON of `cdpr capacity --json`.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct CapacityReport {
    /// Robot name.
    pub robot: String,
    /// The pose (m, rad).
    pub pose: Vec<f64>,
    /// The required set.
    pub required: RequiredReport,
    /// The margin (N for point robots; N and N·m with a length scale of 1 m otherwise); null
    /// when infinite (no facet).
    pub capacity_margin: Option<f64>,
    /// margin ≥ 0.
    pub feasible: bool,
    /// The facet reached first.
    pub limiting_facet: Option<FacetReport>,
    /// Number of facets of the available wrench set.
    pub facets: usize,
}

impl CapacityRequest {
    /// Checks the request and builds the required set.
    pub fn validate(&self) -> Result<(), ApiError> {
        self.required().map(|_| ())
    }

    fn required(&self) -> Result<(RequiredWrenchSet, &'static str), ApiError> {
        let robot = &self.robot;
        cdpr_wrench::require_enough_cables(&robot.robot, "the capacity margin (wrench closure)")?;
        let p = pose(robot, &self.pose)?;
        let centre = external_wrench(robot, &p, self.wrench.as_deref())?;
        let motion = robot.robot.motion();
        let split = self.force_radius.is_some() || self.moment_radius.is_some();
        if (self.wrench_box.is_some() as u8 + self.wrench_ball.is_some() as u8 + split as u8) > 1 {
            return Err(ApiError::invalid(
                "give one required set: --wrench-box, --wrench-ball, or --force-radius/--moment-radius",
            ));
        }
        for (name, v) in [
            ("--wrench-ball", self.wrench_ball),
            ("--force-radius", self.force_radius),
            ("--moment-radius", self.moment_radius),
        ] {
            if let Some(v) = v.filter(|v| !(v.is_finite() && *v >= 0.0)) {
                return Err(ApiError::invalid(format!(
                    "{name}: the radius must be a finite number ≥ 0, got {v}"
                )));
            }
        }
        if self.moment_radius.is_some() && !motion.has_orientation() {
            return Err(ApiError::invalid(format!(
                "--moment-radius: a `{}` robot takes no moments (use --force-radius)",
                motion.name()
            )));
        }
        let dof = centre.len();
        Ok(match (&self.wrench_box, self.wrench_ball) {
            _ if split => (
                RequiredWrenchSet::force_and_moment_balls(
                    centre,
                    motion.translation_dof(),
                    self.force_radius.unwrap_or(0.0),
                    self.moment_radius.unwrap_or(0.0),
                )?,
                "force-moment-balls",
            ),
            (Some(h), _) => {
                if h.len() != dof {
                    return Err(ApiError::invalid(format!(
                        "--wrench-box needs {dof} half-widths (one per wrench component), got {}",
                        h.len()
                    )));
                }
                (
                    RequiredWrenchSet::boxed(centre, DVector::from_column_slice(h))?,
                    "box",
                )
            }
            (None, Some(r)) => (RequiredWrenchSet::ball(centre, r)?, "ball"),
            (None, None) => (RequiredWrenchSet::point(centre)?, "point"),
        })
    }

    /// The capacity margin.
    pub fn run(&self) -> Result<CapacityReport, ApiError> {
        let (required, shape) = self.required()?;
        let robot = &self.robot;
        let p = pose(robot, &self.pose)?;
        let w = robot.robot.inverse_kinematics(&p)?.wrench_matrix();
        let aws = hyperplane_shifting::available_wrench_set(&w, &robot.bounds)?;
        let limit = limiting_facet(&aws, &required)?;
        let margin = limit.map_or(f64::INFINITY, |(_, m)| m);
        let (force_radius, moment_radius) = required.force_and_moment_radii().unzip();
        Ok(CapacityReport {
            robot: robot.name.clone(),
            pose: self.pose.clone(),
            required: RequiredReport {
                shape: shape.to_string(),
                centre: required.centre().as_slice().to_vec(),
                half_widths: required.half_widths().map(<[f64]>::to_vec),
                radius: required.radius(),
                force_radius,
                moment_radius,
            },
            capacity_margin: margin.is_finite().then_some(margin),
            feasible: margin >= 0.0,
            limiting_facet: limit.map(|(k, _)| {
                let f = &aws.facets()[k];
                FacetReport {
                    index: k,
                    normal: f.normal.as_slice().to_vec(),
                    offset: f.offset,
                }
            }),
            facets: aws.facets().len(),
        })
    }
}
