//! # Forward kinematics over a batch
//!
//! From measured cable lengths to the platform pose by Levenberg–Marquardt
//! ([`cdpr_kinematics::ForwardKinematics`]; Pott 2018), from a guess or, without one, from the
//! solver's fixed set of starts (every distinct solution kept, the best first). Every answer is
//! certified: the residual max |l_i(pose) − L_i| recomputed at the pose, the iterations, the
//! status, and the smallest singular value of the Jacobian (the `cdpr forward` command).

use crate::arrays::{FloatArray, Rows, batch_shape, shape_string, to_numpy};
use crate::model::Robot;
use crate::requests::{api_error, api_robot, matrix};
use crate::{map_poses, run_batch, value_error};
use cdpr_api::ForwardRequest;
use cdpr_kinematics::{ForwardKinematics, ForwardSettings, ForwardSolution, MotionPattern, Pose};
use numpy::PyArrayDyn;
use pyo3::IntoPyObjectExt;
use pyo3::prelude::*;

/// Forward-kinematics answers.
///
/// ``pose`` (N, DOF): the best pose found (motion-pattern coordinates, m and rad);
/// ``residual`` (N,): max |l_i(pose) − L_i| (m); ``iterations`` (N,); ``converged`` (N,) bool;
/// ``status``: list of ``"solved"``, ``"fitted"``, ``"inconsistent"``, ``"no pose within
/// tolerance"``, ``"above the anchors"`` or ``"did not converge"`` (as ``cdpr forward``);
/// ``residual_rms`` (N,): ‖l(pose) − L‖/√n (m); ``pose_std`` (N, DOF): standard deviations
/// √diag(σ²(JᵀJ)⁻¹) of the pose with σ = ``length_sigma`` (m; rad for rotations);
/// ``min_singular_value`` (N,): σ_min of the Jacobian at the pose (pose error ≲ length error /
/// σ_min); ``solutions``: for one set of lengths without a guess, every distinct pose found
/// (S, DOF), best first (else None). One set of lengths in gives scalars and ``pose`` (DOF,).
#[pyclass(module = "cdpr", frozen, get_all)]
pub struct ForwardResult {
    pub pose: Py<PyArrayDyn<f64>>,
    pub residual: Py<PyAny>,
    pub iterations: Py<PyAny>,
    pub converged: Py<PyAny>,
    pub status: Py<PyAny>,
    pub min_singular_value: Py<PyAny>,
    pub solutions: Option<Py<PyArrayDyn<f64>>>,
    pub residual_rms: Py<PyAny>,
    pub pose_std: Py<PyArrayDyn<f64>>,
}

#[pymethods]
impl ForwardResult {
    fn __repr__(&self, py: Python<'_>) -> String {
        format!(
            "ForwardResult(status={}, residual={})",
            self.status.bind(py),
            self.residual.bind(py)
        )
    }
}

pub fn forward_kinematics(
    robot: &Robot,
    py: Python<'_>,
    lengths: &Bound<'_, PyAny>,
    guess: Option<&Bound<'_, PyAny>>,
    tolerance: f64,
    max_iterations: usize,
    length_sigma: f64,
) -> PyResult<ForwardResult> {
    let geo = robot.geometry();
    let motion = geo.motion();
    let n = geo.cable_count();
    let settings = ForwardSettings {
        tolerance,
        max_iterations,
        length_sigma,
    };
    // Validates the settings and n ≥ DOF once, with the library's message.
    ForwardKinematics::new(geo, settings).map_err(value_error)?;
    let rows = Rows::new(lengths, n, "lengths", "measured cable lengths, m")?;
    let count = rows.count;
    let data = rows.array.data();
    let garr = guess.map(|g| FloatArray::new(g, "guess")).transpose()?;
    let guesses = read_guesses(robot, garr.as_ref(), count, rows.single)?;
    if rows.single {
        let request = ForwardRequest {
            robot: api_robot(robot),
            lengths: data.to_vec(),
            guess: garr.as_ref().map(|g| g.data().into_owned()),
            tolerance,
            length_sigma,
            max_iterations,
        };
        return forward_at(py, &request);
    }
    let multistart = guesses.is_none();
    let widths: [usize; 0] = [];
    let answers: Vec<Vec<ForwardSolution>> = run_batch(py, count, || {
        map_poses(
            count,
            &widths,
            Vec::new(),
            || ForwardKinematics::new(geo, settings).expect("validated above"),
            |fk, k, _, _| {
                let l = &data[k * n..(k + 1) * n];
                let prefix = |e| format!("lengths[{k}]: {e}");
                match &guesses {
                    Some((g, per_row)) => {
                        let g = if *per_row { &g[k] } else { &g[0] };
                        fk.solve(l, g).map(|s| vec![s]).map_err(prefix)
                    }
                    None => fk.solve_multistart(l).map_err(prefix),
                }
            },
        )
        .map_err(value_error)
    })?;
    batch_result(py, motion, (rows.single, multistart), &answers)
}

