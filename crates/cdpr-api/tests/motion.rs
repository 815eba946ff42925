//! Timed trajectories (inverse dynamics) and forward dynamics through their requests, against
//! hand-derived values; their validation messages and JSON round trips.

use cdpr_api::simulate::{SimulateRequest, TensionProfile};
use cdpr_api::timed::{CasprTrajectorySource, TimedSettings};
use cdpr_api::trajectory::{TrajectoryReport, TrajectoryRequest, Waypoint};
use cdpr_api::{Robot, RobotSource};

const G: f64 = 9.80665;

/// A 2 kg point under two cables from (0, 2) and (2, 2), tensions in [0, 10 000] N.
const HANG: &str = r#"
name = "hang"
motion = "point2"

[tension]
min = 0.0
max = 10000.0

[platform]
mass = 2.0

[[cables]]
frame = [0.0, 2.0]
[[cables]]
frame = [2.0, 2.0]
"#;

/// A 3 kg point in space under four cables from above.
const FALL: &str = r#"
name = "fall"
motion = "point3"

[tension]
min = 0.0
max = 1000.0

[platform]
mass = 3.0

[[cables]]
frame = [1.0, 1.0, 3.0]
[[cables]]
frame = [-1.0, 1.0, 3.0]
[[cables]]
frame = [-1.0, -1.0, 3.0]
[[cables]]
frame = [1.0, -1.0, 3.0]
"#;

fn robot(text: &str) -> Robot {
    Robot::from_source(RobotSource::toml(text)).unwrap()
}

fn timed(law: &str, duration: f64, dt: f64, dynamics: bool) -> TimedSettings {
    TimedSettings {
        time_law: Some(law.parse().unwrap()),
        duration: Some(duration),
        dt: Some(dt),
        dynamics,
        ..TimedSettings::default()
    }
}

/// A quintic lift from (1, 0) to (1, 1) in 2 s: at each sample ÿ = 60τ(1 − 3τ + 2τ²)/T²
/// (Δ = 1 m); both cables carry t = m (g + ÿ) ℓ / (2 (h − y)) with ℓ = √(1 + (h − y)²), the
/// inertial wrench is (0, m ÿ), and l̇ = −(h − y)/ℓ · ẏ.
#[test]
fn a_quintic_lift_balances_weight_and_inertia() {
    let mut r = TrajectoryRequest::segment(robot(HANG), vec![1.0, 0.0], vec![1.0, 1.0]);
    r.timing = timed("quintic", 2.0, 0.1, true);
    let TrajectoryReport::Timed(v) = r.run().unwrap() else {
        panic!("a timed report")
    };
    assert_eq!(v.t.len(), 21);
    assert_eq!(v.feasible_count, 21);
    for k in 0..v.t.len() {
        let tau = v.t[k] / 2.0;
        let y = 10.0 * tau.powi(3) - 15.0 * tau.powi(4) + 6.0 * tau.powi(5);
        let y_dot = 30.0 * tau * tau * (1.0 - tau).powi(2) / 2.0;
        let y_dd = 60.0 * tau * (1.0 - 3.0 * tau + 2.0 * tau * tau) / 4.0;
        let rise = 2.0 - y;
        let l = (1.0 + rise * rise).sqrt();
        let t = 2.0 * (G + y_dd) * l / (2.0 * rise);
        let tensions = v.tensions[k].as_ref().unwrap();
        for ti in tensions {
            assert!((ti - t).abs() < 1e-9 * t, "t = {}: {ti} vs {t}", v.t[k]);
        }
        let w = &v.inertial_wrench.as_ref().unwrap()[k];
        assert!(w[0].abs() < 1e-12 && (w[1] - 2.0 * y_dd).abs() < 1e-9);
        for (i, l_dot) in v.cable_speeds[k].iter().enumerate() {
            assert!((l_dot + rise / l * y_dot).abs() < 1e-12, "cable {i}");
        }
        assert!((v.cable_lengths[k][0] - l).abs() < 1e-12);
    }
    assert!(v.drive_train.is_none());
}

