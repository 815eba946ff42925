//! `--cable-model straight|elastic|catenary` (issue 29 contract): the sag-aware fields of
//! `cdpr kinematics` and `cdpr tension`, the default unchanged, usage errors exit 2.

#![allow(clippy::needless_range_loop)] // per-cable JSON arrays side by side

use crate::common;

use common::{cdpr, json, robot};

fn floats(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

const POSE: &str = "0,0,3,0,0,0";

#[test]
fn cogiro_at_50_n_sags_about_5_cm_and_1_2_degrees() {
    // Issue 29's introduction: on CoGiRo a cable at 50 N hangs about 5 cm below its chord and
    // pulls 1.2° away from it (WireCenter's cable: 0.023 kg/m, E·S = 1.1e11 · π · 0.006² N).
    let cogiro = robot("wirecenter-cogiro.toml");
    let t = "50,50,50,50,50,50,50,50";
    let v = json(&[
        "--kinematics",
        "standard",
        "kinematics",
        &cogiro,
        "--pose",
        POSE,
        "--cable-model",
        "catenary",
        "--tensions",
        t,
        "--json",
    ]);
    assert_eq!(v["cable_model"], "catenary");
    let (sag, angle) = (floats(&v["max_sag"]), floats(&v["angle_to_chord"]));
    let (l0, chord) = (
        floats(&v["unstrained_lengths"]),
        floats(&v["chord_lengths"]),
    );
    let (ta, tb) = (
        floats(&v["frame_end_tensions"]),
        floats(&v["platform_end_tensions"]),
    );
    for i in 0..8 {
        assert!(
            (0.04..0.05).contains(&sag[i]),
            "cable {i}: sag {} m",
            sag[i]
        );
        assert!((1.1..1.2).contains(&angle[i].to_degrees()), "cable {i}");
        assert!(ta[i] > tb[i] && (tb[i] - 50.0).abs() < 1e-9);
        // Sag outweighs the stretch: more cable than the chord.
        assert!(l0[i] > chord[i]);
    }
    let w = v["wrench_matrix"].as_array().unwrap();
    assert_eq!(w.len(), 6);
    for j in 0..8 {
        let u: f64 = (0..3).map(|r| w[r][j].as_f64().unwrap().powi(2)).sum();
        assert!((u - 1.0).abs() < 1e-12, "column {j} is a unit force");
    }
}

#[test]
fn default_is_straight_and_elastic_statics_match_it() {
    let r = robot("ipanema-like-8.toml");
    let pose = "0.2,-0.1,1.0,0.02,0,0";
    let plain = json(&["tension", &r, "--pose", pose, "--json"]);
    let straight = json(&[
        "tension",
        &r,
        "--pose",
        pose,
        "--json",
        "--cable-model",
        "straight",
    ]);
    assert_eq!(plain, straight);
    let elastic = json(&[
        "tension",
        &r,
        "--pose",
        pose,
        "--json",
        "--cable-model",
        "elastic",
    ]);
    assert_eq!(elastic["feasible"], true);
    let (a, b) = (floats(&plain["tensions"]), floats(&elastic["tensions"]));
    for (x, y) in a.iter().zip(&b) {
        assert!((x - y).abs() < 1e-9 * x.abs().max(1.0), "{x} vs {y}");
    }
    let (l0, chord) = (
        floats(&elastic["unstrained_lengths"]),
        floats(&elastic["chord_lengths"]),
    );
    for i in 0..8 {
        assert!((l0[i] - chord[i] / (1.0 + b[i] / 6e4)).abs() < 1e-12);
    }
}

#[test]
fn catenary_statics_every_method_certified_or_explained() {
    let cogiro = robot("wirecenter-cogiro.toml");
    for method in [
        "l2",
        "l1",
        "linf",
        "improved-closed-form",
        "barycenter",
        "l2-max",
    ] {
        let v = json(&[
            "--kinematics",
            "standard",
            "tension",
            &cogiro,
            "--pose",
            POSE,
            "--method",
            method,
            "--cable-model",
            "catenary",
            "--json",
        ]);
        if v["feasible"] == true {
            assert!(v["residual"].as_f64().unwrap() < 1e-9, "{method}");
            let (tb, ta) = (floats(&v["tensions"]), floats(&v["frame_end_tensions"]));
            for (a, b) in floats(&v["platform_end_tensions"]).iter().zip(&tb) {
                assert!((a - b).abs() <= 1e-12 * b, "{method}: {a} vs {b}");
            }
            assert!(
                ta.iter().all(|&t| (0.0..=720.0 + 1e-6).contains(&t)),
                "{method}"
            );
            assert_eq!(floats(&v["unstrained_lengths"]).len(), 8);
        } else {
            assert!(v["reason"].is_string(), "{method}");
        }
    }
}

#[test]
fn missing_keys_and_tensions_are_usage_errors() {
    let fails = |args: &[&str], needle: &str| {
        let out = cdpr().args(args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{args:?}: {err}");
    };
    let r = robot("ipanema-like-8.toml");
    let p = "0,0,1,0,0,0";
    fails(
        &["tension", &r, "--pose", p, "--cable-model", "catenary"],
        "linear_density",
    );
    fails(
        &["kinematics", &r, "--pose", p, "--cable-model", "elastic"],
        "--tensions",
    );
    fails(
        &[
            "kinematics",
            &r,
            "--pose",
            p,
            "--cable-model",
            "elastic",
            "--tensions",
            "1,2",
        ],
        "8 numbers",
    );
    fails(
        &[
            "tension",
            &robot("wirecenter-cogiro.toml"),
            "--pose",
            POSE,
            "--cable-model",
            "catenary",
        ],
        "pulleys",
    );
    fails(
        &[
            "tension",
            &robot("krut-4.toml"),
            "--pose",
            "0,0",
            "--cable-model",
            "elastic",
        ],
        "axial_stiffness",
    );
}

#[test]
fn trajectory_reports_unstrained_lengths_per_sample() {
    let r = robot("ipanema-like-8.toml");
    let v = json(&[
        "trajectory",
        &r,
        "--from",
        "0,0,1,0,0,0",
        "--to",
        "0.3,0.2,1.2,0,0,0",
        "--samples",
        "4",
        "--cable-model",
        "elastic",
        "--json",
    ]);
    assert_eq!(v["cable_model"], "elastic");
    let lengths = v["unstrained_lengths"].as_array().unwrap();
    assert_eq!(lengths.len(), 4);
    for (k, l) in lengths.iter().enumerate() {
        let (l0, t) = (floats(l), floats(&v["platform_end_tensions"][k]));
        let pose: Vec<String> = floats(&v["poses"][k])
            .iter()
            .map(|x| x.to_string())
            .collect();
        let kin = json(&["kinematics", &r, "--pose", &pose.join(","), "--json"]);
        let chord = floats(&kin["lengths"]);
        for i in 0..8 {
            assert!(
                (l0[i] - chord[i] / (1.0 + t[i] / 6e4)).abs() < 1e-12,
                "sample {k}"
            );
        }
    }
    // Without the flag, no new fields.
    let plain = json(&[
        "trajectory",
        &r,
        "--from",
        "0,0,1,0,0,0",
        "--to",
        "0.3,0.2,1.2,0,0,0",
        "--samples",
        "4",
        "--json",
    ]);
    assert!(plain.get("unstrained_lengths").is_none());
}

#[test]
fn forward_from_unstrained_lengths_returns_the_statics_pose() {
    // Issue 29 check: forward kinematics returns the pose whose tensions gave the lengths.
    // CoGiRo (25 kg, centre of mass off the origin) with sagging cables: l2 statics at POSE give
    // the unstrained lengths; `cdpr forward --unstrained-lengths` goes back to POSE and the
    // same tensions (from its default start, the straight cables' pose for those lengths).
    let cogiro = robot("wirecenter-cogiro.toml");
    let statics = json(&[
        "--kinematics",
        "standard",
        "tension",
        &cogiro,
        "--pose",
        POSE,
        "--method",
        "l2",
        "--cable-model",
        "catenary",
        "--json",
    ]);
    assert_eq!(statics["feasible"], true);
    let l0: Vec<String> = floats(&statics["unstrained_lengths"])
        .iter()
        .map(|x| x.to_string())
        .collect();
    let v = json(&[
        "--kinematics",
        "standard",
        "forward",
        &cogiro,
        "--unstrained-lengths",
        &l0.join(","),
        "--cable-model",
        "catenary",
        "--json",
    ]);
    assert_eq!(v["status"], "equilibrium", "{v}");
    assert_eq!(v["cable_model"], "catenary");
    let truth = [0.0, 0.0, 3.0, 0.0, 0.0, 0.0];
    for (p, t) in floats(&v["pose"]).iter().zip(truth) {
        assert!((p - t).abs() < 1e-9, "{p} vs {t}");
    }
    for (a, b) in floats(&v["tensions"])
        .iter()
        .zip(floats(&statics["tensions"]))
    {
        assert!((a - b).abs() < 1e-6 * b.max(1.0), "{a} vs {b}");
    }
    assert!(v["residual"].as_f64().unwrap() < 1e-6);
    assert_eq!(v["slack_cables"].as_array().unwrap().len(), 0);
    assert_eq!(floats(&v["frame_end_tensions"]).len(), 8);
    // Usage errors exit 2: straight cables have no unstrained lengths, a wrong count.
    for (args, needle) in [
        (
            vec!["--cable-model", "straight"],
            "--cable-model elastic or catenary",
        ),
        (
            vec!["--cable-model", "catenary", "--guess", "0,0"],
            "needs 6",
        ),
    ] {
        let mut all = vec![
            "--kinematics",
            "standard",
            "forward",
            &cogiro,
            "--unstrained-lengths",
            "10,10,10,10,10,10,10,10",
        ];
        all.extend(args);
        let out = cdpr().args(&all).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{all:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{all:?}: {err}");
    }
}

#[test]
fn workspace_with_sagging_cables() {
    // `cdpr workspace --cable-model`: weightless-limit equality and the shrinking set are tested
    // in cdpr-api (tests/workspace.rs); here the flag reaches the request (the JSON's verdict
    // count changes on CoGiRo's edge) and the criteria without a sagging version exit 2.
    let cogiro = robot("wirecenter-cogiro.toml");
    let count = |model: &str| {
        let v = json(&[
            "--kinematics",
            "standard",
            "workspace",
            &cogiro,
            "--grid",
            "6",
            "--cable-model",
            model,
            "--json",
        ]);
        v["feasible_points"].as_u64().unwrap()
    };
    assert_eq!(count("elastic"), count("straight"));
    assert!(count("catenary") < count("straight"));
    for (args, needle) in [
        (
            vec![&cogiro, "--criteria", "tension,isotropic:1"],
            "isotropic-force criterion has no version",
        ),
        (
            vec![
                &cogiro,
                "--criteria",
                "capacity",
                "--wrench-box",
                "1,1,1,1,1,1",
            ],
            "capacity criterion without the tension criterion",
        ),
    ] {
        let mut all = vec!["--kinematics", "standard", "workspace", "--grid", "2"];
        all.extend(args);
        all.extend(["--cable-model", "catenary"]);
        let out = cdpr().args(&all).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{all:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{all:?}: {err}");
    }
}

/// `drum_angles` (issue 29 follow-up): with a `winch` on every cable the trajectory's
/// compensation reports φ = L0/ρ, ρ the drum radius (4 cm) or, with `cable_diameter` d = 3 mm,
/// the single-layer helix √((r + d/2)² + (d/2π)²) = 4.1503 cm.
#[test]
fn trajectory_reports_drum_angles_with_the_cable_build_up() {
    let text = std::fs::read_to_string(robot("ipanema-like-8.toml")).unwrap();
    let dir = std::env::temp_dir().join(format!("cdpr-drum-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let run = |winch: &str, name: &str| {
        let file = dir.join(name);
        let with = text.replace(
            "axial_stiffness = 60000.0",
            &format!("axial_stiffness = 60000.0\nwinch = {{ {winch} }}"),
        );
        std::fs::write(&file, with).unwrap();
        let f = file.display().to_string();
        json(&[
            "trajectory",
            &f,
            "--from",
            "0,0,1,0,0,0",
            "--to",
            "0.3,0.2,1.2,0,0,0",
            "--samples",
            "3",
            "--cable-model",
            "elastic",
            "--json",
        ])
    };
    let base = "drum_radius = 0.04, gear_ratio = 8.0, motor_inertia = 1e-4";
    let plain = run(base, "plain.toml");
    let helix = run(&format!("{base}, cable_diameter = 0.003"), "helix.toml");
    let rho = (0.04f64 + 0.0015).hypot(0.003 / std::f64::consts::TAU);
    assert!((rho - 0.0415027).abs() < 1e-7, "{rho}");
    for k in 0..3 {
        let l0 = floats(&plain["unstrained_lengths"][k]);
        assert_eq!(l0, floats(&helix["unstrained_lengths"][k]));
        let (a, b) = (
            floats(&plain["drum_angles"][k]),
            floats(&helix["drum_angles"][k]),
        );
        for i in 0..8 {
            assert!(
                (a[i] - l0[i] / 0.04).abs() < 1e-12 * a[i],
                "sample {k} cable {i}"
            );
            assert!(
                (b[i] - l0[i] / rho).abs() < 1e-12 * b[i],
                "sample {k} cable {i}"
            );
        }
    }
    // Without winches, no drum angles.
    let none = json(&[
        "trajectory",
        &robot("ipanema-like-8.toml"),
        "--from",
        "0,0,1,0,0,0",
        "--to",
        "0.3,0.2,1.2,0,0,0",
        "--samples",
        "3",
        "--cable-model",
        "elastic",
        "--json",
    ]);
    assert!(none.get("drum_angles").is_none());
    // A bad diameter names the key.
    let file = dir.join("bad.toml");
    std::fs::write(
        &file,
        text.replace(
            "axial_stiffness = 60000.0",
            &format!("axial_stiffness = 60000.0\nwinch = {{ {base}, cable_diameter = -1.0 }}"),
        ),
    )
    .unwrap();
    let out = cdpr()
        .args([
            "kinematics",
            &file.display().to_string(),
            "--pose",
            "0,0,1,0,0,0",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("cable_diameter"));
}

/// Multi-layer drums (issue 29, spool build-up): r = 4 cm, d = 3 mm, N = 10 turns per layer,
/// C = 6 m on the winch. Layer k pays out ρ_k = √((0.0415 + 0.003 k)² + (0.003/2π)²) per radian
/// and holds λ_k = 20π ρ_k: λ_0 = 2.6077 m, λ_1 = 2.7962 m, so C = 6 m fills layers 0 and 1 and
/// 0.596 m of layer 2. With L0 ≈ 2.2–2.9 m paid out, C − L0 lies on layer 1 and
/// φ = (C − λ_0 − λ_1)/ρ_2 + (λ_0 + λ_1 − (C − L0))/ρ_1. `cdpr convert` keeps the keys; a
/// `cable_length` shorter than L0 is an error naming the cable.
#[test]
fn trajectory_drum_angles_on_a_multi_layer_drum() {
    let text = std::fs::read_to_string(robot("ipanema-like-8.toml")).unwrap();
    let dir = std::env::temp_dir().join(format!("cdpr-layers-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let write = |winch: &str, name: &str| {
        let file = dir.join(name);
        let with = text.replace(
            "axial_stiffness = 60000.0",
            &format!("axial_stiffness = 60000.0\nwinch = {{ {winch} }}"),
        );
        std::fs::write(&file, with).unwrap();
        file.display().to_string()
    };
    let args = |f: &str| {
        [
            "trajectory",
            f,
            "--from",
            "0,0,1,0,0,0",
            "--to",
            "0.3,0.2,1.2,0,0,0",
            "--samples",
            "3",
            "--cable-model",
            "elastic",
            "--json",
        ]
        .map(String::from)
    };
    let base = "drum_radius = 0.04, gear_ratio = 8.0, motor_inertia = 1e-4, cable_diameter = 0.003";
    let f = write(
        &format!("{base}, turns_per_layer = 10, cable_length = 6.0"),
        "layers.toml",
    );
    let v = json(&args(&f).iter().map(String::as_str).collect::<Vec<_>>());
    let rho = |k: f64| (0.0415f64 + 0.003 * k).hypot(0.003 / std::f64::consts::TAU);
    let lambda = |k: f64| 20.0 * std::f64::consts::PI * rho(k);
    assert!((lambda(0.0) - 2.6077).abs() < 1e-4 && (lambda(1.0) - 2.7962).abs() < 1e-4);
    let (c, s1, s2) = (6.0, lambda(0.0), lambda(0.0) + lambda(1.0));
    for k in 0..3 {
        let l0 = floats(&v["unstrained_lengths"][k]);
        let phi = floats(&v["drum_angles"][k]);
        for i in 0..8 {
            let wound = c - l0[i];
            assert!(
                s1 < wound && wound < s2,
                "sample {k} cable {i}: W = {wound} off layer 1"
            );
            let expected = (c - s2) / rho(2.0) + (s2 - wound) / rho(1.0);
            assert!(
                (phi[i] - expected).abs() < 1e-12 * expected,
                "sample {k} cable {i}: {} vs {expected}",
                phi[i]
            );
        }
    }
    // `cdpr convert` writes the keys back; the converted robot gives the same angles.
    let out = dir.join("converted.toml").display().to_string();
    json(&["convert", &f, "-o", &out, "--json"]);
    let converted = std::fs::read_to_string(&out).unwrap();
    assert_eq!(
        converted.matches("turns_per_layer = 10").count(),
        8,
        "{converted}"
    );
    assert_eq!(
        converted.matches("cable_length = 6").count(),
        8,
        "{converted}"
    );
    let again = json(&args(&out).iter().map(String::as_str).collect::<Vec<_>>());
    assert_eq!(again["drum_angles"], v["drum_angles"]);
    // 2 m of cable cannot pay out L0 ≈ 2.6 m: the drum would be empty.
    let short = write(
        &format!("{base}, turns_per_layer = 10, cable_length = 2.0"),
        "short.toml",
    );
    let out = cdpr()
        .args(args(&short).iter().map(String::as_str))
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("pose 1: cable 1: paid-out length ")
            && err.contains("exceeds winch.cable_length = 2 m (the drum would be empty)"),
        "{err}"
    );
    // Half the keys: an error naming the missing one.
    let half = write(&format!("{base}, turns_per_layer = 10"), "half.toml");
    let out = cdpr()
        .args(args(&half).iter().map(String::as_str))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("cables[1].winch.turns_per_layer") && err.contains("winch.cable_length"),
        "{err}"
    );
}

/// The scene JSON embedded in a viewer page.
fn scene_of(html: &str) -> serde_json::Value {
    let tag = "id=\"scene\">";
    let start = html.find(tag).unwrap() + tag.len();
    let mut de =
        serde_json::Deserializer::from_str(&html[start..]).into_iter::<serde_json::Value>();
    de.next().unwrap().unwrap()
}

/// The HTML viewer draws CoGiRo's sagging cables as catenaries under `--cable-model catenary`
/// (each a polyline from the frame anchor to the attachment, below the chord), straight
/// otherwise.
#[test]
fn viewer_draws_catenaries() {
    let cogiro = robot("wirecenter-cogiro.toml");
    let dir = std::env::temp_dir().join(format!("cdpr-viewer-sag-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let page = |model: &str| {
        let file = dir.join(format!("{model}.html"));
        let out = cdpr()
            .args([
                "--kinematics",
                "standard",
                "workspace",
                &cogiro,
                "--grid",
                "4",
                "--draw-pose",
                "0,0,3,0,0,0",
                "--cable-model",
                model,
                "--plot",
                &file.display().to_string(),
            ])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        scene_of(
            &std::fs::read_to_string(&file)
                .unwrap()
                .replace("<\\/", "</"),
        )
    };
    let straight = page("straight");
    assert_eq!(straight["cableCurves"].as_array().unwrap().len(), 0);
    let sag = page("catenary");
    let curves = sag["cableCurves"].as_array().unwrap();
    let cables = sag["cables"].as_array().unwrap();
    assert_eq!(curves.len(), 8);
    let mut deepest: f64 = 0.0;
    for (curve, cable) in curves.iter().zip(cables) {
        let pts: Vec<Vec<f64>> = curve.as_array().unwrap().iter().map(floats).collect();
        assert_eq!(pts.len(), 33);
        let (a, b) = (floats(&cable[0]), floats(&cable[1]));
        for k in 0..3 {
            assert!((pts[0][k] - a[k]).abs() < 1e-9 && (pts[32][k] - b[k]).abs() < 1e-9);
        }
        // Every inner point lies below the chord (heavier than the straight line).
        for p in &pts[1..32] {
            let s = (0..3).map(|k| (p[k] - a[k]) * (b[k] - a[k])).sum::<f64>()
                / (0..3).map(|k| (b[k] - a[k]).powi(2)).sum::<f64>();
            let on_chord: Vec<f64> = (0..3).map(|k| a[k] + s * (b[k] - a[k])).collect();
            assert!(p[2] < on_chord[2], "{p:?} above the chord");
            deepest = deepest.max(on_chord[2] - p[2]);
        }
    }
    // CoGiRo's cables sag centimetres at 50 N (issue 29); at (0, 0, 3 m) the l2 statics leave
    // cable 1 at about 1 N, hanging metres below its 9.4 m chord (docs/algorithms.md).
    assert!(deepest > 0.005 && deepest < 5.0, "{deepest}");
    assert!(sag["legend"].to_string().contains("catenaries"));
}

/// `--cable-model elastic` over pulleys (issue 29): `kinematics`, `tension` and `forward` on
/// ipanema-like-8-pulleys (E·S = 60 kN). The statics and W are the straight pulley model's,
/// L0 = l/(1 + t/EA) with l the pulley model's whole length (wrapped arc + free segment), and
/// `forward --unstrained-lengths` returns the statics' pose and tensions.
#[test]
fn elastic_cables_over_pulleys() {
    let r = robot("ipanema-like-8-pulleys.toml");
    let pose = "0.2,0.1,1.1,0.02,-0.01,0.05";
    let ea = 6e4;
    let straight_kin = json(&["kinematics", &r, "--pose", pose, "--json"]);
    assert_eq!(straight_kin["kinematics"], "pulley");
    let (l, free) = (
        floats(&straight_kin["lengths"]),
        floats(&straight_kin["free_lengths"]),
    );
    let t = [120.0, 90.0, 150.0, 100.0, 110.0, 130.0, 95.0, 140.0];
    let t_text: Vec<String> = t.iter().map(|x| x.to_string()).collect();
    let kin = json(&[
        "kinematics",
        &r,
        "--pose",
        pose,
        "--cable-model",
        "elastic",
        "--tensions",
        &t_text.join(","),
        "--json",
    ]);
    let (l0, chord, wrapped) = (
        floats(&kin["unstrained_lengths"]),
        floats(&kin["chord_lengths"]),
        floats(&kin["wrapped_lengths"]),
    );
    for i in 0..8 {
        assert!(
            (l0[i] - l[i] / (1.0 + t[i] / ea)).abs() < 1e-12,
            "cable {i}"
        );
        assert!((chord[i] - free[i]).abs() < 1e-12, "cable {i}");
        assert!((wrapped[i] + free[i] - l[i]).abs() < 1e-12, "cable {i}");
    }
    let (w0, w1) = (&straight_kin["wrench_matrix"], &kin["wrench_matrix"]);
    for r in 0..6 {
        let (a, b) = (floats(&w0[r]), floats(&w1[r]));
        for j in 0..8 {
            assert!(
                (a[j] - b[j]).abs() < 1e-12,
                "W[{r}][{j}]: {} vs {}",
                a[j],
                b[j]
            );
        }
    }
    // Tensions: the straight pulley answer.
    let straight = json(&["tension", &r, "--pose", pose, "--json"]);
    let elastic = json(&[
        "tension",
        &r,
        "--pose",
        pose,
        "--cable-model",
        "elastic",
        "--json",
    ]);
    assert_eq!(elastic["feasible"], true, "{elastic}");
    let (ts, te) = (floats(&straight["tensions"]), floats(&elastic["tensions"]));
    let l0 = floats(&elastic["unstrained_lengths"]);
    for i in 0..8 {
        assert!(
            (ts[i] - te[i]).abs() < 1e-9 * ts[i],
            "{} vs {}",
            ts[i],
            te[i]
        );
        assert!(
            (l0[i] - l[i] / (1.0 + te[i] / ea)).abs() < 1e-12,
            "cable {i}"
        );
    }
    // Forward from those unstrained lengths under the platform's weight: back to the pose.
    let l0_text: Vec<String> = l0.iter().map(|x| x.to_string()).collect();
    let v = json(&[
        "forward",
        &r,
        "--unstrained-lengths",
        &l0_text.join(","),
        "--cable-model",
        "elastic",
        "--json",
    ]);
    assert_eq!(v["status"], "equilibrium", "{v}");
    let truth = [0.2, 0.1, 1.1, 0.02, -0.01, 0.05];
    for (p, t) in floats(&v["pose"]).iter().zip(truth) {
        assert!((p - t).abs() < 1e-9, "{p} vs {t}");
    }
    for (a, b) in floats(&v["tensions"]).iter().zip(&te) {
        assert!((a - b).abs() < 1e-6 * b, "{a} vs {b}");
    }
    assert_eq!(floats(&v["wrapped_lengths"]).len(), 8);
    // The table names the wrapped arc.
    let out = cdpr()
        .args(["tension", &r, "--pose", pose, "--cable-model", "elastic"])
        .output()
        .unwrap();
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("wrapped (m)"));
    // Robots without pulleys keep their JSON (no wrapped lengths).
    let plain = json(&[
        "tension",
        &robot("ipanema-like-8.toml"),
        "--pose",
        pose,
        "--cable-model",
        "elastic",
        "--json",
    ]);
    assert!(plain.get("wrapped_lengths").is_none());
}

/// The workspace with elastic cables over pulleys is the straight pulley robot's.
#[test]
fn elastic_workspace_over_pulleys_is_the_straight_one() {
    let r = robot("ipanema-like-8-pulleys.toml");
    let count = |model: &str| {
        let v = json(&[
            "workspace",
            &r,
            "--grid",
            "6",
            "--cable-model",
            model,
            "--json",
        ]);
        v["feasible_points"].as_u64().unwrap()
    };
    let straight = count("straight");
    assert!(straight > 0);
    assert_eq!(count("elastic"), straight);
}
