//! `cdpr isotropic`: the maximum isotropic force (Krut, Company & Pierrot 2004, §IV) at a pose, or its map.

use super::{
    CliError, Numbers, external_wrench, load_robot, num, pose, pose_text, print_json, wrench_text,
};
use cdpr::RobotDescription;
use cdpr::kinematics::{MotionPattern, Pose};
use cdpr::plot::{ForcePolygonPlot, HeatMap};
use cdpr::polytope::{
    InscribedEllipse, IsotropicForce, hyperplane_shifting, isotropic_force_under_load,
    largest_inscribed_ellipse,
};
use indicatif::ProgressBar;
use nalgebra::{DVector, Vector3};
use rayon::prelude::*;
use serde_json::{Value, json};
use std::io::IsTerminal;
use std::path::PathBuf;

/// Maximum isotropic force (Krut, Company & Pierrot 2004): the largest force the platform can
/// resist in EVERY direction with tensions in [t_min, t_max], i.e. the radius of the largest
/// ball centred at the origin inside the available force polytope {W t} (eq. 19). It is signed:
/// negative when the origin is outside the polytope (the pose cannot even hold a zero load).
///
/// The platform's weight (its `mass` and `gravity` in the robot file) and --wrench are included:
/// the index is the extra force the platform resists in every direction ON TOP OF that external
/// wrench w_ext (as `capacity` and `workspace` add it): facets n_k · w <= d_k become
/// n_k · w <= d_k + n_k · w_ext. A robot file without mass gives eq. (19) exactly. JSON
/// `external_wrench` (N, N·m) says which w_ext was used.
///
/// For point robots (point2, point3) every wrench component is a force. For planar and spatial
/// robots the index is the FORCE AT ZERO MOMENT: the largest force ball inside the slice
/// {moment = 0} of the available wrench set (JSON `definition` says which). `wrench_radius` is
/// the ball in the full wrench space (forces and moments mixed, unit-dependent).
///
/// One pose: `cdpr isotropic ROBOT.toml --pose 0,0 [--ellipse] [--plot polygon.png] [--json]`;
/// for point2 robots `--plot` draws the available force polygon with the largest centred circle
/// and ellipse and the facet the circle touches (Krut, Company & Pierrot 2004, Fig. 4); for
/// point3 robots `--plot polytope.html` writes a 3-D view of the force polytope with the
/// largest ball centred at −w_ext (radius = the index).
/// A map: `cdpr isotropic ROBOT.toml --grid 100 [--box ...] [--orientation PHI] [--z Z]
/// [--plot map.png] [--json]` evaluates (M+1)² poses in parallel (Krut, Company & Pierrot 2004, Figs. 9–10; white
/// where the index is negative).
///
/// The force polygon of --plot and the ellipse of --ellipse are those of the available wrench
/// set itself (no load).
///
/// JSON (pose): `isotropic_force` (N), `wrench_radius` (N and N·m combined), `external_wrench`
/// (N, N·m), `definition`, `facets` (a count), `vertices` (of the available wrench set, N, N·m;
/// wrench spaces of dimension 2 and 3), `faces` (lists of vertex indices, counter-clockwise seen
/// from outside; edges in 2-D), `normals` (unit, outward) and `offsets` (N, N·m; n · w ≤ d) of
/// the faces, `ellipse` (with --ellipse: `semi_axes` N, `angle` rad,
/// `angle_deg`, `area` N²). JSON (grid): `grid` {`x`, `y` (m), `values` (N; rows along y, null
/// where undefined)}, `stats` {`min`, `max` (N), `argmax` (m), `positive_fraction`,
/// `undefined`, `centre` (N)}, `external_wrench`, `definition`.
#[derive(clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    /// Robot file: .toml, CASPR NAME_cables.xml or WireCenter .wcrfx.
    robot: PathBuf,
    /// Platform pose (motion-pattern coordinates), e.g. --pose 0,0 (point2) or 0.1,-0.2,0
    /// (planar). Give either --pose or --grid.
    #[arg(
        long,
        allow_hyphen_values = true,
        conflicts_with = "grid",
        required_unless_present = "grid"
    )]
    pose: Option<Numbers>,
    /// Map the index over a (M+1) × (M+1) grid of positions (M intervals per side).
    #[arg(long, value_name = "M", value_parser = super::count)]
    grid: Option<usize>,
    /// Grid: the area XMIN,XMAX,YMIN,YMAX (default: the bounding box of the frame anchors).
    #[arg(
        long = "box",
        allow_hyphen_values = true,
        value_name = "XMIN,XMAX,YMIN,YMAX",
        requires = "grid"
    )]
    area: Option<Numbers>,
    /// Grid: platform orientation φ (rad, rotation about z) for planar and spatial robots.
    #[arg(
        long,
        default_value_t = 0.0,
        allow_hyphen_values = true,
        requires = "grid",
        value_parser = super::finite
    )]
    orientation: f64,
    /// External wrench w_e on the platform (DOF numbers, N and N·m; default zero), added to the
    /// platform's weight from the robot file.
    #[arg(long, allow_hyphen_values = true)]
    wrench: Option<Numbers>,
    /// Grid: height z of the slice for 3-D robots (default: middle of the frame anchors).
    #[arg(long, allow_hyphen_values = true, requires = "grid", value_parser = super::finite)]
    z: Option<f64>,
    /// Write a figure (.png or .svg). Grid: the heat map, white where the index is negative.
    /// Pose (point2 robots only): the available force polygon with the largest centred circle
    /// (radius = the index) and ellipse, the origin and the facet the circle touches
    /// (Krut, Company & Pierrot 2004, Fig. 4). Pose, point3 robots: a 3-D view of the force
    /// polytope with the largest ball centred at −w_ext (.html).
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Pose: also the largest-area centred ellipse inside the force polygon (Krut, Company & Pierrot 2004, §IV-C;
    /// point2 robots only): semi-axes, angle of the major axis, area.
    #[arg(long, conflicts_with = "grid")]
    ellipse: bool,
    /// Write one JSON object on stdout.
    #[arg(long)]
    json: bool,
}

