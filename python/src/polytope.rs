//! # Wrench-set indices and stiffness over a batch
//!
//! Per pose: the capacity margin of a required wrench set (Guay et al. 2014; the `cdpr capacity`
//! command), the maximum isotropic force (Krut, Company & Pierrot 2004; `cdpr isotropic`), both
//! from the available wrench set {W t : t_min ≤ t ≤ t_max} by hyperplane shifting, and the
//! stiffness matrix K = Kp + Ka (Picard, Caro, Plestan & Claveau 2020 eqs. (3)–(4);
//! `cdpr stiffness`).

use crate::arrays::{FloatArray, Rows, shape_string, to_numpy};
use crate::kinematics::pose_at;
use crate::model::Robot;
use crate::requests::{api_error, api_robot, matrix};
use crate::tension::read_wrenches;
use crate::{map_poses, row, run_batch, value_error};
use cdpr_api::{CapacityRequest, IsotropicRequest, StiffnessRequest};
use cdpr_kinematics::PoseKinematics;
use cdpr_polytope::{IsotropicForce, LimitingFacet, RequiredWrenchSet};
use nalgebra::{DMatrix, DVector};
use numpy::PyArrayDyn;
use pyo3::IntoPyObjectExt;
use pyo3::prelude::*;

/// Wraps a per-pose error with the pose index.
fn at<E: std::fmt::Display>(k: usize) -> impl Fn(E) -> String {
    move |e| format!("poses[{k}]: {e}")
}

/// Capacity margins of a batch.
///
/// ``capacity_margin`` (N,): min over the facets of the available wrench set of the distance
/// left around the required set (wrench units: N, N·m); positive iff every required wrench can
/// be balanced with tensions in bounds; ``inf`` when the set has no facet. ``feasible`` (N,)
/// bool: margin ≥ 0. ``limiting_facet`` (N,) int: index of the facet reached first (−1 if
/// none). One pose in gives scalars.
#[pyclass(module = "cdpr", frozen, get_all)]
pub struct CapacityResult {
    pub capacity_margin: Py<PyAny>,
    pub feasible: Py<PyAny>,
    pub limiting_facet: Py<PyAny>,
}

/// Maximum isotropic force of a batch.
///
/// ``isotropic_force`` (N,): radius of the largest ball of forces, added to the external
/// wrench, that the cables can still balance (N); for planar and spatial robots the force at
/// zero added moment; negative when the external wrench itself cannot be held.
/// ``wrench_radius`` (N,): the same ball in the full wrench space (N and N·m combined).
/// ``definition``: what the index means for this motion pattern.
///
/// One pose in (and a wrench space of dimension 2 or 3: point2, point3 or planar robots) also
/// gives the available wrench set {W t : t_min ≤ t ≤ t_max} (no load) as ``cdpr isotropic
/// --json`` does: ``vertices`` (V, DOF) (N, N·m), ``faces`` a list of int arrays of vertex
/// indices, counter-clockwise seen from outside (DOF 2: the edges), ``normals`` (F, DOF) their
/// outward unit normals and ``offsets`` (F,) (n · w ≤ d; N or N·m). ``None`` otherwise.
#[pyclass(module = "cdpr", frozen, get_all)]
pub struct IsotropicResult {
    pub isotropic_force: Py<PyAny>,
    pub wrench_radius: Py<PyAny>,
    pub definition: String,
    pub vertices: Option<Py<PyAny>>,
    pub faces: Option<Vec<Py<PyAny>>>,
    pub normals: Option<Py<PyAny>>,
    pub offsets: Option<Py<PyAny>>,
}

/// Stiffness matrices of a batch: ``stiffness`` K = Kp + Ka, ``passive`` Kp (cable elasticity,
/// k_i = E·S / l_i) and ``active`` Ka (tension-dependent), each (N, DOF, DOF) (N/m, N, N·m/rad).
#[pyclass(module = "cdpr", frozen, get_all)]
pub struct StiffnessResult {
    pub stiffness: Py<PyArrayDyn<f64>>,
    pub passive: Py<PyArrayDyn<f64>>,
    pub active: Py<PyArrayDyn<f64>>,
}

