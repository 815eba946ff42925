//! The orientations request at one position: each sample's verdict is the workspace request's
//! at that orientation and position, and the map's fractions are the share of feasible samples
//! in each cell, counted here from the sample list.

use cdpr_api::{OrientationsRequest, Robot, RobotSource, WorkspaceCriteria, WorkspaceRequest};

/// An 8-cable spatial robot (examples/robots/ipanema-like-8.toml).
fn robot() -> Robot {
    let text = include_str!("../../../examples/robots/ipanema-like-8.toml");
    Robot::from_source(RobotSource::toml(text)).unwrap()
}

fn request(set: &str) -> OrientationsRequest {
    OrientationsRequest {
        robot: robot(),
        criteria: WorkspaceCriteria::default(),
        position: vec![0.0, 0.0, 0.5],
        orientations: set.into(),
    }
}

/// The workspace request's verdict at (0, 0, 0.5) m: the first corner of a one-cell grid.
fn feasible_at(angles_deg: [f64; 3]) -> bool {
    let mut w = WorkspaceRequest::new(robot());
    w.orientation = Some(angles_deg.map(f64::to_radians).to_vec());
    w.area = Some(vec![0.0, 1e-3, 0.0, 1e-3, 0.5, 0.501]);
    w.grid = Some(1);
    w.run().unwrap().workspace.feasible[0]
}

#[test]
fn each_sample_is_the_workspace_verdict_at_its_orientation() {
    let r = request("euler:rx=-20..20,rz=-40..40,n=5").run().unwrap();
    assert_eq!(r.count, 25);
    for s in &r.orientations {
        assert_eq!(s.feasible, feasible_at(s.angles_deg), "{:?}", s.angles_deg);
    }
    assert!(
        r.feasible_count > 0 && r.feasible_count < r.count,
        "a test that can fail"
    );
    // Two ranged angles, one sample per cell: the fraction is the verdict.
    assert_eq!((r.map.x.as_str(), r.map.y.as_str()), ("rx", "rz"));
    for s in &r.orientations {
        let i = r
            .map
            .x_deg
            .iter()
            .position(|&x| (x - s.angles_deg[0]).abs() < 1e-9);
        let j = r
            .map
            .y_deg
            .iter()
            .position(|&y| (y - s.angles_deg[2]).abs() < 1e-9);
        let v = r.map.fraction[j.unwrap()][i.unwrap()];
        assert_eq!(v, Some(if s.feasible { 1.0 } else { 0.0 }));
    }
}

#[test]
fn tilt_maps_count_the_azimuths() {
    let r = request("tilt:30,torsion=-40..40,n=5").run().unwrap();
    assert_eq!((r.map.x.as_str(), r.map.y.as_str()), ("torsion", "tilt"));
    for (j, &tilt) in r.map.y_deg.iter().enumerate() {
        for (i, &torsion) in r.map.x_deg.iter().enumerate() {
            let cell: Vec<bool> = r
                .orientations
                .iter()
                .filter(|s| (s.angles_deg[0] - tilt).abs() < 1e-9)
                .filter(|s| (s.angles_deg[2] - torsion).abs() < 1e-9)
                .map(|s| s.feasible)
                .collect();
            let share = cell.iter().filter(|&&f| f).count() as f64 / cell.len() as f64;
            assert_eq!(r.map.fraction[j][i], Some(share));
        }
    }
}

#[test]
fn errors_name_the_options() {
    let mut r = request("tilt:30,n=3");
    r.position = vec![0.0, 0.0];
    let e = r.validate().unwrap_err().to_string();
    assert!(e.starts_with("--position needs 3 finite numbers"), "{e}");
}
