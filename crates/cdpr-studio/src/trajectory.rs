//! # A path or timed trajectory
//!
//! The segment from one pose to another through cdpr-api's trajectory request, the request
//! `cdpr trajectory --from … --to … --json` runs: without a time law, the tensions at samples of
//! the path parameter s ∈ [0, 1] (∝ the pose distance); with one (`linear`, `cubic`, `quintic`,
//! `trapezoid`, `parabolic-blend`) the timed trajectory every `dt` s, with the inertial wrench
//! balanced when `dynamics` is set, and the motors' speeds and torques when every cable has a
//! `winch` in the robot file. The report is the CLI's JSON.
//!
//! ## References
//! - Thesis Fig. 6.6 (minimum-norm tensions jump along a path); the time laws and the drive
//!   train are documented with `cdpr trajectory` (docs/algorithms.md).

use crate::state::parse_method;
use crate::{Studio, StudioError};
use cdpr_api::Robot;
use cdpr_api::timed::TimedSettings;
use cdpr_api::trajectory::{TrajectoryReport, TrajectoryRequest};
use serde::Deserialize;

/// What the page asks for: the segment, the sampling, the method and load, the time law.
#[derive(Debug, Clone, Deserialize)]
pub struct PathSettings {
    /// The start pose (motion-pattern coordinates: m, rad).
    pub from: Vec<f64>,
    /// The end pose.
    pub to: Vec<f64>,
    /// Samples of an untimed path (default 101).
    #[serde(default)]
    pub samples: Option<usize>,
    /// Tension method (command-line name).
    pub method: String,
    /// External wrench w_e (N, N·m; the robot file's load is added).
    #[serde(default)]
    pub wrench: Option<Vec<f64>>,
    /// The time law and its settings (`time_law`, `duration`, `dt`, `dynamics`, …; none: the
    /// untimed path).
    #[serde(default, flatten)]
    pub timing: TimedSettings,
}

impl Studio {
    /// The path or trajectory of `s` (the JSON of `cdpr trajectory --json`).
    pub fn trajectory(&self, s: &PathSettings) -> Result<TrajectoryReport, StudioError> {
        let robot = Robot::from_description(self.desc.clone());
        let mut request = TrajectoryRequest::segment(robot, s.from.clone(), s.to.clone());
        request.method = parse_method(&s.method)?;
        request.samples = s.samples;
        request.wrench = s.wrench.clone();
        request.timing = s.timing.clone();
        Ok(request.run()?)
    }
}

#[cfg(test)]
mod tests {
    use super::PathSettings;
    use crate::test_support::open;
    use cdpr_api::trajectory::TrajectoryReport;

    fn settings(json: &str) -> PathSettings {
        serde_json::from_str(json).unwrap()
    }

    /// Along an untimed segment the samples are the straight line's poses and each sample's
    /// tensions are the page's state at that pose (the same method and load).
    #[test]
    fn path_samples_are_the_states_on_the_segment() {
        let s = open("tdpm-4.toml");
        let p = settings(
            r#"{"from": [-0.2, 0.0, 0.0], "to": [0.2, 0.1, 0.1], "samples": 5, "method": "l2"}"#,
        );
        let TrajectoryReport::Path(r) = s.trajectory(&p).unwrap() else {
            panic!("an untimed path")
        };
        assert_eq!(r.poses.len(), 5);
        for (k, q) in r.poses.iter().enumerate() {
            let f = k as f64 / 4.0;
            let expect = [-0.2 + 0.4 * f, 0.1 * f, 0.1 * f];
            assert!(
                q.iter().zip(expect).all(|(a, b)| (a - b).abs() < 1e-12),
                "{q:?}"
            );
            assert!((r.s[k] - f).abs() < 1e-12);
            let st = s.state(q, "l2", None).unwrap();
            let (a, b) = (r.tensions[k].as_ref().unwrap(), st.tensions.unwrap());
            // The same problem, solved by the trajectory's solver (to rounding).
            assert!(
                a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-9),
                "{k}: {a:?} {b:?}"
            );
        }
    }

    /// A quintic rest-to-rest trajectory of T = 2 s of a 1 kg point hung from four winches
    /// (drum radius r = 0.1 m, gear ratio G = 3): at t = 0 it is at rest with no acceleration
    /// (quintic), so the motors stand still and each torque is (r/G) t = t/30 N·m.
    #[test]
    fn timed_trajectory_with_winches_has_motor_torques() {
        let winch = "winch = { drum_radius = 0.1, gear_ratio = 3.0, motor_inertia = 0.001 }";
        let cables: String = [(1, 1), (-1, 1), (-1, -1), (1, -1)]
            .iter()
            .map(|(x, y)| format!("[[cables]]\nframe = [{x}.0, {y}.0, 2.0]\n{winch}\n"))
            .collect();
        let text = format!(
            "name = \"hung\"\nmotion = \"point3\"\n[tension]\nmin = 1.0\nmax = 1000.0\n\
             [platform]\nmass = 1.0\n{cables}"
        );
        let s = crate::Studio::open(&[crate::RobotFileText {
            name: "hung.toml".into(),
            text,
        }])
        .unwrap();
        let text = r#"{"from": [0, 0, 1], "to": [0.2, 0.1, 1.2], "method": "l2", "time_law": "quintic", "duration": 2.0, "dt": 0.1, "dynamics": true}"#;
        let TrajectoryReport::Timed(r) = s.trajectory(&settings(text)).unwrap() else {
            panic!("a timed trajectory")
        };
        assert_eq!(r.t.len(), 21);
        assert!((r.t[20] - 2.0).abs() < 1e-12);
        let d = r.drive_train.as_ref().expect("the robot has winches");
        let t0 = r.tensions[0].as_ref().expect("feasible at the start");
        let tau0 = d.motor_torques[0].as_ref().unwrap();
        assert!(d.motor_speeds[0].iter().all(|w| w.abs() < 1e-12));
        for (tau, t) in tau0.iter().zip(t0) {
            assert!(
                (tau - t / 30.0).abs() < 1e-9 * (1.0 + t.abs()),
                "{tau} vs {t}/30"
            );
        }
        let bad = r#"{"from": [0, 0, 0, 0, 0, 0], "to": [0.1, 0, 0, 0, 0, 0], "method": "l2", "time_law": "warp"}"#;
        assert!(serde_json::from_str::<super::PathSettings>(bad).is_err());
    }
}
