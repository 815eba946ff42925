//! # Elastic and sagging cables at one pose
//!
//! The `--cable-model elastic|catenary` versions of `cdpr kinematics`, `cdpr tension` and
//! `cdpr forward` (issue 29), one request each, used by the CLI and Python: the sag-aware
//! inverse kinematics at given platform-end tensions, the statics with sagging cables
//! ([`cdpr_tension::SaggingStatics`], Kozak, Zhou & Wang 2006, §IV) and the elasto-geometric
//! forward kinematics from unstrained lengths ([`cdpr_kinematics::ElastoGeometricForward`],
//! Pott 2018, §6.4). Every cable is Irvine's elastic catenary (Irvine 1981, §2.3).
//!
//! ## References
//! - docs/algorithms.md, "Elastic catenary", "Statics with sagging cables",
//!   "Elasto-geometric forward kinematics".

use cdpr_kinematics::catenary::write_sagging_wrench_matrix;
use cdpr_kinematics::{ElastoGeometricForward, Pose, SaggingCable};
use cdpr_tension::{Method, SaggingOutcome, SaggingSettings, SaggingStatics, TensionSolver};
use nalgebra::DMatrix;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::cable_model::{CableModelName, catenaries};
use crate::inputs::{external_wrench, matrix_rows, method_name, pose, wrench};
use crate::{ApiError, Robot};

/// Per cable the state of its catenary (the sag-aware fields of the reports).
#[derive(Clone, Debug, Default, PartialEq, Serialize, JsonSchema)]
pub struct SaggingCablesReport {
    /// Unstrained lengths L0 (m); over a pulley the whole cable's, its wrapped arc included.
    pub unstrained_lengths: Vec<f64>,
    /// Chord lengths ‖B − A‖ (m); over a pulley of the free segment, from the tangent point.
    pub chord_lengths: Vec<f64>,
    /// Arc ρ β wrapped on each cable's pulley (m; 0 for a cable without one); only for robots
    /// with pulleys.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wrapped_lengths: Option<Vec<f64>>,
    /// Tensions at the frame end T_A (N).
    pub frame_end_tensions: Vec<f64>,
    /// Tensions at the platform end T_B (N).
    pub platform_end_tensions: Vec<f64>,
    /// Largest distance of each cable below its chord (m).
    pub max_sag: Vec<f64>,
    /// Angle between each cable at the platform and its chord (rad).
    pub angle_to_chord: Vec<f64>,
}

impl SaggingCablesReport {
    /// The fields of `cables`; `pulleys`: whether the robot has pulleys (then the wrapped
    /// lengths are reported).
    pub fn of(cables: &[SaggingCable], pulleys: bool) -> Self {
        let field = |f: fn(&SaggingCable) -> f64| cables.iter().map(f).collect();
        Self {
            unstrained_lengths: field(|c| c.unstrained_length),
            chord_lengths: field(|c| c.chord_length),
            wrapped_lengths: pulleys.then(|| field(|c| c.wrapped_length)),
            frame_end_tensions: field(|c| c.frame_end_tension),
            platform_end_tensions: field(|c| c.platform_end_tension),
            max_sag: field(|c| c.max_sag),
            angle_to_chord: field(|c| c.angle_to_chord),
        }
    }
}

/// The cable model of a request, which must not be `straight`.
fn model_of(
    robot: &Robot,
    name: CableModelName,
) -> Result<cdpr_kinematics::RobotCatenaries, ApiError> {
    catenaries(robot, name.model())?
        .ok_or_else(|| ApiError::invalid("this analysis needs --cable-model elastic or catenary"))
}

/// Per-cable numbers: one per cable, finite, ≥ 0 (> 0 when `positive`); `flag` names them.
fn per_cable(
    values: &[f64],
    n: usize,
    flag: &str,
    unit: &str,
    positive: bool,
) -> Result<(), ApiError> {
    if values.len() != n {
        return Err(ApiError::invalid(format!(
            "{flag} needs {n} numbers (one per cable), got {}",
            values.len()
        )));
    }
    if let Some(i) = values
        .iter()
        .position(|&v| !(v.is_finite() && (v > 0.0 || (!positive && v == 0.0))))
    {
        let bound = if positive { "> 0" } else { "≥ 0" };
        return Err(ApiError::invalid(format!(
            "{flag}: cable {} has {} {unit}; values are finite numbers {bound}",
            i + 1,
            values[i]
        )));
    }
    Ok(())
}

/// The sag-aware inverse kinematics at a pose (`cdpr kinematics --cable-model elastic|catenary
/// --tensions …`).
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
pub struct SaggingKinematicsRequest {
    /// The robot.
    pub robot: Robot,
    /// Platform pose (m, rad).
    pub pose: Vec<f64>,
    /// `elastic` or `catenary`.
    pub cable_model: CableModelName,
    /// Platform-end tensions T_B, one per cable (N, ≥ 0).
    pub tensions: Vec<f64>,
}

