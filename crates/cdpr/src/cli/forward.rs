//! `cdpr forward`: forward kinematics, from measured cable lengths to the platform pose.

use super::{CliError, Numbers, load_robot, print_report, request_robot};
use cdpr::api::{ForwardReport, ForwardRequest};
use std::path::PathBuf;

/// The platform pose whose cable lengths are the measured ones (Levenberg–Marquardt on
/// l(x) − L with the analytic Jacobian; straight or pulley cables, see `--kinematics`).
///
/// With `--guess` it iterates from that pose; without, it starts from the centre of the frame
/// anchors' bounding box in several orientations, from points halfway to its corners and, for a
/// suspended robot (anchors spanning little height), from three heights below the anchors, and
/// reports every distinct solution (a fixed set of starts can miss a pose: give --guess near
/// it). With more cables than DOF and inconsistent (noisy) lengths the answer is the
/// least-squares pose. Every answer is certified: `residual` = max |l_i(pose) − L_i| (m)
/// recomputed at the pose, `iterations`, `converged`, `status` ("solved" when the residual is
/// within --tolerance; with more cables than DOF "fitted" when the least-squares residual is
/// consistent with a length noise --length-sigma (χ² test at 99.9 %), "inconsistent" when it is
/// not; "no pose within tolerance" when the iteration converged to a larger residual with as
/// many cables as DOF; "above the anchors" for a pose in space from which no cable rises, the
/// mirror image of a hanging pose; "did not converge"), and `min_singular_value`, the smallest
/// singular value of the Jacobian (pose error ≲ length error / σ_min). Those outcomes exit 0;
/// bad input exits 2. JSON fields: `kinematics`, `pose` (the best solution, motion-pattern
/// coordinates: m and rad), `residual` (m), `residual_rms` (‖l − L‖/√n, m), `pose_std`
/// (standard deviations √diag(σ²(JᵀJ)⁻¹) with σ = --length-sigma: position m, rotation vector
/// rad), `length_sigma` (m), `iterations`, `converged`, `status`, `min_singular_value`, and
/// `solutions` (every distinct solution found, each with the same fields; one entry with
/// --guess).
///
/// With `--unstrained-lengths L1,…,Ln --cable-model elastic|catenary` (issue 29: elasto-geometric
/// forward kinematics) it finds the platform's equilibrium pose under its weight (robot file)
/// and `--wrench` with elastic or sagging cables of those unstrained lengths (Newton's step from
/// the stiffness matrix, started from --guess or from the straight cables' pose for the
/// unstrained lengths). JSON fields: `cable_model`, `pose`, `tensions` (platform end, N),
/// `frame_end_tensions` (N), `unstrained_lengths` and `chord_lengths` (m), `max_sag` (m),
/// `angle_to_chord` (rad), `residual` (max equilibrium residual, N; moments in N·m divided by
/// the robot's length scale in m), `status` ("equilibrium" or "did not converge"),
/// `iterations`, `slack_cables` (cable numbers from 1), `external_wrench` (N, N·m, at the pose).
#[derive(clap::Args)]
pub struct Args {
    /// Robot file (TOML, CASPR XML or WireCenter .wcrfx).
    robot: PathBuf,
    /// Measured cable lengths L_1,…,L_n (m), in cable order; with pulleys measured from each
    /// cable's `frame` point over its pulley.
    #[arg(
        long,
        allow_hyphen_values = true,
        required_unless_present = "unstrained_lengths",
        conflicts_with = "unstrained_lengths"
    )]
    lengths: Option<Numbers>,
    /// Unstrained cable lengths L0_1,…,L0_n (m) paid out by the winches, for --cable-model
    /// elastic|catenary: the equilibrium pose under the platform's weight and --wrench.
    #[arg(long, allow_hyphen_values = true)]
    unstrained_lengths: Option<Numbers>,
    #[command(flatten)]
    cable_model: super::cable_model::CableModelArgs,
    /// External wrench w_e on the platform with --unstrained-lengths (DOF numbers, N and N·m;
    /// default zero), added to the platform's weight from the robot file.
    #[arg(long, allow_hyphen_values = true)]
    wrench: Option<Numbers>,
    /// Starting pose (motion-pattern coordinates, e.g. x,y,z,rx,ry,rz); without it, multi-start.
    #[arg(long, allow_hyphen_values = true)]
    guess: Option<Numbers>,
    /// A pose solves the lengths when max |l_i − L_i| is at most this (m).
    #[arg(long, default_value_t = 1e-9, allow_hyphen_values = true)]
    tolerance: f64,
    /// Standard deviation σ of the measured lengths (m): with more cables than DOF, a
    /// least-squares residual consistent with it is "fitted"; it scales the pose's `pose_std`.
    #[arg(long, default_value_t = 1e-4, allow_hyphen_values = true)]
    length_sigma: f64,
    /// Iteration limit of each solve (≥ 1; a start that has not converged by then is reported
    /// "did not converge").
    #[arg(long, default_value_t = 100, allow_hyphen_values = true)]
    max_iterations: i64,
    /// Write one JSON object on stdout instead of a table.
    #[arg(long)]
    json: bool,
}