/// Without `dynamics` the same lift is quasi-static: t = m g ℓ / (2 (h − y)), no inertial
/// wrench in the report.
#[test]
fn a_quasi_static_lift_balances_the_weight_only() {
    let mut r = TrajectoryRequest::segment(robot(HANG), vec![1.0, 0.0], vec![1.0, 1.0]);
    r.timing = timed("cubic", 1.0, 0.25, false);
    let TrajectoryReport::Timed(v) = r.run().unwrap() else {
        panic!("a timed report")
    };
    assert!(v.inertial_wrench.is_none());
    let json = serde_json::to_value(&*v).unwrap();
    assert!(json.get("inertial_wrench").is_none());
    for (k, q) in v.poses.iter().enumerate() {
        let rise = 2.0 - q[1];
        let t = 2.0 * G * (1.0 + rise * rise).sqrt() / (2.0 * rise);
        assert!((v.tensions[k].as_ref().unwrap()[0] - t).abs() < 1e-9 * t);
    }
}

/// The untimed path: s at the samples and the same static tensions.
#[test]
fn an_untimed_path_reports_s() {
    let mut r = TrajectoryRequest::segment(robot(HANG), vec![1.0, 0.0], vec![1.0, 1.0]);
    r.samples = Some(5);
    let TrajectoryReport::Path(p) = r.run().unwrap() else {
        panic!("a path report")
    };
    assert_eq!(p.s, [0.0, 0.25, 0.5, 0.75, 1.0]);
    let rise: f64 = 2.0 - 0.5;
    let t = 2.0 * G * (1.0 + rise * rise).sqrt() / (2.0 * rise);
    assert!((p.tensions[2].as_ref().unwrap()[1] - t).abs() < 1e-9 * t);
    assert!(p.cable_model.is_none());
}

fn error(r: &TrajectoryRequest) -> String {
    r.validate().unwrap_err().to_string()
}

#[test]
fn trajectory_requests_refuse_bad_input() {
    let base = TrajectoryRequest::segment(robot(HANG), vec![1.0, 0.0], vec![1.0, 1.0]);
    let mut r = base.clone();
    r.timing.dt = Some(0.1);
    assert_eq!(error(&r), "--dt needs --time-law (a timed trajectory)");
    let mut r = base.clone();
    r.timing = timed("quintic", 1.0, 0.1, false);
    r.samples = Some(3);
    assert!(error(&r).contains("leave --samples and --step out"));
    let mut r = base.clone();
    r.timing = timed("quintic", -1.0, 0.1, false);
    assert!(error(&r).contains("duration"), "{}", error(&r));
    let mut r = base.clone();
    r.timing = timed("quintic", 1.0, 0.1, false);
    r.waypoints = Some(vec![
        Waypoint {
            pose: vec![1.0, 0.0],
            wrench: None,
            time: Some(0.0),
        },
        Waypoint {
            pose: vec![1.0, 1.0],
            wrench: None,
            time: Some(1.0),
        },
    ]);
    assert_eq!(
        error(&r),
        "give the path as --from/--to or as --waypoints, not both"
    );
    r.from = None;
    r.to = None;
    assert_eq!(
        error(&r),
        "give either --duration or a `time` on every waypoint, not both"
    );
    r.timing.duration = None;
    assert!(r.validate().is_ok());
    r.waypoints.as_mut().unwrap()[1].time = None;
    r.waypoints_file = Some("w.toml".into());
    assert_eq!(
        error(&r),
        "w.toml: waypoints[1] has no `time` (give every waypoint a time, or none)"
    );
    let mut r = base.clone();
    r.options.nu = Some(0.5);
    assert!(error(&r).starts_with("--nu is an option of the sotda method only"));
}

