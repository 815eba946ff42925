//! `cdpr stiffness`: the stiffness matrix at one pose under given tensions.

use super::{
    CliError, Numbers, check_method, external_wrench, load_robot, matrix_rows, pose, print_json,
    print_matrix,
};
use cdpr::RobotDescription;
use cdpr::kinematics::{Pose, PoseKinematics};
use cdpr::tension::{Method, TensionOutcome, TensionProblem, TensionSolver};
use serde_json::json;
use std::path::PathBuf;

/// Stiffness matrix K = Kp + Ka (Picard, Caro, Plestan & Claveau 2020, eqs. (3)–(4)), k_i = E·S / l_i.
///
/// Needs `axial_stiffness` (E·S, N) on every cable of the robot file, or --axial-stiffness.
/// JSON fields: `tensions` (N), `tension_method` (null with --tensions), `stiffness` (rows of
/// K), `passive` (Kp), `active` (Ka).
#[derive(clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    /// Robot file: .toml, CASPR NAME_cables.xml or WireCenter .wcrfx.
    robot: PathBuf,
    /// Platform pose (motion-pattern coordinates).
    #[arg(long, allow_hyphen_values = true)]
    pose: Numbers,
    /// Cable tensions t_i, one per cable (N, ≥ 0: a cable only pulls). Without them the
    /// tensions are those of --method balancing the platform's weight and --wrench.
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["method", "wrench"])]
    tensions: Option<Numbers>,
    /// Tension distribution method that gives the tensions when --tensions is not given
    /// (default l2, as `cdpr tension`); sotda needs its own options: use `cdpr tension`.
    #[arg(long, long_help = super::method_help())]
    method: Option<Method>,
    /// External wrench w_e the --method tensions balance with the platform's weight (DOF
    /// numbers; default zero).
    #[arg(long, allow_hyphen_values = true)]
    wrench: Option<Numbers>,
    /// E·S for every cable (N), overriding the robot file.
    #[arg(long, value_parser = super::positive)]
    axial_stiffness: Option<f64>,
    /// Write one JSON object on stdout.
    #[arg(long)]
    json: bool,
}

/// Runs the command.
pub fn run(args: Args) -> Result<(), CliError> {
    let robot = load_robot(&args.robot)?;
    robot.require_no_passive_springs(
        "the stiffness matrix (cables only; the springs' K would add to it)",
    )?;
    let pose = pose(&robot, &args.pose)?;
    let kin = robot.robot.inverse_kinematics(&pose)?;
    let n = robot.robot.cable_count();
    let es = match (args.axial_stiffness, &robot.axial_stiffness) {
        (Some(v), _) => vec![v; n],
        (None, Some(v)) => v.clone(),
        (None, None) => return Err("no axial stiffness: give `axial_stiffness` on every cable of the robot file, or --axial-stiffness".into()),
    };
    let (tensions, method) = match &args.tensions {
        Some(t) => (checked_tensions(t)?, None),
        None => {
            let method = args.method.unwrap_or(Method::L2);
            (
                solved_tensions(&robot, &pose, &kin, method, &args)?,
                Some(method),
            )
        }
    };
    let k = cdpr::wrench::stiffness_matrix(&kin, &tensions, &es)?;
    let kp = cdpr::wrench::passive_stiffness(&kin, &es)?;
    let ka = cdpr::wrench::active_stiffness(&kin, &tensions)?;
    if args.json {
        print_json(&json!({
            "robot": robot.name,
            "pose": args.pose.0,
            "tensions": tensions,
            "tension_method": method.map(|m| m.name()),
            "stiffness": matrix_rows(&k),
            "passive": matrix_rows(&kp),
            "active": matrix_rows(&ka),
        }))
    } else {
        if let Some(m) = method {
            println!("tensions ({}): {} N", m.name(), super::nums(&tensions));
        }
        print_matrix(
            "stiffness K = Kp + Ka (N/m on translations, N·m/rad on rotations, N coupling):",
            &k,
        );
        print_matrix("passive Kp:", &kp);
        print_matrix("active Ka:", &ka);
        Ok(())
    }
}

/// `--tensions` as given: finite and ≥ 0 (a cable only pulls; a negative tension used to give
/// a stiffness matrix without a word).
fn checked_tensions(t: &[f64]) -> Result<Vec<f64>, CliError> {
    if let Some((i, v)) = t
        .iter()
        .enumerate()
        .find(|(_, v)| !(v.is_finite() && **v >= 0.0))
    {
        return Err(format!(
            "--tensions: t_{} = {v} N; tensions are finite and ≥ 0 (a cable can only pull)",
            i + 1
        )
        .into());
    }
    Ok(t.to_vec())
}

/// The tensions of `method` balancing the platform's weight and `--wrench` at the pose; an
/// infeasible pose is an error (no stiffness without tensions).
fn solved_tensions(
    robot: &RobotDescription,
    pose: &Pose,
    kin: &PoseKinematics,
    method: Method,
    args: &Args,
) -> Result<Vec<f64>, CliError> {
    if method == Method::Sotda {
        return Err(
            "--method sotda needs its own options: run `cdpr tension --method sotda` \
                    and pass its tensions with --tensions"
                .into(),
        );
    }
    check_method(robot, method)?;
    let w = kin.wrench_matrix();
    let w_ext = external_wrench(robot, pose, args.wrench.as_deref())?;
    match TensionSolver::new(method).solve(&TensionProblem::new(&w, &w_ext, &robot.bounds))? {
        TensionOutcome::Feasible(s) => Ok(s.tensions.as_slice().to_vec()),
        TensionOutcome::Infeasible(reason) => Err(format!(
            "no tensions within the bounds at this pose ({}): {reason}; give --tensions",
            method.name()
        )
        .into()),
    }
}
