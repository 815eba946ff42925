//! # Forward dynamics
//!
//! `cdpr simulate`: the motion of the platform from a pose and a twist, integrating
//! M(x) ẍ + b(x, ẋ) = W t + w_e + w_g (`cdpr_dynamics::forward_dynamics`) under tensions held
//! constant, a tension profile against time (a timed trajectory's `t` and `tensions`), or
//! elastic cables with commanded unstrained lengths, t_i = max(0, E S_i (l_i − l₀ᵢ)/l₀ᵢ + c l̇_i).
//! Classical RK4 at the fixed step `dt`, or the adaptive Dormand–Prince 5(4) with output every
//! `dt`; the orientation is a unit quaternion renormalised at every step.
//!
//! ## References
//! - Barrette & Gosselin 2005 (the platform's equations of motion).
//! - Dormand & Prince 1980, J. Comput. Appl. Math. 6(1) (the embedded 5(4) pair).

use cdpr_dynamics::{Drive, Integrator, Simulator, State, TimedSample, rigid_body};
use nalgebra::Vector6;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::inputs::{pose, wrench};
use crate::{ApiError, Robot};

/// The integration scheme of a simulation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum IntegratorName {
    /// Classical Runge–Kutta 4 at the fixed step `dt` (the default).
    #[default]
    Rk4,
    /// Dormand–Prince 5(4), adaptive (local error `tolerance`), output every `dt`.
    Rk45,
}

impl IntegratorName {
    /// The name on the command line and in JSON.
    pub fn name(self) -> &'static str {
        match self {
            Self::Rk4 => "rk4",
            Self::Rk45 => "rk45",
        }
    }
}

/// Tensions against time, interpolated linearly (held at the ends): a timed trajectory's `t`
/// and `tensions` (`cdpr trajectory --time-law … --json`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct TensionProfile {
    /// Times (s), strictly increasing.
    pub t: Vec<f64>,
    /// Tensions per time (N, one per cable); a null (an infeasible sample) is refused.
    pub tensions: Vec<Option<Vec<f64>>>,
    /// The profile's file name, shown in error messages.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
}

fn default_tolerance() -> f64 {
    1e-9
}

/// Forward dynamics of the platform (`cdpr simulate`). The drive is exactly one of
/// `tensions`, `tension_profile` and `unstrained_lengths`.
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
pub struct SimulateRequest {
    /// The robot (mass, centre of mass and `inertia` from its `[platform]`).
    pub robot: Robot,
    /// Initial pose (motion-pattern coordinates, m and rad).
    pub from: Vec<f64>,
    /// Initial twist: DOF numbers, velocity (m/s) then angular velocity (rad/s, base axes);
    /// default rest.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<Vec<f64>>,
    /// Simulated time T (s).
    pub duration: f64,
    /// Output period and (RK4) step (s).
    pub dt: f64,
    /// Cable tensions held constant (N), one per cable.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tensions: Option<Vec<f64>>,
    /// Tensions against time.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tension_profile: Option<TensionProfile>,
    /// Elastic cables: the commanded unstrained lengths l₀ (m), one per cable, held constant
    /// (needs `axial_stiffness` on every cable of the robot file).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unstrained_lengths: Option<Vec<f64>>,
    /// Elastic cables: damping c (N·s/m) on taut cables (default 0).
    #[serde(default)]
    pub damping: f64,
    /// `rk4` (default) or `rk45`.
    #[serde(default)]
    pub integrator: IntegratorName,
    /// rk45: local error tolerance per step (default 1e-9).
    #[serde(default = "default_tolerance")]
    pub tolerance: f64,
    /// External wrench w_e held constant (DOF numbers, N and N·m; default zero).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wrench: Option<Vec<f64>>,
}

/// The JSON of `cdpr simulate --json`.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct SimulateReport {
    /// Robot name.
    pub robot: String,
    /// `rk4` or `rk45`.
    pub integrator: String,
    /// Output times (s).
    pub t: Vec<f64>,
    /// The pose at each time (motion-pattern coordinates, m and rad).
    pub poses: Vec<Vec<f64>>,
    /// The twist at each time (DOF numbers: v in m/s, ω in rad/s).
    pub velocities: Vec<Vec<f64>>,
    /// Its rate at each time (m/s², rad/s²).
    pub accelerations: Vec<Vec<f64>>,
    /// Cable tensions at each time (N, per cable).
    pub tensions: Vec<Vec<f64>>,
    /// Integration steps taken.
    pub steps: usize,
    /// Steps rejected by the adaptive integrator (0 with rk4).
    pub rejected_steps: usize,
}

impl SimulateRequest {
    /// Tensions `tensions` held constant from `from` at rest, RK4, every other option at its
    /// default.
    pub fn with_tensions(
        robot: Robot,
        from: Vec<f64>,
        tensions: Vec<f64>,
        duration: f64,
        dt: f64,
    ) -> Self {
        Self {
            robot,
            from,
            velocity: None,
            duration,
            dt,
            tensions: Some(tensions),
            tension_profile: None,
            unstrained_lengths: None,
            damping: 0.0,
            integrator: IntegratorName::Rk4,
            tolerance: default_tolerance(),
            wrench: None,
        }
    }

