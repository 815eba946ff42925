//! `cdpr isotropic` and `cdpr capacity`: the JSON contract and values derived by hand for
//! Krut, Company & Pierrot's (2004) regular robots (motors at 1000 mm, tensions in [50, 500] N).

use crate::common;

use common::{cdpr, json, robot};

fn f(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// At the centre of the 3-motor robot the cables' free tension ranges s_i ∈ [−225, 225] (about
/// the 275 N pretension) make the AWS a regular hexagon with apothem 225·√3 ≈ 389.71 N
/// (Krut, Company & Pierrot 2004, §IV-B); its largest centred ellipse is the inscribed circle.
#[test]
fn isotropic_force_at_the_centre_of_krut_3() {
    let v = json(&[
        "isotropic",
        &robot("krut-3.toml"),
        "--pose",
        "0,0",
        "--ellipse",
        "--json",
    ]);
    let expected = 225.0 * 3f64.sqrt();
    // The robot file rounds the anchors to 1e-6 mm: agreement to 1e-6 relative.
    assert!((f(&v["isotropic_force"]) - expected).abs() < 1e-6 * expected);
    assert!((f(&v["wrench_radius"]) - expected).abs() < 1e-6 * expected);
    assert!(v["definition"].as_str().unwrap().contains("eq. 19"));
    assert_eq!(v["facets"], 6);
    assert_eq!(v["vertices"].as_array().unwrap().len(), 6);
    let e = &v["ellipse"];
    for a in e["semi_axes"].as_array().unwrap() {
        assert!((f(a) - expected).abs() < 1e-5 * expected, "{a}");
    }
    let area = std::f64::consts::PI * expected * expected;
    assert!((f(&e["area"]) - area).abs() < 1e-5 * area);
}

#[test]
fn planar_index_is_the_force_at_zero_moment() {
    let v = json(&[
        "isotropic",
        &robot("tdpm-4.toml"),
        "--pose",
        "0,0,0",
        "--json",
    ]);
    assert!(v["definition"].as_str().unwrap().contains("zero moment"));
    // The zero-moment force ball lies inside the full wrench ball's slice, so it is at least
    // as large as the wrench radius (the slice of a ball of radius r has radius r).
    assert!(f(&v["isotropic_force"]) >= f(&v["wrench_radius"]) - 1e-9);
    assert!(!v["vertices"].as_array().unwrap().is_empty()); // DOF 3: vertices in (f_x, f_y, m)
}

/// 4 motors at 90° steps: the AWS is a square of half-width 2·225 = 450 N at the centre; the
/// corners of the frame's bounding box are outside the workspace (negative index).
#[test]
fn grid_json_of_krut_4() {
    let v = json(&["isotropic", &robot("krut-4.toml"), "--grid", "4", "--json"]);
    let g = &v["grid"];
    assert_eq!(g["shape"], serde_json::json!([5, 5]));
    let rows = g["values"].as_array().unwrap();
    assert_eq!(rows.len(), 5);
    assert!((f(&rows[2][2]) - 450.0).abs() < 1e-6);
    assert!(f(&rows[0][0]) < 0.0 && f(&rows[4][4]) < 0.0);
    let s = &v["stats"];
    assert!((f(&s["max"]) - 450.0).abs() < 1e-6);
    assert!((f(&s["centre"]) - 450.0).abs() < 1e-6);
    assert!(f(&s["argmax"][0]).abs() < 1e-9 && f(&s["argmax"][1]).abs() < 1e-9);
    assert!(f(&s["min"]) < 0.0);
    let frac = f(&s["positive_fraction"]);
    assert!(frac > 0.0 && frac < 1.0);
    // --box: a square well inside the workspace is positive everywhere.
    let v = json(&[
        "isotropic",
        &robot("krut-4.toml"),
        "--grid",
        "2",
        "--box",
        "-0.1,0.1,-0.1,0.1",
        "--json",
    ]);
    assert_eq!(f(&v["stats"]["positive_fraction"]), 1.0);
    assert!((f(&v["grid"]["x"][0]) + 0.1).abs() < 1e-12);
}

#[test]
fn grid_heat_map_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("map.png");
    cdpr()
        .args([
            "isotropic",
            &robot("krut-3.toml"),
            "--grid",
            "30",
            "--plot",
            png.to_str().unwrap(),
        ])
        .assert()
        .success();
    assert!(std::fs::metadata(&png).unwrap().len() > 1000);
    // Spatial robot: a z slice.
    let v = json(&[
        "isotropic",
        &robot("ipanema-like-8.toml"),
        "--grid",
        "4",
        "--z",
        "1",
        "--json",
    ]);
    assert_eq!(f(&v["slice"]["z"]), 1.0);
    assert!(f(&v["stats"]["max"]) > 0.0);
}

