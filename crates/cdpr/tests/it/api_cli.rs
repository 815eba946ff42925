//! Issue 25: the `--json` output of a converted command IS the serialised report of its
//! `cdpr-api` request, built here from the same robot file and options.

use crate::common::{json, robot};
use cdpr::api::{
    CapacityRequest, ForwardRequest, IsotropicMapRequest, IsotropicRequest, KinematicsRequest,
    Method, Robot, RobotSource, StiffnessRequest, TensionRequest,
};

fn api_robot(name: &str) -> Robot {
    let text = std::fs::read_to_string(robot(name)).unwrap();
    Robot::from_source(RobotSource::toml(text)).unwrap()
}

fn same<T: serde::Serialize>(report: &T, cli: serde_json::Value) {
    assert_eq!(serde_json::to_value(report).unwrap(), cli);
}

#[test]
fn pose_commands_print_their_reports() {
    let (file, pose) = (robot("tdpm-4.toml"), "0.1,-0.05,0.1");
    let q = vec![0.1, -0.05, 0.1];
    let r = KinematicsRequest {
        robot: api_robot("tdpm-4.toml"),
        pose: q.clone(),
    };
    same(
        &r.run().unwrap(),
        json(&["kinematics", &file, "--pose", pose, "--json"]),
    );

    let mut t = TensionRequest::new(api_robot("tdpm-4.toml"), q.clone(), Method::ClosedForm);
    t.wrench = Some(vec![0.0, -10.0, 0.0]);
    same(
        &t.run().unwrap(),
        json(&[
            "tension",
            &file,
            "--pose",
            pose,
            "--wrench",
            "0,-10,0",
            "--method",
            "closed-form",
            "--json",
        ]),
    );

    let c = CapacityRequest {
        robot: api_robot("tdpm-4.toml"),
        pose: q.clone(),
        wrench: None,
        wrench_box: Some(vec![5.0, 5.0, 0.5]),
        wrench_ball: None,
        force_radius: None,
        moment_radius: None,
    };
    same(
        &c.run().unwrap(),
        json(&[
            "capacity",
            &file,
            "--pose",
            pose,
            "--wrench-box",
            "5,5,0.5",
            "--json",
        ]),
    );

    let i = IsotropicRequest {
        robot: api_robot("krut-4.toml"),
        pose: vec![0.0, 0.0],
        wrench: None,
        ellipse: true,
    };
    let krut = robot("krut-4.toml");
    same(
        &i.run().unwrap(),
        json(&["isotropic", &krut, "--pose", "0,0", "--ellipse", "--json"]),
    );

    let s = StiffnessRequest {
        robot: api_robot("tdpm-4.toml"),
        pose: q.clone(),
        tensions: Some(vec![10.0, 20.0, 30.0, 40.0]),
        method: None,
        wrench: None,
        axial_stiffness: Some(1000.0),
    };
    same(
        &s.run().unwrap(),
        json(&[
            "stiffness",
            &file,
            "--pose",
            pose,
            "--tensions",
            "10,20,30,40",
            "--axial-stiffness",
            "1000",
            "--json",
        ]),
    );

    let lengths = r.run().unwrap().lengths;
    let l: Vec<String> = lengths.iter().map(|v| format!("{v:?}")).collect();
    let f = ForwardRequest {
        robot: api_robot("tdpm-4.toml"),
        lengths,
        guess: Some(vec![0.0, 0.0, 0.0]),
        tolerance: 1e-9,
        length_sigma: 1e-4,
        max_iterations: 100,
    };
    same(
        &f.run().unwrap(),
        json(&[
            "forward",
            &file,
            "--lengths",
            &l.join(","),
            "--guess",
            "0,0,0",
            "--json",
        ]),
    );
}

#[test]
fn the_isotropic_map_prints_its_report() {
    let m = IsotropicMapRequest {
        robot: api_robot("krut-4.toml"),
        grid: 6,
        area: None,
        orientation: 0.0,
        wrench: None,
        z: None,
    };
    let file = robot("krut-4.toml");
    same(
        &m.run().unwrap(),
        json(&["isotropic", &file, "--grid", "6", "--json"]),
    );
}
