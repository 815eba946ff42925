//! `cdpr workspace --boundary mesh`: a [`MeshRequest`] run by `cdpr-api` (the boundary of a 3-D
//! workspace as a closed triangle mesh and its volume), its report rendered as JSON (the
//! serialised report), text, mesh and point files, or a plot.

use super::region::{draw_pose, save_mesh_scene_plot};
use super::{CliError, num, nums, print_report};
use cdpr::api::{MeshReport, MeshRequest};
use cdpr::workspace::{BoundaryMesh, GridWorkspace};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;
use std::time::Instant;

/// How the report is shown.
pub struct View<'a> {
    /// Pose at which the robot is drawn (motion-pattern coordinates).
    pub draw_pose: Option<&'a [f64]>,
    /// The figure (.svg, .png or .html).
    pub plot: Option<&'a Path>,
    /// The mesh file (.stl, .ply or .obj).
    pub mesh: Option<&'a Path>,
    /// The grid verdicts as CSV.
    pub points: Option<&'a Path>,
    /// One JSON object on stdout.
    pub json: bool,
}

/// Mesh file formats, from the extension.
#[derive(Debug, Clone, Copy, PartialEq)]
enum MeshFormat {
    Stl,
    Ply,
    Obj,
}

fn mesh_format(path: &Path) -> Result<MeshFormat, CliError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("stl") => Ok(MeshFormat::Stl),
        Some("ply") => Ok(MeshFormat::Ply),
        Some("obj") => Ok(MeshFormat::Obj),
        _ => Err(format!(
            "--mesh {}: unknown format (use FILE.stl, FILE.ply or FILE.obj)",
            path.display()
        )
        .into()),
    }
}

/// The options of `cdpr workspace` that exclude each other, checked before any computation:
/// `--mesh` needs `--boundary mesh` and a known format; `--section` is not a mesh; `--points`
/// needs grid verdicts.
pub fn check_options(
    boundary: &str,
    mesh: Option<&Path>,
    points: Option<&Path>,
    section: Option<&str>,
) -> Result<(), CliError> {
    if let Some(path) = mesh {
        if boundary != "mesh" {
            return Err("--mesh FILE writes the boundary mesh: add --boundary mesh".into());
        }
        mesh_format(path)?;
    }
    if section.is_some() && boundary == "mesh" {
        return Err(
            "--section and --boundary mesh are separate runs: the section is a 2-D chord \
             boundary, the mesh a 3-D surface"
                .into(),
        );
    }
    if points.is_some() && (section.is_some() || boundary == "chord") {
        return Err(
            "--points writes grid verdicts: use it with --boundary grid or --boundary mesh".into(),
        );
    }
    Ok(())
}

/// Writes the grid verdicts as CSV.
pub fn write_points(ws: &GridWorkspace, path: &Path) -> Result<(), CliError> {
    let mut w = BufWriter::new(File::create(path).map_err(|e| format!("{}: {e}", path.display()))?);
    ws.write_points_csv(&mut w)?;
    w.flush()?;
    Ok(())
}

fn write_mesh(mesh: &BoundaryMesh, path: &Path) -> Result<(), CliError> {
    let format = mesh_format(path)?;
    let mut w = BufWriter::new(File::create(path).map_err(|e| format!("{}: {e}", path.display()))?);
    match format {
        MeshFormat::Stl => mesh.write_stl(&mut w)?,
        MeshFormat::Ply => mesh.write_ply(&mut w)?,
        MeshFormat::Obj => mesh.write_obj(&mut w)?,
    }
    w.flush()?;
    Ok(())
}

