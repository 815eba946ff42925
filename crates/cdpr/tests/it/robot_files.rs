//! Robot files: every shipped example loads; every kind of bad file gets an error naming the file,
//! the line and the key, never a panic.

use cdpr::{RobotDescription, RobotFileError};
use std::path::PathBuf;

fn examples() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/robots")
}

const GOOD: &str = r#"name = "test"
motion = "planar"
[tension]
min = 5.0
max = 100.0
[limits]
min_cable_length = 0.1
[[cables]]
frame = [1.0, 0.5]
platform = [0.1, 0.1]
[[cables]]
frame = [-1.0, 0.5]
platform = [-0.1, 0.1]
[[cables]]
frame = [-1.0, -0.5]
platform = [-0.1, -0.1]
"#;

/// Parses `text` and returns (line, key, message) of the error.
fn error_of(text: &str) -> (usize, String, String) {
    match RobotDescription::parse(text, "robot.toml").unwrap_err() {
        RobotFileError::Invalid {
            line, key, message, ..
        } => (line, key, message),
        RobotFileError::Syntax { line, message, .. } => (line, String::new(), message),
        e => panic!("unexpected error {e}"),
    }
}

#[test]
fn every_example_robot_loads() {
    let mut count = 0;
    for entry in std::fs::read_dir(examples()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let r = RobotDescription::load(&path).unwrap_or_else(|e| panic!("{e}"));
            assert!(r.robot.cable_count() >= r.robot.dof(), "{}", path.display());
            assert!(
                r.warnings.is_empty(),
                "{}: {:?}",
                path.display(),
                r.warnings
            );
            count += 1;
        }
    }
    assert!(count >= 9, "only {count} example robots");
}

#[test]
fn thesis_robot_values() {
    let r = RobotDescription::load(examples().join("tdpm-3.toml")).unwrap();
    assert_eq!(r.limits.min_jacobian_det, Some(1e-3));
    assert_eq!(r.limits.min_cable_length, Some(0.1));
    assert_eq!(r.bounds.min()[2], 5.0);
    assert_eq!(r.bounds.max()[0], 100.0);
    let ip = RobotDescription::load(examples().join("ipanema-like-8.toml")).unwrap();
    assert_eq!(ip.axial_stiffness.as_deref(), Some(&[60000.0; 8][..]));
}

#[test]
fn unknown_motion() {
    let (line, key, msg) = error_of(&GOOD.replace("\"planar\"", "\"cartesian\""));
    assert_eq!((line, key.as_str()), (2, "motion"));
    assert!(msg.contains("cartesian"), "{msg}");
}

#[test]
fn wrong_vector_length() {
    let (line, key, _) = error_of(&GOOD.replace("frame = [-1.0, 0.5]", "frame = [-1.0, 0.5, 2.0]"));
    assert_eq!((line, key.as_str()), (12, "cables[2].frame"));
}

#[test]
fn nan_and_inf() {
    let (line, key, _) =
        error_of(&GOOD.replace("platform = [-0.1, -0.1]", "platform = [nan, -0.1]"));
    assert_eq!((line, key.as_str()), (16, "cables[3].platform"));
    // `max = inf` is legal (issue 13 §2); NaN is not.
    let (line, key, _) = error_of(&GOOD.replace("max = 100.0", "max = nan"));
    assert_eq!((line, key.as_str()), (5, "tension.max"));
}

#[test]
fn inverted_tension_bounds() {
    let (line, key, msg) = error_of(&GOOD.replace("max = 100.0", "max = 1.0"));
    assert_eq!((line, key.as_str()), (4, "tension.min"));
    assert!(msg.contains("exceeds"), "{msg}");
}

#[test]
fn negative_limits() {
    let (line, key, _) =
        error_of(&GOOD.replace("min_cable_length = 0.1", "min_cable_length = -0.1"));
    assert_eq!((line, key.as_str()), (7, "limits.min_cable_length"));
}

/// A robot with fewer cables than degrees of freedom is a robot (its kinematics is defined);
/// analyses that balance a wrench refuse it by name (tested on the command line).
#[test]
fn fewer_cables_than_dof_loads() {
    let two = GOOD
        .split("[[cables]]")
        .take(3)
        .collect::<Vec<_>>()
        .join("[[cables]]");
    let r = RobotDescription::parse(&two, "robot.toml").unwrap();
    assert_eq!((r.robot.cable_count(), r.robot.dof()), (2, 3));
}

