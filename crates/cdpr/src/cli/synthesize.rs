//! `cdpr synthesize`: dimensional synthesis of a planar robot for maximal dextrous workspace
//! (thesis §6.6, eq. 6.29).

use super::criteria::CriteriaArgs;
use super::dextrous::Range;
use super::region::{save_plot, workspace_plot};
use super::{CliError, Numbers, print_report, request_robot};
use cdpr::api::{RangeReport, SynthesisOptimizer, SynthesisReport, SynthesisRequest};
use cdpr::kinematics::Pose;
use cdpr::workspace::VolumeConvention;
use indicatif::ProgressBar;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};

/// The long help of the command (`--help`), also its documentation.
const LONG_HELP: &str = "\
Dimensional synthesis (thesis §6.6): place the frame anchors on the 2 × 2 square frame
[−1, 1]² to maximise the dextrous workspace area A_d (eq. 6.29).

The design is d = [β1, …, βn]: anchor i sits where the ray from the origin at polar angle βi
(rad) meets the square frame. The platform attachments, tension limits, l_min and D_min come
from the robot file (a planar robot; its frame anchors are replaced by the design). The only
constraint is a minimum angular separation β_min between consecutive anchors, the pair (n, 1)
included, measured the short way round (--min-separation).

The objective is the dextrous area on a fixed grid (--grid M over --grid-box, default the whole
frame, as the thesis' published areas show), for the orientation range --orientations and the
load --wrench (plus gravity) with the workspace criteria of `cdpr workspace`. It is piecewise
constant in d (grid noise), hence the optimisers:
  dynamic-q          the thesis' Dynamic-Q (spherical quadratic approximations, move limit
                     --move-limit ρ, central differences over the wide interval --fd-interval Γ);
  compass            derivative-free compass search with restarts (exact penalty);
  dynamic-q-compass  (default) Dynamic-Q, then the compass search polishes its answer;
  global             dynamic-q-compass, then a global stage: 128 quasi-random designs over
                     every anchor placement with the start's cyclic order (and cables that leave
                     the platform outwards), the best 3 polished by the compass search; the
                     best design of all is returned (seeded, deterministic; slower).

Thesis settings (Tables 6.5–6.10): 3 cables --orientations -0.1:0.1:3 --grid 100, 4 cables
--orientations -0.2:0.2:21 --grid 50; loads L1 0,-10,0; L2 5,-10,0; L3 5,-10,1.

