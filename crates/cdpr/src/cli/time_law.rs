//! `cdpr trajectory … --time-law LAW`: timed trajectories and their inverse dynamics (issue 28).
//!
//! The path of `cdpr trajectory` (segment or waypoints) run with a time law of
//! `cdpr_dynamics::time_law`, sampled every --dt s. At every sample the tensions balance
//! w_e + w_g (+ passive springs), and with --dynamics also the inertial wrench: W t + w_e + w_g =
//! M ẍ + b (`cdpr_dynamics::inverse_dynamics`). JSON adds `t` (s), `velocity`, `acceleration`
//! (DOF numbers per sample: the twist [v (m/s); ω (rad/s)] and its rate), `cable_lengths` (m),
//! `cable_speeds` (l̇ = −Wᵀẋ, m/s), `cable_accelerations` (m/s²) and, with --dynamics,
//! `inertial_wrench` (M ẍ + b, N and N·m). With a `winch` on every cable of the robot file, the
//! drive train (`cdpr_dynamics::drive_train`): `motor_speeds` (rad/s), `motor_torques` (N·m, null
//! where infeasible), `motor_powers` (W), per motor `motor_peak_speed`, `motor_rms_speed`,
//! `motor_peak_torque`, `motor_rms_torque`, `motor_peak_power`, the limits `motor_max_torque`,
//! `motor_max_speed`, `peak_total_power` (W) and the verdict `motors_within_limits` (true,
//! false, or null when unknown) with `motor_limit_violations`.

use super::CliError;
use cdpr::api::Robot;
use cdpr::api::timed::{CasprTrajectorySource, DriveTrainReport, TimedReport, TimedSettings};
use cdpr::dynamics::TimeLaw;
use cdpr::kinematics::Pose;
use cdpr::plot::{LinePlot, Series};
use std::path::Path;

/// The timing flags of `cdpr trajectory`.
#[derive(clap::Args, Debug, Clone)]
pub struct TimingArgs {
    /// Time law along the path: linear, cubic, quintic, trapezoid (--max-acceleration, and
    /// --max-velocity or --duration) or parabolic-blend (--blend-time). Rest at every waypoint
    /// except with parabolic-blend. Replaces --samples/--step by --dt.
    #[arg(long, value_name = "LAW", value_parser = parse_law, group = "timed", conflicts_with_all = ["samples", "step"])]
    pub time_law: Option<TimeLaw>,
    /// A CASPR trajectories file (NAME_trajectories.xml) instead of the path and the time law:
    /// the joint trajectory --trajectory-id ID (linear, cubic, quintic, cubic-average-velocity
    /// or parabolic-blend spline) through the file's points at its times, sampled every
    /// `time_step` s as CASPR does; orientations along CASPR's shortest rotation (or, with
    /// non-zero Euler rates, ω = H(φ) φ̇). See docs/robot-file.md.
    #[arg(long, value_name = "FILE.xml", group = "timed", conflicts_with_all = ["samples", "step", "from", "waypoints"])]
    pub trajectory: Option<std::path::PathBuf>,
    /// The `id` of the trajectory in --trajectory (default: the file's only one).
    #[arg(long, value_name = "ID", requires = "trajectory")]
    pub trajectory_id: Option<String>,
    /// Total duration T (s), shared among segments in proportion to their pose distance (or
    /// give each waypoint a `time` in the --waypoints file).
    #[arg(long, requires = "timed", value_parser = super::positive)]
    pub duration: Option<f64>,
    /// Sampling period (s) of the timed trajectory (default 0.01 s).
    #[arg(long, requires = "timed", value_parser = super::positive)]
    pub dt: Option<f64>,
    /// Largest speed along the path (m/s, 1 rad counting as 1 m): the trapezoid's cruise speed
    /// bound; the other rest-to-rest laws are checked against it.
    #[arg(long, requires = "timed", value_parser = super::positive)]
    pub max_velocity: Option<f64>,
    /// Largest acceleration along the path (m/s²).
    #[arg(long, requires = "timed", value_parser = super::positive)]
    pub max_acceleration: Option<f64>,
    /// Parabolic blend time t_b (s; default a quarter of the shortest segment).
    #[arg(long, requires = "timed", value_parser = super::positive)]
    pub blend_time: Option<f64>,
    /// Inverse dynamics: balance the inertial wrench M ẍ + b too (needs the platform's mass,
    /// and `inertia` for planar and spatial platforms).
    #[arg(long, requires = "timed")]
    pub dynamics: bool,
    /// Motor torques against time (N·m, one line per motor, dashed ±max_torque): needs a
    /// `winch` on every cable of the robot file.
    #[arg(long, value_name = "FILE", requires = "timed")]
    pub motor_torque_plot: Option<std::path::PathBuf>,
    /// Cable speeds l̇ against time (m/s, one line per cable; with winches, dashed ± the cable
    /// speed of max_speed, r/G · max_speed).
    #[arg(long, value_name = "FILE", requires = "timed")]
    pub cable_speed_plot: Option<std::path::PathBuf>,
    /// A self-contained HTML page replaying the trajectory: platform and cables moving, cables
    /// coloured by tension, play button and time slider.
    #[arg(long, value_name = "FILE.html", requires = "timed")]
    pub replay: Option<std::path::PathBuf>,
}

