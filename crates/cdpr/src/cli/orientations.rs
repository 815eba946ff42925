//! `cdpr orientations`: the orientation workspace at a position (the feasible orientations of a
//! sampled set, as a tilt/torsion map and JSON); and the total-orientation and maximal
//! workspaces behind `cdpr workspace --orientations … --kind total|maximal`.

use super::criteria::{CriteriaArgs, CriteriaSetup, default_method};
use super::region::{draw_pose, save_mesh_scene_plot, save_scene_plot};
use super::{CliError, Numbers, load_robot, print_json, print_report};
use cdpr::RobotDescription;
use cdpr::api::{OrientationWorkspaceReport, OrientationWorkspaceRequest, degrees};
use cdpr::plot::HeatMap;
use cdpr::workspace::{
    OrientationSet, OrientationTest, OrientationWorkspaceKind, SampledOrientation,
};
use nalgebra::{Rotation3, Vector3};
use serde_json::{Value, json};
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
    #[arg(long)]
    orientations: OrientationSet,
    #[command(flatten)]
    criteria: CriteriaArgs,
    /// Write the tilt/torsion map (.svg or .png).
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Write one JSON object on stdout.
    #[arg(long)]
    json: bool,
}

/// The orientation test of a robot file (see [`cdpr::api::orientation_test`]).
pub fn orientation_test(
    desc: &RobotDescription,
    setup: &CriteriaSetup,
    set: &OrientationSet,
    kind: OrientationWorkspaceKind,
) -> Result<(OrientationTest, Vec<SampledOrientation>), CliError> {
    Ok(cdpr::api::orientation_test(desc, setup, set, kind)?)
}

/// The map of fractions feasible: axes (x, y) = angle indices, fraction over the others.
pub struct FractionMap {
    /// Angle index along x and y.
    pub axes: (usize, usize),
    /// Sample values along x and y (degrees).
    pub xs: Vec<f64>,
    /// Sample values along y (degrees).
    pub ys: Vec<f64>,
    /// Fraction feasible, row-major, x fastest.
    pub fraction: Vec<f64>,
}

/// Sorted distinct values.
fn distinct(mut v: Vec<f64>) -> Vec<f64> {
    v.sort_by(f64::total_cmp);
    v.dedup_by(|a, b| (*a - *b).abs() <= 1e-12 * b.abs().max(1.0));
    v
}

/// The tilt/torsion map of a set's verdicts.
pub fn fraction_map(
    set: &OrientationSet,
    samples: &[SampledOrientation],
    feasible: &[bool],
) -> FractionMap {
    let axes = match set {
        OrientationSet::TiltTorsion { .. } => (2, 0),
        OrientationSet::EulerBox { min, max, .. } => {
            let ranged: Vec<usize> = (0..3).filter(|&k| min[k] < max[k]).collect();
            match ranged.as_slice() {
                [] => (0, 1),
                [a] => (*a, if *a == 0 { 1 } else { 0 }),
                [a, b, ..] => (*a, *b),
            }
        }
    };
    let deg = |o: &SampledOrientation, k: usize| o.angles[k].to_degrees();
    let xs = distinct(samples.iter().map(|o| deg(o, axes.0)).collect());
    let ys = distinct(samples.iter().map(|o| deg(o, axes.1)).collect());
    let find = |v: &[f64], x: f64| {
        v.iter()
            .position(|a| (a - x).abs() <= 1e-12 * x.abs().max(1.0))
            .unwrap_or(0)
    };
    let mut count = vec![(0usize, 0usize); xs.len() * ys.len()];
    for (o, &ok) in samples.iter().zip(feasible) {
        let cell = find(&ys, deg(o, axes.1)) * xs.len() + find(&xs, deg(o, axes.0));
        count[cell].1 += 1;
        count[cell].0 += ok as usize;
    }
    let fraction = count
        .iter()
        .map(|&(a, n)| {
            if n == 0 {
                f64::NAN
            } else {
                a as f64 / n as f64
            }
        })
        .collect();
    FractionMap {
        axes,
        xs,
        ys,
        fraction,
    }
}

