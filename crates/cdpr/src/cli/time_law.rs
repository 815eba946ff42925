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
use cdpr::dynamics::{
    DriveTrainProfile, DynamicsProfile, RigidBody, TimeLaw, TimedSample, TimingSettings,
    Trajectory, drive_train, inverse_dynamics,
};
use cdpr::kinematics::Pose;
use cdpr::plot::{LinePlot, Series};
use cdpr::tension::TensionSolver;
use nalgebra::DVector;
use serde_json::json;
use std::path::Path;

/// The timing flags of `cdpr trajectory`.
#[derive(clap::Args, Debug, Clone)]
pub struct TimingArgs {
    /// Time law along the path: linear, cubic, quintic, trapezoid (--max-acceleration, and
    /// --max-velocity or --duration) or parabolic-blend (--blend-time). Rest at every waypoint
    /// except with parabolic-blend. Replaces --samples/--step by --dt.
    #[arg(long, value_name = "LAW", value_parser = parse_law, conflicts_with_all = ["samples", "step"])]
    pub time_law: Option<TimeLaw>,
    /// Total duration T (s), shared among segments in proportion to their pose distance (or
    /// give each waypoint a `time` in the --waypoints file).
    #[arg(long, requires = "time_law", value_parser = super::positive)]
    pub duration: Option<f64>,
    /// Sampling period (s) of the timed trajectory (default 0.01 s).
    #[arg(long, requires = "time_law", value_parser = super::positive)]
    pub dt: Option<f64>,
    /// Largest speed along the path (m/s, 1 rad counting as 1 m): the trapezoid's cruise speed
    /// bound; the other rest-to-rest laws are checked against it.
    #[arg(long, requires = "time_law", value_parser = super::positive)]
    pub max_velocity: Option<f64>,
    /// Largest acceleration along the path (m/s²).
    #[arg(long, requires = "time_law", value_parser = super::positive)]
    pub max_acceleration: Option<f64>,
    /// Parabolic blend time t_b (s; default a quarter of the shortest segment).
    #[arg(long, requires = "time_law", value_parser = super::positive)]
    pub blend_time: Option<f64>,
    /// Inverse dynamics: balance the inertial wrench M ẍ + b too (needs the platform's mass,
    /// and `inertia` for planar and spatial platforms).
    #[arg(long, requires = "time_law")]
    pub dynamics: bool,
    /// Motor torques against time (N·m, one line per motor, dashed ±max_torque): needs a
    /// `winch` on every cable of the robot file.
    #[arg(long, value_name = "FILE", requires = "time_law")]
    pub motor_torque_plot: Option<std::path::PathBuf>,
    /// Cable speeds l̇ against time (m/s, one line per cable; with winches, dashed ± the cable
    /// speed of max_speed, r/G · max_speed).
    #[arg(long, value_name = "FILE", requires = "time_law")]
    pub cable_speed_plot: Option<std::path::PathBuf>,
    /// A self-contained HTML page replaying the trajectory: platform and cables moving, cables
    /// coloured by tension, play button and time slider.
    #[arg(long, value_name = "FILE.html", requires = "time_law")]
    pub replay: Option<std::path::PathBuf>,
}

fn parse_law(s: &str) -> Result<TimeLaw, String> {
    s.parse()
}

/// What `cdpr trajectory` hands over in timed mode.
pub struct TimedRequest<'a> {
    /// The robot.
    pub robot: &'a cdpr::RobotDescription,
    /// Waypoint poses.
    pub poses: Vec<Pose>,
    /// w_e at each waypoint (interpolated linearly in time between waypoint times).
    pub wrenches: Vec<DVector<f64>>,
    /// Per-waypoint times from the file, if given.
    pub times: Option<Vec<f64>>,
    /// The tension solver.
    pub solver: &'a mut TensionSolver,
    /// Method name (for output).
    pub method: &'static str,
    /// E·S per cable (SOTDA).
    pub axial_stiffness: Option<&'a [f64]>,
    /// Write JSON.
    pub json: bool,
    /// Plot file.
    pub plot: Option<&'a Path>,
}

