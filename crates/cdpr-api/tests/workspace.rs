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

/// CoGiRo (15 × 11 m, 25 kg; WireCenter's file), straight cables from the frame points
/// (`--kinematics standard`), with its `linear_density` replaced by `density` (kg/m) and its
/// `[tension] max` by `max` (N) when given.
fn cogiro(density: Option<f64>, max: Option<f64>) -> Robot {
    let mut text = include_str!("../../../examples/robots/wirecenter-cogiro.toml").to_string();
    if let Some(d) = density {
        text = text.replace("linear_density = 0.023", &format!("linear_density = {d:?}"));
    }
    if let Some(m) = max {
        text = text.replace("max = 720.0", &format!("max = {m:?}"));
    }
    let mut source = RobotSource::toml(text);
    source.kinematics = Some(cdpr_api::KinematicsModel::Standard);
    Robot::from_source(source).unwrap()
}

/// The grid verdicts (M = 6 over the anchors' box) of `criteria` under `cable_model`.
fn cogiro_verdicts(robot: Robot, criteria: &str, cable_model: Option<&str>) -> Vec<bool> {
    let mut r = WorkspaceRequest::new(robot);
    r.grid = Some(6);
    r.criteria.criteria = Some(criteria.into());
    r.criteria.wrench_box = Some(vec![5.0, 5.0, 5.0, 1.0, 1.0, 1.0]);
    r.criteria.cable_model = cable_model.map(Into::into);
    r.run().unwrap().workspace.feasible
}

#[test]
fn weightless_and_elastic_cables_give_the_straight_verdicts() {
    // With w = 0 every catenary is its chord and the equilibrium is the straight cables' one
    // (an elastic cable only stretches): tension and capacity verdicts equal point by point.
    for criteria in ["tension", "tension,capacity:0"] {
        let straight = cogiro_verdicts(cogiro(None, None), criteria, None);
        let feasible = straight.iter().filter(|&&f| f).count();
        assert!(
            feasible > 10 && feasible < straight.len(),
            "{criteria}: {feasible}"
        );
        let weightless = cogiro_verdicts(cogiro(Some(0.0), None), criteria, Some("catenary"));
        assert_eq!(weightless, straight, "{criteria}: catenary with w = 0");
        let elastic = cogiro_verdicts(cogiro(None, None), criteria, Some("elastic"));
        assert_eq!(elastic, straight, "{criteria}: elastic");
    }
}

#[test]
fn sagging_cables_shrink_cogiros_tension_feasible_set() {
    use cdpr_api::nalgebra::Vector3;
    use cdpr_kinematics::{Pose, PoseKinematics};
    use cdpr_tension::{SaggingOutcome, SaggingSettings, SaggingStatics, TensionSolver};
    // A grid point of M = 6 near the y = −5.2 side: ℓ2 balances the 245 N platform with cables
    // 2 and 8 at t_max = 720 N and cable 5 at 15.6 N (hanging ~0.2 m below its ~11 m chord).
    let pose = Pose::new(
        Vector3::new(0.0035, -3.4961666666666664, 4.279083333333333),
        Rotation3::identity(),
    );
    let verdict = |robot: &Robot, model: Option<&str>| {
        let c = cdpr_api::WorkspaceCriteria {
            criteria: Some("tension".into()),
            cable_model: model.map(Into::into),
            ..Default::default()
        };
        let setup = cdpr_api::CriteriaSetup::new(&c, robot, cdpr_api::Method::L2).unwrap();
        let mut eval = setup
            .evaluator(robot, robot.robot.clone(), &Rotation3::identity())
            .unwrap();
        eval.check(&pose).unwrap()
    };
    let robot = cogiro(None, None);
    assert!(verdict(&robot, None), "straight cables hold the platform");
    assert!(!verdict(&robot, Some("catenary")), "sagging cables do not");
    // Not a solver failure: 740 N of headroom is enough for the catenaries, and there some
    // cable's tension along its length exceeds 720 N.
    let roomy = cogiro(None, Some(740.0));
    assert!(verdict(&roomy, Some("catenary")));
    let model = cdpr_api::criteria::catenaries(&roomy, Some("catenary"))
        .unwrap()
        .unwrap();
    let mut kin = PoseKinematics::for_robot(&roomy.robot);
    roomy.robot.update_kinematics(&pose, &mut kin).unwrap();
    let w_ext = cdpr_api::nalgebra::DVector::from_vec(vec![0.0, 0.0, -245.25, -245.25, 0.0, 0.0]);
    let SaggingOutcome::Feasible(s) = SaggingStatics::new(SaggingSettings::default())
        .solve(
            &mut TensionSolver::new(cdpr_api::Method::L2),
            &kin,
            &model,
            &w_ext,
            &roomy.bounds,
        )
        .unwrap()
    else {
        panic!("feasible with 740 N");
    };
    let largest =
        |c: &cdpr_kinematics::SaggingCable| c.frame_end_tension.max(c.platform_end_tension);
    assert!(s.cables.iter().map(largest).fold(0.0, f64::max) > 720.0);
    // By hand, the along-cable bound: dT/ds₀ = w sin θ and dz/ds₀ = (1 + T/EA) sin θ give
    // (T_A − T_B) + (T_A² − T_B²)/(2EA) = w (z_A − z_B), w = 0.023 kg/m × 9.81 m/s²: every
    // cable rising to its frame point is tenser there than at the platform.
    let (w, ea) = (0.023 * 9.81, 12440706.908215582);
    for (i, c) in s.cables.iter().enumerate() {
        let (ta, tb) = (c.frame_end_tension, c.platform_end_tension);
        let dz = roomy.robot.cables()[i].frame.z
            - (pose.position.z + roomy.robot.cables()[i].platform.z);
        let lhs = (ta - tb) + (ta * ta - tb * tb) / (2.0 * ea);
        assert!(
            (lhs - w * dz).abs() < 1e-9 * ta,
            "cable {}: {lhs} vs {}",
            i + 1,
            w * dz
        );
        assert!(dz > 0.0 && ta > tb);
    }
}

