//! `cdpr synthesize`: dimensional synthesis of a planar robot for maximal dextrous workspace
//! (thesis §6.6, eq. 6.29).

use super::criteria::{CriteriaArgs, CriteriaSetup};
use super::dextrous::Range;
use super::region::{box_json, region, save_plot, workspace_plot};
use super::{CliError, Numbers, load_robot, print_json};
use cdpr::RobotDescription;
use cdpr::api::{Dextrous, dextrous};
use cdpr::kinematics::{MotionPattern, Pose};
use cdpr::tension::Method;
use cdpr::workspace::synthesis::{
    Method as Optimizer, SynthesisSettings, Termination, frame_anchor, in_first_turn,
    robot_from_design, separation_violation, synthesise,
};
use cdpr::workspace::{Grid, OrientationRange, VolumeConvention};
use indicatif::ProgressBar;
use nalgebra::{Rotation3, Vector3};
use serde_json::json;
use std::io::IsTerminal;
use std::path::PathBuf;

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

/// The thesis' tension method: exact for n = DOF, Algorithm 6.1 (the closed-form constrained
/// minimum ℓ1) for n = DOF + 1, the ℓ1 linear program otherwise.
fn default_method(n: usize, dof: usize) -> Method {
    if n == dof {
        Method::Exact
    } else if n == dof + 1 {
        Method::ClosedForm
    } else {
        Method::L1
    }
}

/// Everything the objective needs.
struct Problem<'a> {
    desc: &'a RobotDescription,
    setup: CriteriaSetup,
    platform: Vec<[f64; 2]>,
    range: OrientationRange,
    grid: Grid,
}

impl Problem<'_> {
    fn dextrous(&self, design: &[f64]) -> Result<Dextrous, CliError> {
        let robot = robot_from_design(design, &self.platform)?;
        dextrous(
            &self.setup,
            self.desc,
            &robot,
            &Rotation3::identity(),
            &Vector3::z_axis(),
            &self.range,
            &self.grid,
            &|| {},
        )
        .map_err(CliError::from)
    }
}

