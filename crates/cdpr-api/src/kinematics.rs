//! # Inverse kinematics at a pose
//!
//! Cable lengths l_i, unit vectors u_i and the DOF × n wrench matrix W with W t + w_ext = 0
//! (thesis eqs. (6.2)–(6.4), (6.11); cables over swivel pulleys: Pott 2018), with the closest
//! pair of cables, the cable–platform interference and the passive springs' state.
//!
//! ## References
//! - Pott, *Cable-Driven Parallel Robots: Theory and Application*, Springer 2018 (pulleys).

use cdpr_kinematics::{closest_cables, platform_interference};
use nalgebra::{DVector, Vector3};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::inputs::{matrix_rows, pose};
use crate::{ApiError, KinematicsModel, Robot};

/// Inverse kinematics at one pose (`cdpr kinematics`).
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
pub struct KinematicsRequest {
    /// The robot.
    pub robot: Robot,
    /// Platform pose in motion-pattern coordinates (m, rad).
    pub pose: Vec<f64>,
}

/// Where a cable passes through the platform (`[platform] shape`).
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct PlatformInterferenceReport {
    /// The cable (1-based) that passes deepest through the platform; null if none does.
    pub cable: Option<usize>,
    /// How deep (m); 0 when no cable passes through.
    pub penetration: f64,
}

/// The passive springs' state at the pose.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct PassiveSpringsReport {
    /// Spring lengths (m).
    pub lengths: Vec<f64>,
    /// Spring forces K (l − l0) (N).
    pub forces: Vec<f64>,
    /// Their wrench on the platform (N, N·m), part of w_ext.
    pub wrench: Vec<f64>,
}

/// The JSON of `cdpr kinematics --json`.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct KinematicsReport {
    /// Robot name.
    pub robot: String,
    /// Motion pattern (`point2`, `planar`, `point3`, `spatial`).
    pub motion: String,
    /// The pose (m, rad).
    pub pose: Vec<f64>,
    /// Cable model in force: `pulley` or `standard`.
    pub kinematics: KinematicsModel,
    /// Cable lengths l_i (m), with pulleys measured from `frame` over the pulley.
    pub lengths: Vec<f64>,
    /// The straight part of each cable (m).
    pub free_lengths: Vec<f64>,
    /// Swivel angles γ_i (rad; 0 without a pulley).
    pub swivel_angles: Vec<f64>,
    /// Wrap angles β_i (rad; 0 without a pulley).
    pub wrap_angles: Vec<f64>,
    /// Unit vectors u_i from the platform towards the frame (one array per cable).
    pub unit_vectors: Vec<Vec<f64>>,
    /// Platform attachment points (m).
    pub attachment_points: Vec<Vec<f64>>,
    /// Where each cable leaves the frame or its pulley (m).
    pub exit_points: Vec<Vec<f64>>,
    /// Rows of the wrench matrix W (DOF × n).
    pub wrench_matrix: Vec<Vec<f64>>,
    /// det J (n = DOF only).
    pub jacobian_determinant: Option<f64>,
    /// The two cables (1-based) whose straight segments come closest; null if none.
    pub closest_cables: Option<[usize; 2]>,
    /// Their distance (m).
    pub closest_distance: Option<f64>,
    /// The closest point on each (m).
    pub closest_points: Option<[Vec<f64>; 2]>,
    /// With a `[platform] shape`: the cable passing deepest through the platform; else null.
    pub platform_interference: Option<PlatformInterferenceReport>,
    /// With passive springs: their state; else null.
    pub passive_springs: Option<PassiveSpringsReport>,
}

impl KinematicsRequest {
    /// Checks the request (the pose's coordinate count).
    pub fn validate(&self) -> Result<(), ApiError> {
        pose(&self.robot, &self.pose).map(|_| ())
    }

    /// Inverse kinematics at the pose.
    pub fn run(&self) -> Result<KinematicsReport, ApiError> {
        let robot = &self.robot;
        let p = pose(robot, &self.pose)?;
        let kin = robot.robot.inverse_kinematics(&p)?;
        let n = kin.cable_count();
        let dim = robot.robot.motion().space_dim();
        let vec_of = |v: &Vector3<f64>| v.iter().take(dim).copied().collect::<Vec<f64>>();
        let closest = closest_cables(&kin);
        let through = robot
            .platform_shape
            .as_ref()
            .map(|shape| platform_interference(&kin, shape, &p.position, &p.rotation));
        let passive_springs = match &robot.passive_springs {
            None => None,
            Some(s) => {
                let (sk, forces) = s.state(&p)?;
                let ws = sk.wrench_matrix() * DVector::from_column_slice(&forces);
                Some(PassiveSpringsReport {
                    lengths: sk.lengths().collect(),
                    forces,
                    wrench: ws.as_slice().to_vec(),
                })
            }
        };
        Ok(KinematicsReport {
            robot: robot.name.clone(),
            motion: robot.robot.motion().name().to_string(),
            pose: self.pose.clone(),
            kinematics: self.robot.kinematics_model(),
            lengths: kin.lengths().collect(),
            free_lengths: (0..n).map(|i| kin.free_length(i)).collect(),
            swivel_angles: (0..n).map(|i| kin.swivel_angle(i)).collect(),
            wrap_angles: (0..n).map(|i| kin.wrap_angle(i)).collect(),
            unit_vectors: kin.cables().iter().map(|c| vec_of(&c.unit)).collect(),
            attachment_points: kin
                .cables()
                .iter()
                .map(|c| vec_of(&c.attachment_point))
                .collect(),
            exit_points: (0..n).map(|i| vec_of(&kin.exit_point(i))).collect(),
            wrench_matrix: matrix_rows(&kin.wrench_matrix()),
            jacobian_determinant: kin.jacobian_determinant(),
            closest_cables: closest.map(|c| [c.cables.0 + 1, c.cables.1 + 1]),
            closest_distance: closest.map(|c| c.distance),
            closest_points: closest.map(|c| [vec_of(&c.points.0), vec_of(&c.points.1)]),
            platform_interference: through.map(|t| PlatformInterferenceReport {
                cable: t.map(|p| p.cable + 1),
                penetration: t.map_or(0.0, |p| p.penetration),
            }),
            passive_springs,
        })
    }
}
