//! # Tension distribution over a batch
//!
//! Per pose, tensions t with W t + w_ext = 0 and t_min ≤ t ≤ t_max by one of the methods of
//! `cdpr-tension` (the `cdpr tension` command at one pose). w_ext is the given wrench plus the
//! platform's gravity at that pose (Picard, Caro, Plestan & Claveau 2020, eq. (1)). Every feasible answer is certified by
//! the crate; an infeasible one comes with its reason.

use crate::arrays::{FloatArray, Rows, shape_string, to_numpy, writable, zeros};
use crate::kinematics::pose_at;
use crate::model::Robot;
use crate::requests::{api_error, api_robot};
use crate::{map_poses, row, run_batch, value_error};
use cdpr_api::{ApiError, SotdaSearch, TensionRequest};
use cdpr_kinematics::PoseKinematics;
use cdpr_tension::{
    Method, MethodOptions, SotdaSettings, SotdaVariant, StiffnessData, TensionProblem,
    TensionSolver,
};
use nalgebra::{DMatrix, DVector, Vector3};
use pyo3::IntoPyObjectExt;
use pyo3::prelude::*;
use pyo3::types::PyList;
use std::borrow::Cow;

/// The names of the tension distribution methods (``cdpr.METHODS``).
pub fn method_names() -> Vec<&'static str> {
    Method::ALL.iter().map(|m| m.name()).collect()
}

/// A method from its command-line name.
pub fn parse_method(name: &str) -> PyResult<Method> {
    name.parse().map_err(|_| {
        value_error(format!(
            "method: unknown tension distribution method `{name}` (known: {})",
            method_names().join(", ")
        ))
    })
}

/// The external wrenches of a batch: none (zero), one (DOF,) for every pose, or (N, DOF).
pub struct Wrenches<'a> {
    data: Cow<'a, [f64]>,
    per_pose: bool,
    dof: usize,
}

impl<'a> Wrenches<'a> {
    pub fn at(&self, k: usize) -> &[f64] {
        let k = if self.per_pose { k } else { 0 };
        &self.data[k * self.dof..(k + 1) * self.dof]
    }
}

/// Reads `wrenches` for `count` poses of a robot with `dof` DOF.
pub fn read_wrenches<'py>(
    arr: &'py Option<FloatArray<'py>>,
    count: usize,
    single: bool,
    dof: usize,
) -> PyResult<Wrenches<'py>> {
    let Some(a) = arr else {
        return Ok(Wrenches {
            data: Cow::Owned(vec![0.0; dof]),
            per_pose: false,
            dof,
        });
    };
    let per_pose = match a.shape() {
        [d] if *d == dof => false,
        [n, d] if *d == dof && *n == count && !single => true,
        s => {
            return Err(value_error(format!(
                "wrenches: expected shape ({dof},) or ({count}, {dof}) (one external wrench per \
                 pose, N and N·m), got {}",
                shape_string(s)
            )));
        }
    };
    a.check_finite("wrenches")?;
    Ok(Wrenches {
        data: a.data(),
        per_pose,
        dof,
    })
}

/// SOTDA settings from keyword arguments.
pub fn sotda_settings(
    direction: Option<Vec<f64>>,
    nu: f64,
    search: &str,
) -> PyResult<SotdaSettings> {
    let mut s = SotdaSettings {
        nu,
        ..SotdaSettings::default()
    };
    if let Some(d) = direction {
        s.direction = match d[..] {
            [x, y] => Vector3::new(x, y, 0.0),
            [x, y, z] => Vector3::new(x, y, z),
            _ => {
                return Err(value_error(format!(
                    "direction needs 2 or 3 numbers, got {}",
                    d.len()
                )));
            }
        };
    }
    s.variant = match search {
        "corners" => SotdaVariant::Corners,
        "vertices" => SotdaVariant::Vertices,
        "full" => SotdaVariant::Full,
        other => {
            return Err(value_error(format!(
                "sotda_search: `{other}` is not one of corners, vertices, full"
            )));
        }
    };
    s.validate().map_err(value_error)?;
    Ok(s)
}

/// A solver for `method` (SOTDA with its settings), checking the robot has what it needs.
pub fn solver(robot: &Robot, method: Method, sotda: SotdaSettings) -> PyResult<TensionSolver> {
    cdpr_wrench::require_enough_cables(robot.geometry(), "tension distribution")
        .map_err(value_error)?;
    if method == Method::Sotda {
        if robot.desc.axial_stiffness.is_none() {
            return Err(value_error(
                "sotda needs `axial_stiffness` (E·S, N) on every cable of the robot",
            ));
        }
        Ok(TensionSolver::sotda(sotda))
    } else {
        Ok(TensionSolver::new(method))
    }
}

/// The keyword options of the methods of issue 26 (``interior`` for puncture, ``alternating``
/// for dykstra, ``p`` for p-norm, ``alpha`` for optimally-safe).
#[derive(Debug, Default)]
pub struct PeerOptions {
    pub interior: Option<String>,
    pub alternating: bool,
    pub p: Option<f64>,
    pub alpha: Option<f64>,
}