/// A scalar per pose of a batch: a (N,) array.
fn per_pose(py: Python<'_>, v: Vec<f64>) -> Py<PyAny> {
    let n = v.len();
    to_numpy(py, &[n], v).into_any().unbind()
}

/// `wrench_box` (one half-width per wrench component) or `wrench_ball`, not both.
fn check_required_set(dof: usize, wrench_box: Option<&[f64]>, ball: Option<f64>) -> PyResult<()> {
    if let Some(h) = wrench_box
        && h.len() != dof
    {
        return Err(value_error(format!(
            "wrench_box needs {dof} half-widths (one per wrench component), got {}",
            h.len()
        )));
    }
    if wrench_box.is_some() && ball.is_some() {
        return Err(value_error("give wrench_box or wrench_ball, not both"));
    }
    Ok(())
}

/// The required wrench set's shape centred at zero (each pose of a batch moves its centre).
fn required_set_at_zero(
    dof: usize,
    wrench_box: Option<&[f64]>,
    ball: Option<f64>,
) -> PyResult<RequiredWrenchSet> {
    let zero = DVector::zeros(dof);
    match (wrench_box, ball) {
        (Some(h), _) => RequiredWrenchSet::boxed(zero, DVector::from_column_slice(h)),
        (None, Some(r)) => RequiredWrenchSet::ball(zero, r),
        (None, None) => RequiredWrenchSet::point(zero),
    }
    .map_err(value_error)
}

#[allow(clippy::too_many_arguments)]
pub fn capacity_margin(
    robot: &Robot,
    py: Python<'_>,
    poses: &Bound<'_, PyAny>,
    wrenches: Option<&Bound<'_, PyAny>>,
    wrench_box: Option<Vec<f64>>,
    wrench_ball: Option<f64>,
) -> PyResult<CapacityResult> {
    cdpr_wrench::require_enough_cables(robot.geometry(), "the capacity margin (wrench closure)")
        .map_err(value_error)?;
    let geo = robot.geometry();
    let dof = geo.dof();
    let rows = Rows::new(poses, dof, "poses", robot.pose_hint())?;
    let count = rows.count;
    let data = rows.array.data();
    let warr = wrenches
        .map(|w| FloatArray::new(w, "wrenches"))
        .transpose()?;
    let wr = read_wrenches(&warr, count, rows.single, dof)?;
    check_required_set(dof, wrench_box.as_deref(), wrench_ball)?;
    if rows.single {
        let request = CapacityRequest {
            robot: api_robot(robot),
            pose: data.to_vec(),
            wrench: Some(wr.at(0).to_vec()),
            wrench_box,
            wrench_ball,
            force_radius: None,
            moment_radius: None,
        };
        return capacity_at(py, &request);
    }
    // The required set's shape checked once (centre zero); each pose moves its centre. One
    // kinematics buffer, W and limiting-facet buffers per worker: no allocation per pose.
    let template = required_set_at_zero(dof, wrench_box.as_deref(), wrench_ball)?;
    let facets = LimitingFacet::new(dof, &robot.desc.bounds).map_err(value_error)?;
    let widths = [1, 1];
    let mut outs: Vec<Vec<f64>> = widths.iter().map(|w| vec![0.0; w * count]).collect();
    let slices: Vec<&mut [f64]> = outs.iter_mut().map(|v| v.as_mut_slice()).collect();
    run_batch(py, count, || {
        map_poses(
            count,
            &widths,
            slices,
            || CapacityState {
                kin: PoseKinematics::for_robot(geo),
                w: DMatrix::zeros(dof, geo.cable_count()),
                facets: facets.clone(),
                required: template.clone(),
            },
            |state, k, j, blocks| {
                let q = &data[k * dof..(k + 1) * dof];
                let limit = state.limit_at_pose(robot, (q, wr.at(k)), k)?;
                let [m, f] = blocks else {
                    unreachable!("two outputs")
                };
                m[j] = limit.map_or(f64::INFINITY, |(_, m)| m);
                f[j] = limit.map_or(-1.0, |(i, _)| i as f64);
                Ok::<(), String>(())
            },
        )
        .map_err(value_error)
    })?;
    let margin = outs.remove(0);
    let facet = outs.remove(0);
    let feasible: Vec<bool> = margin.iter().map(|&m| m >= 0.0).collect();
    let facet: Vec<i64> = facet.iter().map(|&f| f as i64).collect();
    Ok(CapacityResult {
        feasible: to_numpy(py, &[count], feasible).into_any().unbind(),
        limiting_facet: to_numpy(py, &[count], facet).into_any().unbind(),
        capacity_margin: per_pose(py, margin),
    })
}

