//! `cdpr dextrous`: the dextrous workspace over a range of orientations (thesis eq. 6.28).

use super::criteria::{CriteriaArgs, default_method};
use super::region::{
    box_json, box_numbers, dextrous, draw_pose, load_text, measure_json, progress, region,
    resolution, rotation, save_grid_plot,
};
use super::{CliError, Numbers, load_robot, print_json};
use cdpr::kinematics::MotionPattern;
use cdpr::plot::tick;
use cdpr::workspace::{Grid, OrientationRange, VolumeConvention};
use nalgebra::{Rotation3, Unit, Vector3};
use serde_json::json;
use std::path::PathBuf;
use std::str::FromStr;

/// The long help of the command (`--help`), also its documentation.
const LONG_HELP: &str = "\
Dextrous workspace W^D[φ_min, φ_max] (thesis eq. 6.28): the positions where every
orientation of the range is feasible, i.e. the intersection of the constant-orientation
workspaces of M_SL regularly spaced orientations φ_min … φ_max (endpoints included), computed
on one grid of (M+1)² points (Algorithm 6.2 with step 4 tested for every orientation).

The §6.5 check (Du Plessis & Snyman): the cheap two-extremes estimate is valid when the
workspace at the central orientation (φ_min + φ_max)/2 contains the intersection of the two
extreme ones; `central_check` reports whether that holds on the grid and how many points
violate it (if any do, increase M_SL).

Planar robots rotate about z. Spatial robots rotate by --orientation · R(--axis, φ) (default
axis z). Point robots have no orientation: the result is the constant-orientation workspace.
The criteria and the load are those of `cdpr workspace` (see its help); the platform's gravity
is evaluated at each orientation.

The area counts each feasible point's grid cell clipped to the box (--volume-convention cells,
the default: never more than the box) or feasible points × cell area (--volume-convention
points: the thesis' convention, which reproduces its published A_d of Tables 6.5–6.10).

JSON: `area` (the dextrous area A_d, m²; in space also `volume`, m³, same number) in the
convention `volume_convention` (\"cells\" or \"points\"), `area_cells` and `area_points` (both),
`feasible_points`, `total_points`, `cell_area` (m² or m³), `central_check` {`holds`,
`violations`, `extremes_points`}, `angles` (rad), `resolution`, `box` (m), `criteria`.";

/// Arguments of the command; see [`LONG_HELP`].
#[derive(clap::Args)]
#[command(allow_negative_numbers = true, after_long_help = LONG_HELP)]
pub struct Args {
    /// Robot file: .toml, CASPR NAME_cables.xml or WireCenter .wcrfx.
    robot: PathBuf,
    /// Orientation range MIN:MAX:M_SL (radians, M_SL ≥ 2 slices with endpoints), e.g.
    /// -0.1:0.1:3 (the thesis' 3-cable setting) or -0.2:0.2:21 (4 cables).
    #[arg(long, allow_hyphen_values = true, value_name = "MIN:MAX:M_SL")]
    orientations: Range,
    /// Spatial robots: rotation axis X,Y,Z of the range (default 0,0,1).
    #[arg(long, allow_hyphen_values = true)]
    axis: Option<Numbers>,
    /// Spatial robots: base orientation rx,ry,rz (XYZ Euler angles) the range rotates from.
    #[arg(long, allow_hyphen_values = true)]
    orientation: Option<Numbers>,
    #[command(flatten)]
    criteria: CriteriaArgs,
    /// Grid resolution M: (M+1)² points (in space (M+1)³). Default 50 (20 in space).
    #[arg(long, value_name = "M", value_parser = super::count)]
    grid: Option<usize>,
    /// Search box XMIN,XMAX,YMIN,YMAX (space: …,ZMIN,ZMAX); default the frame anchors' bounding
    /// box (the thesis' synthesis uses the whole frame: --box -1,1,-1,1).
    #[arg(
        long = "box",
        allow_hyphen_values = true,
        value_name = "XMIN,XMAX,YMIN,YMAX"
    )]
    area: Option<Numbers>,
    /// How feasible points become an area (volume): `cells` (default) counts each point's grid
    /// cell clipped to the box, so a fully feasible box reports exactly its own area; `points`
    /// is the thesis' feasible points × cell area (Algorithm 6.2), which its published areas
    /// follow and which can exceed the box by up to (1 + 1/M)^dim.
    #[arg(long, default_value = "cells", value_name = "cells|points")]
    volume_convention: VolumeConvention,
    /// Pose at which the robot is drawn (default: centre of the box, central orientation).
    #[arg(long, allow_hyphen_values = true, requires = "plot")]
    draw_pose: Option<Numbers>,
    /// Write the workspace figure (.svg or .png).
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Write one JSON object on stdout.
    #[arg(long)]
    json: bool,
}

/// An orientation range `MIN:MAX:M_SL` on the command line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range(pub OrientationRange);

impl FromStr for Range {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let parts: Vec<&str> = s.split(':').map(str::trim).collect();
        let [a, b, k] = parts[..] else {
            return Err(format!(
                "`{s}`: expected MIN:MAX:M_SL, e.g. -0.1:0.1:3 (radians, M_SL slices)"
            ));
        };
        let num = |t: &str| {
            t.parse::<f64>()
                .map_err(|_| format!("`{t}` is not a number (in `{s}`)"))
        };
        let slices = k
            .parse::<usize>()
            .map_err(|_| format!("M_SL = `{k}` is not a whole number (in `{s}`)"))?;
        let r = OrientationRange {
            min: num(a)?,
            max: num(b)?,
            slices,
        };
        r.validate().map_err(|e| format!("`{s}`: {e}"))?;
        if slices > 10_000 {
            return Err(format!("`{s}`: M_SL must be at most 10000"));
        }
        Ok(Range(r))
    }
}