#[test]
fn missing_platform_attachment_of_a_planar_cable() {
    let (line, key, _) = error_of(&GOOD.replace("platform = [-0.1, 0.1]\n", ""));
    assert_eq!((line, key.as_str()), (12, "cables[2].platform"));
}

#[test]
fn unknown_key_and_bad_toml_name_a_line() {
    let (line, _, msg) = error_of(&GOOD.replace("min = 5.0", "mn = 5.0"));
    assert_eq!(line, 4, "{msg}");
    let (line, _, _) = error_of(&GOOD.replace("max = 100.0", "max = [100.0"));
    assert!(line >= 5);
}

#[test]
fn duplicate_cables_warn_and_shared_anchors_are_fine() {
    let dup = format!("{GOOD}[[cables]]\nframe = [-1.0, -0.5]\nplatform = [-0.1, -0.1]\n");
    let r = RobotDescription::parse(&dup, "robot.toml").unwrap();
    assert_eq!(r.warnings.len(), 1, "{:?}", r.warnings);
    let shared = format!("{GOOD}[[cables]]\nframe = [-1.0, -0.5]\nplatform = [0.1, -0.1]\n");
    assert!(
        RobotDescription::parse(&shared, "robot.toml")
            .unwrap()
            .warnings
            .is_empty()
    );
}

#[test]
fn missing_file_is_an_io_error() {
    let e = RobotDescription::load("/nonexistent/robot.toml").unwrap_err();
    assert!(matches!(e, RobotFileError::Io { .. }));
    assert!(e.to_string().contains("/nonexistent/robot.toml"));
}

/// Issue 13 §6: every crate re-exports the nalgebra of its API, one and the same version, so a
/// user pins none; a planar robot is built from 2-vectors.
#[test]
fn every_crate_re_exports_one_nalgebra() {
    use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
    let v: cdpr_kinematics::nalgebra::Vector2<f64> = cdpr_wrench::nalgebra::Vector2::new(1.0, 0.5);
    let a: cdpr_tension::nalgebra::Vector2<f64> = cdpr_polytope::nalgebra::Vector2::new(0.1, 0.0);
    let _: cdpr_workspace::nalgebra::Vector2<f64> = cdpr_io::nalgebra::Vector2::zeros();
    let _: cdpr::nalgebra::Vector2<f64> = v;
    let robot = Robot::new(
        MotionPattern::Planar,
        vec![
            Cable::planar(v, a),
            Cable::planar(-v, -a),
            Cable::planar(cdpr::nalgebra::Vector2::new(0.0, -1.0), a),
        ],
    )
    .unwrap();
    let kin = robot
        .inverse_kinematics(&Pose::planar(0.0, 0.0, 0.0))
        .unwrap();
    // Cable 1 from (0.1, 0) to (1, 0.5): length √(0.81 + 0.25).
    let l1 = kin.lengths().next().unwrap();
    assert!((l1 - (0.81f64 + 0.25).sqrt()).abs() < 1e-12);
    assert_eq!(
        Cable::point2(v).frame,
        cdpr::nalgebra::Vector3::new(1.0, 0.5, 0.0)
    );
}

/// Issue 13 §2: a value of the wrong type names its key (with the cable, counted from 1);
/// `max = inf` is a legal t_max (an unlimited cable), for the file and for one cable.
#[test]
fn wrong_types_name_their_key_and_inf_is_a_legal_t_max() {
    let (line, key, message) = error_of(&GOOD.replace("max = 100.0", "max = \"100\""));
    assert_eq!((line, key.as_str()), (5, "tension.max"), "{message}");
    let text = GOOD.replacen("platform = [-0.1, 0.1]", "platform = \"a\"", 1);
    let (line, key, _) = error_of(&text);
    assert_eq!((line, key.as_str()), (13, "cables[2].platform"));
    let r = RobotDescription::parse(&GOOD.replace("max = 100.0", "max = inf"), "r.toml").unwrap();
    assert!(r.bounds.max().iter().all(|t| *t == f64::INFINITY));
    let one = GOOD.replacen(
        "platform = [0.1, 0.1]",
        "platform = [0.1, 0.1]\nmax = inf",
        1,
    );
    let r = RobotDescription::parse(&one, "r.toml").unwrap();
    assert_eq!(r.bounds.max()[0], f64::INFINITY);
    assert_eq!(r.bounds.max()[1], 100.0);
    let (_, key, _) = error_of(&GOOD.replace("max = 100.0", "max = -inf"));
    assert_eq!(key, "tension.max");
    let (_, key, _) = error_of(&GOOD.replace("min = 5.0", "min = inf"));
    assert_eq!(key, "tension.min");
}
