//! `--kinematics pulley|standard`, the pulley fields of `cdpr kinematics` and `cdpr forward`
//! (issue 14 contract).

use crate::common;

use common::{cdpr, json, robot};

fn floats(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

const POSE: &str = "0.3,-0.2,1.1,0.05,-0.02,0.1";

#[test]
fn kinematics_reports_pulley_fields_and_defaults_to_pulley() {
    let pulley = robot("ipanema-like-8-pulleys.toml");
    let v = json(&["kinematics", &pulley, "--pose", POSE, "--json"]);
    assert_eq!(v["kinematics"], "pulley");
    let (l, lf) = (floats(&v["lengths"]), floats(&v["free_lengths"]));
    let (gamma, beta) = (floats(&v["swivel_angles"]), floats(&v["wrap_angles"]));
    assert_eq!((l.len(), lf.len(), gamma.len(), beta.len()), (8, 8, 8, 8));
    for i in 0..8 {
        assert!((l[i] - (0.05 * beta[i] + lf[i])).abs() < 1e-12, "cable {i}");
        assert!(beta[i] > 0.0);
    }
    // `--kinematics standard` drops the pulleys: the straight robot with the same frame points.
    let s = json(&[
        "kinematics",
        &pulley,
        "--pose",
        POSE,
        "--json",
        "--kinematics",
        "standard",
    ]);
    let straight = json(&[
        "kinematics",
        &robot("ipanema-like-8.toml"),
        "--pose",
        POSE,
        "--json",
    ]);
    assert_eq!(s["kinematics"], "standard");
    assert_eq!(s["lengths"], straight["lengths"]);
    assert_eq!(s["wrench_matrix"], straight["wrench_matrix"]);
    assert_eq!(straight["kinematics"], "standard");
    assert_eq!(floats(&straight["wrap_angles"]), vec![0.0; 8]);
    assert_eq!(straight["free_lengths"], straight["lengths"]);
}

#[test]
fn forward_recovers_the_pose_from_pulley_lengths() {
    let pulley = robot("ipanema-like-8-pulleys.toml");
    let v = json(&["kinematics", &pulley, "--pose", POSE, "--json"]);
    let lengths: Vec<String> = floats(&v["lengths"])
        .iter()
        .map(|x| format!("{x:?}"))
        .collect();
    let lengths = lengths.join(",");
    let truth: Vec<f64> = POSE.split(',').map(|x| x.parse().unwrap()).collect();
    let f = json(&[
        "forward",
        &pulley,
        "--lengths",
        &lengths,
        "--guess",
        "0.28,-0.19,1.08,0.04,0,0.09",
        "--json",
    ]);
    assert_eq!(f["status"], "solved");
    assert_eq!(f["converged"], true);
    assert!(f["residual"].as_f64().unwrap() <= 1e-9);
    assert!(f["iterations"].as_u64().unwrap() >= 1);
    for (a, b) in floats(&f["pose"]).iter().zip(&truth) {
        assert!((a - b).abs() < 1e-9, "{a} vs {b}");
    }
    assert_eq!(f["solutions"].as_array().unwrap().len(), 1);
    // Without a guess: multi-start, and the true pose is among the solutions.
    let m = json(&["forward", &pulley, "--lengths", &lengths, "--json"]);
    assert!(m["solutions"].as_array().unwrap().iter().any(|s| {
        floats(&s["pose"])
            .iter()
            .zip(&truth)
            .all(|(a, b)| (a - b).abs() < 1e-9)
    }));
    // The straight model cannot meet pulley lengths: an outcome (exit 0), not an error.
    let s = json(&[
        "forward",
        &pulley,
        "--lengths",
        &lengths,
        "--guess",
        "0.3,-0.2,1.1,0,0,0",
        "--json",
        "--kinematics",
        "standard",
    ]);
    assert_eq!(s["kinematics"], "standard");
    // 8 cables, 6 DOF: the least-squares residual is far beyond the 0.1 mm length noise.
    assert_eq!(s["status"], "inconsistent");
    assert!(s["residual"].as_f64().unwrap() > 1e-3);
}

#[test]
fn forward_table_and_bad_input() {
    let out = cdpr()
        .args([
            "forward",
            &robot("tdpm-4.toml"),
            "--lengths",
            "1,1,1,1",
            "--guess",
            "0,0,0",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("residual (m)"), "{text}");
    let out = cdpr()
        .args(["forward", &robot("tdpm-4.toml"), "--lengths", "1,1,1"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("cable lengths"));
}

#[test]
fn every_command_takes_kinematics() {
    let out = cdpr()
        .args([
            "tension",
            &robot("ipanema-like-8-pulleys.toml"),
            "--pose",
            "0,0,1,0,0,0",
            "--kinematics",
            "standard",
            "--json",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for cmd in [
        "stiffness",
        "workspace",
        "capacity",
        "trajectory",
        "isotropic",
    ] {
        let out = cdpr().args([cmd, "--help"]).output().unwrap();
        assert!(
            String::from_utf8_lossy(&out.stdout).contains("--kinematics"),
            "{cmd}"
        );
    }
}

/// When the minimum-norm tensions t0 = −W⁺ w_ext lie within the bounds they are the l2 optimum:
/// CAROCA with swivel pulleys (CASPR model) at its home pose, every method of r = 2 that minimises
/// ‖t‖₂ must return them. The build before this session's r = 2 rewrite returned
/// t = (0, 328.6, 630.9, 327.6, 0.9, 329.6, 629.7, 327.3) N here (see the feasible-polygon unit
/// test `a_vertex_pair_made_of_rounding_does_not_exclude_interior_points`).
#[test]
fn l2_returns_the_minimum_norm_tensions_when_they_are_in_bounds() {
    let caroca = robot("caspr-caroca-pulleys.toml");
    let run = |method: &str| {
        json(&[
            "tension",
            &caroca,
            "--pose",
            "0,0,1,0,0,0",
            "--method",
            method,
            "--json",
        ])
    };
    let pinv = run("pinv");
    assert_eq!(pinv["feasible"], true);
    let t0 = floats(&pinv["tensions"]);
    let l2 = floats(&run("l2")["tensions"]);
    for (i, (a, b)) in l2.iter().zip(&t0).enumerate() {
        assert!(
            (a - b).abs() <= 1e-9 * 1000.0,
            "cable {}: {a} N vs {b} N",
            i + 1
        );
    }
}
