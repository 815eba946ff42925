//! `cdpr workspace` (being written: see the issue tracker).

use super::CliError;
use std::path::PathBuf;

/// Constant-orientation workspace by discretisation (Algorithm 6.2) or the chord method.
#[derive(clap::Args)]
pub struct Args {
    /// Robot file (TOML).
    robot: PathBuf,
}

/// Runs the command.
pub fn run(args: Args) -> Result<(), CliError> {
    Err(format!("{}: `workspace` is not available yet", args.robot.display()).into())
}
