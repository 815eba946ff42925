//! # Constant-orientation workspace
//!
//! The positions where every criterion holds at a fixed orientation (thesis eq. (6.23)):
//! Algorithm 6.2 on a grid ([`cdpr_workspace::constant_orientation_workspace`]) or, for robots
//! moving in the plane, the chord method's boundary polygons (§6.4.3). Criteria are written as
//! for `cdpr workspace --criteria` (`tension`, `length[:L]`, `det[:D]`, `wrench-closure`,
//! `capacity[:M]`, `isotropic:F`, `stiffness:K`), and the load is the given wrench plus the
//! platform's gravity at that orientation.

use crate::arrays::to_numpy;
use crate::model::Robot;
use crate::tension::parse_method;
use crate::value_error;
use cdpr_kinematics::{MotionPattern, Pose};
use cdpr_polytope::RequiredWrenchSet;
use cdpr_tension::Method;
use cdpr_workspace::CriterionSpec as Spec;
use cdpr_workspace::{
    ChordSettings, Criterion, Grid, GridWorkspace, MeshSettings, PoseEvaluator, Region,
    VolumeConvention, boundary_mesh, chord_workspace, constant_orientation_workspace,
};
use nalgebra::{DVector, Rotation3, Vector3};
use numpy::PyArrayDyn;
use pyo3::prelude::*;

/// A constant-orientation workspace.
///
/// Grid (``boundary="grid"``): ``feasible`` bool array of shape (M+1, M+1) indexed [iy, ix]
/// (in space (M+1, M+1, M+1) indexed [iz, iy, ix]); axes ``x``, ``y`` (and ``z``) (m);
/// ``points`` (P, dim): the feasible positions; ``area`` (m², or the volume in m³ for robots
/// moving in space, also in ``volume``) in the convention ``volume_convention``: ``"cells"``
/// (each feasible point counts for its cell clipped to the box, the default) or ``"points"``
/// (feasible points × cell area, the thesis' convention); ``area_cells`` and ``area_points``
/// give both; ``cell_area``, ``feasible_points``, ``total_points``.
/// Chord (``boundary="chord"``, planar robots): ``boundaries``: closed polygons, arrays (k, 2),
/// counter-clockwise around regions and clockwise around holes; ``area`` from their signed
/// areas; ``feasible`` is None. Mesh (``boundary="mesh"``, robots moving in space): the grid
/// fields above plus the closed, outward-oriented triangle mesh of the boundary (marching cubes
/// with vertices bisected onto the boundary): ``vertices`` (V, 3) (m), ``faces`` (T, 3) vertex
/// indices, ``surface_area`` (m², box caps included), and ``volume`` from the divergence
/// theorem (m³; ``area`` stays the grid's count, as ``cdpr workspace --boundary mesh`` gives
/// it). Always: ``criteria`` (labels), ``method`` (tension method),
/// ``external_wrench`` (DOF,), ``box`` (the region searched).
#[pyclass(module = "cdpr", frozen, get_all)]
pub struct WorkspaceResult {
    pub feasible: Option<Py<PyArrayDyn<bool>>>,
    pub x: Option<Py<PyArrayDyn<f64>>>,
    pub y: Option<Py<PyArrayDyn<f64>>>,
    pub z: Option<Py<PyArrayDyn<f64>>>,
    pub points: Option<Py<PyArrayDyn<f64>>>,
    pub boundaries: Option<Vec<Py<PyArrayDyn<f64>>>>,
    pub vertices: Option<Py<PyArrayDyn<f64>>>,
    pub faces: Option<Py<PyArrayDyn<i64>>>,
    pub surface_area: Option<f64>,
    pub area: f64,
    pub area_cells: Option<f64>,
    pub area_points: Option<f64>,
    pub volume_convention: Option<String>,
    pub volume: Option<f64>,
    pub cell_area: Option<f64>,
    pub feasible_points: Option<usize>,
    pub total_points: Option<usize>,
    pub criteria: Vec<String>,
    pub method: String,
    pub external_wrench: Py<PyArrayDyn<f64>>,
    #[pyo3(name = "box")]
    pub region: Vec<f64>,
}

