//! # Tension profiles along a path, and timed trajectories
//!
//! `cdpr trajectory`: a path (the segment `from` → `to`, or a polyline of waypoints) with the
//! tensions at every sample by any method, certified (equilibrium and bounds to 1e-9), under
//! w_e (interpolated linearly between waypoints) plus the platform's gravity and springs.
//!
//! Without a time law the path is sampled by count or step in its parameter s ∈ [0, 1]
//! (∝ the pose distance √(‖Δu‖² + θ²)) and the report gives the continuity of the profile: the
//! largest jump per cable and the steps flagged as discontinuities (a jump above `jump_ratio`
//! median jumps). With a time law (or a CASPR spline trajectory) the path is timed and sampled
//! every `dt` s, and with `dynamics` the tensions balance the inertial wrench too
//! ([`crate::timed`]). With `cable_model` elastic or catenary, the untimed report adds the flex
//! and sag compensation: per sample the unstrained lengths the winches pay out.
//!
//! ## References
//! - Thesis Fig. 6.6 (minimum-norm tensions jump); Picard, Caro, Plestan & Claveau 2020, §4
//!   (SOTDA tensions stay continuous).

use cdpr_io::RobotDescription;
use cdpr_kinematics::{Path, PathSample, Pose, Sampling};
use cdpr_tension::Method;
use cdpr_tension::profile::{WaypointWrenches, tension_profile};
use nalgebra::DVector;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::cable_model::{CableModelName, catenaries, compensation};
use crate::inputs::{check_method, method_name, pose, wrench};
use crate::tension::MethodSettings;
use crate::timed::{CasprTrajectorySource, PreparedPath, TimedReport, TimedSettings};
use crate::{ApiError, Robot};

/// One waypoint of a polyline (a `[[waypoints]]` table of the waypoints file).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Waypoint {
    /// The pose in motion-pattern coordinates (m, rad).
    pub pose: Vec<f64>,
    /// The external wrench w_e there (N, N·m; default the request's `wrench`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wrench: Option<Vec<f64>>,
    /// The waypoint's time (s) for a time law (every waypoint or none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct WaypointFile {
    waypoints: Vec<Waypoint>,
}

/// The waypoints of a waypoints file's TOML text (`[[waypoints]]` tables); `file` names it in
/// errors.
pub fn parse_waypoints(text: &str, file: &str) -> Result<Vec<Waypoint>, ApiError> {
    let parsed: WaypointFile =
        toml::from_str(text).map_err(|e| ApiError::invalid(format!("{file}: {e}")))?;
    Ok(parsed.waypoints)
}

fn default_jump_ratio() -> f64 {
    20.0
}

fn default_method() -> Method {
    Method::L2
}

/// Tensions along a path (`cdpr trajectory`).
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
pub struct TrajectoryRequest {
    /// The robot.
    pub robot: Robot,
    /// Start pose of the segment (motion-pattern coordinates, m and rad).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub from: Option<Vec<f64>>,
    /// End pose of the segment.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub to: Option<Vec<f64>>,
    /// A polyline instead of `from`/`to` (at least two waypoints).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub waypoints: Option<Vec<Waypoint>>,
    /// The waypoints file's name, shown in error messages.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub waypoints_file: Option<String>,
    /// Number of samples, evenly spaced in s (at least 2; default 101 without `step`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub samples: Option<usize>,
    /// Largest pose distance between samples (m, 1 rad counting as 1 m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub step: Option<f64>,
    /// External wrench w_e (DOF numbers, N and N·m; default zero), added to the robot file's
    /// load.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wrench: Option<Vec<f64>>,
    /// Tension distribution method (default `l2`).
    #[serde(default = "default_method", with = "method_name")]
    #[schemars(with = "String")]
    pub method: Method,
    /// The method's options (SOTDA's, the peers').
    #[serde(default, flatten)]
    pub options: MethodSettings,
    /// A step is flagged as a discontinuity when its jump exceeds this many median jumps
    /// (default 20).
    #[serde(default = "default_jump_ratio")]
    pub jump_ratio: f64,
    /// The time law and inverse dynamics (timed trajectories).
    #[serde(default, flatten)]
    pub timing: TimedSettings,
    /// A CASPR joint-space trajectory (`NAME_trajectories.xml` and an `id`) instead of the path
    /// and the time law: timed by the file, sampled every `time_step` (`cdpr trajectory
    /// --trajectory FILE --trajectory-id ID`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub caspr_trajectory: Option<CasprTrajectorySource>,
    /// Cable model of the flex and sag compensation (default `straight`: none).
    #[serde(default, skip_serializing_if = "CableModelName::is_straight")]
    pub cable_model: CableModelName,
}

