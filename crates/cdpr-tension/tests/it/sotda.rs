//! SOTDA (Picard, Caro, Plestan & Claveau 2020, Algorithm 1) on an 8-cable spatial robot (redundancy 2).

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
                    pulley: None,
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
        // E = 80 GPa, S = 0.75 mm² (Picard, Caro, Plestan & Claveau 2020, §4).
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
    let seven = robot.permuted(&[0, 1, 2, 3, 4, 5, 6]).unwrap();
    let s7 = setup(
        &seven,
        &Pose::spatial(Vector3::zeros(), 0.0, 0.0, 0.0),
        gravity(1.0),
    );
    let err = TensionSolver::new(Method::Sotda)
        .solve(&problem(&s7))
        .unwrap_err();
    assert!(
        err.to_string()
            .starts_with("method sotda needs redundancy 2; this robot has n − DOF = 1")
    );
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

// ---------------------------------------------------------------------------------------------
// Corners (Picard, Caro, Plestan & Claveau 2020, §3 assumptions (i)–(ii)) vs Vertices vs Full.

fn sotda(
    variant: SotdaVariant,
    direction: Vector3<f64>,
    dw: Option<DVector<f64>>,
) -> TensionSolver {
    TensionSolver::sotda(SotdaSettings {
        direction,
        nu: 1.0,
        variant,
        perturbation: dw,
    })
}

/// Whether some cable of `t` is within `rel` (of its tension range) of its finite t_max.
fn at_t_max(t: &DVector<f64>, b: &TensionBounds, rel: f64) -> bool {
    (0..t.len()).any(|i| {
        let (lo, hi) = (b.min()[i], b.max()[i]);
        hi.is_finite() && t[i] >= hi - rel * (hi - lo)
    })
}

