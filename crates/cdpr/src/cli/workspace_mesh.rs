//! `cdpr workspace --boundary mesh` and `--section AXIS=VALUE`: the boundary of a 3-D workspace as
//! a closed triangle mesh (its volume, files), and exact plane sections by the chord method.

use super::criteria::CriteriaSetup;
use super::region::{box_json, draw_pose, measure_json, save_plot};
use super::{CliError, print_json};
use cdpr::RobotDescription;
use cdpr::kinematics::{MotionPattern, Pose};
use cdpr::plot::WorkspacePlot;
use cdpr::workspace::{
    BoundaryMesh, BoxFace, ChordSettings, ChordWorkspace, Grid, GridWorkspace, MeshSettings,
    PoseEvaluator, Region, Section, VolumeConvention, boundary_mesh, chord_section,
};
use nalgebra::{Rotation3, Vector2};
use serde_json::{Value, json};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;
use std::time::Instant;

/// The options of `cdpr workspace` that the mesh and section modes check against each other.
pub struct Options<'a> {
    /// `--boundary`.
    pub boundary: &'a str,
    /// `--mesh`.
    pub mesh: Option<&'a Path>,
    /// `--points`.
    pub points: Option<&'a Path>,
    /// `--section`.
    pub section: Option<&'a str>,
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

/// Usage errors, before any computation: `--boundary mesh` and `--section` need a robot moving
/// in space; `--mesh` needs `--boundary mesh`; `--points` needs grid verdicts.
pub fn check_options(o: &Options<'_>, motion: MotionPattern) -> Result<(), CliError> {
    let dim = motion.space_dim();
    if o.boundary == "mesh" && dim != 3 {
        return Err(format!(
            "--boundary mesh builds the boundary surface of a workspace in space; this robot is \
             `{}` (moving in a plane): use --boundary chord, the chord method, for its exact \
             boundary curves",
            motion.name()
        )
        .into());
    }
    if let Some(path) = o.mesh {
        if o.boundary != "mesh" {
            return Err("--mesh FILE writes the boundary mesh: add --boundary mesh".into());
        }
        mesh_format(path)?;
    }
    if let Some(s) = o.section {
        if dim != 3 {
            return Err(format!(
                "--section {s} cuts a workspace in space; this robot is `{}` (moving in a \
                 plane): use --boundary chord for its exact boundary",
                motion.name()
            )
            .into());
        }
        if o.boundary == "mesh" {
            return Err(
                "--section and --boundary mesh are separate runs: the section is a 2-D chord \
                 boundary, the mesh a 3-D surface"
                    .into(),
            );
        }
    }
    if o.points.is_some() && (o.section.is_some() || o.boundary == "chord") {
        return Err(
            "--points writes grid verdicts: use it with --boundary grid or --boundary mesh".into(),
        );
    }
    Ok(())
}

/// `AXIS=VALUE` (x, y or z; metres) within the box along that axis.
pub fn parse_section(s: &str, region: &Region) -> Result<Section, CliError> {
    let (axis, value) = s
        .split_once('=')
        .ok_or_else(|| format!("--section {s}: expected AXIS=VALUE, e.g. z=1.2"))?;
    let axis = match axis.trim() {
        "x" => 0,
        "y" => 1,
        "z" => 2,
        a => return Err(format!("--section {s}: axis `{a}` is not x, y or z").into()),
    };
    let value: f64 = value
        .trim()
        .parse()
        .map_err(|_| format!("--section {s}: `{value}` is not a number"))?;
    let section = Section { axis, value };
    section.validate(region).map_err(|_| {
        format!(
            "--section {s}: {} = {value} is outside the box [{}, {}] (m)",
            ["x", "y", "z"][axis],
            region.min[axis],
            region.max[axis]
        )
    })?;
    Ok(section)
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

/// What the mesh and section modes share with the rest of `cdpr workspace`.
pub struct Context<'a> {
    /// Robot file.
    pub desc: &'a RobotDescription,
    /// Criteria.
    pub setup: &'a CriteriaSetup,
    /// Evaluator at the orientation.
    pub eval: &'a PoseEvaluator,
    /// Orientation.
    pub rotation: &'a Rotation3<f64>,
    /// Orientation as given (for reports).
    pub orientation: &'a [f64],
    /// w_ext (N, N·m).
    pub w_ext: &'a [f64],
    /// Search box.
    pub region: &'a Region,
    /// Grid resolution M (with --section: of the grid seeding the walks).
    pub m: usize,
    /// How the grid count turns points into a volume (`grid_volume`).
    pub volume_convention: VolumeConvention,
    /// `--draw-pose`.
    pub draw_pose: Option<&'a [f64]>,
    /// `--plot` file.
    pub plot: Option<&'a Path>,
    /// `--json`.
    pub json: bool,
}