/// The JSON of `cdpr trajectory --json`: an untimed profile, or a timed trajectory.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
#[serde(untagged)]
pub enum TrajectoryReport {
    /// Tensions along the path parameter s.
    Path(Box<PathReport>),
    /// A timed trajectory (`time_law`).
    Timed(Box<TimedReport>),
}

/// Tensions along the path parameter s.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct PathReport {
    /// Robot name.
    pub robot: String,
    /// The method's name.
    pub method: String,
    /// SOTDA's ν (null with another method).
    pub nu: Option<f64>,
    /// Path parameter s ∈ [0, 1] of each sample.
    pub s: Vec<f64>,
    /// The pose of each sample (m, rad).
    pub poses: Vec<Vec<f64>>,
    /// Tensions per sample (N), null where infeasible.
    pub tensions: Vec<Option<Vec<f64>>>,
    /// Why a sample is infeasible (null where feasible).
    pub reasons: Vec<Option<String>>,
    /// Feasible samples.
    pub feasible_count: usize,
    /// Per cable, the largest |t_i(k+1) − t_i(k)| between consecutive feasible samples (N).
    pub max_jump: Vec<f64>,
    /// The steps k → k+1 flagged as discontinuities.
    pub discontinuities: Vec<usize>,
    /// Lower tension bounds (N).
    pub t_min: Vec<f64>,
    /// Upper tension bounds (N; null when unbounded).
    pub t_max: Vec<f64>,
    /// The cable model of the compensation (elastic or catenary).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cable_model: Option<String>,
    /// Per sample the unstrained lengths L0 (m) the winches pay out (null where the
    /// sagging-cable statics have no certified equilibrium).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unstrained_lengths: Option<Vec<Option<Vec<f64>>>>,
    /// Per sample the platform-end tensions of the sagging-cable statics (N).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub platform_end_tensions: Option<Vec<Option<Vec<f64>>>>,
    /// Per sample why the sagging-cable statics have no equilibrium (null where they have).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cable_model_reasons: Option<Vec<Option<String>>>,
    /// With a `winch` on every cable: per sample the drum angles (rad) that pay out the
    /// unstrained lengths, L0/ρ with ρ the drum radius or, with `winch.cable_diameter` d, the
    /// single-layer helix's √((r + d/2)² + (d/2π)²) (m/rad); on a multi-layer drum
    /// (`winch.turns_per_layer` N, `winch.cable_length` C, m) Φ(C) − Φ(C − L0), Φ(W) the
    /// angle that winds W (m) onto the empty drum, 2πN rad per layer, layer k at
    /// ρ_k = √((r + d/2 + k d)² + (d/2π)²); null where `unstrained_lengths` is.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub drum_angles: Option<Vec<Option<Vec<f64>>>>,
}

impl TrajectoryRequest {
    /// The segment `from` → `to` with every option at its default.
    pub fn segment(robot: Robot, from: Vec<f64>, to: Vec<f64>) -> Self {
        Self {
            robot,
            from: Some(from),
            to: Some(to),
            waypoints: None,
            waypoints_file: None,
            samples: None,
            step: None,
            wrench: None,
            method: Method::L2,
            options: MethodSettings::default(),
            jump_ratio: default_jump_ratio(),
            timing: TimedSettings::default(),
            caspr_trajectory: None,
            cable_model: CableModelName::Straight,
        }
    }

    /// Whether the trajectory is timed (a time law or a CASPR trajectory).
    pub fn is_timed(&self) -> bool {
        self.timing.is_timed() || self.caspr_trajectory.is_some()
    }

    /// Checks the request (the messages of the command line): the method and its options, the
    /// path, the sampling, the time law.
    pub fn validate(&self) -> Result<(), ApiError> {
        let prepared = self.prepare()?;
        if self.timing.is_timed() {
            self.timing.trajectory(&self.robot, &prepared)?;
        }
        Ok(())
    }

    /// The CASPR trajectory's waypoints (its points), wrenches and times, and its spline.
    #[allow(clippy::type_complexity)]
    fn caspr_points(
        &self,
        source: &CasprTrajectorySource,
        default_wrench: &DVector<f64>,
    ) -> Result<
        (
            Vec<Pose>,
            Vec<DVector<f64>>,
            (String, cdpr_dynamics::JointSpline),
        ),
        ApiError,
    > {
        if self.from.is_some() || self.waypoints.as_ref().is_some_and(|w| !w.is_empty()) {
            return Err(ApiError::invalid(
                "give the path as --from/--to, as --waypoints or as --trajectory, not two of them",
            ));
        }
        self.timing.refuse_with_caspr()?;
        let t = source.read(&self.robot)?;
        let motion = self.robot.robot.motion();
        let poses = t
            .points
            .iter()
            .map(|p| Pose::from_coordinates(motion, &p.q))
            .collect::<Result<Vec<_>, _>>()?;
        let wrenches = vec![default_wrench.clone(); poses.len()];
        Ok((poses, wrenches, (t.id, t.spline)))
    }

