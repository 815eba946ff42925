//! `cdpr simulate`: forward dynamics of the platform (issue 28).

use super::{CliError, Numbers, load_robot, pose};
use cdpr::dynamics::{Drive, Integrator, Simulator, State, TimedSample};
use cdpr::plot::{LinePlot, Series};
use nalgebra::Vector6;
use serde_json::json;
use std::path::PathBuf;

/// Forward dynamics: the motion of the platform from a pose and a twist under given cable
/// tensions, a tension profile, or elastic cables with commanded unstrained lengths.
///
/// Integrates M(x) ẍ + b(x, ẋ) = W t + w_e + w_g (mass, centre of mass and `inertia` from the
/// robot file's `[platform]`) with classical RK4 at the fixed step --dt, or the adaptive
/// Dormand–Prince 5(4) (--integrator rk45, output every --dt). The orientation is a unit
/// quaternion renormalised at every step. A state that stops being finite, or a pose where a
/// cable length vanishes, stops the run with the time it happened (exit 2).
///
/// JSON fields: `t` (s), `poses` (motion-pattern coordinates), `velocities` (twist [v (m/s);
/// ω (rad/s)], DOF numbers), `accelerations` (m/s², rad/s²), `tensions` (N, per cable),
/// `steps`, `rejected_steps`, `integrator`.
#[derive(clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    /// Robot file: .toml, CASPR NAME_cables.xml or WireCenter .wcrfx.
    robot: PathBuf,
    /// Initial pose (motion-pattern coordinates).
    #[arg(long, allow_hyphen_values = true)]
    from: Numbers,
    /// Initial twist: DOF numbers, velocity (m/s) then angular velocity (rad/s, base axes);
    /// default rest.
    #[arg(long, allow_hyphen_values = true)]
    velocity: Option<Numbers>,
    /// Simulated time T (s).
    #[arg(long, value_parser = super::positive)]
    duration: f64,
    /// Output period and (RK4) step (s).
    #[arg(long, value_parser = super::positive)]
    dt: f64,
    /// Cable tensions held constant (N), one per cable.
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["tension_profile", "unstrained_lengths"])]
    tensions: Option<Numbers>,
    /// Tensions against time from the JSON of `cdpr trajectory … --time-law … --json` (its
    /// `t` and `tensions`), interpolated linearly.
    #[arg(long, value_name = "FILE.json", conflicts_with = "unstrained_lengths")]
    tension_profile: Option<PathBuf>,
    /// Elastic cables: the commanded unstrained lengths l₀ (m), one per cable, held constant;
    /// t_i = max(0, E S_i (l_i − l₀ᵢ) / l₀ᵢ + c l̇_i) with `axial_stiffness` E S from the robot
    /// file (a slack cable pulls nothing).
    #[arg(long, allow_hyphen_values = true)]
    unstrained_lengths: Option<Numbers>,
    /// Elastic cables: damping c (N·s/m) on taut cables.
    #[arg(long, default_value_t = 0.0, value_parser = super::non_negative, requires = "unstrained_lengths")]
    damping: f64,
    /// rk4 (fixed step) or rk45 (adaptive Dormand–Prince 5(4)).
    #[arg(long, value_enum, default_value = "rk4")]
    integrator: IntegratorArg,
    /// rk45: local error tolerance per step.
    #[arg(long, default_value_t = 1e-9, value_parser = super::positive)]
    tolerance: f64,
    /// External wrench w_e held constant (DOF numbers, N and N·m; default zero).
    #[arg(long, allow_hyphen_values = true)]
    wrench: Option<Numbers>,
    /// Pose coordinates against time (PNG or SVG).
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Write one JSON object on stdout.
    #[arg(long)]
    json: bool,
}

/// The integrators.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum IntegratorArg {
    /// Classical Runge–Kutta 4, fixed step.
    Rk4,
    /// Dormand–Prince 5(4), adaptive.
    Rk45,
}