/// The `time` of every waypoint, or of none (`None`); a usage error naming the first waypoint
/// without one when only some have it, or a time in the file without --time-law.
pub fn waypoint_times<W>(
    file: &Path,
    waypoints: &[W],
    time: impl Fn(&W) -> Option<f64>,
) -> Result<Option<Vec<f64>>, CliError> {
    let given: Vec<Option<f64>> = waypoints.iter().map(time).collect();
    if given.iter().all(Option::is_none) {
        return Ok(None);
    }
    match given.iter().position(Option::is_none) {
        Some(k) => Err(format!(
            "{}: waypoints[{k}] has no `time` (give every waypoint a time, or none)",
            file.display()
        )
        .into()),
        None => Ok(Some(given.into_iter().flatten().collect())),
    }
}

/// The platform's rigid body from the robot file (see [`cdpr::api::criteria::rigid_body`]).
pub fn rigid_body(robot: &cdpr::RobotDescription) -> Result<RigidBody, CliError> {
    Ok(cdpr::api::criteria::rigid_body(robot)?)
}

/// Runs the timed trajectory.
pub fn run(args: &TimingArgs, req: TimedRequest) -> Result<(), CliError> {
    let law = args.time_law.expect("timed mode");
    if req.times.is_some() && args.duration.is_some() {
        return Err("give either --duration or a `time` on every waypoint, not both".into());
    }
    let robot = req.robot;
    if args.motor_torque_plot.is_some() && robot.winches.is_none() {
        return Err(
            "--motor-torque-plot needs the drive train: `winch = { drum_radius, gear_ratio, motor_inertia }` on every cable of the robot file"
                .into(),
        );
    }
    let motion = robot.robot.motion();
    let settings = TimingSettings {
        law,
        duration: args.duration,
        waypoint_times: req.times.clone(),
        max_velocity: args.max_velocity,
        max_acceleration: args.max_acceleration,
        blend_time: args.blend_time,
    };
    let traj = Trajectory::new(motion, &req.poses, &settings)?;
    let dt = args.dt.unwrap_or(0.01);
    let samples = traj.sample(dt)?;
    let body = if args.dynamics {
        Some(rigid_body(robot)?)
    } else {
        None
    };
    for s in &samples {
        robot
            .load_wrench(&s.pose)
            .map_err(|e| format!("at t = {} s: {e}", s.t))?;
    }
    let times = traj.waypoint_times();
    let wrench_at = |t: f64| -> DVector<f64> {
        let k = times.partition_point(|&c| c <= t).clamp(1, times.len() - 1) - 1;
        let span = times[k + 1] - times[k];
        let tau = if span > 0.0 {
            ((t - times[k]) / span).clamp(0.0, 1.0)
        } else {
            1.0
        };
        &req.wrenches[k] * (1.0 - tau) + &req.wrenches[k + 1] * tau
    };
    let profile = inverse_dynamics(
        &robot.robot,
        body.as_ref(),
        &samples,
        &robot.bounds,
        req.solver,
        req.axial_stiffness,
        |_, s: &TimedSample| {
            wrench_at(s.t)
                + robot
                    .load_wrench(&s.pose)
                    .expect("checked at every sample above")
        },
    )?;
    let drive = match &robot.winches {
        Some(w) => Some(drive_train(w, &profile)?),
        None => None,
    };
    if let Some(file) = req.plot {
        cdpr::plot::save(
            &tension_plot(robot, law, req.method, args.dynamics, &profile),
            file,
        )?;
    }
    if let (Some(file), Some(d)) = (&args.motor_torque_plot, &drive) {
        cdpr::plot::save(&motor_torque_plot(robot, law, &profile, d), file)?;
    }
    if let Some(file) = &args.cable_speed_plot {
        cdpr::plot::save(&cable_speed_plot(robot, law, &profile), file)?;
    }
    if let Some(file) = &args.replay {
        let replay = replay(robot, law, req.method, &samples, &profile);
        cdpr::plot::replay::save_html(&replay, file)
            .map_err(|e| format!("{}: cannot write: {e}", file.display()))?;
    }
    let n = robot.robot.cable_count();
    let dof = motion.dof();
    if req.json {
        let rows = |flat: &[f64], w: usize| -> Vec<Vec<f64>> {
            flat.chunks(w).map(|c| c.to_vec()).collect()
        };
        let mut out = json!({
            "robot": robot.name,
            "method": req.method,
            "time_law": law.name(),
            "dynamics": args.dynamics,
            "dt": dt,
            "duration": traj.time_span().1 - traj.time_span().0,
            "waypoint_times": times,
            "t": profile.t,
            "poses": samples.iter().map(|s| s.pose.coordinates(motion)).collect::<Vec<_>>(),
            "velocity": samples.iter().map(|s| TimedSample::components(motion, &s.twist)).collect::<Vec<_>>(),
            "acceleration": samples.iter().map(|s| TimedSample::components(motion, &s.twist_rate)).collect::<Vec<_>>(),
            "cable_lengths": rows(&profile.cable_lengths, n),
            "cable_speeds": rows(&profile.cable_speeds, n),
            "cable_accelerations": rows(&profile.cable_accelerations, n),
            "tensions": profile.tensions.iter().map(|t| t.as_ref().map(|t| t.as_slice().to_vec())).collect::<Vec<_>>(),
            "reasons": profile.reasons,
            "feasible_count": profile.feasible_count(),
            "t_min": robot.bounds.min().as_slice(),
            "t_max": robot.bounds.max().as_slice(),
        });
        if args.dynamics {
            out["inertial_wrench"] = json!(rows(&profile.inertial_wrench, dof));
        }
        if let (Some(d), Some(w)) = (&drive, &robot.winches) {
            let nullable = |flat: &[f64]| -> Vec<Option<Vec<f64>>> {
                flat.chunks(n)
                    .map(|c| c.iter().all(|v| v.is_finite()).then(|| c.to_vec()))
                    .collect()
            };
            let finite = |v: &[f64]| -> Vec<Option<f64>> {
                v.iter().map(|x| x.is_finite().then_some(*x)).collect()
            };
            out["motor_speeds"] = json!(rows(&d.motor_speeds, n));
            out["motor_torques"] = json!(nullable(&d.motor_torques));
            out["motor_powers"] = json!(nullable(&d.motor_powers));
            out["motor_peak_speed"] = json!(d.peak_speed);
            out["motor_rms_speed"] = json!(d.rms_speed);
            out["motor_peak_torque"] = json!(d.peak_torque);
            out["motor_rms_torque"] = json!(d.rms_torque);
            out["motor_peak_power"] = json!(finite(&d.peak_power));
            out["peak_total_power"] =
                json!(d.peak_total_power.is_finite().then_some(d.peak_total_power));
            out["motor_max_torque"] = json!(w.iter().map(|w| w.max_torque).collect::<Vec<_>>());
            out["motor_max_speed"] = json!(w.iter().map(|w| w.max_speed).collect::<Vec<_>>());
            out["motors_within_limits"] = json!(d.within_limits);
            out["motor_limit_violations"] = json!(d.violations);
        }
        super::print_json(&out)
    } else {
        print_table(robot, law, req.method, args.dynamics, &profile);
        if let Some(d) = &drive {
            print_drive_train(d);
        }
        Ok(())
    }
}