/// One set of lengths with the request's iteration limit: the `cdpr forward` request and its
/// report (``solutions``: every distinct pose of a multi-start, best first).
fn forward_at(py: Python<'_>, request: &ForwardRequest) -> PyResult<ForwardResult> {
    let r = request.run().map_err(api_error)?;
    let best = r.best;
    let dof = best.pose.len();
    let solutions = request.guess.is_none().then(|| {
        let rows: Vec<Vec<f64>> = r.solutions.iter().map(|s| s.pose.clone()).collect();
        matrix(py, &rows, dof).unbind()
    });
    Ok(ForwardResult {
        pose: to_numpy(py, &[dof], best.pose).unbind(),
        residual: best.residual.into_py_any(py)?,
        iterations: (best.iterations as i64).into_py_any(py)?,
        converged: best.converged.into_py_any(py)?,
        status: best.status.into_py_any(py)?,
        min_singular_value: best.min_singular_value.into_py_any(py)?,
        solutions,
        residual_rms: best.residual_rms.into_py_any(py)?,
        pose_std: to_numpy(py, &[dof], best.pose_std).unbind(),
    })
}

/// The guesses (``(DOF,)`` for every row or one per row) as poses, and whether one per row.
fn read_guesses(
    robot: &Robot,
    garr: Option<&FloatArray<'_>>,
    count: usize,
    single: bool,
) -> PyResult<Option<(Vec<Pose>, bool)>> {
    let (motion, dof) = (robot.motion_pattern(), robot.geometry().dof());
    Ok(match garr {
        None => None,
        Some(a) => {
            let per_row = match a.shape() {
                [d] if *d == dof => false,
                [c, d] if *d == dof && *c == count && !single => true,
                s => {
                    return Err(value_error(format!(
                        "guess: expected shape ({dof},) or ({count}, {dof}) ({}), got {}",
                        robot.pose_hint(),
                        shape_string(s)
                    )));
                }
            };
            a.check_finite("guess")?;
            let poses = a
                .data()
                .chunks(dof)
                .map(|q| Pose::from_coordinates(motion, q))
                .collect::<Result<Vec<_>, _>>()
                .map_err(|e| value_error(format!("guess: {e}")))?;
            Some((poses, per_row))
        }
    })
}

/// The result of a batch (or of one set of lengths with another iteration limit than the
/// request's): the best answer of each row; one set of lengths without a guess also gives every
/// answer (`solutions`).
fn batch_result(
    py: Python<'_>,
    motion: MotionPattern,
    (single, multistart): (bool, bool),
    answers: &[Vec<ForwardSolution>],
) -> PyResult<ForwardResult> {
    let (dof, count) = (motion.dof(), answers.len());
    let best: Vec<&ForwardSolution> = answers.iter().map(|a| &a[0]).collect();
    let poses: Vec<f64> = best
        .iter()
        .flat_map(|s| s.pose.coordinates(motion))
        .collect();
    let scalar = |v: Vec<f64>| -> PyResult<Py<PyAny>> {
        Ok(if single {
            v[0].into_pyobject(py)?.into_any().unbind()
        } else {
            to_numpy(py, &[count], v).into_any().unbind()
        })
    };
    let iterations: Vec<i64> = best.iter().map(|s| s.iterations as i64).collect();
    let converged: Vec<bool> = best.iter().map(|s| s.converged).collect();
    let status: Vec<&str> = best.iter().map(|s| s.status.name()).collect();
    Ok(ForwardResult {
        pose: to_numpy(py, &batch_shape(single, count, &[dof]), poses).unbind(),
        residual: scalar(best.iter().map(|s| s.residual).collect())?,
        residual_rms: scalar(best.iter().map(|s| s.residual_rms).collect())?,
        pose_std: to_numpy(
            py,
            &batch_shape(single, count, &[dof]),
            best.iter().flat_map(|s| s.pose_std(dof).to_vec()).collect(),
        )
        .unbind(),
        min_singular_value: scalar(best.iter().map(|s| s.min_singular_value).collect())?,
        iterations: if single {
            iterations[0].into_pyobject(py)?.into_any().unbind()
        } else {
            to_numpy(py, &[count], iterations).into_any().unbind()
        },
        converged: if single {
            converged[0]
                .into_pyobject(py)?
                .to_owned()
                .into_any()
                .unbind()
        } else {
            to_numpy(py, &[count], converged).into_any().unbind()
        },
        status: if single {
            status[0].into_pyobject(py)?.into_any().unbind()
        } else {
            status.into_pyobject(py)?.into_any().unbind()
        },
        solutions: (single && multistart).then(|| {
            let all: Vec<f64> = answers[0]
                .iter()
                .flat_map(|s| s.pose.coordinates(motion))
                .collect();
            to_numpy(py, &[answers[0].len(), dof], all).unbind()
        }),
    })
}
