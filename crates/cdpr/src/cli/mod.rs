//! Shared conventions of the `cdpr` subcommands: argument parsing, robot loading, output.

pub mod cable_model;
pub mod calibrate;
pub mod capacity;
pub mod convert;
pub mod criteria;
pub mod dextrous;
pub mod forward;
pub mod isotropic;
pub mod kinematics;
pub mod orientations;
pub mod region;
pub mod robot_plot;
pub mod simulate;
pub mod stiffness;
pub mod stiffness_map;
pub mod synthesize;
pub mod tension;
pub mod time_law;
pub mod trajectory;
pub mod workspace;
pub mod workspace_chord;
pub mod workspace_grid;
pub mod workspace_mesh;

use cdpr::RobotDescription;
use cdpr::io::LoadOptions;
use nalgebra::DMatrix;
use std::path::Path;
use std::sync::OnceLock;

/// Options every command applies when it loads its robot file (`--cable-set`).
static LOAD_OPTIONS: OnceLock<LoadOptions> = OnceLock::new();

/// Sets the load options once, from the global command-line flags.
pub fn set_load_options(options: LoadOptions) {
    let _ = LOAD_OPTIONS.set(options);
}

/// Any error a command reports (printed on stderr, exit code 2).
pub type CliError = Box<dyn std::error::Error>;

/// Comma-separated numbers on the command line (`-0.5,0.2,0`).
#[derive(Debug, Clone, PartialEq)]
pub struct Numbers(pub Vec<f64>);

impl std::str::FromStr for Numbers {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        s.split(',')
            .map(|p| {
                let p = p.trim();
                p.parse::<f64>().map_err(|_| {
                    format!(
                        "`{p}` is not a number (expected comma-separated numbers like -0.5,0.2,0)"
                    )
                })
            })
            .collect::<Result<_, _>>()
            .map(Numbers)
    }
}

impl std::ops::Deref for Numbers {
    type Target = [f64];
    fn deref(&self) -> &[f64] {
        &self.0
    }
}

/// `value_parser` of a quantity that must be a finite number > 0 (clap names the option:
/// "invalid value '-0.1' for '--chord <CHORD>': must be a finite number > 0").
pub fn positive(s: &str) -> Result<f64, String> {
    let v = number(s)?;
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(format!("must be a finite number > 0, got {s}"))
    }
}

/// `value_parser` of a quantity that must be a finite number ≥ 0.
pub fn non_negative(s: &str) -> Result<f64, String> {
    let v = number(s)?;
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err(format!("must be a finite number ≥ 0, got {s}"))
    }
}

/// `value_parser` of a weight in [0, 1] (SOTDA's ν).
pub fn unit_interval(s: &str) -> Result<f64, String> {
    let v = number(s)?;
    if (0.0..=1.0).contains(&v) {
        Ok(v)
    } else {
        Err(format!("must lie in [0, 1], got {s}"))
    }
}

/// `value_parser` of a finite number (any sign).
pub fn finite(s: &str) -> Result<f64, String> {
    let v = number(s)?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(format!("must be a finite number, got {s}"))
    }
}

/// `value_parser` of a count: a whole number ≥ 1 (grid intervals, samples).
pub fn count(s: &str) -> Result<usize, String> {
    match s.trim().parse::<i64>() {
        Ok(v) if v >= 1 => usize::try_from(v).map_err(|_| format!("{s} is too large")),
        Ok(_) => Err(format!("must be a whole number ≥ 1, got {s}")),
        Err(_) => Err(format!("`{s}` is not a whole number (expected 1, 2, 3, …)")),
    }
}

fn number(s: &str) -> Result<f64, String> {
    s.trim()
        .parse::<f64>()
        .map_err(|_| format!("`{s}` is not a number"))
}

/// The long help of a `--method` option: every tension distribution method with one line.
pub fn method_help() -> String {
    let mut s = String::from(
        "Tension distribution method (n cables, DOF degrees of freedom, redundancy r = n − DOF):",
    );
    for m in cdpr::tension::Method::ALL {
        s.push_str(&format!("\n  {:<21} {}", m.name(), m.summary()));
    }
    s
}

/// The cable model of `--kinematics` (a global option every command takes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum KinematicsModel {
    /// Cables over their swivel pulleys (Pott 2018): length = wrapped arc + free segment.
    Pulley,
    /// Straight cables from each `frame` point; pulleys in the robot file are ignored.
    Standard,
}

/// `--kinematics` as given, set once by `main` before a command runs (a process-wide option:
/// every command loads its robot through [`load_robot`], which applies it).
static KINEMATICS: OnceLock<Option<KinematicsModel>> = OnceLock::new();

/// Records `--kinematics` for [`load_robot`].
pub fn set_kinematics_model(model: Option<KinematicsModel>) {
    // A second call (never made by `main`) keeps the first value.
    let _ = KINEMATICS.set(model);
}

/// A usage error (exit 2) when `method` does not apply to the robot: its redundancy
/// n − DOF ("method closed-form needs redundancy 1; this robot has n − DOF = 2; methods that
/// apply: …"), or an infinite t_max for the improved closed form. Every command that takes
/// `--method` calls it before any pose is evaluated.
pub fn check_method(
    robot: &RobotDescription,
    method: cdpr::tension::Method,
) -> Result<(), CliError> {
    cdpr::wrench::require_enough_cables(&robot.robot, "tension distribution")?;
    let r = robot.robot.cable_count() as isize - robot.robot.dof() as isize;
    method.check_redundancy(r)?;
    if method == cdpr::tension::Method::ImprovedClosedForm
        && let Some(cable) = robot.bounds.max().iter().position(|v| !v.is_finite())
    {
        return Err(cdpr::tension::TensionError::NeedsFiniteBounds { method, cable }.into());
    }
    Ok(())
}

