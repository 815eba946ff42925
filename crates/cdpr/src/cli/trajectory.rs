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

use super::tension::{SotdaSearch, sotda_settings};
use super::{CliError, Numbers, check_method, load_robot, pose, print_json, wrench};
use cdpr::kinematics::{Path, PathSample, Pose, Sampling};
use cdpr::plot::{LinePlot, Series};
use cdpr::tension::profile::{TensionProfile, WaypointWrenches, tension_profile};
use cdpr::tension::{Method, TensionSolver};
use nalgebra::DVector;
use serde::Deserialize;
use serde_json::json;
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
/// sagging-cable statics (null where it has no certified equilibrium).
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

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct WaypointFile {
    waypoints: Vec<Waypoint>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Waypoint {
    pose: Vec<f64>,
    wrench: Option<Vec<f64>>,
    /// The waypoint's time (s) for --time-law.
    time: Option<f64>,
}

/// Runs the command.
pub fn run(args: Args) -> Result<(), CliError> {
    let robot = load_robot(&args.robot)?;
    check_method(&robot, args.method)?;
    super::tension::refuse_sotda_options(
        args.method,
        args.nu,
        args.direction.is_some(),
        args.full,
    )?;
    let motion = robot.robot.motion();
    let default_wrench = wrench(&robot, args.wrench.as_deref())?;
    let mut times: Option<Vec<f64>> = None;
    let (poses, wrenches): (Vec<Pose>, Vec<DVector<f64>>) = match (&args.waypoints, &args.from) {
        (Some(file), _) => {
            let text = std::fs::read_to_string(file)
                .map_err(|e| format!("{}: cannot read: {e}", file.display()))?;
            let parsed: WaypointFile =
                toml::from_str(&text).map_err(|e| format!("{}: {e}", file.display()))?;
            if parsed.waypoints.len() < 2 {
                return Err(format!("{}: needs at least two [[waypoints]]", file.display()).into());
            }
            let mut poses = Vec::new();
            let mut wrenches = Vec::new();
            times = super::time_law::waypoint_times(file, &parsed.waypoints, |w| w.time)?;
            for (k, w) in parsed.waypoints.iter().enumerate() {
                poses.push(
                    pose(&robot, &w.pose)
                        .map_err(|e| format!("{}: waypoints[{k}].pose: {e}", file.display()))?,
                );
                wrenches.push(match &w.wrench {
                    Some(v) => wrench(&robot, Some(v))
                        .map_err(|e| format!("{}: waypoints[{k}].wrench: {e}", file.display()))?,
                    None => default_wrench.clone(),
                });
            }
            (poses, wrenches)
        }
        (None, Some(from)) => {
            let to = args.to.as_ref().ok_or("--from needs --to")?;
            (
                vec![pose(&robot, from)?, pose(&robot, to)?],
                vec![default_wrench.clone(), default_wrench.clone()],
            )
        }
        (None, None) => {
            return Err("give the path: --from POSE --to POSE, or --waypoints FILE".into());
        }
    };
    let sampling = match (args.samples, args.step) {
        (Some(n), _) => Sampling::Count(n),
        (None, Some(h)) => Sampling::Step(h),
        (None, None) => Sampling::Count(101),
    };
    if let Sampling::Count(n) = sampling
        && n > 10_000_000
    {
        return Err("--samples: at most 10 000 000".into());
    }
    if !(args.jump_ratio.is_finite() && args.jump_ratio > 1.0) {
        return Err("--jump-ratio must be a finite number > 1".into());
    }
    let path = Path::new(motion, poses.clone())?;
    let samples = path.sample(sampling)?;
    let way = WaypointWrenches::new(motion, &poses, wrenches.clone())?;
    let es = robot.axial_stiffness.clone();
    let mut solver = if args.method == Method::Sotda {
        if es.is_none() {
            return Err(
                "sotda needs `axial_stiffness` (E·S, N) on every cable of the robot file".into(),
            );
        }
        TensionSolver::sotda(sotda_settings(
            args.direction.as_deref(),
            args.nu.unwrap_or(1.0),
            SotdaSearch::from_args(args.sotda_search, args.full),
        )?)
    } else {
        TensionSolver::new(args.method)
    };
    if args.timing.time_law.is_some() {
        return super::time_law::run(
            &args.timing,
            super::time_law::TimedRequest {
                robot: &robot,
                poses,
                wrenches,
                times,
                solver: &mut solver,
                method: args.method.name(),
                axial_stiffness: es.as_deref(),
                json: args.json,
                plot: args.plot.as_deref(),
            },
        );
    }
    // Weight and passive springs at each sample (checked here: a spring of zero length is an
    // error naming the sample, not a panic in the profile).
    for sample in &samples {
        robot
            .load_wrench(&sample.pose)
            .map_err(|e| format!("at s = {}: {e}", sample.s))?;
    }
    let gravity = |p: &Pose| robot.load_wrench(p).expect("checked at every sample above");
    let profile = tension_profile(
        &robot.robot,
        &samples,
        &robot.bounds,
        &mut solver,
        es.as_deref(),
        |sample: &PathSample| way.at(sample.s) + gravity(&sample.pose),
    )?;
    let discontinuities = profile.discontinuities(args.jump_ratio);
    let compensation = match args.cable_model.catenaries(&robot)? {
        None => None,
        Some(cables) => {
            let w = |k: usize| way.at(samples[k].s) + gravity(&samples[k].pose);
            let poses: Vec<Pose> = samples.iter().map(|p| p.pose).collect();
            let c = super::cable_model::compensation(&robot, &cables, args.method, &poses, w)?;
            Some((args.cable_model.model().name(), c))
        }
    };
    if let Some(file) = &args.plot {
        cdpr::plot::save(&profile_plot(&robot, &args, &profile), file)?;
    }
    if args.json {
        let mut v = json!({
            "robot": robot.name,
            "method": args.method.name(),
            "nu": (args.method == Method::Sotda).then_some(args.nu.unwrap_or(1.0)),
            "s": profile.s,
            "poses": samples.iter().map(|p| p.pose.coordinates(motion)).collect::<Vec<_>>(),
            "tensions": profile.tensions.iter().map(|t| t.as_ref().map(|t| t.as_slice().to_vec())).collect::<Vec<_>>(),
            "reasons": profile.reasons,
            "feasible_count": profile.feasible_count(),
            "max_jump": profile.max_jump,
            "discontinuities": discontinuities,
            "t_min": robot.bounds.min().as_slice(),
            "t_max": robot.bounds.max().as_slice(),
        });
        if let Some((name, (lengths, tensions, reasons))) = compensation {
            v["cable_model"] = json!(name);
            v["unstrained_lengths"] = json!(lengths);
            v["platform_end_tensions"] = json!(tensions);
            v["cable_model_reasons"] = json!(reasons);
        }
        print_json(&v)
    } else {
        print_table(&robot, &args, &profile, &samples, &discontinuities);
        if let Some((name, (lengths, _, reasons))) = compensation {
            println!("unstrained lengths L0_i in m ({name} cables) along s");
            for (k, (l, r)) in lengths.iter().zip(&reasons).enumerate() {
                match l {
                    Some(l) => println!("{:>8.4}  {}", profile.s[k], super::nums(l)),
                    None => println!("{:>8.4}  {}", profile.s[k], r.as_deref().unwrap_or("")),
                }
            }
        }
        Ok(())
    }
}

fn print_table(
    robot: &cdpr::RobotDescription,
    args: &Args,
    profile: &TensionProfile,
    samples: &[PathSample],
    discontinuities: &[usize],
) {
    let n = robot.robot.cable_count();
    println!(
        "robot {}, method {}, {} samples, {} feasible",
        robot.name,
        args.method.name(),
        profile.s.len(),
        profile.feasible_count()
    );
    let head: Vec<String> = (1..=n)
        .map(|i| format!("{:>10}", format!("t{i}")))
        .collect();
    println!("tensions t_i in N along the path parameter s ∈ [0, 1]");
    println!("{:>8}  {}", "s", head.join(" "));
    // At most ~40 rows in the table: every k-th sample, plus every infeasible one.
    let every = profile.s.len().div_ceil(40).max(1);
    for (k, (s, t)) in profile.s.iter().zip(&profile.tensions).enumerate() {
        match t {
            Some(t) if k % every == 0 || k + 1 == profile.s.len() => {
                let cells: Vec<String> = t.iter().map(|v| format!("{v:>10.4}")).collect();
                println!("{s:>8.4}  {}", cells.join(" "));
            }
            Some(_) => {}
            None => println!(
                "{s:>8.4}  infeasible at {}: {}",
                super::pose_text(
                    &samples[k].pose.coordinates(robot.robot.motion()),
                    robot.robot.motion().space_dim()
                ),
                profile.reasons[k].as_deref().unwrap_or("")
            ),
        }
    }
    let jumps: Vec<String> = profile
        .max_jump
        .iter()
        .map(|v| format!("{v:>10.4}"))
        .collect();
    println!("{:>8}  {}", "max jump", jumps.join(" "));
    if discontinuities.is_empty() {
        println!("no discontinuity flagged (jump ratio {})", args.jump_ratio);
    } else {
        let at: Vec<String> = discontinuities
            .iter()
            .map(|&k| format!("{:.4}→{:.4}", profile.s[k], profile.s[k + 1]))
            .collect();
        println!("discontinuities flagged at s = {}", at.join(", "));
    }
}

/// One line per cable against s, NaN (a gap) where infeasible, dashed t_min / t_max.
pub fn profile_plot(
    robot: &cdpr::RobotDescription,
    args: &Args,
    profile: &TensionProfile,
) -> LinePlot {
    let n = robot.robot.cable_count();
    let series = (0..n)
        .map(|i| Series {
            label: format!("t{}", i + 1),
            points: profile
                .s
                .iter()
                .zip(&profile.tensions)
                .map(|(&s, t)| (s, t.as_ref().map_or(f64::NAN, |t| t[i])))
                .collect(),
        })
        .collect();
    let mut reference_lines = Vec::new();
    let (lo, hi) = (robot.bounds.min(), robot.bounds.max());
    if lo.iter().all(|&v| v == lo[0]) {
        reference_lines.push((lo[0], format!("t_min = {} N", cdpr::plot::tick(lo[0]))));
    }
    if hi.iter().all(|&v| v == hi[0]) && hi[0].is_finite() {
        reference_lines.push((hi[0], format!("t_max = {} N", cdpr::plot::tick(hi[0]))));
    }
    let nu = if args.method == Method::Sotda {
        format!(", ν = {}", args.nu.unwrap_or(1.0))
    } else {
        String::new()
    };
    LinePlot {
        title: format!(
            "{}: tensions along the path ({}{nu}; {} of {} samples feasible)",
            robot.name,
            args.method.name(),
            profile.feasible_count(),
            profile.s.len()
        ),
        labels: (
            "path parameter s (0 at the first waypoint, 1 at the last)".into(),
            "cable tension (N)".into(),
        ),
        series,
        reference_lines,
        gap_label: Some("infeasible poses".into()),
    }
}
