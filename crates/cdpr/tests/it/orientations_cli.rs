//! `cdpr workspace --orientations … --kind total|maximal` and `cdpr orientations`: a
//! one-orientation set equals `--orientation`; total ⊆ constant ⊆ maximal in counts; the map
//! and the per-orientation verdicts agree; non-spatial robots and bad sets are usage errors.

use crate::common;

use common::{cdpr, json, robot};

fn count(args: &[&str]) -> u64 {
    let mut a = vec!["workspace", "--grid", "8", "--json"];
    let file = robot("ipanema-like-8.toml");
    a.push(&file);
    a.extend_from_slice(args);
    json(&a)["feasible_points"].as_u64().unwrap()
}

#[test]
fn one_orientation_equals_the_constant_orientation_workspace() {
    let (rx, ry, rz) = (3f64.to_radians(), (-2f64).to_radians(), 4f64.to_radians());
    let o = format!("{rx},{ry},{rz}");
    let constant = count(&["--orientation", &o]);
    assert!(constant > 0);
    for kind in ["total", "maximal"] {
        assert_eq!(
            count(&["--orientations", "euler:rx=3,ry=-2,rz=4", "--kind", kind]),
            constant,
            "{kind}"
        );
    }
}

#[test]
fn total_is_smallest_and_maximal_largest() {
    let set = "euler:rx=-4..4,rz=-4..4,n=3";
    let total = count(&["--orientations", set]);
    let maximal = count(&["--orientations", set, "--kind", "maximal"]);
    for o in ["0,0,0", "0.0698131700797732,0,-0.0698131700797732"] {
        let c = count(&["--orientation", o]);
        assert!(total <= c && c <= maximal, "{total} ≤ {c} ≤ {maximal}");
    }
    assert!(total < maximal);
    let v = json(&[
        "workspace",
        &robot("ipanema-like-8.toml"),
        "--grid",
        "8",
        "--orientations",
        set,
        "--json",
    ]);
    assert_eq!(v["kind"], "total");
    assert_eq!(v["orientation_count"], 9);
    let limiting = v["limiting_orientations"].as_array().unwrap();
    assert!(!limiting.is_empty());
    let summed: u64 = v["limiting_summary"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["boundary_points"].as_u64().unwrap())
        .sum();
    assert_eq!(summed as usize, limiting.len());
}

#[test]
fn orientations_at_a_position_agree_with_their_map() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("map.png");
    let v = json(&[
        "orientations",
        &robot("ipanema-like-8.toml"),
        "--position",
        "0,0,1",
        "--orientations",
        "tilt:10,torsion=-10..10,n=5",
        "--plot",
        png.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(v["count"], 205);
    let list = v["orientations"].as_array().unwrap();
    let feasible = list.iter().filter(|o| o["feasible"] == true).count();
    assert_eq!(v["feasible_count"].as_u64().unwrap() as usize, feasible);
    // Fractions weighted by the azimuths per tilt ring (1, 4, 8, 12, 16) give the count back.
    let rings = [1.0, 4.0, 8.0, 12.0, 16.0];
    let rows = v["map"]["fraction"].as_array().unwrap();
    let mut total = 0.0;
    for (ring, row) in rings.iter().zip(rows) {
        for f in row.as_array().unwrap() {
            total += f.as_f64().unwrap() * ring;
        }
    }
    assert!((total - feasible as f64).abs() < 1e-9);
    // The untilted, untwisted orientation is the first sample; it is feasible at the centre
    // (the constant-orientation workspace contains it).
    assert_eq!(list[2]["angles_deg"], serde_json::json!([0.0, 0.0, 0.0]));
    assert_eq!(list[2]["feasible"], true);
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
}

#[test]
fn usage_errors() {
    for (args, says) in [
        (
            vec![
                "orientations",
                "tdpm-4.toml",
                "--position",
                "0,0,0",
                "--orientations",
                "tilt:5",
            ],
            "spatial",
        ),
        (
            vec![
                "orientations",
                "ipanema-like-8.toml",
                "--position",
                "0,0",
                "--orientations",
                "tilt:5",
            ],
            "--position",
        ),
        (
            vec![
                "workspace",
                "ipanema-like-8.toml",
                "--orientations",
                "tilt:5,n=1",
            ],
            "n ≥ 2",
        ),
        (
            vec!["workspace", "ipanema-like-8.toml", "--kind", "total"],
            "--orientations",
        ),
    ] {
        let mut a: Vec<String> = args.iter().map(|s| s.to_string()).collect();
        a[1] = robot(args[1]);
        let out = cdpr().args(&a).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(says), "{args:?}: {err}");
    }
}

/// `--orientations … --boundary mesh`: a one-orientation set gives the constant-orientation
/// boundary mesh's volume, and total ⊆ maximal holds for the mesh volumes.
#[test]
fn orientation_workspaces_as_boundary_meshes() {
    let r = robot("ipanema-like-8.toml");
    let mesh = |extra: &[&str]| {
        let mut a = vec![
            "workspace",
            r.as_str(),
            "--boundary",
            "mesh",
            "--grid",
            "6",
            "--criteria",
            "wrench-closure",
            "--json",
        ];
        a.extend_from_slice(extra);
        json(&a)
    };
    let constant = mesh(&[]);
    let one = mesh(&["--orientations", "euler:rz=0"]);
    assert_eq!(one["method"], "mesh");
    assert_eq!(one["watertight"], true);
    let v = |j: &serde_json::Value| j["volume"].as_f64().unwrap();
    assert!(
        (v(&one) - v(&constant)).abs() <= 1e-9 * v(&constant),
        "{one}"
    );
    let total = mesh(&["--orientations", "euler:rz=-3..3,n=3"]);
    let maximal = mesh(&["--orientations", "euler:rz=-3..3,n=3", "--kind", "maximal"]);
    assert!(v(&total) <= v(&constant) + 1e-9 && v(&constant) <= v(&maximal) + 1e-9);
    assert!(v(&total) < v(&maximal), "{total} {maximal}");
    assert!(!total["limiting_summary"].as_array().unwrap().is_empty());
}
