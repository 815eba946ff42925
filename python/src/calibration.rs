//! # Calibration from cable-length readings
//!
//! `cdpr.calibrate(robot, samples, known_poses=…, unknowns=…)`: the `cdpr-calibration` crate
//! (known poses: per-cable least squares; unknown poses: self-calibration with the gauge fixed,
//! Borgstrom et al. 2009; Miermeister & Pott 2012), its report as a dict with the field names
//! of `cdpr calibrate --json`: the same `cdpr_api::CalibrationRequest` as the command line,
//! with the samples as arrays.

use crate::arrays::{FloatArray, shape_string};
use crate::model::Robot;
use crate::requests::{api_error, api_robot};
use crate::value_error;
use cdpr_api::{CalibrationReport, SamplesSource};
use cdpr_calibration::Unknowns;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Calibrates ``robot`` from ``samples`` (``(k, n)`` readings ρ, true length = gain · ρ +
/// offset): from ``known_poses`` (``(k, DOF)``) when given, else by self-calibration (unknown
/// poses). ``unknowns``: comma-separated ``frame``, ``platform``, ``offsets``, ``gains``.
/// ``relative``: readings count from ``reference`` (a pose, default the origin). A robot file
/// with the cables' ``offset`` and ``gain`` keys (written by ``cdpr calibrate -o``) gives the
/// starting offsets and gains (held when not unknowns); otherwise 0 and 1. Returns a dict
/// with the fields of ``cdpr calibrate --json`` (``frame``, ``platform``, ``offsets``,
/// ``gains``, ``poses``, ``residual_rms``, ``sigma``, ``identifiable``, ``rank_deficiency``,
/// ``condition_number``, ``samples_needed``, ``reason``, …; ``None`` for undefined values).
#[pyfunction]
#[pyo3(signature = (robot, samples, known_poses=None, *, unknowns="frame,offsets", relative=false, reference=None))]
pub fn calibrate<'py>(
    py: Python<'py>,
    robot: &Robot,
    samples: &Bound<'py, PyAny>,
    known_poses: Option<&Bound<'py, PyAny>>,
    unknowns: &str,
    relative: bool,
    reference: Option<Vec<f64>>,
) -> PyResult<Bound<'py, PyDict>> {
    let geo = robot.geometry();
    let (n, dof) = (geo.cable_count(), geo.dof());
    // The unknowns first, then the arrays, then the request (the order of the messages).
    Unknowns::parse(unknowns).map_err(value_error)?;
    let s = FloatArray::new(samples, "samples")?;
    let k = match s.shape() {
        [k, c] if *c == n => *k,
        other => {
            return Err(value_error(format!(
                "samples: expected shape (k, {n}) (one reading per cable), got {}",
                shape_string(other)
            )));
        }
    };
    s.check_finite("samples")?;
    let poses = match known_poses {
        None => None,
        Some(p) => {
            let a = FloatArray::new(p, "known_poses")?;
            if a.shape() != [k, dof] {
                return Err(value_error(format!(
                    "known_poses: expected shape ({k}, {dof}) ({}), got {}",
                    robot.pose_hint(),
                    shape_string(a.shape())
                )));
            }
            a.check_finite("known_poses")?;
            Some(a.data().into_owned())
        }
    };
    let rows = |data: &[f64], width: usize| -> Vec<Vec<f64>> {
        data.chunks(width).map(<[f64]>::to_vec).collect()
    };
    let mut request = cdpr_api::CalibrationRequest::new(
        api_robot(robot),
        SamplesSource::Arrays {
            readings: rows(&s.data()[..], n),
            poses: poses.map(|p| rows(&p[..], dof)),
        },
    );
    request.unknowns = unknowns.to_string();
    request.relative = relative;
    // Python's reference defaults to the origin (not the robot file's `home_pose`).
    request.reference = Some(reference.unwrap_or_else(|| vec![0.0; dof]));
    let report = py.detach(|| request.run()).map_err(api_error)?;
    to_dict(py, &report)
}

/// The report as the dict of `cdpr calibrate --json` (the fields Python has always returned).
fn to_dict<'py>(py: Python<'py>, r: &CalibrationReport) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("samples", r.samples)?;
    d.set_item("frame", r.frame.clone())?;
    d.set_item("platform", r.platform.clone())?;
    d.set_item("offsets", r.offsets.clone())?;
    d.set_item("gains", r.gains.clone())?;
    d.set_item("poses", r.poses.clone())?;
    d.set_item("residual_rms", r.residual_rms)?;
    d.set_item("residual_max", r.residual_max)?;
    d.set_item("length_sigma", r.length_sigma)?;
    let sigma = match &r.sigma {
        None => None,
        Some(s) => {
            let g = PyDict::new(py);
            g.set_item("frame", s.frame.clone())?;
            g.set_item("platform", s.platform.clone())?;
            g.set_item("offsets", s.offsets.clone())?;
            g.set_item("gains", s.gains.clone())?;
            Some(g)
        }
    };
    d.set_item("sigma", sigma)?;
    d.set_item("identifiable", r.identifiable)?;
    d.set_item("rank_deficiency", r.rank_deficiency)?;
    d.set_item("condition_number", r.condition_number)?;
    d.set_item("parameters", r.parameters)?;
    d.set_item("gauge_count", r.gauge_count)?;
    d.set_item("gauge", r.gauge.clone())?;
    d.set_item("samples_needed", r.samples_needed)?;
    d.set_item("reason", r.reason.clone())?;
    d.set_item("iterations", r.iterations)?;
    d.set_item("converged", r.converged)?;
    d.set_item("warnings", r.warnings.clone())?;
    Ok(d)
}