#[test]
fn sagging_criteria_never_panic_or_err_over_random_cogiro_poses() {
    use cdpr_api::nalgebra::Vector3;
    use cdpr_kinematics::{Pose, PoseKinematics};
    use cdpr_tension::{SaggingOutcome, SaggingSettings, SaggingStatics, TensionSolver};
    // 300 poses (SplitMix64, seed 29) over the frame's box, tilted by up to 0.3 rad: every
    // verdict is a verdict (no error, no panic), feasible tensions are finite, and an
    // infeasible sagging solve says why.
    let robot = cogiro(None, None);
    let c = cdpr_api::WorkspaceCriteria {
        criteria: Some("tension,capacity:0".into()),
        wrench_box: Some(vec![5.0, 5.0, 5.0, 1.0, 1.0, 1.0]),
        cable_model: Some("catenary".into()),
        ..Default::default()
    };
    let setup = cdpr_api::CriteriaSetup::new(&c, &robot, cdpr_api::Method::L2).unwrap();
    let model = setup.catenaries.clone().unwrap();
    let mut state = 29u64;
    let mut uniform = move || {
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut kin = PoseKinematics::for_robot(&robot.robot);
    let mut statics = SaggingStatics::new(SaggingSettings::default());
    let mut solver = TensionSolver::new(cdpr_api::Method::L2);
    let mut feasible = 0;
    for _ in 0..300 {
        let mut u = |a: f64, b: f64| a + (b - a) * uniform();
        let position = Vector3::new(u(-7.0, 7.0), u(-5.0, 5.0), u(0.0, 5.0));
        let rotation = Rotation3::from_euler_angles(u(-0.3, 0.3), u(-0.3, 0.3), u(-0.3, 0.3));
        let pose = Pose::new(position, rotation);
        let mut eval = setup
            .evaluator(&robot, robot.robot.clone(), &rotation)
            .unwrap();
        eval.check(&pose).unwrap();
        if robot.robot.update_kinematics(&pose, &mut kin).is_err() {
            continue;
        }
        let w_ext = setup.external_wrench(&robot, &rotation).unwrap();
        match statics
            .solve(&mut solver, &kin, &model, &w_ext, &robot.bounds)
            .unwrap()
        {
            SaggingOutcome::Feasible(s) => {
                feasible += 1;
                assert!(s.tensions.iter().all(|t| t.is_finite()));
                assert!(s.cables.iter().all(|c| c.unstrained_length.is_finite()));
            }
            SaggingOutcome::Infeasible(r) => assert!(!r.to_string().is_empty()),
        }
    }
    assert!(feasible > 0, "some random poses are feasible");
}