/// Runs the command.
pub fn run(args: Args) -> Result<(), CliError> {
    let robot = load_robot(&args.robot)?;
    robot.require_no_passive_springs("simulate")?;
    let motion = robot.robot.motion();
    let n = robot.robot.cable_count();
    let body = super::time_law::rigid_body(&robot)?;
    let start_pose = pose(&robot, &args.from)?;
    let twist = match &args.velocity {
        Some(v) => {
            if v.len() != motion.dof() {
                return Err(format!(
                    "--velocity: {} numbers for a {} platform, expected {}",
                    v.len(),
                    motion.name(),
                    motion.dof()
                )
                .into());
            }
            if let Some(x) = v.iter().find(|x| !x.is_finite()) {
                return Err(format!("--velocity: {x} is not finite").into());
            }
            cdpr::dynamics::rigid_body::embed(motion, v)
        }
        None => Vector6::zeros(),
    };
    let drive = match (
        &args.tensions,
        &args.tension_profile,
        &args.unstrained_lengths,
    ) {
        (Some(t), _, _) => Drive::Tensions(t.0.clone()),
        (None, Some(file), _) => tension_profile(file)?,
        (None, None, Some(l0)) => {
            let es = robot.axial_stiffness.clone().ok_or(
                "--unstrained-lengths needs `axial_stiffness` (E·S, N) on every cable of the robot file",
            )?;
            Drive::Elastic {
                unstrained_lengths: l0.0.clone(),
                axial_stiffness: es,
                damping: vec![args.damping; n],
            }
        }
        (None, None, None) => {
            return Err(
                "give the drive: --tensions T1,…,Tn, --tension-profile FILE.json or --unstrained-lengths L1,…,Ln"
                    .into(),
            );
        }
    };
    let external = super::wrench(&robot, args.wrench.as_deref())?;
    let mut sim = Simulator::new(&robot.robot, body, drive, external.as_slice())?;
    let integrator = match args.integrator {
        IntegratorArg::Rk4 => Integrator::Rk4,
        IntegratorArg::Rk45 => Integrator::Rk45 {
            tolerance: args.tolerance,
        },
    };
    let run = sim.run(
        State::new(&start_pose, twist),
        args.duration,
        args.dt,
        integrator,
    )?;
    let poses: Vec<Vec<f64>> = run
        .states
        .iter()
        .map(|s| s.pose().coordinates(motion))
        .collect();
    if let Some(file) = &args.plot {
        cdpr::plot::save(&pose_plot(&robot, &run.t, &poses), file)?;
    }
    if args.json {
        super::print_json(&json!({
            "robot": robot.name,
            "integrator": match args.integrator { IntegratorArg::Rk4 => "rk4", IntegratorArg::Rk45 => "rk45" },
            "t": run.t,
            "poses": poses,
            "velocities": run.states.iter().map(|s| TimedSample::components(motion, &s.twist)).collect::<Vec<_>>(),
            "accelerations": run.accelerations.iter().map(|a| TimedSample::components(motion, a)).collect::<Vec<_>>(),
            "tensions": run.tensions.chunks(n).map(<[f64]>::to_vec).collect::<Vec<_>>(),
            "steps": run.steps,
            "rejected_steps": run.rejected,
        }))
    } else {
        println!(
            "robot {}, {} steps ({}), {} s",
            robot.name,
            run.steps,
            match args.integrator {
                IntegratorArg::Rk4 => "RK4".to_string(),
                IntegratorArg::Rk45 => format!("RK45, {} rejected", run.rejected),
            },
            args.duration
        );
        println!("pose coordinates (m, rad) against time t (s)");
        let every = run.t.len().div_ceil(20).max(1);
        for (k, (t, q)) in run.t.iter().zip(&poses).enumerate() {
            if k % every == 0 || k + 1 == run.t.len() {
                let cells: Vec<String> = q.iter().map(|v| format!("{v:>10.5}")).collect();
                println!("{t:>9.4}  {}", cells.join(" "));
            }
        }
        Ok(())
    }
}

/// `t` and `tensions` of a trajectory JSON.
fn tension_profile(file: &std::path::Path) -> Result<Drive, CliError> {
    let text = std::fs::read_to_string(file)
        .map_err(|e| format!("{}: cannot read: {e}", file.display()))?;
    let v: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", file.display()))?;
    let times: Vec<f64> = serde_json::from_value(v["t"].clone()).map_err(|e| {
        format!(
            "{}: `t` must be an array of times in s: {e}",
            file.display()
        )
    })?;
    let raw: Vec<Option<Vec<f64>>> =
        serde_json::from_value(v["tensions"].clone()).map_err(|e| {
            format!(
                "{}: `tensions` must be an array of arrays of N: {e}",
                file.display()
            )
        })?;
    let tensions = raw
        .into_iter()
        .enumerate()
        .map(|(k, t)| {
            t.ok_or_else(|| {
                format!(
                    "{}: tensions[{k}] is null (an infeasible sample): no tension to apply",
                    file.display()
                )
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Drive::Profile { times, tensions })
}

fn pose_plot(robot: &cdpr::RobotDescription, t: &[f64], poses: &[Vec<f64>]) -> LinePlot {
    let names: &[&str] = match robot.robot.motion() {
        cdpr::kinematics::MotionPattern::Point2 => &["x (m)", "y (m)"],
        cdpr::kinematics::MotionPattern::Planar => &["x (m)", "y (m)", "φ (rad)"],
        cdpr::kinematics::MotionPattern::Point3 => &["x (m)", "y (m)", "z (m)"],
        cdpr::kinematics::MotionPattern::Spatial => &[
            "x (m)",
            "y (m)",
            "z (m)",
            "r_x (rad)",
            "r_y (rad)",
            "r_z (rad)",
        ],
    };
    LinePlot {
        title: format!("{}: simulated motion (forward dynamics)", robot.name),
        labels: ("time t (s)".into(), "pose coordinate (m or rad)".into()),
        series: names
            .iter()
            .enumerate()
            .map(|(i, name)| Series {
                label: (*name).into(),
                points: t.iter().zip(poses).map(|(&t, q)| (t, q[i])).collect(),
            })
            .collect(),
        reference_lines: Vec::new(),
        gap_label: None,
    }
}