    /// Checks the request (the messages of the command line).
    pub fn validate(&self) -> Result<(), ApiError> {
        self.simulator_inputs().map(|_| ())
    }

    /// Runs the simulation.
    pub fn run(&self) -> Result<SimulateReport, ApiError> {
        let (drive, start) = self.simulator_inputs()?;
        let robot = &self.robot;
        let motion = robot.robot.motion();
        let n = robot.robot.cable_count();
        let body = crate::criteria::rigid_body(robot)?;
        let external = wrench(robot, self.wrench.as_deref())?;
        let mut sim = Simulator::new(&robot.robot, body, drive, external.as_slice())?;
        let integrator = match self.integrator {
            IntegratorName::Rk4 => Integrator::Rk4,
            IntegratorName::Rk45 => Integrator::Rk45 {
                tolerance: self.tolerance,
            },
        };
        let run = sim.run(start, self.duration, self.dt, integrator)?;
        let components = |v: &Vector6<f64>| TimedSample::components(motion, v);
        Ok(SimulateReport {
            robot: robot.name.clone(),
            integrator: self.integrator.name().to_string(),
            poses: run
                .states
                .iter()
                .map(|s| s.pose().coordinates(motion))
                .collect(),
            velocities: run.states.iter().map(|s| components(&s.twist)).collect(),
            accelerations: run.accelerations.iter().map(components).collect(),
            tensions: run.tensions.chunks(n.max(1)).map(<[f64]>::to_vec).collect(),
            t: run.t,
            steps: run.steps,
            rejected_steps: run.rejected,
        })
    }

    /// The drive and the start state, checked.
    fn simulator_inputs(&self) -> Result<(Drive, State), ApiError> {
        let robot = &self.robot;
        robot
            .require_no_passive_springs("simulate")
            .map_err(ApiError::invalid)?;
        crate::criteria::rigid_body(robot)?;
        let start = pose(robot, &self.from)?;
        let twist = match &self.velocity {
            Some(v) => self.twist(v)?,
            None => Vector6::zeros(),
        };
        for (name, v) in [("--duration", self.duration), ("--dt", self.dt)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(ApiError::invalid(format!(
                    "{name} = {v}: must be a finite number > 0"
                )));
            }
        }
        if !(self.damping.is_finite() && self.damping >= 0.0) {
            return Err(ApiError::invalid(format!(
                "--damping = {}: must be a finite number ≥ 0",
                self.damping
            )));
        }
        Ok((self.drive()?, State::new(&start, twist)))
    }

    /// The initial twist from its DOF numbers.
    fn twist(&self, v: &[f64]) -> Result<Vector6<f64>, ApiError> {
        let motion = self.robot.robot.motion();
        if v.len() != motion.dof() {
            return Err(ApiError::invalid(format!(
                "--velocity: {} numbers for a {} platform, expected {}",
                v.len(),
                motion.name(),
                motion.dof()
            )));
        }
        if let Some(x) = v.iter().find(|x| !x.is_finite()) {
            return Err(ApiError::invalid(format!("--velocity: {x} is not finite")));
        }
        Ok(rigid_body::embed(motion, v))
    }

    /// The drive: exactly one of the three.
    fn drive(&self) -> Result<Drive, ApiError> {
        let n = self.robot.robot.cable_count();
        if self.damping != 0.0 && self.unstrained_lengths.is_none() {
            return Err(ApiError::invalid("--damping needs --unstrained-lengths"));
        }
        match (
            &self.tensions,
            &self.tension_profile,
            &self.unstrained_lengths,
        ) {
            (Some(t), None, None) => Ok(Drive::Tensions(t.clone())),
            (None, Some(p), None) => profile(p),
            (None, None, Some(l0)) => {
                let es = self.robot.axial_stiffness.clone().ok_or(ApiError::invalid(
                    "--unstrained-lengths needs `axial_stiffness` (E·S, N) on every cable of the robot file",
                ))?;
                Ok(Drive::Elastic {
                    unstrained_lengths: l0.clone(),
                    axial_stiffness: es,
                    damping: vec![self.damping; n],
                })
            }
            (None, None, None) => Err(ApiError::invalid(
                "give the drive: --tensions T1,…,Tn, --tension-profile FILE.json or --unstrained-lengths L1,…,Ln",
            )),
            _ => Err(ApiError::invalid(
                "give one drive: --tensions, --tension-profile or --unstrained-lengths",
            )),
        }
    }
}

/// A tension profile's drive (a null sample is refused, naming the file and the sample).
fn profile(p: &TensionProfile) -> Result<Drive, ApiError> {
    let prefix = p.file.as_ref().map_or(String::new(), |f| format!("{f}: "));
    let tensions = p
        .tensions
        .iter()
        .enumerate()
        .map(|(k, t)| {
            t.clone().ok_or_else(|| {
                ApiError::invalid(format!(
                    "{prefix}tensions[{k}] is null (an infeasible sample): no tension to apply"
                ))
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Drive::Profile {
        times: p.t.clone(),
        tensions,
    })
}
