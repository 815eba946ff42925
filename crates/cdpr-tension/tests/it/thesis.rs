//! Hand-derived values: the thesis 4-cable robot (Tables 6.1–6.3, t ∈ [5, 100] as Table 6.4) and
//! a point robot whose optima can be written down.

use crate::common;

use cdpr_kinematics::Pose;
use cdpr_tension::{
    FeasiblePolygon, Infeasibility, Method, Objective, TensionBounds, TensionOutcome,
    TensionProblem, TensionSolver, feasible_interval, interior_point,
};
use common::{four_cable, load};
use nalgebra::{DMatrix, DVector};

fn solve(method: Method, p: &TensionProblem) -> TensionOutcome {
    TensionSolver::new(method).solve(p).unwrap()
}

/// At the origin with load L1 the robot is mirror-symmetric (x → −x swaps cables 1↔2 and 3↔4,
/// flips f_x and τ): the unique l2 optimum is symmetric, t1 = t2, t3 = t4. Then the moment and
/// x-force balance automatically and the y balance reads 2 t1 (0.5 − s)/l₁ − 2 t3 · 0.4/l₃ = 10,
/// with s = 0.1/√2, l₁ = |(1 − s, 0.5 − s)|, l₃ = |(0.9, 0.4)|. ‖t‖ grows with t3, so t3 = t_min = 5
/// and t1 = (10 + 0.8·5/l₃) l₁ / (2 (0.5 − s)) ≈ 16.765.
#[test]
fn four_cable_l1_load_at_origin_by_hand() {
    let w = four_cable(0.5)
        .inverse_kinematics(&Pose::planar(0.0, 0.0, 0.0))
        .unwrap()
        .wrench_matrix();
    let we = load(1);
    let b = TensionBounds::uniform(4, 5.0, 100.0).unwrap();
    let p = TensionProblem::new(&w, &we, &b);
    let s = 0.1 / 2f64.sqrt();
    let l1 = ((1.0 - s).powi(2) + (0.5 - s).powi(2)).sqrt();
    let l3 = 0.97f64.sqrt();
    let t1 = (10.0 + 0.8 * 5.0 / l3) * l1 / (2.0 * (0.5 - s));
    let expected = DVector::from_vec(vec![t1, t1, 5.0, 5.0]);
    assert!((t1 - 16.765).abs() < 1e-3);
    for m in [Method::L2, Method::L1, Method::ClosedForm] {
        let t = solve(m, &p).tensions().unwrap().clone();
        if m == Method::L2 {
            assert!((&t - &expected).amax() < 1e-9, "{m}: {t}");
        }
        assert!((t.sum() - expected.sum()).abs() < 1e-9, "{m}: {t}");
    }
    // The feasible interval of Alg. 6.1 contains the symmetric point.
    let iv = feasible_interval(&p).unwrap().unwrap();
    let f = iv.free_cable;
    assert!(iv.lambda.0 <= expected[f] + 1e-9 && expected[f] <= iv.lambda.1 + 1e-9);
}

/// All three loads of Table 6.3 at a few poses: closed form, l1 and Clarabel agree.
#[test]
fn four_cable_table_loads_agree_with_clarabel() {
    let robot = four_cable(0.5);
    let b = TensionBounds::uniform(4, 5.0, 100.0).unwrap();
    for k in 1..=3 {
        for (x, y, phi) in [(0.0, 0.0, 0.0), (0.3, -0.1, 0.05), (-0.4, 0.2, 0.1)] {
            let w = robot
                .inverse_kinematics(&Pose::planar(x, y, phi))
                .unwrap()
                .wrench_matrix();
            let we = load(k);
            let p = TensionProblem::new(&w, &we, &b);
            let cf = solve(Method::ClosedForm, &p);
            let l1 = solve(Method::L1, &p);
            let ip = interior_point(&p, Objective::L1).unwrap();
            assert_eq!(cf.is_feasible(), ip.is_ok(), "L{k} at ({x}, {y}, {phi})");
            assert_eq!(l1.is_feasible(), ip.is_ok());
            if let Ok(t) = ip {
                let s = cf.tensions().unwrap().sum();
                assert!((s - t.sum()).abs() <= 1e-7 * s, "L{k}: {s} vs {}", t.sum());
                assert!((l1.tensions().unwrap().sum() - s).abs() <= 1e-9 * s);
            }
        }
    }
}