/// Point on four cables from (±1, ±1) (no external wrench): W t = 0 gives t = (a, b, b, a), so
/// the feasible polygon is the square [1, 10]² in (a, b) with the t_min–t_min corner (1, 1).
/// With k_i = E S_i / l = (20, 10, 10, 10), l = √2 and u_i = (±1, ±1)/√2 (Picard, Caro, Plestan & Claveau 2020, eq. (4)):
///
/// ```text
///   Kp = Σ k_i u_i u_iᵀ = [[25, 5], [5, 25]],  Ka = Σ t_i/l (I − u_i u_iᵀ) = [[S, −D], [−D, S]]
///   S = (a + b)/√2,  D = (a − b)/√2,  K = [[P, Q], [Q, P]],  P = 25 + S,  Q = 5 − D.
/// ```
///
/// δw_e = K(1, 1) e_y = (Q₀, P₀) = (5, 25 + √2) and d = x give
/// d·K⁻¹δw_e = (P Q₀ − Q P₀)/(P² − Q²): 0 at (1, 1), the best of all vertices, and at the
/// corners with a cable at t_max: 0.0422 at (10, 10), 0.1864 at (10, 1), 0.1442 at (1, 10).
/// So Vertices picks t = 1 and Corners (the paper's candidates) t = 10.
#[test]
fn corners_skip_the_t_min_t_min_vertex() {
    let robot = Robot::new(
        MotionPattern::Point2,
        [[1.0, 1.0], [1.0, -1.0], [-1.0, 1.0], [-1.0, -1.0]]
            .iter()
            .map(|f| Cable {
                frame: Vector3::new(f[0], f[1], 0.0),
                platform: Vector3::zeros(),
                pulley: None,
            })
            .collect(),
    )
    .unwrap();
    let kin = robot
        .inverse_kinematics(&Pose::point(0.0, 0.0, 0.0))
        .unwrap();
    let w = kin.wrench_matrix();
    let we = DVector::zeros(2);
    let b = TensionBounds::uniform(4, 1.0, 10.0).unwrap();
    let l = 2f64.sqrt();
    let es: Vec<f64> = [20.0, 10.0, 10.0, 10.0].iter().map(|k| k * l).collect();
    let p = TensionProblem {
        stiffness: Some(StiffnessData {
            kinematics: &kin,
            axial_stiffness: &es,
        }),
        ..TensionProblem::new(&w, &we, &b)
    };
    let (p0, q0) = (25.0 + 2.0 / l, 5.0);
    let dw = DVector::from_vec(vec![q0, p0]);
    let hand = |a: f64, bb: f64| {
        let (pp, qq) = (25.0 + (a + bb) / l, 5.0 - (a - bb) / l);
        ((pp * q0 - qq * p0) / (pp * pp - qq * qq)).abs()
    };
    let settings = SotdaSettings {
        direction: Vector3::x(),
        perturbation: Some(dw.clone()),
        ..SotdaSettings::default()
    };
    let disp = |t: &DVector<f64>| {
        sotda_displacement(p.stiffness.as_ref().unwrap(), &settings, &we, t.as_slice())
            .unwrap()
            .unwrap()
    };
    // The objective matches the hand-derived values at the four vertices.
    for (a, bb) in [(1.0, 1.0), (1.0, 10.0), (10.0, 1.0), (10.0, 10.0)] {
        let t = DVector::from_vec(vec![a, bb, bb, a]);
        assert!((disp(&t) - hand(a, bb)).abs() < 1e-12, "({a}, {bb})");
    }
    assert!(hand(1.0, 1.0) < 1e-15);
    assert!((hand(10.0, 10.0) - 0.04223).abs() < 1e-4);
    assert!(hand(10.0, 10.0) < hand(1.0, 10.0) && hand(1.0, 10.0) < hand(10.0, 1.0));

    let poly = FeasiblePolygon::compute(&p).unwrap().unwrap();
    assert_eq!(poly.tension_vertices.len(), 4);
    let solve = |v| {
        let out = sotda(v, Vector3::x(), Some(dw.clone())).solve(&p).unwrap();
        out.tensions().unwrap().clone()
    };
    let (tc, tv, tf) = (
        solve(SotdaVariant::Corners),
        solve(SotdaVariant::Vertices),
        solve(SotdaVariant::Full),
    );
    assert!(
        (&tv - DVector::from_element(4, 1.0)).amax() < 1e-9,
        "vertices: {tv}"
    );
    assert!(
        (&tc - DVector::from_element(4, 10.0)).amax() < 1e-9,
        "corners: {tc}"
    );
    assert!(at_t_max(&tc, &b, 1e-9) && !at_t_max(&tv, &b, 1e-3));
    assert!(disp(&tv) < 1e-12 && disp(&tf) <= disp(&tv) + 1e-12);
    assert!((disp(&tc) - hand(10.0, 10.0)).abs() < 1e-12);
    // Default settings are the paper's variant.
    assert_eq!(SotdaSettings::default().variant, SotdaVariant::Corners);
}

/// Bounds: t_max = (max t*) · factor, or infinite (then the polygon may be unbounded, or
/// bounded by t_min alone, where Corners falls back to every vertex).
fn arb_t_max_factor() -> impl Strategy<Value = f64> {
    prop_oneof![4 => 1.0f64..2.5, 1 => Just(f64::INFINITY)]
}