fn parse_law(s: &str) -> Result<TimeLaw, String> {
    s.parse()
}

impl TimingArgs {
    /// The request's time law and inverse-dynamics settings.
    pub fn settings(&self) -> TimedSettings {
        TimedSettings {
            time_law: self.time_law,
            duration: self.duration,
            dt: self.dt,
            max_velocity: self.max_velocity,
            max_acceleration: self.max_acceleration,
            blend_time: self.blend_time,
            dynamics: self.dynamics,
        }
    }
}

impl TimingArgs {
    /// The CASPR trajectory of --trajectory, read as text.
    pub fn caspr_source(&self) -> Result<Option<CasprTrajectorySource>, CliError> {
        let Some(file) = &self.trajectory else {
            return Ok(None);
        };
        let text = std::fs::read_to_string(file)
            .map_err(|e| format!("{}: cannot read: {e}", file.display()))?;
        Ok(Some(CasprTrajectorySource {
            text,
            id: self.trajectory_id.clone(),
            file: Some(file.display().to_string()),
        }))
    }
}

/// The outputs asked of a timed trajectory.
pub struct Outputs<'a> {
    /// The timing flags (with the plot files).
    pub timing: &'a TimingArgs,
    /// The tension plot (`--plot`).
    pub plot: Option<&'a Path>,
    /// Write JSON.
    pub json: bool,
}

/// Outputs that need what the robot file lacks (before any computation).
pub fn check_outputs(args: &TimingArgs, robot: &Robot) -> Result<(), CliError> {
    if args.motor_torque_plot.is_some() && robot.winches.is_none() {
        return Err(
            "--motor-torque-plot needs the drive train: `winch = { drum_radius, gear_ratio, motor_inertia }` on every cable of the robot file"
                .into(),
        );
    }
    Ok(())
}

/// Renders a timed trajectory: the plots and the replay, then JSON or the tables.
pub fn render(out: &Outputs, robot: &Robot, r: &TimedReport) -> Result<(), CliError> {
    let args = out.timing;
    if let Some(file) = out.plot {
        cdpr::plot::save(&tension_plot(robot, r), file)?;
    }
    if let (Some(file), Some(d)) = (&args.motor_torque_plot, &r.drive_train) {
        cdpr::plot::save(&motor_torque_plot(robot, r, d), file)?;
    }
    if let Some(file) = &args.cable_speed_plot {
        cdpr::plot::save(&cable_speed_plot(robot, r), file)?;
    }
    if let Some(file) = &args.replay {
        cdpr::plot::replay::save_html(&replay(robot, r)?, file)
            .map_err(|e| format!("{}: cannot write: {e}", file.display()))?;
    }
    if out.json {
        return super::print_report(r);
    }
    print_table(robot, r);
    if let Some(d) = &r.drive_train {
        print_drive_train(d);
    }
    Ok(())
}

