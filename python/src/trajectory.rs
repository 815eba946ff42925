//! # Tension profiles along a path
//!
//! The `cdpr trajectory` command from Python: a polyline of waypoints sampled evenly in the path
//! parameter s (∝ the pose distance √(‖Δp‖² + θ²)), tensions at every sample
//! ([`cdpr_tension::profile::tension_profile`]) under the external wrench interpolated linearly
//! in s between waypoints plus the platform's gravity, and the continuity report (largest jump
//! per cable, flagged discontinuities).

use crate::arrays::{FloatArray, Rows, shape_string, to_numpy};
use crate::model::Robot;
use crate::tension::{parse_method, solver, sotda_settings};
use crate::value_error;
use cdpr_kinematics::{Path, PathSample, Pose, Sampling};
use cdpr_tension::profile::{WaypointWrenches, tension_profile};
use nalgebra::DVector;
use numpy::PyArrayDyn;
use pyo3::prelude::*;

/// Tensions along a path.
///
/// ``s`` (S,): path parameter of each sample in [0, 1]; ``poses`` (S, DOF); ``tensions``
/// (S, n) in N, NaN where infeasible; ``feasible`` (S,) bool; ``reason``: list of S strings
/// (None where feasible); ``max_jump`` (n,): per cable the largest |t_i(k+1) − t_i(k)| over
/// consecutive feasible samples (N); ``discontinuities``: the steps k → k+1 whose jump exceeds
/// ``jump_ratio`` median jumps; ``feasible_count``; ``method``.
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

#[allow(clippy::too_many_arguments)]
pub fn trajectory(
    robot: &Robot,
    py: Python<'_>,
    waypoints: &Bound<'_, PyAny>,
    samples: Option<usize>,
    step: Option<f64>,
    wrenches: Option<&Bound<'_, PyAny>>,
    method: &str,
    direction: Option<Vec<f64>>,
    nu: f64,
    sotda_search: &str,
    jump_ratio: f64,
) -> PyResult<TrajectoryResult> {
    let geo = robot.geometry();
    let motion = geo.motion();
    let (dof, n) = (geo.dof(), geo.cable_count());
    let rows = Rows::new(waypoints, dof, "waypoints", robot.pose_hint())?;
    if rows.single || rows.count < 2 {
        return Err(value_error(format!(
            "waypoints: a path needs at least two poses, shape (K ≥ 2, {dof})"
        )));
    }
    let k_way = rows.count;
    let data = rows.array.data();
    let poses = data
        .chunks(dof)
        .enumerate()
        .map(|(k, q)| {
            Pose::from_coordinates(motion, q)
                .map_err(|e| value_error(format!("waypoints[{k}]: {e}")))
        })
        .collect::<PyResult<Vec<_>>>()?;
    let wrench_rows: Vec<DVector<f64>> = match wrenches {
        None => vec![DVector::zeros(dof); k_way],
        Some(obj) => {
            let a = FloatArray::new(obj, "wrenches")?;
            a.check_finite("wrenches")?;
            let d = a.data();
            match a.shape() {
                [m] if *m == dof => vec![DVector::from_column_slice(&d); k_way],
                [k, m] if *m == dof && *k == k_way => {
                    d.chunks(dof).map(DVector::from_column_slice).collect()
                }
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
    let sampling = match (samples, step) {
        (Some(_), Some(_)) => return Err(value_error("give samples or step, not both")),
        (Some(c), None) if c > 10_000_000 => {
            return Err(value_error("samples: at most 10 000 000"));
        }
        (Some(c), None) => Sampling::Count(c),
        (None, Some(h)) => Sampling::Step(h),
        (None, None) => Sampling::Count(101),
    };
    if !(jump_ratio.is_finite() && jump_ratio > 1.0) {
        return Err(value_error("jump_ratio must be a finite number > 1"));
    }
    let method = parse_method(method)?;
    let mut solver = solver(robot, method, sotda_settings(direction, nu, sotda_search)?)?;
    let desc = &robot.desc;
    let (samples, profile) = crate::parallel(py, || {
        let path = Path::new(motion, poses.clone()).map_err(value_error)?;
        let samples = path.sample(sampling).map_err(value_error)?;
        let way =
            WaypointWrenches::new(motion, &poses, wrench_rows.clone()).map_err(value_error)?;
        // Weight and passive springs at each sample, checked before the profile (a spring of
        // zero length is an error naming the sample).
        for sample in &samples {
            desc.load_wrench(&sample.pose)
                .map_err(|e| value_error(format!("at s = {}: {e}", sample.s)))?;
        }
        let profile = tension_profile(
            geo,
            &samples,
            &desc.bounds,
            &mut solver,
            desc.axial_stiffness.as_deref(),
            |sample: &PathSample| {
                way.at(sample.s)
                    + desc
                        .load_wrench(&sample.pose)
                        .expect("checked at every sample above")
            },
        )
        .map_err(value_error)?;
        Ok((samples, profile))
    })?;
    let count = samples.len();
    let q: Vec<f64> = samples
        .iter()
        .flat_map(|p| p.pose.coordinates(motion))
        .collect();
    let t: Vec<f64> = profile
        .tensions
        .iter()
        .flat_map(|t| match t {
            Some(t) => t.as_slice().to_vec(),
            None => vec![f64::NAN; n],
        })
        .collect();
    let feasible: Vec<bool> = profile.tensions.iter().map(Option::is_some).collect();
    Ok(TrajectoryResult {
        discontinuities: profile.discontinuities(jump_ratio),
        feasible_count: profile.feasible_count(),
        s: to_numpy(py, &[count], profile.s).unbind(),
        poses: to_numpy(py, &[count, dof], q).unbind(),
        tensions: to_numpy(py, &[count, n], t).unbind(),
        feasible: to_numpy(py, &[count], feasible).unbind(),
        reason: profile.reasons,
        max_jump: to_numpy(py, &[n], profile.max_jump).unbind(),
        method: method.name().into(),
    })
}