/// The JSON of `cdpr kinematics --cable-model elastic|catenary --json`.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct SaggingKinematicsReport {
    /// Robot name.
    pub robot: String,
    /// Motion pattern.
    pub motion: String,
    /// The pose (m, rad).
    pub pose: Vec<f64>,
    /// `elastic` or `catenary`.
    pub cable_model: String,
    /// Rows of the sag-aware wrench matrix (DOF × n; columns the unit forces of the cables at
    /// the platform; N/N and N·m/N).
    pub wrench_matrix: Vec<Vec<f64>>,
    /// Each cable's catenary.
    #[serde(flatten)]
    pub cables: SaggingCablesReport,
}

impl SaggingKinematicsRequest {
    /// Runs the analysis.
    pub fn run(&self) -> Result<SaggingKinematicsReport, ApiError> {
        let model = model_of(&self.robot, self.cable_model)?;
        let name = self.cable_model.model().name();
        let kin = self
            .robot
            .robot
            .inverse_kinematics(&pose(&self.robot, &self.pose)?)?;
        per_cable(&self.tensions, kin.cable_count(), "--tensions", "N", false)?;
        let mut cables = Vec::new();
        model.with_tensions(&kin, &self.tensions, &mut cables)?;
        let mut w = DMatrix::zeros(0, 0);
        write_sagging_wrench_matrix(&kin, &cables, &mut w);
        Ok(SaggingKinematicsReport {
            robot: self.robot.name.clone(),
            motion: self.robot.robot.motion().name().to_string(),
            pose: self.pose.clone(),
            cable_model: name.to_string(),
            wrench_matrix: matrix_rows(&w),
            cables: SaggingCablesReport::of(&cables, self.robot.robot.has_pulleys()),
        })
    }
}

fn default_method() -> Method {
    Method::L2
}

/// The statics with sagging cables at a pose (`cdpr tension --cable-model elastic|catenary`).
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
pub struct SaggingTensionRequest {
    /// The robot.
    pub robot: Robot,
    /// Platform pose (m, rad).
    pub pose: Vec<f64>,
    /// External wrench w_e (N, N·m; default zero), added to the robot file's load.
    #[serde(default)]
    pub wrench: Option<Vec<f64>>,
    /// Tension distribution method of each fixed-point iteration (default `l2`; not `sotda`).
    #[serde(default = "default_method", with = "method_name")]
    #[schemars(with = "String")]
    pub method: Method,
    /// `elastic` or `catenary`.
    pub cable_model: CableModelName,
}

/// The JSON of `cdpr tension --cable-model elastic|catenary --json`.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct SaggingTensionReport {
    /// Robot name.
    pub robot: String,
    /// The pose (m, rad).
    pub pose: Vec<f64>,
    /// w_ext: the given wrench plus the robot file's load (N, N·m).
    pub external_wrench: Vec<f64>,
    /// The method's name.
    pub method: String,
    /// `elastic` or `catenary`.
    pub cable_model: String,
    /// Whether a certified equilibrium was found.
    pub feasible: bool,
    /// Platform-end tensions T_B (N), null if infeasible.
    pub tensions: Option<Vec<f64>>,
    /// ‖W(T_B) T_B + w_ext‖∞ with the catenary forces (N, N·m), null if infeasible.
    pub residual: Option<f64>,
    /// Fixed-point iterations (null if infeasible).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub iterations: Option<usize>,
    /// Why there is no equilibrium (null if feasible).
    pub reason: Option<String>,
    /// Rows of the sag-aware wrench matrix at the solution (absent if infeasible).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wrench_matrix: Option<Vec<Vec<f64>>>,
    /// Each cable's catenary at the solution (absent if infeasible).
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub cables: Option<SaggingCablesReport>,
}

