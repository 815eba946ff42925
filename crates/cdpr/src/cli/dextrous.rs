//! `cdpr dextrous` (being written: see the issue tracker).

use super::CliError;
use std::path::PathBuf;

/// Dextrous workspace over a range of orientations (eq. 6.28).
#[derive(clap::Args)]
pub struct Args {
    /// Robot file (TOML).
    robot: PathBuf,
}

/// Runs the command.
pub fn run(args: Args) -> Result<(), CliError> {
    Err(format!("{}: `dextrous` is not available yet", args.robot.display()).into())
}
