//! # Timed trajectories and their inverse dynamics
//!
//! The path of a [`TrajectoryRequest`](crate::trajectory::TrajectoryRequest) run with a time law of `cdpr_dynamics::time_law`
//! (linear, cubic, quintic, trapezoid, parabolic blend), sampled every `dt` s. At every sample
//! the tensions balance w_e + w_g (+ passive springs), and with `dynamics` also the inertial
//! wrench: W t + w_e + w_g = M ẍ + b (`cdpr_dynamics::inverse_dynamics`). With a `winch` on every
//! cable of the robot file the report adds the drive train (`cdpr_dynamics::drive_train`):
//! motor speeds ω = −(G/r) l̇, torques τ = (r/G) t − J_m (G/r) l̈, powers, peaks, RMS values and
//! the verdict against the motors' limits.
//!
//! ## References
//! - Biagiotti & Melchiorri 2008, *Trajectory Planning for Automatic Machines and Robots*, §2.1,
//!   §3.2 (the time laws); Craig 2005, §7.3 (parabolic blends).
//! - Barrette & Gosselin 2005 (the platform's equations of motion).

use cdpr_dynamics::{
    DriveTrainProfile, DynamicsProfile, JointSpline, TimeLaw, TimedSample, TimingSettings,
    Trajectory, drive_train, inverse_dynamics,
};
use cdpr_kinematics::Pose;
use cdpr_tension::{Method, TensionSolver};
use nalgebra::DVector;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::{ApiError, Robot};

/// The time law of a trajectory request and its inverse dynamics.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct TimedSettings {
    /// Time law: `linear`, `cubic`, `quintic`, `trapezoid` or `parabolic-blend` (none: the
    /// untimed profile along s).
    #[serde(default, skip_serializing_if = "Option::is_none", with = "law_name")]
    #[schemars(with = "Option<String>")]
    pub time_law: Option<TimeLaw>,
    /// Total duration T (s), shared among segments in proportion to their pose distance (or a
    /// `time` on every waypoint).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub duration: Option<f64>,
    /// Sampling period (s; default 0.01).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dt: Option<f64>,
    /// Largest speed along the path (m/s, 1 rad counting as 1 m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_velocity: Option<f64>,
    /// Largest acceleration along the path (m/s²).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_acceleration: Option<f64>,
    /// Parabolic blend time t_b (s; default a quarter of the shortest segment).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub blend_time: Option<f64>,
    /// Inverse dynamics: balance the inertial wrench M ẍ + b too.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub dynamics: bool,
}