impl PeerOptions {
    /// The request's options (`cdpr_api::PeerOptions`, the one copy `cdpr tension`,
    /// `trajectory` and `workspace` check).
    pub fn to_api(&self) -> cdpr_api::PeerOptions {
        cdpr_api::PeerOptions {
            interior: self.interior.clone(),
            alternating: self.alternating,
            p: self.p,
            alpha: self.alpha,
        }
    }

    /// The options for `method` (`cdpr_api::PeerOptions::for_method`); an option of another
    /// method is a `ValueError` naming the keyword.
    pub fn for_method(&self, method: Method) -> PyResult<MethodOptions> {
        self.to_api()
            .for_method(method)
            .map_err(|e| value_error(e.to_string().replace("--", "")))
    }
}

/// Tension distributions of a batch.
///
/// ``tensions`` (N, n) in N, NaN where infeasible; ``feasible`` (N,) bool; ``residual`` (N,):
/// ‖W t + w_ext‖∞ of the certified solution (NaN where infeasible); ``reason``: a list of N
/// strings saying why a pose is infeasible (None where feasible); ``external_wrench`` (N, DOF):
/// the w_ext used (given wrench plus gravity); ``method``. One pose in gives ``tensions`` (n,),
/// ``feasible`` a bool, ``residual`` a float and ``reason`` a str or None.
#[pyclass(module = "cdpr", frozen, get_all)]
pub struct TensionResult {
    pub tensions: Py<PyAny>,
    pub feasible: Py<PyAny>,
    pub residual: Py<PyAny>,
    pub reason: Py<PyAny>,
    pub external_wrench: Py<PyAny>,
    pub method: String,
}

#[pymethods]
impl TensionResult {
    fn __repr__(&self, py: Python<'_>) -> String {
        format!(
            "TensionResult(method={:?}, feasible={})",
            self.method,
            self.feasible.bind(py)
        )
    }
}

/// Per-task buffers of the tension loop.
struct Buffers {
    kin: PoseKinematics,
    w: DMatrix<f64>,
    w_ext: DVector<f64>,
    t: DVector<f64>,
    solver: TensionSolver,
}

impl Buffers {
    fn new(robot: &Robot, solver: &TensionSolver) -> Self {
        let geo = robot.geometry();
        let (dof, n) = (geo.dof(), geo.cable_count());
        Self {
            kin: PoseKinematics::for_robot(geo),
            w: DMatrix::zeros(dof, n),
            w_ext: DVector::zeros(dof),
            t: DVector::zeros(n),
            solver: solver.clone(),
        }
    }

    /// Pose k (coordinates `q`, external wrench `we`) into row j of the four outputs
    /// (tensions, feasible, residual, w_ext); the reason when infeasible.
    fn solve(
        &mut self,
        robot: &Robot,
        (q, we): (&[f64], &[f64]),
        (k, j): (usize, usize),
        blocks: &mut [&mut [f64]],
    ) -> Result<Option<String>, String> {
        let (desc, geo) = (&robot.desc, robot.geometry());
        let (dof, n) = (geo.dof(), geo.cable_count());
        let [t_out, feas, res, wext] = blocks else {
            unreachable!("four outputs")
        };
        let pose = pose_at(robot, q, k)?;
        let g = desc
            .load_wrench(&pose)
            .map_err(|e| format!("poses[{k}]: {e}"))?;
        for (o, (a, g)) in self.w_ext.iter_mut().zip(we.iter().zip(g.iter())) {
            *o = a + g;
        }
        row(wext, j, dof).copy_from_slice(self.w_ext.as_slice());
        let infeasible = |t_out: &mut [f64], feas: &mut [f64], res: &mut [f64]| {
            row(t_out, j, n).fill(f64::NAN);
            feas[j] = 0.0;
            res[j] = f64::NAN;
        };
        if let Err(e) = geo.update_kinematics(&pose, &mut self.kin) {
            infeasible(t_out, feas, res);
            return Ok(Some(e.to_string()));
        }
        self.kin.write_wrench_matrix(&mut self.w);
        let mut problem = TensionProblem::new(&self.w, &self.w_ext, &desc.bounds);
        if let Some(es) = &desc.axial_stiffness {
            problem.stiffness = Some(StiffnessData {
                kinematics: &self.kin,
                axial_stiffness: es,
            });
        }
        match self
            .solver
            .solve_into(&problem, &mut self.t)
            .map_err(|e| format!("poses[{k}]: {e}"))?
        {
            Ok(residual) => {
                row(t_out, j, n).copy_from_slice(self.t.as_slice());
                feas[j] = 1.0;
                res[j] = residual;
                Ok(None)
            }
            Err(reason) => {
                infeasible(t_out, feas, res);
                Ok(Some(reason.to_string()))
            }
        }
    }
}

