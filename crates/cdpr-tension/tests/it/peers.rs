//! The methods of issue 26 (pott-closed-form, pott-closed-form-ee, puncture, dykstra, l2-mid,
//! vertex-centroid, p-norm, optimally-safe): hand-derived answers on a one-equation problem,
//! and properties on random robots (equilibrium and bounds of every answer, verdicts against
//! the LP, l2-mid's optimality against every other feasible answer, pott-closed-form against
//! an independent pseudo-inverse from nalgebra's SVD).

use cdpr_kinematics::strategies::arb_robot_and_pose;
use cdpr_tension::{
    GiveUp, Infeasibility, Method, MethodOptions, PunctureInterior, TensionBounds, TensionOutcome,
    TensionProblem, TensionSolver, certify,
};
use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;

/// The methods of issue 26.
const PEERS: [Method; 8] = [
    Method::PottClosedForm,
    Method::PottClosedFormEe,
    Method::Puncture,
    Method::Dykstra,
    Method::L2Mid,
    Method::VertexCentroid,
    Method::PNorm,
    Method::OptimallySafe,
];

fn solve_with(
    method: Method,
    options: MethodOptions,
    w: &DMatrix<f64>,
    we: &DVector<f64>,
    b: &TensionBounds,
) -> TensionOutcome {
    TensionSolver::new(method)
        .with_options(options)
        .unwrap()
        .solve(&TensionProblem::new(w, we, b))
        .unwrap()
}

fn solve(method: Method, w: &DMatrix<f64>, we: &DVector<f64>, b: &TensionBounds) -> TensionOutcome {
    solve_with(method, MethodOptions::default(), w, we, b)
}

fn assert_close(t: &DVector<f64>, expected: &[f64], tol: f64, what: &str) {
    for (a, e) in t.iter().zip(expected) {
        assert!((a - e).abs() <= tol, "{what}: {t:?} against {expected:?}");
    }
}

/// t1 − t2 = 1 (W = [1, −1], w_ext = −1), bounds [1, 10] N: the equilibrium line
/// t = (6, 5) + μ (1, 1), the feasible segment from (2, 1) to (10, 9), t_m = (5.5, 5.5).
#[test]
fn hand_derived_on_one_equation() {
    let w = DMatrix::from_row_slice(1, 2, &[1.0, -1.0]);
    let we = DVector::from_vec(vec![-1.0]);
    let b = TensionBounds::uniform(2, 1.0, 10.0).unwrap();
    let t = |m: Method| solve(m, &w, &we, &b).tensions().unwrap().clone();
    // The projection of t_m onto the line: (6, 5); it is inside, so also l2-mid's and
    // dykstra's answer, the midpoint of the segment (vertex-centroid: ((2, 1) + (10, 9))/2),
    // the p-norm optimum (deviations ±0.5 + μ, minimal at μ = 0) and the optimally safe
    // point (t2 − 1 = 9 − t2 = s: t2 = 5).
    for m in [
        Method::PottClosedForm,
        Method::L2Mid,
        Method::Dykstra,
        Method::VertexCentroid,
        Method::PNorm,
        Method::OptimallySafe,
    ] {
        assert_close(&t(m), &[6.0, 5.0], 1e-6, m.name());
    }
    // Energy-efficient: d = N Nᵀ 1 = (1, 1); lowered by δ = min(5, 4): cable 2 at t_min.
    assert_close(&t(Method::PottClosedFormEe), &[2.0, 1.0], 1e-12, "ee");
    // Puncture from t₀ = (0.5, −0.5) towards (6, 5): cable 2 enters last, at (2, 1).
    assert_close(&t(Method::Puncture), &[2.0, 1.0], 1e-12, "puncture");
    let cf = MethodOptions {
        interior: PunctureInterior::ClosedForm,
        ..Default::default()
    };
    let tc = solve_with(Method::Puncture, cf, &w, &we, &b);
    assert_close(tc.tensions().unwrap(), &[2.0, 1.0], 1e-12, "puncture cf");
    // α = 3: t2 − 1 = s, 9 − t2 = 3 s: s = 2, t = (4, 3).
    let a3 = MethodOptions {
        alpha: 3.0,
        ..Default::default()
    };
    let ts = solve_with(Method::OptimallySafe, a3, &w, &we, &b);
    assert_close(
        ts.tensions().unwrap(),
        &[4.0, 3.0],
        1e-9,
        "optimally-safe α = 3",
    );
    // p = 2 is l2-mid on uniform bounds.
    let p2 = MethodOptions {
        p: 2.0,
        ..Default::default()
    };
    let tp = solve_with(Method::PNorm, p2, &w, &we, &b);
    assert_close(tp.tensions().unwrap(), &[6.0, 5.0], 1e-6, "p-norm p = 2");
}

