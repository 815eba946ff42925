//! SOTDA (seed 002, Algorithm 1) on an 8-cable spatial robot (redundancy 2).

use cdpr_kinematics::strategies::arb_robot;
use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
use cdpr_tension::{
    FeasiblePolygon, Method, SotdaSettings, SotdaVariant, StiffnessData, TensionBounds,
    TensionProblem, TensionSolver, sotda_displacement,
};
use nalgebra::{DVector, Vector2, Vector3};
use proptest::prelude::*;

/// IPAnema-1-like: frame anchors at the corners of a ±2 × ±1.5 × ±1 box, platform attachments
/// at the corners of a ±0.1 box, cable i joins corresponding corners.
fn eight_cable() -> Robot {
    let mut cables = Vec::new();
    for sx in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            for sz in [-1.0, 1.0] {
                cables.push(Cable {
                    frame: Vector3::new(2.0 * sx, 1.5 * sy, sz),
                    platform: Vector3::new(0.1 * sx, 0.1 * sy, 0.1 * sz),
                });
            }
        }
    }
    Robot::new(MotionPattern::Spatial, cables).unwrap()
}

struct Setup {
    kin: cdpr_kinematics::PoseKinematics,
    w: nalgebra::DMatrix<f64>,
    we: DVector<f64>,
    b: TensionBounds,
    es: Vec<f64>,
}

fn setup(robot: &Robot, pose: &Pose, we: DVector<f64>) -> Setup {
    let kin = robot.inverse_kinematics(pose).unwrap();
    let n = robot.cable_count();
    Setup {
        w: kin.wrench_matrix(),
        kin,
        we,
        b: TensionBounds::uniform(n, 1.0, 1000.0).unwrap(),
        // E = 80 GPa, S = 0.75 mm² (seed 002 §4).
        es: vec![80e9 * 0.75e-6; n],
    }
}

fn problem(s: &Setup) -> TensionProblem<'_> {
    TensionProblem {
        stiffness: Some(StiffnessData {
            kinematics: &s.kin,
            axial_stiffness: &s.es,
        }),
        ..TensionProblem::new(&s.w, &s.we, &s.b)
    }
}

fn gravity(mass: f64) -> DVector<f64> {
    DVector::from_vec(vec![0.0, 0.0, -9.80665 * mass, 0.0, 0.0, 0.0])
}

fn check_sotda(s: &Setup, direction: Vector3<f64>, seed: &[f64]) {
    let p = problem(s);
    let settings = |variant, nu| SotdaSettings {
        direction,
        nu,
        variant,
        perturbation: None,
    };
    let disp = |set: &SotdaSettings, t: &DVector<f64>| {
        sotda_displacement(p.stiffness.as_ref().unwrap(), set, &s.we, t.as_slice())
            .unwrap()
            .unwrap()
    };
    let full_set = settings(SotdaVariant::Full, 1.0);
    let full = TensionSolver::sotda(full_set.clone()).solve(&p).unwrap();
    let corners = TensionSolver::sotda(settings(SotdaVariant::Corners, 1.0))
        .solve(&p)
        .unwrap();
    let Ok(poly) = FeasiblePolygon::compute(&p).unwrap() else {
        assert!(!full.is_feasible() && !corners.is_feasible());
        return;
    };
    let (tf, tc) = (full.tensions().unwrap(), corners.tensions().unwrap());
    let (df, dc) = (disp(&full_set, tf), disp(&full_set, tc));
    // The corner variant can only be worse (its candidates are among the full variant's).
    assert!(dc >= df * (1.0 - 1e-12), "corners {dc} < full {df}");
    // No sampled polygon point beats the full optimum.
    let k = poly.vertices.len();
    let c = poly.barycenter_lambda();
    for (j, w) in seed.chunks(2).enumerate() {
        let (a, b) = (poly.vertices[j % k], poly.vertices[(j + 1) % k]);
        let l: Vector2<f64> = c + (a - c) * w[0] + (b - a) * (w[0] * w[1]);
        assert!(poly.contains(&l, &s.b));
        let d = disp(&full_set, &poly.tensions_at(&l));
        assert!(df <= d * (1.0 + 1e-9) + 1e-15, "sample {d} beats full {df}");
    }
    for v in &poly.tension_vertices {
        assert!(df <= disp(&full_set, v) * (1.0 + 1e-9) + 1e-15);
    }
    // ν = 0: the barycentre; ν = 1: the optimum; ν = ½: halfway.
    let bary = TensionSolver::new(Method::Barycenter).solve(&p).unwrap();
    let tb = bary.tensions().unwrap();
    let nu0 = TensionSolver::sotda(settings(SotdaVariant::Full, 0.0))
        .solve(&p)
        .unwrap();
    assert!((nu0.tensions().unwrap() - tb).amax() < 1e-9 * tb.amax());
    let half = TensionSolver::sotda(settings(SotdaVariant::Full, 0.5))
        .solve(&p)
        .unwrap();
    assert!((half.tensions().unwrap() - (tb + tf) * 0.5).amax() < 1e-9 * tb.amax());
}