/// What the index means for this motion pattern (JSON `definition`).
fn definition(motion: MotionPattern) -> &'static str {
    if motion.has_orientation() {
        "force at zero moment: radius of the largest force ball centred at -w_ext (the origin \
         without load) inside the moment = 0 slice of the available wrench set \
         {W t : t_min <= t <= t_max}; negative when -w_ext is outside"
    } else {
        "radius of the largest force ball centred at -w_ext (the origin without load) inside the \
         available force polytope {W t : t_min <= t <= t_max} (Krut, Company & Pierrot 2004, \
         eq. 19); negative when -w_ext is outside"
    }
}

/// Runs the command.
pub fn run(args: Args) -> Result<(), CliError> {
    let robot = load_robot(&args.robot)?;
    cdpr::wrench::require_enough_cables(&robot.robot, "the isotropic force (wrench closure)")?;
    match (&args.pose, args.grid) {
        (Some(q), _) => run_pose(&args, &robot, q),
        (None, Some(m)) => run_grid(&args, &robot, m),
        (None, None) => Err("give --pose or --grid".into()),
    }
}

fn ellipse_json(e: &Option<InscribedEllipse>) -> Value {
    match e {
        Some(e) => json!({
            "semi_axes": e.semi_axes,
            "angle": e.angle,
            "angle_deg": e.angle.to_degrees(),
            "area": e.area(),
        }),
        None => Value::Null,
    }
}

