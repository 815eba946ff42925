//! `cdpr workspace --boundary mesh`, `--mesh`, `--points` and `--section`: JSON contract, a
//! hand-computed volume, files, usage errors.

use crate::common;

use common::{cdpr, json, robot};
use serde_json::Value;
use std::path::Path;

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap()
}

/// A point robot with four cables to the corners of the tetrahedron (0,0,0), (4,0,0), (0,4,0),
/// (0,0,4): its wrench-closure workspace is the open tetrahedron.
fn tetra_file(dir: &Path) -> String {
    let mut text =
        String::from("name = \"tetra\"\nmotion = \"point3\"\n[tension]\nmin = 1.0\nmax = 10.0\n");
    for c in [
        [0.0, 0.0, 0.0],
        [4.0, 0.0, 0.0],
        [0.0, 4.0, 0.0],
        [0.0, 0.0, 4.0],
    ] {
        text.push_str(&format!(
            "[[cables]]\nframe = [{}, {}, {}]\n",
            c[0], c[1], c[2]
        ));
    }
    let path = dir.join("tetra.toml");
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

/// In the box [0.5, 1.5]³ only the face x + y + z = 4 of the tetrahedron passes: the workspace
/// is the box minus the corner simplex x + y + z > 4 at (1.5, 1.5, 1.5), legs 0.5, so
/// V = 1 − 0.5³/6 exactly; the mesh finds it to 1e-6 at any M, the grid count does not.
#[test]
fn mesh_volume_of_a_box_clipped_tetrahedron_is_exact() {
    let dir = tempfile::tempdir().unwrap();
    let file = tetra_file(dir.path());
    let exact = 1.0 - 0.125 / 6.0;
    for m in ["5", "12"] {
        let v = json(&[
            "workspace",
            &file,
            "--boundary",
            "mesh",
            "--criteria",
            "wrench-closure",
            "--box",
            "0.5,1.5,0.5,1.5,0.5,1.5",
            "--grid",
            m,
            "--json",
        ]);
        assert!(
            (f(&v["volume"]) - exact).abs() < 1e-6 * exact,
            "m = {m}: {}",
            v["volume"]
        );
        assert_eq!(v["grid_volume"], v["area"]);
        assert!((f(&v["grid_volume"]) - exact).abs() > 1e-3);
        assert_eq!(v["watertight"], true);
        assert_eq!(v["components"], 1);
        for face in ["x_min", "x_max", "y_min", "y_max", "z_min", "z_max"] {
            assert_eq!(v["box_faces_reached"][face], true, "{face}");
        }
        let nv = v["vertices"].as_array().unwrap().len();
        let tris = v["triangles"].as_array().unwrap();
        assert!(
            tris.iter()
                .flat_map(|t| t.as_array().unwrap())
                .all(|i| (i.as_u64().unwrap() as usize) < nv)
        );
        // Box area 6 minus the three corner triangles (legs 0.5) plus the cut triangle (side 0.5√2).
        let area = 6.0 - 3.0 * 0.125 + 3f64.sqrt() / 4.0 * 0.5;
        assert!(
            (f(&v["surface_area"]) - area).abs() < 1e-6,
            "{}",
            v["surface_area"]
        );
    }
}

/// The 8-cable robot with gravity: contract fields, files written and readable.
#[test]
fn ipanema_mesh_json_and_files() {
    let dir = tempfile::tempdir().unwrap();
    let stl = dir.path().join("ws.stl");
    let ply = dir.path().join("ws.ply");
    let csv = dir.path().join("ws.csv");
    let r = robot("ipanema-like-8.toml");
    let v = json(&[
        "workspace",
        &r,
        "--boundary",
        "mesh",
        "--grid",
        "8",
        "--mesh",
        stl.to_str().unwrap(),
        "--points",
        csv.to_str().unwrap(),
        "--json",
    ]);
    for key in [
        "volume",
        "grid_volume",
        "surface_area",
        "components",
        "vertices",
        "triangles",
        "area",
        "feasible_points",
        "total_points",
        "cell_area",
        "resolution",
        "box",
    ] {
        assert!(!v[key].is_null(), "{key}");
    }
    assert_eq!(v["method"], "mesh");
    assert_eq!(v["total_points"], 729);
    let nt = v["triangles"].as_array().unwrap().len();
    let bytes = std::fs::read(&stl).unwrap();
    assert_eq!(bytes.len(), 84 + 50 * nt);
    let text = std::fs::read_to_string(&csv).unwrap();
    assert_eq!(text.lines().next(), Some("x (m),y (m),z (m),feasible"));
    assert_eq!(text.lines().count(), 730);
    let ones = text.lines().skip(1).filter(|l| l.ends_with(",1")).count();
    assert_eq!(ones as u64, v["feasible_points"].as_u64().unwrap());
    json(&[
        "workspace",
        &r,
        "--boundary",
        "mesh",
        "--grid",
        "6",
        "--mesh",
        ply.to_str().unwrap(),
        "--json",
    ]);
    let ply = std::fs::read_to_string(&ply).unwrap();
    assert!(ply.starts_with("ply\nformat ascii 1.0\n") && ply.contains("property double nx"));
    // Text output carries units.
    let out = cdpr()
        .args(["workspace", &r, "--boundary", "mesh", "--grid", "6"])
        .output()
        .unwrap();
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.contains(" m³") && text.contains(" m²") && text.contains("box faces reached"),
        "{text}"
    );
}