/// One worker's buffers of a capacity batch.
struct CapacityState {
    kin: PoseKinematics,
    w: DMatrix<f64>,
    facets: LimitingFacet,
    required: RequiredWrenchSet,
}

impl CapacityState {
    /// The limiting facet and margin at pose k (coordinates `q`, external wrench `we`): the
    /// required set centred at `we` + the robot file's load at the pose, against the AWS of
    /// the pose's W (the facet index and margin of `cdpr capacity`, without building the set).
    fn limit_at_pose(
        &mut self,
        robot: &Robot,
        (q, we): (&[f64], &[f64]),
        k: usize,
    ) -> Result<Option<(usize, f64)>, String> {
        let pose = pose_at(robot, q, k)?;
        let load = robot.desc.load_wrench(&pose).map_err(at(k))?;
        let mut centre = [0.0; 6];
        for (c, (a, b)) in centre.iter_mut().zip(we.iter().zip(load.iter())) {
            *c = a + b;
        }
        self.required
            .set_centre(&centre[..we.len()])
            .map_err(at(k))?;
        robot
            .geometry()
            .update_kinematics(&pose, &mut self.kin)
            .map_err(at(k))?;
        self.kin.write_wrench_matrix(&mut self.w);
        self.facets.at(&self.w, &self.required).map_err(at(k))
    }
}

/// One pose: the `cdpr capacity` request and its report.
fn capacity_at(py: Python<'_>, request: &CapacityRequest) -> PyResult<CapacityResult> {
    let r = request.run().map_err(api_error)?;
    Ok(CapacityResult {
        capacity_margin: r.capacity_margin.unwrap_or(f64::INFINITY).into_py_any(py)?,
        feasible: r.feasible.into_py_any(py)?,
        limiting_facet: r
            .limiting_facet
            .map_or(-1, |f| f.index as i64)
            .into_py_any(py)?,
    })
}