/// Point robot with cables along +x, −x, +y, −y: W = [[1, −1, 0, 0], [0, 0, 1, −1]], load
/// (0, −10), t ∈ [5, 100]. Then t1 = t2 and t3 = t4 + 10, and every optimum is by hand:
#[test]
fn cross_point_robot_by_hand() {
    let w = DMatrix::from_row_slice(2, 4, &[1.0, -1.0, 0.0, 0.0, 0.0, 0.0, 1.0, -1.0]);
    let we = DVector::from_vec(vec![0.0, -10.0]);
    let b = TensionBounds::uniform(4, 5.0, 100.0).unwrap();
    let p = TensionProblem::new(&w, &we, &b);
    let t = |m| solve(m, &p).tensions().unwrap().clone();
    let v = |a: [f64; 4]| DVector::from_row_slice(&a);
    // min Σt and min ‖t‖²: everything as low as possible.
    assert!((t(Method::L1) - v([5.0, 5.0, 15.0, 5.0])).amax() < 1e-9);
    assert!((t(Method::L2) - v([5.0, 5.0, 15.0, 5.0])).amax() < 1e-9);
    // max: t3 = 100, t4 = 90, t1 = t2 = 100.
    assert!((t(Method::L1Max) - v([100.0, 100.0, 100.0, 90.0])).amax() < 1e-9);
    assert!((t(Method::L2Max) - v([100.0, 100.0, 100.0, 90.0])).amax() < 1e-9);
    // min max t = 15 (t3 ≥ 15), t1 = t2 anywhere in [5, 15].
    let li = t(Method::Linf);
    assert!((li.max() - 15.0).abs() < 1e-9 && (li[0] - li[1]).abs() < 1e-9);
    // Polygon: (t1, t4) ∈ [5, 100] × [5, 90], a rectangle: centroid (52.5, 47.5). In tension
    // space t = (t1, t1, t4 + 10, t4), whose sides are √2 times longer: area 2 · 95 · 85.
    assert!((t(Method::Barycenter) - v([52.5, 52.5, 57.5, 47.5])).amax() < 1e-9);
    let poly = FeasiblePolygon::compute(&p).unwrap().unwrap();
    assert_eq!(poly.vertices.len(), 4);
    assert!(
        (poly.area() - 2.0 * 95.0 * 85.0).abs() < 1e-6,
        "{}",
        poly.area()
    );
    // pinv: t = (0, 0, 5, −5) violates t_min.
    assert!(matches!(
        solve(Method::Pinv, &p),
        TensionOutcome::Infeasible(Infeasibility::BoundsViolated { .. })
    ));
    // Pott 2014: mean 52.5 everywhere, then the minimum-norm correction: t3 = 57.5, t4 = 47.5.
    assert!((t(Method::ImprovedClosedForm) - v([52.5, 52.5, 57.5, 47.5])).amax() < 1e-9);
    // Too much load: t3 − t4 = 100 > 95 is impossible.
    let heavy = DVector::from_vec(vec![0.0, -100.0]);
    let p2 = TensionProblem::new(&w, &heavy, &b);
    for m in [Method::L1, Method::L2, Method::Linf, Method::Barycenter] {
        assert_eq!(
            solve(m, &p2),
            TensionOutcome::Infeasible(Infeasibility::NoFeasibleTension),
            "{m}"
        );
    }
}