/// Numbers in columns of 10, 4 decimals.
pub fn cells(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{x:>10.4}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// The column heads t1 … tn.
pub fn cable_head(n: usize) -> String {
    (1..=n)
        .map(|i| format!("{:>10}", format!("t{i}")))
        .collect::<Vec<_>>()
        .join(" ")
}

/// Peaks, RMS values and the verdict of the drive train.
fn print_drive_train(d: &DriveTrainReport) {
    let nan = |v: &[Option<f64>]| -> Vec<f64> { v.iter().map(|x| x.unwrap_or(f64::NAN)).collect() };
    println!("drive train (motor i winds cable i in for ω, τ > 0)");
    println!("{:>9}  {}  (rad/s)", "peak |ω|", cells(&d.motor_peak_speed));
    println!("{:>9}  {}  (rad/s)", "RMS ω", cells(&d.motor_rms_speed));
    println!("{:>9}  {}  (N·m)", "peak |τ|", cells(&d.motor_peak_torque));
    println!(
        "{:>9}  {}  (N·m)",
        "RMS τ",
        cells(&nan(&d.motor_rms_torque))
    );
    println!("{:>9}  {}  (W)", "peak P", cells(&nan(&d.motor_peak_power)));
    println!(
        "peak total power Σ τ ω: {:.4} W",
        d.peak_total_power.unwrap_or(f64::NAN)
    );
    match d.motors_within_limits {
        Some(true) => println!("the motors can do it: every torque and speed within its limits"),
        Some(false) => {
            println!("the motors cannot do it:");
            for v in &d.motor_limit_violations {
                println!("  {v}");
            }
        }
        None => println!(
            "limits not checked (no max_torque/max_speed given, or infeasible samples leave the torque unknown)"
        ),
    }
}

/// The tension table against time (at most ~40 rows, every infeasible sample) and the peak
/// cable rates.
fn print_table(robot: &Robot, r: &TimedReport) {
    let n = robot.robot.cable_count();
    println!(
        "robot {}, time law {}, method {}, {}, {} samples, {} feasible",
        robot.name,
        r.time_law,
        r.method,
        if r.dynamics {
            "inverse dynamics (W t + w = M ẍ + b)"
        } else {
            "quasi-static (no inertia)"
        },
        r.t.len(),
        r.feasible_count
    );
    println!("cable tensions t_i in N against time t in s");
    println!("{:>9}  {}", "t (s)", cable_head(n));
    let every = r.t.len().div_ceil(40).max(1);
    for (k, (t, ts)) in r.t.iter().zip(&r.tensions).enumerate() {
        match ts {
            Some(v) if k % every == 0 || k + 1 == r.t.len() => println!("{t:>9.4}  {}", cells(v)),
            Some(_) => {}
            None => println!(
                "{t:>9.4}  infeasible: {}",
                r.reasons[k].as_deref().unwrap_or("")
            ),
        }
    }
    let peak = |rows: &[Vec<f64>]| -> Vec<f64> {
        (0..n)
            .map(|i| {
                rows.iter()
                    .map(|row| row[i])
                    .filter(|v| v.is_finite())
                    .fold(0.0f64, |a, v| a.max(v.abs()))
            })
            .collect()
    };
    println!(
        "{:>9}  {}  (m/s)",
        "peak |l̇|",
        cells(&peak(&r.cable_speeds))
    );
    println!(
        "{:>9}  {}  (m/s²)",
        "peak |l̈|",
        cells(&peak(&r.cable_accelerations))
    );
}

/// Tensions against time, one line per cable, dashed t_min / t_max, gaps where infeasible.
fn tension_plot(robot: &Robot, r: &TimedReport) -> LinePlot {
    LinePlot {
        title: format!(
            "{}: tensions against time ({} law, {}, {}; {} of {} samples feasible)",
            robot.name,
            r.time_law,
            r.method,
            if r.dynamics {
                "inverse dynamics"
            } else {
                "quasi-static"
            },
            r.feasible_count,
            r.t.len()
        ),
        labels: ("time t (s)".into(), "cable tension (N)".into()),
        series: tension_series(robot.robot.cable_count(), &r.t, &r.tensions),
        reference_lines: bound_lines(robot),
        gap_label: Some("infeasible samples".into()),
    }
}

/// Dashed ± lines at a limit shared by every motor (none when the limits differ or are absent).
fn limit_lines(limits: &[Option<f64>], name: &str, unit: &str) -> Vec<(f64, String)> {
    match limits.first().copied().flatten() {
        Some(v) if limits.iter().all(|l| *l == Some(v)) => vec![
            (v, format!("+{} {unit} ({name})", cdpr::plot::tick(v))),
            (-v, format!("−{} {unit} ({name})", cdpr::plot::tick(v))),
        ],
        _ => Vec::new(),
    }
}

/// One series per column of `rows` against time, labelled `name i`; NaN (a gap) where a row is
/// missing.
fn column_series(name: &str, n: usize, t: &[f64], rows: &[Option<&Vec<f64>>]) -> Vec<Series> {
    (0..n)
        .map(|i| Series {
            label: format!("{name} {}", i + 1),
            points: t
                .iter()
                .zip(rows)
                .map(|(&t, row)| (t, row.map_or(f64::NAN, |row| row[i])))
                .collect(),
        })
        .collect()
}

/// Motor torques against time, one line per motor, dashed ±max_torque, gaps where infeasible.
fn motor_torque_plot(robot: &Robot, r: &TimedReport, d: &DriveTrainReport) -> LinePlot {
    let rows: Vec<Option<&Vec<f64>>> = d.motor_torques.iter().map(Option::as_ref).collect();
    LinePlot {
        title: format!(
            "{}: motor torques against time ({} law; τ = (r/G) t − J_m (G/r) d²l/dt², > 0 winds in)",
            robot.name, r.time_law
        ),
        labels: ("time t (s)".into(), "motor torque τ (N·m)".into()),
        series: column_series("motor", d.motor_max_torque.len(), &r.t, &rows),
        reference_lines: limit_lines(&d.motor_max_torque, "max", "N·m"),
        gap_label: Some("infeasible samples".into()),
    }
}

/// Cable speeds l̇ against time, one line per cable; with winches of one max_speed, dashed ±
/// the cable speed it allows (r/G · max_speed).
fn cable_speed_plot(robot: &Robot, r: &TimedReport) -> LinePlot {
    let rows: Vec<Option<&Vec<f64>>> = r.cable_speeds.iter().map(Some).collect();
    let limits: Vec<Option<f64>> = robot
        .winches
        .iter()
        .flatten()
        .map(|w| w.max_speed.map(|s| s * w.drum_radius / w.gear_ratio))
        .collect();
    LinePlot {
        title: format!(
            "{}: cable speeds against time ({} law; dl/dt = −Wᵀ dx/dt, > 0 pays out)",
            robot.name, r.time_law
        ),
        labels: ("time t (s)".into(), "cable speed dl/dt (m/s)".into()),
        series: column_series("cable", robot.robot.cable_count(), &r.t, &rows),
        reference_lines: limit_lines(&limits, "max", "m/s"),
        gap_label: None,
    }
}

/// The replay page's data: anchors, attachments, poses and tensions at every sample.
fn replay(robot: &Robot, r: &TimedReport) -> Result<cdpr::plot::Replay, CliError> {
    let triple = |v: &nalgebra::Vector3<f64>| [v.x, v.y, v.z];
    let cables = robot.robot.cables();
    let motion = robot.robot.motion();
    let poses = r
        .poses
        .iter()
        .map(|q| Pose::from_coordinates(motion, q))
        .collect::<Result<Vec<_>, _>>()?;
    let t_min = r.t_min.iter().cloned().fold(f64::INFINITY, f64::min);
    // The colour scale ends at the largest tension met (the largest finite bound if none is).
    let met = r
        .tensions
        .iter()
        .flatten()
        .flat_map(|t| t.iter().cloned())
        .fold(f64::NEG_INFINITY, f64::max);
    let bound = r
        .t_max
        .iter()
        .cloned()
        .filter(|v| v.is_finite())
        .fold(t_min, f64::max);
    Ok(cdpr::plot::Replay {
        title: format!(
            "{}: {} trajectory, {} tensions, {:.3} s",
            robot.name,
            r.time_law,
            r.method,
            r.t.last().copied().unwrap_or(0.0)
        ),
        anchors: cables.iter().map(|c| triple(&c.frame)).collect(),
        attachments: cables.iter().map(|c| triple(&c.platform)).collect(),
        t: r.t.clone(),
        positions: poses.iter().map(|p| triple(&p.position)).collect(),
        rotations: poses
            .iter()
            .map(|p| {
                let m = p.rotation.matrix();
                [0, 1, 2].map(|r| [m[(r, 0)], m[(r, 1)], m[(r, 2)]])
            })
            .collect(),
        tensions: r.tensions.clone(),
        reasons: r.reasons.clone(),
        t_min,
        t_max: if met.is_finite() { met } else { bound },
        planar: motion.space_dim() == 2,
    })
}

/// One series per cable of tensions against `x`, NaN (a gap) where infeasible.
pub fn tension_series(n: usize, x: &[f64], tensions: &[Option<Vec<f64>>]) -> Vec<Series> {
    (0..n)
        .map(|i| Series {
            label: format!("t{}", i + 1),
            points: x
                .iter()
                .zip(tensions)
                .map(|(&x, t)| (x, t.as_ref().map_or(f64::NAN, |t| t[i])))
                .collect(),
        })
        .collect()
}

/// Dashed t_min / t_max lines when every cable shares the bound.
pub fn bound_lines(robot: &Robot) -> Vec<(f64, String)> {
    let mut lines = Vec::new();
    let (lo, hi) = (robot.bounds.min(), robot.bounds.max());
    if lo.iter().all(|&v| v == lo[0]) {
        lines.push((lo[0], format!("t_min = {} N", cdpr::plot::tick(lo[0]))));
    }
    if hi.iter().all(|&v| v == hi[0]) && hi[0].is_finite() {
        lines.push((hi[0], format!("t_max = {} N", cdpr::plot::tick(hi[0]))));
    }
    lines
}
