//! `cdpr orientations`: the orientation workspace at a position (the feasible orientations of a
//! sampled set, as a tilt/torsion map and JSON); and the total-orientation and maximal
//! workspaces behind `cdpr workspace --orientations … --kind total|maximal`.

use super::criteria::CriteriaArgs;
use super::region::{draw_pose, save_mesh_scene_plot, save_scene_plot};
use super::{CliError, Numbers, print_report, request_robot};
use cdpr::api::{
    OrientationWorkspaceReport, OrientationWorkspaceRequest, OrientationsReport,
    OrientationsRequest,
};
use cdpr::plot::HeatMap;
use cdpr::workspace::OrientationSet;
use nalgebra::Rotation3;
use serde_json::json;
use std::path::{Path, PathBuf};

/// The `--orientations` syntax, shared by the help texts.
pub const SYNTAX_HELP: &str = "\
Orientation sets (--orientations, angles in degrees):
  euler:rx=A..B,ry=A..B,rz=A..B,n=N
        a box of XYZ Euler angles (R = Rx(rx) Ry(ry) Rz(rz), as --orientation); an omitted
        angle is 0, a single value (rz=5) fixes it; N values per range, endpoints included
        (default 3): up to N³ orientations.
  tilt:T,torsion=A..B,n=N[,azimuths=K]
        a tilt cone of half-angle T around the base z axis plus a torsion range, in the
        tilt-and-torsion angles of Bonev, Zlatanov & Gosselin (2002):
        R = Rz(φ) Ry(θ) Rz(σ − φ), tilt θ towards azimuth φ, torsion σ. Sampled on N tilt
        rings θ = 0 … T (ring k with round(K k/(N − 1)) azimuths, K = 4(N − 1) by default)
        and N torsions A … B (default torsion 0, N = 3).
  The set is sampled: verdicts at the samples are exact, nothing is claimed between them.";

/// The long help of `cdpr orientations`.
const LONG_HELP: &str = "\
The orientation workspace at a position: which orientations of a sampled set are feasible
there (every criterion of --criteria holds, as in `cdpr workspace`; the platform's gravity is
evaluated at each orientation).

JSON: `position` (m), `orientation_set`, `angle_names`, `count`, `feasible_count`,
`orientations` ([{`angles_deg`, `feasible`}], in sampling order), and `map` {`x`, `y` (angle
names), `x_deg`, `y_deg` (sample values, degrees), `fraction` (rows by y: the fraction of the
samples at (x, y) that are feasible, over the third angle)}.

--plot FILE.svg|png draws that map: tilt θ against torsion σ, coloured by the fraction of
azimuths feasible (tilt sets), or rx against ry coloured by the fraction of rz feasible
(Euler boxes; the two ranged angles when only two vary).";

/// Arguments of `cdpr orientations`.
#[derive(clap::Args)]
#[command(allow_negative_numbers = true, after_long_help = format!("{LONG_HELP}\n\n{SYNTAX_HELP}"))]
pub struct Args {
    /// Robot file (TOML), a `spatial` robot.
    robot: PathBuf,
    /// Platform position x,y,z (m).
    #[arg(long, allow_hyphen_values = true)]
    position: Numbers,
    /// The orientation set, e.g. `tilt:20,torsion=-30..30,n=5` or
    /// `euler:rx=-10..10,ry=-10..10,rz=-20..20,n=5` (degrees; see below).
    #[arg(long, value_parser = set_spec)]
    orientations: String,
    #[command(flatten)]
    criteria: CriteriaArgs,
    /// Write the tilt/torsion map (.svg or .png).
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Write one JSON object on stdout.
    #[arg(long)]
    json: bool,
}

/// Runs `cdpr orientations`: parse → request → run → render.
pub fn run(args: Args) -> Result<(), CliError> {
    let request = OrientationsRequest {
        robot: request_robot(&args.robot)?,
        criteria: args.criteria.to_request(),
        position: args.position.0.clone(),
        orientations: args.orientations.clone(),
    };
    let r = request.run()?;
    if let Some(path) = &args.plot {
        save_map(&r, path)?;
    }
    if args.json {
        return print_report(&r);
    }
    print_orientations(&r);
    if let Some(p) = &args.plot {
        println!("plot written to {}", p.display());
    }
    Ok(())
}

