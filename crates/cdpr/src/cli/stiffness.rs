//! `cdpr stiffness`: the stiffness matrix at one pose under given tensions.

use super::{CliError, Numbers, load_robot, matrix_rows, pose, print_json, print_matrix};
use serde_json::json;
use std::path::PathBuf;

/// Stiffness matrix K = Kp + Ka (Picard, Caro, Plestan & Claveau 2020, eqs. (3)–(4)), k_i = E·S / l_i.
///
/// Needs `axial_stiffness` (E·S, N) on every cable of the robot file, or --axial-stiffness.
/// JSON fields: `stiffness` (rows of K), `passive` (Kp), `active` (Ka).
#[derive(clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    /// Robot file: .toml, CASPR NAME_cables.xml or WireCenter .wcrfx.
    robot: PathBuf,
    /// Platform pose (motion-pattern coordinates).
    #[arg(long, allow_hyphen_values = true)]
    pose: Numbers,
    /// Cable tensions t_i, one per cable (N).
    #[arg(long, allow_hyphen_values = true)]
    tensions: Numbers,
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
    let k = cdpr::wrench::stiffness_matrix(&kin, &args.tensions, &es)?;
    let kp = cdpr::wrench::passive_stiffness(&kin, &es)?;
    let ka = cdpr::wrench::active_stiffness(&kin, &args.tensions)?;
    if args.json {
        print_json(&json!({
            "robot": robot.name,
            "pose": args.pose.0,
            "tensions": args.tensions.0,
            "stiffness": matrix_rows(&k),
            "passive": matrix_rows(&kp),
            "active": matrix_rows(&ka),
        }))
    } else {
        print_matrix(
            "stiffness K = Kp + Ka (N/m on translations, N·m/rad on rotations, N coupling):",
            &k,
        );
        print_matrix("passive Kp:", &kp);
        print_matrix("active Ka:", &ka);
        Ok(())
    }
}
