//! `cdpr trajectory --time-law … --dynamics`, `cdpr simulate` and `--criteria dynamic`
//! (issue 28 contract: flag and JSON names).

use crate::common;

use common::{cdpr, json, robot};

fn floats(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// The timed JSON fields, the quintic peak speed 1.875 Δ/T, rest at both ends, and the
/// inertial wrench M ẍ (a point of the 8-cable robot moving along x: m ẍ).
#[test]
fn timed_trajectory_json() {
    let r = robot("ipanema-like-8.toml");
    let v = json(&[
        "trajectory",
        &r,
        "--from",
        "-0.2,0,1,0,0,0",
        "--to",
        "0.2,0,1,0,0,0",
        "--time-law",
        "quintic",
        "--duration",
        "2",
        "--dt",
        "0.5",
        "--dynamics",
        "--json",
    ]);
    assert_eq!(floats(&v["t"]), [0.0, 0.5, 1.0, 1.5, 2.0]);
    for key in [
        "velocity",
        "acceleration",
        "cable_lengths",
        "cable_speeds",
        "cable_accelerations",
        "inertial_wrench",
        "tensions",
    ] {
        assert_eq!(v[key].as_array().unwrap().len(), 5, "{key}");
    }
    let vel = floats(&v["velocity"][2]);
    assert!((vel[0] - 1.875 * 0.4 / 2.0).abs() < 1e-12);
    assert_eq!(floats(&v["velocity"][0]), [0.0; 6]);
    // m = 5 kg: inertial force m ẍ at t = 0.5 s (τ = 0.25: s̈ = 60τ(1 − 3τ + 2τ²) Δ/T²).
    let tau: f64 = 0.25;
    let sdd = 60.0 * tau * (1.0 - 3.0 * tau + 2.0 * tau * tau) * 0.4 / 4.0;
    assert!((floats(&v["inertial_wrench"][1])[0] - 5.0 * sdd).abs() < 1e-9);
    // l̇ = −Wᵀẋ: at rest, zero.
    assert!(
        floats(&v["cable_speeds"][0])
            .iter()
            .all(|x| x.abs() < 1e-15)
    );
    assert_eq!(v["feasible_count"], 5);
    // Without --dynamics: no inertial wrench.
    let q = json(&[
        "trajectory",
        &r,
        "--from",
        "-0.2,0,1,0,0,0",
        "--to",
        "0.2,0,1,0,0,0",
        "--time-law",
        "cubic",
        "--duration",
        "2",
        "--json",
    ]);
    assert!(q.get("inertial_wrench").is_none());
    assert_eq!(q["t"].as_array().unwrap().len(), 201);
}

/// Bad input exits 2 naming the key and the value.
#[test]
fn timed_trajectory_bad_input() {
    let r = robot("ipanema-like-8.toml");
    let base = [
        "trajectory",
        &r,
        "--from",
        "0,0,1,0,0,0",
        "--to",
        "0.2,0,1,0,0,0",
    ];
    for (extra, needle) in [
        (
            vec!["--time-law", "cubic", "--duration", "-1"],
            "--duration",
        ),
        (
            vec!["--time-law", "cubic", "--duration", "1", "--dt", "0"],
            "--dt",
        ),
        (
            vec![
                "--time-law",
                "trapezoid",
                "--duration",
                "1",
                "--max-acceleration",
                "0.1",
            ],
            "max-acceleration = 0.1",
        ),
        (
            vec![
                "--time-law",
                "quintic",
                "--duration",
                "1",
                "--max-velocity",
                "0.1",
            ],
            "max-velocity = 0.1",
        ),
    ] {
        let out = cdpr().args(base).args(&extra).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{extra:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{extra:?}: {err}");
    }
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("w.toml");
    std::fs::write(
        &file,
        "[[waypoints]]\npose = [0, 0, 1, 0, 0, 0]\ntime = 0.0\n[[waypoints]]\npose = [0.2, 0, 1, 0, 0, 0]\ntime = 1.0\n[[waypoints]]\npose = [0.2, 0.2, 1, 0, 0, 0]\ntime = 0.5\n",
    )
    .unwrap();
    let out = cdpr()
        .args([
            "trajectory",
            &r,
            "--waypoints",
            file.to_str().unwrap(),
            "--time-law",
            "cubic",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("waypoints[2].time = 0.5"));
}

/// Free fall with zero tensions: z = z₀ − g t²/2 (RK4 exact on quadratics).
#[test]
fn simulate_free_fall() {
    let r = robot("ipanema-like-8.toml");
    let v = json(&[
        "simulate",
        &r,
        "--from",
        "0,0,1,0,0,0",
        "--duration",
        "0.3",
        "--dt",
        "0.01",
        "--tensions",
        "0,0,0,0,0,0,0,0",
        "--json",
    ]);
    let t = floats(&v["t"]);
    assert_eq!(t.len(), 31);
    for (k, &tk) in t.iter().enumerate() {
        let z = floats(&v["poses"][k])[2];
        assert!(
            (z - (1.0 - 0.5 * 9.80665 * tk * tk)).abs() < 1e-12,
            "{tk}: {z}"
        );
    }
    for key in ["velocities", "accelerations", "tensions"] {
        assert_eq!(v[key].as_array().unwrap().len(), 31, "{key}");
    }
    let out = cdpr()
        .args([
            "simulate",
            &r,
            "--from",
            "0,0,1,0,0,0",
            "--duration",
            "1",
            "--dt",
            "0.1",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "no drive is a usage error");
}

/// `--criteria dynamic`: the two-cable point mass's closed form at grid points.
#[test]
fn dynamic_workspace_closed_form() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("two.toml");
    std::fs::write(
        &file,
        "name = \"two\"\nmotion = \"point2\"\n[tension]\nmin = 0.0\nmax = 1e6\n[platform]\nmass = 3.0\ngravity = [0.0, -9.81]\n[[cables]]\nframe = [0.0, 1.5]\n[[cables]]\nframe = [2.0, 1.5]\n",
    )
    .unwrap();
    let points = dir.path().join("p.csv");
    let out = cdpr()
        .args([
            "workspace",
            file.to_str().unwrap(),
            "--criteria",
            "dynamic",
            "--acceleration-box",
            "2,1",
            "--box",
            "-0.5,2.5,-1,1.4",
            "--grid",
            "20",
            "--points",
            points.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&points).unwrap();
    let mut checked = 0;
    for line in text.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let (x, y): (f64, f64) = (f[0].parse().unwrap(), f[1].parse().unwrap());
        let feasible = f[2].trim() == "true" || f[2].trim() == "1";
        let mut slack = f64::INFINITY;
        for (ax, ay) in [(-2.0, -1.0), (-2.0, 1.0), (2.0, -1.0), (2.0, 1.0)] {
            let xi = x + (1.5 - y) * ax / (9.81 + ay);
            slack = slack.min(xi).min(2.0 - xi);
        }
        if slack.abs() > 1e-9 && (1.5 - y).abs() > 1e-9 {
            assert_eq!(feasible, slack > 0.0, "({x}, {y})");
            checked += 1;
        }
    }
    assert!(checked > 300);
}