/// Runs the command.
pub fn run(args: Args) -> Result<(), CliError> {
    let desc = load_robot(&args.robot)?;
    desc.require_no_passive_springs("synthesize")?;
    let robot = &desc.robot;
    if robot.motion() != MotionPattern::Planar {
        return Err(format!(
            "synthesize places anchors on the planar square frame; this robot is `{}` (need planar)",
            robot.motion().name()
        )
        .into());
    }
    let n = robot.cable_count();
    if args.start.len() != n {
        return Err(format!(
            "--start has {} angles but the robot file has {n} cables (one angle per cable)",
            args.start.len()
        )
        .into());
    }
    let method = args
        .criteria
        .method
        .unwrap_or_else(|| default_method(n, robot.dof()));
    let setup = super::criteria::setup(&args.criteria, &desc, method)?;
    let platform: Vec<[f64; 2]> = robot
        .cables()
        .iter()
        .map(|c| [c.platform.x, c.platform.y])
        .collect();
    let frame_box = [-1.0, 1.0, -1.0, 1.0];
    let region = region(
        robot,
        Some(args.grid_box.as_deref().unwrap_or(&frame_box)),
        "--grid-box",
    )?;
    let m = args.grid.unwrap_or(if n == robot.dof() { 100 } else { 50 });
    if !(1..=1000).contains(&m) {
        return Err("--grid M must lie in [1, 1000]".into());
    }
    let problem = Problem {
        desc: &desc,
        setup,
        platform,
        range: args.orientations.0,
        grid: Grid::new(m, region),
    };
    let mut settings = SynthesisSettings {
        method: match args.optimizer.as_str() {
            "dynamic-q" => Optimizer::DynamicQ,
            "compass" => Optimizer::CompassSearch,
            "global" => Optimizer::Global,
            _ => Optimizer::DynamicQThenCompass,
        },
        ..SynthesisSettings::default()
    };
    settings.multi_start.platform = Some(problem.platform.clone());
    if let Some(b) = args.min_separation {
        settings.min_separation = b;
    }
    settings.dynamic_q.move_limit = args.move_limit;
    settings.dynamic_q.fd_interval = args.fd_interval.unwrap_or(if n <= 3 { 0.05 } else { 0.1 });
    settings.validate()?;
    settings
        .check_feasible_separation(n)
        .map_err(|e| format!("--min-separation: {e}"))?;
    // Bad input (a non-finite angle, an invalid criterion) is reported here, not hidden as −∞.
    let start_ws = problem.dextrous(&args.start)?;
    let bar = if std::io::stderr().is_terminal() {
        ProgressBar::new_spinner()
    } else {
        ProgressBar::hidden()
    };
    let mut calls = 0usize;
    let mut objective = |d: &[f64]| -> f64 {
        calls += 1;
        bar.set_message(format!("{calls} area evaluations"));
        bar.tick();
        problem
            .dextrous(d)
            .map_or(f64::NEG_INFINITY, |w| w.workspace.area)
    };
    let result = synthesise(&mut objective, &args.start, &settings)?;
    bar.finish_and_clear();
    let best = problem.dextrous(&result.design)?;
    let anchors: Vec<[f64; 2]> = result.design.iter().map(|&b| frame_anchor(b)).collect();
    let termination = match result.termination {
        Termination::Converged => "converged",
        Termination::Budget => "budget",
    };
    if let Some(path) = &args.plot {
        let opt = robot_from_design(&result.design, &problem.platform)?;
        let c = (region.min + region.max) * 0.5;
        let pose = Pose::planar(c.x, c.y, problem.range.central());
        let mut fig = workspace_plot(
            &opt,
            &pose,
            Some(&best.workspace),
            Vec::new(),
            format!(
                "{}: optimised design, dextrous workspace φ ∈ [{}, {}]",
                desc.name, problem.range.min, problem.range.max
            ),
            vec![format!(
                "A_d = {:.4} (start {:.4}); β = {}",
                result.area,
                start_ws.workspace.area,
                result
                    .design
                    .iter()
                    .map(|b| format!("{b:.4}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            )],
        );
        fig.frame = vec![(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
        save_plot(&fig, path)?;
    }
    if args.json {
        return print_json(&json!({
            "robot": desc.name,
            "optimizer": args.optimizer,
            "criteria": problem.setup.labels(),
            "tension_method": method.name(),
            "orientations": { "min": problem.range.min, "max": problem.range.max, "slices": problem.range.slices },
            "resolution": m,
            "box": box_json(&region, 2),
            "min_separation": settings.min_separation,
            "start": args.start.0,
            "start_area": start_ws.workspace.area,
            "start_constraint_violation": separation_violation(&args.start, settings.min_separation),
            "design": in_first_turn(&result.design),
            "area": result.area,
            "anchors": anchors,
            "constraint_violation": result.constraint_violation,
            "evaluations": { "function": result.evaluations.function, "gradient": result.evaluations.gradient },
            "iterations": result.iterations,
            "termination": termination,
            "feasible_points": best.workspace.feasible_points,
            "total_points": best.workspace.total_points,
            "cell_area": best.workspace.cell_area,
            "volume_convention": VolumeConvention::Points.name(),
            "central_check": {
                "holds": best.central_check.holds,
                "violations": best.central_check.violations,
                "extremes_points": best.central_check.extremes_points,
            },
        }));
    }
    let fmt = |v: &[f64]| {
        v.iter()
            .map(|b| format!("{b:.4}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    println!(
        "robot {}: synthesis of {n} frame anchors for the dextrous workspace φ ∈ [{}, {}] ({} slices), \
         grid m = {m}",
        desc.name, problem.range.min, problem.range.max, problem.range.slices
    );
    println!(
        "criteria: {} (tensions: {}); optimiser {}, β_min = {:.4}",
        problem.setup.labels().join(", "),
        method.name(),
        args.optimizer,
        settings.min_separation
    );
    println!("A_d in m², {}", VolumeConvention::Points.describe());
    println!(
        "start    d0 = [{}]  A_d = {:.6}",
        fmt(&args.start),
        start_ws.workspace.area
    );
    println!(
        "optimum  d* = [{}]  A_d = {:.6} ({} points)",
        fmt(&in_first_turn(&result.design)),
        result.area,
        best.workspace.feasible_points
    );
    for (i, a) in anchors.iter().enumerate() {
        println!("  anchor c{} = ({:.4}, {:.4})", i + 1, a[0], a[1]);
    }
    println!(
        "{} area evaluations, {} gradients, {} iterations, {termination}; constraint violation {:.2e}",
        result.evaluations.function,
        result.evaluations.gradient,
        result.iterations,
        result.constraint_violation
    );
    if !best.central_check.holds {
        println!(
            "note: the §6.5 central check fails at the optimum ({} points): consider more slices",
            best.central_check.violations
        );
    }
    if let Some(p) = &args.plot {
        println!("plot written to {}", p.display());
    }
    Ok(())
}
