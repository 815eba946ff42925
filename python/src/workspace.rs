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
use crate::requests::{api_robot, keyword_error};
use crate::tension::parse_method;
use crate::value_error;
use cdpr_api::{ChordRequest, MeshRequest, WorkspaceCriteria, WorkspaceRequest};
use cdpr_workspace::{BoundaryMesh, GridWorkspace, VolumeConvention};
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

/// The keyword arguments of `Robot.workspace` (as `cdpr workspace` takes its flags).
pub struct WorkspaceArgs<'a> {
    pub resolution: Option<usize>,
    pub region_box: Option<Vec<f64>>,
    pub orientation: Option<Vec<f64>>,
    pub criteria: Option<Vec<String>>,
    pub method: Option<&'a str>,
    pub wrench: Option<Vec<f64>>,
    pub wrench_box: Option<Vec<f64>>,
    pub boundary: &'a str,
    pub chord: f64,
    pub volume_convention: &'a str,
    /// The tension method's options (``interior``, ``alternating``, ``p``, ``alpha``).
    pub peer: crate::tension::PeerOptions,
}

/// The criteria of the request of `cdpr workspace` (`--criteria`, `--method`, `--wrench`,
/// `--wrench-box`): one parser and one set of checks for both front ends.
fn criteria(a: &WorkspaceArgs<'_>) -> PyResult<WorkspaceCriteria> {
    Ok(WorkspaceCriteria {
        criteria: a.criteria.as_ref().map(|c| c.join(",")),
        method: a.method.map(parse_method).transpose()?,
        wrench: a.wrench.clone(),
        wrench_box: a.wrench_box.clone(),
        peer: a.peer.to_api(),
        ..WorkspaceCriteria::default()
    })
}

/// The options of `cdpr workspace` as the keyword arguments of `Robot.workspace`.
const KEYWORDS: [(&str, &str); 14] = [
    ("--criteria", "criteria"),
    ("--wrench-box", "wrench_box"),
    ("--acceleration-box", "acceleration_box"),
    ("--wrench", "wrench"),
    ("--box", "box"),
    ("--grid M", "resolution"),
    ("--orientation", "orientation"),
    ("--boundary ", "boundary="),
    ("--chord", "chord"),
    ("--method", "method"),
    ("--interior", "interior"),
    ("--alternating", "alternating"),
    ("--p", "p"),
    ("--alpha", "alpha"),
];

/// A request's error in the words of the keyword arguments.
fn error(e: cdpr_api::ApiError) -> PyErr {
    keyword_error(e, &KEYWORDS)
}

/// The constant-orientation workspace: the `WorkspaceRequest` (grid), `MeshRequest` or
/// `ChordRequest` of `cdpr-api` that `cdpr workspace --boundary grid|mesh|chord` runs, run in
/// parallel with the GIL released, its report turned into the Python result.
pub fn workspace(
    robot: &Robot,
    py: Python<'_>,
    a: &WorkspaceArgs<'_>,
) -> PyResult<WorkspaceResult> {
    let convention: VolumeConvention = a
        .volume_convention
        .parse()
        .map_err(|e: String| value_error(format!("volume_convention: {e}")))?;
    let (robot, criteria) = (api_robot(robot), criteria(a)?);
    let (orientation, area, grid) = (a.orientation.clone(), a.region_box.clone(), a.resolution);
    match a.boundary {
        "grid" => {
            let request = WorkspaceRequest {
                robot,
                criteria,
                orientation,
                area,
                grid,
                volume_convention: convention,
            };
            let r = crate::parallel(py, || request.run().map_err(error))?;
            let mut out = result(
                py,
                &r.external_wrench,
                r.criteria,
                r.tension_method,
                r.area_box,
            );
            fill_grid(py, &mut out, &r.workspace, convention);
            Ok(out)
        }
        "mesh" => {
            let mut request = MeshRequest::new(robot);
            (request.criteria, request.orientation, request.area) = (criteria, orientation, area);
            (request.grid, request.volume_convention) = (grid, convention);
            let r = crate::parallel(py, || request.run().map_err(error))?;
            let mut out = result(
                py,
                &r.external_wrench,
                r.criteria,
                r.tension_method,
                r.area_box,
            );
            fill_grid(py, &mut out, &r.mesh.grid, convention);
            fill_mesh(py, &mut out, &r.mesh);
            Ok(out)
        }
        "chord" => {
            let mut request = ChordRequest::new(robot);
            (request.criteria, request.orientation, request.area) = (criteria, orientation, area);
            (request.grid, request.chord) = (grid, a.chord);
            let r = crate::parallel(py, || request.run().map_err(error))?;
            let mut out = result(
                py,
                &r.external_wrench,
                r.criteria,
                r.tension_method,
                r.area_box,
            );
            out.area = r.curves.area;
            out.boundaries = Some(
                r.curves
                    .boundaries
                    .iter()
                    .map(|b| {
                        let v: Vec<f64> = b.iter().flatten().copied().collect();
                        to_numpy(py, &[b.len(), 2], v).unbind()
                    })
                    .collect(),
            );
            Ok(out)
        }
        other => Err(value_error(format!(
            "boundary: `{other}` is not one of grid, chord, mesh"
        ))),
    }
}

/// A result with the fields every boundary has (the rest filled in after).
fn result(
    py: Python<'_>,
    w_ext: &[f64],
    criteria: Vec<String>,
    method: String,
    region: Vec<f64>,
) -> WorkspaceResult {
    WorkspaceResult {
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
        criteria,
        method,
        external_wrench: to_numpy(py, &[w_ext.len()], w_ext.to_vec()).unbind(),
        region,
    }
}

/// The mesh fields of a result: vertices, faces, surface area and the enclosed volume.
fn fill_mesh(py: Python<'_>, out: &mut WorkspaceResult, mesh: &BoundaryMesh) {
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

/// The grid fields of a result from grid verdicts.
fn fill_grid(
    py: Python<'_>,
    out: &mut WorkspaceResult,
    ws: &GridWorkspace,
    convention: VolumeConvention,
) {
    let (dim, grid) = (ws.dim, &ws.grid);
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
    out.feasible = Some(to_numpy(py, &vec![p; dim], ws.feasible.clone()).unbind());
}
