//! The `cdpr` binary: output formats, exit codes, error messages.

use crate::common;

use common::{cdpr, json, robot};

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
    assert!(String::from_utf8_lossy(&out.stderr).contains("cable 1 has zero length"));
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
    // The minimum-norm solution itself (issue 13: it balances the wrench, breaks a bound).
    assert_eq!(v["tensions"].as_array().unwrap().len(), 4);
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

/// Runs a command that must fail with exit code 2 and returns its stderr.
fn stderr_of_failure(args: &[&str]) -> String {
    let out = cdpr().args(args).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    err
}

/// Issue 13 §2: negative numbers reach the program and are rejected by the option's name (not
/// clap's "unexpected argument '-0' found"); --box names the axis; an overflowing coordinate
/// is not "zero length"; a plot in a missing folder says so; --chord 1e-7 blames no tolerance.
#[test]
fn messages_a_person_understands() {
    let tdpm = robot("tdpm-4.toml");
    for (args, wanted) in [
        (
            vec!["workspace", &tdpm, "--boundary", "chord", "--chord", "-0.1"],
            "'--chord <CHORD>': must be a finite number > 0",
        ),
        (
            vec![
                "tension", &tdpm, "--pose", "0,0,0", "--method", "sotda", "--nu", "-0.5",
            ],
            "'--nu <NU>': must lie in [0, 1]",
        ),
        (
            vec!["workspace", &tdpm, "--grid", "-5"],
            "'--grid <M>': must be a whole number ≥ 1",
        ),
        (
            vec!["workspace", &tdpm, "--box", "1,-1,-1,1"],
            "--box: along x, XMIN = 1 m must be less than XMAX = -1 m",
        ),
        (
            vec!["kinematics", &tdpm, "--pose", "1e155,0,0"],
            "cable 1: its length at this pose is not a finite number",
        ),
        (
            vec![
                "workspace",
                &tdpm,
                "--grid",
                "2",
                "--plot",
                "/no/such/dir/x.png",
            ],
            "cannot write /no/such/dir/x.png: no such directory",
        ),
    ] {
        let err = stderr_of_failure(&args);
        assert!(err.contains(wanted), "{args:?}: {err}");
        assert!(
            !err.contains("unexpected argument") && !err.contains("Os {"),
            "{err}"
        );
    }
    let err = stderr_of_failure(&[
        "workspace",
        &robot("ipanema-like-8.toml"),
        "--box",
        "-1,1,-1,1,2,2",
    ]);
    assert!(err.contains("along z, ZMIN = 2 m"), "{err}");
    // A chord of 1e-7 m on a load no pose can hold: runs (no tolerance of the user's to blame).
    let out = cdpr()
        .args(["workspace", &tdpm, "--boundary", "chord", "--chord", "1e-7"])
        .args(["--wrench", "0,-1e6,0", "--grid", "4"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && !err.contains("tolerance"), "{err}");
}

/// Issue 13 §2: printed numbers read as written (no `-0`, no `Some(`, no
/// `-98.10000000000001`), with units.
#[test]
fn printed_numbers_have_units_and_no_debug_noise() {
    let out = cdpr()
        .args([
            "tension",
            &robot("ipanema-like-8.toml"),
            "--pose",
            "0,0,1,0,0,0",
        ])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}");
    assert!(
        text.contains(" N, ") && text.contains(" N·m") && text.contains("(0 m, 0 m, 1 m, 0 rad"),
        "{text}"
    );
    assert!(text.contains("tension (N)"), "{text}");
    for bad in ["Some(", "-0 ", "-0,", "000000001", "99999999"] {
        assert!(!text.contains(bad), "{bad} in {text}");
    }
}

/// Issue 13 §2: `tension --help` lists every method with its line.
#[test]
fn tension_help_lists_every_method() {
    let out = cdpr().args(["tension", "--help"]).output().unwrap();
    let help = String::from_utf8_lossy(&out.stdout);
    for m in cdpr::tension::Method::ALL {
        let line = format!("{:<21} {}", m.name(), m.summary());
        assert!(help.contains(&line), "{line} missing from\n{help}");
    }
    let out = cdpr().args(["trajectory", "--help"]).output().unwrap();
    let help = String::from_utf8_lossy(&out.stdout);
    assert!(
        help.contains("pose   = [..]") && help.contains("wrench = [..]"),
        "{help}"
    );
}

