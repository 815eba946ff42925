//! # Elastic and sagging cables at one pose (``cable_model=``)
//!
//! ``inverse_kinematics``, ``tensions`` and ``forward_kinematics`` with
//! ``cable_model="elastic"`` or ``"catenary"`` (issue 29): the requests of
//! `cdpr_api::sagging` the command line builds for ``--cable-model`` (Irvine's elastic
//! catenary; statics with sagging cables, Kozak, Zhou & Wang 2006; elasto-geometric forward
//! kinematics, Pott 2018, §6.4), so the answers are the command's JSON.

use crate::arrays::to_numpy;
use crate::model::Robot;
use crate::requests::{api_error, api_robot, matrix};
use crate::value_error;
use cdpr_api::cable_model::CableModelName;
use cdpr_api::sagging::{
    ElastoGeometricRequest, SaggingCablesReport, SaggingKinematicsRequest, SaggingTensionRequest,
};
use numpy::PyArrayDyn;
use pyo3::prelude::*;

/// The answer of a ``cable_model=`` call at one pose.
///
/// Per cable (n,): ``unstrained_lengths`` (m), ``chord_lengths`` (m), ``frame_end_tensions``
/// and ``platform_end_tensions`` (N), ``max_sag`` (m, below the chord), ``angle_to_chord``
/// (rad, at the platform); ``wrench_matrix`` (DOF, n): the unit forces of the cables at the
/// platform. ``tensions`` (N, platform end), ``feasible``, ``residual``, ``iterations`` and
/// ``reason`` for ``tensions``; ``pose`` (m, rad), ``status``, ``slack_cables`` (1-based) for
/// ``forward_kinematics``; ``external_wrench`` (N, N·m) for both. Fields that do not apply (or
/// an infeasible pose's per-cable arrays) are None.
#[pyclass(module = "cdpr", frozen, get_all)]
pub struct SaggingResult {
    pub cable_model: String,
    pub pose: Option<Vec<f64>>,
    pub feasible: bool,
    pub tensions: Option<Py<PyArrayDyn<f64>>>,
    pub residual: Option<f64>,
    pub iterations: Option<usize>,
    pub reason: Option<String>,
    pub status: Option<String>,
    pub slack_cables: Option<Vec<usize>>,
    pub external_wrench: Option<Py<PyArrayDyn<f64>>>,
    pub wrench_matrix: Option<Py<PyArrayDyn<f64>>>,
    pub unstrained_lengths: Option<Py<PyArrayDyn<f64>>>,
    pub chord_lengths: Option<Py<PyArrayDyn<f64>>>,
    pub frame_end_tensions: Option<Py<PyArrayDyn<f64>>>,
    pub platform_end_tensions: Option<Py<PyArrayDyn<f64>>>,
    pub max_sag: Option<Py<PyArrayDyn<f64>>>,
    pub angle_to_chord: Option<Py<PyArrayDyn<f64>>>,
}

#[pymethods]
impl SaggingResult {
    fn __repr__(&self) -> String {
        format!(
            "SaggingResult(cable_model={:?}, feasible={}, status={:?})",
            self.cable_model, self.feasible, self.status
        )
    }
}

/// ``cable_model=``: ``None`` for ``"straight"``, else the model; a ``ValueError`` names the
/// keyword otherwise.
pub fn model_name(name: &str) -> PyResult<Option<CableModelName>> {
    match name {
        "straight" => Ok(None),
        "elastic" => Ok(Some(CableModelName::Elastic)),
        "catenary" => Ok(Some(CableModelName::Catenary)),
        _ => Err(value_error(format!(
            "cable_model: unknown cable model `{name}` (expected straight, elastic or catenary)"
        ))),
    }
}

fn vector(py: Python<'_>, v: &[f64]) -> Py<PyArrayDyn<f64>> {
    to_numpy(py, &[v.len()], v.to_vec()).unbind()
}

fn empty(model: CableModelName) -> SaggingResult {
    SaggingResult {
        cable_model: model.model().name().to_string(),
        pose: None,
        feasible: true,
        tensions: None,
        residual: None,
        iterations: None,
        reason: None,
        status: None,
        slack_cables: None,
        external_wrench: None,
        wrench_matrix: None,
        unstrained_lengths: None,
        chord_lengths: None,
        frame_end_tensions: None,
        platform_end_tensions: None,
        max_sag: None,
        angle_to_chord: None,
    }
}