/// t1 − t2 = 12 with bounds [1, 10]: t1 = t2 + 12 ≥ 13 > 10, the feasible set is empty. The
/// complete methods prove it; the closed form breaks a bound; the puncture line misses.
#[test]
fn hand_derived_empty_set() {
    let w = DMatrix::from_row_slice(1, 2, &[1.0, -1.0]);
    let we = DVector::from_vec(vec![-12.0]);
    let b = TensionBounds::uniform(2, 1.0, 10.0).unwrap();
    for m in [
        Method::L2Mid,
        Method::VertexCentroid,
        Method::OptimallySafe,
        Method::PNorm,
        Method::Dykstra,
    ] {
        assert_eq!(
            solve(m, &w, &we, &b).infeasibility(),
            Some(&Infeasibility::NoFeasibleTension),
            "{m}"
        );
    }
    assert!(matches!(
        solve(Method::PottClosedForm, &w, &we, &b).infeasibility(),
        Some(Infeasibility::BoundsViolated { .. })
    ));
    assert_eq!(
        solve(Method::Puncture, &w, &we, &b).infeasibility(),
        Some(&Infeasibility::Inconclusive { method: "puncture" })
    );
}

/// Redundancy 2, t1 − t2 − t3 = 25 with bounds [1, 10]: t1 = t2 + t3 + 25 ≥ 27 > 10, the
/// feasible polygon is empty. vertex-centroid finds no vertex and the clipped polygon confirms
/// it (no dense active set); at every t1 the residual of the nearest bounded point is ≥ 17 N,
/// so an answer would fail its certificate.
#[test]
fn vertex_centroid_confirms_an_empty_polygon_at_redundancy_2() {
    let w = DMatrix::from_row_slice(1, 3, &[1.0, -1.0, -1.0]);
    let we = DVector::from_vec(vec![-25.0]);
    let b = TensionBounds::uniform(3, 1.0, 10.0).unwrap();
    for m in [Method::VertexCentroid, Method::L2Mid] {
        assert_eq!(
            solve(m, &w, &we, &b).infeasibility(),
            Some(&Infeasibility::NoFeasibleTension),
            "{m}"
        );
    }
    // With t1 − t2 − t3 = 8 the set is the single point (10, 1, 1) (t1 = t2 + t3 + 8 ≤ 10
    // forces t2 = t3 = 1): one vertex, its own centroid.
    let point = DVector::from_vec(vec![-8.0]);
    let t = solve(Method::VertexCentroid, &w, &point, &b);
    assert_close(
        t.tensions().unwrap(),
        &[10.0, 1.0, 1.0],
        1e-9,
        "single point",
    );
}