    /// Runs the analysis.
    pub fn run(&self) -> Result<TrajectoryReport, ApiError> {
        let prepared = self.prepare()?;
        if self.is_timed() {
            let report = crate::timed::run(&self.robot, &self.timing, self.method, prepared)?;
            return Ok(TrajectoryReport::Timed(Box::new(report)));
        }
        Ok(TrajectoryReport::Path(Box::new(self.run_path(prepared)?)))
    }

    /// The sampling of the untimed path (default 101 samples).
    fn sampling(&self) -> Result<Sampling, ApiError> {
        let sampling = match (self.samples, self.step) {
            (Some(_), Some(_)) => {
                return Err(ApiError::invalid("give --samples or --step, not both"));
            }
            (Some(n), None) => Sampling::Count(n),
            (None, Some(h)) => Sampling::Step(h),
            (None, None) => Sampling::Count(101),
        };
        if let Sampling::Count(n) = sampling
            && n > 10_000_000
        {
            return Err(ApiError::invalid("--samples: at most 10 000 000"));
        }
        Ok(sampling)
    }

    /// Checks everything but the time law and builds the waypoints and the solver.
    pub(crate) fn prepare(&self) -> Result<PreparedPath, ApiError> {
        let robot = &self.robot;
        check_method(robot, self.method)?;
        crate::tension::refuse_sotda_options(
            self.method,
            self.options.nu.is_some(),
            self.options.direction.is_some(),
            false,
        )?;
        let default_wrench = wrench(robot, self.wrench.as_deref())?;
        if let Some(source) = &self.caspr_trajectory {
            let (poses, wrenches, caspr) = self.caspr_points(source, &default_wrench)?;
            if self.samples.is_some() || self.step.is_some() {
                return Err(ApiError::invalid(
                    "a CASPR trajectory is sampled every time_step of its file: leave --samples and --step out",
                ));
            }
            let solver = self.options.solver(robot, self.method)?;
            return Ok(PreparedPath {
                times: Some(caspr.1.waypoint_times()),
                poses,
                wrenches,
                solver,
                caspr: Some(caspr),
            });
        }
        let (poses, wrenches, times) = self.waypoint_poses(&default_wrench)?;
        if !self.timing.is_timed() {
            self.timing.refuse_untimed()?;
        } else if self.samples.is_some() || self.step.is_some() {
            return Err(ApiError::invalid(
                "a timed trajectory is sampled every --dt s: leave --samples and --step out",
            ));
        }
        let sampling = self.sampling()?;
        if !(self.jump_ratio.is_finite() && self.jump_ratio > 1.0) {
            return Err(ApiError::invalid(
                "--jump-ratio must be a finite number > 1",
            ));
        }
        let motion = robot.robot.motion();
        Path::new(motion, poses.clone())?.sample(sampling)?;
        WaypointWrenches::new(motion, &poses, wrenches.clone())?;
        let solver = self.options.solver(robot, self.method)?;
        Ok(PreparedPath {
            poses,
            wrenches,
            times,
            solver,
            caspr: None,
        })
    }

    /// The waypoint poses, their wrenches (w_e) and times.
    #[allow(clippy::type_complexity)]
    fn waypoint_poses(
        &self,
        default_wrench: &DVector<f64>,
    ) -> Result<(Vec<Pose>, Vec<DVector<f64>>, Option<Vec<f64>>), ApiError> {
        let robot = &self.robot;
        match (&self.waypoints, &self.from) {
            (Some(w), Some(_)) if !w.is_empty() => Err(ApiError::invalid(
                "give the path as --from/--to or as --waypoints, not both",
            )),
            (Some(w), _) => waypoint_list(robot, w, self.waypoints_file.as_deref(), default_wrench),
            (None, Some(from)) => {
                let to = self
                    .to
                    .as_ref()
                    .ok_or(ApiError::invalid("--from needs --to"))?;
                let ends = vec![pose(robot, from)?, pose(robot, to)?];
                Ok((ends, vec![default_wrench.clone(); 2], None))
            }
            (None, None) => Err(ApiError::invalid(
                "give the path: --from POSE --to POSE, or --waypoints FILE",
            )),
        }
    }

