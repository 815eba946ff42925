//! `cdpr stiffness-map` (being written: see the issue tracker).

use super::CliError;
use std::path::PathBuf;

/// Platform displacement over the feasible polygon (seed 002 Fig. 4).
#[derive(clap::Args)]
pub struct Args {
    /// Robot file (TOML).
    robot: PathBuf,
}

/// Runs the command.
pub fn run(args: Args) -> Result<(), CliError> {
    Err(format!("{}: `stiffness-map` is not available yet", args.robot.display()).into())
}