/// Runs the request (timed: JSON `seconds`) and renders its report.
pub fn run(request: &MeshRequest, view: &View<'_>) -> Result<(), CliError> {
    let start = Instant::now();
    let mut report = request.run()?;
    report.seconds = Some(start.elapsed().as_secs_f64());
    if let Some(path) = view.mesh {
        write_mesh(&report.mesh, path)?;
    }
    if let Some(path) = view.points {
        write_points(&report.mesh.grid, path)?;
    }
    if let Some(path) = view.plot {
        save_mesh_plot(request, &report, view.draw_pose, path)?;
    }
    if view.json {
        return print_report(&report);
    }
    print_mesh(&report);
    let written = [
        ("mesh", view.mesh),
        ("grid verdicts", view.points),
        ("plot", view.plot),
    ];
    for (what, path) in written {
        if let Some(p) = path {
            println!("{what} written to {}", p.display());
        }
    }
    Ok(())
}

/// The certified surface itself: an isometric view with three sections (.svg/.png) or the
/// interactive page (.html), not the grid cells.
fn save_mesh_plot(
    request: &MeshRequest,
    r: &MeshReport,
    q: Option<&[f64]>,
    path: &Path,
) -> Result<(), CliError> {
    let desc = request.robot.description();
    let region = &r.mesh.grid.grid.region;
    let rotation = super::region::rotation(desc.robot.motion(), request.orientation.as_deref())?;
    let pose = draw_pose(&desc.robot, q, region, &rotation)?;
    save_mesh_scene_plot(
        desc,
        &pose,
        &r.mesh,
        (
            format!(
                "{}: constant-orientation workspace{}",
                desc.name,
                orientation_suffix(&r.orientation)
            ),
            vec![format!(
                "volume {} m³ (boundary mesh, m = {}); grid count {} m³ ({}); {}",
                num(r.volume),
                r.resolution,
                num(r.grid_volume),
                r.volume_convention,
                r.criteria.join(", ")
            )],
        ),
        request.criteria.cable_model.as_deref(),
        path,
    )
}

/// `, orientation (0.1 rad, …)` in a figure title; nothing for a point robot.
fn orientation_suffix(orientation: &[f64]) -> String {
    if orientation.is_empty() {
        String::new()
    } else {
        format!(", orientation {}", super::pose_text(orientation, 0))
    }
}

/// The text answer (before the list of files written).
fn print_mesh(r: &MeshReport) {
    super::region::print_header(
        &r.robot,
        "boundary mesh of the constant-orientation workspace",
        &r.orientation,
        &r.external_wrench,
        3,
        &r.criteria,
        &r.tension_method,
    );
    println!(
        "grid m = {} over {} m: {} of {} points feasible; grid count {:.6} m³ ({} convention)",
        r.resolution,
        nums(&r.area_box),
        r.feasible_points,
        r.total_points,
        r.grid_volume,
        r.volume_convention
    );
    println!(
        "volume {:.6} m³ (enclosed by the mesh; {})",
        r.volume,
        super::region::vertex_placement(r.tolerance)
    );
    println!(
        "surface {:.6} m² (of which {:.6} m² on the box faces); {} component(s): {} region(s), \
         {} cavit{}",
        r.surface_area,
        r.cap_area,
        r.components,
        r.regions,
        r.cavities,
        if r.cavities == 1 { "y" } else { "ies" }
    );
    for (k, s) in r.shells.iter().enumerate() {
        println!(
            "  shell {}: volume {:+.6} m³, area {:.6} m², genus {}, {} triangles",
            k + 1,
            s.volume,
            s.area,
            s.genus,
            s.triangles
        );
    }
    let reached = r.box_faces_reached.reached();
    println!(
        "box faces reached: {}",
        if reached.is_empty() {
            "none".to_string()
        } else {
            reached.join(", ")
        }
    );
    println!(
        "mesh: {} vertices, {} triangles, {}; {} pose evaluations in {:.3} s",
        r.vertices.len(),
        r.triangles.len(),
        if r.watertight {
            "closed and consistently oriented".to_string()
        } else {
            format!("{} unpaired edges (please report)", r.mesh.edge_defects())
        },
        r.evaluations,
        r.seconds.unwrap_or(0.0)
    );
}