/// JSON `faces` (vertex indices, counter-clockwise seen from outside; edges for DOF 2),
/// `normals` (outward, unit) and `offsets` (N, N·m: n · w ≤ d), one per face, when the set has
/// vertices.
fn add_faces_json(v: &mut Value, aws: &cdpr::polytope::AvailableWrenchSet) {
    if let Some(faces) = aws.faces() {
        let facet = |f: &cdpr::polytope::Face| &aws.facets()[f.facet];
        v["faces"] = json!(faces.iter().map(|f| &f.vertices).collect::<Vec<_>>());
        v["normals"] = json!(
            faces
                .iter()
                .map(|f| facet(f).normal.as_slice())
                .collect::<Vec<_>>()
        );
        v["offsets"] = json!(faces.iter().map(|f| facet(f).offset).collect::<Vec<_>>());
    }
}

/// The HTML view of a point3 robot's force polytope with the largest ball centred at −w_ext.
fn save_polytope_view(
    robot: &RobotDescription,
    q: &[f64],
    aws: &cdpr::polytope::AvailableWrenchSet,
    w_ext: &DVector<f64>,
    force: f64,
    path: &std::path::Path,
) -> Result<(), CliError> {
    let centre = [-w_ext[0], -w_ext[1], -w_ext[2]];
    let mut scene = cdpr::plot::force_polytope_scene(aws, centre, force)
        .ok_or("the force polytope is unbounded (an infinite t_max): nothing to draw")?;
    scene.title = format!(
        "{}: available force polytope {{W t}} at position ({}) m",
        robot.name,
        q.iter()
            .map(|v| cdpr::plot::tick(*v))
            .collect::<Vec<_>>()
            .join(", ")
    );
    scene.legend = vec![
        format!("maximum isotropic force on top of w_ext: {} N", num(force)),
        format!(
            "w_ext {} (the platform's weight and --wrench)",
            wrench_text(w_ext.as_slice(), 3)
        ),
        format!("{} facets", aws.facets().len()),
    ];
    cdpr::plot::save_scene(&scene, path)?;
    Ok(())
}