/// Runs the command.
pub fn run(args: Args) -> Result<(), CliError> {
    let desc = load_robot(&args.robot)?;
    let robot = &desc.robot;
    let motion = robot.motion();
    let dim = motion.space_dim();
    let method = args
        .criteria
        .method
        .unwrap_or_else(|| default_method(robot));
    let setup = super::criteria::setup(&args.criteria, &desc, method)?;
    let (base, axis) = match motion {
        MotionPattern::Spatial => {
            let axis = match args.axis.as_deref() {
                None => Vector3::z_axis(),
                Some([x, y, z]) => Unit::try_new(Vector3::new(*x, *y, *z), 1e-12)
                    .filter(|a| a.iter().all(|v| v.is_finite()))
                    .ok_or("--axis must be a finite non-zero vector X,Y,Z")?,
                Some(a) => {
                    return Err(format!("--axis needs 3 numbers X,Y,Z, got {}", a.len()).into());
                }
            };
            (rotation(motion, args.orientation.as_deref())?, axis)
        }
        _ => {
            if args.axis.is_some() || args.orientation.is_some() {
                return Err(format!(
                    "--axis and --orientation apply to spatial robots; a `{}` robot rotates about z",
                    motion.name()
                )
                .into());
            }
            (Rotation3::identity(), Vector3::z_axis())
        }
    };
    let range = args.orientations.0;
    let region = region(robot, args.area.as_deref(), "--box")?;
    let m = resolution(args.grid, dim, 50)?;
    let grid = Grid::new(m, region);
    let bar = progress(grid.point_count(dim).div_ceil(grid.points_per_axis()));
    let dex = dextrous(&setup, &desc, robot, &base, &axis, &range, &grid, &bar)?;
    let ws = &dex.workspace;
    let check = dex.central_check;
    let (what, unit) = if dim == 2 {
        ("area", "m²")
    } else {
        ("volume", "m³")
    };
    let conv = args.volume_convention;
    if let Some(path) = &args.plot {
        let central = match motion {
            MotionPattern::Point2 | MotionPattern::Point3 => Rotation3::identity(),
            _ => base * Rotation3::from_axis_angle(&axis, range.central()),
        };
        let pose = draw_pose(robot, args.draw_pose.as_deref(), &region, &central)?;
        let w_ext = setup.external_wrench(&desc, &central)?;
        let title = format!("{}: dextrous workspace (grid)", desc.name);
        let load = load_text(motion, w_ext.as_slice(), method.name());
        let about = match motion {
            MotionPattern::Spatial => format!(" about the axis [{}]", {
                let a = axis.into_inner();
                format!("{}, {}, {}", tick(a.x), tick(a.y), tick(a.z))
            }),
            _ => String::new(),
        };
        let setting = format!(
            "every orientation φ ∈ [{}, {}] rad{about} ({} slices); {load}",
            tick(range.min),
            tick(range.max),
            range.slices
        );
        save_grid_plot(
            &desc,
            &pose,
            ws,
            title,
            vec![
                setting,
                format!(
                    "dextrous {what} {:.4} {unit} ({} of {} points, m = {m}, {conv} convention); \
                     §6.5 check {}",
                    ws.measure(conv),
                    ws.feasible_points,
                    ws.total_points,
                    if check.holds { "holds" } else { "fails" }
                ),
            ],
            path,
        )?;
    }
    if args.json {
        let mut v = json!({
            "robot": desc.name,
            "orientations": { "min": range.min, "max": range.max, "slices": range.slices },
            "angles": dex.angles,
            "criteria": setup.labels(),
            "tension_method": method.name(),
            "box": box_json(&region, dim),
            "resolution": m,
            "dimension": dim,
            "feasible_points": ws.feasible_points,
            "total_points": ws.total_points,
            "cell_area": ws.cell_area,
            "central_check": {
                "holds": check.holds,
                "violations": check.violations,
                "extremes_points": check.extremes_points,
            },
        });
        measure_json(&mut v, ws, conv);
        return print_json(&v);
    }
    println!(
        "robot {}: dextrous workspace for φ ∈ [{}, {}] rad, {} slices",
        desc.name, range.min, range.max, range.slices
    );
    println!(
        "criteria: {} (tensions: {})",
        setup.labels().join(", "),
        method.name()
    );
    println!(
        "grid m = {m} over {} m: {} of {} points feasible at every orientation, cell {what} \
         {:.6e} {unit}",
        super::nums(&box_numbers(&region, dim)),
        ws.feasible_points,
        ws.total_points,
        ws.cell_area
    );
    println!(
        "dextrous {what} {:.6} {unit} ({})",
        ws.measure(conv),
        conv.describe()
    );
    println!(
        "§6.5 check (central orientation contains the two extremes' intersection): {} ({} violating \
         of {} points feasible at both extremes)",
        if check.holds { "holds" } else { "FAILS" },
        check.violations,
        check.extremes_points
    );
    if let Some(p) = &args.plot {
        println!("plot written to {}", p.display());
    }
    Ok(())
}