/// `--boundary mesh`.
pub fn run_mesh(
    r: &Context<'_>,
    mesh_file: Option<&Path>,
    points: Option<&Path>,
) -> Result<(), CliError> {
    let grid = Grid::new(r.m, *r.region);
    let start = Instant::now();
    let mesh = boundary_mesh(r.eval, r.rotation, &grid, &MeshSettings::default())?;
    let seconds = start.elapsed().as_secs_f64();
    if let Some(path) = mesh_file {
        write_mesh(&mesh, path)?;
    }
    if let Some(path) = points {
        write_points(&mesh.grid, path)?;
    }
    if let Some(path) = r.plot {
        save_mesh_plot(r, &mesh, path)?;
    }
    if r.json {
        return print_json(&mesh_json(r, &mesh, seconds));
    }
    print_mesh(r, &mesh, seconds);
    if let Some(p) = mesh_file {
        println!("mesh written to {}", p.display());
    }
    if let Some(p) = points {
        println!("grid verdicts written to {}", p.display());
    }
    if let Some(p) = r.plot {
        println!("plot written to {}", p.display());
    }
    Ok(())
}

/// The certified surface itself: an isometric view with three sections (.svg/.png) or the
/// interactive page (.html), not the grid cells.
fn save_mesh_plot(r: &Context<'_>, mesh: &BoundaryMesh, path: &Path) -> Result<(), CliError> {
    let desc = r.desc;
    let pose = draw_pose(&desc.robot, r.draw_pose, r.region, r.rotation)?;
    super::region::save_mesh_scene_plot(
        desc,
        &pose,
        mesh,
        if r.orientation.is_empty() {
            format!("{}: constant-orientation workspace", desc.name)
        } else {
            format!(
                "{}: constant-orientation workspace, orientation {}",
                desc.name,
                super::pose_text(r.orientation, 0)
            )
        },
        vec![format!(
            "volume {} m³ (boundary mesh, m = {}); grid count {} m³ ({}); {}",
            super::num(mesh.volume),
            r.m,
            super::num(mesh.grid.measure(r.volume_convention)),
            r.volume_convention,
            r.setup.labels().join(", ")
        )],
        path,
    )
}

/// The `--json` answer of `--boundary mesh`.
fn mesh_json(r: &Context<'_>, mesh: &BoundaryMesh, seconds: f64) -> Value {
    let ws = &mesh.grid;
    let mut faces = serde_json::Map::new();
    for f in BoxFace::ALL {
        faces.insert(
            f.name().into(),
            Value::Bool(mesh.box_faces_reached[f as usize]),
        );
    }
    let mut v = json!({
        "robot": r.desc.name,
        "method": "mesh",
        "orientation": r.orientation,
        "external_wrench": r.w_ext,
        "criteria": r.setup.labels(),
        "tension_method": r.setup.method.name(),
        "box": box_json(r.region, 3),
        "resolution": r.m,
        "dimension": 3,
        "feasible_points": ws.feasible_points,
        "total_points": ws.total_points,
        "cell_area": ws.cell_area,
        "grid_volume": ws.measure(r.volume_convention),
        "surface_area": mesh.surface_area,
        "cap_area": mesh.cap_area,
        "components": mesh.components,
        "regions": mesh.regions(),
        "cavities": mesh.cavities(),
        "shells": mesh.shells.iter().map(|s| json!({
            "volume": s.volume, "area": s.area, "genus": s.genus,
            "triangles": s.triangles, "vertices": s.vertices,
        })).collect::<Vec<_>>(),
        "box_faces_reached": faces,
        "tolerance": mesh.tolerance,
        "watertight": mesh.edge_defects() == 0,
        "evaluations": mesh.evaluations,
        "seconds": seconds,
        "vertices": mesh.vertices,
        "triangles": mesh.triangles,
    });
    // The grid's fields as in grid mode (`area` in the chosen convention, both
    // conventions); then `volume` is the mesh's.
    measure_json(&mut v, ws, r.volume_convention);
    v["volume"] = json!(mesh.volume);
    v
}