/// `--pose --plot` draws Krut, Company & Pierrot 2004, Fig. 4 (force polygon, centred circle and ellipse) for point2
/// robots, in PNG and SVG, without changing the JSON; other robots get a clear error.
#[test]
fn force_polygon_plot_is_written_for_point2_robots_only() {
    let dir = tempfile::tempdir().unwrap();
    let k3 = robot("krut-3.toml");
    for ext in ["png", "svg"] {
        let file = dir.path().join(format!("polygon.{ext}"));
        let v = json(&[
            "isotropic",
            &k3,
            "--pose",
            "0.3,-0.2",
            "--plot",
            file.to_str().unwrap(),
            "--json",
        ]);
        assert!(
            v.get("ellipse").is_none(),
            "--plot must not add JSON fields"
        );
        assert!(f(&v["isotropic_force"]) > 0.0);
        assert!(std::fs::metadata(&file).unwrap().len() > 5000, "{ext}");
    }
    let svg = std::fs::read_to_string(dir.path().join("polygon.svg")).unwrap();
    for text in [
        "available force polygon",
        "largest centred circle",
        "largest centred ellipse",
        "touching the circle",
    ] {
        assert!(svg.contains(text), "{text} missing from the SVG");
    }
    let out = cdpr()
        .args([
            "isotropic",
            &robot("tdpm-4.toml"),
            "--pose",
            "0,0,0",
            "--plot",
            dir.path().join("planar.png").to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("point2") && err.contains("planar"), "{err}");
    assert!(!dir.path().join("planar.png").exists());
}

/// krut-4 at the centre: facets at 450 N with normals at 30°, 120°, 210°, 300°. A box of
/// external forces x ∈ [90, 110], y = 0 must be balanced by pulling towards −x: the facet with
/// normal (cos 210°, sin 210°) limits, margin 450 − 110·cos 30° = 354.737 N.
#[test]
fn capacity_margin_of_a_box_by_hand() {
    let v = json(&[
        "capacity",
        &robot("krut-4.toml"),
        "--pose",
        "0,0",
        "--wrench",
        "100,0",
        "--wrench-box",
        "10,0",
        "--json",
    ]);
    let expected = 450.0 - 110.0 * 30f64.to_radians().cos();
    assert!((f(&v["capacity_margin"]) - expected).abs() < 1e-6);
    assert_eq!(v["feasible"], true);
    let n = &v["limiting_facet"]["normal"];
    assert!((f(&n[0]) - 210f64.to_radians().cos()).abs() < 1e-9);
    assert!((f(&n[1]) - 210f64.to_radians().sin()).abs() < 1e-9);
    assert_eq!(v["required"]["shape"], "box");
}

/// A ball of radius ρ around zero: margin = 225√3 − ρ; beyond the isotropic force it is
/// infeasible, which is an answer (exit 0), not an error.
#[test]
fn capacity_margin_of_a_ball_and_infeasibility() {
    let iso = 225.0 * 3f64.sqrt();
    for rho in [100.0, 400.0] {
        let v = json(&[
            "capacity",
            &robot("krut-3.toml"),
            "--pose",
            "0,0",
            "--wrench-ball",
            &rho.to_string(),
            "--json",
        ]);
        assert!((f(&v["capacity_margin"]) - (iso - rho)).abs() < 1e-5);
        assert_eq!(v["feasible"], rho < iso);
        assert_eq!(f(&v["required"]["radius"]), rho);
    }
}

#[test]
fn bad_arguments_are_errors() {
    let fail = |args: &[&str]| {
        let out = cdpr().args(args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        String::from_utf8_lossy(&out.stderr).to_string()
    };
    let k3 = robot("krut-3.toml");
    fail(&["isotropic", &k3, "--pose", "0,0", "--grid", "4"]);
    fail(&["isotropic", &k3]);
    assert!(
        fail(&[
            "isotropic",
            &robot("tdpm-4.toml"),
            "--pose",
            "0,0,0",
            "--ellipse"
        ])
        .contains("point2")
    );
    assert!(fail(&["isotropic", &k3, "--grid", "4", "--box", "1,0,0,1"]).contains("empty"));
    assert!(
        fail(&["capacity", &k3, "--pose", "0,0", "--wrench-box", "1,2,3"]).contains("half-widths")
    );
    assert!(fail(&["capacity", &k3, "--pose", "0,0", "--wrench-ball", "-1"]).contains("radius"));
    fail(&[
        "capacity",
        &k3,
        "--pose",
        "0,0",
        "--wrench-ball",
        "1",
        "--wrench-box",
        "1,1",
    ]);
}

/// `isotropic --grid` on a 3-D robot maps one horizontal slice: the text says at which height
/// (the frame's mid-height by default, `--z` otherwise), as the JSON's `slice.z` does; planar
/// robots print no height (issue 25).
#[test]
fn grid_text_of_a_3d_robot_names_its_height() {
    let text = |args: &[&str]| {
        let out = cdpr().args(args).output().unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).unwrap()
    };
    let r8 = robot("ipanema-like-8.toml");
    let z = f(&json(&["isotropic", &r8, "--grid", "2", "--json"])["slice"]["z"]);
    let first = text(&["isotropic", &r8, "--grid", "2"]);
    let first = first.lines().next().unwrap();
    let printed: f64 = first
        .split(" at z = ")
        .nth(1)
        .and_then(|rest| rest.split(" m, 3 × 3 points").next())
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("no height in `{first}`"));
    // nine significant digits, as every number the CLI prints
    assert!(
        (printed - z).abs() <= 1e-8 * z.abs().max(1.0),
        "{first} (z = {z})"
    );
    let out = text(&["isotropic", &r8, "--grid", "2", "--z", "0.25"]);
    assert!(out.contains(" at z = 0.25 m, 3 × 3 points"), "{out}");
    let planar = text(&["isotropic", &robot("krut-4.toml"), "--grid", "2"]);
    assert!(!planar.contains("at z ="), "{planar}");
}

