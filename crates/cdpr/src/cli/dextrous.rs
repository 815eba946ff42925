//! `cdpr dextrous`: the dextrous workspace over a range of orientations (thesis eq. 6.28).

use super::criteria::CriteriaArgs;
use super::region::{draw_pose, load_text, progress, resolution, save_grid_plot};
use super::{CliError, Numbers, print_report, request_robot};
use cdpr::api::{DextrousReport, DextrousRequest, RangeReport};
use cdpr::kinematics::MotionPattern;
use cdpr::plot::tick;
use cdpr::workspace::{OrientationRange, VolumeConvention};
use std::path::{Path, PathBuf};
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

/// Runs the command: parse → request → run → render.
pub fn run(args: Args) -> Result<(), CliError> {
    let numbers = |n: &Option<Numbers>| n.as_ref().map(|n| n.0.clone());
    let r = args.orientations.0;
    let mut request = DextrousRequest::new(
        request_robot(&args.robot)?,
        RangeReport {
            min: r.min,
            max: r.max,
            slices: r.slices,
        },
    );
    request.criteria = args.criteria.to_request();
    (request.axis, request.orientation) = (numbers(&args.axis), numbers(&args.orientation));
    (request.area, request.grid) = (numbers(&args.area), args.grid);
    request.volume_convention = args.volume_convention;
    request.validate()?;
    let dim = request.robot.robot.motion().space_dim();
    let m = resolution(request.grid, dim, 50)?;
    let bar = progress((m + 1).pow(dim as u32 - 1));
    let report = request.run_with_progress(&|| bar.inc(1))?;
    bar.finish_and_clear();
    if let Some(path) = &args.plot {
        save_dextrous_plot(&request, &report, args.draw_pose.as_deref(), path)?;
    }
    if args.json {
        return print_report(&report);
    }
    print_dextrous(&report, request.volume_convention);
    if let Some(p) = &args.plot {
        println!("plot written to {}", p.display());
    }
    Ok(())
}

/// "area" and "m²" in the plane, "volume" and "m³" in space.
fn measure_words(dim: usize) -> (&'static str, &'static str) {
    if dim == 2 {
        ("area", "m²")
    } else {
        ("volume", "m³")
    }
}

/// The grid figure of the dextrous workspace, the robot drawn at the central orientation.
fn save_dextrous_plot(
    request: &DextrousRequest,
    r: &DextrousReport,
    q: Option<&[f64]>,
    path: &Path,
) -> Result<(), CliError> {
    let desc = request.robot.description();
    let motion = desc.robot.motion();
    let region = &r.workspace.grid.region;
    let pose = draw_pose(&desc.robot, q, region, &r.central_rotation)?;
    let load = load_text(motion, &r.central_wrench, &r.tension_method);
    let about = match motion {
        MotionPattern::Spatial => format!(
            " about the axis [{}, {}, {}]",
            tick(r.axis.x),
            tick(r.axis.y),
            tick(r.axis.z)
        ),
        _ => String::new(),
    };
    let o = &r.orientations;
    let setting = format!(
        "every orientation φ ∈ [{}, {}] rad{about} ({} slices); {load}",
        tick(o.min),
        tick(o.max),
        o.slices
    );
    let (what, unit) = measure_words(r.dimension);
    let measure = format!(
        "dextrous {what} {:.4} {unit} ({} of {} points, m = {}, {} convention); §6.5 check {}",
        r.area,
        r.feasible_points,
        r.total_points,
        r.resolution,
        r.volume_convention,
        if r.central_check.holds {
            "holds"
        } else {
            "fails"
        }
    );
    let title = format!("{}: dextrous workspace (grid)", desc.name);
    save_grid_plot(
        desc,
        &pose,
        &r.workspace,
        title,
        vec![setting, measure],
        path,
    )
}

/// The text answer.
fn print_dextrous(r: &DextrousReport, conv: VolumeConvention) {
    let (what, unit) = measure_words(r.dimension);
    let o = &r.orientations;
    println!(
        "robot {}: dextrous workspace for φ ∈ [{}, {}] rad, {} slices",
        r.robot, o.min, o.max, o.slices
    );
    println!(
        "criteria: {} (tensions: {})",
        r.criteria.join(", "),
        r.tension_method
    );
    println!(
        "grid m = {} over {} m: {} of {} points feasible at every orientation, cell {what} \
         {:.6e} {unit}",
        r.resolution,
        super::nums(&r.area_box),
        r.feasible_points,
        r.total_points,
        r.cell_area
    );
    println!("dextrous {what} {:.6} {unit} ({})", r.area, conv.describe());
    let c = &r.central_check;
    println!(
        "§6.5 check (central orientation contains the two extremes' intersection): {} ({} violating \
         of {} points feasible at both extremes)",
        if c.holds { "holds" } else { "FAILS" },
        c.violations,
        c.extremes_points
    );
}
