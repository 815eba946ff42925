//! The orientation-set workspace request: a total-orientation workspace is the intersection and
//! a maximal one the union of the constant-orientation workspaces of the sampled orientations
//! (each computed by the workspace request), and the mesh of a set seeds on that grid.

use cdpr_api::{OrientationWorkspaceRequest, Robot, RobotSource, WorkspaceRequest};

/// An 8-cable spatial robot (examples/robots/rowc-like-8.toml).
fn robot() -> Robot {
    let text = include_str!("../../../examples/robots/rowc-like-8.toml");
    Robot::from_source(RobotSource::toml(text)).unwrap()
}

/// rx ∈ {−5°, 5°}, ry = rz = 0.
const SET: &str = "euler:rx=-5..5,n=2";

fn request(kind: &str) -> OrientationWorkspaceRequest {
    let mut r = OrientationWorkspaceRequest::new(robot(), SET);
    r.kind = Some(kind.into());
    r.grid = Some(6);
    r
}

/// The workspace request's verdicts at rx (degrees).
fn at(rx_deg: f64) -> Vec<bool> {
    let mut w = WorkspaceRequest::new(robot());
    w.grid = Some(6);
    w.orientation = Some(vec![rx_deg.to_radians(), 0.0, 0.0]);
    w.run().unwrap().workspace.feasible
}

#[test]
fn total_is_the_intersection_and_maximal_the_union_of_the_samples() {
    let (a, b) = (at(-5.0), at(5.0));
    let total = request("total").run().unwrap();
    let maximal = request("maximal").run().unwrap();
    let and: Vec<bool> = a.iter().zip(&b).map(|(x, y)| *x && *y).collect();
    let or: Vec<bool> = a.iter().zip(&b).map(|(x, y)| *x || *y).collect();
    assert_eq!(total.workspace.feasible, and);
    assert_eq!(maximal.workspace.feasible, or);
    assert!(
        total.feasible_points < maximal.feasible_points,
        "the samples differ"
    );
    assert_eq!(
        (total.kind.as_str(), maximal.kind.as_str()),
        ("total", "maximal")
    );
    assert_eq!(total.orientation_count, 2);
    assert_eq!(total.angle_names, ["rx", "ry", "rz"].map(String::from));
    // Every limiting orientation is one of the two samples, and counts sum to the entries.
    let n: usize = total
        .limiting_summary
        .iter()
        .map(|l| l.boundary_points)
        .sum();
    assert_eq!(n, total.limiting_orientations.len());
    for l in &total.limiting_orientations {
        assert!((l.angles_deg[0].abs() - 5.0).abs() < 1e-9 && l.angles_deg[1] == 0.0);
    }
    assert!(maximal.limiting_orientations.is_empty());
}

#[test]
fn the_mesh_of_a_set_counts_the_same_grid() {
    let grid = request("total").run().unwrap();
    let mesh = request("total").run_mesh().unwrap();
    assert_eq!(mesh.feasible_points, grid.feasible_points);
    assert!(mesh.watertight && mesh.volume > 0.0);
}

#[test]
fn errors_name_the_options() {
    let mut r = request("total");
    r.kind = Some("some".into());
    let e = r.validate().unwrap_err().to_string();
    assert!(e.contains("--kind `some`"), "{e}");
    let mut r = request("total");
    r.orientations = "euler:rx=1..".into();
    let e = r.validate().unwrap_err().to_string();
    assert!(e.starts_with("--orientations euler:rx=1..:"), "{e}");
}
