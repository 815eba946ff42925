//! The `cdpr` binary: output formats, exit codes, error messages.

mod common;

use common::{cdpr, robot};

#[test]
fn kinematics_json_has_the_contract_fields() {
    let out = cdpr()
        .args([
            "kinematics",
            &robot("tdpm-4.toml"),
            "--pose",
            "-0.5,0.2,0",
            "--json",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["lengths"].as_array().unwrap().len(), 4);
    assert_eq!(v["unit_vectors"].as_array().unwrap().len(), 4);
    assert_eq!(v["unit_vectors"][0].as_array().unwrap().len(), 2);
    let w = v["wrench_matrix"].as_array().unwrap();
    assert_eq!(w.len(), 3);
    assert_eq!(w[0].as_array().unwrap().len(), 4);
    // Cable 1 at (−0.5, 0.2, 0): ℓ = (1 − 0.5 − s... ) checked against the unit vector.
    let (ux, uy) = (
        v["unit_vectors"][0][0].as_f64().unwrap(),
        v["unit_vectors"][0][1].as_f64().unwrap(),
    );
    assert!((ux * ux + uy * uy - 1.0).abs() < 1e-12);
    assert_eq!(w[0][0].as_f64().unwrap(), ux);
}

#[test]
fn kinematics_table_output() {
    let out = cdpr()
        .args([
            "kinematics",
            &robot("ipanema-like-8.toml"),
            "--pose",
            "0,0,1,0,0,0.1",
        ])
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("wrench matrix W"), "{text}");
}

#[test]
fn bad_input_exits_2_with_a_message() {
    let out = cdpr()
        .args(["kinematics", &robot("tdpm-4.toml"), "--pose", "0,0"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("needs 3"));
    let out = cdpr()
        .args(["kinematics", &robot("tdpm-4.toml"), "--pose", "0,x,0"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let out = cdpr()
        .args(["kinematics", "/nonexistent.toml", "--pose", "0,0,0"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    // A pose that puts the platform attachment of cable 1 on its anchor: degenerate cable.
    let s = 0.0707106781; // ā¹ as written in the file
    let pose = format!("{},{},0", 1.0 - s, 0.5 - s);
    let out = cdpr()
        .args(["kinematics", &robot("tdpm-4.toml"), "--pose", &pose])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("zero length"));
}

#[test]
fn stiffness_json() {
    let out = cdpr()
        .args([
            "stiffness",
            &robot("ipanema-like-8.toml"),
            "--pose",
            "0,0,1,0,0,0",
            "--tensions",
            "100,100,100,100,100,100,100,100",
            "--json",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["stiffness"].as_array().unwrap().len(), 6);
    let out = cdpr()
        .args([
            "stiffness",
            &robot("tdpm-4.toml"),
            "--pose",
            "0,0,0",
            "--tensions",
            "1,1,1,1",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "no axial stiffness in the file");
}

#[test]
fn tension_json_contract_and_infeasible_is_success() {
    let run = |args: &[&str]| {
        let out = cdpr().args(args).output().unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_slice::<serde_json::Value>(&out.stdout).unwrap()
    };
    let v = run(&[
        "tension",
        &robot("tdpm-4.toml"),
        "--pose",
        "0.1,-0.2,0",
        "--wrench",
        "0,-10,0",
        "--method",
        "closed-form",
        "--json",
    ]);
    assert_eq!(v["feasible"], true);
    assert_eq!(v["method"], "closed-form");
    assert!(v["reason"].is_null());
    let t: Vec<f64> = v["tensions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_eq!(t.len(), 4);
    assert!(t.iter().all(|&x| (5.0 - 1e-9..=100.0 + 1e-9).contains(&x)));
    assert!(v["residual"].as_f64().unwrap() < 1e-9);
    // Pinv at the same pose needs a negative tension: infeasible, with a reason, exit code 0.
    let v = run(&[
        "tension",
        &robot("tdpm-4.toml"),
        "--pose",
        "0.1,-0.2,0",
        "--wrench",
        "0,-10,0",
        "--method",
        "pinv",
        "--json",
    ]);
    assert_eq!(v["feasible"], false);
    assert!(v["tensions"].is_null());
    assert!(v["reason"].as_str().unwrap().contains("cable"));
    // Barycentre on the 8-cable robot also reports the feasible polygon.
    let v = run(&[
        "tension",
        &robot("ipanema-like-8.toml"),
        "--pose",
        "0,0,1,0,0,0",
        "--method",
        "barycenter",
        "--json",
    ]);
    assert_eq!(v["feasible"], true);
    assert!(v["polygon"]["vertices_lambda"].as_array().unwrap().len() >= 3);
    let v = run(&[
        "tension",
        &robot("ipanema-like-8.toml"),
        "--pose",
        "0,0,1,0,0,0",
        "--wrench",
        "0,50,0,0,0,0",
        "--method",
        "sotda",
        "--nu",
        "0.5",
        "--json",
    ]);
    assert_eq!(v["feasible"], true);
    assert!(v["displacement"].as_f64().unwrap() > 0.0);
    assert_eq!(v["sotda_search"], "corners");
    // The three searches are nested (corners ⊂ vertices ⊂ full): the displacement never grows.
    let sotda = |extra: &[&str]| {
        let mut args = vec![
            "tension".to_string(),
            robot("ipanema-like-8.toml"),
            "--pose".into(),
            "0,0,1,0,0,0".into(),
            "--wrench".into(),
            "0,50,0,0,0,0".into(),
            "--method".into(),
            "sotda".into(),
            "--json".into(),
        ];
        args.extend(extra.iter().map(|s| s.to_string()));
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let v = run(&args);
        (
            v["displacement"].as_f64().unwrap(),
            v["sotda_search"].as_str().unwrap().to_string(),
        )
    };
    let (corners, name_c) = sotda(&[]);
    let (vertices, name_v) = sotda(&["--sotda-search", "vertices"]);
    let (full, name_f) = sotda(&["--sotda-search", "full"]);
    let (full_alias, name_a) = sotda(&["--full"]);
    assert_eq!((name_c.as_str(), name_v.as_str()), ("corners", "vertices"));
    assert_eq!((name_f.as_str(), name_a.as_str()), ("full", "full"));
    assert!(
        vertices <= corners * (1.0 + 1e-12),
        "{vertices} > {corners}"
    );
    assert!(full <= vertices * (1.0 + 1e-9), "{full} > {vertices}");
    assert_eq!(full, full_alias);
    // --full and --sotda-search together are refused.
    let out = cdpr()
        .args([
            "tension",
            &robot("ipanema-like-8.toml"),
            "--pose",
            "0,0,1,0,0,0",
            "--method",
            "sotda",
            "--full",
            "--sotda-search",
            "vertices",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn tension_bad_method_exits_2() {
    let out = cdpr()
        .args([
            "tension",
            &robot("tdpm-4.toml"),
            "--pose",
            "0,0,0",
            "--method",
            "simplex",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}