fn run_pose(args: &Args, robot: &RobotDescription, q: &[f64]) -> Result<(), CliError> {
    let motion = robot.robot.motion();
    if args.ellipse && motion != MotionPattern::Point2 {
        return Err(format!(
            "--ellipse needs a 2-D force polygon (a point2 robot); this robot is {}",
            motion.name()
        )
        .into());
    }
    let html = args.plot.as_deref().is_some_and(super::region::is_html);
    if args.plot.is_some()
        && motion != MotionPattern::Point2
        && !(html && motion == MotionPattern::Point3)
    {
        return Err(format!(
            "--plot with --pose draws the 2-D force polygon (a point2 robot, .png or .svg) or the \
             3-D force polytope (a point3 robot, .html); this robot is {} (use --grid --plot for a \
             map of the index)",
            motion.name()
        )
        .into());
    }
    if html && motion == MotionPattern::Point2 {
        return Err("--plot: the force polygon of a point2 robot is drawn as .png or .svg".into());
    }
    let p = pose(robot, q)?;
    let w = robot.robot.inverse_kinematics(&p)?.wrench_matrix();
    let aws = hyperplane_shifting::available_wrench_set(&w, &robot.bounds)?;
    let w_ext = external_wrench(robot, &p, args.wrench.as_deref())?;
    let force = isotropic_force_under_load(&aws, motion, &w_ext)?;
    let radius = aws
        .supporting_halfspaces()
        .iter()
        .map(|f| f.offset + f.normal.dot(&w_ext))
        .fold(f64::INFINITY, f64::min);
    let ellipse = if args.ellipse || (args.plot.is_some() && !html) {
        Some(largest_inscribed_ellipse(&aws)?)
    } else {
        None
    };
    if let Some(path) = args.plot.as_ref().filter(|_| html) {
        save_polytope_view(robot, q, &aws, &w_ext, force, path)?;
    } else if let Some(path) = &args.plot {
        let mut fig = ForcePolygonPlot::operational(&aws, ellipse.flatten().as_ref())
            .ok_or("the force polygon is unbounded (an infinite t_max): nothing to draw")?;
        fig.title = format!(
            "{}: available force polygon {{W t}} at position ({})",
            robot.name,
            q.iter()
                .map(|v| cdpr::plot::tick(*v))
                .collect::<Vec<_>>()
                .join(", ")
        );
        cdpr::plot::save(&fig, path)?;
    }
    if args.json {
        let mut v = json!({
            "robot": robot.name,
            "pose": q,
            "isotropic_force": force,
            "wrench_radius": radius,
            "external_wrench": w_ext.as_slice(),
            "definition": definition(motion),
            "facets": aws.facets().len(),
            "vertices": aws.vertices().map(|v| v.iter().map(|p| p.as_slice().to_vec()).collect::<Vec<_>>()),
        });
        add_faces_json(&mut v, &aws);
        if let (true, Some(e)) = (args.ellipse, &ellipse) {
            v["ellipse"] = ellipse_json(e);
        }
        return print_json(&v);
    }
    let forces = motion.translation_dof();
    println!(
        "robot {}, pose {}",
        robot.name,
        pose_text(q, motion.space_dim())
    );
    println!(
        "external wrench w_ext {} (the platform's weight{} included)",
        wrench_text(w_ext.as_slice(), forces),
        if args.wrench.is_some() {
            " and --wrench"
        } else {
            ""
        }
    );
    println!("maximum isotropic force on top of w_ext: {force:.6} N");
    println!("  ({})", definition(motion));
    println!(
        "wrench-space ball radius: {radius:.6} {}",
        if forces == w_ext.len() {
            "N"
        } else {
            "(N and N·m combined, length scale 1 m)"
        }
    );
    println!("available wrench set: {} facets", aws.facets().len());
    if force < 0.0 {
        println!("w_ext is outside the set of wrenches the cables can balance: it cannot be held");
    }
    match ellipse.as_ref().filter(|_| args.ellipse) {
        Some(Some(e)) => println!(
            "largest centred ellipse (no load): semi-axes {:.6} N, {:.6} N; major axis at \
             {:.4}°; area {:.6} N²",
            e.semi_axes[0],
            e.semi_axes[1],
            e.angle.to_degrees(),
            e.area()
        ),
        Some(None) => println!("largest centred ellipse: none (the origin is not strictly inside)"),
        None => {}
    }
    if let Some(p) = &args.plot {
        let what = if html {
            "force polytope view"
        } else {
            "force polygon"
        };
        println!("{what} written to {}", p.display());
    }
    Ok(())
}

/// The pose at grid point (x, y).
fn grid_pose(motion: MotionPattern, x: f64, y: f64, z: f64, phi: f64) -> Pose {
    match motion {
        MotionPattern::Point2 => Pose::point(x, y, 0.0),
        MotionPattern::Planar => Pose::planar(x, y, phi),
        MotionPattern::Point3 => Pose::point(x, y, z),
        MotionPattern::Spatial => Pose::spatial(Vector3::new(x, y, z), 0.0, 0.0, phi),
    }
}

fn run_grid(args: &Args, robot: &RobotDescription, m: usize) -> Result<(), CliError> {
    if !(1..=2000).contains(&m) {
        return Err("--grid M must lie in [1, 2000]".into());
    }
    let map = IsotropicMap::compute(args, robot, m)?;
    let stats = MapStats::of(&map);
    if let Some(path) = &args.plot {
        save_heat_map(robot, &map, &stats, path)?;
    }
    if args.json {
        return print_json(&map_json(robot, &map, &stats));
    }
    print_map(args, robot, &map, &stats);
    if let Some(p) = &args.plot {
        println!("heat map written to {}", p.display());
    }
    Ok(())
}

/// The index over a grid of the box `[x0, x1] × [y0, y1]` at height `z` (3-D robots).
struct IsotropicMap {
    motion: MotionPattern,
    x: (f64, f64),
    y: (f64, f64),
    z: f64,
    orientation: f64,
    /// Points per axis (M + 1).
    k: usize,
    xs: Vec<f64>,
    ys: Vec<f64>,
    /// Row-major (y then x); NaN where the index is undefined.
    values: Vec<f64>,
    w_ext: DVector<f64>,
    template: IsotropicForce,
}

