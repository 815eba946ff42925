//! Interference: `cdpr kinematics` reports the closest cable pair (checked against a sampled
//! oracle), and `--criteria interference[:D]` removes poses where cables cross or pass through
//! the platform (hand cases on the crossed 8-cable robot).

use crate::common;

use common::{json, robot};
use nalgebra::Vector3;
use serde_json::Value;

fn vec3(v: &Value) -> Vector3<f64> {
    Vector3::new(
        v[0].as_f64().unwrap(),
        v[1].as_f64().unwrap(),
        v[2].as_f64().unwrap(),
    )
}

/// The 8-cable example with `shape` added to its `[platform]` table, written to a temp file.
fn with_shape(dir: &tempfile::TempDir, shape: &str) -> String {
    let text = std::fs::read_to_string(robot("ipanema-like-8.toml")).unwrap();
    let text = text.replace(
        "centre_of_mass = [0.0, 0.0, 0.0]",
        &format!("centre_of_mass = [0.0, 0.0, 0.0]\nshape = {shape}"),
    );
    let path = dir.path().join("shaped.toml");
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

/// On the crossed robot, an upper and a lower cable of the same corner lie in one vertical
/// plane and slope oppositely: they cross. At the centre (0, 0, 1) cables 1 and 5 meet where
/// 0.95 + 1.05 s = 1.05 − 1.05 s, s = 1/21 of the way from the attachments: at
/// (0.1 + 1.9/21, 0.1 + 1.4/21, 1.0).
#[test]
fn crossed_cables_are_reported_at_distance_zero() {
    let v = json(&[
        "kinematics",
        &robot("ipanema-like-8.toml"),
        "--pose",
        "0,0,1,0,0,0",
        "--json",
    ]);
    assert!(v["closest_distance"].as_f64().unwrap() < 1e-12);
    let pair = [
        v["closest_cables"][0].as_u64().unwrap(),
        v["closest_cables"][1].as_u64().unwrap(),
    ];
    assert!([[1, 5], [2, 6], [3, 7], [4, 8]].contains(&pair), "{pair:?}");
    if pair == [1, 5] {
        let p = vec3(&v["closest_points"][0]);
        let expected = Vector3::new(0.1 + 1.9 / 21.0, 0.1 + 1.4 / 21.0, 1.0);
        assert!((p - expected).norm() < 1e-12, "{p}");
    }
    assert!(v["platform_interference"].is_null()); // no shape in the file
}

/// At a rotated pose the closest distance is positive and equals the minimum over all pairs
/// of a brute-force sampling of the segments (anchors from the file, attachment points from
/// the JSON), within the sampling step.
#[test]
fn closest_pair_matches_a_sampled_oracle() {
    let file = robot("ipanema-like-8.toml");
    let v = json(&[
        "kinematics",
        &file,
        "--pose",
        "0.3,-0.2,1.1,0.2,-0.15,0.4",
        "--json",
    ]);
    let desc = cdpr::RobotDescription::load(&file).unwrap();
    let attach: Vec<Vector3<f64>> = v["attachment_points"]
        .as_array()
        .unwrap()
        .iter()
        .map(vec3)
        .collect();
    let anchors: Vec<Vector3<f64>> = desc.robot.cables().iter().map(|c| c.frame).collect();
    let steps = 400;
    let mut best = (f64::INFINITY, 0, 0);
    for i in 0..8 {
        for j in i + 1..8 {
            for a in 0..=steps {
                let p = attach[i] + (anchors[i] - attach[i]) * (a as f64 / steps as f64);
                for b in 0..=steps {
                    let q = attach[j] + (anchors[j] - attach[j]) * (b as f64 / steps as f64);
                    let d = (p - q).norm();
                    if d < best.0 {
                        best = (d, i + 1, j + 1);
                    }
                }
            }
        }
    }
    let d = v["closest_distance"].as_f64().unwrap();
    assert!(d > 1e-3, "{d}");
    let step = 3.5 / steps as f64; // longest cable / steps bounds the sampling error
    assert!(
        d <= best.0 + 1e-12 && d >= best.0 - step,
        "{d} vs {}",
        best.0
    );
    assert_eq!(
        [
            v["closest_cables"][0].as_u64().unwrap(),
            v["closest_cables"][1].as_u64().unwrap()
        ],
        [best.1 as u64, best.2 as u64]
    );
}

/// Rotated by π about z, every attachment sits at the corner opposite its anchor: every cable
/// passes through the box platform. Unrotated, each cable leaves its corner outwards: none.
#[test]
fn cable_through_the_platform_is_reported() {
    let dir = tempfile::tempdir().unwrap();
    let file = with_shape(&dir, "\"attachments\"");
    let v = json(&["kinematics", &file, "--pose", "0,0,1,0,0,0", "--json"]);
    assert!(v["platform_interference"]["cable"].is_null());
    let pi = std::f64::consts::PI.to_string();
    let pose = format!("0,0,1,0,0,{pi}");
    let v = json(&["kinematics", &file, "--pose", &pose, "--json"]);
    assert!(v["platform_interference"]["cable"].as_u64().is_some());
    assert!(v["platform_interference"]["penetration"].as_f64().unwrap() > 1e-3);
}

fn points(file: &str, criteria: &str, orientation: &str) -> u64 {
    json(&[
        "workspace",
        file,
        "--criteria",
        criteria,
        "--orientation",
        orientation,
        "--grid",
        "6",
        "--json",
    ])["feasible_points"]
        .as_u64()
        .unwrap()
}

#[test]
fn interference_criterion_empties_the_crossed_robot_workspace() {
    let file = robot("ipanema-like-8.toml");
    // The cables of a corner always cross (see above): no interference-free position.
    assert!(points(&file, "tension", "0,0,0") > 0);
    assert_eq!(points(&file, "tension,interference", "0,0,0"), 0);
    // Half-turned platform, box shape: every cable passes through the platform.
    let dir = tempfile::tempdir().unwrap();
    let shaped = with_shape(&dir, "{ box = [0.2, 0.2, 0.1] }");
    let pi = std::f64::consts::PI.to_string();
    assert!(points(&shaped, "length", &format!("0,0,{pi}")) > 0);
    assert_eq!(
        points(&shaped, "length,interference", &format!("0,0,{pi}")),
        0
    );
}
