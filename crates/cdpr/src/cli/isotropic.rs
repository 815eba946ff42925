//! `cdpr isotropic`: the maximum isotropic force (Krut, Company & Pierrot 2004, §IV) at a pose, or its map.

use super::{CliError, Numbers, load_robot, num, pose_text, print_report, wrench_text};
use cdpr::RobotDescription;
use cdpr::api::{
    IsotropicMapReport, IsotropicMapRequest, IsotropicReport, IsotropicRequest, Robot,
};
use cdpr::kinematics::MotionPattern;
use cdpr::nalgebra::DVector;
use cdpr::plot::{ForcePolygonPlot, HeatMap};
use cdpr::polytope::largest_inscribed_ellipse;
use indicatif::ProgressBar;
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
    /// Grid: height z of the slice for 3-D robots (default: middle of the default region: the frame
    /// anchors' heights, or for a suspended robot down to half the frame's width below them).
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
    let request = IsotropicRequest {
        robot: Robot::from_description(robot.clone()),
        pose: q.to_vec(),
        wrench: args.wrench.as_ref().map(|w| w.0.clone()),
        ellipse: args.ellipse,
    };
    request.validate()?;
    if let Some(path) = args.plot.as_ref().filter(|_| !html) {
        plot_polygon(&request, path)?;
    }
    let report = request.run()?;
    if args.json {
        return print_report(&report);
    }
    if let Some(path) = args.plot.as_ref().filter(|_| html) {
        let w_ext = DVector::from_column_slice(&report.external_wrench);
        let aws = request.wrench_set()?;
        save_polytope_view(robot, q, &aws, &w_ext, report.isotropic_force, path)?;
    }
    print_pose_text(&report, motion, args);
    Ok(())
}

/// The available force polygon with its largest centred circle and ellipse (point2 robots).
fn plot_polygon(request: &IsotropicRequest, path: &std::path::Path) -> Result<(), CliError> {
    let aws = request.wrench_set()?;
    let ellipse = largest_inscribed_ellipse(&aws)?;
    let mut fig = ForcePolygonPlot::operational(&aws, ellipse.as_ref())
        .ok_or("the force polygon is unbounded (an infinite t_max): nothing to draw")?;
    fig.title = format!(
        "{}: available force polygon {{W t}} at position ({})",
        request.robot.name,
        request
            .pose
            .iter()
            .map(|v| cdpr::plot::tick(*v))
            .collect::<Vec<_>>()
            .join(", ")
    );
    cdpr::plot::save(&fig, path)?;
    Ok(())
}

/// The pose report as text.
fn print_pose_text(r: &IsotropicReport, motion: MotionPattern, args: &Args) {
    let forces = motion.translation_dof();
    println!(
        "robot {}, pose {}",
        r.robot,
        pose_text(&r.pose, motion.space_dim())
    );
    println!(
        "external wrench w_ext {} (the platform's weight{} included)",
        wrench_text(&r.external_wrench, forces),
        if args.wrench.is_some() {
            " and --wrench"
        } else {
            ""
        }
    );
    println!(
        "maximum isotropic force on top of w_ext: {:.6} N",
        r.isotropic_force
    );
    println!("  ({})", r.definition);
    println!(
        "wrench-space ball radius: {:.6} {}",
        r.wrench_radius,
        if forces == r.external_wrench.len() {
            "N"
        } else {
            "(N and N·m combined, length scale 1 m)"
        }
    );
    println!("available wrench set: {} facets", r.facets);
    if r.isotropic_force < 0.0 {
        println!("w_ext is outside the set of wrenches the cables can balance: it cannot be held");
    }
    match &r.ellipse {
        Some(Some(e)) => println!(
            "largest centred ellipse (no load): semi-axes {:.6} N, {:.6} N; major axis at \
             {:.4}°; area {:.6} N²",
            e.semi_axes[0], e.semi_axes[1], e.angle_deg, e.area
        ),
        Some(None) => println!("largest centred ellipse: none (the origin is not strictly inside)"),
        None => {}
    }
    if let Some(p) = &args.plot {
        let what = if super::region::is_html(p) {
            "force polytope view"
        } else {
            "force polygon"
        };
        println!("{what} written to {}", p.display());
    }
}