/// Peaks, RMS values and the verdict of the drive train.
fn print_drive_train(d: &DriveTrainProfile) {
    let cells = |v: &[f64]| -> String {
        v.iter()
            .map(|x| format!("{x:>10.4}"))
            .collect::<Vec<_>>()
            .join(" ")
    };
    println!("drive train (motor i winds cable i in for ω, τ > 0)");
    println!("{:>9}  {}  (rad/s)", "peak |ω|", cells(&d.peak_speed));
    println!("{:>9}  {}  (rad/s)", "RMS ω", cells(&d.rms_speed));
    println!("{:>9}  {}  (N·m)", "peak |τ|", cells(&d.peak_torque));
    let rms: Vec<f64> = d.rms_torque.iter().map(|v| v.unwrap_or(f64::NAN)).collect();
    println!("{:>9}  {}  (N·m)", "RMS τ", cells(&rms));
    println!("{:>9}  {}  (W)", "peak P", cells(&d.peak_power));
    println!("peak total power Σ τ ω: {:.4} W", d.peak_total_power);
    match d.within_limits {
        Some(true) => println!("the motors can do it: every torque and speed within its limits"),
        Some(false) => {
            println!("the motors cannot do it:");
            for v in &d.violations {
                println!("  {v}");
            }
        }
        None => println!(
            "limits not checked (no max_torque/max_speed given, or infeasible samples leave the torque unknown)"
        ),
    }
}