/// The text answer of `--boundary mesh` (before the list of files written).
fn print_mesh(r: &Context<'_>, mesh: &BoundaryMesh, seconds: f64) {
    let ws = &mesh.grid;
    let defects = mesh.edge_defects();
    let reached: Vec<&str> = BoxFace::ALL
        .iter()
        .filter(|f| mesh.box_faces_reached[**f as usize])
        .map(|f| f.name())
        .collect();
    header(r, "boundary mesh of the constant-orientation workspace");
    println!(
        "grid m = {} over {} (m): {} of {} points feasible; grid count {:.6} m³ ({} convention)",
        r.m,
        box_json(r.region, 3),
        ws.feasible_points,
        ws.total_points,
        ws.measure(r.volume_convention),
        r.volume_convention
    );
    println!(
        "volume {:.6} m³ (enclosed by the mesh; vertices within {:.1e} m of the boundary)",
        mesh.volume,
        0.5 * mesh.tolerance
    );
    println!(
        "surface {:.6} m² (of which {:.6} m² on the box faces); {} component(s): {} region(s), \
         {} cavit{}",
        mesh.surface_area,
        mesh.cap_area,
        mesh.components,
        mesh.regions(),
        mesh.cavities(),
        if mesh.cavities() == 1 { "y" } else { "ies" }
    );
    for (k, s) in mesh.shells.iter().enumerate() {
        println!(
            "  shell {}: volume {:+.6} m³, area {:.6} m², genus {}, {} triangles",
            k + 1,
            s.volume,
            s.area,
            s.genus,
            s.triangles
        );
    }
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
        mesh.vertices.len(),
        mesh.triangles.len(),
        if defects == 0 {
            "closed and consistently oriented".to_string()
        } else {
            format!("{defects} unpaired edges (please report)")
        },
        mesh.evaluations,
        seconds
    );
}

fn header(r: &Context<'_>, what: &str) {
    println!(
        "robot {}: {what}{}, w_ext {}",
        r.desc.name,
        super::region::at_orientation(r.orientation),
        super::wrench_text(r.w_ext, r.desc.robot.motion().translation_dof())
    );
    println!(
        "criteria: {} (tensions: {})",
        r.setup.labels().join(", "),
        r.setup.method.name()
    );
}

/// Adds the chord method's result fields (`area`, `boundaries`, `signed_areas`, `bifurcations`,
/// `abandoned`, `evaluations`) to a JSON object.
pub fn with_chord_fields(mut v: Value, ws: &ChordWorkspace) -> Value {
    let b = &ws.boundaries;
    v["area"] = json!(ws.area);
    v["boundaries"] = json!(b.iter().map(|p| &p.vertices).collect::<Vec<_>>());
    v["signed_areas"] = json!(b.iter().map(|p| p.signed_area()).collect::<Vec<_>>());
    v["bifurcations"] = json!(
        b.iter()
            .map(|p| p
                .bifurcations
                .iter()
                .map(|&k| p.vertices[k])
                .collect::<Vec<_>>())
            .collect::<Vec<_>>()
    );
    v["abandoned"] = json!(ws.abandoned);
    v["evaluations"] = json!(ws.evaluations);
    v
}

