//! `cdpr stiffness`: the stiffness matrix at one pose under given tensions.

use super::{CliError, Numbers, print_matrix, print_report, request_robot};
use cdpr::api::StiffnessRequest;
use cdpr::tension::Method;
use nalgebra::DMatrix;
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

/// Runs the command: the request, its report, rendered as JSON or tables.
pub fn run(args: Args) -> Result<(), CliError> {
    let request = StiffnessRequest {
        robot: request_robot(&args.robot)?,
        pose: args.pose.0,
        tensions: args.tensions.map(|t| t.0),
        method: args.method,
        wrench: args.wrench.map(|w| w.0),
        axial_stiffness: args.axial_stiffness,
    };
    let r = request.run()?;
    if args.json {
        return print_report(&r);
    }
    if let Some(m) = &r.tension_method {
        println!("tensions ({m}): {} N", super::nums(&r.tensions));
    }
    print_matrix(
        "stiffness K = Kp + Ka (N/m on translations, N·m/rad on rotations, N coupling):",
        &matrix(&r.stiffness),
    );
    print_matrix("passive Kp:", &matrix(&r.passive));
    print_matrix("active Ka:", &matrix(&r.active));
    Ok(())
}

/// A matrix from its rows.
fn matrix(rows: &[Vec<f64>]) -> DMatrix<f64> {
    let cols = rows.first().map_or(0, Vec::len);
    DMatrix::from_row_iterator(rows.len(), cols, rows.iter().flatten().copied())
}
