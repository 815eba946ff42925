//! Issue 27 on the command line: `cdpr calibrate` (CSV in, JSON contract out, bad input exits
//! 2 naming line and column), `cdpr forward` on suspended robots and measured lengths, and the
//! default region of `cdpr workspace` for suspended robots. Issue 25's `forward` messages.

use crate::common;

use cdpr::RobotDescription;
use cdpr::kinematics::nalgebra::Vector3;
use cdpr::kinematics::{Cable, Pose, Robot};
use common::{cdpr, json, robot};

fn tmp(name: &str) -> String {
    let dir = std::env::temp_dir().join(format!("cdpr-calibrate-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name).display().to_string()
}

/// The spidercam as built: anchors moved by a few centimetres.
fn spidercam_as_built() -> (Robot, Robot) {
    let nominal = RobotDescription::load(robot("spidercam-like-4.toml"))
        .unwrap()
        .robot;
    let shifts = [
        [0.03, -0.02, 0.01],
        [-0.01, 0.04, -0.02],
        [0.02, 0.01, 0.03],
        [-0.03, -0.01, 0.0],
    ];
    let cables = nominal
        .cables()
        .iter()
        .zip(shifts)
        .map(|(c, s)| Cable::point3(c.frame + Vector3::from(s)))
        .collect();
    let truth = Robot::new(nominal.motion(), cables).unwrap();
    (nominal, truth)
}

/// k hanging poses over the pitch.
fn hanging_poses(k: usize) -> Vec<Pose> {
    (0..k)
        .map(|j| {
            let t = j as f64;
            Pose::point(
                35.0 * (0.7 * t).sin(),
                25.0 * (1.3 * t + 0.4).cos(),
                12.0 + 8.0 * (0.5 * t).sin(),
            )
        })
        .collect()
}

/// A CSV of readings (true lengths minus `offsets`), with the pose columns when `known`.
fn csv(truth: &Robot, poses: &[Pose], offsets: &[f64], known: bool) -> String {
    let mut s = String::from(if known {
        "x,y,z,l1,l2,l3,l4\n"
    } else {
        "l1,l2,l3,l4\n"
    });
    for p in poses {
        let l: Vec<String> = truth
            .inverse_kinematics(p)
            .unwrap()
            .lengths()
            .zip(offsets)
            .map(|(l, o)| format!("{:.15}", l - o))
            .collect();
        if known {
            let q = p.position;
            s += &format!("{},{},{},", q.x, q.y, q.z);
        }
        s += &l.join(",");
        s.push('\n');
    }
    s
}

#[test]
fn calibrate_known_poses_recovers_the_anchors() {
    let (_, truth) = spidercam_as_built();
    let path = tmp("known.csv");
    let offsets = [0.1, -0.05, 0.02, 0.0];
    std::fs::write(&path, csv(&truth, &hanging_poses(12), &offsets, true)).unwrap();
    let out_robot = tmp("calibrated.toml");
    let v = json(&[
        "calibrate",
        &robot("spidercam-like-4.toml"),
        "--samples",
        &path,
        "--known-poses",
        "-o",
        &out_robot,
        "--json",
    ]);
    assert_eq!(v["identifiable"], true, "{v}");
    assert_eq!(v["rank_deficiency"], 0);
    assert!(v["poses"].is_null());
    for (i, c) in truth.cables().iter().enumerate() {
        for k in 0..3 {
            let got = v["frame"][i][k].as_f64().unwrap();
            assert!((got - c.frame[k]).abs() < 1e-9, "{i} {k}: {got}");
        }
        let o = v["offsets"][i].as_f64().unwrap();
        assert!((o - offsets[i]).abs() < 1e-9);
    }
    for key in [
        "platform",
        "gains",
        "residual_rms",
        "sigma",
        "condition_number",
        "samples_needed",
    ] {
        assert!(v.get(key).is_some(), "{key}");
    }
    // The written robot carries the calibrated anchors, offsets and gains exactly (robot-file
    // keys `frame`, `offset`, `gain`).
    let written = RobotDescription::load(&out_robot).unwrap();
    assert!((written.robot.cables()[2].frame - truth.cables()[2].frame).norm() < 1e-9);
    let encoders = written.encoders.as_ref().expect("offset and gain keys");
    for (i, c) in written.robot.cables().iter().enumerate() {
        for k in 0..3 {
            assert_eq!(c.frame[k], v["frame"][i][k].as_f64().unwrap());
        }
        assert_eq!(encoders.offsets[i], v["offsets"][i].as_f64().unwrap());
        assert_eq!(encoders.gains[i], v["gains"][i].as_f64().unwrap());
    }
    // Round trip: the written file is the calibrated model. Calibrating its anchors again from
    // the same readings starts from its offsets (held: not unknowns) and changes nothing.
    let again = json(&[
        "calibrate",
        &out_robot,
        "--samples",
        &path,
        "--known-poses",
        "--unknowns",
        "frame",
        "--json",
    ]);
    assert_eq!(again["identifiable"], true, "{again}");
    assert!(again["residual_rms"].as_f64().unwrap() < 1e-9, "{again}");
    for i in 0..4 {
        assert_eq!(again["offsets"][i], v["offsets"][i]);
        for k in 0..3 {
            let (a, b) = (
                again["frame"][i][k].as_f64().unwrap(),
                v["frame"][i][k].as_f64().unwrap(),
            );
            assert!((a - b).abs() < 1e-9, "{i} {k}: {a} vs {b}");
        }
    }
}

#[test]
fn calibrate_self_calibration_and_identifiability() {
    let (_, truth) = spidercam_as_built();
    let path = tmp("self.csv");
    std::fs::write(&path, csv(&truth, &hanging_poses(30), &[0.0; 4], false)).unwrap();
    let v = json(&[
        "calibrate",
        &robot("spidercam-like-4.toml"),
        "--samples",
        &path,
        "--unknowns",
        "frame",
        "--json",
    ]);
    assert_eq!(v["identifiable"], true, "{v}");
    assert_eq!(v["gauge_count"], 6);
    assert_eq!(v["poses"].as_array().unwrap().len(), 30);
    let d = |f: &serde_json::Value, i: usize, j: usize| {
        (0..3)
            .map(|k| (f[i][k].as_f64().unwrap() - f[j][k].as_f64().unwrap()).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    for (i, j) in [(0, 1), (0, 2), (1, 3), (2, 3)] {
        let expected = (truth.cables()[i].frame - truth.cables()[j].frame).norm();
        assert!((d(&v["frame"], i, j) - expected).abs() < 1e-9);
    }
    // Too few samples: k (4 − 3) ≥ 16 − 6 needs 10 (frame and offsets).
    std::fs::write(&path, csv(&truth, &hanging_poses(6), &[0.0; 4], false)).unwrap();
    let v = json(&[
        "calibrate",
        &robot("spidercam-like-4.toml"),
        "--samples",
        &path,
        "--json",
    ]);
    assert_eq!(v["identifiable"], false);
    assert_eq!(v["samples_needed"], 10);
}

/// Six cables, six DOF: never self-calibrates; `identifiable: false`, exit 0.
#[test]
fn calibrate_a_six_cable_spatial_robot_is_not_identifiable() {
    let crane = RobotDescription::load(robot("caspr-nist-robocrane.toml"))
        .unwrap()
        .robot;
    let mut s = String::from("l1,l2,l3,l4,l5,l6\n");
    for k in 0..20 {
        let t = k as f64;
        let p = Pose::spatial(
            Vector3::new(0.3 * t.sin(), 0.3 * t.cos(), 1.5 + 0.2 * (0.5 * t).sin()),
            0.05 * t.cos(),
            0.0,
            0.1 * t.sin(),
        );
        let l: Vec<String> = crane
            .inverse_kinematics(&p)
            .unwrap()
            .lengths()
            .map(|l| l.to_string())
            .collect();
        s += &l.join(",");
        s.push('\n');
    }
    let path = tmp("crane.csv");
    std::fs::write(&path, s).unwrap();
    let v = json(&[
        "calibrate",
        &robot("caspr-nist-robocrane.toml"),
        "--samples",
        &path,
        "--json",
    ]);
    assert_eq!(v["identifiable"], false);
    assert!(v["samples_needed"].is_null());
    assert!(v["reason"].as_str().unwrap().contains("as many cables"));
}

fn failure(args: &[&str]) -> String {
    let out = cdpr().args(args).output().unwrap();
    assert_eq!(out.status.code(), Some(2), "{args:?}");
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn calibrate_csv_errors_name_line_and_column() {
    let r = robot("spidercam-like-4.toml");
    let path = tmp("bad.csv");
    for (text, expected) in [
        ("l1,l2,l3\n1,2,3\n", "missing column `l4`"),
        ("l1,l2,l3,l4\n1,2,3\n", ":2: 3 fields, the header has 4"),
        (
            "# comment\nl1,l2,l3,l4\n1,2,x,4\n",
            ":3, column 3 (`l3`): `x` is not a number",
        ),
        (
            "x,y,z,l1,l2,l3,l4\n1,2,3,4,5,6,7\n",
            "pose columns need --known-poses",
        ),
    ] {
        std::fs::write(&path, text).unwrap();
        let e = failure(&["calibrate", &r, "--samples", &path]);
        assert!(e.contains(expected), "{text:?}: {e}");
    }
    std::fs::write(&path, "l1,l2,l3,l4\n1,2,3,4\n").unwrap();
    let e = failure(&["calibrate", &r, "--samples", &path, "--known-poses"]);
    assert!(e.contains("missing column `x`"), "{e}");
    let e = failure(&["calibrate", &r, "--samples", &path, "--unknowns", "anchors"]);
    assert!(e.contains("unknown parameter group `anchors`"), "{e}");
}

/// Issue 27: the spidercam's exact lengths at (0, 0, 10) and the RoboCrane's home pose are found
/// without a guess; the mirror pose above the anchors is flagged; rounded lengths are fitted.
#[test]
fn forward_finds_suspended_robots_hanging() {
    let spider = RobotDescription::load(robot("spidercam-like-4.toml"))
        .unwrap()
        .robot;
    let lengths: Vec<String> = spider
        .inverse_kinematics(&Pose::point(0.0, 0.0, 10.0))
        .unwrap()
        .lengths()
        .map(|l| l.to_string())
        .collect();
    let l = lengths.join(",");
    let r = robot("spidercam-like-4.toml");
    let v = json(&["forward", &r, "--lengths", &l, "--json"]);
    assert_eq!(v["status"], "solved", "{v}");
    assert!((v["pose"][2].as_f64().unwrap() - 10.0).abs() < 1e-9);
    let v = json(&[
        "forward",
        &r,
        "--lengths",
        &l,
        "--guess",
        "0,0,45",
        "--json",
    ]);
    assert_eq!(v["status"], "above the anchors", "{v}");
    // 0.1 mm rounding: fitted, with residual_rms and pose_std.
    let rounded: Vec<String> = spider
        .inverse_kinematics(&Pose::point(3.0, -7.0, 10.0))
        .unwrap()
        .lengths()
        .map(|l| format!("{:.4}", l))
        .collect();
    let v = json(&["forward", &r, "--lengths", &rounded.join(","), "--json"]);
    assert_eq!(v["status"], "fitted", "{v}");
    assert!(v["residual_rms"].as_f64().unwrap() < 1e-4);
    assert_eq!(v["pose_std"].as_array().unwrap().len(), 3);
    assert_eq!(v["length_sigma"], 1e-4);
    let crane = RobotDescription::load(robot("caspr-nist-robocrane.toml"))
        .unwrap()
        .robot;
    let lengths: Vec<String> = crane
        .inverse_kinematics(&Pose::spatial(Vector3::new(0.0, 0.0, 1.5), 0.0, 0.0, 0.0))
        .unwrap()
        .lengths()
        .map(|l| l.to_string())
        .collect();
    let v = json(&[
        "forward",
        &robot("caspr-nist-robocrane.toml"),
        "--lengths",
        &lengths.join(","),
        "--json",
    ]);
    let home = v["solutions"].as_array().unwrap().iter().any(|s| {
        let q: Vec<f64> = s["pose"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        q.iter()
            .zip([0.0, 0.0, 1.5, 0.0, 0.0, 0.0])
            .all(|(a, b)| (a - b).abs() < 1e-8)
    });
    assert!(home, "{v}");
}

/// Issue 25: the cable count is blamed, negative lengths name the cable, `--tolerance -1` gets
/// the validation message, and `--help` names every robot format.
#[test]
fn forward_messages() {
    let r = robot("spidercam-like-4.toml");
    let e = failure(&["forward", &r, "--lengths", "1,1,1"]);
    assert!(e.contains("3 values given, the robot has 4 cables"), "{e}");
    assert!(!e.contains("motion pattern"), "{e}");
    let e = failure(&["forward", &r, "--lengths", "30,-1,30,30"]);
    assert!(e.contains("cable 2 is negative"), "{e}");
    let e = failure(&[
        "forward",
        &r,
        "--lengths",
        "30,30,30,30",
        "--tolerance",
        "-1",
    ]);
    assert!(e.contains("tolerance (must be finite and > 0)"), "{e}");
    let e = failure(&[
        "forward",
        &r,
        "--lengths",
        "30,30,30,30",
        "--length-sigma",
        "-1",
    ]);
    assert!(e.contains("σ"), "{e}");
    let out = cdpr().args(["forward", "--help"]).output().unwrap();
    let help = String::from_utf8_lossy(&out.stdout);
    assert!(help.contains("CASPR") && help.contains(".wcrfx"), "{help}");
}

/// Issue 27: suspended robots get the default region extended below their anchors: these
/// exited 2 with "region is empty or degenerate along axis 2".
#[test]
fn workspace_of_suspended_robots_runs() {
    for name in [
        "spidercam-like-4.toml",
        "caspr-nist-robocrane.toml",
        "caspr-caroca.toml",
        "caspr-cogiro.toml",
    ] {
        let v = json(&["workspace", &robot(name), "--grid", "4", "--json"]);
        assert!(v["box"].is_array() || v.is_object(), "{name}: {v}");
    }
}
