//! The pieces the region commands share (`workspace`, `orientations`, `dextrous`, `synthesize`,
//! `isotropic`): orientation and box from the command line, grids mapped in parallel with a
//! progress bar, the dextrous verdicts of a grid, plots and their titles, box and measure JSON.

use super::CliError;
use cdpr::RobotDescription;
use cdpr::kinematics::{MotionPattern, Pose, Robot};
use cdpr::plot::{Figure, Panels, WorkspacePlot};
use cdpr::workspace::{GridWorkspace, Region};
use indicatif::ProgressBar;
use nalgebra::{Rotation3, Vector3};
use std::io::IsTerminal;
use std::path::Path;

/// The platform orientation from command-line numbers (see [`cdpr::api::region::rotation`]).
pub fn rotation(motion: MotionPattern, q: Option<&[f64]>) -> Result<Rotation3<f64>, CliError> {
    Ok(cdpr::api::region::rotation(motion, q)?)
}

/// Grid resolution (see [`cdpr::api::region::resolution`]).
pub fn resolution(m: Option<usize>, dim: usize, default_2d: usize) -> Result<usize, CliError> {
    Ok(cdpr::api::region::resolution(m, dim, default_2d)?)
}

/// A progress bar on stderr counting `len` chunks, hidden unless stderr is a terminal.
pub fn progress(len: usize) -> ProgressBar {
    if std::io::stderr().is_terminal() {
        ProgressBar::new(len as u64)
    } else {
        ProgressBar::hidden()
    }
}

/// The pose at which the robot is drawn: `--draw-pose` or the box centre at `rotation`.
pub fn draw_pose(
    robot: &Robot,
    q: Option<&[f64]>,
    region: &Region,
    rotation: &Rotation3<f64>,
) -> Result<Pose, CliError> {
    match q {
        Some(q) => Ok(Pose::from_coordinates(robot.motion(), q)?),
        None => {
            let mut c = (region.min + region.max) * 0.5;
            if robot.motion().space_dim() == 2 {
                c.z = 0.0;
            }
            Ok(Pose::new(c, *rotation))
        }
    }
}

/// A figure's title (robot and what is drawn) and the line under it: orientation (rad), load
/// (N, N·m) and tension method, e.g. "orientation φ = 0.1 rad; load w_ext = [0, -10, 0] (N, N, N·m);
/// tensions l2".
pub fn plot_title(
    robot: &str,
    what: &str,
    motion: MotionPattern,
    orientation: &[f64],
    w_ext: &[f64],
    method: &str,
) -> (String, String) {
    let orientation = match motion {
        MotionPattern::Planar => format!(
            "orientation φ = {} rad; ",
            cdpr::plot::tick(orientation.first().copied().unwrap_or(0.0))
        ),
        MotionPattern::Spatial => format!("orientation [{}] rad; ", tick_list(orientation)),
        _ => String::new(),
    };
    (
        format!("{robot}: {what}"),
        format!("{orientation}{}", load_text(motion, w_ext, method)),
    )
}

/// "load w_ext = [0, -10, 0] (N, N, N·m); tensions l2".
pub fn load_text(motion: MotionPattern, w_ext: &[f64], method: &str) -> String {
    let units = match motion {
        MotionPattern::Planar => "N, N, N·m",
        MotionPattern::Spatial => "forces N, moments N·m",
        _ => "N",
    };
    format!(
        "load w_ext = [{}] ({units}); tensions {}",
        tick_list(w_ext),
        method
    )
}

