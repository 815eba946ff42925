//! # Stiffness matrix at a pose
//!
//! K = Kp + Ka under given tensions (or those of a tension distribution method balancing the
//! robot file's load and w_e), with k_i = E·S / l_i (Picard, Caro, Plestan & Claveau 2020,
//! eqs. (3)–(4)).
//!
//! ## References
//! - Picard, Caro, Plestan & Claveau 2020 (passive and active stiffness, eqs. (3)–(4)).

use cdpr_tension::{Method, TensionOutcome, TensionProblem, TensionSolver};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::inputs::{check_method, external_wrench, matrix_rows, option_method_name, pose};
use crate::{ApiError, Robot};

/// The stiffness matrix at one pose (`cdpr stiffness`).
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
pub struct StiffnessRequest {
    /// The robot.
    pub robot: Robot,
    /// Platform pose (m, rad).
    pub pose: Vec<f64>,
    /// Cable tensions t_i (N, ≥ 0); without them, those of `method`.
    #[serde(default)]
    pub tensions: Option<Vec<f64>>,
    /// Tension distribution method when `tensions` is absent (default `l2`; not `sotda`).
    #[serde(default, with = "option_method_name")]
    #[schemars(with = "Option<String>")]
    pub method: Option<Method>,
    /// External wrench w_e the `method` tensions balance with the robot file's load (N, N·m).
    #[serde(default)]
    pub wrench: Option<Vec<f64>>,
    /// E·S for every cable (N), overriding the robot file.
    #[serde(default)]
    pub axial_stiffness: Option<f64>,
}

/// The JSON of `cdpr stiffness --json`.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct StiffnessReport {
    /// Robot name.
    pub robot: String,
    /// The pose (m, rad).
    pub pose: Vec<f64>,
    /// The tensions used (N).
    pub tensions: Vec<f64>,
    /// The method that gave them; null when given.
    pub tension_method: Option<String>,
    /// Rows of K = Kp + Ka (N/m, N·m/rad, N).
    pub stiffness: Vec<Vec<f64>>,
    /// Rows of Kp.
    pub passive: Vec<Vec<f64>>,
    /// Rows of Ka.
    pub active: Vec<Vec<f64>>,
}

impl StiffnessRequest {
    /// Checks the request.
    pub fn validate(&self) -> Result<(), ApiError> {
        self.axial_stiffness().map(|_| ())?;
        if self.tensions.is_some() && (self.method.is_some() || self.wrench.is_some()) {
            return Err(ApiError::invalid(
                "--tensions excludes --method and --wrench (they give the tensions)",
            ));
        }
        let p = pose(&self.robot, &self.pose)?;
        match &self.tensions {
            Some(t) => checked_tensions(t),
            None => {
                let method = self.method.unwrap_or(Method::L2);
                if method == Method::Sotda {
                    return Err(ApiError::invalid(
                        "--method sotda needs its own options: run `cdpr tension --method sotda` \
                         and pass its tensions with --tensions",
                    ));
                }
                check_method(&self.robot, method)?;
                external_wrench(&self.robot, &p, self.wrench.as_deref()).map(|_| ())
            }
        }
    }

    fn axial_stiffness(&self) -> Result<Vec<f64>, ApiError> {
        let n = self.robot.robot.cable_count();
        self.robot
            .require_no_passive_springs(
                "the stiffness matrix (cables only; the springs' K would add to it)",
            )
            .map_err(ApiError::Invalid)?;
        match (self.axial_stiffness, &self.robot.axial_stiffness) {
            (Some(v), _) if !(v.is_finite() && v > 0.0) => Err(ApiError::invalid(format!(
                "--axial-stiffness must be a finite number > 0, got {v}"
            ))),
            (Some(v), _) => Ok(vec![v; n]),
            (None, Some(v)) => Ok(v.clone()),
            (None, None) => Err(ApiError::invalid(
                "no axial stiffness: give `axial_stiffness` on every cable of the robot file, or \
                 --axial-stiffness",
            )),
        }
    }

    /// K, Kp and Ka.
    pub fn run(&self) -> Result<StiffnessReport, ApiError> {
        self.validate()?;
        let es = self.axial_stiffness()?;
        let robot = &self.robot;
        let p = pose(robot, &self.pose)?;
        let kin = robot.robot.inverse_kinematics(&p)?;
        let (tensions, method) = match &self.tensions {
            Some(t) => (t.clone(), None),
            None => {
                let method = self.method.unwrap_or(Method::L2);
                let w = kin.wrench_matrix();
                let w_ext = external_wrench(robot, &p, self.wrench.as_deref())?;
                let problem = TensionProblem::new(&w, &w_ext, &robot.bounds);
                match TensionSolver::new(method).solve(&problem)? {
                    TensionOutcome::Feasible(s) => (s.tensions.as_slice().to_vec(), Some(method)),
                    TensionOutcome::Infeasible(reason) => {
                        return Err(ApiError::invalid(format!(
                            "no tensions within the bounds at this pose ({}): {reason}; give \
                             --tensions",
                            method.name()
                        )));
                    }
                }
            }
        };
        let k = cdpr_wrench::stiffness_matrix(&kin, &tensions, &es)?;
        let kp = cdpr_wrench::passive_stiffness(&kin, &es)?;
        let ka = cdpr_wrench::active_stiffness(&kin, &tensions)?;
        Ok(StiffnessReport {
            robot: robot.name.clone(),
            pose: self.pose.clone(),
            tensions,
            tension_method: method.map(|m| m.name().to_string()),
            stiffness: matrix_rows(&k),
            passive: matrix_rows(&kp),
            active: matrix_rows(&ka),
        })
    }
}

/// Tensions as given: finite and ≥ 0 (a cable can only pull).
fn checked_tensions(t: &[f64]) -> Result<(), ApiError> {
    if let Some((i, v)) = t
        .iter()
        .enumerate()
        .find(|(_, v)| !(v.is_finite() && **v >= 0.0))
    {
        return Err(ApiError::invalid(format!(
            "--tensions: t_{} = {v} N; tensions are finite and ≥ 0 (a cable can only pull)",
            i + 1
        )));
    }
    Ok(())
}