/// Serde of an optional [`TimeLaw`] by name.
mod law_name {
    use cdpr_dynamics::TimeLaw;
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(m: &Option<TimeLaw>, s: S) -> Result<S::Ok, S::Error> {
        match m {
            Some(m) => s.serialize_some(m.name()),
            None => s.serialize_none(),
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<TimeLaw>, D::Error> {
        Option::<String>::deserialize(d)?
            .map(|s| s.parse().map_err(serde::de::Error::custom))
            .transpose()
    }
}

impl TimedSettings {
    /// Whether the trajectory is timed.
    pub fn is_timed(&self) -> bool {
        self.time_law.is_some()
    }

    /// The sampling period (s).
    pub fn period(&self) -> f64 {
        self.dt.unwrap_or(0.01)
    }

    /// Options of a time law given without one.
    pub(crate) fn refuse_untimed(&self) -> Result<(), ApiError> {
        let given = [
            ("--duration", self.duration.is_some()),
            ("--dt", self.dt.is_some()),
            ("--max-velocity", self.max_velocity.is_some()),
            ("--max-acceleration", self.max_acceleration.is_some()),
            ("--blend-time", self.blend_time.is_some()),
            ("--dynamics", self.dynamics),
        ];
        match given.iter().find(|(_, set)| *set) {
            Some((name, _)) => Err(ApiError::invalid(format!(
                "{name} needs --time-law (a timed trajectory)"
            ))),
            None => Ok(()),
        }
    }

    /// Time-law options given with a CASPR trajectory (which has its own times and step).
    pub(crate) fn refuse_with_caspr(&self) -> Result<(), ApiError> {
        let given = [
            ("--time-law", self.time_law.is_some()),
            ("--duration", self.duration.is_some()),
            ("--dt", self.dt.is_some()),
            ("--max-velocity", self.max_velocity.is_some()),
            ("--max-acceleration", self.max_acceleration.is_some()),
            ("--blend-time", self.blend_time.is_some()),
        ];
        match given.iter().find(|(_, set)| *set) {
            Some((name, _)) => Err(ApiError::invalid(format!(
                "{name} does not apply to --trajectory: the CASPR file gives the points' times, \
                 its spline and its time_step"
            ))),
            None => Ok(()),
        }
    }

    /// The timed trajectory through the prepared waypoints.
    pub(crate) fn trajectory(
        &self,
        robot: &Robot,
        prepared: &PreparedPath,
    ) -> Result<Trajectory, ApiError> {
        let Some(law) = self.time_law else {
            return Err(ApiError::invalid("give --time-law LAW"));
        };
        if prepared.times.is_some() && self.duration.is_some() {
            return Err(ApiError::invalid(
                "give either --duration or a `time` on every waypoint, not both",
            ));
        }
        let settings = TimingSettings {
            law,
            duration: self.duration,
            waypoint_times: prepared.times.clone(),
            max_velocity: self.max_velocity,
            max_acceleration: self.max_acceleration,
            blend_time: self.blend_time,
        };
        Ok(Trajectory::new(
            robot.robot.motion(),
            &prepared.poses,
            &settings,
        )?)
    }
}

/// A CASPR joint-space trajectory as data: the text of `NAME_trajectories.xml` and the `id` of
/// one of its trajectories (read by `cdpr_io::parse_caspr_trajectory`; the splines:
/// `cdpr_dynamics::joint_spline`). It replaces the path and the time law: the file gives the
/// points, their times and the sampling period `time_step`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CasprTrajectorySource {
    /// The text of the CASPR trajectories file.
    pub text: String,
    /// The trajectory's `id` (default: the file's only joint trajectory).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub id: Option<String>,
    /// The file name shown in error messages (default `robot_trajectories.xml`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
}

impl CasprTrajectorySource {
    /// Reads the trajectory for `robot` (errors name the file, line and element).
    pub fn read(&self, robot: &Robot) -> Result<cdpr_io::CasprTrajectory, ApiError> {
        let file =
            std::path::PathBuf::from(self.file.as_deref().unwrap_or("robot_trajectories.xml"));
        let id = match &self.id {
            Some(id) => id.clone(),
            None => {
                let ids = cdpr_io::caspr_trajectory_ids(&self.text, &file)?;
                match ids.as_slice() {
                    [(id, _)] => id.clone(),
                    _ => {
                        let names: Vec<&str> = ids.iter().map(|(i, _)| i.as_str()).collect();
                        return Err(ApiError::invalid(format!(
                            "{}: give --trajectory-id (the file has {} joint trajectories: {})",
                            file.display(),
                            names.len(),
                            names.join(", ")
                        )));
                    }
                }
            }
        };
        Ok(cdpr_io::parse_caspr_trajectory(
            &self.text,
            &file,
            &id,
            robot.robot.motion(),
        )?)
    }
}

/// The samples of a timed trajectory and what the report says of its timing.
pub(crate) struct Timeline {
    samples: Vec<TimedSample>,
    waypoint_times: Vec<f64>,
    duration: f64,
    law: String,
    dt: f64,
    trajectory_id: Option<String>,
}

impl Timeline {
    /// A time law's samples every `timing.period()` s.
    pub(crate) fn of_law(timing: &TimedSettings, traj: &Trajectory) -> Result<Self, ApiError> {
        let dt = timing.period();
        let (start, end) = traj.time_span();
        Ok(Self {
            samples: traj.sample(dt)?,
            waypoint_times: traj.waypoint_times(),
            duration: end - start,
            law: timing.time_law.map_or("", |l| l.name()).to_string(),
            dt,
            trajectory_id: None,
        })
    }

