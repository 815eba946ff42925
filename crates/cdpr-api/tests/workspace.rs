//! The workspace request: hand-derived areas, the same verdicts as the library's own grid
//! routine, its progress callback, its validation errors and its JSON form.

use std::sync::atomic::{AtomicUsize, Ordering};

use cdpr_api::nalgebra::Rotation3;
use cdpr_api::{Robot, RobotSource, WorkspaceRequest};
use cdpr_workspace::{
    Criterion, Grid, PoseEvaluator, Region, VolumeConvention, constant_orientation_workspace,
};

/// A point2 robot: four cables from (±1, ±1), tensions in [1, 10] N, no mass.
const SQUARE: &str = r#"
name = "square"
motion = "point2"

[tension]
min = 1.0
max = 10.0

[[cables]]
frame = [1.0, 1.0]
[[cables]]
frame = [-1.0, 1.0]
[[cables]]
frame = [-1.0, -1.0]
[[cables]]
frame = [1.0, -1.0]
"#;

fn square() -> Robot {
    Robot::from_source(RobotSource::toml(SQUARE)).unwrap()
}

/// Wrench closure over [0.4, 1.6] × [−0.6, 0.6] with M = 3.
fn closure_request() -> WorkspaceRequest {
    let mut r = WorkspaceRequest::new(square());
    r.criteria.criteria = Some("wrench-closure".into());
    r.area = Some(vec![0.4, 1.6, -0.6, 0.6]);
    r.grid = Some(3);
    r
}

#[test]
fn wrench_closure_area_of_the_square_by_hand() {
    // x = 0.4, 0.8 lie inside the square of anchors (closure), x = 1.2, 1.6 outside; every
    // y = −0.6, −0.2, 0.2, 0.6 inside: 2 × 4 = 8 feasible points, cells 0.4 × 0.4 = 0.16 m².
    // Points: 8 × 0.16 = 1.28 m². Cells clipped to the box: x weights 1/2 (edge) + 1, y weights
    // 1/2 + 1 + 1 + 1/2 = 3, so 4.5 cells = 0.72 m².
    let r = closure_request().run().unwrap();
    assert_eq!((r.feasible_points, r.total_points), (8, 16));
    assert!((r.cell_area - 0.16).abs() < 1e-12);
    assert!((r.area_points - 1.28).abs() < 1e-12);
    assert!((r.area_cells - 0.72).abs() < 1e-12);
    assert_eq!(r.area, r.area_cells);
    assert_eq!(r.volume_convention, "cells");
    assert_eq!(r.method, "grid");
    assert_eq!(r.criteria, vec!["wrench-closure"]);
    assert_eq!(r.area_box, vec![0.4, 1.6, -0.6, 0.6]);
    assert!(r.orientation.is_empty() && r.volume.is_none());
    assert_eq!(r.external_wrench, vec![0.0, 0.0]);
}

#[test]
fn the_verdicts_are_those_of_the_library_grid() {
    let mut request = WorkspaceRequest::new(square());
    request.grid = Some(12);
    request.area = Some(vec![-1.2, 1.2, -1.1, 1.3]);
    let report = request.run().unwrap();
    let desc = request.robot.description();
    let eval = PoseEvaluator::new(
        desc.robot.clone(),
        desc.bounds.clone(),
        vec![Criterion::TensionFeasible {
            method: cdpr_api::Method::L2, // the default: n = 4 > DOF = 2
            wrench: cdpr_api::nalgebra::DVector::zeros(2),
        }],
    )
    .unwrap();
    let grid = Grid::new(12, Region::planar(-1.2, 1.2, -1.1, 1.3));
    let direct = constant_orientation_workspace(&eval, &Rotation3::identity(), &grid).unwrap();
    assert_eq!(report.workspace, direct);
    assert!(report.feasible_points > 0 && report.feasible_points < report.total_points);
}

#[test]
fn progress_counts_rows() {
    let rows = AtomicUsize::new(0);
    closure_request()
        .run_with_progress(&|| {
            rows.fetch_add(1, Ordering::Relaxed);
        })
        .unwrap();
    assert_eq!(rows.load(Ordering::Relaxed), 4);
}

#[test]
fn validation_names_the_option() {
    let msg = |r: WorkspaceRequest| r.validate().unwrap_err().to_string();
    let mut r = closure_request();
    r.grid = Some(0);
    assert_eq!(msg(r), "--grid M must lie in [1, 4000] for a 2-D grid");
    let mut r = closure_request();
    r.criteria.criteria = Some("capacity".into());
    assert!(msg(r).contains("--criteria capacity needs --wrench-box"));
    let mut r = closure_request();
    r.criteria.acceleration_box = Some(vec![1.0, 1.0]);
    assert_eq!(msg(r), "--acceleration-box needs `dynamic` in --criteria");
    let mut r = closure_request();
    r.area = Some(vec![1.0, 0.0, 0.0, 1.0]);
    assert!(msg(r).contains("must be less than"));
    let mut r = closure_request();
    r.orientation = Some(vec![0.3]);
    assert!(msg(r).contains("has no orientation"));
    let mut r = closure_request();
    r.criteria.criteria = Some("nonsense".into());
    assert!(msg(r).starts_with("--criteria: unknown criterion `nonsense`"));
}

#[test]
fn a_browser_request_in_json() {
    let json = serde_json::json!({
        "robot": { "format": "toml", "text": SQUARE },
        "criteria": "wrench-closure",
        "box": [0.4, 1.6, -0.6, 0.6],
        "grid": 3,
        "volume_convention": "points",
    });
    let r: WorkspaceRequest = serde_json::from_value(json).unwrap();
    assert_eq!(r.volume_convention, VolumeConvention::Points);
    let report = r.run().unwrap();
    assert!((report.area - 1.28).abs() < 1e-12);
    let back: WorkspaceRequest = serde_json::from_str(&serde_json::to_string(&r).unwrap()).unwrap();
    assert_eq!(back.run().unwrap().workspace, report.workspace);
    let value = serde_json::to_value(&report).unwrap();
    assert_eq!(value["box"], serde_json::json!([0.4, 1.6, -0.6, 0.6]));
    assert!(value.get("workspace").is_none() && value.get("volume").is_none());
    let defaults: WorkspaceRequest = serde_json::from_value(
        serde_json::json!({ "robot": { "format": "toml", "text": SQUARE } }),
    )
    .unwrap();
    assert_eq!(defaults.volume_convention, VolumeConvention::Cells);
    assert_eq!(defaults.run().unwrap().resolution, 50);
}