/// `--section AXIS=VALUE`.
pub fn run_section(r: &Context<'_>, section: Section, chord: f64) -> Result<(), CliError> {
    let desc = r.desc;
    let robot = &desc.robot;
    let settings = ChordSettings {
        chord,
        seed_resolution: r.m,
        ..ChordSettings::default()
    };
    let ws = chord_section(r.eval, r.rotation, section, r.region, &settings)?;
    let names = ["x", "y", "z"];
    let [a, b] = section.in_plane_axes();
    let plane = format!("{} = {}", names[section.axis], section.value);
    let regions = ws
        .boundaries
        .iter()
        .filter(|p| p.signed_area() > 0.0)
        .count();
    let holes = ws.boundaries.len() - regions;
    if let Some(path) = r.plot {
        // The robot drawn at --draw-pose, or at the box centre moved into the plane.
        let mut pose = draw_pose(robot, r.draw_pose, r.region, r.rotation)?;
        if r.draw_pose.is_none() {
            pose = Pose::new(
                section.embed(Vector2::new(pose.position[a], pose.position[b])),
                pose.rotation,
            );
        }
        let polys: Vec<Vec<(f64, f64)>> = ws
            .boundaries
            .iter()
            .map(|p| p.vertices.iter().map(|v| (v[0], v[1])).collect())
            .collect();
        let (lo, hi) = (r.region.min, r.region.max);
        let fig = WorkspacePlot {
            title: format!("{}: workspace section {plane} m", desc.name),
            anchor_names: cdpr::plot::cable_names(&desc.cable_names),
            boundaries: polys,
            fill_boundaries: true,
            frame: vec![
                (lo[a], lo[b]),
                (hi[a], lo[b]),
                (hi[a], hi[b]),
                (lo[a], hi[b]),
            ],
            markers: ws
                .boundaries
                .iter()
                .flat_map(|p| {
                    p.bifurcations
                        .iter()
                        .map(|&k| (p.vertices[k][0], p.vertices[k][1]))
                })
                .collect(),
            notes: vec![
                format!(
                    "area {:.4} m², {regions} region(s), {holes} hole(s); chord method, d = {} m, \
                     vertices on the boundary to 1e-8 m",
                    ws.area, chord
                ),
                format!(
                    "{}{}; thin rectangle: the search box; robot projected at its draw pose",
                    if r.orientation.is_empty() {
                        String::new()
                    } else {
                        format!("orientation {}; ", super::pose_text(r.orientation, 0))
                    },
                    r.setup.labels().join(", ")
                ),
            ],
            axis_names: Some((format!("{} (m)", names[a]), format!("{} (m)", names[b]))),
            ..WorkspacePlot::default()
        }
        .with_robot_projected(robot, &pose, [a, b]);
        save_plot(&fig, path)?;
    }
    if r.json {
        return print_json(&with_chord_fields(
            json!({
                "robot": desc.name,
                "method": "chord",
                "section": {
                    "axis": names[section.axis],
                    "value": section.value,
                    "plane_axes": [names[a], names[b]],
                },
                "orientation": r.orientation,
                "external_wrench": r.w_ext,
                "criteria": r.setup.labels(),
                "tension_method": r.setup.method.name(),
                "box": box_json(r.region, 3),
                "chord": chord,
            }),
            &ws,
        ));
    }
    header(r, &format!("workspace section {plane} m"));
    println!(
        "area {:.6} m² in the ({}, {}) plane: {regions} region(s), {holes} hole(s), chord d = {} m, \
         {} pose evaluations",
        ws.area, names[a], names[b], chord, ws.evaluations
    );
    for (k, p) in ws.boundaries.iter().enumerate() {
        println!(
            "  boundary {}: {} vertices, signed area {:+.6} m², perimeter {:.4} m, {} bifurcation \
             point(s)",
            k + 1,
            p.vertices.len(),
            p.signed_area(),
            p.perimeter(),
            p.bifurcations.len()
        );
    }
    if ws.abandoned > 0 {
        println!(
            "warning: {} boundary walk(s) abandoned (curves missing)",
            ws.abandoned
        );
    }
    if let Some(p) = r.plot {
        println!("plot written to {}", p.display());
    }
    Ok(())
}