/// Issue 13 §1: `isotropic` includes the platform's weight, as `capacity` does. A point2 robot
/// with 4 cables along ±x, ±y from far away, t ∈ [1, 10] N: the force set is [−9, 9]² N; a
/// 0.5 kg platform (4.903325 N down) leaves 9 − 4.903325 N in every direction.
#[test]
fn isotropic_includes_the_weight() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("p.toml");
    std::fs::write(
        &file,
        "motion = \"point2\"\n[tension]\nmin = 1.0\nmax = 10.0\n[platform]\nmass = 0.5\n\
         [[cables]]\nframe = [1e6, 0.0]\n[[cables]]\nframe = [-1e6, 0.0]\n\
         [[cables]]\nframe = [0.0, 1e6]\n[[cables]]\nframe = [0.0, -1e6]\n",
    )
    .unwrap();
    let file = file.display().to_string();
    let v = json(&["isotropic", &file, "--pose", "0,0", "--json"]);
    let f = v["isotropic_force"].as_f64().unwrap();
    assert!((f - (9.0 - 0.5 * 9.80665)).abs() < 1e-6, "{f}");
    assert!((v["external_wrench"][1].as_f64().unwrap() + 0.5 * 9.80665).abs() < 1e-12);
    // The capacity margin of the weight alone is the same number (a ball of radius 0).
    let c = json(&["capacity", &file, "--pose", "0,0", "--json"]);
    assert!((c["capacity_margin"].as_f64().unwrap() - f).abs() < 1e-6);
    let text = cdpr()
        .args(["isotropic", &file, "--pose", "0,0"])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(
        text.contains("weight") && text.contains("-4.903325 N]"),
        "{text}"
    );
}

