//! `cdpr calibrate`: kinematic calibration from cable-length readings (crate
//! `cdpr-calibration`).

use super::{CliError, load_robot, print_json};
use cdpr::RobotDescription;
use cdpr::calibration::{Calibration, Readings, Samples, Unknowns, calibrate_with_encoders};
use cdpr::io::Encoders;
use cdpr::kinematics::nalgebra::Vector3;
use cdpr::kinematics::{MotionPattern, Pose};
use serde_json::{Value, json};
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

/// Runs the command.
pub fn run(args: Args) -> Result<(), CliError> {
    let desc = load_robot(&args.robot)?;
    let robot = &desc.robot;
    let motion = robot.motion();
    let unknowns = Unknowns::parse(&args.unknowns)?;
    let samples = read_samples(&args.samples, motion, robot.cable_count(), args.known_poses)?;
    let readings = if args.relative {
        let reference = match &desc.home_pose {
            Some(q) => Pose::from_coordinates(motion, q)?,
            None => Pose::from_coordinates(motion, &vec![0.0; motion.dof()])?,
        };
        Readings::Relative { reference }
    } else {
        Readings::Absolute
    };
    // A robot file written by `calibrate -o` holds calibrated encoders: start from them.
    let encoders = desc
        .encoders
        .clone()
        .unwrap_or_else(|| Encoders::identity(robot.cable_count()));
    let cal = calibrate_with_encoders(
        robot,
        &encoders.offsets,
        &encoders.gains,
        &samples,
        unknowns,
        &readings,
    )?;
    for w in &cal.warnings {
        eprintln!("warning: {w}");
    }
    if let Some(out) = &args.output {
        write_robot(&desc, &cal, out)?;
    }
    if args.json {
        print_json(&report(&desc, &args, &cal))
    } else {
        print_table(&desc, &cal);
        Ok(())
    }
}

/// The pose columns of a motion pattern.
fn pose_columns(motion: MotionPattern) -> &'static [&'static str] {
    match motion {
        MotionPattern::Point2 => &["x", "y"],
        MotionPattern::Planar => &["x", "y", "phi"],
        MotionPattern::Point3 => &["x", "y", "z"],
        MotionPattern::Spatial => &["x", "y", "z", "rx", "ry", "rz"],
    }
}

/// Reads the CSV; errors name the file, line and column (exit 2).
fn read_samples(
    path: &Path,
    motion: MotionPattern,
    n: usize,
    known_poses: bool,
) -> Result<Samples, CliError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
    let file = path.display();
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let Some((header_line, header)) = lines.next() else {
        return Err(format!("{file}: no header line (expected l1,…,l{n})").into());
    };
    let names: Vec<String> = header.split(',').map(|s| s.trim().to_lowercase()).collect();
    let find = |name: &str| names.iter().position(|c| c == name);
    let mut wanted: Vec<String> = (1..=n).map(|i| format!("l{i}")).collect();
    if known_poses {
        wanted.splice(0..0, pose_columns(motion).iter().map(|s| s.to_string()));
    }
    let mut index = Vec::with_capacity(wanted.len());
    for w in &wanted {
        match find(w) {
            Some(c) => index.push(c),
            None => {
                return Err(format!(
                    "{file}:{header_line}: missing column `{w}` (the header needs {}{})",
                    wanted.join(","),
                    if known_poses {
                        format!(
                            ": the pose of a {} robot and one reading per cable",
                            motion.name()
                        )
                    } else {
                        ": one reading per cable".to_string()
                    }
                )
                .into());
            }
        }
    }
    if let Some((c, extra)) = names.iter().enumerate().find(|(_, c)| !wanted.contains(c)) {
        return Err(format!(
            "{file}:{header_line}, column {}: unexpected column `{extra}` (expected {}{})",
            c + 1,
            wanted.join(","),
            if !known_poses && pose_columns(motion).contains(&extra.as_str()) {
                "; pose columns need --known-poses"
            } else {
                ""
            }
        )
        .into());
    }
    let dof = motion.dof();
    let (mut readings, mut poses) = (Vec::new(), Vec::new());
    for (line, row) in lines {
        let fields: Vec<&str> = row.split(',').map(str::trim).collect();
        if fields.len() != names.len() {
            return Err(format!(
                "{file}:{line}: {} fields, the header has {} columns",
                fields.len(),
                names.len()
            )
            .into());
        }
        let mut values = Vec::with_capacity(wanted.len());
        for (w, &c) in wanted.iter().zip(&index) {
            let v: f64 = fields[c].parse().map_err(|_| {
                format!(
                    "{file}:{line}, column {} (`{w}`): `{}` is not a number",
                    c + 1,
                    fields[c]
                )
            })?;
            if !v.is_finite() {
                return Err(format!(
                    "{file}:{line}, column {} (`{w}`): not a finite number ({v})",
                    c + 1
                )
                .into());
            }
            values.push(v);
        }
        if known_poses {
            poses.push(Pose::from_coordinates(motion, &values[..dof])?);
            readings.extend_from_slice(&values[dof..]);
        } else {
            readings.extend_from_slice(&values);
        }
    }
    if readings.is_empty() {
        return Err(format!("{file}: no samples after the header").into());
    }
    Ok(Samples {
        readings,
        poses: known_poses.then_some(poses),
    })
}

/// A point as its motion pattern's number of coordinates.
fn point(v: &Vector3<f64>, dim: usize) -> Vec<f64> {
    v.iter().take(dim).copied().collect()
}

fn finite_or_null(v: f64) -> Value {
    if v.is_finite() { json!(v) } else { Value::Null }
}

fn report(desc: &RobotDescription, args: &Args, cal: &Calibration) -> Value {
    let motion = desc.robot.motion();
    let dim = motion.space_dim();
    let points = |v: &[Vector3<f64>]| -> Value { v.iter().map(|p| point(p, dim)).collect() };
    let p = &cal.parameters;
    let sigma = cal.sigma.as_ref().map(|s| {
        json!({
            "frame": s.frame.as_deref().map(points),
            "platform": s.platform.as_deref().map(points),
            "offsets": s.offsets,
            "gains": s.gains,
        })
    });
    let unknowns: Vec<&str> = args.unknowns.split(',').map(str::trim).collect();
    json!({
        "robot": desc.name,
        "motion": motion.name(),
        "samples": cal.counting.equations / desc.robot.cable_count(),
        "cables": desc.robot.cable_count(),
        "known_poses": args.known_poses,
        "relative": args.relative,
        "unknowns": unknowns,
        "frame": points(&p.frame),
        "platform": motion.has_orientation().then(|| points(&p.platform)),
        "offsets": p.offsets,
        "gains": p.gains,
        "poses": cal.poses_estimated.then(|| {
            cal.poses.iter().map(|x| x.coordinates(motion)).collect::<Vec<_>>()
        }),
        "residual_rms": finite_or_null(cal.residual_rms),
        "residual_max": finite_or_null(cal.residual_max),
        "length_sigma": cal.length_sigma,
        "sigma": sigma,
        "identifiable": cal.identifiable,
        "rank_deficiency": cal.rank_deficiency,
        "condition_number": finite_or_null(cal.condition_number),
        "parameters": cal.counting.parameters,
        "gauge_count": cal.counting.gauge,
        "gauge": cal.gauge,
        "samples_needed": cal.counting.samples_needed,
        "reason": cal.counting.reason,
        "iterations": cal.iterations,
        "converged": cal.converged,
        "warnings": cal.warnings,
    })
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
