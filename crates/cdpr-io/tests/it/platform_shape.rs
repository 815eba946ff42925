//! `[platform] shape`: a box, the hull of vertices, or the hull of the attachments; bad shapes
//! are errors naming the file, line and key; attachments inside the shape warn.

use cdpr_io::{RobotDescription, RobotFileError};

/// The 8-cable example robot (attachments at the corners of a 0.2 × 0.2 × 0.1 box) with a
/// `[platform]` section ending in `shape_line`.
fn robot(shape_line: &str) -> String {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/robots/ipanema-like-8.toml"
    );
    let text = std::fs::read_to_string(path).unwrap();
    text.replace(
        "centre_of_mass = [0.0, 0.0, 0.0]",
        &format!("centre_of_mass = [0.0, 0.0, 0.0]\n{shape_line}"),
    )
}

fn invalid(text: &str) -> (usize, String, String) {
    match RobotDescription::parse(text, "robot.toml").unwrap_err() {
        RobotFileError::Invalid {
            line, key, message, ..
        } => (line, key, message),
        e => panic!("unexpected error {e}"),
    }
}

#[test]
fn box_vertices_and_attachments_give_the_same_cuboid() {
    let shapes = [
        "shape = { box = [0.2, 0.2, 0.1] }",
        "shape = { box = [0.2, 0.2, 0.1], centre = [0.0, 0.0, 0.0] }",
        "shape = \"attachments\"",
        "shape = { vertices = [[0.1, 0.1, 0.05], [-0.1, 0.1, 0.05], [0.1, -0.1, 0.05], \
         [-0.1, -0.1, 0.05], [0.1, 0.1, -0.05], [-0.1, 0.1, -0.05], [0.1, -0.1, -0.05], \
         [-0.1, -0.1, -0.05], [0.0, 0.0, 0.0]] }",
    ];
    for s in shapes {
        let d = RobotDescription::parse(&robot(s), "robot.toml").unwrap();
        let hull = d.platform_shape.as_ref().expect(s);
        assert_eq!(hull.vertices().len(), 8, "{s}");
        assert_eq!(hull.faces().len(), 6, "{s}");
        assert!((hull.volume() - 0.2 * 0.2 * 0.1).abs() < 1e-15, "{s}");
        assert!(d.warnings.is_empty(), "{s}: {:?}", d.warnings);
    }
    assert!(
        RobotDescription::parse(&robot(""), "robot.toml")
            .unwrap()
            .platform_shape
            .is_none()
    );
}

#[test]
fn attachments_inside_the_shape_warn() {
    let d = RobotDescription::parse(&robot("shape = { box = [1.0, 1.0, 1.0] }"), "r.toml").unwrap();
    assert_eq!(d.warnings.len(), 8);
    assert!(d.warnings[0].contains("inside the platform shape"));
}

#[test]
fn bad_shapes_name_line_and_key() {
    let line = robot("")
        .lines()
        .position(|l| l.starts_with("centre_of_mass"))
        .unwrap()
        + 2;
    for (shape, says) in [
        ("shape = { box = [0.2, 0.0, 0.1] }", "box side 0"),
        ("shape = { box = [0.2, 0.1] }", "box needs 3 numbers"),
        (
            "shape = { vertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]] }",
            "coplanar",
        ),
        ("shape = { vertices = [[0.0, 0.0, 0.0]] }", "1 points"),
        ("shape = \"sphere\"", "unknown shape"),
        (
            "shape = { box = [1.0, 1.0, 1.0], vertices = [[0.0, 0.0, 0.0]] }",
            "exactly one",
        ),
    ] {
        let (l, key, message) = invalid(&robot(shape));
        assert_eq!((l, key.as_str()), (line, "platform.shape"), "{shape}");
        assert!(message.contains(says), "{shape}: {message}");
    }
    // A planar robot has no polyhedral platform.
    let planar = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/robots/tdpm-4.toml"
    );
    let text = std::fs::read_to_string(planar).unwrap();
    let text = if text.contains("[platform]") {
        text.replace(
            "[platform]",
            "[platform]\nshape = { box = [0.1, 0.1, 0.1] }",
        )
    } else {
        format!("{text}\n[platform]\nshape = {{ box = [0.1, 0.1, 0.1] }}\n")
    };
    assert!(invalid(&text).2.contains("spatial"));
}

/// A negative t_min is an error naming its key and line (a cable can only pull; issue 25: it
/// used to be a warning, and negative tensions then counted as feasible), in `[tension]` and
/// per cable.
#[test]
fn negative_tension_bounds_are_errors_with_key_and_line() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/robots/tdpm-3.toml"
    );
    let text = std::fs::read_to_string(path).unwrap();
    assert!(RobotDescription::parse(&text, "robot.toml").is_ok());
    let (line, key, message) =
        invalid(&text.replace("min = 5.0\nmax = 100.0", "min = -5.0\nmax = -1.0"));
    assert_eq!((line, key.as_str()), (6, "tension.min"), "{message}");
    assert!(
        message.contains("negative") && message.contains("-5"),
        "{message}"
    );
    let per_cable = text.replace("frame = [-1.0, 1.0]\n", "frame = [-1.0, 1.0]\nmin = -0.5\n");
    let (line, key, message) = invalid(&per_cable);
    assert_eq!((line, key.as_str()), (19, "cables[2].min"), "{message}");
    assert!(message.contains("can only pull"), "{message}");
}