impl IsotropicMap {
    /// Reads the box, height and load, then maps the index in parallel (one evaluator per
    /// worker; a pose where the index is undefined, a cable of zero length or a singular W, is
    /// NaN: null in JSON, white in the plot).
    fn compute(args: &Args, robot: &RobotDescription, m: usize) -> Result<Self, CliError> {
        let motion = robot.robot.motion();
        let (lo, hi) = robot.robot.frame_bounding_box();
        let (x0, x1, y0, y1) = match &args.area {
            Some(b) if b.len() == 4 => (b[0], b[1], b[2], b[3]),
            Some(b) => return Err(format!("--box needs 4 numbers, got {}", b.len()).into()),
            None => (lo.x, hi.x, lo.y, hi.y),
        };
        if !(x0 < x1 && y0 < y1 && [x0, x1, y0, y1].iter().all(|v| v.is_finite())) {
            return Err(
                format!("the grid box [{x0}, {x1}] × [{y0}, {y1}] is empty or not finite").into(),
            );
        }
        let z = args.z.unwrap_or(0.5 * (lo.z + hi.z));
        if !z.is_finite() || !args.orientation.is_finite() {
            return Err("--z and --orientation must be finite".into());
        }
        let k = m + 1;
        let axis = |a: f64, b: f64| -> Vec<f64> {
            (0..k).map(|i| a + (b - a) * i as f64 / m as f64).collect()
        };
        let (xs, ys) = (axis(x0, x1), axis(y0, y1));
        let slice_pose = grid_pose(motion, x0, y0, z, args.orientation);
        let w_ext = external_wrench(robot, &slice_pose, args.wrench.as_deref())?;
        let template =
            IsotropicForce::new(&robot.robot, &robot.bounds)?.with_load(w_ext.as_slice())?;
        let bar = if std::io::stderr().is_terminal() {
            ProgressBar::new(k as u64)
        } else {
            ProgressBar::hidden()
        };
        let rows: Vec<Vec<f64>> = ys
            .par_iter()
            .map_init(
                || template.clone(),
                |index, &y| {
                    let row = xs
                        .iter()
                        .map(|&x| {
                            index
                                .force_at_pose(&grid_pose(motion, x, y, z, args.orientation))
                                .unwrap_or(f64::NAN)
                        })
                        .collect();
                    bar.inc(1);
                    row
                },
            )
            .collect();
        bar.finish_and_clear();
        Ok(Self {
            motion,
            x: (x0, x1),
            y: (y0, y1),
            z,
            orientation: args.orientation,
            k,
            xs,
            ys,
            values: rows.concat(),
            w_ext,
            template,
        })
    }
}

/// What the text, JSON and plot report of a map.
struct MapStats {
    vmin: f64,
    vmax: f64,
    argmax: Option<[f64; 2]>,
    positive: usize,
    undefined: usize,
    /// The index at the centre of the box.
    centre: Option<f64>,
}

impl MapStats {
    fn of(map: &IsotropicMap) -> Self {
        let defined: Vec<(usize, f64)> = map
            .values
            .iter()
            .copied()
            .enumerate()
            .filter(|(_, v)| !v.is_nan())
            .collect();
        let (amax, vmax) = defined
            .iter()
            .copied()
            .fold((usize::MAX, f64::NEG_INFINITY), |a, b| {
                if b.1 > a.1 { b } else { a }
            });
        let k = map.k;
        let centre_pose = grid_pose(
            map.motion,
            0.5 * (map.x.0 + map.x.1),
            0.5 * (map.y.0 + map.y.1),
            map.z,
            map.orientation,
        );
        Self {
            vmin: defined.iter().map(|p| p.1).fold(f64::INFINITY, f64::min),
            vmax,
            argmax: (amax != usize::MAX).then(|| [map.xs[amax % k], map.ys[amax / k]]),
            positive: defined.iter().filter(|p| p.1 > 0.0).count(),
            undefined: map.values.len() - defined.len(),
            centre: map.template.clone().force_at_pose(&centre_pose).ok(),
        }
    }
}