    /// The untimed profile.
    fn run_path(&self, mut prepared: PreparedPath) -> Result<PathReport, ApiError> {
        let robot = &self.robot;
        let motion = robot.robot.motion();
        let poses = &prepared.poses;
        let samples = Path::new(motion, poses.clone())?.sample(self.sampling()?)?;
        let way = WaypointWrenches::new(motion, poses, prepared.wrenches.clone())?;
        // Weight and passive springs at each sample (checked here: a spring of zero length is
        // an error naming the sample, not a panic in the profile).
        for sample in &samples {
            robot
                .load_wrench(&sample.pose)
                .map_err(|e| ApiError::invalid(format!("at s = {}: {e}", sample.s)))?;
        }
        let load = |sample: &PathSample| -> DVector<f64> {
            way.at(sample.s)
                + robot
                    .load_wrench(&sample.pose)
                    .expect("checked at every sample above")
        };
        let profile = tension_profile(
            &robot.robot,
            &samples,
            &robot.bounds,
            &mut prepared.solver,
            robot.axial_stiffness.as_deref(),
            load,
        )?;
        let mut report = PathReport {
            robot: robot.name.clone(),
            method: self.method.name().to_string(),
            nu: self.options.nu_of(self.method),
            discontinuities: profile.discontinuities(self.jump_ratio),
            feasible_count: profile.feasible_count(),
            poses: samples.iter().map(|p| p.pose.coordinates(motion)).collect(),
            tensions: profile
                .tensions
                .iter()
                .map(|t| t.as_ref().map(|t| t.as_slice().to_vec()))
                .collect(),
            s: profile.s,
            reasons: profile.reasons,
            max_jump: profile.max_jump,
            t_min: robot.bounds.min().as_slice().to_vec(),
            t_max: robot.bounds.max().as_slice().to_vec(),
            cable_model: None,
            unstrained_lengths: None,
            platform_end_tensions: None,
            cable_model_reasons: None,
            drum_angles: None,
        };
        if let Some(cables) = catenaries(robot, self.cable_model.model())? {
            let at: Vec<Pose> = samples.iter().map(|p| p.pose).collect();
            let c = compensation(robot, &cables, self.method, &at, |k| load(&samples[k]))?;
            report.cable_model = Some(self.cable_model.model().name().to_string());
            report.unstrained_lengths = Some(c.unstrained_lengths);
            report.platform_end_tensions = Some(c.platform_end_tensions);
            report.cable_model_reasons = Some(c.reasons);
            report.drum_angles = c.drum_angles;
        }
        Ok(report)
    }
}

/// The poses, wrenches and times of a waypoint list (errors name the file and the waypoint).
#[allow(clippy::type_complexity)]
fn waypoint_list(
    robot: &RobotDescription,
    waypoints: &[Waypoint],
    file: Option<&str>,
    default_wrench: &DVector<f64>,
) -> Result<(Vec<Pose>, Vec<DVector<f64>>, Option<Vec<f64>>), ApiError> {
    let prefix = file.map_or(String::new(), |f| format!("{f}: "));
    if waypoints.len() < 2 {
        return Err(ApiError::invalid(format!(
            "{prefix}needs at least two [[waypoints]]"
        )));
    }
    let times = waypoint_times(waypoints, &prefix)?;
    let (mut poses, mut wrenches) = (Vec::new(), Vec::new());
    for (k, w) in waypoints.iter().enumerate() {
        poses.push(
            pose(robot, &w.pose)
                .map_err(|e| ApiError::invalid(format!("{prefix}waypoints[{k}].pose: {e}")))?,
        );
        wrenches.push(match &w.wrench {
            Some(v) => wrench(robot, Some(v))
                .map_err(|e| ApiError::invalid(format!("{prefix}waypoints[{k}].wrench: {e}")))?,
            None => default_wrench.clone(),
        });
    }
    Ok((poses, wrenches, times))
}

/// The `time` of every waypoint, or of none (`None`); an error naming the first waypoint
/// without one when only some have it.
fn waypoint_times(waypoints: &[Waypoint], prefix: &str) -> Result<Option<Vec<f64>>, ApiError> {
    let given: Vec<Option<f64>> = waypoints.iter().map(|w| w.time).collect();
    if given.iter().all(Option::is_none) {
        return Ok(None);
    }
    match given.iter().position(Option::is_none) {
        Some(k) => Err(ApiError::invalid(format!(
            "{prefix}waypoints[{k}] has no `time` (give every waypoint a time, or none)"
        ))),
        None => Ok(Some(given.into_iter().flatten().collect())),
    }
}