#[pymethods]
impl WorkspaceResult {
    fn __repr__(&self) -> String {
        format!(
            "WorkspaceResult(area={}, feasible_points={}, total_points={}, criteria={:?})",
            self.area,
            self.feasible_points
                .map_or("None".into(), |v| v.to_string()),
            self.total_points.map_or("None".into(), |v| v.to_string()),
            self.criteria
        )
    }
}

/// The criteria of `tokens` (default: tension, plus length and det when the robot has limits).
fn specs(robot: &Robot, tokens: Option<Vec<String>>) -> PyResult<Vec<Spec>> {
    let limits = robot.desc.limits;
    cdpr_workspace::parse_criteria(
        tokens.as_ref().map(|t| t.iter().map(String::as_str)),
        robot.motion_pattern(),
        limits.min_cable_length,
        limits.min_jacobian_det,
    )
    .map_err(|e| value_error(format!("criteria: {e}")))
}

/// The platform orientation: φ (planar), rx, ry, rz (spatial), none (point robots).
fn rotation(motion: MotionPattern, q: &[f64]) -> PyResult<Rotation3<f64>> {
    if let Some(v) = q.iter().find(|v| !v.is_finite()) {
        return Err(value_error(format!(
            "orientation: {v} is not a finite number"
        )));
    }
    match (motion, q) {
        (MotionPattern::Point2 | MotionPattern::Point3, q) if q.iter().all(|&v| v == 0.0) => {
            Ok(Rotation3::identity())
        }
        (MotionPattern::Point2 | MotionPattern::Point3, _) => Err(value_error(format!(
            "a `{}` robot has no orientation: omit orientation",
            motion.name()
        ))),
        (_, []) => Ok(Rotation3::identity()),
        (MotionPattern::Planar, [phi]) => Ok(Rotation3::from_axis_angle(&Vector3::z_axis(), *phi)),
        (MotionPattern::Spatial, [rx, ry, rz]) => {
            Ok(Pose::spatial(Vector3::zeros(), *rx, *ry, *rz).rotation)
        }
        _ => Err(value_error(format!(
            "orientation needs {} for a `{}` robot, got {} numbers",
            if motion == MotionPattern::Planar {
                "1 number (φ)"
            } else {
                "3 numbers (rx, ry, rz)"
            },
            motion.name(),
            q.len()
        ))),
    }
}

/// The search box: (xmin, xmax, ymin, ymax[, zmin, zmax]), default [`Region::default_for`]
/// (the frame anchors' box, extended below anchors that span little height).
fn region(robot: &Robot, b: Option<Vec<f64>>) -> PyResult<Region> {
    let dim = robot.motion_pattern().space_dim();
    let r = match b {
        None => Region::default_for(robot.geometry()),
        Some(b) if dim == 2 && b.len() == 4 => Region::planar(b[0], b[1], b[2], b[3]),
        Some(b) if dim == 3 && b.len() == 6 => Region::cuboid(
            Vector3::new(b[0], b[2], b[4]),
            Vector3::new(b[1], b[3], b[5]),
        ),
        Some(b) => {
            return Err(value_error(format!(
                "box needs {} numbers for a `{}` robot, got {}",
                if dim == 2 {
                    "4 (xmin, xmax, ymin, ymax)"
                } else {
                    "6 (xmin, xmax, ymin, ymax, zmin, zmax)"
                },
                robot.motion_pattern().name(),
                b.len()
            )));
        }
    };
    r.validate(dim).map_err(value_error)?;
    Ok(r)
}