/// The heat map of `--grid --plot`.
fn save_heat_map(
    robot: &RobotDescription,
    map: &IsotropicMap,
    stats: &MapStats,
    path: &std::path::Path,
) -> Result<(), CliError> {
    let fig = HeatMap {
        title: format!(
            "{}: maximum isotropic force{}",
            robot.name,
            if map.motion.has_orientation() {
                " at zero moment"
            } else {
                ""
            }
        ),
        labels: (
            super::region::length_axis("x"),
            super::region::length_axis("y"),
        ),
        value_label: "isotropic force (N)".into(),
        x_range: map.x,
        y_range: map.y,
        shape: (map.k, map.k),
        values: map.values.clone(),
        blank_below: 0.0,
        markers: robot
            .robot
            .cables()
            .iter()
            .map(|c| (c.frame.x, c.frame.y))
            .collect(),
        outlines: Vec::new(),
        highlight: match stats.argmax {
            Some([x, y]) if stats.vmax > 0.0 => {
                vec![((x, y), format!("max {:.1} N", stats.vmax))]
            }
            _ => Vec::new(),
        },
    };
    cdpr::plot::save(&fig, path)?;
    Ok(())
}

/// The `--grid --json` answer.
fn map_json(robot: &RobotDescription, map: &IsotropicMap, stats: &MapStats) -> serde_json::Value {
    let finite = |v: f64| v.is_finite().then_some(v);
    let grid_rows: Vec<Vec<Option<f64>>> = map
        .values
        .chunks(map.k)
        .map(|r| r.iter().map(|&v| finite(v)).collect())
        .collect();
    let mut slice = json!({ "orientation": map.orientation });
    if map.motion.space_dim() == 3 {
        slice["z"] = json!(map.z);
    }
    json!({
        "robot": robot.name,
        "definition": definition(map.motion),
        "external_wrench": map.w_ext.as_slice(),
        "slice": slice,
        "grid": {
            "x": map.xs,
            "y": map.ys,
            "shape": [map.k, map.k],
            "values": grid_rows,
        },
        "stats": {
            "min": finite(stats.vmin),
            "max": finite(stats.vmax),
            "argmax": stats.argmax,
            "positive_fraction": stats.positive as f64 / map.values.len() as f64,
            "undefined": stats.undefined,
            "centre": stats.centre.and_then(finite),
        },
    })
}

/// The text answer of `--grid`.
fn print_map(args: &Args, robot: &RobotDescription, map: &IsotropicMap, stats: &MapStats) {
    let k = map.k;
    // A 3-D robot is mapped in the horizontal plane at one height: say which.
    let height = if map.motion.space_dim() == 3 {
        format!(" at z = {} m", num(map.z))
    } else {
        String::new()
    };
    println!(
        "robot {}: maximum isotropic force over [{}, {}] m × [{}, {}] m{height}, {k} × {k} points",
        robot.name,
        num(map.x.0),
        num(map.x.1),
        num(map.y.0),
        num(map.y.1)
    );
    println!(
        "on top of w_ext {} (the platform's weight{} included)",
        wrench_text(map.w_ext.as_slice(), map.motion.translation_dof()),
        if args.wrench.is_some() {
            " and --wrench"
        } else {
            ""
        }
    );
    println!("  ({})", definition(map.motion));
    match stats.argmax {
        Some([x, y]) => println!(
            "max {:.6} N at ({} m, {} m); min {:.6} N",
            stats.vmax,
            num(x),
            num(y),
            stats.vmin
        ),
        None => println!("no defined value"),
    }
    if let Some(c) = stats.centre {
        println!("centre of the box: {c:.6} N");
    }
    println!(
        "positive (pose holds every force up to the index): {:.1} % of the grid; undefined: {}",
        100.0 * stats.positive as f64 / map.values.len() as f64,
        stats.undefined
    );
}
