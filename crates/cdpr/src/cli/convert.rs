//! `cdpr convert`: a robot file in another format.

use super::{CliError, load_robot, print_json};
use serde_json::json;
use std::path::PathBuf;

/// Reads a robot file in any format (cdpr TOML, CASPR NAME_cables.xml, WireCenter .wcrfx) and
/// writes it as cdpr TOML (.toml) or WireCenter (.wcrfx), by the output's extension.
///
/// Every modelled number is kept: geometry, swivel pulleys, per-cable tension bounds, axial
/// stiffness, platform mass, centre of mass, inertia and gravity (written explicitly: CASPR's and
/// WireLib's 9.81 m/s² is not cdpr's default 9.80665 m/s²), cable names, the home pose. A
/// .wcrfx cannot hold per-cable bounds or stiffnesses that differ (an error) nor limits, the home
/// pose or a non-WireLib gravity (listed as warnings). CASPR files are read, not written.
/// Example: `cdpr convert CAROCA_cables.xml --cable-set with_rotating_pulleys -o caroca.toml`.
/// JSON fields (--json): `input`, `output`, `robot`, `cables`, `warnings` (what was adjusted on
/// reading or is not written).
#[derive(clap::Args)]
pub struct Args {
    /// Robot file to read: .toml, CASPR NAME_cables.xml or WireCenter .wcrfx.
    input: PathBuf,
    /// File to write: .toml or .wcrfx.
    #[arg(short, long)]
    output: PathBuf,
    /// Write one JSON object on stdout instead of a sentence.
    #[arg(long)]
    json: bool,
}

/// Runs the command.
pub fn run(args: Args) -> Result<(), CliError> {
    let robot = load_robot(&args.input)?;
    let source = args
        .input
        .file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let header = format!("{} — converted by `cdpr convert` from {source}", robot.name);
    let losses = robot.save(&args.output, &header)?;
    for w in &losses {
        eprintln!("warning: {}: {w}", args.output.display());
    }
    if args.json {
        let mut warnings = robot.warnings.clone();
        warnings.extend(losses);
        print_json(&json!({
            "input": args.input,
            "output": args.output,
            "robot": robot.name,
            "cables": robot.robot.cable_count(),
            "warnings": warnings,
        }))
    } else {
        println!(
            "wrote {} ({}, {} cables) from {}",
            args.output.display(),
            robot.name,
            robot.robot.cable_count(),
            args.input.display()
        );
        Ok(())
    }
}