/// `faces`, `normals`, `offsets` of a point3 robot's force polytope (JSON): every vertex
/// satisfies every face inequality n · v ≤ d, each face's vertices lie on it, faces turn
/// counter-clockwise seen from outside, and V − E + F = 2. For the krut-3 hexagon the faces
/// are its six edges.
#[test]
fn polytope_faces_normals_and_offsets_in_json() {
    let v = json(&[
        "isotropic",
        &robot("hangprinter-v4.toml"),
        "--pose",
        "0,0,0.5",
        "--json",
    ]);
    let pts: Vec<[f64; 3]> = v["vertices"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| [0, 1, 2].map(|k| f(&p[k])))
        .collect();
    let faces = v["faces"].as_array().unwrap();
    let (normals, offsets) = (
        v["normals"].as_array().unwrap(),
        v["offsets"].as_array().unwrap(),
    );
    assert_eq!((faces.len(), normals.len()), (offsets.len(), offsets.len()));
    let tol = 1e-7 * 100.0;
    let mut edges = 0;
    for ((face, n), d) in faces.iter().zip(normals).zip(offsets) {
        let n = [0, 1, 2].map(|k| f(&n[k]));
        let d = f(d);
        let dot = |p: &[f64; 3]| n[0] * p[0] + n[1] * p[1] + n[2] * p[2];
        for p in &pts {
            assert!(dot(p) <= d + tol);
        }
        let idx: Vec<usize> = face
            .as_array()
            .unwrap()
            .iter()
            .map(|i| i.as_u64().unwrap() as usize)
            .collect();
        edges += idx.len();
        for i in &idx {
            assert!((dot(&pts[*i]) - d).abs() <= tol);
        }
        let [a, b, c] = [0, 1, 2].map(|k| pts[idx[k]]);
        let (u, w) = (
            [0, 1, 2].map(|k| b[k] - a[k]),
            [0, 1, 2].map(|k| c[k] - a[k]),
        );
        let cross = [
            u[1] * w[2] - u[2] * w[1],
            u[2] * w[0] - u[0] * w[2],
            u[0] * w[1] - u[1] * w[0],
        ];
        assert!(
            dot(&cross) > 0.0,
            "face {idx:?} is clockwise seen from outside"
        );
    }
    assert_eq!(pts.len() as i64 - edges as i64 / 2 + faces.len() as i64, 2);
    assert_eq!(faces.len(), 12); // 4 generators: a zonotope with 4·3 faces
    let k3 = json(&[
        "isotropic",
        &robot("krut-3.toml"),
        "--pose",
        "0,0",
        "--json",
    ]);
    assert_eq!(k3["faces"].as_array().unwrap().len(), 6);
    assert_eq!(k3["faces"][0].as_array().unwrap().len(), 2);
}

