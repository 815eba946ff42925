//! Elastic cables over swivel pulleys (issue 29): a frictionless pulley carries one tension
//! along the whole cable, so L0 = l/(1 + t/EA) with l = ρ β + l_f the pulley model's length,
//! the force on the platform is along the free segment, and the elasto-geometric forward
//! kinematics inverts it through l(x) and the pulley stiffness.

use cdpr_kinematics::nalgebra::{DMatrix, DVector, Vector3};
use cdpr_kinematics::reference_robots::ipanema_like_8_pulleys;
use cdpr_kinematics::{
    Cable, ElastoGeometricForward, ElastoGeometricStatus, KinematicsError, MotionPattern, Pose,
    Pulley, Robot, RobotCatenaries,
};
use std::f64::consts::FRAC_PI_3;

/// One cable over a pulley of radius 1 m swivelling about +z at the origin, to a point
/// platform.
fn one_pulley() -> Robot {
    let cable = Cable {
        pulley: Some(Pulley::from_axis(1.0, Vector3::z())),
        ..Cable::point3(Vector3::zeros())
    };
    Robot::new(MotionPattern::Point3, vec![cable]).unwrap()
}

/// By hand: B = (3, 0, 0) from the pulley centre M = (1, 0, 0) of radius 1: BM = 2, the free
/// segment l_f = √(BM² − ρ²) = √3 leaves the pulley at C = (3/2, 0, √3/2) after the wrap
/// β = 2π/3 over the top; at 100 N with EA = 10⁴ N the cable's unstrained length is
/// (2π/3 + √3)/1.01 (m), of which √3/1.01 is the free segment's.
#[test]
fn one_pulley_hand_value() {
    let robot = one_pulley();
    let kin = robot
        .inverse_kinematics(&Pose::point(3.0, 0.0, 0.0))
        .unwrap();
    let model = RobotCatenaries::elastic(&[1e4]).unwrap();
    let mut cables = Vec::new();
    model.with_tensions(&kin, &[100.0], &mut cables).unwrap();
    let c = &cables[0];
    let (arc, free) = (2.0 * FRAC_PI_3, 3f64.sqrt());
    assert!((c.wrapped_length - arc).abs() < 1e-15, "{c:?}");
    assert!((c.chord_length - free).abs() < 1e-15, "{c:?}");
    assert!(
        (c.unstrained_length - (arc + free) / 1.01).abs() < 1e-14,
        "{c:?}"
    );
    assert!((c.solution.unstrained_length - free / 1.01).abs() < 1e-14);
    assert_eq!((c.platform_end_tension, c.max_sag), (100.0, 0.0));
    assert!((c.frame_end_tension - 100.0).abs() < 1e-12);
    // The cable pulls B towards C: u = (C − B)/l_f = (−√3/2, 0, 1/2).
    let u = Vector3::new(-(3f64.sqrt()) / 2.0, 0.0, 0.5);
    assert!((c.unit - u).amax() < 1e-15, "{}", c.unit);
    // Back from the whole cable's unstrained length: the same tension and state.
    let mut back = Vec::new();
    model
        .with_lengths(&kin, &[c.unstrained_length], &mut back)
        .unwrap();
    assert!(
        (back[0].platform_end_tension - 100.0).abs() < 1e-9,
        "{back:?}"
    );
    assert_eq!(back[0].unstrained_length, c.unstrained_length);
    assert!((back[0].wrapped_length - arc).abs() < 1e-15);
}

fn truth() -> Pose {
    Pose::spatial(Vector3::new(0.2, 0.1, 1.1), 0.02, -0.01, 0.05)
}

const TENSIONS: [f64; 8] = [120.0, 90.0, 150.0, 100.0, 110.0, 130.0, 95.0, 140.0];

/// The unstrained lengths that hold the pulley robot at `pose` with tensions `t` and the
/// external wrench they balance, W t + w_ext = 0 (W from the elastic cables' forces).
fn inverse(robot: &Robot, model: &RobotCatenaries, pose: &Pose, t: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let kin = robot.inverse_kinematics(pose).unwrap();
    let mut cables = Vec::new();
    model.with_tensions(&kin, t, &mut cables).unwrap();
    let mut w = DMatrix::zeros(0, 0);
    cdpr_kinematics::catenary::write_sagging_wrench_matrix(&kin, &cables, &mut w);
    let w_ext = -(w * DVector::from_column_slice(t));
    (
        cables.iter().map(|c| c.unstrained_length).collect(),
        w_ext.as_slice().to_vec(),
    )
}

/// With EA → ∞ (here infinite) the elastic pulley cables are the straight pulley cables: the
/// unstrained lengths are the pulley model's lengths and W is its wrench matrix.
#[test]
fn rigid_limit_is_the_straight_pulley_model() {
    let robot = ipanema_like_8_pulleys();
    let kin = robot.inverse_kinematics(&truth()).unwrap();
    let mut w = DMatrix::zeros(0, 0);
    kin.write_wrench_matrix(&mut w);
    for ea in [f64::INFINITY, 1e18] {
        let model = RobotCatenaries::elastic(&[ea; 8]).unwrap();
        let mut cables = Vec::new();
        model.with_tensions(&kin, &TENSIONS, &mut cables).unwrap();
        for (i, c) in cables.iter().enumerate() {
            let l = kin.cables()[i].length;
            assert!(
                (c.unstrained_length - l).abs() < 1e-14 * l,
                "cable {i}: {c:?}"
            );
            assert!((c.wrapped_length + kin.free_length(i) - l).abs() < 1e-14 * l);
            assert!(c.wrapped_length > 0.01, "a wrapped arc: {c:?}");
        }
        let mut ws = DMatrix::zeros(0, 0);
        cdpr_kinematics::catenary::write_sagging_wrench_matrix(&kin, &cables, &mut ws);
        assert!((&ws - &w).amax() < 1e-14, "{}", &ws - &w);
    }
}