#[test]
fn a_trajectory_request_survives_a_json_round_trip() {
    let mut r = TrajectoryRequest::segment(robot(HANG), vec![1.0, 0.0], vec![1.0, 1.0]);
    r.timing = timed("trapezoid", 2.0, 0.1, true);
    r.timing.max_acceleration = Some(2.0);
    let text = serde_json::to_string(&r).unwrap();
    let back: TrajectoryRequest = serde_json::from_str(&text).unwrap();
    assert_eq!(
        serde_json::to_value(back.run().unwrap()).unwrap(),
        serde_json::to_value(r.run().unwrap()).unwrap()
    );
    assert!(text.contains(r#""time_law":"trapezoid""#), "{text}");
}

/// Zero tensions: free fall, z = z₀ − g t²/2, which RK4 integrates exactly (to round-off).
#[test]
fn zero_tensions_fall_freely() {
    let r =
        SimulateRequest::with_tensions(robot(FALL), vec![0.0, 0.0, 1.0], vec![0.0; 4], 0.5, 0.01);
    let v = r.run().unwrap();
    assert_eq!(v.t.len(), 51);
    for (k, t) in v.t.iter().enumerate() {
        let z = 1.0 - G * t * t / 2.0;
        assert!((v.poses[k][2] - z).abs() < 1e-12, "t = {t}");
        assert!((v.velocities[k][2] + G * t).abs() < 1e-12);
        assert!((v.accelerations[k][2] + G).abs() < 1e-12);
        assert_eq!(v.tensions[k], [0.0; 4]);
    }
    assert_eq!((v.integrator.as_str(), v.rejected_steps), ("rk4", 0));
}

/// A tension profile that holds four equal tensions t balancing the weight: the platform at
/// (0, 0, 1) stays at rest.
#[test]
fn a_balancing_profile_holds_the_platform() {
    // At (0, 0, 1) each unit vector is (±1, ±1, 2)/√6: the vertical sum is 4 · 2t/√6 = m g.
    let t = 3.0 * G * 6f64.sqrt() / 8.0;
    let mut r = SimulateRequest::with_tensions(robot(FALL), vec![0.0, 0.0, 1.0], vec![], 0.2, 0.05);
    r.tensions = None;
    r.tension_profile = Some(TensionProfile {
        t: vec![0.0, 1.0],
        tensions: vec![Some(vec![t; 4]), Some(vec![t; 4])],
        file: None,
    });
    let v = r.run().unwrap();
    for q in &v.poses {
        assert!(
            (q[0].abs() + q[1].abs() + (q[2] - 1.0).abs()) < 1e-12,
            "{q:?}"
        );
    }
}

#[test]
fn simulate_requests_refuse_bad_input() {
    let base =
        SimulateRequest::with_tensions(robot(FALL), vec![0.0, 0.0, 1.0], vec![0.0; 4], 0.5, 0.01);
    let message = |r: &SimulateRequest| r.validate().unwrap_err().to_string();
    let mut r = base.clone();
    r.unstrained_lengths = Some(vec![1.0; 4]);
    assert_eq!(
        message(&r),
        "give one drive: --tensions, --tension-profile or --unstrained-lengths"
    );
    r.tensions = None;
    assert!(message(&r).starts_with("--unstrained-lengths needs `axial_stiffness`"));
    let mut r = base.clone();
    r.damping = 2.0;
    assert_eq!(message(&r), "--damping needs --unstrained-lengths");
    let mut r = base.clone();
    r.dt = 0.0;
    assert_eq!(message(&r), "--dt = 0: must be a finite number > 0");
    let mut r = base.clone();
    r.velocity = Some(vec![1.0]);
    assert_eq!(
        message(&r),
        "--velocity: 1 numbers for a point3 platform, expected 3"
    );
    let mut r = base.clone();
    r.tensions = None;
    r.tension_profile = Some(TensionProfile {
        t: vec![0.0, 1.0],
        tensions: vec![Some(vec![0.0; 4]), None],
        file: Some("p.json".into()),
    });
    assert_eq!(
        message(&r),
        "p.json: tensions[1] is null (an infeasible sample): no tension to apply"
    );
    let text = serde_json::to_string(&base).unwrap();
    let back: SimulateRequest = serde_json::from_str(&text).unwrap();
    assert_eq!(back.run().unwrap(), base.run().unwrap());
}

/// Two CASPR trajectories for the hanging point: the quintic lift of
/// `a_quintic_lift_balances_weight_and_inertia` and a linear move.
const LIFT_XML: &str = r#"<?xml version="1.0" encoding="utf-8"?>
<trajectories>
  <joint_trajectories>
    <quintic_spline_trajectory id="lift" time_definition="relative" time_step="0.1">
      <points>
        <point><q>1 0</q><q_dot>0 0</q_dot><q_ddot>0 0</q_ddot></point>
        <point time="2.0"><q>1 1</q><q_dot>0 0</q_dot><q_ddot>0 0</q_ddot></point>
      </points>
    </quintic_spline_trajectory>
    <linear_spline_trajectory id="slide" time_definition="absolute" time_step="0.5">
      <points>
        <point><q>0.5 0.5</q></point>
        <point time="1.0"><q>1.5 0.5</q></point>
      </points>
    </linear_spline_trajectory>
  </joint_trajectories>
</trajectories>"#;

fn caspr(id: Option<&str>) -> TrajectoryRequest {
    let mut r = TrajectoryRequest::segment(robot(HANG), vec![], vec![]);
    r.from = None;
    r.to = None;
    r.caspr_trajectory = Some(CasprTrajectorySource {
        text: LIFT_XML.into(),
        id: id.map(str::to_string),
        file: Some("hang_trajectories.xml".into()),
    });
    r
}

/// A CASPR quintic lift is the time law's quintic lift: the same samples, tensions and
/// inertial wrench (t = m (g + ÿ) ℓ / (2 (h − y)) at each sample), and the report names the
/// trajectory.
#[test]
fn a_caspr_quintic_lift_is_the_quintic_time_law() {
    let mut r = caspr(Some("lift"));
    r.timing.dynamics = true;
    let TrajectoryReport::Timed(v) = r.run().unwrap() else {
        panic!("a timed report")
    };
    assert_eq!(v.time_law, "quintic_spline_trajectory");
    assert_eq!(v.trajectory_id.as_deref(), Some("lift"));
    assert_eq!((v.t.len(), v.dt, v.duration), (21, 0.1, 2.0));
    assert_eq!(v.waypoint_times, [0.0, 2.0]);
    for k in 0..v.t.len() {
        let tau = v.t[k] / 2.0;
        let y = 10.0 * tau.powi(3) - 15.0 * tau.powi(4) + 6.0 * tau.powi(5);
        let y_dd = 60.0 * tau * (1.0 - 3.0 * tau + 2.0 * tau * tau) / 4.0;
        let rise = 2.0 - y;
        let t = 2.0 * (G + y_dd) * (1.0 + rise * rise).sqrt() / (2.0 * rise);
        for ti in v.tensions[k].as_ref().unwrap() {
            assert!((ti - t).abs() < 1e-9 * t, "t = {}: {ti} vs {t}", v.t[k]);
        }
        let w = &v.inertial_wrench.as_ref().unwrap()[k];
        assert!((w[1] - 2.0 * y_dd).abs() < 1e-9);
    }
    let mut law = TrajectoryRequest::segment(robot(HANG), vec![1.0, 0.0], vec![1.0, 1.0]);
    law.timing = timed("quintic", 2.0, 0.1, true);
    let TrajectoryReport::Timed(l) = law.run().unwrap() else {
        panic!("a timed report")
    };
    for k in 0..v.t.len() {
        assert!((l.poses[k][1] - v.poses[k][1]).abs() < 1e-14);
        assert!((l.velocity[k][1] - v.velocity[k][1]).abs() < 1e-13);
    }
    // The request survives a JSON round trip.
    let text = serde_json::to_string(&r).unwrap();
    let back: TrajectoryRequest = serde_json::from_str(&text).unwrap();
    assert_eq!(
        serde_json::to_value(back.run().unwrap()).unwrap(),
        serde_json::to_value(TrajectoryReport::Timed(v)).unwrap()
    );
}

#[test]
fn caspr_trajectory_requests_refuse_bad_input() {
    let e = error(&caspr(None));
    assert_eq!(
        e,
        "hang_trajectories.xml: give --trajectory-id (the file has 2 joint trajectories: lift, slide)"
    );
    let e = error(&caspr(Some("drop")));
    assert!(
        e.starts_with("hang_trajectories.xml:3: <joint_trajectories>: no joint trajectory with id `drop` (the file has: lift, slide)"),
        "{e}"
    );
    let mut r = caspr(Some("slide"));
    r.timing.time_law = Some("cubic".parse().unwrap());
    assert!(
        error(&r).starts_with("--time-law does not apply to --trajectory"),
        "{}",
        error(&r)
    );
    let mut r = caspr(Some("slide"));
    r.timing.dt = Some(0.1);
    assert!(error(&r).starts_with("--dt does not apply to --trajectory"));
    let mut r = caspr(Some("slide"));
    r.from = Some(vec![1.0, 0.0]);
    r.to = Some(vec![1.0, 1.0]);
    assert!(error(&r).contains("not two of them"));
    let mut r = caspr(Some("slide"));
    r.samples = Some(4);
    assert!(error(&r).contains("leave --samples and --step out"));
    assert!(caspr(Some("slide")).validate().is_ok());
}
