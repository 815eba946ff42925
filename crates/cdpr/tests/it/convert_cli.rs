//! The model-import contract on the command line: `cdpr kinematics` reads CASPR and WireCenter
//! files (with `--cable-set`), `cdpr convert` writes TOML and .wcrfx whose results are
//! identical, and errors name the file, line and element.

use crate::common;
use common::{cdpr, json};
use std::path::PathBuf;

fn data(rel: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../cdpr-io/tests/data")
        .join(rel)
        .display()
        .to_string()
}

fn tmp(name: &str) -> String {
    let dir = // Cargo's scratch directory for integration tests (target/tmp), reused by every run, so
    // that no run leaves a directory behind in the system's temporary directory.
    std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("convert_cli");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name).display().to_string()
}

#[test]
fn caspr_and_converted_toml_give_the_same_kinematics() {
    let caroca = data("caspr/spatial_manipulators/CAROCA/CAROCA_cables.xml");
    let out = tmp("caroca.toml");
    let pose = "0.1,-0.2,1.1,0.05,-0.02,0.1";
    let r = json(&[
        "convert",
        &caroca,
        "--cable-set",
        "with_rotating_pulleys",
        "-o",
        &out,
        "--json",
    ]);
    assert_eq!(r["cables"], 8);
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.contains("pulley = { radius = 0.045"), "{text}");
    assert!(text.contains("gravity = [0.0, 0.0, -9.81]"), "{text}");
    let a = json(&[
        "kinematics",
        &caroca,
        "--cable-set",
        "with_rotating_pulleys",
        "--pose",
        pose,
        "--json",
    ]);
    let b = json(&["kinematics", &out, "--pose", pose, "--json"]);
    assert_eq!(a["lengths"], b["lengths"]);
    assert_eq!(a["wrench_matrix"], b["wrench_matrix"]);
    // And through .wcrfx.
    let w = tmp("caroca.wcrfx");
    json(&["convert", &out, "-o", &w, "--json"]);
    let c = json(&["kinematics", &w, "--pose", pose, "--json"]);
    assert_eq!(a["lengths"], c["lengths"]);
    assert_eq!(a["wrench_matrix"], c["wrench_matrix"]);
}

#[test]
fn wcrfx_kinematics_and_tension_run() {
    let ipanema = data("wirecenter/IPAnema.wcrfx");
    // Straight cables: chain 1, base (-2, 1.5, 2), platform (-0.06, 0.06, 0), at (0, 0, 1).
    let k = json(&[
        "kinematics",
        &ipanema,
        "--pose",
        "0,0,1,0,0,0",
        "--kinematics",
        "standard",
        "--json",
    ]);
    let l0 = k["lengths"][0].as_f64().unwrap();
    assert!((l0 - (1.94f64.powi(2) + 1.44f64.powi(2) + 1.0).sqrt()).abs() < 1e-12);
    // The file's pulleys (radius 0.1 m, Q = I), Pott 2018: b = P - a = (1.94, -1.44, -1) in the
    // pulley frame, ρ = |b_xy|, BM = √((ρ - r)² + b_z²), free length l_f = √(BM² - r²), wrap
    // β = acos(l_f / BM) + acos(b_z / BM), l = β r + l_f.
    let k = json(&["kinematics", &ipanema, "--pose", "0,0,1,0,0,0", "--json"]);
    let l0 = k["lengths"][0].as_f64().unwrap();
    let (r, rho, bz) = (0.1f64, (1.94f64.powi(2) + 1.44f64.powi(2)).sqrt(), -1.0f64);
    let bm = ((rho - r).powi(2) + bz * bz).sqrt();
    let lf = (bm * bm - r * r).sqrt();
    let beta = (lf / bm).acos() + (bz / bm).acos();
    assert!(
        (l0 - (beta * r + lf)).abs() < 1e-9,
        "{l0} vs {}",
        beta * r + lf
    );
    let t = json(&["tension", &ipanema, "--pose", "0,0,1,0,0,0", "--json"]);
    assert!(t["feasible"].is_boolean(), "{t}");
}

