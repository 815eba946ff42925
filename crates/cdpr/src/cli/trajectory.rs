//! `cdpr trajectory`: tension profiles along a path (issue 8).
//!
//! The waypoints file (`--waypoints FILE.toml`) has these keys:
//!
//! ```toml
//! [[waypoints]]
//! pose = [1.2, 0.35, 0.59, 0.0, 0.0, 0.0]   # motion-pattern coordinates
//! wrench = [0.0, 30.0, 0.0, 0.0, 0.0, 0.0]  # optional w_e at this waypoint (default: --wrench)
//! [[waypoints]]
//! pose = [1.8, 0.35, 0.59, 0.0, 0.0, 0.0]
//! ```
//!
//! Between waypoints the wrench is interpolated linearly in the path parameter s.

use super::tension::SotdaSearch;
use super::{CliError, Numbers, print_report, request_robot};
use cdpr::api::cable_model::CableModelName;
use cdpr::api::trajectory::{PathReport, TrajectoryReport, TrajectoryRequest, parse_waypoints};
use cdpr::api::{MethodSettings, Robot};
use cdpr::plot::LinePlot;
use cdpr::tension::Method;
use std::path::PathBuf;

/// Tensions along a path: profiles, infeasible samples, largest jumps.
///
/// The path is the segment --from → --to, or the polyline of --waypoints FILE.toml
/// (`[[waypoints]]` tables with `pose = [...]` and an optional `wrench = [...]`; the wrench is
/// interpolated linearly in s between waypoints, waypoints without one use --wrench). Positions
/// are interpolated linearly, orientations by the shortest rotation; s ∈ [0, 1] is proportional to
/// the pose distance √(‖Δp‖² + θ²) (θ in rad). Sampled by --samples N (evenly in s) or --step H
/// (at most H apart, every waypoint included).
///
/// At every sample the tensions come from --method (any method of `cdpr tension`), with w_e plus
/// the platform's gravity, and are certified (equilibrium and bounds to 1e-9); infeasible samples
/// are listed with their s and reason, never dropped.
///
/// Continuity: `max_jump` is, per cable, the largest |t_i(k+1) − t_i(k)| between consecutive
/// feasible samples; `discontinuities` lists the steps k → k+1 whose jump exceeds --jump-ratio
/// times the median jump (a continuous profile's jumps shrink with the step, a discontinuity's do
/// not: refine the sampling to tell them apart).
///
/// JSON fields: `s`, `tensions` (array per sample, null where infeasible), `max_jump` (per
/// cable), `reasons` (null or string per sample), `feasible_count`, `discontinuities` (indices k),
/// `method`, `poses`, `t_min`, `t_max`. With `--cable-model elastic|catenary`: `cable_model`, and
/// per sample `unstrained_lengths` (m: what the winches pay out for the platform to be there,
/// flex and sag compensation), `platform_end_tensions` (N) and `cable_model_reasons` from the
/// sagging-cable statics (null where it has no certified equilibrium); with a `winch` on every
/// cable also `drum_angles` (rad, per sample: L0 over the winch's payout radius, the cable's
/// build-up on a single-layer drum included when `winch.cable_diameter` is given).
#[derive(clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    /// Robot file: .toml, CASPR NAME_cables.xml or WireCenter .wcrfx.
    robot: PathBuf,
    /// Start pose (motion-pattern coordinates), e.g. --from 1.2,0.35,0.59,0,0,0.
    #[arg(
        long,
        allow_hyphen_values = true,
        requires = "to",
        conflicts_with = "waypoints"
    )]
    from: Option<Numbers>,
    /// End pose of the straight segment.
    #[arg(long, allow_hyphen_values = true, requires = "from")]
    to: Option<Numbers>,
    /// A polyline in a TOML file instead of --from/--to: one `[[waypoints]]` table per
    /// waypoint, in path order, at least 2, with the keys
    ///   pose   = [..]  the pose in motion-pattern coordinates (m, and rad for angles), required;
    ///   wrench = [..]  the external wrench w_e there (DOF numbers, N and N·m), optional
    ///                  (default --wrench); interpolated linearly in s between waypoints.
    /// Example: [[waypoints]] pose = [-0.5, 0.0, 0.0]   [[waypoints]] pose = [0.5, 0.2, 0.1]
    /// wrench = [0.0, -10.0, 0.0]. See docs/robot-file.md.
    #[arg(long, value_name = "FILE.toml", verbatim_doc_comment)]
    waypoints: Option<PathBuf>,
    /// Number of samples, evenly spaced in s (at least 2).
    #[arg(long, conflicts_with = "step", value_parser = super::count)]
    samples: Option<usize>,
    /// Largest pose distance between samples (alternative to --samples; default: 101 samples).
    #[arg(long, value_parser = super::positive)]
    step: Option<f64>,
    /// External wrench w_e held constant along the path (DOF numbers; default zero).
    #[arg(long, allow_hyphen_values = true)]
    wrench: Option<Numbers>,
    /// Tension distribution method (see `cdpr tension --help` for the list).
    #[arg(long, default_value = "l2")]
    method: Method,
    /// SOTDA: ν ∈ [0, 1] between the barycentre (0) and the stiffness-oriented optimum (1);
    /// default 1. Refused with another method.
    #[arg(long, value_parser = super::unit_interval)]
    nu: Option<f64>,
    /// SOTDA: direction d of the displacement to minimise (2 or 3 numbers; default +y).
    /// Refused with another method.
    #[arg(long, allow_hyphen_values = true)]
    direction: Option<Numbers>,
    /// SOTDA: which points of the feasible polygon are evaluated. corners: Picard, Caro, Plestan & Claveau's (2020) real-time
    /// variant, the vertices with a cable at t_max; vertices: every vertex; full: a grid over
    /// the whole polygon refined by a pattern search.
    #[arg(long, value_enum, default_value = "corners", conflicts_with = "full")]
    sotda_search: SotdaSearch,
    /// SOTDA: search the whole polygon (same as --sotda-search full).
    #[arg(long)]
    full: bool,
    /// `--interior`, `--alternating`, `--p`, `--alpha`: the method's options, as `cdpr
    /// tension` takes them.
    #[command(flatten)]
    peer: super::tension::PeerOptions,
    /// A step is flagged as a discontinuity when its jump exceeds this many median jumps.
    #[arg(long, default_value_t = 20.0, value_parser = super::positive)]
    jump_ratio: f64,
    /// Tension profiles (one line per cable vs s, dashed t_min/t_max, gaps where infeasible).
    #[arg(long)]
    plot: Option<PathBuf>,
    #[command(flatten)]
    cable_model: super::cable_model::CableModelArgs,
    /// Write one JSON object on stdout.
    #[arg(long)]
    json: bool,
    /// Timed trajectories and inverse dynamics (issue 28; see `cli/time_law.rs`).
    #[command(flatten)]
    timing: super::time_law::TimingArgs,
}