fn arb_motion_and_robot() -> impl Strategy<Value = Robot> {
    prop_oneof![
        arb_robot(MotionPattern::Point2, 4..=4),
        arb_robot(MotionPattern::Planar, 5..=5),
        arb_robot(MotionPattern::Point3, 5..=5),
        arb_robot(MotionPattern::Spatial, 8..=8),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, failure_persistence: None, ..ProptestConfig::default() })]

    /// Random feasible redundancy-2 problems (w_ext = −W t* with t* in the box): the variants'
    /// candidate sets are nested (Corners ⊆ Vertices ⊆ Full), Corners picks the best vertex with
    /// a cable at t_max whenever there is one (independent oracle: `FeasiblePolygon` vertices),
    /// and every answer is feasible and in equilibrium.
    #[test]
    fn sotda_variants_are_nested(
        robot in arb_motion_and_robot(),
        frac in prop::collection::vec(0.0f64..1.0, 8),
        factor in arb_t_max_factor(),
        d in prop::collection::vec(-1.0f64..1.0, 3),
    ) {
        let direction = Vector3::new(d[0], d[1], d[2]);
        let td = robot.motion().translation_dof();
        prop_assume!(direction.as_slice()[..td].iter().map(|v| v * v).sum::<f64>() > 0.01);
        let n = robot.cable_count();
        let kin = robot.inverse_kinematics(&Pose::from_coordinates(robot.motion(), &vec![0.0; robot.motion().dof()]).unwrap()).unwrap();
        let w = kin.wrench_matrix();
        let t_star = DVector::from_fn(n, |i, _| 1.0 + 999.0 * frac[i]);
        let we = -(&w * &t_star);
        let b = TensionBounds::uniform(n, 1.0, t_star.max() * factor).unwrap();
        let es = vec![80e9 * 0.75e-6; n];
        let p = TensionProblem {
            stiffness: Some(StiffnessData { kinematics: &kin, axial_stiffness: &es }),
            ..TensionProblem::new(&w, &we, &b)
        };
        let settings = SotdaSettings { direction, ..SotdaSettings::default() };
        let disp = |t: &DVector<f64>| {
            sotda_displacement(p.stiffness.as_ref().unwrap(), &settings, &we, t.as_slice())
                .unwrap()
                .unwrap_or(f64::INFINITY)
        };
        let run = |v| sotda(v, direction, None).solve(&p).unwrap();
        let (c, v, f) = (run(SotdaVariant::Corners), run(SotdaVariant::Vertices), run(SotdaVariant::Full));
        let poly = FeasiblePolygon::compute(&p).unwrap();
        prop_assert_eq!(c.is_feasible(), poly.is_ok());
        prop_assert_eq!(v.is_feasible(), poly.is_ok());
        prop_assert_eq!(f.is_feasible(), poly.is_ok());
        let Ok(poly) = poly else { return Ok(()) };
        if factor.is_finite() {
            prop_assert!(c.is_feasible(), "a finite box around t* is always feasible and bounded");
        }
        let scale = t_star.amax().max(we.amax());
        for out in [&c, &v, &f] {
            let t = out.tensions().unwrap();
            prop_assert!((&w * t + &we).amax() <= 1e-9 * scale, "equilibrium");
            for i in 0..n {
                let (lo, hi) = (b.min()[i], b.max()[i]);
                prop_assert!(t[i] >= lo - 1e-9 * scale && t[i] <= hi + 1e-9 * hi.min(1e300), "bounds");
            }
        }
        let (tc, tv, tf) = (c.tensions().unwrap(), v.tensions().unwrap(), f.tensions().unwrap());
        let (dc, dv, df) = (disp(tc), disp(tv), disp(tf));
        prop_assert!(dv <= dc * (1.0 + 1e-9) + 1e-18, "vertices {dv} > corners {dc}");
        prop_assert!(df <= dv * (1.0 + 1e-9) + 1e-18, "full {df} > vertices {dv}");
        // Oracle: the best vertex overall and the best vertex with a cable at t_max.
        let mut best_all = f64::INFINITY;
        let mut best_max = f64::INFINITY;
        for tv in &poly.tension_vertices {
            let d = disp(tv);
            best_all = best_all.min(d);
            if at_t_max(tv, &b, 1e-10) {
                best_max = best_max.min(d);
            }
        }
        prop_assert!((dv - best_all).abs() <= 1e-9 * best_all, "vertices {dv} vs oracle {best_all}");
        if poly.tension_vertices.iter().any(|tv| at_t_max(tv, &b, 1e-10)) && best_max.is_finite() {
            prop_assert!(at_t_max(tc, &b, 1e-8), "corners has no cable at t_max: {tc}");
            prop_assert!((dc - best_max).abs() <= 1e-9 * best_max, "corners {dc} vs oracle {best_max}");
        } else {
            // Fallback: every vertex.
            prop_assert!((dc - best_all).abs() <= 1e-9 * best_all, "fallback {dc} vs {best_all}");
        }
    }
}