#[test]
fn errors_name_file_line_and_element() {
    let vsd = data("caspr/planar_manipulators/2_DoF_VSD/2_DoF_VSD_cables.xml");
    let out = cdpr()
        .args(["kinematics", &vsd, "--pose", "0.2,0.3"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let msg = String::from_utf8_lossy(&out.stderr);
    assert!(
        msg.contains("2_DoF_VSD_cables.xml:5: <cable_vsd_torsion_spring>: not modelled"),
        "{msg}"
    );
    // The same file with its ideal-cable set reads.
    let k = json(&[
        "kinematics",
        &vsd,
        "--cable-set",
        "stiff",
        "--pose",
        "0.2,0.3",
        "--json",
    ]);
    assert_eq!(k["lengths"].as_array().unwrap().len(), 4);
    // --cable-set on a TOML robot is a usage error.
    let toml = common::robot("tdpm-4.toml");
    let out = cdpr()
        .args(["kinematics", &toml, "--cable-set", "a", "--pose", "0,0,0"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("CASPR models only"));
    // Writing CASPR is refused, as is a .wcrfx that cannot hold per-cable bounds.
    let nist = data("caspr/spatial_manipulators/NIST_ROBOCRANE/NIST_RoboCrane_cables.xml");
    let out = cdpr()
        .args(["convert", &nist, "-o", &tmp("nist.wcrfx")])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("per-cable tension bounds differ"));
}

/// 2DIPAnema2 declares 3R3T (spatial, 6 DOF) for 4 cables: `kinematics` gives its lengths and
/// the 6 × 4 W; the analyses that balance a wrench exit 2 naming n and DOF.
#[test]
fn fewer_cables_than_dof_kinematics_works_analyses_refuse() {
    let robot = data("wirecenter/2DIPAnema2.wcrfx");
    let pose = "0.01,-0.02,0,0,0,0.1";
    let r = json(&["kinematics", &robot, "--pose", pose, "--json"]);
    assert_eq!(r["lengths"].as_array().unwrap().len(), 4);
    let w = r["wrench_matrix"].as_array().unwrap();
    assert_eq!((w.len(), w[0].as_array().unwrap().len()), (6, 4));
    for args in [
        vec!["tension", robot.as_str(), "--pose", pose],
        vec![
            "capacity",
            robot.as_str(),
            "--pose",
            pose,
            "--wrench-ball",
            "1",
        ],
        vec!["isotropic", robot.as_str(), "--pose", pose],
        vec!["workspace", robot.as_str(), "--grid", "3"],
    ] {
        let out = cdpr().args(&args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains("needs at least as many cables as degrees of freedom (n ≥ DOF); this spatial robot has n = 4 cables for DOF = 6"),
            "{args:?}: {err}"
        );
    }
}

/// CASPR's Passive_springs_planar: `kinematics` reports the springs' lengths, forces
/// K (l − l0) and wrench; `tension` balances weight + springs (its `external_wrench` is their
/// sum and W t + w_ext = 0); the converted TOML keeps the springs and gives the same tensions;
/// analyses that keep one wrench over many poses refuse by name.
#[test]
fn passive_springs_enter_the_external_wrench_pose_by_pose() {
    let model =
        data("caspr/planar_manipulators/Passive_springs_planar/Passive_springs_planar_cables.xml");
    let pose = "0.2,-0.1,0.3";
    let k = json(&["kinematics", &model, "--pose", pose, "--json"]);
    let springs = &k["passive_springs"];
    let (lengths, forces) = (
        springs["lengths"].as_array().unwrap(),
        springs["forces"].as_array().unwrap(),
    );
    assert_eq!(lengths.len(), 4);
    for (l, f) in lengths.iter().zip(forces) {
        let (l, f) = (l.as_f64().unwrap(), f.as_f64().unwrap());
        assert!(
            (f - 5.0 * (l - 1.0)).abs() < 1e-12,
            "K = 5 N/m, l0 = 1 m: {f} vs {l}"
        );
    }
    let ws: Vec<f64> = springs["wrench"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let t = json(&["tension", &model, "--pose", pose, "--json"]);
    let w_ext: Vec<f64> = t["external_wrench"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    // Weight 3 kg × 9.81 m/s² along −y (CASPR's −z in this vertical plane), at the joint.
    let weight = [0.0, -3.0 * 9.81, 0.0];
    for i in 0..3 {
        assert!((w_ext[i] - (weight[i] + ws[i])).abs() < 1e-12, "{w_ext:?}");
    }
    let tensions: Vec<f64> = t["tensions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let w = k["wrench_matrix"].as_array().unwrap();
    for (r, row) in w.iter().enumerate() {
        let wt: f64 = row
            .as_array()
            .unwrap()
            .iter()
            .zip(&tensions)
            .map(|(a, t)| a.as_f64().unwrap() * t)
            .sum();
        assert!((wt + w_ext[r]).abs() < 1e-9, "row {r}: {wt} + {}", w_ext[r]);
    }
    // Converted: the same tensions.
    let out = tmp("passive-springs.toml");
    json(&["convert", &model, "-o", &out, "--json"]);
    assert!(
        std::fs::read_to_string(&out)
            .unwrap()
            .contains("[[passive_springs]]")
    );
    let t2 = json(&["tension", &out, "--pose", pose, "--json"]);
    assert_eq!(t2["tensions"], t["tensions"]);
    assert_eq!(t2["external_wrench"], t["external_wrench"]);
    // One wrench over a grid, or the cables' stiffness alone: refused by name.
    for args in [
        vec!["workspace", model.as_str(), "--grid", "3"],
        vec![
            "stiffness",
            model.as_str(),
            "--pose",
            pose,
            "--tensions",
            "1,1,1,1",
        ],
    ] {
        let o = cdpr().args(&args).output().unwrap();
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains("4 passive spring(s)"), "{args:?}: {err}");
    }
}
