//! # Tension profiles along a path, timed trajectories, forward dynamics
//!
//! The `cdpr trajectory` and `cdpr simulate` commands from Python, through their requests
//! (`cdpr_api::trajectory::TrajectoryRequest`, `cdpr_api::simulate::SimulateRequest`): a
//! polyline of waypoints sampled evenly in the path parameter s, or timed by a time law and
//! sampled every `dt` s (with inverse dynamics and the drive train), and the platform's motion
//! under given tensions. The answers are the command line's JSON, as numpy arrays.
//!
//! ## References
//! - docs/architecture.md, "Requests and reports" (issue 25); docs/algorithms.md (issue 28).

use crate::arrays::{FloatArray, Rows, shape_string, to_numpy};
use crate::model::Robot;
use crate::requests::{api_error, api_robot, matrix};
use crate::tension::{parse_method, sotda_settings};
use crate::value_error;
use cdpr_api::MethodSettings;
use cdpr_api::timed::{TimedReport, TimedSettings};
use cdpr_api::trajectory::{PathReport, TrajectoryReport, TrajectoryRequest, Waypoint};
use cdpr_tension::Method;
use numpy::PyArrayDyn;
use pyo3::prelude::*;

/// Tensions along a path.
///
/// ``s`` (S,): path parameter of each sample in [0, 1]; ``poses`` (S, DOF); ``tensions``
/// (S, n) in N, NaN where infeasible; ``feasible`` (S,) bool; ``reason``: list of S strings
/// (None where feasible); ``max_jump`` (n,): per cable the largest |t_i(k+1) − t_i(k)| over
/// consecutive feasible samples (N); ``discontinuities``: the steps k → k+1 whose jump exceeds
/// ``jump_ratio`` median jumps; ``feasible_count``; ``method``. With ``cable_model`` elastic
/// or catenary: ``cable_model``, ``unstrained_lengths`` (S, n) in m and
/// ``platform_end_tensions`` (S, n) in N (NaN where the sagging statics have no equilibrium),
/// ``cable_model_reasons``, and with a winch on every cable ``drum_angles`` (S, n) in rad;
/// else None.
#[pyclass(module = "cdpr", frozen, get_all)]
pub struct TrajectoryResult {
    pub s: Py<PyArrayDyn<f64>>,
    pub poses: Py<PyArrayDyn<f64>>,
    pub tensions: Py<PyArrayDyn<f64>>,
    pub feasible: Py<PyArrayDyn<bool>>,
    pub reason: Vec<Option<String>>,
    pub max_jump: Py<PyArrayDyn<f64>>,
    pub discontinuities: Vec<usize>,
    pub feasible_count: usize,
    pub method: String,
    pub cable_model: Option<String>,
    pub unstrained_lengths: Option<Py<PyArrayDyn<f64>>>,
    pub platform_end_tensions: Option<Py<PyArrayDyn<f64>>>,
    pub cable_model_reasons: Option<Vec<Option<String>>>,
    pub drum_angles: Option<Py<PyArrayDyn<f64>>>,
}

#[pymethods]
impl TrajectoryResult {
    fn __repr__(&self) -> String {
        format!(
            "TrajectoryResult(method={:?}, samples={}, feasible_count={}, discontinuities={:?})",
            self.method,
            self.reason.len(),
            self.feasible_count,
            self.discontinuities
        )
    }
}

