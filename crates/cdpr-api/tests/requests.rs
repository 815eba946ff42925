//! Requests against hand-derived values, their validation errors and their JSON round trip.

use cdpr_api::{
    ApiError, CapacityRequest, ForwardRequest, KinematicsRequest, Method, PeerOptions, Robot,
    RobotSource, StiffnessRequest, TensionRequest,
};

/// A point2 robot: four cables from (±1, ±1) to the point platform, tensions in [1, 10] N, no
/// mass.
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

fn message(e: ApiError) -> String {
    e.to_string()
}

#[test]
fn kinematics_of_the_square_at_its_centre() {
    let r = KinematicsRequest {
        robot: square(),
        pose: vec![0.0, 0.0],
    }
    .run()
    .unwrap();
    let s = 0.5f64.sqrt();
    for l in &r.lengths {
        assert!((l - 2f64.sqrt()).abs() < 1e-12);
    }
    // Cable 1 points from the platform towards (1, 1).
    assert!((r.unit_vectors[0][0] - s).abs() < 1e-12 && (r.unit_vectors[0][1] - s).abs() < 1e-12);
    assert_eq!(r.wrench_matrix.len(), 2);
    assert_eq!(r.motion, "point2");
}

/// With no load the unit vectors sum to zero: t = (1, 1, 1, 1) N balances, and no feasible t is
/// smaller (every t_i ≥ 1 N), so it is the ℓ2 optimum.
#[test]
fn l2_tensions_of_the_unloaded_square_sit_on_t_min() {
    let r = TensionRequest::new(square(), vec![0.0, 0.0], Method::L2)
        .run()
        .unwrap();
    assert!(r.feasible);
    for t in r.tensions.unwrap() {
        assert!((t - 1.0).abs() < 1e-7, "t = {t}");
    }
    assert!(r.polygon.is_none() && r.sotda.is_none());
}

#[test]
fn a_request_survives_a_json_round_trip() {
    let mut request = TensionRequest::new(square(), vec![0.1, -0.2], Method::Barycenter);
    request.wrench = Some(vec![0.5, -2.0]);
    let json = serde_json::to_string(&request).unwrap();
    let back: TensionRequest = serde_json::from_str(&json).unwrap();
    assert_eq!(back.robot.description(), request.robot.description());
    assert_eq!(back.wrench, request.wrench);
    assert_eq!(back.method, Method::Barycenter);
    let (a, b) = (request.run().unwrap(), back.run().unwrap());
    assert_eq!(a, b);
    assert!(a.polygon.is_some());
}

#[test]
fn a_browser_request_takes_defaults() {
    let json = serde_json::json!({
        "robot": { "format": "toml", "text": SQUARE },
        "pose": [0.0, 0.0],
    });
    let r: TensionRequest = serde_json::from_value(json).unwrap();
    assert_eq!(r.method, Method::L2);
    assert_eq!(r.nu, 1.0);
}

#[test]
fn a_malformed_robot_fails_with_its_line() {
    let json = serde_json::json!({
        "robot": { "format": "toml", "text": SQUARE.replace("[1.0, -1.0]", "[1.0, nan]"), "file": "x.toml" },
        "pose": [0.0, 0.0],
    });
    let e = serde_json::from_value::<KinematicsRequest>(json).unwrap_err();
    // The fourth cable's frame is on line 16 of SQUARE.
    assert!(
        e.to_string().contains("x.toml:16: `cables[4].frame`"),
        "{e}"
    );
    let e = serde_json::from_value::<TensionRequest>(serde_json::json!({
        "robot": { "format": "toml", "text": SQUARE },
        "pose": [0.0, 0.0],
        "method": "l7",
    }))
    .unwrap_err();
    assert!(e.to_string().contains("l7"), "{e}");
}

