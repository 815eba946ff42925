//! `cdpr orientations`: the orientation workspace at a position (the feasible orientations of a
//! sampled set, as a tilt/torsion map and JSON); and the total-orientation and maximal
//! workspaces behind `cdpr workspace --orientations … --kind total|maximal`.

use super::criteria::{CriteriaArgs, CriteriaSetup, default_method};
use super::{CliError, Numbers, load_robot, print_json};
use cdpr::RobotDescription;
use cdpr::kinematics::MotionPattern;
use cdpr::plot::HeatMap;
use cdpr::workspace::{
    Grid, MeshSettings, OrientationSet, OrientationTest, OrientationWorkspaceKind, Region,
    SampledOrientation, VolumeConvention, orientation_boundary_mesh, orientation_workspace,
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

/// The orientation test of a robot file: one evaluator per sampled orientation.
pub fn orientation_test(
    desc: &RobotDescription,
    setup: &CriteriaSetup,
    set: &OrientationSet,
    kind: OrientationWorkspaceKind,
) -> Result<(OrientationTest, Vec<SampledOrientation>), CliError> {
    let motion = desc.robot.motion();
    if motion != MotionPattern::Spatial {
        return Err(format!(
            "--orientations samples platform orientations in space: `spatial` robots only, this \
             one is `{motion}` (planar robots: `cdpr dextrous`)"
        )
        .into());
    }
    let samples = set.orientations()?;
    let evals = samples
        .iter()
        .map(|o| setup.evaluator(desc, desc.robot.clone(), &o.rotation))
        .collect::<Result<Vec<_>, _>>()?;
    let test = OrientationTest::new(kind, samples.iter().map(|o| o.rotation).collect(), evals)?;
    Ok((test, samples))
}

/// Angles in degrees.
pub fn degrees(o: &SampledOrientation) -> [f64; 3] {
    o.angles.map(f64::to_degrees)
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

/// How often each of `count` sampled orientations is the limiting one: `(orientation, times)`
/// for those that are, most frequent first (ties by index).
fn rank_limiting(limiting: impl Iterator<Item = usize>, count: usize) -> Vec<(usize, usize)> {
    let mut per = vec![0usize; count];
    for k in limiting {
        per[k] += 1;
    }
    let mut ranked: Vec<(usize, usize)> = per
        .into_iter()
        .enumerate()
        .filter(|&(_, n)| n > 0)
        .collect();
    ranked.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    ranked
}

/// `cdpr workspace --orientations SET [--kind total|maximal] --boundary mesh`: the certified
/// boundary mesh of the total-orientation or maximal workspace, with the limiting orientation at
/// every boundary vertex of a total-orientation workspace.
#[allow(clippy::too_many_arguments)]
pub fn run_workspace_mesh(
    desc: &RobotDescription,
    setup: &CriteriaSetup,
    set: &OrientationSet,
    kind: OrientationWorkspaceKind,
    region: &Region,
    m: usize,
    plot: Option<&Path>,
    draw_pose: Option<&[f64]>,
    json_out: bool,
) -> Result<(), CliError> {
    let grid = Grid::new(m, *region);
    let (test, samples) = orientation_test(desc, setup, set, kind)?;
    let om = orientation_boundary_mesh(&test, &grid, &MeshSettings::default())?;
    let mesh = &om.mesh;
    let ranked = rank_limiting(om.limiting.iter().flatten().copied(), samples.len());
    let title = format!(
        "{}: {} workspace over {set} ({} orientations)",
        desc.name,
        kind.name(),
        samples.len()
    );
    let watertight = mesh.edge_defects() == 0;
    let summary = format!(
        "volume {} m³ (boundary mesh, m = {m}); {}",
        super::num(mesh.volume),
        setup.labels().join(", ")
    );
    if let Some(path) = plot {
        let pose =
            super::region::draw_pose(&desc.robot, draw_pose, region, &Rotation3::identity())?;
        super::region::save_mesh_scene_plot(
            desc,
            &pose,
            mesh,
            title.clone(),
            vec![summary.clone()],
            path,
        )?;
    }
    if json_out {
        return print_json(&json!({
            "robot": desc.name,
            "method": "mesh",
            "kind": kind.name(),
            "orientation_set": set.to_string(),
            "orientation_count": samples.len(),
            "angle_names": set.angle_names(),
            "criteria": setup.labels(),
            "tension_method": setup.method.name(),
            "box": super::region::box_json(region, 3),
            "resolution": m,
            "dimension": 3,
            "volume": mesh.volume,
            "surface_area": mesh.surface_area,
            "components": mesh.components,
            "vertices": mesh.vertices.len(),
            "triangles": mesh.triangles.len(),
            "tolerance": mesh.tolerance,
            "watertight": watertight,
            "feasible_points": mesh.grid.feasible_points,
            "total_points": mesh.grid.total_points,
            "limiting_summary": ranked.iter().map(|&(k, n)| json!({
                "angles_deg": degrees(&samples[k]),
                "boundary_vertices": n,
            })).collect::<Vec<_>>(),
        }));
    }
    println!("{title}");
    println!(
        "criteria: {} (tensions: {})",
        setup.labels().join(", "),
        setup.method.name()
    );
    println!(
        "boundary mesh from a grid of m = {m}: volume {} m³, surface {} m², {} component(s), \
         {} vertices, {} triangles{}",
        super::num(mesh.volume),
        super::num(mesh.surface_area),
        mesh.components,
        mesh.vertices.len(),
        mesh.triangles.len(),
        if watertight {
            ", closed"
        } else {
            ", NOT closed (please report)"
        }
    );
    for &(k, n) in ranked.iter().take(5) {
        let a = degrees(&samples[k]);
        println!(
            "  limiting ({:.2}, {:.2}, {:.2})° at {n} vertices",
            a[0], a[1], a[2]
        );
    }
    if let Some(p) = plot {
        println!("plot written to {}", p.display());
    }
    Ok(())
}

/// `cdpr workspace --orientations SET [--kind total|maximal]`: the grid workspace of the
/// set, with the limiting orientations of a total-orientation workspace.
#[allow(clippy::too_many_arguments)]
pub fn run_workspace(
    desc: &RobotDescription,
    setup: &CriteriaSetup,
    set: &OrientationSet,
    kind: OrientationWorkspaceKind,
    region: &Region,
    m: usize,
    plot: Option<&Path>,
    draw_pose: Option<&[f64]>,
    json_out: bool,
    convention: VolumeConvention,
) -> Result<(), CliError> {
    let grid = Grid::new(m, *region);
    let (test, samples) = orientation_test(desc, setup, set, kind)?;
    let ws = orientation_workspace(&test, &grid)?;
    let names = set.angle_names();
    let ranked = rank_limiting(ws.limiting.iter().map(|l| l.orientation), samples.len());
    let w = &ws.workspace;
    let title = format!(
        "{}: {} workspace over {set} ({} orientations)",
        desc.name,
        kind.name(),
        samples.len()
    );
    let volume = w.measure(convention);
    let summary = format!(
        "volume {:.4} m³ ({} of {} points, m = {m}, {} convention); {}",
        volume,
        w.feasible_points,
        w.total_points,
        convention,
        setup.labels().join(", ")
    );
    if let Some(path) = plot {
        let pose =
            super::region::draw_pose(&desc.robot, draw_pose, region, &Rotation3::identity())?;
        super::region::save_scene_plot(desc, &pose, w, title.clone(), vec![summary.clone()], path)?;
    }
    if json_out {
        let mut v = json!({
            "robot": desc.name,
            "method": "grid",
            "kind": kind.name(),
            "orientation_set": set.to_string(),
            "orientation_count": samples.len(),
            "angle_names": names,
            "criteria": setup.labels(),
            "tension_method": setup.method.name(),
            "box": super::region::box_json(region, 3),
            "resolution": m,
            "dimension": 3,
            "feasible_points": w.feasible_points,
            "total_points": w.total_points,
            "cell_area": w.cell_area,
            "limiting_orientations": ws.limiting.iter().map(|l| json!({
                "point": [l.boundary_point.x, l.boundary_point.y, l.boundary_point.z],
                "angles_deg": degrees(&samples[l.orientation]),
            })).collect::<Vec<_>>(),
            "limiting_summary": ranked.iter().map(|&(k, n)| json!({
                "angles_deg": degrees(&samples[k]),
                "boundary_points": n,
            })).collect::<Vec<_>>(),
        });
        super::region::measure_json(&mut v, w, convention);
        return print_json(&v);
    }
    println!("{title}");
    println!(
        "criteria: {} (tensions: {})",
        setup.labels().join(", "),
        setup.method.name()
    );
    println!(
        "grid m = {m} over {}: {} of {} points in the {} workspace, cell volume {:.6e} m³",
        super::region::box_json(region, 3),
        w.feasible_points,
        w.total_points,
        kind.name(),
        w.cell_area
    );
    println!("volume {volume:.6} m³ ({convention} convention)");
    if !ranked.is_empty() {
        println!(
            "limiting orientations at {} boundary grid points ({}, degrees):",
            ws.limiting.len(),
            names.join(", ")
        );
        for &(k, n) in ranked.iter().take(5) {
            let a = degrees(&samples[k]);
            println!("  ({:.2}, {:.2}, {:.2}) at {n} point(s)", a[0], a[1], a[2]);
        }
    }
    if let Some(p) = plot {
        println!("plot written to {}", p.display());
    }
    Ok(())
}