/// The name of the angle the map folds over.
fn folded(r: &OrientationsReport) -> &str {
    &r.angle_names[3 - r.map_axes.0 - r.map_axes.1]
}

/// The tilt/torsion (or Euler) map as a heat map.
fn save_map(r: &OrientationsReport, path: &Path) -> Result<(), CliError> {
    let m = &r.map;
    let (nx, ny) = (m.x_deg.len(), m.y_deg.len());
    let [x, y, z] = r.position;
    let fig = HeatMap {
        title: format!("{}: feasible orientations at ({x}, {y}, {z}) m", r.robot),
        labels: (format!("{} (°)", m.x), format!("{} (°)", m.y)),
        value_label: format!("fraction of {} samples feasible", folded(r)),
        x_range: (m.x_deg[0], m.x_deg[nx - 1]),
        y_range: (m.y_deg[0], m.y_deg[ny - 1]),
        shape: (nx, ny),
        values: m
            .fraction
            .iter()
            .flatten()
            .map(|v| v.unwrap_or(f64::NAN))
            .collect(),
        blank_below: f64::NEG_INFINITY,
        markers: Vec::new(),
        outlines: Vec::new(),
        highlight: Vec::new(),
    };
    cdpr::plot::save(&fig, path)?;
    Ok(())
}

/// The text answer: counts and the map as a table.
fn print_orientations(r: &OrientationsReport) {
    let [x, y, z] = r.position;
    println!(
        "robot {}: orientation workspace at ({x}, {y}, {z}) m over {}",
        r.robot, r.orientation_set
    );
    println!("criteria: {}", r.criteria.join(", "));
    println!(
        "{} of {} sampled orientations feasible ({:.1} %)",
        r.feasible_count,
        r.count,
        100.0 * r.feasible_count as f64 / r.count as f64
    );
    let m = &r.map;
    println!(
        "map: {} (rows) × {} (columns), fraction feasible over {}",
        m.y,
        m.x,
        folded(r)
    );
    let header: Vec<String> = m.x_deg.iter().map(|x| format!("{x:>7.1}")).collect();
    println!(
        "{:>9} {}",
        format!("{}\\{}", m.y, m.x)
            .chars()
            .take(9)
            .collect::<String>(),
        header.join("")
    );
    for (y, row) in m.y_deg.iter().zip(&m.fraction) {
        let cells: Vec<String> = row
            .iter()
            .map(|v| format!("{:>7.2}", v.unwrap_or(f64::NAN)))
            .collect();
        println!("{y:>8.1}° {}", cells.join(""));
    }
}

/// The `--orientations` value: a valid orientation set, kept as written (the request parses it).
pub fn set_spec(s: &str) -> Result<String, String> {
    s.parse::<OrientationSet>().map_err(|e| e.to_string())?;
    Ok(s.to_string())
}

/// How a workspace over an orientation set is shown.
pub struct View<'a> {
    /// The figure (.svg, .png or .html).
    pub plot: Option<&'a Path>,
    /// Pose at which the robot is drawn.
    pub draw_pose: Option<&'a [f64]>,
    /// One JSON object on stdout.
    pub json: bool,
}

/// "ROBOT: total workspace over SET (N orientations)".
fn set_title(robot: &str, kind: &str, set: &str, count: usize) -> String {
    format!("{robot}: {kind} workspace over {set} ({count} orientations)")
}