fn print_table(
    robot: &cdpr::RobotDescription,
    law: TimeLaw,
    method: &str,
    dynamics: bool,
    profile: &DynamicsProfile,
) {
    let n = robot.robot.cable_count();
    println!(
        "robot {}, time law {law}, method {method}, {}, {} samples, {} feasible",
        robot.name,
        if dynamics {
            "inverse dynamics (W t + w = M ẍ + b)"
        } else {
            "quasi-static (no inertia)"
        },
        profile.t.len(),
        profile.feasible_count()
    );
    let head: Vec<String> = (1..=n)
        .map(|i| format!("{:>10}", format!("t{i}")))
        .collect();
    println!("cable tensions t_i in N against time t in s");
    println!("{:>9}  {}", "t (s)", head.join(" "));
    let every = profile.t.len().div_ceil(40).max(1);
    for (k, (t, ts)) in profile.t.iter().zip(&profile.tensions).enumerate() {
        match ts {
            Some(v) if k % every == 0 || k + 1 == profile.t.len() => {
                let cells: Vec<String> = v.iter().map(|x| format!("{x:>10.4}")).collect();
                println!("{t:>9.4}  {}", cells.join(" "));
            }
            Some(_) => {}
            None => println!(
                "{t:>9.4}  infeasible: {}",
                profile.reasons[k].as_deref().unwrap_or("")
            ),
        }
    }
    let peak = |flat: &[f64]| -> Vec<String> {
        (0..n)
            .map(|i| {
                let m = flat
                    .iter()
                    .skip(i)
                    .step_by(n)
                    .filter(|v| v.is_finite())
                    .fold(0.0f64, |a, &v| a.max(v.abs()));
                format!("{m:>10.4}")
            })
            .collect()
    };
    println!(
        "{:>9}  {}  (m/s)",
        "peak |l̇|",
        peak(&profile.cable_speeds).join(" ")
    );
    println!(
        "{:>9}  {}  (m/s²)",
        "peak |l̈|",
        peak(&profile.cable_accelerations).join(" ")
    );
}