#[allow(clippy::too_many_arguments)]
pub fn workspace(
    robot: &Robot,
    py: Python<'_>,
    resolution: Option<usize>,
    region_box: Option<Vec<f64>>,
    orientation: Option<Vec<f64>>,
    criteria: Option<Vec<String>>,
    method: Option<&str>,
    wrench: Option<Vec<f64>>,
    wrench_box: Option<Vec<f64>>,
    boundary: &str,
    chord: f64,
    volume_convention: &str,
) -> PyResult<WorkspaceResult> {
    let convention: VolumeConvention = volume_convention
        .parse()
        .map_err(|e: String| value_error(format!("volume_convention: {e}")))?;
    let geo = robot.geometry();
    let desc = &robot.desc;
    let motion = geo.motion();
    let (dof, dim) = (geo.dof(), motion.space_dim());
    cdpr_wrench::require_enough_cables(robot.geometry(), "the wrench-feasible workspace")
        .map_err(value_error)?;
    let method = match method {
        Some(m) => parse_method(m)?,
        None if geo.cable_count() == dof => Method::Exact,
        None => Method::L2,
    };
    let specs = specs(robot, criteria)?;
    let rot = rotation(motion, orientation.as_deref().unwrap_or(&[]))?;
    let region = region(robot, region_box)?;
    let max = if dim == 2 { 4000 } else { 300 };
    let m = resolution.unwrap_or(if dim == 2 { 50 } else { 20 });
    if !(1..=max).contains(&m) {
        return Err(value_error(format!(
            "resolution must lie in [1, {max}] for a {dim}-D grid, got {m}"
        )));
    }
    let w = match &wrench {
        Some(w) => cdpr_wrench::wrench_from_slice(motion, w).map_err(value_error)?,
        None => DVector::zeros(dof),
    };
    desc.require_no_passive_springs("workspace")
        .map_err(value_error)?;
    let w_ext = w + desc
        .platform
        .gravity_wrench(motion, &Pose::new(Vector3::zeros(), rot));
    if specs.iter().any(|s| matches!(s, Spec::Capacity(_))) {
        match &wrench_box {
            None => {
                return Err(value_error(
                    "criteria capacity needs wrench_box (half-widths per wrench component)",
                ));
            }
            Some(b) if b.len() != dof => {
                return Err(value_error(format!(
                    "wrench_box needs {dof} half-widths (one per wrench component), got {}",
                    b.len()
                )));
            }
            Some(_) => {}
        }
    }
    let stiffness_spec = |s: &Spec| matches!(s, Spec::Stiffness(_) | Spec::StiffnessFloor(..));
    let needs_stiffness = specs.iter().any(stiffness_spec)
        || (method == Method::Sotda && specs.contains(&Spec::Tension));
    if needs_stiffness && desc.axial_stiffness.is_none() {
        return Err(value_error(
            "the stiffness criterion and the sotda method need `axial_stiffness` (E·S, N) on \
             every cable of the robot",
        ));
    }
    if specs.iter().any(stiffness_spec) && !specs.contains(&Spec::Tension) {
        return Err(value_error(
            "criteria stiffness:K needs the tension criterion too (K uses its tensions)",
        ));
    }
    let crit = specs
        .iter()
        .map(|s| {
            Ok(match s {
                Spec::Tension => Criterion::TensionFeasible {
                    method,
                    wrench: w_ext.clone(),
                },
                Spec::Length(l) => Criterion::MinCableLength(*l),
                Spec::Det(d) => Criterion::MinJacobianDeterminant(*d),
                Spec::WrenchClosure => Criterion::WrenchClosure,
                Spec::Capacity(m) => Criterion::CapacityMargin {
                    required: RequiredWrenchSet::boxed(
                        w_ext.clone(),
                        DVector::from_column_slice(wrench_box.as_deref().unwrap_or_default()),
                    )
                    .map_err(value_error)?,
                    min_margin: *m,
                },
                Spec::Isotropic(f) => Criterion::IsotropicForceUnderLoad {
                    min: *f,
                    wrench: w_ext.clone(),
                },
                Spec::Stiffness(k) => Criterion::Stiffness { min_eigenvalue: *k },
                Spec::StiffnessFloor(kt, kr) => Criterion::StiffnessFloor {
                    translational: *kt,
                    rotational: *kr,
                },
                Spec::Interference(d) => Criterion::Interference {
                    min_distance: *d,
                    platform: desc.platform_shape.clone().map(std::sync::Arc::new),
                },
                Spec::Dynamic => {
                    return Err(value_error(
                        "criteria dynamic is not in the Python package yet: use `cdpr workspace --criteria dynamic --acceleration-box …`",
                    ));
                }
            })
        })
        .collect::<PyResult<Vec<_>>>()?;
    let mut eval =
        PoseEvaluator::new(geo.clone(), desc.bounds.clone(), crit).map_err(value_error)?;
    if let Some(es) = &desc.axial_stiffness {
        eval = eval.with_axial_stiffness(es.clone()).map_err(value_error)?;
    }
    eval.validate().map_err(value_error)?;
    let labels: Vec<String> = specs.iter().map(Spec::label).collect();
    let box_list: Vec<f64> = (0..dim)
        .flat_map(|k| [region.min[k], region.max[k]])
        .collect();
    let external_wrench = to_numpy(py, &[dof], w_ext.as_slice().to_vec()).unbind();
    let mut out = WorkspaceResult {
        feasible: None,
        x: None,
        y: None,
        z: None,
        points: None,
        boundaries: None,
        vertices: None,
        faces: None,
        surface_area: None,
        area: 0.0,
        area_cells: None,
        area_points: None,
        volume_convention: None,
        volume: None,
        cell_area: None,
        feasible_points: None,
        total_points: None,
        criteria: labels,
        method: method.name().into(),
        external_wrench,
        region: box_list,
    };
    match boundary {
        "grid" => {
            let grid = Grid::new(m, region);
            let ws = crate::parallel(py, || {
                constant_orientation_workspace(&eval, &rot, &grid).map_err(value_error)
            })?;
            fill_grid(py, &mut out, &grid, ws, convention);
        }
        "mesh" => {
            let grid = Grid::new(m, region);
            let mesh = crate::parallel(py, || {
                boundary_mesh(&eval, &rot, &grid, &MeshSettings::default()).map_err(value_error)
            })?;
            fill_grid(py, &mut out, &grid, mesh.grid.clone(), convention);
            let v: Vec<f64> = mesh.vertices.iter().flatten().copied().collect();
            let f: Vec<i64> = mesh
                .triangles
                .iter()
                .flatten()
                .map(|&i| i64::from(i))
                .collect();
            out.vertices = Some(to_numpy(py, &[mesh.vertices.len(), 3], v).unbind());
            out.faces = Some(to_numpy(py, &[mesh.triangles.len(), 3], f).unbind());
            out.surface_area = Some(mesh.surface_area);
            out.volume = Some(mesh.volume);
        }
        "chord" => {
            if dim != 2 {
                return Err(value_error(format!(
                    "boundary=\"chord\" maps boundary curves in the plane; this robot is `{}` \
                     (use boundary=\"grid\")",
                    motion.name()
                )));
            }
            let phi = orientation
                .as_deref()
                .and_then(|o| o.first().copied())
                .unwrap_or(0.0);
            let settings = ChordSettings {
                chord,
                seed_resolution: m,
                ..ChordSettings::default()
            };
            let ws = crate::parallel(py, || {
                chord_workspace(&eval, phi, &region, &settings).map_err(value_error)
            })?;
            out.area = ws.area;
            out.boundaries = Some(
                ws.boundaries
                    .iter()
                    .map(|b| {
                        let v: Vec<f64> = b.vertices.iter().flatten().copied().collect();
                        to_numpy(py, &[b.vertices.len(), 2], v).unbind()
                    })
                    .collect(),
            );
        }
        other => {
            return Err(value_error(format!(
                "boundary: `{other}` is not one of grid, chord, mesh"
            )));
        }
    }
    Ok(out)
}

