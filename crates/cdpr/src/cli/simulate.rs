//! `cdpr simulate`: forward dynamics of the platform (issue 28).

use super::{CliError, Numbers, print_report, request_robot};
use cdpr::api::simulate::{IntegratorName, SimulateRequest, TensionProfile};
use cdpr::plot::{LinePlot, Series};
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

/// Runs the command: the request, its report, rendered as JSON or a table (and the plot).
pub fn run(args: Args) -> Result<(), CliError> {
    let request = SimulateRequest {
        robot: request_robot(&args.robot)?,
        from: args.from.0,
        velocity: args.velocity.map(|v| v.0),
        duration: args.duration,
        dt: args.dt,
        tensions: args.tensions.map(|t| t.0),
        tension_profile: args
            .tension_profile
            .as_deref()
            .map(tension_profile)
            .transpose()?,
        unstrained_lengths: args.unstrained_lengths.map(|l| l.0),
        damping: args.damping,
        integrator: match args.integrator {
            IntegratorArg::Rk4 => IntegratorName::Rk4,
            IntegratorArg::Rk45 => IntegratorName::Rk45,
        },
        tolerance: args.tolerance,
        wrench: args.wrench.map(|w| w.0),
    };
    let r = request.run()?;
    if let Some(file) = &args.plot {
        cdpr::plot::save(&pose_plot(&request.robot, &r.t, &r.poses), file)?;
    }
    if args.json {
        return print_report(&r);
    }
    println!(
        "robot {}, {} steps ({}), {} s",
        r.robot,
        r.steps,
        match request.integrator {
            IntegratorName::Rk4 => "RK4".to_string(),
            IntegratorName::Rk45 => format!("RK45, {} rejected", r.rejected_steps),
        },
        args.duration
    );
    println!("pose coordinates (m, rad) against time t (s)");
    let every = r.t.len().div_ceil(20).max(1);
    for (k, (t, q)) in r.t.iter().zip(&r.poses).enumerate() {
        if k % every == 0 || k + 1 == r.t.len() {
            let cells: Vec<String> = q.iter().map(|v| format!("{v:>10.5}")).collect();
            println!("{t:>9.4}  {}", cells.join(" "));
        }
    }
    Ok(())
}

/// `t` and `tensions` of a trajectory JSON.
fn tension_profile(file: &std::path::Path) -> Result<TensionProfile, CliError> {
    let text = std::fs::read_to_string(file)
        .map_err(|e| format!("{}: cannot read: {e}", file.display()))?;
    let v: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", file.display()))?;
    let t: Vec<f64> = serde_json::from_value(v["t"].clone()).map_err(|e| {
        format!(
            "{}: `t` must be an array of times in s: {e}",
            file.display()
        )
    })?;
    let tensions: Vec<Option<Vec<f64>>> =
        serde_json::from_value(v["tensions"].clone()).map_err(|e| {
            format!(
                "{}: `tensions` must be an array of arrays of N: {e}",
                file.display()
            )
        })?;
    Ok(TensionProfile {
        t,
        tensions,
        file: Some(file.display().to_string()),
    })
}

fn pose_plot(robot: &cdpr::api::Robot, t: &[f64], poses: &[Vec<f64>]) -> LinePlot {
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