impl SaggingTensionRequest {
    /// Runs the analysis.
    pub fn run(&self) -> Result<SaggingTensionReport, ApiError> {
        let name = self.cable_model.model().name();
        if self.method == Method::Sotda {
            return Err(ApiError::invalid(format!(
                "--cable-model {name} does not apply to sotda (its stiffness model is the straight cables')"
            )));
        }
        let model = model_of(&self.robot, self.cable_model)?;
        let p = pose(&self.robot, &self.pose)?;
        let kin = self.robot.robot.inverse_kinematics(&p)?;
        let w_ext = external_wrench(&self.robot, &p, self.wrench.as_deref())?;
        let outcome = SaggingStatics::new(SaggingSettings::default()).solve(
            &mut TensionSolver::new(self.method),
            &kin,
            &model,
            &w_ext,
            &self.robot.bounds,
        )?;
        let mut r = SaggingTensionReport {
            robot: self.robot.name.clone(),
            pose: self.pose.clone(),
            external_wrench: w_ext.as_slice().to_vec(),
            method: self.method.name().to_string(),
            cable_model: name.to_string(),
            feasible: false,
            tensions: None,
            residual: None,
            iterations: None,
            reason: None,
            wrench_matrix: None,
            cables: None,
        };
        match outcome {
            SaggingOutcome::Feasible(s) => {
                r.feasible = true;
                r.tensions = Some(s.tensions.as_slice().to_vec());
                r.residual = Some(s.residual);
                r.iterations = Some(s.iterations);
                r.wrench_matrix = Some(matrix_rows(&s.wrench_matrix));
                r.cables = Some(SaggingCablesReport::of(
                    &s.cables,
                    self.robot.robot.has_pulleys(),
                ));
            }
            SaggingOutcome::Infeasible(why) => r.reason = Some(why.to_string()),
        }
        Ok(r)
    }
}

/// The elasto-geometric forward kinematics (`cdpr forward --unstrained-lengths …
/// --cable-model elastic|catenary`).
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
pub struct ElastoGeometricRequest {
    /// The robot.
    pub robot: Robot,
    /// Unstrained lengths L0, one per cable (m, > 0).
    pub unstrained_lengths: Vec<f64>,
    /// `elastic` or `catenary`.
    pub cable_model: CableModelName,
    /// External wrench w_e (N, N·m; default zero), added to the robot file's load.
    #[serde(default)]
    pub wrench: Option<Vec<f64>>,
    /// Start pose (m, rad); default the straight cables' poses for the lengths (multi-start).
    #[serde(default)]
    pub guess: Option<Vec<f64>>,
}

/// The JSON of `cdpr forward --unstrained-lengths … --json`.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct ElastoGeometricReport {
    /// Robot name.
    pub robot: String,
    /// Motion pattern.
    pub motion: String,
    /// `elastic` or `catenary`.
    pub cable_model: String,
    /// The equilibrium pose found (m, rad).
    pub pose: Vec<f64>,
    /// Platform-end tensions (N).
    pub tensions: Vec<f64>,
    /// max |g| of the equilibrium (N; moments divided by the robot's length scale).
    pub residual: f64,
    /// `equilibrium` or `did not converge`.
    pub status: String,
    /// Iterations taken.
    pub iterations: usize,
    /// The slack cables (1-based).
    pub slack_cables: Vec<usize>,
    /// w_ext at the pose: the given wrench plus the robot file's load (N, N·m).
    pub external_wrench: Vec<f64>,
    /// Each cable's catenary at the pose.
    #[serde(flatten)]
    pub cables: SaggingCablesReport,
}

impl ElastoGeometricRequest {
    /// Runs the analysis.
    pub fn run(&self) -> Result<ElastoGeometricReport, ApiError> {
        let robot = &self.robot;
        let model = model_of(robot, self.cable_model).map_err(|_| {
            ApiError::invalid("--unstrained-lengths needs --cable-model elastic or catenary (straight cables have no unstrained length: use --lengths)")
        })?;
        let l0 = &self.unstrained_lengths;
        per_cable(
            l0,
            robot.robot.cable_count(),
            "--unstrained-lengths",
            "m",
            true,
        )?;
        let w_e = wrench(robot, self.wrench.as_deref())?;
        let guess: Option<Pose> = self.guess.as_deref().map(|g| pose(robot, g)).transpose()?;
        let mut fk = ElastoGeometricForward::new(&robot.robot, &model, Default::default())?;
        let mut load = |p: &Pose, out: &mut [f64]| {
            let w = robot.load_wrench(p)? + &w_e;
            out.copy_from_slice(w.as_slice());
            Ok(())
        };
        let sol = match guess {
            Some(g) => fk.solve_with_load(l0, &mut load, &g)?,
            None => fk.solve_multistart_with_load(l0, &mut load)?,
        };
        let motion = robot.robot.motion();
        let n = robot.robot.cable_count();
        Ok(ElastoGeometricReport {
            robot: robot.name.clone(),
            motion: motion.name().to_string(),
            cable_model: self.cable_model.model().name().to_string(),
            pose: sol.pose.coordinates(motion),
            tensions: fk.cables().iter().map(|c| c.platform_end_tension).collect(),
            residual: sol.residual,
            status: sol.status.name().to_string(),
            iterations: sol.iterations,
            slack_cables: (0..n).filter(|&i| fk.is_slack(i)).map(|i| i + 1).collect(),
            external_wrench: (robot.load_wrench(&sol.pose)? + &w_e).as_slice().to_vec(),
            cables: SaggingCablesReport::of(fk.cables(), robot.robot.has_pulleys()),
        })
    }
}
