//! `cdpr isotropic` (being written: see the issue tracker).

use super::CliError;
use std::path::PathBuf;

/// Maximum isotropic force (seed 001) at a pose, or its heat map over a grid.
#[derive(clap::Args)]
pub struct Args {
    /// Robot file (TOML).
    robot: PathBuf,
}

/// Runs the command.
pub fn run(args: Args) -> Result<(), CliError> {
    Err(format!("{}: `isotropic` is not available yet", args.robot.display()).into())
}