/// Runs `cdpr orientations`.
pub fn run(args: Args) -> Result<(), CliError> {
    let desc = load_robot(&args.robot)?;
    let method = args
        .criteria
        .method
        .unwrap_or_else(|| default_method(&desc.robot));
    let setup = super::criteria::setup(&args.criteria, &desc, method)?;
    let u = match args.position.0.as_slice() {
        [x, y, z] if [x, y, z].iter().all(|v| v.is_finite()) => Vector3::new(*x, *y, *z),
        p => {
            return Err(format!("--position needs 3 finite numbers x,y,z (m), got {p:?}").into());
        }
    };
    let set = &args.orientations;
    let (mut test, samples) =
        orientation_test(&desc, &setup, set, OrientationWorkspaceKind::Total)?;
    let feasible = test.feasible_orientations(u);
    let count = feasible.iter().filter(|&&f| f).count();
    let names = set.angle_names();
    let map = fraction_map(set, &samples, &feasible);
    let spec = set.to_string();
    if let Some(path) = &args.plot {
        let (nx, ny) = (map.xs.len(), map.ys.len());
        let over = names[3 - map.axes.0 - map.axes.1];
        let fig = HeatMap {
            title: format!(
                "{}: feasible orientations at ({}, {}, {}) m",
                desc.name, u.x, u.y, u.z
            ),
            labels: (
                format!("{} (°)", names[map.axes.0]),
                format!("{} (°)", names[map.axes.1]),
            ),
            value_label: format!("fraction of {over} samples feasible"),
            x_range: (map.xs[0], map.xs[nx - 1]),
            y_range: (map.ys[0], map.ys[ny - 1]),
            shape: (nx, ny),
            values: map.fraction.clone(),
            blank_below: f64::NEG_INFINITY,
            markers: Vec::new(),
            outlines: Vec::new(),
            highlight: Vec::new(),
        };
        cdpr::plot::save(&fig, path)?;
    }
    if args.json {
        return print_json(&json!({
            "robot": desc.name,
            "position": [u.x, u.y, u.z],
            "orientation_set": spec,
            "angle_names": names,
            "criteria": setup.labels(),
            "count": samples.len(),
            "feasible_count": count,
            "orientations": samples.iter().zip(&feasible).map(|(o, f)| json!({
                "angles_deg": degrees(o),
                "feasible": f,
            })).collect::<Vec<_>>(),
            "map": {
                "x": names[map.axes.0],
                "y": names[map.axes.1],
                "x_deg": map.xs,
                "y_deg": map.ys,
                "fraction": map.fraction.chunks(map.xs.len().max(1)).map(|r| r.iter().map(|v| if v.is_finite() { json!(v) } else { Value::Null }).collect::<Vec<_>>()).collect::<Vec<_>>(),
            },
        }));
    }
    println!(
        "robot {}: orientation workspace at ({}, {}, {}) m over {spec}",
        desc.name, u.x, u.y, u.z
    );
    println!("criteria: {}", setup.labels().join(", "));
    println!(
        "{count} of {} sampled orientations feasible ({:.1} %)",
        samples.len(),
        100.0 * count as f64 / samples.len() as f64
    );
    println!(
        "map: {} (rows) × {} (columns), fraction feasible over {}",
        names[map.axes.1],
        names[map.axes.0],
        names[3 - map.axes.0 - map.axes.1]
    );
    let header: Vec<String> = map.xs.iter().map(|x| format!("{x:>7.1}")).collect();
    println!(
        "{:>9} {}",
        format!("{}\\{}", names[map.axes.1], names[map.axes.0])
            .chars()
            .take(9)
            .collect::<String>(),
        header.join("")
    );
    for (j, y) in map.ys.iter().enumerate() {
        let row: Vec<String> = (0..map.xs.len())
            .map(|i| format!("{:>7.2}", map.fraction[j * map.xs.len() + i]))
            .collect();
        println!("{y:>8.1}° {}", row.join(""));
    }
    if let Some(p) = &args.plot {
        println!("plot written to {}", p.display());
    }
    Ok(())
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
        save_mesh_scene_plot(desc, &pose, &r.mesh, title.clone(), vec![summary], path)?;
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
            title.clone(),
            vec![summary],
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
