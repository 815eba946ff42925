//! `cdpr trajectory` and `cdpr stiffness-map` (issue 8): JSON contract, infeasible samples kept,
//! continuity, per-waypoint wrenches, the stiffness-oriented study of Picard, Caro, Plestan & Claveau 2020.

use crate::common;

use common::{cdpr, json, robot};

use nalgebra::{DMatrix, DVector};
use serde_json::Value;

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

const X0: &str = "1.5,0.35,0.59,0,0,0";
const LOAD: &str = "0,50,0,0,0,0";

fn rowc_trajectory(method: &str, samples: usize, extra: &[&str]) -> Value {
    let n = samples.to_string();
    let r = robot("rowc-like-8.toml");
    let mut args = vec![
        "trajectory",
        r.as_str(),
        "--from",
        "0.8,0.35,0.59,0,0,0",
        "--to",
        "2.2,0.35,1.4,0,0,0.05",
        "--samples",
        n.as_str(),
        "--wrench",
        "0,30,0,0,0,0",
        "--method",
        method,
        "--json",
    ];
    args.extend_from_slice(extra);
    json(&args)
}

#[test]
fn trajectory_json_has_the_contract_fields() {
    let v = rowc_trajectory("sotda", 41, &["--nu", "0.9"]);
    let s = floats(&v["s"]);
    assert_eq!(s.len(), 41);
    assert_eq!(s[0], 0.0);
    assert_eq!(s[40], 1.0);
    assert!(s.windows(2).all(|w| w[1] > w[0]));
    let t = v["tensions"].as_array().unwrap();
    assert_eq!(t.len(), 41);
    assert_eq!(v["feasible_count"].as_u64(), Some(41));
    for sample in t {
        let ti = floats(sample);
        assert_eq!(ti.len(), 8);
        assert!(ti.iter().all(|&x| (10.0..=200.0).contains(&x)), "{ti:?}");
    }
    let jumps = floats(&v["max_jump"]);
    assert_eq!(jumps.len(), 8);
    // max_jump is the largest consecutive difference, recomputed here.
    for (i, &j) in jumps.iter().enumerate() {
        let expect = t
            .windows(2)
            .map(|w| (w[1][i].as_f64().unwrap() - w[0][i].as_f64().unwrap()).abs())
            .fold(0.0, f64::max);
        assert!((j - expect).abs() < 1e-12);
    }
    assert_eq!(v["method"], "sotda");
    assert!(v["reasons"].as_array().unwrap().iter().all(Value::is_null));
    assert!(v["discontinuities"].as_array().unwrap().is_empty());
}

/// Same tensions as `cdpr tension` at a sample pose (ℓ2 has a unique answer).
#[test]
fn trajectory_samples_match_the_tension_command() {
    let v = rowc_trajectory("l2", 5, &[]);
    let pose: Vec<String> = floats(&v["poses"][2])
        .iter()
        .map(|x| x.to_string())
        .collect();
    let one = json(&[
        "tension",
        &robot("rowc-like-8.toml"),
        "--pose",
        &pose.join(","),
        "--wrench",
        "0,30,0,0,0,0",
        "--method",
        "l2",
        "--json",
    ]);
    let (a, b) = (floats(&v["tensions"][2]), floats(&one["tensions"]));
    for (x, y) in a.iter().zip(&b) {
        assert!((x - y).abs() < 1e-9 * y.abs().max(1.0), "{a:?} vs {b:?}");
    }
}