fn tick_list(v: &[f64]) -> String {
    v.iter()
        .map(|x| cdpr::plot::tick(*x))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Axis label of a length coordinate (robot files are in SI units, docs/robot-file.md).
pub fn length_axis(axis: &str) -> String {
    format!("{axis} (m)")
}

/// What an empty grid or chord result draws in the middle of the chart.
pub const EMPTY_WORKSPACE: &str = "no feasible pose in the box";

/// The planar workspace figure: anchors, cables at `pose`, feasible cells, outlined (and
/// filled) boundaries; a note in the middle when nothing is feasible.
pub fn workspace_plot(
    robot: &Robot,
    pose: &Pose,
    ws: Option<&GridWorkspace>,
    boundaries: Vec<Vec<(f64, f64)>>,
    title: String,
    notes: Vec<String>,
) -> WorkspacePlot {
    let mut feasible_points = Vec::new();
    let mut cell = (0.0, 0.0);
    if let Some(ws) = ws {
        cell = grid_cell(ws);
        feasible_points = layer_points(ws, 0);
    }
    let fill = ws.is_none() && !boundaries.is_empty();
    let empty = feasible_points.is_empty() && boundaries.is_empty();
    WorkspacePlot {
        title,
        feasible_points,
        cell,
        boundaries,
        fill_boundaries: fill,
        notes,
        axis_names: Some((length_axis("x"), length_axis("y"))),
        empty_message: empty.then(|| EMPTY_WORKSPACE.to_string()),
        ..WorkspacePlot::default()
    }
    .with_robot(robot, pose)
}

/// The 3-D figure (`.html` viewer, or isometric view and sections) of a spatial or point3
/// workspace on a grid: the surface of the grid cells, the robot at `pose`.
pub fn save_scene_plot(
    desc: &RobotDescription,
    pose: &Pose,
    ws: &GridWorkspace,
    (title, mut legend): (String, Vec<String>),
    cable_model: Option<&str>,
    path: &Path,
) -> Result<(), CliError> {
    let (cable_curves, note) = super::cable_model::draw_curves(desc, cable_model, pose)?;
    legend.extend(note);
    let (vertices, triangles) = cdpr::plot::grid_surface(ws);
    let r = &ws.grid.region;
    let scene = cdpr::plot::Scene {
        title,
        vertices,
        triangles,
        region: ([r.min.x, r.min.y, r.min.z], [r.max.x, r.max.y, r.max.z]),
        legend,
        mesh_label: format!(
            "grid cells of the feasible points (m = {})",
            ws.grid.resolution
        ),
        anchor_names: cdpr::plot::cable_names(&desc.cable_names),
        ..cdpr::plot::Scene::default()
    }
    .with_robot(&desc.robot, pose, desc.platform_shape.as_ref());
    let scene = cdpr::plot::Scene {
        cable_curves,
        ..scene
    };
    cdpr::plot::save_scene(&scene, path)?;
    Ok(())
}

/// The 3-D figure of a boundary mesh (`--boundary mesh`): the certified surface in place of the
/// grid cells.
pub fn save_mesh_scene_plot(
    desc: &RobotDescription,
    pose: &Pose,
    mesh: &cdpr::workspace::BoundaryMesh,
    (title, mut legend): (String, Vec<String>),
    cable_model: Option<&str>,
    path: &Path,
) -> Result<(), CliError> {
    let (cable_curves, note) = super::cable_model::draw_curves(desc, cable_model, pose)?;
    legend.extend(note);
    let r = &mesh.grid.grid.region;
    let scene = cdpr::plot::Scene {
        title,
        vertices: mesh.vertices.clone(),
        triangles: mesh.triangles.clone(),
        region: ([r.min.x, r.min.y, r.min.z], [r.max.x, r.max.y, r.max.z]),
        legend,
        mesh_label: format!("boundary mesh ({})", vertex_placement(mesh.tolerance)),
        anchor_names: cdpr::plot::cable_names(&desc.cable_names),
        ..cdpr::plot::Scene::default()
    }
    .with_robot(&desc.robot, pose, desc.platform_shape.as_ref());
    let scene = cdpr::plot::Scene {
        cable_curves,
        ..scene
    };
    cdpr::plot::save_scene(&scene, path)?;
    Ok(())
}

/// Whether `path` names an HTML page (only 3-D workspaces have one).
pub fn is_html(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("html"))
}

/// The (Δx, Δy) spacing of a grid.
fn grid_cell(ws: &GridWorkspace) -> (f64, f64) {
    let m = ws.grid.resolution as f64;
    let ext = ws.grid.region.extent();
    (ext.x / m, ext.y / m)
}

/// The feasible (x, y) points of z-layer `k` of a grid (the only layer of a planar grid).
fn layer_points(ws: &GridWorkspace, k: usize) -> Vec<(f64, f64)> {
    let p = ws.grid.points_per_axis();
    let first = if ws.dim == 3 { k * p * p } else { 0 };
    (first..first + p * p)
        .filter(|&idx| ws.feasible[idx])
        .map(|idx| {
            let u = ws.point(idx);
            (u.x, u.y)
        })
        .collect()
}

/// Number of z-slices drawn for a 3-D workspace.
pub const SLICES: usize = 4;

