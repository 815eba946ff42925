//! The robot-file key `winch` (issue 28 contract): TOML read and write, WireCenter's
//! `<winch>` (`<drum>`, `<motor>`), errors naming file, line and key.

use cdpr_io::{RobotDescription, RobotFileError};
use std::path::Path;

fn robot(winches: [&str; 3]) -> String {
    let mut s = String::from("motion = \"point2\"\n[tension]\nmin = 1.0\nmax = 10.0\n");
    for (frame, w) in ["[1.0, 0.0]", "[-1.0, 1.0]", "[-1.0, -1.0]"]
        .iter()
        .zip(winches)
    {
        s += &format!("[[cables]]\nframe = {frame}\n{w}\n");
    }
    s
}

const FULL: &str = "winch = { drum_radius = 0.05, gear_ratio = 10.0, motor_inertia = 1.5e-4, max_torque = 3.0, max_speed = 600.0 }";
const BARE: &str = "winch = { drum_radius = 0.04, gear_ratio = 1.0, motor_inertia = 0.0 }";

fn err(text: &str) -> (usize, String, String) {
    match RobotDescription::parse(text, "r.toml").unwrap_err() {
        RobotFileError::Invalid {
            line, key, message, ..
        } => (line, key, message),
        e => panic!("unexpected {e}"),
    }
}

#[test]
fn toml_key_reads_and_writes_back() {
    let d = RobotDescription::parse(&robot([FULL, BARE, FULL]), "r.toml").unwrap();
    let w = d.winches.as_ref().unwrap();
    assert_eq!(w.len(), 3);
    assert_eq!(
        (w[0].drum_radius, w[0].gear_ratio, w[0].motor_inertia),
        (0.05, 10.0, 1.5e-4)
    );
    assert_eq!((w[0].max_torque, w[0].max_speed), (Some(3.0), Some(600.0)));
    assert_eq!((w[1].max_torque, w[1].max_speed), (None, None));
    let text = d.to_toml("round trip");
    assert_eq!(text.matches("winch = {").count(), 3, "{text}");
    let again = RobotDescription::parse(&text, "again.toml").unwrap();
    assert_eq!(again.winches, d.winches);
    let none = RobotDescription::parse(&robot(["", "", ""]), "r.toml").unwrap();
    assert_eq!(none.winches, None);
    assert!(!none.to_toml("x").contains("winch"));
}

#[test]
fn bad_winches_name_line_and_key() {
    let (line, key, message) = err(&robot([
        FULL,
        "winch = { drum_radius = -0.05, gear_ratio = 10.0, motor_inertia = 0.0 }",
        FULL,
    ]));
    assert_eq!((line, key.as_str()), (10, "cables[2].winch.drum_radius"));
    assert!(
        message.contains("-0.05") && message.contains("positive"),
        "{message}"
    );
    let (_, key, _) = err(&robot([
        "winch = { drum_radius = 0.05, gear_ratio = 10.0, motor_inertia = nan }",
        BARE,
        BARE,
    ]));
    assert_eq!(key, "cables[1].winch.motor_inertia");
    let (_, key, _) = err(&robot([
        BARE,
        BARE,
        "winch = { drum_radius = 0.05, gear_ratio = 10.0, motor_inertia = 0.0, max_speed = 0.0 }",
    ]));
    assert_eq!(key, "cables[3].winch.max_speed");
    let (_, key, message) = err(&robot([FULL, "", FULL]));
    assert_eq!(key, "cables.winch");
    assert!(message.contains("some cables but not all"), "{message}");
    // A missing or unknown field is named by the TOML reader, with the key of its line.
    let (line, key, message) = err(&robot([
        BARE,
        "winch = { drum_radius = 0.05, gear_ratio = 10.0 }",
        BARE,
    ]));
    assert_eq!((line, key.as_str()), (10, "cables[2].winch"));
    assert!(message.contains("motor_inertia"), "{message}");
    let (_, _, message) = err(&robot([
        BARE,
        BARE,
        "winch = { drum_radius = 0.05, gear_ratio = 10.0, motor_inertia = 0.0, friction = 1.0 }",
    ]));
    assert!(message.contains("friction"), "{message}");
}

