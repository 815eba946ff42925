//! The stiffness-map request (Picard, Caro, Plestan & Claveau 2020, Fig. 4): the barycentre's and
//! the optimum's tensions balance the load (W t + w_ext = 0, W from the kinematics request), the
//! optimum's displacement is no more than any grid value's, the curve runs from the barycentre
//! (ν = 0) to the optimum (ν = 1), and a robot without redundancy 2 is refused.

use cdpr_api::{KinematicsRequest, Robot, RobotSource, StiffnessMapRequest};

fn robot(text: &str) -> Robot {
    Robot::from_source(RobotSource::toml(text)).unwrap()
}

fn rowc() -> Robot {
    robot(include_str!("../../../examples/robots/rowc-like-8.toml"))
}

const POSE: [f64; 6] = [1.5, 0.35, 0.59, 0.0, 0.0, 0.0];

fn request() -> StiffnessMapRequest {
    let mut r = StiffnessMapRequest::new(rowc(), POSE.to_vec());
    r.wrench = Some(vec![0.0, 50.0, 0.0, 0.0, 0.0, 0.0]);
    r.grid = 24;
    r
}

#[test]
fn tensions_balance_the_load_and_the_optimum_is_least() {
    let report = request().run().unwrap();
    assert!(report.feasible && report.reason.is_none());
    let map = report.map.unwrap();
    let k = KinematicsRequest {
        robot: rowc(),
        pose: POSE.to_vec(),
    }
    .run()
    .unwrap();
    for t in [&map.tensions_barycenter, &map.tensions_optimum] {
        for (row, w) in k.wrench_matrix.iter().zip(&map.external_wrench) {
            let wt: f64 = row.iter().zip(t).map(|(a, b)| a * b).sum();
            assert!(
                (wt + w).abs() < 1e-6 * (1.0 + w.abs()),
                "W t + w_ext = {}",
                wt + w
            );
        }
    }
    let values: Vec<f64> = map
        .grid
        .values
        .iter()
        .flatten()
        .flatten()
        .copied()
        .collect();
    assert!(values.len() > 10, "the grid samples the polygon");
    for v in &values {
        assert!(map.displacement_optimum <= v + 1e-9, "{v} < the optimum");
    }
    let (first, last) = (map.nu_curve[0], map.nu_curve[map.nu_curve.len() - 1]);
    assert_eq!((first[0], last[0]), (0.0, 1.0));
    assert!((first[1] - map.displacement_barycenter).abs() < 1e-9);
    assert!((last[1] - map.displacement_optimum).abs() < 1e-9);
    let r = 100.0 * (map.displacement_barycenter - map.displacement_optimum)
        / map.displacement_barycenter;
    assert!((map.reduction_percent - r).abs() < 1e-12);
}

#[test]
fn redundancy_other_than_two_is_refused() {
    let tdpm4 = robot(include_str!("../../../examples/robots/tdpm-4.toml"));
    let e = StiffnessMapRequest::new(tdpm4, vec![0.0, 0.0, 0.0])
        .validate()
        .unwrap_err()
        .to_string();
    assert!(!e.is_empty());
    let mut r = request();
    r.grid = 1;
    let e = r.validate().unwrap_err().to_string();
    assert_eq!(e, "--grid must lie in [2, 2000]");
}