/// Runs the command: the request, its report, rendered as JSON or a table.
pub fn run(args: Args) -> Result<(), CliError> {
    if let Some(l0) = &args.unstrained_lengths {
        let robot = load_robot(&args.robot)?;
        let (w, g) = (args.wrench.as_deref(), args.guess.as_deref());
        return super::cable_model::forward(robot, &args.cable_model, l0, w, g, args.json);
    }
    if args.cable_model.model() != cdpr::kinematics::CableModel::Straight || args.wrench.is_some() {
        return Err("--cable-model elastic|catenary and --wrench go with --unstrained-lengths (measured lengths --lengths are the straight cables')".into());
    }
    let request = ForwardRequest {
        robot: request_robot(&args.robot)?,
        lengths: args.lengths.map(|l| l.0).unwrap_or_default(),
        guess: args.guess.map(|g| g.0),
        tolerance: args.tolerance,
        length_sigma: args.length_sigma,
        max_iterations: usize::try_from(args.max_iterations).map_err(|_| {
            format!(
                "--max-iterations {}: expected an integer ≥ 1",
                args.max_iterations
            )
        })?,
    };
    let report = request.run()?;
    if args.json {
        print_report(&report)
    } else {
        print_text(&report, request.guess.is_some());
        Ok(())
    }
}

/// The report as a table.
fn print_text(r: &ForwardReport, from_guess: bool) {
    println!(
        "robot {} ({}, {} kinematics), {} from {}",
        r.robot,
        r.motion,
        r.kinematics.name(),
        if r.solutions.len() == 1 {
            "1 answer".to_string()
        } else {
            format!("{} distinct solutions", r.solutions.len())
        },
        if from_guess {
            "the guess"
        } else {
            "the multi-start"
        }
    );
    println!(
        "{:>3}  {:<24} {:>12} {:>12} {:>6} {:>12}  pose (m, rad)",
        "#", "status", "residual (m)", "rms (m)", "iter", "σ_min(J)"
    );
    for (i, s) in r.solutions.iter().enumerate() {
        let p: Vec<String> = s.pose.iter().map(|x| format!("{x:.9}")).collect();
        println!(
            "{:>3}  {:<24} {:>12.3e} {:>12.3e} {:>6} {:>12.4e}  {}",
            i + 1,
            s.status,
            s.residual,
            s.residual_rms,
            s.iterations,
            s.min_singular_value,
            p.join(",")
        );
    }
    let std: Vec<String> = r.best.pose_std.iter().map(|x| format!("{x:.3e}")).collect();
    println!(
        "pose standard deviations of #1 (σ = {:e} m per length; m, rad): {}",
        r.length_sigma,
        std.join(",")
    );
}