/// Exact: 2 cables on a point, t = −W⁻¹ w; singular when the cables are parallel.
#[test]
fn exact_by_hand_and_singular() {
    let w = DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, 1.0]);
    let we = DVector::from_vec(vec![-3.0, -4.0]);
    let b = TensionBounds::uniform(2, 0.0, 10.0).unwrap();
    let out = solve(Method::Exact, &TensionProblem::new(&w, &we, &b));
    assert!((out.tensions().unwrap() - DVector::from_vec(vec![3.0, 4.0])).amax() < 1e-14);
    let par = DMatrix::from_row_slice(2, 2, &[1.0, 1.0, 0.0, 0.0]);
    assert!(matches!(
        solve(Method::Exact, &TensionProblem::new(&par, &we, &b)),
        TensionOutcome::Infeasible(Infeasibility::SingularPose { .. })
    ));
    // Exact needs n = DOF.
    let w3 = DMatrix::from_row_slice(2, 3, &[1.0, 0.0, -1.0, 0.0, 1.0, -1.0]);
    let b3 = TensionBounds::uniform(3, 0.0, 10.0).unwrap();
    let err = TensionSolver::new(Method::Exact)
        .solve(&TensionProblem::new(&w3, &we, &b3))
        .unwrap_err();
    assert!(matches!(
        err,
        cdpr_tension::TensionError::MethodNotApplicable {
            method: Method::Exact,
            redundancy: 1,
            ..
        }
    ));
    assert!(
        err.to_string()
            .starts_with("method exact needs redundancy 0; this robot has n − DOF = 1")
    );
}

/// Issue 13 §1: pinv is the unconstrained minimum-norm solution. When it breaks a bound the
/// outcome still hands out t = −W⁺ w_ext (it balances the wrench) and names the cable.
/// Two opposed cables, t1 − t2 = 3: W⁺ = (½, −½)ᵀ, t = (1.5, −1.5), cable 2 below t_min = 0.
#[test]
fn pinv_hands_out_its_solution_when_a_bound_breaks() {
    let w = DMatrix::from_row_slice(1, 2, &[1.0, -1.0]);
    let we = DVector::from_vec(vec![-3.0]);
    let b = TensionBounds::uniform(2, 0.0, 10.0).unwrap();
    let p = TensionProblem::new(&w, &we, &b);
    let out = solve(Method::Pinv, &p);
    assert!(!out.is_feasible());
    assert!(out.tensions().is_none());
    let t = out.balancing_tensions().unwrap();
    assert!(
        (t - DVector::from_vec(vec![1.5, -1.5])).amax() < 1e-15,
        "{t}"
    );
    assert!((&w * t + &we).amax() < 1e-15);
    match out.infeasibility().unwrap() {
        Infeasibility::BoundsViolated {
            cable,
            tension,
            bound,
            ..
        } => {
            assert_eq!(*cable, 1);
            assert!((tension + 1.5).abs() < 1e-15);
            assert_eq!(*bound, 0.0);
        }
        other => panic!("{other:?}"),
    }
    // The message names the cable, its tension and the bound it breaks (issue 25).
    assert_eq!(
        out.infeasibility().unwrap().to_string(),
        "the solution needs cable 2 at -1.5 N, below its t_min of 0 N"
    );
    // Exact (n = DOF) likewise: t = −W⁻¹ w_ext = (3, 4) breaks t_max = 3.5 of cable 2.
    let w2 = DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, 1.0]);
    let we2 = DVector::from_vec(vec![-3.0, -4.0]);
    let b2 = TensionBounds::uniform(2, 0.0, 3.5).unwrap();
    let out = solve(Method::Exact, &TensionProblem::new(&w2, &we2, &b2));
    assert_eq!(out.balancing_tensions().unwrap().as_slice(), &[3.0, 4.0]);
    assert_eq!(
        out.infeasibility().unwrap().to_string(),
        "the solution needs cable 2 at 4 N, above its t_max of 3.5 N"
    );
}