/// A timed trajectory (``time_law=``), the JSON of ``cdpr trajectory --time-law … --json``.
///
/// ``t`` (S,) in s; ``poses`` (S, DOF); ``velocity``, ``acceleration`` (S, DOF): the twist
/// [v (m/s); ω (rad/s)] and its rate; ``cable_lengths`` (m), ``cable_speeds`` (l̇ = −Wᵀẋ, m/s),
/// ``cable_accelerations`` (m/s²), ``tensions`` (N, NaN where infeasible), all (S, n);
/// ``feasible``, ``reason``, ``feasible_count``; ``inertial_wrench`` (S, DOF; M ẍ + b in N and
/// N·m) with ``dynamics``, else None; with a winch on every cable ``motor_speeds`` (rad/s),
/// ``motor_torques`` (N·m, NaN where infeasible), ``motor_powers`` (W), all (S, n),
/// ``motors_within_limits`` and ``motor_limit_violations``, else None; ``waypoint_times`` (s),
/// ``duration`` (s), ``dt`` (s), ``time_law``, ``method``, ``dynamics``.
#[pyclass(module = "cdpr", frozen, get_all)]
pub struct TimedTrajectoryResult {
    pub t: Py<PyArrayDyn<f64>>,
    pub poses: Py<PyArrayDyn<f64>>,
    pub velocity: Py<PyArrayDyn<f64>>,
    pub acceleration: Py<PyArrayDyn<f64>>,
    pub cable_lengths: Py<PyArrayDyn<f64>>,
    pub cable_speeds: Py<PyArrayDyn<f64>>,
    pub cable_accelerations: Py<PyArrayDyn<f64>>,
    pub tensions: Py<PyArrayDyn<f64>>,
    pub feasible: Py<PyArrayDyn<bool>>,
    pub reason: Vec<Option<String>>,
    pub feasible_count: usize,
    pub inertial_wrench: Option<Py<PyArrayDyn<f64>>>,
    pub motor_speeds: Option<Py<PyArrayDyn<f64>>>,
    pub motor_torques: Option<Py<PyArrayDyn<f64>>>,
    pub motor_powers: Option<Py<PyArrayDyn<f64>>>,
    pub motors_within_limits: Option<bool>,
    pub motor_limit_violations: Option<Vec<String>>,
    pub waypoint_times: Vec<f64>,
    pub duration: f64,
    pub dt: f64,
    pub time_law: String,
    pub method: String,
    pub dynamics: bool,
}

#[pymethods]
impl TimedTrajectoryResult {
    fn __repr__(&self) -> String {
        format!(
            "TimedTrajectoryResult(time_law={:?}, method={:?}, dynamics={}, samples={}, \
             feasible_count={}, duration={})",
            self.time_law,
            self.method,
            self.dynamics,
            self.reason.len(),
            self.feasible_count,
            self.duration
        )
    }
}

/// The options of a tension method along a path (``method=`` and SOTDA's).
pub struct MethodArgs {
    /// The method's name.
    pub method: String,
    /// SOTDA's direction.
    pub direction: Option<Vec<f64>>,
    /// SOTDA's ν.
    pub nu: f64,
    /// SOTDA's search.
    pub sotda_search: String,
    /// The peers' options (``interior``, ``alternating``, ``p``, ``alpha``), refused with
    /// another method as ``cdpr trajectory`` refuses them.
    pub peer: crate::tension::PeerOptions,
}

/// The path of ``trajectory``: waypoints, their wrenches (and times), the sampling.
pub struct PathArgs<'a, 'py> {
    /// (K ≥ 2, DOF) waypoints (none with a CASPR trajectory).
    pub waypoints: Option<&'a Bound<'py, PyAny>>,
    /// A CASPR joint-space trajectory instead of the waypoints and the time law.
    pub caspr: Option<cdpr_api::timed::CasprTrajectorySource>,
    /// (DOF,) or (K, DOF) external wrenches.
    pub wrenches: Option<&'a Bound<'py, PyAny>>,
    /// (K,) waypoint times (s).
    pub times: Option<Vec<f64>>,
    /// Samples evenly in s.
    pub samples: Option<usize>,
    /// Largest pose distance between samples.
    pub step: Option<f64>,
    /// The discontinuity threshold.
    pub jump_ratio: f64,
}