/// `--plot X.html` with a point3 robot writes the polytope view (no robot, axes in N, the
/// ball); a point2 robot asks for .png/.svg, a planar one is refused.
#[test]
fn polytope_view_of_a_point3_robot() {
    let dir = tempfile::tempdir().unwrap();
    let page = dir.path().join("poly.html");
    let out = cdpr()
        .args([
            "isotropic",
            &robot("hangprinter-v4.toml"),
            "--pose",
            "0,0,0.5",
            "--plot",
        ])
        .arg(&page)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let html = std::fs::read_to_string(&page).unwrap();
    for s in [
        "\"units\":\"N\"",
        "\"ball\":{\"centre\":[",
        "\"hideBox\":true",
        "\"anchors\":[]",
    ] {
        assert!(html.contains(s), "{s}");
    }
    for (r, pose) in [("krut-3.toml", "0,0"), ("tdpm-4.toml", "0,0,0")] {
        let out = cdpr()
            .args(["isotropic", &robot(r), "--pose", pose, "--plot"])
            .arg(&page)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{r}");
    }
}

/// A suspended robot's isotropic map lies, by default, at the middle height of its default
/// region (issue 25's audit): spidercam-like-4's anchors are all at z = 30 m on a 100 m × 70 m
/// frame, so the region reaches 50 m below them and the slice is at 30 − 25 = 5 m, where the
/// hanging camera has positive isotropic force; at the anchors' own height (the old default)
/// nothing is reachable.
#[test]
fn a_suspended_robot_is_mapped_below_its_anchors() {
    let file = robot("spidercam-like-4.toml");
    let map = json(&["isotropic", &file, "--grid", "5", "--json"]);
    assert_eq!(f(&map["slice"]["z"]), 5.0);
    assert!(
        f(&map["stats"]["positive_fraction"]) > 0.0,
        "{}",
        map["stats"]
    );
    let at_anchors = json(&["isotropic", &file, "--grid", "5", "--z", "30", "--json"]);
    assert_eq!(f(&at_anchors["stats"]["positive_fraction"]), 0.0);
    // Robots whose anchors span their height keep the middle of the anchors (z ∈ {0, 2} m).
    let ipanema = json(&[
        "isotropic",
        &robot("ipanema-like-8.toml"),
        "--grid",
        "3",
        "--json",
    ]);
    assert_eq!(f(&ipanema["slice"]["z"]), 1.0);
}