    /// A CASPR trajectory's samples every `time_step`.
    pub(crate) fn of_caspr(id: &str, spline: &JointSpline) -> Self {
        let (start, end) = spline.time_span();
        Self {
            samples: spline.samples(),
            waypoint_times: spline.waypoint_times(),
            duration: end - start,
            law: spline.kind().element().to_string(),
            dt: spline.time_step(),
            trajectory_id: Some(id.to_string()),
        }
    }
}

/// A checked request: waypoint poses, their wrenches and times, the solver.
pub(crate) struct PreparedPath {
    /// Waypoint poses.
    pub poses: Vec<Pose>,
    /// w_e at each waypoint.
    pub wrenches: Vec<DVector<f64>>,
    /// Per-waypoint times, when every waypoint has one.
    pub times: Option<Vec<f64>>,
    /// The solver.
    pub solver: TensionSolver,
    /// A CASPR trajectory (its id and spline) instead of a time law.
    pub caspr: Option<(String, JointSpline)>,
}

/// The drive train along a timed trajectory (robots with a `winch` on every cable).
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct DriveTrainReport {
    /// Motor speeds ω (rad/s, > 0 winds in), per sample and motor.
    pub motor_speeds: Vec<Vec<f64>>,
    /// Motor torques τ (N·m, > 0 winds in), per sample and motor; null where infeasible.
    pub motor_torques: Vec<Option<Vec<f64>>>,
    /// Motor powers τ ω (W), per sample and motor; null where infeasible.
    pub motor_powers: Vec<Option<Vec<f64>>>,
    /// Per motor, max |ω| (rad/s).
    pub motor_peak_speed: Vec<f64>,
    /// Per motor, the RMS speed (rad/s).
    pub motor_rms_speed: Vec<f64>,
    /// Per motor, max |τ| over the feasible samples (N·m; null when none is feasible).
    pub motor_peak_torque: Vec<f64>,
    /// Per motor, the RMS torque (N·m; null when a sample is infeasible).
    pub motor_rms_torque: Vec<Option<f64>>,
    /// Per motor, max τ ω over the feasible samples (W).
    pub motor_peak_power: Vec<Option<f64>>,
    /// Max over time of Σ τ ω (W).
    pub peak_total_power: Option<f64>,
    /// Per motor, the robot file's `max_torque` (N·m) or null.
    pub motor_max_torque: Vec<Option<f64>>,
    /// Per motor, the robot file's `max_speed` (rad/s) or null.
    pub motor_max_speed: Vec<Option<f64>>,
    /// Can these motors do it (null: no limit given, or infeasible samples leave τ unknown)?
    pub motors_within_limits: Option<bool>,
    /// Every exceeded limit, with the motor, the value and the first time.
    pub motor_limit_violations: Vec<String>,
}

/// A timed trajectory (the JSON of `cdpr trajectory --time-law … --json`).
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct TimedReport {
    /// Robot name.
    pub robot: String,
    /// The method's name.
    pub method: String,
    /// The time law (`linear`, …), or the CASPR trajectory's element
    /// (`quintic_spline_trajectory`, …).
    pub time_law: String,
    /// The CASPR trajectory's `id` (with `caspr_trajectory`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub trajectory_id: Option<String>,
    /// Whether the inertial wrench is balanced (inverse dynamics) or not (quasi-static).
    pub dynamics: bool,
    /// Sampling period (s).
    pub dt: f64,
    /// Duration (s).
    pub duration: f64,
    /// The time of each waypoint (s).
    pub waypoint_times: Vec<f64>,
    /// Sample times (s).
    pub t: Vec<f64>,
    /// The pose of each sample (m, rad).
    pub poses: Vec<Vec<f64>>,
    /// Twist ẋ per sample (DOF numbers: v in m/s, ω in rad/s).
    pub velocity: Vec<Vec<f64>>,
    /// Its rate ẍ per sample (m/s², rad/s²).
    pub acceleration: Vec<Vec<f64>>,
    /// Cable lengths l (m) per sample.
    pub cable_lengths: Vec<Vec<f64>>,
    /// Cable speeds l̇ = −Wᵀẋ (m/s) per sample.
    pub cable_speeds: Vec<Vec<f64>>,
    /// Cable accelerations l̈ (m/s²) per sample.
    pub cable_accelerations: Vec<Vec<f64>>,
    /// Tensions per sample (N), null where infeasible.
    pub tensions: Vec<Option<Vec<f64>>>,
    /// Why a sample is infeasible (null where feasible).
    pub reasons: Vec<Option<String>>,
    /// Feasible samples.
    pub feasible_count: usize,
    /// Lower tension bounds (N).
    pub t_min: Vec<f64>,
    /// Upper tension bounds (N; null when unbounded).
    pub t_max: Vec<f64>,
    /// With `dynamics`: the inertial wrench M ẍ + b per sample (N, N·m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub inertial_wrench: Option<Vec<Vec<f64>>>,
    /// The drive train, when every cable has a `winch`.
    #[serde(flatten)]
    pub drive_train: Option<DriveTrainReport>,
}

/// w_e at time t: linear between the waypoint times.
fn wrench_at(times: &[f64], wrenches: &[DVector<f64>], t: f64) -> DVector<f64> {
    let k = times.partition_point(|&c| c <= t).clamp(1, times.len() - 1) - 1;
    let span = times[k + 1] - times[k];
    let tau = if span > 0.0 {
        ((t - times[k]) / span).clamp(0.0, 1.0)
    } else {
        1.0
    };
    &wrenches[k] * (1.0 - tau) + &wrenches[k + 1] * tau
}

/// Runs the timed trajectory of a prepared request (its time law, or its CASPR trajectory).
pub(crate) fn run(
    robot: &Robot,
    timing: &TimedSettings,
    method: Method,
    mut prepared: PreparedPath,
) -> Result<TimedReport, ApiError> {
    let timeline = match &prepared.caspr {
        Some((id, spline)) => Timeline::of_caspr(id, spline),
        None => Timeline::of_law(timing, &timing.trajectory(robot, &prepared)?)?,
    };
    let samples = &timeline.samples;
    let body = match timing.dynamics {
        true => Some(crate::criteria::rigid_body(robot)?),
        false => None,
    };
    for s in samples {
        robot
            .load_wrench(&s.pose)
            .map_err(|e| ApiError::invalid(format!("at t = {} s: {e}", s.t)))?;
    }
    let times = &timeline.waypoint_times;
    let profile = inverse_dynamics(
        &robot.robot,
        body.as_ref(),
        samples,
        &robot.bounds,
        &mut prepared.solver,
        robot.axial_stiffness.as_deref(),
        |_, s: &TimedSample| {
            wrench_at(times, &prepared.wrenches, s.t)
                + robot
                    .load_wrench(&s.pose)
                    .expect("checked at every sample above")
        },
    )?;
    let drive = match &robot.winches {
        Some(w) => Some(drive_report(w, &drive_train(w, &profile)?)),
        None => None,
    };
    let head = Head {
        robot,
        timing,
        method,
    };
    Ok(report(&head, &timeline, profile, drive))
}

/// Rows of a flat per-sample quantity.
fn rows(flat: &[f64], width: usize) -> Vec<Vec<f64>> {
    flat.chunks(width.max(1)).map(<[f64]>::to_vec).collect()
}

/// What the report repeats of the request.
struct Head<'a> {
    robot: &'a Robot,
    timing: &'a TimedSettings,
    method: Method,
}

