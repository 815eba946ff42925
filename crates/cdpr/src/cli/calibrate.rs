//! `cdpr calibrate`: kinematic calibration from cable-length readings (crate
//! `cdpr-calibration`).

use super::{CliError, print_report, request_robot};
use cdpr::RobotDescription;
use cdpr::api::{CalibrationRequest, SamplesSource};
use cdpr::calibration::{Calibration, Unknowns};
use cdpr::io::Encoders;
use cdpr::kinematics::nalgebra::Vector3;
use std::path::{Path, PathBuf};

/// Calibrates a robot from samples of its cable-length readings: frame anchors, platform
/// attachments, length offsets and encoder gains (true length = gain_i · reading + offset_i).
///
/// With --known-poses the CSV gives each sample's pose (measured by a tracker) and each cable is
/// fitted by least squares on its own. Without, the poses are unknowns too (self-calibration,
/// Borgstrom et al. 2009; Miermeister & Pott 2012): Levenberg–Marquardt on poses and parameters
/// from the nominal robot's forward kinematics, with the gauge fixed (anchor 1 held, anchor 2
/// moving only along the line from anchor 1, anchor 3 only in the plane of anchors 1–3; the JSON
/// `gauge` says what is held). The samples identify p parameters up to the gauge g only if
/// k (n − d) ≥ p − g (k samples, n cables, d DOF) and the Jacobian has full rank: otherwise
/// `identifiable` is false, with `samples_needed` and `reason` (exit 0). A robot with as many
/// cables as DOF never self-calibrates. A condition number above 1e3 is warned about. Robots
/// with swivel pulleys calibrate from known poses with the pulley model (pulley radius and
/// orientation held); their self-calibration is refused (exit 2, with the reason).
///
/// CSV (comma-separated, a header line first, `#` comments and blank lines skipped): with
/// --known-poses the pose coordinates by name (point2 `x,y`; planar `x,y,phi`; point3 `x,y,z`;
/// spatial `x,y,z,rx,ry,rz`, m and rad), and always the readings `l1,…,ln` (one per cable).
/// With --relative the readings count from the reference pose (the robot file's `home_pose`,
/// else the origin): true length = gain · reading + offset + the length at the reference pose
/// (the Hangprinter workflow).
///
/// JSON fields: `robot`, `motion`, `samples` (k), `cables` (n), `known_poses`, `relative`,
/// `unknowns`, `frame` (calibrated anchors, m), `platform` (attachments, m), `offsets` (m),
/// `gains`, `poses` (self-calibration: the estimated poses, motion-pattern coordinates, m and rad;
/// null with known poses), `residual_rms` (√(Σr²/N), m), `residual_max` (m), `length_sigma`
/// (σ̂ = √(Σr²/(N − P)), m), `sigma` (per parameter group `frame`, `platform`, `offsets`,
/// `gains`: standard deviations from σ̂²(JᵀJ)⁻¹, null for groups not calibrated; null when not
/// identifiable), `identifiable`, `rank_deficiency`, `condition_number` (of the column-scaled
/// Jacobian; null when singular), `parameters` (p), `gauge_count` (g), `gauge` (what is held),
/// `samples_needed`, `reason`, `iterations`, `converged`, `warnings`.
#[derive(clap::Args)]
pub struct Args {
    /// The nominal robot file (TOML, CASPR XML or WireCenter .wcrfx).
    robot: PathBuf,
    /// The samples (CSV, see above).
    #[arg(long)]
    samples: PathBuf,
    /// The CSV gives each sample's pose (calibration from known poses).
    #[arg(long)]
    known_poses: bool,
    /// The parameter groups to calibrate, comma-separated: frame, platform, offsets, gains.
    #[arg(long, default_value = "frame,offsets")]
    unknowns: String,
    /// Readings relative to the reference pose (the file's `home_pose`, else the origin).
    #[arg(long)]
    relative: bool,
    /// Write the calibrated robot (TOML or .wcrfx, by extension): anchors and attachments, and
    /// in TOML the offsets and gains as the cables' `offset` and `gain` keys (.wcrfx cannot
    /// hold them: a warning says so).
    #[arg(short = 'o', long = "output", value_name = "OUT")]
    output: Option<PathBuf>,
    /// Write one JSON object on stdout instead of a table.
    #[arg(long)]
    json: bool,
}