A_d is counted as the thesis does (feasible points × cell area, JSON `volume_convention`
\"points\"), so that its published areas are reproduced; `cdpr dextrous --volume-convention
points` gives the same number for a design.

JSON: `design` (optimised angles, rad, shifted by whole turns so that β1 ∈ [−π, π]), `area` (its A_d, m²), `evaluations` {`function`,
`gradient`}, `start`, `start_area`, `termination` (\"converged\" or \"budget\"), `anchors`
(optimised frame points), `constraint_violation`, `iterations`, `feasible_points`,
`total_points`, `cell_area`, `central_check`.";

/// Arguments of the command; see [`LONG_HELP`].
#[derive(clap::Args)]
#[command(allow_negative_numbers = true, after_long_help = LONG_HELP)]
pub struct Args {
    /// Robot file: .toml, CASPR NAME_cables.xml or WireCenter .wcrfx, planar: platform attachments, limits and gravity are used.
    robot: PathBuf,
    /// Orientation range MIN:MAX:M_SL of the dextrous workspace, e.g. -0.1:0.1:3.
    #[arg(long, allow_hyphen_values = true, value_name = "MIN:MAX:M_SL")]
    orientations: Range,
    #[command(flatten)]
    criteria: CriteriaArgs,
    /// Grid resolution M of the objective: (M+1)² points over --grid-box. Default 100 for n = 3
    /// cables, 50 otherwise (the thesis).
    #[arg(long, value_name = "M", value_parser = super::count)]
    grid: Option<usize>,
    /// Box of the objective's grid XMIN,XMAX,YMIN,YMAX (default the whole frame -1,1,-1,1).
    #[arg(long, allow_hyphen_values = true, value_name = "XMIN,XMAX,YMIN,YMAX")]
    grid_box: Option<Numbers>,
    /// Starting design β1,…,βn (rad), one angle per cable of the robot file.
    #[arg(long, allow_hyphen_values = true, value_name = "β1,…,βn")]
    start: Numbers,
    /// Optimiser: dynamic-q, compass, dynamic-q-compass or global.
    #[arg(long, default_value = "dynamic-q-compass", value_parser = ["dynamic-q", "compass", "dynamic-q-compass", "global"])]
    optimizer: String,
    /// β_min (rad): minimum separation of consecutive anchors. Default π/18 (10°), the separation
    /// active at every published optimum.
    #[arg(long, value_parser = super::non_negative)]
    min_separation: Option<f64>,
    /// Dynamic-Q move limit ρ (rad).
    #[arg(long, default_value_t = 0.1, value_parser = super::positive)]
    move_limit: f64,
    /// Dynamic-Q central-difference interval Γ (rad). Default 0.05 for 3 cables, 0.1 otherwise.
    #[arg(long, value_parser = super::positive)]
    fd_interval: Option<f64>,
    /// Write the optimised design's dextrous workspace (.svg or .png).
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Write one JSON object on stdout.
    #[arg(long)]
    json: bool,
}

/// The request of the command line.
fn request(args: &Args) -> Result<SynthesisRequest, CliError> {
    let r = args.orientations.0;
    let range = RangeReport {
        min: r.min,
        max: r.max,
        slices: r.slices,
    };
    let mut request =
        SynthesisRequest::new(request_robot(&args.robot)?, range, args.start.0.clone());
    request.criteria = args.criteria.to_request();
    request.grid = args.grid;
    request.grid_box = args.grid_box.as_ref().map(|b| b.0.clone());
    request.optimizer = SynthesisOptimizer::from_name(&args.optimizer).unwrap_or_default();
    request.min_separation = args.min_separation;
    request.move_limit = args.move_limit;
    request.fd_interval = args.fd_interval;
    Ok(request)
}

/// Runs the command: parse → request → run → render.
pub fn run(args: Args) -> Result<(), CliError> {
    let request = request(&args)?;
    request.validate()?;
    let bar = if std::io::stderr().is_terminal() {
        ProgressBar::new_spinner()
    } else {
        ProgressBar::hidden()
    };
    let report = request.run_with_progress(&|calls| {
        bar.set_message(format!("{calls} area evaluations"));
        bar.tick();
    })?;
    bar.finish_and_clear();
    if let Some(path) = &args.plot {
        save_synthesis_plot(&report, path)?;
    }
    if args.json {
        return print_report(&report);
    }
    print_synthesis(&report);
    if let Some(p) = &args.plot {
        println!("plot written to {}", p.display());
    }
    Ok(())
}

/// Angles with 4 decimals, comma-separated.
fn angles(v: &[f64]) -> String {
    v.iter()
        .map(|b| format!("{b:.4}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The optimised design's dextrous workspace on the square frame.
fn save_synthesis_plot(report: &SynthesisReport, path: &Path) -> Result<(), CliError> {
    let opt = report.optimised_robot()?;
    let region = report.workspace.grid.region;
    let c = (region.min + region.max) * 0.5;
    let range = report.orientations;
    let pose = Pose::planar(c.x, c.y, 0.5 * (range.min + range.max));
    let mut fig = workspace_plot(
        &opt,
        &pose,
        Some(&report.workspace),
        Vec::new(),
        format!(
            "{}: optimised design, dextrous workspace φ ∈ [{}, {}]",
            report.robot, range.min, range.max
        ),
        vec![format!(
            "A_d = {:.4} (start {:.4}); β = {}",
            report.area,
            report.start_area,
            angles(&report.design_raw)
        )],
    );
    fig.frame = vec![(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    save_plot(&fig, path)
}

/// The report as text.
fn print_synthesis(r: &SynthesisReport) {
    let o = r.orientations;
    println!(
        "robot {}: synthesis of {} frame anchors for the dextrous workspace φ ∈ [{}, {}] ({} slices), \
         grid m = {}",
        r.robot,
        r.start.len(),
        o.min,
        o.max,
        o.slices,
        r.resolution
    );
    println!(
        "criteria: {} (tensions: {}); optimiser {}, β_min = {:.4}",
        r.criteria.join(", "),
        r.tension_method,
        r.optimizer,
        r.min_separation
    );
    println!("A_d in m², {}", VolumeConvention::Points.describe());
    println!(
        "start    d0 = [{}]  A_d = {:.6}",
        angles(&r.start),
        r.start_area
    );
    println!(
        "optimum  d* = [{}]  A_d = {:.6} ({} points)",
        angles(&r.design),
        r.area,
        r.feasible_points
    );
    for (i, a) in r.anchors.iter().enumerate() {
        println!("  anchor c{} = ({:.4}, {:.4})", i + 1, a[0], a[1]);
    }
    println!(
        "{} area evaluations, {} gradients, {} iterations, {}; constraint violation {:.2e}",
        r.evaluations.function,
        r.evaluations.gradient,
        r.iterations,
        r.termination,
        r.constraint_violation
    );
    if !r.central_check.holds {
        println!(
            "note: the §6.5 central check fails at the optimum ({} points): consider more slices",
            r.central_check.violations
        );
    }
}
