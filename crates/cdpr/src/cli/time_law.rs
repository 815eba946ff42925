//! `cdpr trajectory … --time-law LAW`: timed trajectories and their inverse dynamics (issue 28).
//!
//! The path of `cdpr trajectory` (segment or waypoints) run with a time law of
//! `cdpr_dynamics::time_law`, sampled every --dt s. At every sample the tensions balance
//! w_e + w_g (+ passive springs), and with --dynamics also the inertial wrench: W t + w_e + w_g =
//! M ẍ + b (`cdpr_dynamics::inverse_dynamics`). JSON adds `t` (s), `velocity`, `acceleration`
//! (DOF numbers per sample: the twist [v (m/s); ω (rad/s)] and its rate), `cable_lengths` (m),
//! `cable_speeds` (l̇ = −Wᵀẋ, m/s), `cable_accelerations` (m/s²) and, with --dynamics,
//! `inertial_wrench` (M ẍ + b, N and N·m).

use super::CliError;
use cdpr::dynamics::{
    DynamicsProfile, RigidBody, TimeLaw, TimedSample, TimingSettings, Trajectory, inverse_dynamics,
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

/// The platform's rigid body from the robot file (usage error if the file lacks what the
/// motion pattern needs, or if the inertia is not symmetric positive definite).
pub fn rigid_body(robot: &cdpr::RobotDescription) -> Result<RigidBody, CliError> {
    let p = &robot.platform;
    if !(p.mass.is_finite() && p.mass > 0.0) {
        return Err(format!(
            "[platform] mass = {} kg: dynamics needs a finite positive platform mass",
            p.mass
        )
        .into());
    }
    if robot.robot.motion().has_orientation() {
        let inertia = robot.inertia.ok_or(
            "dynamics of a planar or spatial platform needs `[platform] inertia` (kg·m², about the centre of mass)",
        )?;
        RigidBody::new(p, inertia).map_err(|e| format!("[platform] inertia: {e}").into())
    } else {
        Ok(RigidBody::point_mass(p)?)
    }
}

/// Runs the timed trajectory.
pub fn run(args: &TimingArgs, req: TimedRequest) -> Result<(), CliError> {
    let law = args.time_law.expect("timed mode");
    if req.times.is_some() && args.duration.is_some() {
        return Err("give either --duration or a `time` on every waypoint, not both".into());
    }
    let robot = req.robot;
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
    if let Some(file) = req.plot {
        cdpr::plot::save(
            &tension_plot(robot, law, req.method, args.dynamics, &profile),
            file,
        )?;
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
        super::print_json(&out)
    } else {
        print_table(robot, law, req.method, args.dynamics, &profile);
        Ok(())
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