/// Issue 13 §1: the capacity ball with separate force (N) and moment (N·m) radii on a planar
/// robot: a moment radius 0 gives the force-only margin, growing it can only shrink the margin;
/// point robots refuse a moment radius.
#[test]
fn capacity_force_and_moment_radii() {
    let run = |extra: &[&str]| -> serde_json::Value {
        let tdpm = robot("tdpm-4.toml");
        let out = cdpr()
            .args(["capacity", &tdpm, "--pose", "0,0,0", "--json"])
            .args(extra)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let f_only = run(&["--force-radius", "1"]);
    let both = run(&["--force-radius", "1", "--moment-radius", "0.5"]);
    assert_eq!(f_only["required"]["shape"], "force-moment-balls");
    assert_eq!(both["required"]["moment_radius"], 0.5);
    let (a, b) = (
        f_only["capacity_margin"].as_f64().unwrap(),
        both["capacity_margin"].as_f64().unwrap(),
    );
    assert!(b < a, "{a} {b}");
    let none = run(&[]);
    assert!(a < none["capacity_margin"].as_f64().unwrap());
    let err = stderr_of_failure(&[
        "capacity",
        &robot("krut-3.toml"),
        "--pose",
        "0,0",
        "--moment-radius",
        "1",
    ]);
    assert!(err.contains("--moment-radius"), "{err}");
}

/// Issue 13 §1: every command that takes `--method` (and stiffness-map, which always uses sotda)
/// rejects a method that does not apply to the robot with exit code 2 and one message, before
/// any pose is evaluated (the workspace grid below would take hours; it used to print
/// `volume 0.000000` and exit 0).
#[test]
fn inapplicable_methods_exit_2_up_front() {
    let r8 = robot("ipanema-like-8.toml");
    let r4 = robot("tdpm-4.toml");
    let peers = "pott-closed-form, pott-closed-form-ee, puncture, dykstra, l2-mid, vertex-centroid, \
                 p-norm, optimally-safe";
    let r2 = format!(
        "methods that apply: pinv, l1, l1-max, l2, l2-max, linf, improved-closed-form, barycenter, \
         sotda, {peers}"
    );
    let r1 = format!(
        "methods that apply: pinv, closed-form, l1, l1-max, l2, l2-max, linf, improved-closed-form, \
         {peers}"
    );
    let cases: Vec<(Vec<&str>, String)> = vec![
        (
            vec![
                "tension",
                &r8,
                "--pose",
                "0,0,1,0,0,0",
                "--method",
                "closed-form",
            ],
            format!("method closed-form needs redundancy 1; this robot has n − DOF = 2; {r2}"),
        ),
        (
            vec!["workspace", &r8, "--grid", "400", "--method", "closed-form"],
            format!("method closed-form needs redundancy 1; this robot has n − DOF = 2; {r2}"),
        ),
        (
            vec![
                "dextrous",
                &r4,
                "--orientations",
                "-0.1:0.1:3",
                "--method",
                "barycenter",
            ],
            format!("method barycenter needs redundancy 2; this robot has n − DOF = 1; {r1}"),
        ),
        (
            vec![
                "trajectory",
                &r4,
                "--from",
                "0,0,0",
                "--to",
                "0.1,0,0",
                "--method",
                "exact",
            ],
            format!("method exact needs redundancy 0; this robot has n − DOF = 1; {r1}"),
        ),
        (
            vec![
                "synthesize",
                &r4,
                "--orientations",
                "-0.1:0.1:3",
                "--start",
                "0.5,2.5,3.8,5.5",
                "--method",
                "sotda",
            ],
            format!("method sotda needs redundancy 2; this robot has n − DOF = 1; {r1}"),
        ),
        (
            vec!["stiffness-map", &r4, "--pose", "0,0,0"],
            format!("method sotda needs redundancy 2; this robot has n − DOF = 1; {r1}"),
        ),
    ];
    for (args, message) in cases {
        let out = cdpr().args(&args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(out.stdout.is_empty(), "{args:?}");
        assert_eq!(
            String::from_utf8_lossy(&out.stderr).trim(),
            format!("error: {message}"),
            "{args:?}"
        );
    }
}

/// Issue 13 §1: `tension --method pinv --json` gives t = −W⁺ w_ext in `tensions` even when a
/// bound breaks; `feasible` is false and `reason` names the cable.
#[test]
fn pinv_json_keeps_its_tensions() {
    // tdpm-4 under a large downward load: the minimum-norm solution pushes on a cable.
    let out = cdpr()
        .args([
            "tension",
            &robot("tdpm-4.toml"),
            "--pose",
            "0,0,0",
            "--wrench",
            "0,1000,0",
            "--method",
            "pinv",
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
    assert_eq!(v["feasible"], false, "{v}");
    let t: Vec<f64> = v["tensions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_eq!(t.len(), 4);
    assert!(v["reason"].as_str().unwrap().contains("cable "), "{v}");
    // It balances the wrench: W t + w_ext = 0 with W from `kinematics`.
    let k: serde_json::Value = serde_json::from_slice(
        &cdpr()
            .args([
                "kinematics",
                &robot("tdpm-4.toml"),
                "--pose",
                "0,0,0",
                "--json",
            ])
            .output()
            .unwrap()
            .stdout,
    )
    .unwrap();
    let we: Vec<f64> = v["external_wrench"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    for (row, e) in k["wrench_matrix"].as_array().unwrap().iter().zip(&we) {
        let s: f64 = row
            .as_array()
            .unwrap()
            .iter()
            .zip(&t)
            .map(|(a, b)| a.as_f64().unwrap() * b)
            .sum();
        assert!((s + e).abs() < 1e-9 * 1000.0, "{s} + {e}");
    }
}

/// `stiffness` refuses negative tensions (a cable only pulls; issue 25: they gave a matrix
/// without a word) and, without --tensions, takes them from --method as `tension` does (l2 by
/// default): the same tensions as `cdpr tension` at the pose, and the same matrix as passing
/// them with --tensions.
#[test]
fn stiffness_refuses_negative_tensions_and_solves_with_method() {
    let r8 = robot("ipanema-like-8.toml");
    let pose = "0,0,1,0,0,0";
    let out = cdpr()
        .args([
            "stiffness",
            &r8,
            "--pose",
            pose,
            "--tensions",
            "100,100,100,-5,100,100,100,100",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("t_4 = -5 N") && err.contains("can only pull"),
        "{err}"
    );
    for method in [None, Some("l1")] {
        let mut args = vec!["stiffness", r8.as_str(), "--pose", pose, "--json"];
        let mut tension = vec!["tension", r8.as_str(), "--pose", pose, "--json"];
        if let Some(m) = method {
            args.extend(["--method", m]);
            tension.extend(["--method", m]);
        }
        let v = json(&args);
        assert_eq!(v["tension_method"], method.unwrap_or("l2"));
        let t = json(&tension);
        assert_eq!(v["tensions"], t["tensions"], "{method:?}");
        let given: Vec<String> = v["tensions"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| format!("{}", x.as_f64().unwrap()))
            .collect();
        let again = json(&[
            "stiffness",
            &r8,
            "--pose",
            pose,
            "--tensions",
            &given.join(","),
            "--json",
        ]);
        assert_eq!(again["stiffness"], v["stiffness"]);
        assert!(again["tension_method"].is_null());
    }
}

/// Issue 26: the options of the peers' methods work with their method and are refused (exit 2,
/// naming the option and its method) with another; every new method answers in JSON.
#[test]
fn peer_methods_and_their_options() {
    let tdpm = robot("tdpm-4.toml");
    let base = [
        "tension", &tdpm, "--pose", "0,0,0", "--wrench", "0,-10,0", "--json",
    ];
    for (method, extra) in [
        ("pott-closed-form", vec![]),
        ("pott-closed-form-ee", vec![]),
        ("puncture", vec!["--interior", "cf"]),
        ("dykstra", vec!["--alternating"]),
        ("l2-mid", vec![]),
        ("vertex-centroid", vec![]),
        ("p-norm", vec!["--p", "6"]),
        ("optimally-safe", vec!["--alpha", "2"]),
    ] {
        let mut args = base.to_vec();
        args.extend(["--method", method]);
        args.extend(extra);
        let v = json(&args);
        assert_eq!(v["method"], method);
        assert_eq!(v["feasible"], true, "{v}");
    }
    for (method, extra, wanted) in [
        (
            "l2",
            vec!["--alpha", "2"],
            "--alpha is an option of another method, not of l2",
        ),
        (
            "dykstra",
            vec!["--p", "3"],
            "--p is an option of another method",
        ),
        (
            "l2-mid",
            vec!["--alternating"],
            "--alternating is an option of another method",
        ),
        ("puncture", vec!["--interior", "x"], "expected icf or cf"),
        (
            "p-norm",
            vec!["--p", "1.5"],
            "expected a finite exponent p ≥ 2",
        ),
    ] {
        let mut args = base.to_vec();
        args.extend(["--method", method]);
        args.extend(extra);
        let err = stderr_of_failure(&args);
        assert!(err.contains(wanted), "{args:?}: {err}");
    }
}

/// An empty feasible set names its binding cables. Krut-3 at the centre under a 1000 N load
/// straight down, by hand: cables 1 and 2 (30°, 150°) carry τ, cable 3 (270°) t₃ with
/// τ − t₃ = 1000 N; widening [50, 500] N by s: τ = 500 + s, t₃ = 50 − s gives s = 275 N,
/// τ = 775 N, t₃ = −225 N.
#[test]
fn infeasible_answers_name_the_binding_cables() {
    let k3 = robot("krut-3.toml");
    let args = ["tension", &k3, "--pose", "0,0", "--wrench", "0,-1000"];
    for method in ["l2", "linf", "l1", "barycenter", "vertex-centroid"] {
        let out = cdpr()
            .args(args)
            .args(["--method", method])
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&out.stdout);
        if !text.contains("empty feasible set") {
            continue; // a method with another reason (e.g. not applicable at r = 1)
        }
        for line in [
            "binding cables (the balancing tensions closest to the bounds break them by 275 N):",
            "  cable 1 would need 775 N, above its t_max of 500 N",
            "  cable 3 would need -225 N, below its t_min of 50 N",
        ] {
            assert!(text.contains(line), "{method}: {line}\n{text}");
        }
    }
    let v = json(&[&args[..], &["--method", "linf", "--json"]].concat());
    let b = &v["binding_cables"];
    assert!((b["violation"].as_f64().unwrap() - 275.0).abs() < 1e-6);
    assert_eq!(b["cables"][2]["cable"], 3);
    assert_eq!(b["cables"][2]["which"], "t_min");
    assert!((b["cables"][2]["tension"].as_f64().unwrap() + 225.0).abs() < 1e-6);
    // Feasible answers carry none.
    let v = json(&["tension", &k3, "--pose", "0,0", "--json"]);
    assert!(v.get("binding_cables").is_none());
}

/// --nu, --direction and --full belong to SOTDA: with another method they are refused (exit
/// 2) with a message naming the method, in `tension` and `trajectory`.
#[test]
fn sotda_options_with_another_method_are_refused() {
    let k3 = robot("krut-3.toml");
    let e = stderr_of_failure(&["tension", &k3, "--pose", "0,0", "--nu", "0.5"]);
    assert!(
        e.contains("--nu is an option of the sotda method only, and the method is l2"),
        "{e}"
    );
    let e = stderr_of_failure(&[
        "tension",
        &k3,
        "--pose",
        "0,0",
        "--method",
        "linf",
        "--direction",
        "1,0",
        "--full",
    ]);
    assert!(
        e.contains("--direction, --full are options of the sotda method only"),
        "{e}"
    );
    assert!(e.contains("linf"), "{e}");
    let e = stderr_of_failure(&[
        "trajectory",
        &k3,
        "--from",
        "0,0",
        "--to",
        "0.1,0",
        "--nu",
        "0.3",
    ]);
    assert!(
        e.contains("--nu is an option of the sotda method only"),
        "{e}"
    );
}