/// The options of the peers' methods reach `cdpr trajectory` as they reach `cdpr tension`
/// (one check, `cdpr_api::PeerOptions::for_method`): p-norm's tensions move with --p, each
/// sample equals `cdpr tension` at its pose with the same --p, and --p with l2 is a usage
/// error (exit 2) naming the flag. (Before, `trajectory` had no such flags.)
#[test]
fn peer_options_reach_the_trajectory() {
    let p4 = rowc_trajectory("p-norm", 5, &["--p", "4"]);
    let p6 = rowc_trajectory("p-norm", 5, &["--p", "6"]);
    let pose: Vec<String> = floats(&p6["poses"][2])
        .iter()
        .map(|x| x.to_string())
        .collect();
    let one = json(&[
        "tension",
        &robot("rowc-like-8.toml"),
        "--pose",
        &pose.join(","),
        "--wrench",
        "0,30,0,0,0,0",
        "--method",
        "p-norm",
        "--p",
        "6",
        "--json",
    ]);
    let (a, b) = (floats(&p6["tensions"][2]), floats(&one["tensions"]));
    for (x, y) in a.iter().zip(&b) {
        assert!((x - y).abs() < 1e-9 * y.abs().max(1.0), "{a:?} vs {b:?}");
    }
    let c = floats(&p4["tensions"][2]);
    let moved = a
        .iter()
        .zip(&c)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(
        moved > 1e-3,
        "p = 4 and p = 6 give the same tensions: {a:?}"
    );
    let out = cdpr()
        .args([
            "trajectory",
            &robot("rowc-like-8.toml"),
            "--from",
            "0.8,0.35,0.59,0,0,0",
            "--to",
            "2.2,0.35,1.4,0,0,0.05",
            "--method",
            "l2",
            "--p",
            "6",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--p is an option of another method, not of l2"),
        "{err}"
    );
}

/// Done-when: profiles are continuous for barycenter, l2 and sotda with ν < 1 (max jump → 0 as
/// the step → 0).
#[test]
fn profiles_are_continuous_inside_the_workspace() {
    for (method, extra) in [
        ("barycenter", vec![]),
        ("l2", vec![]),
        ("sotda", vec!["--nu", "0.5"]),
        ("sotda", vec!["--nu", "0.9"]),
    ] {
        let jump = |n: usize| {
            let v = rowc_trajectory(method, n, &extra);
            assert_eq!(v["feasible_count"].as_u64(), Some(n as u64));
            floats(&v["max_jump"]).into_iter().fold(0.0, f64::max)
        };
        let (coarse, fine) = (jump(40), jump(320));
        assert!(
            fine < coarse / 4.0,
            "{method} {extra:?}: max jump {coarse} N with 40 samples, {fine} N with 320"
        );
    }
}

/// Thesis Fig. 6.6 section: the samples beyond the workspace are reported (null tensions with
/// their s and a reason) and the steep rise before the boundary is flagged.
#[test]
fn infeasible_samples_are_reported_and_the_jump_flagged() {
    let v = json(&[
        "trajectory",
        &robot("tdpm-4-fig6.6.toml"),
        "--from",
        "0.54,-0.2,0",
        "--to",
        "0.54,0.05,0",
        "--samples",
        "2501",
        "--wrench",
        "0,-10,0",
        "--method",
        "l2",
        "--json",
    ]);
    let s = floats(&v["s"]);
    let t = v["tensions"].as_array().unwrap();
    let reasons = v["reasons"].as_array().unwrap();
    let y = |k: usize| -0.2 + 0.25 * s[k];
    let first_out = (0..s.len()).find(|&k| t[k].is_null()).unwrap();
    assert!(y(first_out).abs() < 2e-3, "leaves at y = {}", y(first_out));
    assert!((first_out..s.len()).all(|k| t[k].is_null() && reasons[k].is_string()));
    assert_eq!(v["feasible_count"].as_u64(), Some(first_out as u64));
    let flagged: Vec<usize> = v["discontinuities"]
        .as_array()
        .unwrap()
        .iter()
        .map(|k| k.as_u64().unwrap() as usize)
        .collect();
    assert!(!flagged.is_empty());
    assert!(flagged.iter().all(|&k| y(k).abs() < 1.2e-2), "{flagged:?}");
}

#[test]
fn waypoints_file_with_per_waypoint_wrench_and_step() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("path.toml");
    std::fs::write(
        &file,
        "[[waypoints]]\npose = [1.0, 0.35, 0.6, 0, 0, 0]\nwrench = [0, 0, 0, 0, 0, 0]\n\
         [[waypoints]]\npose = [1.5, 0.35, 0.6, 0, 0, 0]\nwrench = [0, 40, 0, 0, 0, 0]\n\
         [[waypoints]]\npose = [1.5, 0.35, 1.1, 0, 0, 0]\n",
    )
    .unwrap();
    let svg = dir.path().join("profile.svg");
    let v = json(&[
        "trajectory",
        &robot("rowc-like-8.toml"),
        "--waypoints",
        file.to_str().unwrap(),
        "--step",
        "0.1",
        "--wrench",
        "0,20,0,0,0,0",
        "--method",
        "l2",
        "--plot",
        svg.to_str().unwrap(),
        "--json",
    ]);
    // Two legs of length 0.5 at step 0.1: 5 + 5 pieces, 11 samples, the corner at s = 0.5.
    let s = floats(&v["s"]);
    assert_eq!(s.len(), 11);
    assert!((s[5] - 0.5).abs() < 1e-12);
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<svg"));
    // At s = 0.25 the wrench is halfway between the first two waypoints: (0, 20, 0, ...);
    // the third waypoint has no wrench and takes --wrench (0, 20, ...), so at s = 0.75 it is
    // halfway between 40 and 20: 30.
    for (k, fy) in [(0usize, 0.0), (5, 40.0), (10, 20.0)] {
        let pose: Vec<String> = floats(&v["poses"][k])
            .iter()
            .map(|x| x.to_string())
            .collect();
        let w = format!("0,{fy},0,0,0,0");
        let one = json(&[
            "tension",
            &robot("rowc-like-8.toml"),
            "--pose",
            &pose.join(","),
            "--wrench",
            &w,
            "--method",
            "l2",
            "--json",
        ]);
        let (a, b) = (floats(&v["tensions"][k]), floats(&one["tensions"]));
        for (x, y) in a.iter().zip(&b) {
            assert!(
                (x - y).abs() < 1e-9 * y.abs().max(1.0),
                "sample {k}: {a:?} vs {b:?}"
            );
        }
    }
    // Interpolated samples differ from both neighbours' constant-wrench answers.
    let mid = json(&[
        "tension",
        &robot("rowc-like-8.toml"),
        "--pose",
        "1.25,0.35,0.6,0,0,0",
        "--wrench",
        "0,20,0,0,0,0",
        "--method",
        "l2",
        "--json",
    ]);
    let (a, b) = (floats(&v["tensions"][2]), floats(&mid["tensions"]));
    assert!((floats(&v["poses"][2])[0] - 1.2).abs() < 1e-12);
    // sample 2 is at x = 1.2 with wrench 16 N: not the same problem as x = 1.25, 20 N.
    assert!(a.iter().zip(&b).any(|(x, y)| (x - y).abs() > 1e-6));
}