/// The section z = 1 of the 8-cable robot by the chord method, with its plot; its area agrees
/// with the z = 1 layer of the grid.
#[test]
fn section_by_the_chord_method() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("section.png");
    let r = robot("ipanema-like-8.toml");
    let v = json(&[
        "workspace",
        &r,
        "--section",
        "z=1",
        "--plot",
        png.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(v["section"]["axis"], "z");
    assert_eq!(v["section"]["plane_axes"], serde_json::json!(["x", "y"]));
    let area = f(&v["area"]);
    // The grid layer z = 1 (m = 40) counted with the same verdicts.
    let csv = dir.path().join("g.csv");
    json(&[
        "workspace",
        &r,
        "--grid",
        "40",
        "--points",
        csv.to_str().unwrap(),
        "--json",
    ]);
    let text = std::fs::read_to_string(&csv).unwrap();
    let layer = text
        .lines()
        .skip(1)
        .filter(|l| l.split(',').nth(2) == Some("1") && l.ends_with(",1"))
        .count();
    let grid_area = layer as f64 * (4.0 / 40.0) * (3.0 / 40.0);
    assert!(
        (area - grid_area).abs() < 0.05 * area,
        "{area} vs {grid_area}"
    );
    assert!(std::fs::metadata(&png).unwrap().len() > 1000);
}

#[test]
fn usage_errors() {
    let fails = |args: &[&str]| {
        let out = cdpr().args(args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?} should fail");
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    let planar = robot("tdpm-4.toml");
    let spatial = robot("ipanema-like-8.toml");
    let err = fails(&["workspace", &planar, "--boundary", "mesh"]);
    assert!(err.contains("--boundary chord"), "{err}");
    let err = fails(&["workspace", &planar, "--section", "z=0"]);
    assert!(err.contains("chord"), "{err}");
    let err = fails(&["workspace", &spatial, "--mesh", "a.stl"]);
    assert!(err.contains("--boundary mesh"), "{err}");
    let err = fails(&[
        "workspace",
        &spatial,
        "--boundary",
        "mesh",
        "--mesh",
        "a.vtk",
    ]);
    assert!(err.contains(".stl"), "{err}");
    let err = fails(&["workspace", &spatial, "--section", "w=1"]);
    assert!(err.contains("axis"), "{err}");
    let err = fails(&["workspace", &spatial, "--section", "z=7"]);
    assert!(err.contains("outside the box"), "{err}");
    let err = fails(&[
        "workspace",
        &spatial,
        "--section",
        "z=1",
        "--points",
        "p.csv",
    ]);
    assert!(err.contains("--points"), "{err}");
}

/// `--boundary mesh --plot`: the figure shows the certified surface (the mesh's own label), as an
/// interactive page for .html and as an isometric view with sections for .png.
#[test]
fn mesh_plots_draw_the_boundary_mesh() {
    let dir = tempfile::tempdir().unwrap();
    let file = tetra_file(dir.path());
    for name in ["ws.html", "ws.svg"] {
        let out = dir.path().join(name);
        let o = out.display().to_string();
        let run = cdpr()
            .args([
                "workspace",
                file.as_str(),
                "--boundary",
                "mesh",
                "--criteria",
                "wrench-closure",
                "--box",
                "0.5,1.5,0.5,1.5,0.5,1.5",
                "--grid",
                "6",
                "--plot",
                o.as_str(),
            ])
            .output()
            .unwrap();
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        let text = std::fs::read_to_string(&out).unwrap();
        assert!(
            text.contains("boundary mesh (vertices within 5.0e-9 m of the boundary"),
            "{name}"
        );
    }
}

/// The text header of a point robot's mesh prints no empty orientation and its w_ext as every
/// command prints numbers (`num`: round-off trimmed) with units (issue 25: `orientation []`, `w_ext [0.0, 0.0,
/// -49.033249999999995]`).
#[test]
fn mesh_text_header_prints_numbers_as_the_other_commands() {
    let dir = tempfile::tempdir().unwrap();
    let file = tetra_file(dir.path());
    let out = cdpr()
        .args([
            "workspace",
            &file,
            "--boundary",
            "mesh",
            "--criteria",
            "wrench-closure",
            "--box",
            "0.5,1.5,0.5,1.5,0.5,1.5",
            "--grid",
            "4",
            "--wrench",
            "0,0,-49.033249999999995",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let header = text.lines().next().unwrap();
    assert!(
        header.ends_with(
            "boundary mesh of the constant-orientation workspace, w_ext [0 N, 0 N, -49.03325 N]"
        ),
        "{header}"
    );
    assert!(!text.contains("[]") && !text.contains("999999"), "{text}");
}
