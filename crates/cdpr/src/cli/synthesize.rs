//! `cdpr synthesize` (being written: see the issue tracker).

use super::CliError;
use std::path::PathBuf;

/// Dimensional synthesis: frame anchor angles maximising the dextrous workspace (eq. 6.29).
#[derive(clap::Args)]
pub struct Args {
    /// Robot file (TOML).
    robot: PathBuf,
}

/// Runs the command.
pub fn run(args: Args) -> Result<(), CliError> {
    Err(format!(
        "{}: `synthesize` is not available yet",
        args.robot.display()
    )
    .into())
}