#[test]
fn validate_names_what_is_wrong() {
    let wrong_pose = KinematicsRequest {
        robot: square(),
        pose: vec![0.0, 0.0, 0.0],
    };
    assert!(wrong_pose.validate().is_err());

    let mut t = TensionRequest::new(square(), vec![0.0, 0.0], Method::L2);
    t.options = PeerOptions {
        p: Some(3.0),
        ..PeerOptions::default()
    };
    let m = message(t.validate().unwrap_err());
    assert!(
        m.contains("--p is an option of another method, not of l2"),
        "{m}"
    );
    t.method = Method::Sotda;
    t.options = PeerOptions::default();
    let m = message(t.validate().unwrap_err());
    assert!(m.contains("sotda needs `axial_stiffness`"), "{m}");
    t.method = Method::L2;
    t.nu = 1.5;
    assert!(message(t.validate().unwrap_err()).contains("[0, 1]"));

    let mut c = CapacityRequest {
        robot: square(),
        pose: vec![0.0, 0.0],
        wrench: None,
        wrench_box: Some(vec![1.0, 1.0, 1.0]),
        wrench_ball: None,
        force_radius: None,
        moment_radius: None,
    };
    let m = message(c.validate().unwrap_err());
    assert!(m.contains("--wrench-box needs 2 half-widths"), "{m}");
    c.wrench_box = None;
    c.moment_radius = Some(1.0);
    let m = message(c.validate().unwrap_err());
    assert!(m.contains("a `point2` robot takes no moments"), "{m}");
    c.moment_radius = None;
    c.wrench_ball = Some(-1.0);
    let m = message(c.validate().unwrap_err());
    assert!(
        m.contains("--wrench-ball: the radius must be a finite number ≥ 0"),
        "{m}"
    );

    let mut s = StiffnessRequest {
        robot: square(),
        pose: vec![0.0, 0.0],
        tensions: Some(vec![1.0, -1.0, 1.0, 1.0]),
        method: None,
        wrench: None,
        axial_stiffness: None,
    };
    let m = message(s.validate().unwrap_err());
    assert!(m.contains("no axial stiffness"), "{m}");
    s.axial_stiffness = Some(1000.0);
    let m = message(s.validate().unwrap_err());
    assert!(m.contains("t_2 = -1 N"), "{m}");
}

/// A point-mass square: K = Ka + Kp with Kp = Σ k_i u_i u_iᵀ, k_i = E·S / l_i; at the centre
/// Σ u_i u_iᵀ = 2 I (each diagonal pair contributes I), so Kp = 2 (E·S/√2) I = √2 E·S I.
#[test]
fn passive_stiffness_of_the_square_by_hand() {
    let r = StiffnessRequest {
        robot: square(),
        pose: vec![0.0, 0.0],
        tensions: Some(vec![0.0; 4]),
        method: None,
        wrench: None,
        axial_stiffness: Some(1000.0),
    }
    .run()
    .unwrap();
    let kp = 2f64.sqrt() * 1000.0;
    assert!((r.passive[0][0] - kp).abs() < 1e-6 * kp, "{:?}", r.passive);
    assert!(r.passive[0][1].abs() < 1e-9 * kp);
    assert!(r.tension_method.is_none());
}

/// The square's lengths at (0.3, 0.2): |a_i − p| for the anchors (±1, ±1).
fn square_lengths() -> Vec<f64> {
    [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)]
        .iter()
        .map(|(x, y): &(f64, f64)| (x - 0.3).hypot(y - 0.2))
        .collect()
}

#[test]
fn forward_request_takes_an_iteration_limit() {
    let json = serde_json::json!({
        "robot": { "format": "toml", "text": SQUARE },
        "lengths": square_lengths(),
        "guess": [0.0, 0.0],
    });
    let mut r: ForwardRequest = serde_json::from_value(json).unwrap();
    assert_eq!(r.max_iterations, 100);
    let solved = r.run().unwrap().best;
    assert!(solved.converged && solved.iterations > 1, "{solved:?}");
    assert!((solved.pose[0] - 0.3).abs() < 1e-9 && (solved.pose[1] - 0.2).abs() < 1e-9);
    // One step from (0, 0) cannot meet 1e-9 on these nonlinear lengths.
    r.max_iterations = 1;
    let cut = r.run().unwrap().best;
    assert!(!cut.converged && cut.iterations <= 1, "{cut:?}");
    assert_eq!(cut.status, "did not converge");
    r.max_iterations = 0;
    assert!(message(r.validate().unwrap_err()).contains("iteration"));
}
