//! `cdpr capacity` (being written: see the issue tracker).

use super::CliError;
use std::path::PathBuf;

/// Capacity margin of a required wrench set (box or ball) at a pose.
#[derive(clap::Args)]
pub struct Args {
    /// Robot file (TOML).
    robot: PathBuf,
}

/// Runs the command.
pub fn run(args: Args) -> Result<(), CliError> {
    Err(format!("{}: `capacity` is not available yet", args.robot.display()).into())
}