fn report(
    request: &Head,
    timeline: &Timeline,
    profile: DynamicsProfile,
    drive_train: Option<DriveTrainReport>,
) -> TimedReport {
    let samples = &timeline.samples;
    let robot = &request.robot;
    let motion = robot.robot.motion();
    let n = robot.robot.cable_count();
    let components = |f: fn(&TimedSample) -> &nalgebra::Vector6<f64>| -> Vec<Vec<f64>> {
        samples
            .iter()
            .map(|s| TimedSample::components(motion, f(s)))
            .collect()
    };
    TimedReport {
        robot: robot.name.clone(),
        method: request.method.name().to_string(),
        time_law: timeline.law.clone(),
        trajectory_id: timeline.trajectory_id.clone(),
        dynamics: request.timing.dynamics,
        dt: timeline.dt,
        duration: timeline.duration,
        waypoint_times: timeline.waypoint_times.clone(),
        poses: samples.iter().map(|s| s.pose.coordinates(motion)).collect(),
        velocity: components(|s| &s.twist),
        acceleration: components(|s| &s.twist_rate),
        cable_lengths: rows(&profile.cable_lengths, n),
        cable_speeds: rows(&profile.cable_speeds, n),
        cable_accelerations: rows(&profile.cable_accelerations, n),
        tensions: profile
            .tensions
            .iter()
            .map(|t| t.as_ref().map(|t| t.as_slice().to_vec()))
            .collect(),
        feasible_count: profile.feasible_count(),
        inertial_wrench: request
            .timing
            .dynamics
            .then(|| rows(&profile.inertial_wrench, motion.dof())),
        t: profile.t,
        reasons: profile.reasons,
        t_min: robot.bounds.min().as_slice().to_vec(),
        t_max: robot.bounds.max().as_slice().to_vec(),
        drive_train,
    }
}

fn drive_report(winches: &[cdpr_dynamics::Winch], d: &DriveTrainProfile) -> DriveTrainReport {
    let n = d.motors;
    let nullable = |flat: &[f64]| -> Vec<Option<Vec<f64>>> {
        flat.chunks(n.max(1))
            .map(|c| c.iter().all(|v| v.is_finite()).then(|| c.to_vec()))
            .collect()
    };
    let finite = |v: f64| v.is_finite().then_some(v);
    DriveTrainReport {
        motor_speeds: rows(&d.motor_speeds, n),
        motor_torques: nullable(&d.motor_torques),
        motor_powers: nullable(&d.motor_powers),
        motor_peak_speed: d.peak_speed.clone(),
        motor_rms_speed: d.rms_speed.clone(),
        motor_peak_torque: d.peak_torque.clone(),
        motor_rms_torque: d.rms_torque.clone(),
        motor_peak_power: d.peak_power.iter().map(|&v| finite(v)).collect(),
        peak_total_power: finite(d.peak_total_power),
        motor_max_torque: winches.iter().map(|w| w.max_torque).collect(),
        motor_max_speed: winches.iter().map(|w| w.max_speed).collect(),
        motors_within_limits: d.within_limits,
        motor_limit_violations: d.violations.clone(),
    }
}
