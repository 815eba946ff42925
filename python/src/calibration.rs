//! # Calibration from cable-length readings
//!
//! `cdpr.calibrate(robot, samples, known_poses=…, unknowns=…)`: the `cdpr-calibration` crate
//! (known poses: per-cable least squares; unknown poses: self-calibration with the gauge fixed,
//! Borgstrom et al. 2009; Miermeister & Pott 2012), its report as a dict with the field names
//! of `cdpr calibrate --json`.

use crate::arrays::{FloatArray, shape_string};
use crate::model::Robot;
use crate::value_error;
use cdpr_calibration::{Calibration, Readings, Samples, Unknowns, calibrate_with_encoders};
use cdpr_io::Encoders;
use cdpr_kinematics::Pose;
use cdpr_kinematics::nalgebra::Vector3;
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
    let (n, motion, dof) = (geo.cable_count(), geo.motion(), geo.dof());
    let unknowns = Unknowns::parse(unknowns).map_err(value_error)?;
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
            let poses = a
                .data()
                .chunks(dof)
                .map(|q| Pose::from_coordinates(motion, q))
                .collect::<Result<Vec<_>, _>>()
                .map_err(value_error)?;
            Some(poses)
        }
    };
    let readings = if relative {
        let q = reference.unwrap_or_else(|| vec![0.0; dof]);
        let reference = Pose::from_coordinates(motion, &q).map_err(value_error)?;
        Readings::Relative { reference }
    } else {
        Readings::Absolute
    };
    let samples = Samples {
        readings: s.data().into_owned(),
        poses,
    };
    let encoders = robot
        .desc
        .encoders
        .clone()
        .unwrap_or_else(|| Encoders::identity(n));
    let cal = py
        .detach(|| {
            calibrate_with_encoders(
                geo,
                &encoders.offsets,
                &encoders.gains,
                &samples,
                unknowns,
                &readings,
            )
        })
        .map_err(value_error)?;
    report(py, robot, &cal, k)
}

fn finite(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

fn report<'py>(
    py: Python<'py>,
    robot: &Robot,
    cal: &Calibration,
    k: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let motion = robot.geometry().motion();
    let dim = motion.space_dim();
    let points = |v: &[Vector3<f64>]| -> Vec<Vec<f64>> {
        v.iter()
            .map(|p| p.iter().take(dim).copied().collect())
            .collect()
    };
    let p = &cal.parameters;
    let d = PyDict::new(py);
    d.set_item("samples", k)?;
    d.set_item("frame", points(&p.frame))?;
    d.set_item(
        "platform",
        motion.has_orientation().then(|| points(&p.platform)),
    )?;
    d.set_item("offsets", p.offsets.clone())?;
    d.set_item("gains", p.gains.clone())?;
    d.set_item(
        "poses",
        cal.poses_estimated.then(|| {
            cal.poses
                .iter()
                .map(|x| x.coordinates(motion))
                .collect::<Vec<_>>()
        }),
    )?;
    d.set_item("residual_rms", finite(cal.residual_rms))?;
    d.set_item("residual_max", finite(cal.residual_max))?;
    d.set_item("length_sigma", cal.length_sigma)?;
    let sigma = match &cal.sigma {
        None => None,
        Some(s) => {
            let g = PyDict::new(py);
            g.set_item("frame", s.frame.as_deref().map(points))?;
            g.set_item("platform", s.platform.as_deref().map(points))?;
            g.set_item("offsets", s.offsets.clone())?;
            g.set_item("gains", s.gains.clone())?;
            Some(g)
        }
    };
    d.set_item("sigma", sigma)?;
    d.set_item("identifiable", cal.identifiable)?;
    d.set_item("rank_deficiency", cal.rank_deficiency)?;
    d.set_item("condition_number", finite(cal.condition_number))?;
    d.set_item("parameters", cal.counting.parameters)?;
    d.set_item("gauge_count", cal.counting.gauge)?;
    d.set_item("gauge", cal.gauge.clone())?;
    d.set_item("samples_needed", cal.counting.samples_needed)?;
    d.set_item("reason", cal.counting.reason.clone())?;
    d.set_item("iterations", cal.iterations)?;
    d.set_item("converged", cal.converged)?;
    d.set_item("warnings", cal.warnings.clone())?;
    Ok(d)
}