/// Runs `cdpr trajectory`'s request: a [`TrajectoryResult`] without a time law, else a
/// [`TimedTrajectoryResult`].
pub fn trajectory(
    robot: &Robot,
    py: Python<'_>,
    path: PathArgs,
    method: MethodArgs,
    (timing, cable_model): (TimedSettings, cdpr_api::cable_model::CableModelName),
) -> PyResult<Py<PyAny>> {
    let mut request = TrajectoryRequest::segment(api_robot(robot), Vec::new(), Vec::new());
    request.from = None;
    request.to = None;
    match (path.waypoints, &path.caspr) {
        (Some(_), Some(_)) => {
            return Err(value_error(
                "give waypoints or caspr_trajectory, not both (the CASPR file gives the path and its times)",
            ));
        }
        (None, None) => {
            return Err(value_error(
                "waypoints: a path needs at least two poses, shape (K ≥ 2, DOF), or caspr_trajectory=",
            ));
        }
        (Some(w), None) => request.waypoints = Some(waypoint_list(robot, w, &path)?),
        (None, Some(source)) => request.caspr_trajectory = Some(source.clone()),
    }
    request.samples = path.samples;
    request.step = path.step;
    request.jump_ratio = path.jump_ratio;
    request.method = parse_method(&method.method)?;
    request.options = method_settings(request.method, method)?;
    request.timing = timing;
    request.cable_model = cable_model;
    if let (Some(_), Some(_)) = (path.samples, path.step) {
        return Err(value_error("give samples or step, not both"));
    }
    if !(path.jump_ratio.is_finite() && path.jump_ratio > 1.0) {
        return Err(value_error("jump_ratio must be a finite number > 1"));
    }
    let n = robot.geometry().cable_count();
    let report = crate::parallel(py, || request.run().map_err(api_error))?;
    Ok(match report {
        TrajectoryReport::Path(r) => Py::new(py, path_result(py, &r, n))?.into_any(),
        TrajectoryReport::Timed(r) => Py::new(py, timed_result(py, &r, n))?.into_any(),
    })
}

/// SOTDA's options, checked as :meth:`tensions` checks them, kept only for SOTDA (the other
/// methods ignore them, as before the request).
fn method_settings(method: Method, args: MethodArgs) -> PyResult<MethodSettings> {
    sotda_settings(args.direction.clone(), args.nu, &args.sotda_search)?;
    let sotda = method == Method::Sotda;
    Ok(MethodSettings {
        direction: args.direction.filter(|_| sotda),
        nu: sotda.then_some(args.nu),
        sotda_search: match args.sotda_search.as_str() {
            "vertices" => cdpr_api::SotdaSearch::Vertices,
            "full" => cdpr_api::SotdaSearch::Full,
            _ => cdpr_api::SotdaSearch::Corners,
        },
        peer: args.peer.to_api(),
    })
}

/// The waypoints of the request: poses, per-waypoint wrenches and times.
fn waypoint_list(
    robot: &Robot,
    waypoints: &Bound<'_, PyAny>,
    path: &PathArgs,
) -> PyResult<Vec<Waypoint>> {
    let dof = robot.geometry().dof();
    let rows = Rows::new(waypoints, dof, "waypoints", robot.pose_hint())?;
    if rows.single || rows.count < 2 {
        return Err(value_error(format!(
            "waypoints: a path needs at least two poses, shape (K ≥ 2, {dof})"
        )));
    }
    let k_way = rows.count;
    let wrenches: Vec<Vec<f64>> = match path.wrenches {
        None => vec![vec![0.0; dof]; k_way],
        Some(obj) => {
            let a = FloatArray::new(obj, "wrenches")?;
            a.check_finite("wrenches")?;
            let d = a.data();
            match a.shape() {
                [m] if *m == dof => vec![d.to_vec(); k_way],
                [k, m] if *m == dof && *k == k_way => d.chunks(dof).map(<[f64]>::to_vec).collect(),
                s => {
                    return Err(value_error(format!(
                        "wrenches: expected shape ({dof},) or ({k_way}, {dof}) (one external \
                         wrench per waypoint, interpolated in s), got {}",
                        shape_string(s)
                    )));
                }
            }
        }
    };
    if let Some(t) = &path.times
        && t.len() != k_way
    {
        return Err(value_error(format!(
            "times: {} numbers for {k_way} waypoints (one time per waypoint, s)",
            t.len()
        )));
    }
    Ok(rows
        .array
        .data()
        .chunks(dof)
        .zip(wrenches)
        .enumerate()
        .map(|(k, (q, w))| Waypoint {
            pose: q.to_vec(),
            wrench: Some(w),
            time: path.times.as_ref().map(|t| t[k]),
        })
        .collect())
}