/// The z-layers drawn for a 3-D grid of resolution m: the layers nearest the centres of
/// [`SLICES`] equal bands of the box height, without repeats.
pub fn slice_layers(m: usize) -> Vec<usize> {
    let mut layers: Vec<usize> = (0..SLICES)
        .map(|j| (((j as f64 + 0.5) / SLICES as f64) * m as f64).round() as usize)
        .collect();
    layers.dedup();
    layers
}

/// A 3-D grid workspace as [`SLICES`] z-slices side by side (2 × 2), each with the frame anchors
/// seen from above (coinciding anchors share a label) and the cables at `pose` moved to the
/// slice height; the title and notes above all slices.
pub fn workspace_slices(
    robot: &Robot,
    pose: &Pose,
    ws: &GridWorkspace,
    title: String,
    notes: Vec<String>,
) -> Panels<WorkspacePlot> {
    let p = ws.grid.points_per_axis();
    let panels = slice_layers(ws.grid.resolution)
        .into_iter()
        .map(|k| {
            let z = ws.point(k * p * p).z;
            let points = layer_points(ws, k);
            let count = points.len();
            let mut at = *pose;
            at.position.z = z;
            WorkspacePlot {
                title: format!("slice z = {}", cdpr::plot::tick(z)),
                notes: vec![format!("{count} of {} points feasible", p * p)],
                empty_message: (count == 0).then(|| EMPTY_WORKSPACE.to_string()),
                feasible_points: points,
                cell: grid_cell(ws),
                axis_names: Some((length_axis("x"), length_axis("y"))),
                ..WorkspacePlot::default()
            }
            .with_robot(robot, &at)
        })
        .collect();
    Panels {
        title,
        notes,
        columns: 2,
        panel_size: (640, 680),
        panels,
    }
}

/// Writes a plot (SVG or PNG by extension).
pub fn save_plot(fig: &impl Figure, path: &Path) -> Result<(), CliError> {
    cdpr::plot::save(fig, path)?;
    Ok(())
}

/// The grid workspace figure: one chart for planar robots, z-slices for 3-D ones.
pub fn save_grid_plot(
    desc: &RobotDescription,
    pose: &Pose,
    ws: &GridWorkspace,
    title: String,
    notes: Vec<String>,
    path: &Path,
) -> Result<(), CliError> {
    let (robot, names) = (&desc.robot, cdpr::plot::cable_names(&desc.cable_names));
    if ws.dim == 3 {
        let mut fig = workspace_slices(robot, pose, ws, title, notes);
        for p in &mut fig.panels {
            p.anchor_names.clone_from(&names);
        }
        save_plot(&fig, path)
    } else {
        let mut fig = workspace_plot(robot, pose, Some(ws), Vec::new(), title, notes);
        fig.anchor_names = names;
        save_plot(&fig, path)
    }
}

/// ` at orientation (φ rad, …)` for a robot with an orientation, nothing for a point robot
/// (titles and headers used to print `orientation []`).
pub fn at_orientation(orientation: &[f64]) -> String {
    if orientation.is_empty() {
        String::new()
    } else {
        format!(" at orientation {}", super::pose_text(orientation, 0))
    }
}

/// The box of a report's numbers XMIN, XMAX, YMIN, YMAX[, ZMIN, ZMAX] (m).
pub fn box_region(b: &[f64]) -> Region {
    match b {
        [x0, x1, y0, y1] => Region::planar(*x0, *x1, *y0, *y1),
        _ => Region::cuboid(
            Vector3::new(b[0], b[2], b[4]),
            Vector3::new(b[1], b[3], b[5]),
        ),
    }
}

/// The two header lines of a region answer: "robot R: WHAT at orientation (…), w_ext […]" (no
/// orientation for a point robot) and "criteria: … (tensions: METHOD)"; `forces` is the number
/// of force components of the wrench (the rest are moments).
pub fn print_header(
    robot: &str,
    what: &str,
    orientation: &[f64],
    w_ext: &[f64],
    forces: usize,
    criteria: &[String],
    method: &str,
) {
    println!(
        "robot {robot}: {what}{}, w_ext {}",
        at_orientation(orientation),
        super::wrench_text(w_ext, forces)
    );
    println!("criteria: {} (tensions: {method})", criteria.join(", "));
}

/// "vertices within 2.0e-8 m of the boundary": the placement of a mesh's vertices (ε/2 along
/// their grid edge), as the text, the figures and the HTML legend say it.
pub fn vertex_placement(tolerance: f64) -> String {
    format!("vertices within {:.1e} m of the boundary", 0.5 * tolerance)
}