/// L0 = l/(1 + t/EA) with the whole length l, not only the free segment's.
#[test]
fn unstrained_length_stretches_the_whole_cable() {
    let robot = ipanema_like_8_pulleys();
    let kin = robot.inverse_kinematics(&truth()).unwrap();
    let ea = 6e4;
    let model = RobotCatenaries::elastic(&[ea; 8]).unwrap();
    let mut cables = Vec::new();
    model.with_tensions(&kin, &TENSIONS, &mut cables).unwrap();
    for (i, (c, t)) in cables.iter().zip(TENSIONS).enumerate() {
        let l = kin.cables()[i].length;
        assert!(
            (c.unstrained_length - l / (1.0 + t / ea)).abs() < 1e-14 * l,
            "cable {i}"
        );
    }
}

/// Round trip pose → tensions → L0 → elasto-geometric forward kinematics, from a nearby
/// guess and from the straight cables' poses (multi-start), back to the pose within 1e-9.
#[test]
fn round_trip_through_the_elasto_geometric_forward_kinematics() {
    let robot = ipanema_like_8_pulleys();
    let model = RobotCatenaries::elastic(&[6e4; 8]).unwrap();
    let truth = truth();
    let (l0, w_ext) = inverse(&robot, &model, &truth, &TENSIONS);
    let mut fk = ElastoGeometricForward::new(&robot, &model, Default::default()).unwrap();
    let guess = Pose::spatial(Vector3::new(0.22, 0.08, 1.12), 0.0, 0.0, 0.06);
    let sol = fk.solve(&l0, &w_ext, &guess).unwrap();
    assert_eq!(sol.status, ElastoGeometricStatus::Equilibrium, "{sol:?}");
    assert!(
        (sol.pose.position - truth.position).norm() < 1e-9,
        "{sol:?}"
    );
    assert!((sol.pose.rotation.matrix() - truth.rotation.matrix()).norm() < 1e-9);
    for (i, (c, t)) in fk.cables().iter().zip(TENSIONS).enumerate() {
        assert!(
            (c.platform_end_tension - t).abs() < 1e-6 * t,
            "cable {i}: {c:?}"
        );
        assert!((c.unstrained_length - l0[i]).abs() == 0.0);
        assert!(c.wrapped_length > 0.0);
    }
    let mut load = |_: &Pose, out: &mut [f64]| {
        out.copy_from_slice(&w_ext);
        Ok(())
    };
    let multi = fk.solve_multistart_with_load(&l0, &mut load).unwrap();
    assert_eq!(multi.status, ElastoGeometricStatus::Equilibrium);
    assert!(
        (multi.pose.position - truth.position).norm() < 1e-9,
        "{multi:?}"
    );
}

/// Without the pulleys' arcs (the free segments alone) the same lengths put the platform
/// elsewhere: the round trip above depends on the whole length.
#[test]
fn the_wrapped_arc_moves_the_pose() {
    let robot = ipanema_like_8_pulleys();
    let model = RobotCatenaries::elastic(&[6e4; 8]).unwrap();
    let (l0, w_ext) = inverse(&robot, &model, &truth(), &TENSIONS);
    let standard = Robot::new(
        MotionPattern::Spatial,
        robot
            .cables()
            .iter()
            .map(|c| Cable { pulley: None, ..*c })
            .collect(),
    )
    .unwrap();
    let mut fk = ElastoGeometricForward::new(&standard, &model, Default::default()).unwrap();
    let sol = fk.solve(&l0, &w_ext, &truth()).unwrap();
    assert!(
        (sol.pose.position - truth().position).norm() > 1e-3,
        "{sol:?}"
    );
}

/// A heavy cable over a pulley is not modelled: an error naming the cable.
#[test]
fn heavy_cables_over_pulleys_are_refused() {
    let robot = ipanema_like_8_pulleys();
    let model =
        RobotCatenaries::new(&[0.02; 8], &[6e4; 8], &Vector3::new(0.0, 0.0, -9.81)).unwrap();
    let kin = robot.inverse_kinematics(&truth()).unwrap();
    let e = model
        .with_tensions(&kin, &TENSIONS, &mut Vec::new())
        .unwrap_err();
    assert!(
        matches!(e, KinematicsError::UnsupportedPulley { cable: 0, .. }),
        "{e}"
    );
    assert!(e.to_string().starts_with("cable 1: "), "{e}");
    assert!(matches!(
        ElastoGeometricForward::new(&robot, &model, Default::default()),
        Err(KinematicsError::UnsupportedPulley { cable: 0, .. })
    ));
}