/// Runs the command: parse → request → run → render.
pub fn run(args: Args) -> Result<(), CliError> {
    let robot = request_robot(&args.robot)?;
    // The unknowns are checked before the samples file is read (as they were before the request).
    Unknowns::parse(&args.unknowns)?;
    let text = std::fs::read_to_string(&args.samples)
        .map_err(|e| format!("{}: cannot read: {e}", args.samples.display()))?;
    let mut request = CalibrationRequest::new(
        robot,
        SamplesSource::Csv {
            text,
            file: Some(args.samples.display().to_string()),
            known_poses: args.known_poses,
        },
    );
    request.unknowns = args.unknowns.clone();
    request.relative = args.relative;
    let report = request.run()?;
    for w in &report.warnings {
        eprintln!("warning: {w}");
    }
    if let Some(out) = &args.output {
        write_robot(request.robot.description(), &report.calibration, out)?;
    }
    if args.json {
        print_report(&report)
    } else {
        print_table(request.robot.description(), &report.calibration);
        Ok(())
    }
}

/// A point as its motion pattern's number of coordinates.
fn point(v: &Vector3<f64>, dim: usize) -> Vec<f64> {
    v.iter().take(dim).copied().collect()
}

fn print_table(desc: &RobotDescription, cal: &Calibration) {
    let motion = desc.robot.motion();
    let dim = motion.space_dim();
    println!(
        "robot {} ({motion}), {} samples of {} cables, {}",
        desc.name,
        cal.counting.equations / desc.robot.cable_count(),
        desc.robot.cable_count(),
        if cal.poses_estimated {
            "self-calibration (unknown poses)"
        } else {
            "known poses"
        }
    );
    if !cal.identifiable {
        println!("not identifiable: {}", identifiability_reason(cal));
        return;
    }
    let fmt = |v: &Vector3<f64>| {
        point(v, dim)
            .iter()
            .map(|x| format!("{x:.6}"))
            .collect::<Vec<_>>()
            .join(",")
    };
    println!(
        "{:>3}  {:<30} {:<24} {:>12} {:>10}",
        "#", "frame anchor (m)", "change from nominal (m)", "offset (m)", "gain"
    );
    for (i, c) in desc.robot.cables().iter().enumerate() {
        println!(
            "{:>3}  {:<30} {:<24} {:>12.6} {:>10.6}",
            i + 1,
            fmt(&cal.parameters.frame[i]),
            fmt(&(cal.parameters.frame[i] - c.frame)),
            cal.parameters.offsets[i],
            cal.parameters.gains[i]
        );
    }
    println!(
        "residual rms {:.3e} m, max {:.3e} m, σ̂ {} m; condition number {:.3e}",
        cal.residual_rms,
        cal.residual_max,
        cal.length_sigma
            .map_or("—".to_string(), |s| format!("{s:.3e}")),
        cal.condition_number
    );
    if !cal.gauge.is_empty() {
        println!("gauge held at nominal: {}", cal.gauge.join("; "));
    }
}

fn identifiability_reason(cal: &Calibration) -> String {
    match (&cal.counting.reason, cal.rank_deficiency) {
        (Some(r), _) => r.clone(),
        (None, d) => format!("the Jacobian is rank deficient by {d}"),
    }
}

/// Writes the calibrated geometry, offsets and gains (robot-file keys `offset`, `gain`).
fn write_robot(desc: &RobotDescription, cal: &Calibration, out: &Path) -> Result<(), CliError> {
    if !cal.identifiable {
        return Err(format!(
            "not writing {}: the samples do not identify the unknowns ({})",
            out.display(),
            identifiability_reason(cal)
        )
        .into());
    }
    let mut calibrated = desc.clone();
    let mut cables = desc.robot.cables().to_vec();
    for (i, c) in cables.iter_mut().enumerate() {
        c.frame = cal.parameters.frame[i];
        c.platform = cal.parameters.platform[i];
    }
    calibrated.robot = cdpr::kinematics::Robot::new(desc.robot.motion(), cables)?;
    calibrated.encoders = Some(Encoders {
        offsets: cal.parameters.offsets.clone(),
        gains: cal.parameters.gains.clone(),
    });
    let header = format!(
        "{} — calibrated by `cdpr calibrate` (residual rms {:.3e} m; the cables' `offset` (m) \
         and `gain` keys: true length = gain · reading + offset)",
        desc.name, cal.residual_rms,
    );
    for w in calibrated.save(out, &header)? {
        eprintln!("warning: {}: {w}", out.display());
    }
    Ok(())
}