/// `cdpr workspace --orientations SET [--kind total|maximal] --boundary mesh`: the certified
/// boundary mesh of the total-orientation or maximal workspace, with the limiting orientation at
/// every boundary vertex of a total-orientation workspace.
pub fn run_workspace_mesh(
    request: &OrientationWorkspaceRequest,
    view: &View<'_>,
) -> Result<(), CliError> {
    let r = request.run_mesh()?;
    let title = set_title(&r.robot, &r.kind, &r.orientation_set, r.orientation_count);
    if let Some(path) = view.plot {
        let desc = request.robot.description();
        let region = &r.mesh.grid.grid.region;
        let pose = draw_pose(&desc.robot, view.draw_pose, region, &Rotation3::identity())?;
        let summary = format!(
            "volume {} m³ (boundary mesh, m = {}); {}",
            super::num(r.volume),
            r.resolution,
            r.criteria.join(", ")
        );
        save_mesh_scene_plot(
            desc,
            &pose,
            &r.mesh,
            (title.clone(), vec![summary]),
            request.criteria.cable_model.as_deref(),
            path,
        )?;
    }
    if view.json {
        return print_report(&r);
    }
    println!("{title}");
    println!(
        "criteria: {} (tensions: {})",
        r.criteria.join(", "),
        r.tension_method
    );
    println!(
        "boundary mesh from a grid of m = {}: volume {} m³, surface {} m², {} component(s), \
         {} vertices, {} triangles{}",
        r.resolution,
        super::num(r.volume),
        super::num(r.surface_area),
        r.components,
        r.vertices,
        r.triangles,
        if r.watertight {
            ", closed"
        } else {
            ", NOT closed (please report)"
        }
    );
    for l in r.limiting_summary.iter().take(5) {
        let a = l.angles_deg;
        println!(
            "  limiting ({:.2}, {:.2}, {:.2})° at {} vertices",
            a[0], a[1], a[2], l.boundary_vertices
        );
    }
    if let Some(p) = view.plot {
        println!("plot written to {}", p.display());
    }
    Ok(())
}

/// `cdpr workspace --orientations SET [--kind total|maximal]`: the grid workspace of the
/// set, with the limiting orientations of a total-orientation workspace.
pub fn run_workspace(
    request: &OrientationWorkspaceRequest,
    view: &View<'_>,
) -> Result<(), CliError> {
    let r = request.run()?;
    let title = set_title(&r.robot, &r.kind, &r.orientation_set, r.orientation_count);
    if let Some(path) = view.plot {
        let desc = request.robot.description();
        let region = &r.workspace.grid.region;
        let pose = draw_pose(&desc.robot, view.draw_pose, region, &Rotation3::identity())?;
        let summary = format!(
            "volume {:.4} m³ ({} of {} points, m = {}, {} convention); {}",
            r.area,
            r.feasible_points,
            r.total_points,
            r.resolution,
            r.volume_convention,
            r.criteria.join(", ")
        );
        save_scene_plot(
            desc,
            &pose,
            &r.workspace,
            (title.clone(), vec![summary]),
            request.criteria.cable_model.as_deref(),
            path,
        )?;
    }
    if view.json {
        return print_report(&r);
    }
    print_workspace(&title, &r);
    if let Some(p) = view.plot {
        println!("plot written to {}", p.display());
    }
    Ok(())
}

/// The text answer of the grid workspace over a set.
fn print_workspace(title: &str, r: &OrientationWorkspaceReport) {
    println!("{title}");
    println!(
        "criteria: {} (tensions: {})",
        r.criteria.join(", "),
        r.tension_method
    );
    println!(
        "grid m = {} over {}: {} of {} points in the {} workspace, cell volume {:.6e} m³",
        r.resolution,
        json!(r.area_box),
        r.feasible_points,
        r.total_points,
        r.kind,
        r.cell_area
    );
    println!(
        "volume {:.6} m³ ({} convention)",
        r.area, r.volume_convention
    );
    if !r.limiting_summary.is_empty() {
        println!(
            "limiting orientations at {} boundary grid points ({}, degrees):",
            r.limiting_orientations.len(),
            r.angle_names.join(", ")
        );
        for l in r.limiting_summary.iter().take(5) {
            let a = l.angles_deg;
            println!(
                "  ({:.2}, {:.2}, {:.2}) at {} point(s)",
                a[0], a[1], a[2], l.boundary_points
            );
        }
    }
}