#[test]
fn trajectory_bad_input_exits_2() {
    let r = robot("rowc-like-8.toml");
    for args in [
        vec!["trajectory", r.as_str(), "--samples", "10"],
        vec![
            "trajectory",
            r.as_str(),
            "--from",
            "0,0,0",
            "--to",
            "1,1,1,0,0,0",
        ],
        vec![
            "trajectory",
            r.as_str(),
            "--from",
            "1,0.35,0.6,0,0,0",
            "--to",
            "2,0.35,0.6,0,0,0",
            "--samples",
            "1",
        ],
        vec![
            "trajectory",
            r.as_str(),
            "--from",
            "1,0.35,0.6,0,0,0",
            "--to",
            "2,0.35,0.6,0,0,0",
            "--method",
            "sotda",
            "--nu",
            "1.5",
        ],
    ] {
        let out = cdpr().args(&args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(!out.stderr.is_empty());
    }
    // sotda without axial stiffness.
    let out = cdpr()
        .args(["stiffness-map", &robot("tdpm-4.toml"), "--pose", "0,0,0"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}

fn stiffness_map() -> Value {
    json(&[
        "stiffness-map",
        &robot("rowc-like-8.toml"),
        "--pose",
        X0,
        "--wrench",
        LOAD,
        "--grid",
        "40",
        "--json",
    ])
}

/// Done-when: the displacement at the SOTDA optimum is ≤ at every sampled polygon point.
#[test]
fn sotda_optimum_beats_every_grid_point() {
    let v = stiffness_map();
    let d_opt = v["displacement_optimum"].as_f64().unwrap();
    let d_bary = v["displacement_barycenter"].as_f64().unwrap();
    let mut count = 0;
    for row in v["grid"]["values"].as_array().unwrap() {
        for x in row.as_array().unwrap() {
            if let Some(x) = x.as_f64() {
                assert!(d_opt <= x * (1.0 + 1e-9), "optimum {d_opt} > grid {x}");
                count += 1;
            }
        }
    }
    assert!(count > 200, "only {count} grid points in the polygon");
    assert!(d_opt < d_bary);
    let red = v["reduction_percent"].as_f64().unwrap();
    assert!((red - 100.0 * (d_bary - d_opt) / d_bary).abs() < 1e-9);
    // ν-curve: from the barycentre (ν = 0) to the optimum (ν = 1).
    let nu = v["nu_curve"].as_array().unwrap();
    assert_eq!(floats(&nu[0]), vec![0.0, d_bary]);
    assert_eq!(floats(nu.last().unwrap()), vec![1.0, d_opt]);
    assert!(v["polygon"].as_array().unwrap().len() >= 3);
    assert_eq!(v["grid"]["lambda1"].as_array().unwrap().len(), 40);
}

/// The barycentre's displacement, recomputed independently: K from `cdpr stiffness` at the
/// barycentre tensions, δX = K⁻¹ w_e, |δp_y| in mm.
#[test]
fn barycentre_displacement_matches_the_stiffness_command() {
    let v = stiffness_map();
    let t: Vec<String> = floats(&v["tensions_barycenter"])
        .iter()
        .map(|x| x.to_string())
        .collect();
    let k = json(&[
        "stiffness",
        &robot("rowc-like-8.toml"),
        "--pose",
        X0,
        "--tensions",
        &t.join(","),
        "--json",
    ]);
    let rows: Vec<Vec<f64>> = k["stiffness"]
        .as_array()
        .unwrap()
        .iter()
        .map(floats)
        .collect();
    let km = DMatrix::from_fn(6, 6, |r, c| rows[r][c]);
    let dx = km
        .lu()
        .solve(&DVector::from_vec(vec![0.0, 50.0, 0.0, 0.0, 0.0, 0.0]))
        .unwrap();
    let expect = dx[1].abs() * 1e3;
    let got = v["displacement_barycenter"].as_f64().unwrap();
    assert!((got - expect).abs() < 1e-9 * expect, "{got} vs {expect}");
    // Millimetres, and a lateral stiffness of the order of the paper's (displacements of ~10 mm).
    assert!((1.0..100.0).contains(&got), "{got} mm");
}

#[test]
fn stiffness_map_writes_a_plot_and_a_table() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("map.png");
    let out = cdpr()
        .args([
            "stiffness-map",
            &robot("rowc-like-8.toml"),
            "--pose",
            X0,
            "--wrench",
            LOAD,
            "--grid",
            "30",
            "--plot",
            png.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("reduction"), "{text}");
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
    // A pose outside the workspace is a normal (exit 0) answer.
    let v = json(&[
        "stiffness-map",
        &robot("rowc-like-8.toml"),
        "--pose",
        "1.5,0.35,0.59,0,0,0",
        "--wrench",
        "0,5000,0,0,0,0",
        "--json",
    ]);
    assert_eq!(v["feasible"], false);
    assert!(v["reason"].is_string());
}

/// A reader that stops early (`cdpr trajectory … | head -1`) ends the program quietly: no panic
/// on the broken pipe (Rust ignores SIGPIPE unless `main` restores it).
#[cfg(unix)]
#[test]
fn a_closed_pipe_ends_the_output_without_a_panic() {
    use std::io::{BufRead, BufReader};
    use std::process::{Command, Stdio};
    let r = robot("rowc-like-8.toml");
    let mut child = Command::new(assert_cmd::cargo::cargo_bin("cdpr"))
        .args([
            "trajectory",
            r.as_str(),
            "--from",
            "0.8,0.35,0.59,0,0,0",
            "--to",
            "2.2,0.35,1.4,0,0,0.05",
            "--samples",
            "20000",
            "--wrench",
            LOAD,
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut first)
        .unwrap();
    assert!(!first.is_empty());
    // The reader is dropped here: the pipe is closed while cdpr still has lines to print.
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_ne!(out.status.code(), Some(101), "{stderr}");
}

/// `--samples 1` is refused in the path's terms (issue 25: it blamed the motion pattern).
#[test]
fn one_sample_is_refused_by_name() {
    let out = cdpr()
        .args([
            "trajectory",
            &robot("rowc-like-8.toml"),
            "--from",
            "1,0.35,0.6,0,0,0",
            "--to",
            "2,0.35,0.6,0,0,0",
            "--samples",
            "1",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("a path needs at least 2 samples (its two ends), got 1")
            && !err.contains("motion pattern"),
        "{err}"
    );
}
