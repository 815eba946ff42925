//! `CalibrationRequest`: the samples CSV of `cdpr calibrate` (errors naming line and column),
//! the same calibration from CSV text and from arrays, and the request as JSON.

use cdpr_api::{CalibrationRequest, Robot, RobotSource, SamplesSource, parse_samples_csv};
use cdpr_kinematics::{MotionPattern, Pose, Robot as Geometry};

fn spidercam() -> Robot {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/robots/spidercam-like-4.toml"
    ))
    .unwrap();
    Robot::from_source(RobotSource::toml(text)).unwrap()
}

fn csv_error(text: &str, known_poses: bool) -> String {
    parse_samples_csv(text, "s.csv", MotionPattern::Point3, 4, known_poses)
        .unwrap_err()
        .to_string()
}

#[test]
fn csv_errors_name_the_file_line_and_column() {
    // Line numbers count comments and blank lines; columns count from 1.
    let e = csv_error("# c\n\nl1,l2,l3,l4\n1,2,x,4\n", false);
    assert_eq!(e, "s.csv:4, column 3 (`l3`): `x` is not a number");
    let e = csv_error("l1,l2,l3,l4\n1,2,3\n", false);
    assert_eq!(e, "s.csv:2: 3 fields, the header has 4 columns");
    let e = csv_error("l1,l2,l4\n", false);
    assert!(e.starts_with("s.csv:1: missing column `l3`"), "{e}");
    let e = csv_error("x,l1,l2,l3,l4\n", false);
    assert_eq!(
        e,
        "s.csv:1, column 1: unexpected column `x` (expected l1,l2,l3,l4; pose columns need --known-poses)"
    );
    let e = csv_error("l1,l2,l3,l4\n1,inf,3,4\n", false);
    assert_eq!(e, "s.csv:2, column 2 (`l2`): not a finite number (inf)");
    assert_eq!(
        csv_error("# only\n", false),
        "s.csv: no header line (expected l1,…,l4)"
    );
    assert_eq!(
        csv_error("l1,l2,l3,l4\n", false),
        "s.csv: no samples after the header"
    );
}

#[test]
fn csv_columns_are_found_by_name_in_any_order() {
    let s = parse_samples_csv(
        "L4, z, l1, y, l2, x, l3\n4,3,1,2,2,1,3\n",
        "s.csv",
        MotionPattern::Point3,
        4,
        true,
    )
    .unwrap();
    assert_eq!(s.readings, [1.0, 2.0, 3.0, 4.0]);
    let p = &s.poses.unwrap()[0];
    assert_eq!(p.position.as_slice(), [1.0, 2.0, 3.0]);
}

/// Samples of the nominal robot at known poses: the calibration from the CSV text and from
/// arrays is the same, and recovers the nominal anchors with zero offsets.
#[test]
fn csv_and_arrays_give_one_calibration() {
    let robot = spidercam();
    let geo: &Geometry = &robot.robot;
    let poses: Vec<[f64; 3]> = (0..8)
        .map(|j| {
            let t = j as f64;
            [
                30.0 * (0.7 * t).sin(),
                20.0 * (1.3 * t + 0.4).cos(),
                12.0 + 6.0 * (0.5 * t).sin(),
            ]
        })
        .collect();
    let lengths: Vec<Vec<f64>> = poses
        .iter()
        .map(|p| {
            geo.inverse_kinematics(&Pose::point(p[0], p[1], p[2]))
                .unwrap()
                .lengths()
                .collect()
        })
        .collect();
    let mut text = String::from("x,y,z,l1,l2,l3,l4\n");
    for (p, l) in poses.iter().zip(&lengths) {
        let row: Vec<String> = p.iter().chain(l).map(|v| format!("{v:?}")).collect();
        text += &(row.join(",") + "\n");
    }
    let from_csv = CalibrationRequest::new(
        robot.clone(),
        SamplesSource::Csv {
            text,
            file: None,
            known_poses: true,
        },
    );
    let from_arrays = CalibrationRequest::new(
        robot.clone(),
        SamplesSource::Arrays {
            readings: lengths,
            poses: Some(poses.iter().map(|p| p.to_vec()).collect()),
        },
    );
    let (a, b) = (from_csv.run().unwrap(), from_arrays.run().unwrap());
    assert_eq!(
        serde_json::to_value(&a).unwrap(),
        serde_json::to_value(&b).unwrap()
    );
    assert_eq!((a.samples, a.cables, a.known_poses), (8, 4, true));
    for (c, f) in geo.cables().iter().zip(&a.frame) {
        for k in 0..3 {
            assert!((c.frame[k] - f[k]).abs() < 1e-6, "{f:?}");
        }
    }
    assert!(a.offsets.iter().all(|o| o.abs() < 1e-6), "{:?}", a.offsets);
}

#[test]
fn requests_are_checked_in_the_order_the_command_line_reports() {
    let robot = spidercam();
    let mut r = CalibrationRequest::new(
        robot,
        SamplesSource::Arrays {
            readings: vec![vec![1.0, 2.0, 3.0]],
            poses: None,
        },
    );
    assert_eq!(
        r.validate().unwrap_err().to_string(),
        "samples: row 1 has 3 readings, expected 4 (one per cable)"
    );
    r.unknowns = "frame,bogus".into();
    assert!(
        r.validate().unwrap_err().to_string().contains("`bogus`"),
        "the unknowns come first"
    );
}

/// The request travels as JSON (a browser sends it): CSV text inside.
#[test]
fn a_request_deserialises_from_json() {
    let toml = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/robots/spidercam-like-4.toml"
    ))
    .unwrap();
    let csv = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/calibration/spidercam-known.csv"
    ))
    .unwrap();
    let json = serde_json::json!({
        "robot": { "format": "toml", "text": toml },
        "samples": { "csv": { "text": csv, "known_poses": true } },
    });
    let r: CalibrationRequest = serde_json::from_value(json).unwrap();
    assert_eq!(r.unknowns, "frame,offsets");
    let report = r.run().unwrap();
    assert!(report.identifiable);
    assert_eq!(report.unknowns, ["frame", "offsets"]);
}