/// Loads a robot file (TOML, CASPR or WireCenter, by extension; `--cable-set` applied), applies
/// `--kinematics` (`standard` drops the pulleys) and prints the file's warnings on stderr.
pub fn load_robot(path: &Path) -> Result<RobotDescription, CliError> {
    let mut robot =
        RobotDescription::load_with(path, LOAD_OPTIONS.get_or_init(LoadOptions::default))?;
    if KINEMATICS.get().copied().flatten() == Some(KinematicsModel::Standard) {
        robot.robot = robot.robot.without_pulleys();
    }
    for w in &robot.warnings {
        eprintln!("warning: {}: {w}", path.display());
    }
    Ok(robot)
}

/// A number as a person reads it: at most 9 significant digits (so that round-off such as
/// −98.10000000000001 prints as −98.1), never `-0`, scientific notation only for very large or
/// very small magnitudes, `inf`/`-inf`/`NaN` spelled out.
pub fn num(v: f64) -> String {
    if v.is_nan() {
        return "NaN".into();
    }
    if v.is_infinite() {
        return if v > 0.0 { "inf".into() } else { "-inf".into() };
    }
    // Round to 9 significant digits through the shortest decimal of the rounded value.
    let r: f64 = format!("{v:.8e}").parse().unwrap_or(v);
    if r == 0.0 {
        return "0".into();
    }
    let a = r.abs();
    if (1e-4..1e9).contains(&a) {
        format!("{r}")
    } else {
        format!("{r:e}")
    }
}

/// A list of numbers as `[a, b, c]` (each by [`num`]).
#[allow(dead_code)] // lead: unused at this merge; the surface work uses it next
pub fn nums(v: &[f64]) -> String {
    format!(
        "[{}]",
        v.iter().map(|&x| num(x)).collect::<Vec<_>>().join(", ")
    )
}

/// A wrench with its units: forces in N, moments in N·m (the first `forces` components are
/// A pose for the robot's motion pattern from command-line numbers.
pub fn pose(robot: &RobotDescription, q: &[f64]) -> Result<cdpr::kinematics::Pose, CliError> {
    Ok(cdpr::kinematics::Pose::from_coordinates(
        robot.robot.motion(),
        q,
    )?)
}

/// forces), e.g. `[0 N, -98.1 N, 0 N·m]`.
pub fn wrench_text(w: &[f64], forces: usize) -> String {
    let parts: Vec<String> = w
        .iter()
        .enumerate()
        .map(|(i, &x)| format!("{} {}", num(x), if i < forces { "N" } else { "N·m" }))
        .collect();
    format!("[{}]", parts.join(", "))
}

/// A pose with its units: positions in m, angles in rad (motion-pattern coordinates).
pub fn pose_text(q: &[f64], positions: usize) -> String {
    let parts: Vec<String> = q
        .iter()
        .enumerate()
        .map(|(i, &x)| format!("{} {}", num(x), if i < positions { "m" } else { "rad" }))
        .collect();
    format!("({})", parts.join(", "))
}

/// Prints a matrix as an aligned table with a heading.
pub fn print_matrix(title: &str, m: &DMatrix<f64>) {
    println!("{title}");
    for r in m.row_iter() {
        // A value that rounds to zero prints as 0, never -0.
        let cells: Vec<String> = r
            .iter()
            .map(|&v| format!("{:>12.6}", if v.abs() < 5e-7 { 0.0 } else { v }))
            .collect();
        println!("  {}", cells.join(" "));
    }
}

/// The robot of a request ([`cdpr::api::Robot`]), loaded by [`load_robot`].
pub fn request_robot(path: &Path) -> Result<cdpr::api::Robot, CliError> {
    Ok(cdpr::api::Robot::from_description(load_robot(path)?))
}

/// Prints a report as the command's JSON (keys in the same sorted order as [`print_json`]).
pub fn print_report<T: serde::Serialize>(report: &T) -> Result<(), CliError> {
    print_json(&serde_json::to_value(report)?)
}

/// Prints a JSON value on stdout.
pub fn print_json(v: &serde_json::Value) -> Result<(), CliError> {
    println!("{}", serde_json::to_string_pretty(v)?);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 13 §2: no `-0`, no `-98.10000000000001`, no `Some([…])`: one formatter.
    #[test]
    fn numbers_read_as_a_person_writes_them() {
        assert_eq!(num(-0.0), "0");
        assert_eq!(num(-1e-300), "-1e-300");
        assert_eq!(num(-98.10000000000001), "-98.1");
        assert_eq!(num(0.1 + 0.2), "0.3");
        assert_eq!(num(1966.5), "1966.5");
        assert_eq!(num(-0.49999999994), "-0.5");
        assert_eq!(num(f64::INFINITY), "inf");
        assert_eq!(num(1e155), "1e155");
        assert_eq!(num(2.5e-7), "2.5e-7");
        assert_eq!(nums(&[0.0, -0.0, 1.5]), "[0, 0, 1.5]");
        assert_eq!(
            wrench_text(&[0.0, -98.10000000000001, -0.0], 2),
            "[0 N, -98.1 N, 0 N·m]"
        );
        assert_eq!(pose_text(&[0.5, -0.2, 0.1], 2), "(0.5 m, -0.2 m, 0.1 rad)");
    }
}
