//! The `cdpr` command: analysis and design of cable-driven parallel robots from robot files.
//! Run `cdpr --help`, or `cdpr COMMAND --help` for each command.

mod cli;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// Analysis and design of cable-driven parallel robots (CDPRs).
///
/// Every command reads a robot file — cdpr TOML (see examples/robots/ and docs/robot-file.md), a
/// CASPR model (NAME_cables.xml with NAME_bodies.xml beside it; --cable-set ID picks a cable set)
/// or a WireCenter .wcrfx — prints a readable table, or one JSON object on stdout with --json, and writes a plot with
/// --plot FILE.svg|FILE.png where it has one. Poses and wrenches are comma-separated numbers in the
/// order of the robot's motion pattern: point2 (x,y), planar (x,y,phi), point3 (x,y,z),
/// spatial (x,y,z,rx,ry,rz: XYZ Euler angles in radians). Negative numbers work: --pose -0.5,0.2,0.
///
/// Exit codes: 0 on success (an infeasible result is a success), 2 on bad input.
#[derive(Parser)]
#[command(name = "cdpr", version, about, long_about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// CASPR models: the <cable_set id> to read (default: the file's default_cable_set).
    #[arg(long, global = true, value_name = "ID")]
    cable_set: Option<String>,
    /// Cable model: `pulley` (each cable over its swivel pulley, Pott 2018: length = wrapped arc +
    /// free segment; the default when the robot file gives any pulley) or `standard` (straight
    /// cables from each `frame` point; pulleys ignored).
    #[arg(long, global = true, value_enum, value_name = "MODEL")]
    kinematics: Option<cli::KinematicsModel>,
}

#[derive(Subcommand)]
enum Command {
    /// Inverse kinematics at a pose: cable lengths, unit vectors and the wrench matrix W.
    Kinematics(cli::kinematics::Args),
    /// Forward kinematics: the platform pose from measured cable lengths, with its certificate.
    Forward(cli::forward::Args),
    /// Stiffness matrix K = Kp + Ka at a pose under given cable tensions (Picard, Caro, Plestan & Claveau 2020, eq. (4)).
    Stiffness(cli::stiffness::Args),
    /// Cable tensions at a pose by any tension distribution method (closed form, l1, l2, SOTDA, ...).
    Tension(cli::tension::Args),
    /// Maximum isotropic force (Krut, Company & Pierrot 2004) at a pose, or its heat map over a grid.
    Isotropic(cli::isotropic::Args),
    /// Capacity margin of a required wrench set (box or ball) at a pose.
    Capacity(cli::capacity::Args),
    /// Constant-orientation workspace by discretisation (Algorithm 6.2) or the chord method.
    Workspace(cli::workspace::Args),
    /// Dextrous workspace over a range of orientations (eq. 6.28).
    Dextrous(cli::dextrous::Args),
    /// Orientation workspace at a position: the feasible orientations of a sampled set (spatial robots).
    Orientations(cli::orientations::Args),
    /// Dimensional synthesis: frame anchor angles maximising the dextrous workspace (eq. 6.29).
    Synthesize(cli::synthesize::Args),
    /// Tensions along a path: profiles, infeasible samples, largest jumps.
    Trajectory(cli::trajectory::Args),
    /// Platform displacement over the feasible polygon (Picard, Caro, Plestan & Claveau 2020, Fig. 4).
    StiffnessMap(cli::stiffness_map::Args),
    /// Writes a robot file in another format: `cdpr convert IN -o OUT.toml|OUT.wcrfx`.
    Convert(cli::convert::Args),
    /// Forward dynamics: the platform's motion under given tensions or elastic cables.
    Simulate(cli::simulate::Args),
    /// Calibration from cable-length readings: anchors, attachments, offsets, gains (known poses or self-calibration).
    Calibrate(cli::calibrate::Args),
}

fn main() -> ExitCode {
    // Rust ignores SIGPIPE, so printing into a closed pipe (`cdpr trajectory … | head`) would
    // panic; the default action ends the program quietly, as other command-line tools do.
    #[cfg(unix)]
    // SAFETY: called first thing in `main`, before any other thread exists.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let cli = Cli::parse();
    let mut options = cdpr::io::LoadOptions::default();
    options.cable_set = cli.cable_set;
    cli::set_load_options(options);
    cli::set_kinematics_model(cli.kinematics);
    let result = match cli.command {
        Command::Kinematics(a) => cli::kinematics::run(a),
        Command::Forward(a) => cli::forward::run(a),
        Command::Stiffness(a) => cli::stiffness::run(a),
        Command::Tension(a) => cli::tension::run(a),
        Command::Isotropic(a) => cli::isotropic::run(a),
        Command::Capacity(a) => cli::capacity::run(a),
        Command::Workspace(a) => cli::workspace::run(a),
        Command::Dextrous(a) => cli::dextrous::run(a),
        Command::Orientations(a) => cli::orientations::run(a),
        Command::Synthesize(a) => cli::synthesize::run(a),
        Command::Trajectory(a) => cli::trajectory::run(a),
        Command::StiffnessMap(a) => cli::stiffness_map::run(a),
        Command::Convert(a) => cli::convert::run(a),
        Command::Simulate(a) => cli::simulate::run(a),
        Command::Calibrate(a) => cli::calibrate::run(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}