/// Runs the command: the request, its report, rendered as JSON, tables and plots.
pub fn run(args: Args) -> Result<(), CliError> {
    let request = request(&args)?;
    super::time_law::check_outputs(&args.timing, &request.robot)?;
    match request.run()? {
        TrajectoryReport::Path(r) => render(&args, &request.robot, &r),
        TrajectoryReport::Timed(r) => {
            let out = super::time_law::Outputs {
                timing: &args.timing,
                plot: args.plot.as_deref(),
                json: args.json,
            };
            super::time_law::render(&out, &request.robot, &r)
        }
    }
}

/// The request of the command line.
fn request(args: &Args) -> Result<TrajectoryRequest, CliError> {
    cdpr::api::refuse_sotda_options(
        args.method,
        args.nu.is_some(),
        args.direction.is_some(),
        args.full,
    )?;
    let robot = request_robot(&args.robot)?;
    let waypoints = match &args.waypoints {
        Some(file) => {
            let text = std::fs::read_to_string(file)
                .map_err(|e| format!("{}: cannot read: {e}", file.display()))?;
            Some(parse_waypoints(&text, &file.display().to_string())?)
        }
        None => None,
    };
    let mut request = TrajectoryRequest::segment(robot, Vec::new(), Vec::new());
    request.from = args.from.as_ref().map(|p| p.0.clone());
    request.to = args.to.as_ref().map(|p| p.0.clone());
    request.waypoints = waypoints;
    request.waypoints_file = args.waypoints.as_ref().map(|f| f.display().to_string());
    request.samples = args.samples;
    request.step = args.step;
    request.wrench = args.wrench.as_ref().map(|w| w.0.clone());
    request.method = args.method;
    request.options = MethodSettings {
        direction: args.direction.as_ref().map(|d| d.0.clone()),
        nu: args.nu,
        sotda_search: SotdaSearch::from_args(args.sotda_search, args.full).to_api(),
        peer: args.peer.to_api(),
    };
    request.jump_ratio = args.jump_ratio;
    request.timing = args.timing.settings();
    request.caspr_trajectory = args.timing.caspr_source()?;
    request.cable_model = match args.cable_model.cable_model {
        super::cable_model::CableModelName::Straight => CableModelName::Straight,
        super::cable_model::CableModelName::Elastic => CableModelName::Elastic,
        super::cable_model::CableModelName::Catenary => CableModelName::Catenary,
    };
    Ok(request)
}

