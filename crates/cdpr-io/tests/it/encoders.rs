//! The robot-file keys `offset` and `gain` of each cable (issue 27: `cdpr calibrate -o` writes
//! the calibrated encoders): TOML read and write, defaults, errors naming file, line and key.

use cdpr_io::{Encoders, RobotDescription, RobotFileError};

fn robot(keys: [&str; 3]) -> String {
    let mut s = String::from("motion = \"point2\"\n[tension]\nmin = 1.0\nmax = 10.0\n");
    for (frame, k) in ["[1.0, 0.0]", "[-1.0, 1.0]", "[-1.0, -1.0]"]
        .iter()
        .zip(keys)
    {
        s += &format!("[[cables]]\nframe = {frame}\n{k}\n");
    }
    s
}

#[test]
fn offsets_and_gains_read_and_write_back_exactly() {
    let d = RobotDescription::parse(
        &robot([
            "offset = 0.0123456789012345\ngain = 1.0001",
            "offset = -0.05",
            "gain = 0.999",
        ]),
        "r.toml",
    )
    .unwrap();
    // Missing keys default to offset 0 and gain 1.
    assert_eq!(
        d.encoders,
        Some(Encoders {
            offsets: vec![0.0123456789012345, -0.05, 0.0],
            gains: vec![1.0001, 1.0, 0.999],
        })
    );
    let text = d.to_toml("round trip");
    assert_eq!(text.matches("\noffset = ").count(), 3, "{text}");
    assert_eq!(text.matches("\ngain = ").count(), 3, "{text}");
    let again = RobotDescription::parse(&text, "again.toml").unwrap();
    assert_eq!(again, d);
    // Length from a reading: l = g ρ + o.
    assert_eq!(
        d.encoders.as_ref().unwrap().lengths(&[2.0, 2.0, 2.0]),
        vec![1.0001 * 2.0 + 0.0123456789012345, 2.0 - 0.05, 0.999 * 2.0]
    );
    // Absent everywhere: none, and nothing written.
    let none = RobotDescription::parse(&robot(["", "", ""]), "r.toml").unwrap();
    assert_eq!(none.encoders, None);
    let text = none.to_toml("x");
    assert!(!text.contains("offset") && !text.contains("gain"), "{text}");
    // .wcrfx cannot hold them: listed among the losses.
    assert!(
        d.wcrfx_losses()
            .iter()
            .any(|l| l.contains("offsets and gains"))
    );
    assert!(none.wcrfx_losses().iter().all(|l| !l.contains("offsets")));
}

#[test]
fn bad_offsets_and_gains_name_line_and_key() {
    let err = |text: &str| match RobotDescription::parse(text, "r.toml").unwrap_err() {
        RobotFileError::Invalid {
            line, key, message, ..
        } => (line, key, message),
        e => panic!("unexpected {e}"),
    };
    let (line, key, message) = err(&robot(["", "gain = 0.0", ""]));
    assert_eq!((line, key.as_str()), (10, "cables[2].gain"));
    assert!(message.contains("zero"), "{message}");
    let (line, key, _) = err(&robot(["offset = nan", "", ""]));
    assert_eq!((line, key.as_str()), (7, "cables[1].offset"));
    let (_, key, _) = err(&robot(["", "", "gain = inf"]));
    assert_eq!(key, "cables[3].gain");
    // A value of the wrong type names its key too.
    let (_, key, _) = err(&robot(["", "", "offset = \"1 cm\""]));
    assert_eq!(key, "cables[3].offset");
}
