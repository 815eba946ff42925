//! The robot-file key `pulley` (issue 14 contract): both forms, errors naming file, line and key,
//! and a round trip of the written form.

use cdpr_io::{RobotDescription, RobotFileError, pulley_toml};
use cdpr_kinematics::reference_robots::ipanema_like_8_pulleys;
use cdpr_kinematics::{Pulley, Robot};
use nalgebra::Vector3;

fn examples() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/robots")
}

/// A 4-cable point3 robot whose first cable carries `pulley`.
fn with_pulley(pulley: &str) -> String {
    format!(
        r#"motion = "point3"
[tension]
min = 1.0
max = 10.0
[[cables]]
frame = [2.0, 0.0, 2.0]
pulley = {pulley}
[[cables]]
frame = [-2.0, 0.0, 2.0]
[[cables]]
frame = [0.0, 2.0, 2.0]
[[cables]]
frame = [0.0, 0.0, -2.0]
"#
    )
}

fn invalid(text: &str) -> (usize, String, String) {
    match RobotDescription::parse(text, "r.toml").unwrap_err() {
        RobotFileError::Invalid {
            line, key, message, ..
        } => (line, key, message),
        RobotFileError::Syntax { line, message, .. } => (line, String::new(), message),
        e => panic!("unexpected {e}"),
    }
}

#[test]
fn example_robot_has_the_reference_pulleys() {
    let d = RobotDescription::load(examples().join("ipanema-like-8-pulleys.toml")).unwrap();
    assert_eq!(d.robot.cables(), ipanema_like_8_pulleys().cables());
    assert!(d.robot.has_pulleys());
}

#[test]
fn axis_and_orientation_forms() {
    let d = RobotDescription::parse(
        &with_pulley("{ radius = 0.1, axis = [0.0, 0.0, 3.0] }"),
        "r.toml",
    )
    .unwrap();
    let p = d.robot.cables()[0].pulley.unwrap();
    assert_eq!(p, Pulley::from_axis(0.1, Vector3::z()));
    assert!(d.robot.cables()[1].pulley.is_none());
    // Rows of Q: the third column is the axis (here −y), the first the zero of the swivel angle.
    let d = RobotDescription::parse(
        &with_pulley(
            "{ radius = 0.1, orientation = [[0.0, 1.0, 0.0], [0.0, 0.0, -1.0], [-1.0, 0.0, 0.0]] }",
        ),
        "r.toml",
    )
    .unwrap();
    let p = d.robot.cables()[0].pulley.unwrap();
    assert_eq!(p.axis(), Vector3::new(0.0, -1.0, 0.0));
    assert_eq!(p.orientation.column(0), Vector3::new(0.0, 0.0, -1.0));
}

#[test]
fn bad_pulleys_name_line_and_key() {
    let cases = [
        (
            "{ radius = -0.1, axis = [0.0, 0.0, 1.0] }",
            "cables[1].pulley.radius",
            "positive",
        ),
        ("{ radius = 0.1 }", "cables[1].pulley", "axis"),
        (
            "{ radius = 0.1, axis = [0.0, 0.0, 1.0], orientation = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] }",
            "cables[1].pulley",
            "not both",
        ),
        (
            "{ radius = 0.1, axis = [0.0, 1.0] }",
            "cables[1].pulley.axis",
            "3",
        ),
        (
            "{ radius = 0.1, axis = [0.0, 0.0, 0.0] }",
            "cables[1].pulley.axis",
            "zero",
        ),
        (
            "{ radius = 0.1, orientation = [[1.0, 0.0], [0.0, 1.0]] }",
            "cables[1].pulley.orientation",
            "3 rows",
        ),
        (
            "{ radius = 0.1, orientation = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 2.0]] }",
            "cables[1].pulley",
            "orthonormal",
        ),
    ];
    for (pulley, key, words) in cases {
        let (line, k, message) = invalid(&with_pulley(pulley));
        assert_eq!(line, 7, "{pulley}: {message}");
        assert_eq!(k, key, "{pulley}: {message}");
        assert!(message.contains(words), "{pulley}: {message}");
    }
    // Unknown keys inside the table are syntax errors on that line.
    let (line, _, message) = invalid(&with_pulley("{ radius = 0.1, axle = [0.0, 0.0, 1.0] }"));
    assert_eq!(line, 7);
    assert!(message.contains("axle"), "{message}");
}

#[test]
fn written_pulleys_read_back_identically() {
    for axis in [
        Vector3::z(),
        Vector3::new(0.3, -1.7, 0.2),
        Vector3::new(1.0, 1e-3, -1e-7),
    ] {
        let p = Pulley::from_axis(0.0371, axis);
        let d = RobotDescription::parse(&with_pulley(&pulley_toml(&p)), "r.toml").unwrap();
        assert_eq!(d.robot.cables()[0].pulley, Some(p));
    }
}

#[test]
fn files_without_pulley_keys_have_straight_cables() {
    for entry in std::fs::read_dir(examples()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml")
            && !std::fs::read_to_string(&path).unwrap().contains("pulley =")
        {
            let d = RobotDescription::load(&path).unwrap();
            assert!(!d.robot.has_pulleys(), "{}", path.display());
            let straight: Robot = d.robot.without_pulleys();
            assert_eq!(straight, d.robot);
        }
    }
}