/// Fills the per-cable arrays of `r` from a report.
fn with_cables(py: Python<'_>, mut r: SaggingResult, c: &SaggingCablesReport) -> SaggingResult {
    r.unstrained_lengths = Some(vector(py, &c.unstrained_lengths));
    r.chord_lengths = Some(vector(py, &c.chord_lengths));
    r.frame_end_tensions = Some(vector(py, &c.frame_end_tensions));
    r.platform_end_tensions = Some(vector(py, &c.platform_end_tensions));
    r.max_sag = Some(vector(py, &c.max_sag));
    r.angle_to_chord = Some(vector(py, &c.angle_to_chord));
    r
}

/// One pose as the request takes it: a ``(DOF,)`` sequence.
fn one(obj: &Bound<'_, PyAny>, what: &str, hint: &str) -> PyResult<Vec<f64>> {
    obj.extract::<Vec<f64>>().map_err(|_| {
        value_error(format!(
            "{what}: cable_model elastic or catenary takes one {hint}, not a batch"
        ))
    })
}

/// ``inverse_kinematics(pose, cable_model=…, tensions=…)``.
pub fn kinematics(
    robot: &Robot,
    py: Python<'_>,
    pose: &Bound<'_, PyAny>,
    model: CableModelName,
    tensions: Option<Vec<f64>>,
) -> PyResult<SaggingResult> {
    let n = robot.geometry().cable_count();
    let tensions = tensions.ok_or_else(|| {
        value_error(format!(
            "tensions: cable_model={:?} needs the {n} platform-end tensions (N)",
            model.model().name()
        ))
    })?;
    let request = SaggingKinematicsRequest {
        robot: api_robot(robot),
        pose: one(pose, "poses", "pose (DOF,)")?,
        cable_model: model,
        tensions,
    };
    let r = crate::parallel(py, || request.run().map_err(api_error))?;
    let mut out = with_cables(py, empty(model), &r.cables);
    out.wrench_matrix = Some(matrix(py, &r.wrench_matrix, n).unbind());
    out.pose = Some(r.pose);
    Ok(out)
}

/// ``tensions(pose, wrench, method, cable_model=…)``.
pub fn tension(
    robot: &Robot,
    py: Python<'_>,
    pose: &Bound<'_, PyAny>,
    wrench: Option<&Bound<'_, PyAny>>,
    method: cdpr_tension::Method,
    model: CableModelName,
) -> PyResult<SaggingResult> {
    let request = SaggingTensionRequest {
        robot: api_robot(robot),
        pose: one(pose, "poses", "pose (DOF,)")?,
        wrench: wrench
            .map(|w| one(w, "wrenches", "wrench (DOF,)"))
            .transpose()?,
        method,
        cable_model: model,
    };
    let r = crate::parallel(py, || request.run().map_err(api_error))?;
    let n = robot.geometry().cable_count();
    let mut out = match &r.cables {
        Some(c) => with_cables(py, empty(model), c),
        None => empty(model),
    };
    out.pose = Some(r.pose);
    out.feasible = r.feasible;
    out.tensions = r.tensions.as_deref().map(|t| vector(py, t));
    out.residual = r.residual;
    out.iterations = r.iterations;
    out.reason = r.reason;
    out.external_wrench = Some(vector(py, &r.external_wrench));
    out.wrench_matrix = r
        .wrench_matrix
        .as_deref()
        .map(|w| matrix(py, w, n).unbind());
    Ok(out)
}

/// ``forward_kinematics(unstrained_lengths, guess, cable_model=…, wrench=…)``.
pub fn forward(
    robot: &Robot,
    py: Python<'_>,
    lengths: &Bound<'_, PyAny>,
    guess: Option<&Bound<'_, PyAny>>,
    wrench: Option<Vec<f64>>,
    model: CableModelName,
) -> PyResult<SaggingResult> {
    let request = ElastoGeometricRequest {
        robot: api_robot(robot),
        unstrained_lengths: one(lengths, "lengths", "set of unstrained lengths (n,)")?,
        cable_model: model,
        wrench,
        guess: guess.map(|g| one(g, "guess", "pose (DOF,)")).transpose()?,
    };
    let r = crate::parallel(py, || request.run().map_err(api_error))?;
    let mut out = with_cables(py, empty(model), &r.cables);
    out.feasible = r.status == "equilibrium";
    out.pose = Some(r.pose);
    out.tensions = Some(vector(py, &r.tensions));
    out.residual = Some(r.residual);
    out.iterations = Some(r.iterations);
    out.status = Some(r.status);
    out.slack_cables = Some(r.slack_cables);
    out.external_wrench = Some(vector(py, &r.external_wrench));
    Ok(out)
}
