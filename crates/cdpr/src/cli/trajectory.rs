//! `cdpr trajectory` (being written: see the issue tracker).

use super::CliError;
use std::path::PathBuf;

/// Tensions along a path: profiles, infeasible samples, largest jumps.
#[derive(clap::Args)]
pub struct Args {
    /// Robot file (TOML).
    robot: PathBuf,
}

/// Runs the command.
pub fn run(args: Args) -> Result<(), CliError> {
    Err(format!("{}: `trajectory` is not available yet", args.robot.display()).into())
}
