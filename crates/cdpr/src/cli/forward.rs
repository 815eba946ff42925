//! `cdpr forward`: forward kinematics, from measured cable lengths to the platform pose.

use super::{CliError, Numbers, print_report, request_robot};
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
#[derive(clap::Args)]
pub struct Args {
    /// Robot file (TOML, CASPR XML or WireCenter .wcrfx).
    robot: PathBuf,
    /// Measured cable lengths L_1,…,L_n (m), in cable order; with pulleys measured from each
    /// cable's `frame` point over its pulley.
    #[arg(long, allow_hyphen_values = true)]
    lengths: Numbers,
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
    /// Write one JSON object on stdout instead of a table.
    #[arg(long)]
    json: bool,
}

/// Runs the command: the request, its report, rendered as JSON or a table.
pub fn run(args: Args) -> Result<(), CliError> {
    let request = ForwardRequest {
        robot: request_robot(&args.robot)?,
        lengths: args.lengths.0,
        guess: args.guess.map(|g| g.0),
        tolerance: args.tolerance,
        length_sigma: args.length_sigma,
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
