//! # Forward kinematics
//!
//! The platform pose whose cable lengths are the measured ones: Levenberg–Marquardt on
//! l(x) − L with the analytic Jacobian, from a guess or a multi-start, every answer certified by
//! its recomputed residual, its status and the smallest singular value of the Jacobian.
//!
//! ## References
//! - Pott 2018, §5 (forward kinematics of cable robots); Merlet 2015 (multiple solutions).

use cdpr_kinematics::{ForwardKinematics, ForwardSettings, ForwardSolution, MotionPattern};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::inputs::pose;
use crate::{ApiError, KinematicsModel, Robot};

fn default_tolerance() -> f64 {
    ForwardSettings::default().tolerance
}

fn default_length_sigma() -> f64 {
    ForwardSettings::default().length_sigma
}

fn default_max_iterations() -> usize {
    ForwardSettings::default().max_iterations
}

/// The pose from measured cable lengths (`cdpr forward`).
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
pub struct ForwardRequest {
    /// The robot.
    pub robot: Robot,
    /// Measured cable lengths L_1,…,L_n (m), in cable order.
    pub lengths: Vec<f64>,
    /// Starting pose (m, rad); without it, multi-start.
    #[serde(default)]
    pub guess: Option<Vec<f64>>,
    /// A pose solves the lengths when max |l_i − L_i| is at most this (m; default 1e-9).
    #[serde(default = "default_tolerance")]
    pub tolerance: f64,
    /// Standard deviation σ of the measured lengths (m; default 1e-4).
    #[serde(default = "default_length_sigma")]
    pub length_sigma: f64,
    /// Iteration limit of each Gauss–Newton / Levenberg–Marquardt solve (≥ 1; default 100).
    #[serde(default = "default_max_iterations")]
    pub max_iterations: usize,
}

/// One solution of the forward kinematics.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct ForwardSolutionReport {
    /// The pose (m, rad).
    pub pose: Vec<f64>,
    /// max |l_i(pose) − L_i| (m).
    pub residual: f64,
    /// ‖l − L‖/√n (m).
    pub residual_rms: f64,
    /// Standard deviations of the pose (position m, rotation vector rad).
    pub pose_std: Vec<f64>,
    /// Iterations used.
    pub iterations: usize,
    /// Whether the iteration converged.
    pub converged: bool,
    /// `solved`, `fitted`, `inconsistent`, `no pose within tolerance`, `above the anchors` or
    /// `did not converge`.
    pub status: String,
    /// Smallest singular value of the Jacobian.
    pub min_singular_value: f64,
}

impl ForwardSolutionReport {
    fn of(motion: MotionPattern, s: &ForwardSolution) -> Self {
        Self {
            pose: s.pose.coordinates(motion).to_vec(),
            residual: s.residual,
            residual_rms: s.residual_rms,
            pose_std: s.pose_std(motion.dof()).to_vec(),
            iterations: s.iterations,
            converged: s.converged,
            status: s.status.name().to_string(),
            min_singular_value: s.min_singular_value,
        }
    }
}

/// The JSON of `cdpr forward --json`: the best solution's fields, then every solution.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct ForwardReport {
    /// Robot name.
    pub robot: String,
    /// Motion pattern.
    pub motion: String,
    /// Cable model in force.
    pub kinematics: KinematicsModel,
    /// σ of the lengths (m).
    pub length_sigma: f64,
    /// The best solution.
    #[serde(flatten)]
    pub best: ForwardSolutionReport,
    /// Every distinct solution found (one with a guess).
    pub solutions: Vec<ForwardSolutionReport>,
}

impl ForwardRequest {
    fn settings(&self) -> ForwardSettings {
        ForwardSettings {
            tolerance: self.tolerance,
            length_sigma: self.length_sigma,
            max_iterations: self.max_iterations,
        }
    }

    /// Checks the request (settings, guess).
    pub fn validate(&self) -> Result<(), ApiError> {
        ForwardKinematics::new(&self.robot.robot, self.settings())?;
        if let Some(g) = &self.guess {
            pose(&self.robot, g)?;
        }
        Ok(())
    }

    /// Solves for the pose.
    pub fn run(&self) -> Result<ForwardReport, ApiError> {
        let robot = &self.robot;
        let motion = robot.robot.motion();
        let mut fk = ForwardKinematics::new(&robot.robot, self.settings())?;
        let solutions = match &self.guess {
            Some(g) => vec![fk.solve(&self.lengths, &pose(robot, g)?)?],
            None => fk.solve_multistart(&self.lengths)?,
        };
        let solutions: Vec<_> = solutions
            .iter()
            .map(|s| ForwardSolutionReport::of(motion, s))
            .collect();
        Ok(ForwardReport {
            robot: robot.name.clone(),
            motion: motion.name().to_string(),
            kinematics: robot.kinematics_model(),
            length_sigma: self.length_sigma,
            best: solutions
                .first()
                .cloned()
                .ok_or_else(|| ApiError::invalid("forward kinematics found no solution"))?,
            solutions,
        })
    }
}
