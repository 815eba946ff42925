//! The dextrous workspace request: its verdicts are the intersection of the constant-orientation
//! workspaces of its slices (each computed by the workspace request, one orientation at a time),
//! its §6.5 check counts what that intersection says, and its errors name the options.

use cdpr_api::{DextrousRequest, RangeReport, Robot, RobotSource, WorkspaceRequest};

/// The four-cable planar robot of the thesis (examples/robots/tdpm-4.toml).
fn tdpm4() -> Robot {
    let text = include_str!("../../../examples/robots/tdpm-4.toml");
    Robot::from_source(RobotSource::toml(text)).unwrap()
}

const RANGE: RangeReport = RangeReport {
    min: -0.2,
    max: 0.2,
    slices: 5,
};

fn request() -> DextrousRequest {
    let mut r = DextrousRequest::new(tdpm4(), RANGE);
    r.criteria.wrench = Some(vec![0.0, -10.0, 0.0]);
    r.grid = Some(16);
    r
}

/// The verdicts of the workspace request at orientation φ, same criteria, box and grid.
fn slice(phi: f64) -> Vec<bool> {
    let d = request();
    let mut w = WorkspaceRequest::new(d.robot);
    (w.criteria, w.grid, w.orientation) = (d.criteria, d.grid, Some(vec![phi]));
    w.run().unwrap().workspace.feasible
}

#[test]
fn dextrous_verdicts_are_the_intersection_of_the_slices() {
    let r = request().run().unwrap();
    let even = [-0.2, -0.1, 0.0, 0.1, 0.2];
    assert!(
        r.angles
            .iter()
            .zip(even)
            .all(|(a, b)| (a - b).abs() < 1e-15)
    );
    let slices: Vec<Vec<bool>> = r.angles.iter().map(|&a| slice(a)).collect();
    let n = slices[0].len();
    let every = |k: usize| slices.iter().all(|s| s[k]);
    let expected: Vec<bool> = (0..n).map(every).collect();
    assert_eq!(r.workspace.feasible, expected);
    let feasible = expected.iter().filter(|&&v| v).count();
    assert!(
        feasible > 0 && feasible < n,
        "{feasible} of {n}: a test that can fail"
    );
    assert_eq!(r.feasible_points, feasible);
    // §6.5: points feasible at both extremes, and those of them the central slice (φ = 0) loses.
    let extremes = (0..n).filter(|&k| slices[0][k] && slices[4][k]);
    assert_eq!(r.central_check.extremes_points, extremes.clone().count());
    let violations = extremes.filter(|&k| !slices[2][k]).count();
    assert_eq!(r.central_check.violations, violations);
    assert_eq!(r.central_check.holds, violations == 0);
    assert_eq!(r.area, r.area_cells);
    assert_eq!(r.total_points, 17 * 17);
}

#[test]
fn dextrous_errors_name_the_options() {
    let mut r = request();
    r.axis = Some(vec![0.0, 0.0, 1.0]);
    let e = r.validate().unwrap_err().to_string();
    assert!(
        e.contains("--axis and --orientation apply to spatial robots"),
        "{e}"
    );
    let mut r = request();
    r.orientations.slices = 1;
    assert!(r.validate().is_err());
    let mut r = request();
    r.grid = Some(0);
    let e = r.validate().unwrap_err().to_string();
    assert!(e.contains("--grid M must lie in"), "{e}");
}

#[test]
fn dextrous_json_has_the_command_line_fields() {
    let r = request().run().unwrap();
    let v = serde_json::to_value(&r).unwrap();
    let keys: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
    let expected = [
        "angles",
        "area",
        "area_cells",
        "area_points",
        "box",
        "cell_area",
        "central_check",
        "criteria",
        "dimension",
        "feasible_points",
        "orientations",
        "resolution",
        "robot",
        "tension_method",
        "total_points",
        "volume_convention",
    ];
    assert_eq!(keys, expected);
}