/// Tension distributions at one pose (through the request) or a batch (the pose loop).
#[allow(clippy::too_many_arguments)]
pub fn tensions(
    robot: &Robot,
    py: Python<'_>,
    poses: &Bound<'_, PyAny>,
    wrenches: Option<&Bound<'_, PyAny>>,
    method: &str,
    direction: Option<Vec<f64>>,
    nu: f64,
    sotda_search: &str,
    peer: PeerOptions,
) -> PyResult<TensionResult> {
    let dof = robot.geometry().dof();
    let method = parse_method(method)?;
    let options = peer.for_method(method)?;
    let sotda = sotda_settings(direction.clone(), nu, sotda_search)?;
    let base_solver = solver(robot, method, sotda)?
        .with_options(options)
        .map_err(value_error)?;
    let rows = Rows::new(poses, dof, "poses", robot.pose_hint())?;
    let data = rows.array.data();
    let warr = wrenches
        .map(|w| FloatArray::new(w, "wrenches"))
        .transpose()?;
    let wr = read_wrenches(&warr, rows.count, rows.single, dof)?;
    if !rows.single {
        return tension_batch(robot, py, &data, &wr, &base_solver);
    }
    let request = TensionRequest {
        robot: api_robot(robot),
        pose: data.to_vec(),
        wrench: Some(wr.at(0).to_vec()),
        method,
        direction,
        nu,
        sotda_search: match sotda_search {
            "vertices" => SotdaSearch::Vertices,
            "full" => SotdaSearch::Full,
            _ => SotdaSearch::Corners,
        },
        options: peer.to_api(),
    };
    tension_at(py, &request)
}

/// A batch of poses (`data`: N rows of DOF coordinates), in parallel.
fn tension_batch(
    robot: &Robot,
    py: Python<'_>,
    data: &[f64],
    wr: &Wrenches<'_>,
    base_solver: &TensionSolver,
) -> PyResult<TensionResult> {
    let (dof, n) = (robot.geometry().dof(), robot.geometry().cable_count());
    let count = data.len() / dof;
    let widths = [n, 1, 1, dof];
    let mut arrays = [zeros(py, &[count, n]), zeros(py, &[count, dof])];
    let (mut f, mut r) = (vec![0.0; count], vec![0.0; count]);
    let [t_arr, w_arr] = &mut arrays;
    let mut outs = writable(std::slice::from_mut(t_arr));
    outs.push(&mut f);
    outs.push(&mut r);
    outs.extend(writable(std::slice::from_mut(w_arr)));
    let reasons = run_batch(py, count, || {
        map_poses(
            count,
            &widths,
            outs,
            || Buffers::new(robot, base_solver),
            |b, k, j, blocks| {
                let q = &data[k * dof..(k + 1) * dof];
                b.solve(robot, (q, wr.at(k)), (k, j), blocks)
            },
        )
        .map_err(|e: String| value_error(e))
    })?;
    let feasible: Vec<bool> = f.iter().map(|&v| v == 1.0).collect();
    let [tensions, external_wrench] = arrays.map(|a| a.into_any().unbind());
    Ok(TensionResult {
        tensions,
        feasible: to_numpy(py, &[count], feasible).into_any().unbind(),
        residual: to_numpy(py, &[count], r).into_any().unbind(),
        reason: PyList::new(py, reasons)?.into_any().unbind(),
        external_wrench,
        method: base_solver.method().name().to_string(),
    })
}

/// One pose: the `cdpr tension` request and its report. A pose where the cables' directions
/// are undefined is an infeasible answer with its reason, as in a batch.
fn tension_at(py: Python<'_>, request: &TensionRequest) -> PyResult<TensionResult> {
    request.validate().map_err(api_error)?;
    let n = request.robot.robot.cable_count();
    let (tensions, feasible, residual, reason, w_ext) = match request.run() {
        Ok(r) if r.feasible => (
            r.tensions.unwrap_or_else(|| vec![f64::NAN; n]),
            true,
            r.residual.unwrap_or(f64::NAN),
            None,
            r.external_wrench,
        ),
        Ok(r) => (
            vec![f64::NAN; n],
            false,
            f64::NAN,
            r.reason,
            r.external_wrench,
        ),
        Err(ApiError::Kinematics(e)) => {
            let p = cdpr_api::inputs::pose(&request.robot, &request.pose).map_err(api_error)?;
            let w =
                cdpr_api::inputs::external_wrench(&request.robot, &p, request.wrench.as_deref())
                    .map_err(api_error)?;
            (
                vec![f64::NAN; n],
                false,
                f64::NAN,
                Some(e.to_string()),
                w.as_slice().to_vec(),
            )
        }
        Err(e) => return Err(api_error(e)),
    };
    let dof = w_ext.len();
    Ok(TensionResult {
        tensions: to_numpy(py, &[n], tensions).into_any().unbind(),
        feasible: feasible.into_py_any(py)?,
        residual: residual.into_py_any(py)?,
        reason: reason.into_py_any(py)?,
        external_wrench: to_numpy(py, &[dof], w_ext).into_any().unbind(),
        method: request.method.name().to_string(),
    })
}
