//! The robot-file key `linear_density` (issue 29 contract): TOML read and write, WireCenter's
//! `<cable weight>`, errors naming file, line and key.

use cdpr_io::{RobotDescription, RobotFileError};
use std::path::Path;

fn robot(densities: [&str; 3]) -> String {
    let mut s = String::from("motion = \"point2\"\n[tension]\nmin = 1.0\nmax = 10.0\n");
    for (frame, rho) in ["[1.0, 0.0]", "[-1.0, 1.0]", "[-1.0, -1.0]"]
        .iter()
        .zip(densities)
    {
        s += &format!("[[cables]]\nframe = {frame}\n{rho}\n");
    }
    s
}

#[test]
fn toml_key_reads_and_writes_back() {
    let d = RobotDescription::parse(
        &robot([
            "linear_density = 0.02",
            "linear_density = 0.0",
            "linear_density = 1.5",
        ]),
        "r.toml",
    )
    .unwrap();
    assert_eq!(d.linear_density, Some(vec![0.02, 0.0, 1.5]));
    let text = d.to_toml("round trip");
    assert_eq!(text.matches("linear_density = ").count(), 3, "{text}");
    let again = RobotDescription::parse(&text, "again.toml").unwrap();
    assert_eq!(again.linear_density, d.linear_density);
    // Absent everywhere: none, and nothing written.
    let none = RobotDescription::parse(&robot(["", "", ""]), "r.toml").unwrap();
    assert_eq!(none.linear_density, None);
    assert!(!none.to_toml("x").contains("linear_density"));
}

#[test]
fn bad_densities_name_line_and_key() {
    let err = |text: &str| match RobotDescription::parse(text, "r.toml").unwrap_err() {
        RobotFileError::Invalid {
            line, key, message, ..
        } => (line, key, message),
        e => panic!("unexpected {e}"),
    };
    let (line, key, message) = err(&robot(["", "linear_density = -0.1", ""]));
    assert_eq!((line, key.as_str()), (10, "cables[2].linear_density"));
    assert!(message.contains("negative"), "{message}");
    let (_, key, message) = err(&robot(["linear_density = 0.1", "", ""]));
    assert_eq!(key, "cables.linear_density");
    assert!(message.contains("some cables but not all"), "{message}");
    let (_, key, _) = err(&robot(["linear_density = nan", "", ""]));
    assert_eq!(key, "cables[1].linear_density");
}

#[test]
fn wirecenter_cable_weight_is_the_linear_density() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/wirecenter");
    // CoGiRo.wcrfx: <cable ... weight="0.023000" />.
    let d = RobotDescription::load(data.join("CoGiRo.wcrfx")).unwrap();
    assert_eq!(d.linear_density, Some(vec![0.023; 8]));
    let lucia = RobotDescription::load(data.join("EXPO2015_Lucia.wcrfx")).unwrap();
    assert_eq!(lucia.linear_density, Some(vec![0.198; 8]));
    // Written back as the cable type's weight.
    let text = d.to_wcrfx("x.wcrfx").unwrap();
    assert!(text.contains("weight=\"0.023\""), "{text}");
    let again = RobotDescription::parse_wcrfx(&text, "x.wcrfx").unwrap();
    assert_eq!(again.linear_density, d.linear_density);
    // Per-cable densities that differ do not fit one cable type.
    let mut mixed = d.clone();
    mixed.linear_density.as_mut().unwrap()[3] = 0.05;
    assert!(matches!(
        mixed.to_wcrfx("x.wcrfx"),
        Err(RobotFileError::Unrepresentable { .. })
    ));
}
