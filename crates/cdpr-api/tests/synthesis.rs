//! `SynthesisRequest`: the command line's checks and messages, and the invariants of a run
//! (the design keeps its separation, never loses area, its anchors sit on the square frame,
//! A_d is feasible points × cell area).

use cdpr_api::{RangeReport, Robot, RobotSource, SynthesisOptimizer, SynthesisRequest};

fn robot(file: &str) -> Robot {
    let text = std::fs::read_to_string(format!(
        "{}/../../examples/robots/{file}",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    Robot::from_source(RobotSource::toml(text)).unwrap()
}

const RANGE: RangeReport = RangeReport {
    min: -0.1,
    max: 0.1,
    slices: 3,
};

fn error(r: &SynthesisRequest) -> String {
    r.validate().unwrap_err().to_string()
}

#[test]
fn bad_requests_get_the_command_line_messages() {
    let r = SynthesisRequest::new(robot("tdpm-3.toml"), RANGE, vec![0.0, 1.0]);
    assert_eq!(
        error(&r),
        "--start has 2 angles but the robot file has 3 cables (one angle per cable)"
    );
    let r = SynthesisRequest::new(robot("ipanema-like-8.toml"), RANGE, vec![0.0; 8]);
    assert!(
        error(&r).contains("this robot is `spatial` (need planar)"),
        "{}",
        error(&r)
    );
    let mut r = SynthesisRequest::new(robot("tdpm-3.toml"), RANGE, vec![0.8, 2.4, 4.7]);
    r.grid = Some(1001);
    assert_eq!(error(&r), "--grid M must lie in [1, 1000]");
    r.grid = None;
    r.min_separation = Some(3.0);
    let e = error(&r);
    assert!(
        e.starts_with("--min-separation: ") && e.contains("2π/3 = 2.0944 rad"),
        "{e}"
    );
    r.min_separation = None;
    r.grid_box = Some(vec![1.0, 2.0, 3.0]);
    assert!(
        error(&r).starts_with("--grid-box needs 4 numbers"),
        "{}",
        error(&r)
    );
    r.grid_box = None;
    assert!(r.validate().is_ok());
    // The default grid is the thesis': 100 for 3 cables, 50 for 4.
    assert_eq!(r.resolution(), 100);
    let r4 = SynthesisRequest::new(robot("tdpm-4.toml"), RANGE, vec![0.8, 2.4, 3.9, 5.5]);
    assert_eq!(r4.resolution(), 50);
}

#[test]
fn a_run_keeps_its_invariants() {
    let mut r = SynthesisRequest::new(robot("tdpm-3.toml"), RANGE, vec![0.2814, 3.978, 4.278]);
    r.criteria.wrench = Some(vec![0.0, -10.0, 0.0]);
    r.grid = Some(16);
    r.optimizer = SynthesisOptimizer::Compass;
    let calls = std::sync::atomic::AtomicUsize::new(0);
    let report = r
        .run_with_progress(&|k| calls.store(k, std::sync::atomic::Ordering::Relaxed))
        .unwrap();
    assert_eq!(
        calls.into_inner(),
        report.evaluations.function,
        "one progress call per area evaluation"
    );
    assert!(report.area >= report.start_area, "{report:?}");
    assert_eq!(
        report.area,
        report.feasible_points as f64 * report.cell_area,
        "points convention"
    );
    assert_eq!((report.total_points, report.resolution), (17 * 17, 16));
    assert_eq!(report.constraint_violation, 0.0);
    for a in &report.anchors {
        assert!((a[0].abs().max(a[1].abs()) - 1.0).abs() < 1e-12, "{a:?}");
    }
    assert!(report.design[0].abs() <= std::f64::consts::PI);
    let json = serde_json::to_value(&report).unwrap();
    assert_eq!(json["optimizer"], "compass");
    assert_eq!(json["volume_convention"], "points");
    assert_eq!(json["box"], serde_json::json!([-1.0, 1.0, -1.0, 1.0]));
    assert!(json.get("workspace").is_none() && json.get("design_raw").is_none());
}

/// The request travels as JSON with the command line's defaults.
#[test]
fn a_request_deserialises_from_json_with_defaults() {
    let toml = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/robots/tdpm-3.toml"
    ))
    .unwrap();
    let r: SynthesisRequest = serde_json::from_value(serde_json::json!({
        "robot": { "format": "toml", "text": toml },
        "orientations": { "min": -0.1, "max": 0.1, "slices": 3 },
        "start": [0.8, 2.4, 4.7],
        "optimizer": "global",
    }))
    .unwrap();
    assert_eq!(r.optimizer, SynthesisOptimizer::Global);
    assert_eq!((r.move_limit, r.grid, r.min_separation), (0.1, None, None));
    assert!(r.validate().is_ok());
}