#[test]
fn sotda_on_the_eight_cable_robot() {
    let robot = eight_cable();
    let seed: Vec<f64> = (0..400)
        .map(|i| ((i * 7919) % 1000) as f64 / 1000.0)
        .collect();
    for (pose, we) in [
        (
            Pose::spatial(Vector3::zeros(), 0.0, 0.0, 0.0),
            gravity(10.0),
        ),
        (
            Pose::spatial(Vector3::new(0.3, -0.2, 0.1), 0.05, -0.1, 0.1),
            gravity(10.0),
        ),
        (
            Pose::spatial(Vector3::new(-0.5, 0.4, -0.2), 0.0, 0.1, 0.0),
            DVector::from_vec(vec![0.0, 50.0, -98.0, 0.0, 0.0, 0.0]),
        ),
    ] {
        let s = setup(&robot, &pose, we);
        assert!(FeasiblePolygon::compute(&problem(&s)).unwrap().is_ok());
        for d in [Vector3::y(), Vector3::z(), Vector3::new(1.0, 1.0, 0.0)] {
            check_sotda(&s, d, &seed);
        }
    }
}

#[test]
fn sotda_settings_and_redundancy_are_checked() {
    let robot = eight_cable();
    let s = setup(
        &robot,
        &Pose::spatial(Vector3::zeros(), 0.0, 0.0, 0.0),
        gravity(1.0),
    );
    let p = problem(&s);
    let bad = SotdaSettings {
        nu: 1.5,
        ..SotdaSettings::default()
    };
    assert!(TensionSolver::sotda(bad).solve(&p).is_err());
    // 7 cables: redundancy 1, not applicable.
    let seven = robot.permuted(&[0, 1, 2, 3, 4, 5, 6]);
    let s7 = setup(
        &seven,
        &Pose::spatial(Vector3::zeros(), 0.0, 0.0, 0.0),
        gravity(1.0),
    );
    let out = TensionSolver::new(Method::Sotda)
        .solve(&problem(&s7))
        .unwrap();
    assert!(out.infeasibility().unwrap().to_string().contains("needs 2"));
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 16, failure_persistence: None, ..ProptestConfig::default() })]

    /// Random 8-cable spatial robots: same properties wherever the polygon is non-empty.
    #[test]
    fn sotda_properties_on_random_robots(
        robot in arb_robot(MotionPattern::Spatial, 8..=8),
        frac in prop::collection::vec(0.0f64..1.0, 8),
        seed in prop::collection::vec(0.0f64..1.0, 60),
    ) {
        let kin = robot.inverse_kinematics(&Pose::spatial(Vector3::zeros(), 0.0, 0.0, 0.0)).unwrap();
        let w = kin.wrench_matrix();
        let t = DVector::from_fn(8, |i, _| 1.0 + 999.0 * frac[i]);
        let s = setup(&robot, &Pose::spatial(Vector3::zeros(), 0.0, 0.0, 0.0), -(&w * t));
        check_sotda(&s, Vector3::y(), &seed);
    }
}