/// l2-mid on a target outside: t1 − t2 = 8, bounds [1, 10]: the segment (9, 1)–(10, 2);
/// t_m's projection onto the line is (9.5, 1.5), inside: l2-mid = (9.5, 1.5). With t1 − t2 = 9
/// the set is the single point (10, 1): no interior, so p-norm gives up; the others find it.
#[test]
fn hand_derived_thin_sets() {
    let w = DMatrix::from_row_slice(1, 2, &[1.0, -1.0]);
    let b = TensionBounds::uniform(2, 1.0, 10.0).unwrap();
    let we = DVector::from_vec(vec![-8.0]);
    let t = solve(Method::L2Mid, &w, &we, &b);
    assert_close(t.tensions().unwrap(), &[9.5, 1.5], 1e-12, "l2-mid");
    let point = DVector::from_vec(vec![-9.0]);
    for m in [Method::L2Mid, Method::VertexCentroid, Method::OptimallySafe] {
        let t = solve(m, &w, &point, &b);
        assert_close(t.tensions().unwrap(), &[10.0, 1.0], 1e-9, m.name());
    }
    assert_eq!(
        solve(Method::PNorm, &w, &point, &b).infeasibility(),
        Some(&Infeasibility::GaveUp {
            method: "p-norm",
            reason: GiveUp::EmptyInterior
        })
    );
}

/// A cable fixed at t_min = t_max leaves no interior for the barriers: p-norm moves it into
/// the load and solves for the others. t1 + t2 − t3 = 4 (W = [1, 1, −1], w_ext = −4), t3 fixed
/// at 2, t1, t2 ∈ [1, 10]: t1 + t2 = 6, t_m = (5.5, 5.5), min |t1 − 5.5|^p + |t2 − 5.5|^p on
/// the line is the symmetric point (3, 3) for every p (p = 2: also l2-mid's answer). Before
/// the reduction p-norm gave up (`EmptyInterior`) here.
#[test]
fn p_norm_with_a_fixed_cable() {
    let w = DMatrix::from_row_slice(1, 3, &[1.0, 1.0, -1.0]);
    let we = DVector::from_vec(vec![-4.0]);
    let b = TensionBounds::new(vec![1.0, 1.0, 2.0], vec![10.0, 10.0, 2.0]).unwrap();
    for p in [2.0, 4.0, 6.0] {
        let o = MethodOptions {
            p,
            ..Default::default()
        };
        let t = solve_with(Method::PNorm, o, &w, &we, &b);
        assert_close(
            t.tensions().unwrap(),
            &[3.0, 3.0, 2.0],
            1e-6,
            "p-norm, fixed t3",
        );
    }
    let t = solve(Method::L2Mid, &w, &we, &b);
    assert_close(
        t.tensions().unwrap(),
        &[3.0, 3.0, 2.0],
        1e-9,
        "l2-mid, fixed t3",
    );
    // Only fixed cables (fewer free cables than DOF): still the documented give-up.
    let all = TensionBounds::new(vec![3.0, 3.0, 2.0], vec![3.0, 3.0, 2.0]).unwrap();
    assert_eq!(
        solve(Method::PNorm, &w, &we, &all).infeasibility(),
        Some(&Infeasibility::GaveUp {
            method: "p-norm",
            reason: GiveUp::EmptyInterior
        })
    );
}

/// An iteration cap of 1 makes dykstra give up where the closed form is outside the box.
#[test]
fn dykstra_cap_is_a_give_up() {
    let w = DMatrix::from_row_slice(1, 2, &[1.0, -1.0]);
    let b = TensionBounds::uniform(2, 1.0, 10.0).unwrap();
    let we = DVector::from_vec(vec![-8.5]);
    let one = MethodOptions {
        max_iterations: 1,
        ..Default::default()
    };
    let out = solve_with(Method::Dykstra, one, &w, &we, &b);
    // Whatever one projection pair reaches, it is certified tensions or a give-up, never an
    // "infeasible" verdict (the set is non-empty: t2 ∈ [1, 1.5]).
    match out.infeasibility() {
        None => assert!(certify(&w, &we, &b, out.tensions().unwrap().as_slice()).is_valid()),
        Some(r) => assert!(matches!(r, Infeasibility::GaveUp { .. }), "{r:?}"),
    }
}