/// The grid fields of a result from grid verdicts.
fn fill_grid(
    py: Python<'_>,
    out: &mut WorkspaceResult,
    grid: &Grid,
    ws: GridWorkspace,
    convention: VolumeConvention,
) {
    let dim = ws.dim;
    let p = grid.resolution + 1;
    let axis = |stride: usize, k: usize| -> Vec<f64> {
        (0..p).map(|i| grid.point(dim, i * stride)[k]).collect()
    };
    out.x = Some(to_numpy(py, &[p], axis(1, 0)).unbind());
    out.y = Some(to_numpy(py, &[p], axis(p, 1)).unbind());
    let measure = ws.measure(convention);
    if dim == 3 {
        out.z = Some(to_numpy(py, &[p], axis(p * p, 2)).unbind());
        out.volume = Some(measure);
    }
    let pts: Vec<f64> = ws
        .feasible_positions()
        .flat_map(|u| u.as_slice()[..dim].to_vec())
        .collect();
    out.points = Some(to_numpy(py, &[ws.feasible_points, dim], pts).unbind());
    out.area = measure;
    out.area_cells = Some(ws.clipped_area);
    out.area_points = Some(ws.area);
    out.volume_convention = Some(convention.name().into());
    out.cell_area = Some(ws.cell_area);
    out.feasible_points = Some(ws.feasible_points);
    out.total_points = Some(ws.total_points);
    out.feasible = Some(to_numpy(py, &vec![p; dim], ws.feasible).unbind());
}