fn run_grid(args: &Args, robot: &RobotDescription, m: usize) -> Result<(), CliError> {
    let request = IsotropicMapRequest {
        robot: Robot::from_description(robot.clone()),
        grid: m,
        area: args.area.as_ref().map(|b| b.0.clone()),
        orientation: args.orientation,
        wrench: args.wrench.as_ref().map(|w| w.0.clone()),
        z: args.z,
    };
    request.validate()?;
    let bar = if std::io::stderr().is_terminal() {
        ProgressBar::new(m as u64 + 1)
    } else {
        ProgressBar::hidden()
    };
    let map = request.run_with_progress(&|| bar.inc(1))?;
    bar.finish_and_clear();
    if let Some(path) = &args.plot {
        save_heat_map(robot, &map, path)?;
    }
    if args.json {
        return print_report(&map);
    }
    print_map(args, robot.robot.motion(), &map);
    if let Some(p) = &args.plot {
        println!("heat map written to {}", p.display());
    }
    Ok(())
}

/// The map's values row-major, NaN where undefined.
fn map_values(map: &IsotropicMapReport) -> Vec<f64> {
    let values = map.grid.values.iter().flatten();
    values.map(|v| v.unwrap_or(f64::NAN)).collect()
}

/// The first and last of an axis.
fn range(axis: &[f64]) -> (f64, f64) {
    (
        axis.first().copied().unwrap_or(0.0),
        axis.last().copied().unwrap_or(0.0),
    )
}

/// The heat map of `--grid --plot`.
fn save_heat_map(
    robot: &RobotDescription,
    map: &IsotropicMapReport,
    path: &std::path::Path,
) -> Result<(), CliError> {
    let stats = &map.stats;
    let fig = HeatMap {
        title: format!(
            "{}: maximum isotropic force{}",
            robot.name,
            if robot.robot.motion().has_orientation() {
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
        x_range: range(&map.grid.x),
        y_range: range(&map.grid.y),
        shape: (map.grid.shape[0], map.grid.shape[1]),
        values: map_values(map),
        blank_below: 0.0,
        markers: robot
            .robot
            .cables()
            .iter()
            .map(|c| (c.frame.x, c.frame.y))
            .collect(),
        outlines: Vec::new(),
        highlight: match (stats.argmax, stats.max) {
            (Some([x, y]), Some(vmax)) if vmax > 0.0 => {
                vec![((x, y), format!("max {vmax:.1} N"))]
            }
            _ => Vec::new(),
        },
    };
    cdpr::plot::save(&fig, path)?;
    Ok(())
}

/// The text answer of `--grid`.
fn print_map(args: &Args, motion: MotionPattern, map: &IsotropicMapReport) {
    let (k, stats) = (map.grid.shape[0], &map.stats);
    let ((x0, x1), (y0, y1)) = (range(&map.grid.x), range(&map.grid.y));
    // A 3-D robot is mapped in the horizontal plane at one height: say which.
    let height = match map.slice.z {
        Some(z) => format!(" at z = {} m", num(z)),
        None => String::new(),
    };
    println!(
        "robot {}: maximum isotropic force over [{}, {}] m × [{}, {}] m{height}, {k} × {k} points",
        map.robot,
        num(x0),
        num(x1),
        num(y0),
        num(y1)
    );
    println!(
        "on top of w_ext {} (the platform's weight{} included)",
        wrench_text(&map.external_wrench, motion.translation_dof()),
        if args.wrench.is_some() {
            " and --wrench"
        } else {
            ""
        }
    );
    println!("  ({})", map.definition);
    match stats.argmax {
        Some([x, y]) => println!(
            "max {:.6} N at ({} m, {} m); min {:.6} N",
            stats.max.unwrap_or(f64::NAN),
            num(x),
            num(y),
            stats.min.unwrap_or(f64::NAN)
        ),
        None => println!("no defined value"),
    }
    if let Some(c) = stats.centre {
        println!("centre of the box: {c:.6} N");
    }
    println!(
        "positive (pose holds every force up to the index): {:.1} % of the grid; undefined: {}",
        100.0 * stats.positive_fraction,
        stats.undefined
    );
}