/// The untimed profile: the plot, then JSON or the tables.
fn render(args: &Args, robot: &Robot, r: &PathReport) -> Result<(), CliError> {
    if let Some(file) = &args.plot {
        cdpr::plot::save(&profile_plot(robot, r), file)?;
    }
    if args.json {
        return print_report(r);
    }
    print_table(robot, r, args.jump_ratio);
    if let (Some(name), Some(lengths), Some(reasons)) = (
        &r.cable_model,
        &r.unstrained_lengths,
        &r.cable_model_reasons,
    ) {
        println!("unstrained lengths L0_i in m ({name} cables) along s");
        for (k, (l, why)) in lengths.iter().zip(reasons).enumerate() {
            match l {
                Some(l) => println!("{:>8.4}  {}", r.s[k], super::nums(l)),
                None => println!("{:>8.4}  {}", r.s[k], why.as_deref().unwrap_or("")),
            }
        }
        if let Some(angles) = &r.drum_angles {
            println!("drum angles φ_i = L0_i/ρ_i in rad along s");
            for (k, a) in angles.iter().enumerate() {
                if let Some(a) = a {
                    println!("{:>8.4}  {}", r.s[k], super::nums(a));
                }
            }
        }
    }
    Ok(())
}

/// The tension table along s (at most ~40 rows, every infeasible sample), jumps, flagged steps.
fn print_table(robot: &Robot, r: &PathReport, jump_ratio: f64) {
    let n = robot.robot.cable_count();
    let motion = robot.robot.motion();
    println!(
        "robot {}, method {}, {} samples, {} feasible",
        robot.name,
        r.method,
        r.s.len(),
        r.feasible_count
    );
    println!("tensions t_i in N along the path parameter s ∈ [0, 1]");
    println!("{:>8}  {}", "s", super::time_law::cable_head(n));
    let every = r.s.len().div_ceil(40).max(1);
    for (k, (s, t)) in r.s.iter().zip(&r.tensions).enumerate() {
        match t {
            Some(t) if k % every == 0 || k + 1 == r.s.len() => {
                println!("{s:>8.4}  {}", super::time_law::cells(t));
            }
            Some(_) => {}
            None => println!(
                "{s:>8.4}  infeasible at {}: {}",
                super::pose_text(&r.poses[k], motion.space_dim()),
                r.reasons[k].as_deref().unwrap_or("")
            ),
        }
    }
    println!("{:>8}  {}", "max jump", super::time_law::cells(&r.max_jump));
    if r.discontinuities.is_empty() {
        println!("no discontinuity flagged (jump ratio {jump_ratio})");
    } else {
        let at: Vec<String> = r
            .discontinuities
            .iter()
            .map(|&k| format!("{:.4}→{:.4}", r.s[k], r.s[k + 1]))
            .collect();
        println!("discontinuities flagged at s = {}", at.join(", "));
    }
}

/// One line per cable against s, NaN (a gap) where infeasible, dashed t_min / t_max.
pub fn profile_plot(robot: &Robot, r: &PathReport) -> LinePlot {
    let nu = r.nu.map_or(String::new(), |nu| format!(", ν = {nu}"));
    LinePlot {
        title: format!(
            "{}: tensions along the path ({}{nu}; {} of {} samples feasible)",
            robot.name,
            r.method,
            r.feasible_count,
            r.s.len()
        ),
        labels: (
            "path parameter s (0 at the first waypoint, 1 at the last)".into(),
            "cable tension (N)".into(),
        ),
        series: super::time_law::tension_series(robot.robot.cable_count(), &r.s, &r.tensions),
        reference_lines: super::time_law::bound_lines(robot),
        gap_label: Some("infeasible poses".into()),
    }
}