/// Tensions against time, one line per cable, dashed t_min / t_max, gaps where infeasible.
fn tension_plot(
    robot: &cdpr::RobotDescription,
    law: TimeLaw,
    method: &str,
    dynamics: bool,
    profile: &DynamicsProfile,
) -> LinePlot {
    let n = robot.robot.cable_count();
    let series = (0..n)
        .map(|i| Series {
            label: format!("t{}", i + 1),
            points: profile
                .t
                .iter()
                .zip(&profile.tensions)
                .map(|(&t, ts)| (t, ts.as_ref().map_or(f64::NAN, |v| v[i])))
                .collect(),
        })
        .collect();
    let mut reference_lines = Vec::new();
    let (lo, hi) = (robot.bounds.min(), robot.bounds.max());
    if lo.iter().all(|&v| v == lo[0]) {
        reference_lines.push((lo[0], format!("t_min = {} N", cdpr::plot::tick(lo[0]))));
    }
    if hi.iter().all(|&v| v == hi[0]) && hi[0].is_finite() {
        reference_lines.push((hi[0], format!("t_max = {} N", cdpr::plot::tick(hi[0]))));
    }
    LinePlot {
        title: format!(
            "{}: tensions against time ({law} law, {method}, {}; {} of {} samples feasible)",
            robot.name,
            if dynamics {
                "inverse dynamics"
            } else {
                "quasi-static"
            },
            profile.feasible_count(),
            profile.t.len()
        ),
        labels: ("time t (s)".into(), "cable tension (N)".into()),
        series,
        reference_lines,
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

/// Motor torques against time, one line per motor, dashed ±max_torque, gaps where infeasible.
fn motor_torque_plot(
    robot: &cdpr::RobotDescription,
    law: TimeLaw,
    profile: &DynamicsProfile,
    d: &DriveTrainProfile,
) -> LinePlot {
    let n = d.motors;
    let series = (0..n)
        .map(|i| Series {
            label: format!("motor {}", i + 1),
            points: profile
                .t
                .iter()
                .enumerate()
                .map(|(k, &t)| (t, d.motor_torques[k * n + i]))
                .collect(),
        })
        .collect();
    let limits: Vec<Option<f64>> = robot
        .winches
        .iter()
        .flatten()
        .map(|w| w.max_torque)
        .collect();
    LinePlot {
        title: format!(
            "{}: motor torques against time ({law} law; τ = (r/G) t − J_m (G/r) d²l/dt², > 0 winds in)",
            robot.name
        ),
        labels: ("time t (s)".into(), "motor torque τ (N·m)".into()),
        series,
        reference_lines: limit_lines(&limits, "max", "N·m"),
        gap_label: Some("infeasible samples".into()),
    }
}

/// Cable speeds l̇ against time, one line per cable; with winches of one max_speed, dashed ±
/// the cable speed it allows (r/G · max_speed).
fn cable_speed_plot(
    robot: &cdpr::RobotDescription,
    law: TimeLaw,
    profile: &DynamicsProfile,
) -> LinePlot {
    let n = profile.cables;
    let series = (0..n)
        .map(|i| Series {
            label: format!("cable {}", i + 1),
            points: profile
                .t
                .iter()
                .enumerate()
                .map(|(k, &t)| (t, profile.cable_speeds[k * n + i]))
                .collect(),
        })
        .collect();
    let limits: Vec<Option<f64>> = robot
        .winches
        .iter()
        .flatten()
        .map(|w| w.max_speed.map(|s| s * w.drum_radius / w.gear_ratio))
        .collect();
    LinePlot {
        title: format!(
            "{}: cable speeds against time ({law} law; dl/dt = −Wᵀ dx/dt, > 0 pays out)",
            robot.name
        ),
        labels: ("time t (s)".into(), "cable speed dl/dt (m/s)".into()),
        series,
        reference_lines: limit_lines(&limits, "max", "m/s"),
        gap_label: None,
    }
}

/// The replay page's data: anchors, attachments, poses and tensions at every sample.
fn replay(
    robot: &cdpr::RobotDescription,
    law: TimeLaw,
    method: &str,
    samples: &[TimedSample],
    profile: &DynamicsProfile,
) -> cdpr::plot::Replay {
    let triple = |v: &nalgebra::Vector3<f64>| [v.x, v.y, v.z];
    let cables = robot.robot.cables();
    let (lo, hi) = (robot.bounds.min(), robot.bounds.max());
    let t_min = lo.iter().cloned().fold(f64::INFINITY, f64::min);
    // The colour scale ends at the largest tension met (the largest finite bound if none is).
    let met = profile
        .tensions
        .iter()
        .flatten()
        .flat_map(|t| t.iter().cloned())
        .fold(f64::NEG_INFINITY, f64::max);
    let bound = hi
        .iter()
        .cloned()
        .filter(|v| v.is_finite())
        .fold(t_min, f64::max);
    let t_max = if met.is_finite() { met } else { bound };
    cdpr::plot::Replay {
        title: format!(
            "{}: {law} trajectory, {method} tensions, {:.3} s",
            robot.name,
            profile.t.last().copied().unwrap_or(0.0)
        ),
        anchors: cables.iter().map(|c| triple(&c.frame)).collect(),
        attachments: cables.iter().map(|c| triple(&c.platform)).collect(),
        t: profile.t.clone(),
        positions: samples.iter().map(|s| triple(&s.pose.position)).collect(),
        rotations: samples
            .iter()
            .map(|s| {
                let m = s.pose.rotation.matrix();
                [0, 1, 2].map(|r| [m[(r, 0)], m[(r, 1)], m[(r, 2)]])
            })
            .collect(),
        tensions: profile
            .tensions
            .iter()
            .map(|t| t.as_ref().map(|t| t.as_slice().to_vec()))
            .collect(),
        reasons: profile.reasons.clone(),
        t_min,
        t_max,
        planar: robot.robot.motion().space_dim() == 2,
    }
}