pub fn isotropic(
    robot: &Robot,
    py: Python<'_>,
    poses: &Bound<'_, PyAny>,
    wrenches: Option<&Bound<'_, PyAny>>,
) -> PyResult<IsotropicResult> {
    cdpr_wrench::require_enough_cables(robot.geometry(), "the isotropic force (wrench closure)")
        .map_err(value_error)?;
    let geo = robot.geometry();
    let dof = geo.dof();
    let rows = Rows::new(poses, dof, "poses", robot.pose_hint())?;
    let count = rows.count;
    let data = rows.array.data();
    let warr = wrenches
        .map(|w| FloatArray::new(w, "wrenches"))
        .transpose()?;
    let wr = read_wrenches(&warr, count, rows.single, dof)?;
    if rows.single {
        let request = IsotropicRequest {
            robot: api_robot(robot),
            pose: data.to_vec(),
            wrench: Some(wr.at(0).to_vec()),
            ellipse: false,
        };
        return isotropic_at(py, &request, dof);
    }
    let desc = &robot.desc;
    // One allocation-free evaluator per worker (hyperplane shifting on the fly, no facet list:
    // what `cdpr isotropic --grid` runs), its load set pose by pose.
    let template = IsotropicForce::new(geo, &desc.bounds).map_err(value_error)?;
    let widths = [1, 1];
    let mut outs: Vec<Vec<f64>> = widths.iter().map(|w| vec![0.0; w * count]).collect();
    let slices: Vec<&mut [f64]> = outs.iter_mut().map(|v| v.as_mut_slice()).collect();
    run_batch(py, count, || {
        map_poses(
            count,
            &widths,
            slices,
            || template.clone(),
            |index, k, j, blocks| {
                let pose = pose_at(robot, &data[k * dof..(k + 1) * dof], k)?;
                let load = desc
                    .load_wrench(&pose)
                    .map_err(|e| format!("poses[{k}]: {e}"))?;
                let mut w_ext = [0.0; 6];
                for (i, (a, b)) in wr.at(k).iter().zip(load.iter()).enumerate() {
                    w_ext[i] = a + b;
                }
                index.set_load(&w_ext[..dof]).map_err(at(k))?;
                let [f, r] = blocks else {
                    unreachable!("two outputs")
                };
                (f[j], r[j]) = index.indices_at_pose(&pose).map_err(at(k))?;
                Ok::<(), String>(())
            },
        )
        .map_err(value_error)
    })?;
    let radius = outs.pop().unwrap();
    let force = outs.pop().unwrap();
    Ok(IsotropicResult {
        isotropic_force: per_pose(py, force),
        wrench_radius: per_pose(py, radius),
        definition: cdpr_api::definition(robot.motion_pattern()).into(),
        vertices: None,
        faces: None,
        normals: None,
        offsets: None,
    })
}

/// One pose: the `cdpr isotropic` request and its report, the polytope's faces included.
fn isotropic_at(
    py: Python<'_>,
    request: &IsotropicRequest,
    dof: usize,
) -> PyResult<IsotropicResult> {
    let r = request.run().map_err(api_error)?;
    let faces = r.faces.map(|fs| {
        fs.into_iter()
            .map(|f| {
                let ids: Vec<i64> = f.into_iter().map(|i| i as i64).collect();
                to_numpy(py, &[ids.len()], ids).into_any().unbind()
            })
            .collect()
    });
    Ok(IsotropicResult {
        isotropic_force: r.isotropic_force.into_py_any(py)?,
        wrench_radius: r.wrench_radius.into_py_any(py)?,
        definition: r.definition,
        vertices: r.vertices.map(|v| matrix(py, &v, dof).into_any().unbind()),
        faces,
        normals: r.normals.map(|n| matrix(py, &n, dof).into_any().unbind()),
        offsets: r.offsets.map(|d| per_pose(py, d)),
    })
}