/// Rows with a NaN row where a sample has none.
fn nan_rows(rows: &[Option<Vec<f64>>], width: usize) -> Vec<f64> {
    rows.iter()
        .flat_map(|r| r.clone().unwrap_or_else(|| vec![f64::NAN; width]))
        .collect()
}

fn nan_matrix<'py>(
    py: Python<'py>,
    rows: &[Option<Vec<f64>>],
    width: usize,
) -> Py<PyArrayDyn<f64>> {
    to_numpy(py, &[rows.len(), width], nan_rows(rows, width)).unbind()
}

fn path_result(py: Python<'_>, r: &PathReport, n: usize) -> TrajectoryResult {
    let count = r.s.len();
    let dof = r.poses.first().map_or(0, Vec::len);
    TrajectoryResult {
        s: to_numpy(py, &[count], r.s.clone()).unbind(),
        poses: matrix(py, &r.poses, dof).unbind(),
        tensions: nan_matrix(py, &r.tensions, n),
        feasible: feasible(py, &r.tensions),
        reason: r.reasons.clone(),
        max_jump: to_numpy(py, &[n], r.max_jump.clone()).unbind(),
        discontinuities: r.discontinuities.clone(),
        feasible_count: r.feasible_count,
        method: r.method.clone(),
        cable_model: r.cable_model.clone(),
        unstrained_lengths: r.unstrained_lengths.as_ref().map(|l| nan_matrix(py, l, n)),
        platform_end_tensions: r
            .platform_end_tensions
            .as_ref()
            .map(|t| nan_matrix(py, t, n)),
        cable_model_reasons: r.cable_model_reasons.clone(),
        drum_angles: r.drum_angles.as_ref().map(|a| nan_matrix(py, a, n)),
    }
}

fn feasible(py: Python<'_>, tensions: &[Option<Vec<f64>>]) -> Py<PyArrayDyn<bool>> {
    let f: Vec<bool> = tensions.iter().map(Option::is_some).collect();
    to_numpy(py, &[f.len()], f).unbind()
}

fn timed_result(py: Python<'_>, r: &TimedReport, n: usize) -> TimedTrajectoryResult {
    let dof = r.poses.first().map_or(0, Vec::len);
    let d = r.drive_train.as_ref();
    TimedTrajectoryResult {
        t: to_numpy(py, &[r.t.len()], r.t.clone()).unbind(),
        poses: matrix(py, &r.poses, dof).unbind(),
        velocity: matrix(py, &r.velocity, dof).unbind(),
        acceleration: matrix(py, &r.acceleration, dof).unbind(),
        cable_lengths: matrix(py, &r.cable_lengths, n).unbind(),
        cable_speeds: matrix(py, &r.cable_speeds, n).unbind(),
        cable_accelerations: matrix(py, &r.cable_accelerations, n).unbind(),
        tensions: nan_matrix(py, &r.tensions, n),
        feasible: feasible(py, &r.tensions),
        reason: r.reasons.clone(),
        feasible_count: r.feasible_count,
        inertial_wrench: r
            .inertial_wrench
            .as_ref()
            .map(|w| matrix(py, w, dof).unbind()),
        motor_speeds: d.map(|d| matrix(py, &d.motor_speeds, n).unbind()),
        motor_torques: d.map(|d| nan_matrix(py, &d.motor_torques, n)),
        motor_powers: d.map(|d| nan_matrix(py, &d.motor_powers, n)),
        motors_within_limits: d.and_then(|d| d.motors_within_limits),
        motor_limit_violations: d.map(|d| d.motor_limit_violations.clone()),
        waypoint_times: r.waypoint_times.clone(),
        duration: r.duration,
        dt: r.dt,
        time_law: r.time_law.clone(),
        method: r.method.clone(),
        dynamics: r.dynamics,
    }
}