#[derive(Debug, Clone)]
struct Case {
    w: DMatrix<f64>,
    we: DVector<f64>,
    b: TensionBounds,
}

fn arb_case() -> impl Strategy<Value = Case> {
    (
        arb_robot_and_pose(1..=3),
        prop::collection::vec(0.0f64..5.0, 12),
        prop::collection::vec(1.0f64..100.0, 12),
        prop::collection::vec(0.0f64..1.0, 12),
        prop::collection::vec(-1.0f64..1.0, 6),
        prop_oneof![Just(0.0), 0.0f64..60.0],
    )
        .prop_map(|((robot, pose), lo, span, frac, dir, mag)| {
            let w = robot.inverse_kinematics(&pose).unwrap().wrench_matrix();
            let (m, n) = w.shape();
            let lo: Vec<f64> = lo[..n].to_vec();
            let hi: Vec<f64> = (0..n).map(|i| lo[i] + span[i]).collect();
            let tr = DVector::from_fn(n, |i, _| lo[i] + frac[i] * span[i]);
            let we = -(&w * tr) + DVector::from_fn(m, |k, _| mag * dir[k]);
            Case {
                w,
                we,
                b: TensionBounds::new(lo, hi).unwrap(),
            }
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// Every answer is in equilibrium and in bounds; the complete methods agree with the LP's
    /// verdict (give-ups aside); dykstra and p-norm never answer "infeasible" on a feasible
    /// set; l2-mid is at least as close to t_m as every other feasible answer;
    /// pott-closed-form equals t_m − W⁺(w + W t_m) with W⁺ from the SVD.
    #[test]
    fn peers_are_certified_and_consistent(c in arb_case()) {
        let lp = TensionSolver::new(Method::L1)
            .solve(&TensionProblem::new(&c.w, &c.we, &c.b))
            .unwrap();
        if matches!(lp.infeasibility(), Some(Infeasibility::SingularPose { .. })) {
            return Ok(());
        }
        let feasible = lp.is_feasible();
        let tm = DVector::from_fn(c.w.ncols(), |i, _| 0.5 * (c.b.min()[i] + c.b.max()[i]));
        let mut answers = Vec::new();
        for m in PEERS {
            let out = solve(m, &c.w, &c.we, &c.b);
            match &out {
                TensionOutcome::Feasible(s) => {
                    prop_assert!(certify(&c.w, &c.we, &c.b, s.tensions.as_slice()).is_valid(), "{m}");
                    prop_assert!(feasible, "{m} feasible where the LP is not");
                    answers.push((m, s.tensions.clone()));
                }
                TensionOutcome::Infeasible(r) => {
                    let gave_up = matches!(r, Infeasibility::GaveUp { .. });
                    match m {
                        Method::L2Mid | Method::VertexCentroid | Method::OptimallySafe => {
                            prop_assert!(!feasible, "{m}: {r}")
                        }
                        Method::Dykstra | Method::PNorm => {
                            prop_assert!(!feasible || gave_up, "{m}: {r}")
                        }
                        _ => {}
                    }
                }
            }
            if m == Method::PottClosedForm {
                let t = out.balancing_tensions().unwrap();
                let pinv = c.w.clone().pseudo_inverse(1e-13).unwrap();
                let reference = &tm - pinv * (&c.we + &c.w * &tm);
                let scale = tm.amax().max(1.0);
                prop_assert!((t - &reference).amax() <= 1e-8 * scale, "{t} vs {reference}");
            }
        }
        if let Some((_, best)) = answers.iter().find(|(m, _)| *m == Method::L2Mid) {
            let own = (best - &tm).norm();
            for (m, t) in &answers {
                let other = (t - &tm).norm();
                prop_assert!(own <= other + 1e-7 * other.max(1.0), "{m} beats l2-mid: {other} < {own}");
            }
        }
    }
}

/// Puncture on ill-conditioned W (rows 10⁻⁵·k from dependent, k = 1, 10, 100, 1000: Hadamard
/// ratios on both sides of the fast path's 10⁻³, where its line start t0 = −W⁺ w_ext leaves the
/// normal equations for the QR null space) against the transcription with the SVD's t0 and the
/// improved closed form's interior point: the same verdict, tensions within the problems' own
/// conditioning (10⁻⁶ N at 500 N).
#[test]
fn ill_conditioned_puncture_equals_the_svd_line() {
    let mut feasible = 0;
    for k in [1.0, 10.0, 100.0, 1000.0] {
        let mut w = DMatrix::from_fn(3, 5, |i, j| ((i * 5 + j) as f64 * 0.7).sin());
        for j in 0..5 {
            w[(2, j)] = w[(0, j)] + w[(1, j)] + k * 1e-5 * ((j as f64) - 2.0);
        }
        // In equilibrium with t* = (400, 550, 500, 620, 480) N: the set is not empty.
        let t_star = DVector::from_vec(vec![400.0, 550.0, 500.0, 620.0, 480.0]);
        let we = -(&w * &t_star);
        let b = TensionBounds::new(vec![1.0; 5], vec![1000.0; 5]).unwrap();
        let icf = solve(Method::ImprovedClosedForm, &w, &we, &b);
        let Some(interior) = icf.tensions() else {
            continue;
        };
        let t0 = -(w.clone().pseudo_inverse(1e-15).unwrap() * &we);
        let d = interior - &t0;
        let (mut enter, mut leave) = (f64::NEG_INFINITY, f64::INFINITY);
        for i in 0..5 {
            let (lo, hi) = ((1.0 - t0[i]) / d[i], (1000.0 - t0[i]) / d[i]);
            enter = enter.max(lo.min(hi));
            leave = leave.min(lo.max(hi));
        }
        let out = solve(Method::Puncture, &w, &we, &b);
        assert_eq!(out.is_feasible(), enter <= leave, "k = {k}: {out:?}");
        if let Some(t) = out.tensions() {
            let reference = &t0 + enter * &d;
            assert!(
                (t - &reference).amax() <= 1e-6,
                "k = {k}: {t} vs {reference}"
            );
            feasible += 1;
        }
    }
    assert!(feasible >= 2, "{feasible} feasible lines");
}

/// An ill-conditioned W (one row 10⁻⁵ from the sum of the others, below the fast path's
/// Hadamard ratio of 10⁻³): Pott's closed form then runs on the QR null space and still equals
/// the SVD's t_m − W⁺(w + W t_m) within the problem's own conditioning (the two factorisations
/// differ by about 3·10⁻⁸ N at this 500 N scale), and both variants are in equilibrium.
#[test]
fn ill_conditioned_closed_form_takes_the_null_space() {
    let mut w = DMatrix::from_fn(3, 5, |i, j| ((i * 5 + j) as f64 * 0.7).sin());
    // Row 2 almost row 0 + row 1: nearly rank 2.
    for j in 0..5 {
        w[(2, j)] = w[(0, j)] + w[(1, j)] + 1e-5 * ((j as f64) - 2.0);
    }
    let we = DVector::from_vec(vec![0.3, -0.2, 0.1 + 1e-6]);
    let b = TensionBounds::new(vec![0.0; 5], vec![1000.0; 5]).unwrap();
    let tm = DVector::from_element(5, 500.0);
    let pinv = w.clone().pseudo_inverse(1e-15).unwrap();
    let reference = &tm - &pinv * (&we + &w * &tm);
    for m in [Method::PottClosedForm, Method::PottClosedFormEe] {
        let out = solve(m, &w, &we, &b);
        let t = out.balancing_tensions().unwrap();
        if m == Method::PottClosedForm {
            assert!((t - &reference).amax() <= 1e-6, "{t} vs {reference}");
        }
        assert!(
            certify(&w, &we, &b, t.as_slice()).residual < 1e-6,
            "{m}: {out:?}"
        );
    }
}