pub fn stiffness(
    robot: &Robot,
    py: Python<'_>,
    poses: &Bound<'_, PyAny>,
    tensions: &Bound<'_, PyAny>,
    axial_stiffness: Option<&Bound<'_, PyAny>>,
) -> PyResult<StiffnessResult> {
    robot
        .desc
        .require_no_passive_springs("stiffness (cables only; the springs' K would add to it)")
        .map_err(value_error)?;
    let geo = robot.geometry();
    let (dof, n) = (geo.dof(), geo.cable_count());
    let rows = Rows::new(poses, dof, "poses", robot.pose_hint())?;
    let count = rows.count;
    let data = rows.array.data();
    let t = FloatArray::new(tensions, "tensions")?;
    let per_pose_t = match t.shape() {
        [m] if *m == n => false,
        [c, m] if *m == n && *c == count && !rows.single => true,
        s => {
            return Err(value_error(format!(
                "tensions: expected shape ({n},) or ({count}, {n}) (one tension per cable, N), \
                 got {}",
                shape_string(s)
            )));
        }
    };
    t.check_finite("tensions")?;
    let tdata = t.data();
    let es = axial_stiffness_arg(robot, axial_stiffness)?;
    if rows.single {
        return stiffness_at(py, robot, data.to_vec(), tdata.into_owned(), es);
    }
    let widths = [dof * dof; 3];
    let mut outs: Vec<Vec<f64>> = widths.iter().map(|w| vec![0.0; w * count]).collect();
    let slices: Vec<&mut [f64]> = outs.iter_mut().map(|v| v.as_mut_slice()).collect();
    run_batch(py, count, || {
        map_poses(
            count,
            &widths,
            slices,
            || (PoseKinematics::for_robot(geo), DMatrix::zeros(dof, dof)),
            |(kin, km), k, j, blocks| {
                let pose = pose_at(robot, &data[k * dof..(k + 1) * dof], k)?;
                geo.update_kinematics(&pose, kin).map_err(at(k))?;
                let tk = if per_pose_t {
                    &tdata[k * n..(k + 1) * n]
                } else {
                    &tdata[..n]
                };
                cdpr_wrench::write_stiffness_matrix(kin, tk, &es, km).map_err(at(k))?;
                let kp = cdpr_wrench::passive_stiffness(kin, &es).map_err(at(k))?;
                let ka = cdpr_wrench::active_stiffness(kin, tk).map_err(at(k))?;
                for (out, m) in blocks.iter_mut().zip([&*km, &kp, &ka]) {
                    let out = row(out, j, dof * dof);
                    for r in 0..dof {
                        for c in 0..dof {
                            out[r * dof + c] = m[(r, c)];
                        }
                    }
                }
                Ok::<(), String>(())
            },
        )
        .map_err(value_error)
    })?;
    let shape = [count, dof, dof];
    let mut outs = outs.into_iter();
    let mut next = || to_numpy(py, &shape, outs.next().unwrap()).unbind();
    Ok(StiffnessResult {
        stiffness: next(),
        passive: next(),
        active: next(),
    })
}

/// E·S per cable (N): ``axial_stiffness`` (a number or ``(n,)``) or the robot's.
fn axial_stiffness_arg(
    robot: &Robot,
    axial_stiffness: Option<&Bound<'_, PyAny>>,
) -> PyResult<Vec<f64>> {
    let n = robot.geometry().cable_count();
    Ok(match axial_stiffness {
        Some(obj) => {
            let v = if let Ok(x) = obj.extract::<f64>() {
                vec![x; n]
            } else {
                let a = FloatArray::new(obj, "axial_stiffness")?;
                if a.shape() != [n] {
                    return Err(value_error(format!(
                        "axial_stiffness: expected a number or shape ({n},), got {}",
                        shape_string(a.shape())
                    )));
                }
                a.data().into_owned()
            };
            if let Some(x) = v.iter().find(|x| !(x.is_finite() && **x > 0.0)) {
                return Err(value_error(format!(
                    "axial_stiffness: {x} must be a finite number > 0"
                )));
            }
            v
        }
        None => robot.desc.axial_stiffness.clone().ok_or_else(|| {
            value_error(
                "no axial stiffness: give `axial_stiffness` on every cable of the robot file, \
                 or axial_stiffness=",
            )
        })?,
    })
}

/// One pose: the `cdpr stiffness` request (tensions given; `es` replaces the robot's E·S) and
/// its report.
fn stiffness_at(
    py: Python<'_>,
    robot: &Robot,
    pose: Vec<f64>,
    tensions: Vec<f64>,
    es: Vec<f64>,
) -> PyResult<StiffnessResult> {
    let dof = robot.geometry().dof();
    let mut desc = (*robot.desc).clone();
    desc.axial_stiffness = Some(es);
    let request = StiffnessRequest {
        robot: cdpr_api::Robot::from_description(desc),
        pose,
        tensions: Some(tensions),
        method: None,
        wrench: None,
        axial_stiffness: None,
    };
    let r = request.run().map_err(api_error)?;
    Ok(StiffnessResult {
        stiffness: matrix(py, &r.stiffness, dof).unbind(),
        passive: matrix(py, &r.passive, dof).unbind(),
        active: matrix(py, &r.active, dof).unbind(),
    })
}