#[test]
fn wirecenter_winch_is_read() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/wirecenter");
    // IPAnema.wcrfx: <motor inertia="0.001527" angular_velocity="6000" gear_ratio="3">,
    // <drum r_drum="0.1">, <cable max_velocity="2">: max_speed = min(6000 rpm = 628.3 rad/s,
    // 2 m/s × 3 / 0.1 m = 60 rad/s) = 60 rad/s.
    let d = RobotDescription::load(data.join("IPAnema.wcrfx")).unwrap();
    let w = d.winches.as_ref().unwrap();
    assert_eq!(w.len(), 8);
    assert_eq!(
        (w[0].drum_radius, w[0].gear_ratio, w[0].motor_inertia),
        (0.1, 3.0, 0.001527)
    );
    assert!((w[0].max_speed.unwrap() - 60.0).abs() < 1e-9);
    assert_eq!(w[0].max_torque, None);
    // HRPCables: G = 25, r = 0.075, max_velocity 2.618 m/s → 872.67 rad/s > 6000 rpm.
    let hrp = RobotDescription::load(data.join("HRPCables.wcrfx")).unwrap();
    let w = hrp.winches.unwrap();
    assert!((w[0].max_speed.unwrap() - 6000.0 * std::f64::consts::TAU / 60.0).abs() < 1e-9);
    // A file without <winch>: none. The writer says it drops them.
    let none = RobotDescription::load(data.join("MACARM.wcrfx")).unwrap();
    assert_eq!(none.winches, None);
    assert!(d.wcrfx_losses().iter().any(|l| l.contains("winches")));
}

/// Multi-layer drums (issue 29): `turns_per_layer` and `cable_length` read, written back, and
/// every wrong combination named by its key.
#[test]
fn layered_drum_keys_read_write_back_and_name_their_errors() {
    let layered = "winch = { drum_radius = 0.04, gear_ratio = 8.0, motor_inertia = 1e-4, cable_diameter = 0.003, turns_per_layer = 25, cable_length = 12.5 }";
    let d = RobotDescription::parse(&robot([layered, layered, layered]), "r.toml").unwrap();
    let w = d.winches.as_ref().unwrap();
    let l = w[1].layers.unwrap();
    assert_eq!((l.turns_per_layer, l.cable_length), (25, 12.5));
    let text = d.to_toml("round trip");
    assert_eq!(text.matches("turns_per_layer = 25").count(), 3, "{text}");
    assert_eq!(text.matches("cable_length = 12.5").count(), 3, "{text}");
    let again = RobotDescription::parse(&text, "again.toml").unwrap();
    assert_eq!(again.winches, d.winches);
    // Without the keys, no layers and nothing written.
    let plain = RobotDescription::parse(&robot([FULL, BARE, FULL]), "r.toml").unwrap();
    assert!(
        plain
            .winches
            .as_ref()
            .unwrap()
            .iter()
            .all(|w| w.layers.is_none())
    );
    let text = plain.to_toml("x");
    assert!(
        !text.contains("turns_per_layer") && !text.contains("cable_length"),
        "{text}"
    );
    let base = "drum_radius = 0.04, gear_ratio = 8.0, motor_inertia = 1e-4";
    for (extra, key, needle) in [
        (
            "cable_diameter = 0.003, turns_per_layer = 25",
            "cables[2].winch.turns_per_layer",
            "needs winch.cable_length",
        ),
        (
            "cable_diameter = 0.003, cable_length = 10.0",
            "cables[2].winch.cable_length",
            "needs winch.turns_per_layer",
        ),
        (
            "turns_per_layer = 25, cable_length = 10.0",
            "cables[2].winch.turns_per_layer",
            "needs winch.cable_diameter",
        ),
        (
            "cable_diameter = 0.003, turns_per_layer = 0, cable_length = 10.0",
            "cables[2].winch.turns_per_layer",
            "integer ≥ 1",
        ),
        (
            "cable_diameter = 0.003, turns_per_layer = -3, cable_length = 10.0",
            "cables[2].winch.turns_per_layer",
            "integer from 1",
        ),
        (
            "cable_diameter = 0.003, turns_per_layer = 25, cable_length = -1.0",
            "cables[2].winch.cable_length",
            "positive",
        ),
    ] {
        let bad = format!("winch = {{ {base}, {extra} }}");
        let (line, k, message) = err(&robot([layered, &bad, layered]));
        assert_eq!((line, k.as_str()), (10, key), "{extra}: {message}");
        assert!(message.contains(needle), "{extra}: {message}");
    }
    // A fractional turn count is refused by the TOML reader, naming the key.
    let bad = format!(
        "winch = {{ {base}, cable_diameter = 0.003, turns_per_layer = 2.5, cable_length = 10.0 }}"
    );
    let (_, key, message) = err(&robot([layered, &bad, layered]));
    assert_eq!(key, "cables[2].winch.turns_per_layer", "{message}");
    assert!(message.contains("2.5 must be an integer"), "{message}");
}
