//! Infinite upper bounds (t_max = +∞ for some cables) with wrenches dominated by the moment.
//!
//! Regression for a `CertificateFailed` (bound violation ≈ 1.3·10⁻⁹) of `l1` on random planar
//! robots: with an infinite t_max the feasible polygon is clipped out of an artificial box of
//! half-width 10⁶ × the data scale, and Sutherland–Hodgman interpolated every vertex along an edge
//! of that box, so vertices inherited an absolute error ≈ ε·R ≈ 10⁻¹⁰ × the data scale. Vertices
//! are now intersections of their two defining lines (see `feasible_polygon` docs).
//!
//! Every method must either return tensions that pass an independent check, or a reason that is
//! not `CertificateFailed`; the verdicts of the complete methods must agree with Clarabel.

use cdpr_kinematics::MotionPattern;
use cdpr_kinematics::strategies::{arb_pose, arb_robot};
use cdpr_tension::{
    Infeasibility, Method, Objective, TensionBounds, TensionOutcome, TensionProblem, TensionSolver,
    interior_point,
};
use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;

#[derive(Debug, Clone)]
struct Case {
    w: DMatrix<f64>,
    we: DVector<f64>,
    b: TensionBounds,
}

/// Planar robots with 4–6 cables (r = 1, 2, 3), bounds [1, ∞) on a random non-empty subset of
/// the cables and [1, hi] on the others, and w_ext = (f_x, f_y, τ) with |τ| up to 50 times |f|.
fn arb_case() -> impl Strategy<Value = Case> {
    (
        arb_robot(MotionPattern::Planar, 4..=6),
        arb_pose(MotionPattern::Planar),
        prop::collection::vec(any::<bool>(), 6),
        prop::collection::vec(2.0f64..200.0, 6),
        prop::collection::vec(-1.0f64..1.0, 2),
        -50.0f64..50.0,
    )
        .prop_map(|(robot, pose, infinite, hi, f, tau)| {
            let w = robot.inverse_kinematics(&pose).unwrap().wrench_matrix();
            let n = w.ncols();
            let mut max: Vec<f64> = (0..n)
                .map(|i| if infinite[i] { f64::INFINITY } else { hi[i] })
                .collect();
            max[0] = f64::INFINITY;
            Case {
                we: DVector::from_vec(vec![f[0], f[1], tau]),
                b: TensionBounds::new(vec![1.0; n], max).unwrap(),
                w,
            }
        })
}

fn check(p: &TensionProblem, t: &DVector<f64>) -> Result<(), TestCaseError> {
    let scale = 1f64
        .max(p.external_wrench.amax())
        .max(p.wrench_matrix.abs().row_sum().amax() * t.amax());
    let res = (p.wrench_matrix * t + p.external_wrench).amax();
    prop_assert!(res <= 1e-9 * scale, "residual {res:e}, scale {scale}");
    for i in 0..t.len() {
        let (lo, hi) = (p.bounds.min()[i], p.bounds.max()[i]);
        prop_assert!(
            t[i] >= lo && t[i] <= hi,
            "cable {i}: {} not in [{lo}, {hi}]",
            t[i]
        );
    }
    Ok(())
}

fn solve(m: Method, p: &TensionProblem) -> TensionOutcome {
    TensionSolver::new(m).solve(p).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig { failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn infinite_t_max_and_moment_dominated_wrenches(case in arb_case()) {
        let p = TensionProblem::new(&case.w, &case.we, &case.b);
        let r = p.redundancy();
        // Clarabel's answer proves the set non-empty once it passes the independent check.
        // (Clarabel may call a set empty that is reached only at tensions ~10⁵: our certified
        // answers are the proof in the other direction.)
        let oracle = interior_point(&p, Objective::L2).unwrap();
        let clarabel_feasible = match &oracle {
            Ok(t) => { check(&p, t)?; true }
            Err(_) => false,
        };
        let mut complete_verdicts = Vec::new();
        for m in Method::ALL.into_iter().filter(|m| *m != Method::Sotda) {
            // Inapplicable methods (wrong redundancy; the methods that start from the middle of
            // the bounds, with t_max = ∞) are usage errors.
            let Ok(o) = TensionSolver::new(m).solve(&p) else {
                prop_assert!(!m.applies_to(r) || m.needs_finite_bounds(), "{m} (r = {r})");
                continue;
            };
            if let TensionOutcome::Feasible(s) = &o {
                check(&p, &s.tensions)?;
            }
            if let TensionOutcome::Infeasible(reason) = &o {
                prop_assert!(
                    !matches!(reason, Infeasibility::CertificateFailed { .. }),
                    "{m} (r = {r}): {reason}"
                );
            }
            let complete = matches!(m, Method::L1 | Method::L2 | Method::Linf)
                || (m == Method::ClosedForm && r == 1);
            if complete {
                prop_assert!(
                    o.is_feasible() || !clarabel_feasible,
                    "{m} (r = {r}) misses a feasible set: {:?}", o
                );
                complete_verdicts.push((m, o.is_feasible(), format!("{o:?}")));
            }
        }
        // The complete methods agree (min Σt, min ‖t‖₂, min max t exist on any non-empty set
        // since t ≥ t_min).
        let first = complete_verdicts[0].1;
        prop_assert!(complete_verdicts.iter().all(|v| v.1 == first), "r = {r}: {:?}", complete_verdicts);
    }
}

/// The case behind the regression: a 4-cable planar robot, t ∈ [1, ∞), a pure-ish moment. Before
/// the fix l2 projected onto the segment [503, 2·10⁸] of λ and returned t₂ = 1 − 1.8·10⁻⁹
/// (`CertificateFailed`). Here l1 = l2 = linf = closed form: λ = 503.24… makes t₂ = 1 exactly.
#[test]
fn regression_planar_four_cables_pure_moment() {
    let w = DMatrix::from_column_slice(
        3,
        4,
        &[
            -0.8974199896064621,
            -0.4411772458488059,
            0.0,
            -0.9979838127553813,
            -0.06346896468536511,
            0.11309393060754541,
            0.8636115547219634,
            0.5041577952890477,
            -0.029923921928810104,
            0.5887788553882083,
            -0.8082941664071017,
            -0.00331144130894627,
        ],
    );
    let we = DVector::from_vec(vec![
        0.3603439324953238,
        0.20467078128697158,
        10.922678284715197,
    ]);
    let b = TensionBounds::new(vec![1.0; 4], vec![f64::INFINITY; 4]).unwrap();
    let p = TensionProblem::new(&w, &we, &b);
    let reference = solve(Method::ClosedForm, &p);
    let tc = reference
        .tensions()
        .expect("closed form is feasible")
        .clone();
    for m in [Method::L1, Method::L2, Method::Linf, Method::Pinv] {
        let o = solve(m, &p);
        if let TensionOutcome::Infeasible(reason) = &o {
            assert!(
                !matches!(reason, Infeasibility::CertificateFailed { .. }),
                "{m}: {reason}"
            );
        }
        if let Some(t) = o.tensions() {
            let scale = 1f64.max(w.abs().row_sum().amax() * t.amax());
            assert!((&w * t + &we).amax() <= 1e-9 * scale, "{m}");
            assert!(t.iter().all(|&v| v >= 1.0), "{m}: {t}");
        }
    }
    assert!(
        TensionSolver::new(Method::ImprovedClosedForm)
            .solve(&p)
            .is_err()
    );
    // One cable is slack at t_min in every minimiser (r = 1: a vertex of the interval).
    assert!(tc.iter().any(|&v| (v - 1.0).abs() <= 1e-12), "{tc}");
    for m in [Method::L1, Method::L2, Method::Linf] {
        let t = solve(m, &p).tensions().expect("feasible").clone();
        assert!((&t - &tc).amax() <= 1e-9 * tc.amax(), "{m}: {t} vs {tc}");
    }
    assert!(matches!(
        solve(Method::L1Max, &p).infeasibility(),
        Some(Infeasibility::Unbounded { .. })
    ));
}

/// Issue 13 §1: l2-max at redundancy ≥ 3 answered "unbounded" whenever some t_max = ∞,
/// without looking at the set. t1 + t2 − t3 + t4 = 1, t ∈ [1, 10]³ × [1, ∞): t4 = 1 − t1 − t2 +
/// t3 ≤ 9, so the set is bounded; max ‖t‖² = 183 at (9, 1, 10, 1), (1, 9, 10, 1) and
/// (1, 1, 10, 9) (l1-max returns (9, 1, 10, 1)).
#[test]
fn l2_max_decides_boundedness_from_the_set() {
    let w = DMatrix::from_row_slice(1, 4, &[1.0, 1.0, -1.0, 1.0]);
    let we = DVector::from_vec(vec![-1.0]);
    let b = TensionBounds::new(vec![1.0; 4], vec![10.0, 10.0, 10.0, f64::INFINITY]).unwrap();
    let p = TensionProblem::new(&w, &we, &b);
    let out = solve(Method::L2Max, &p);
    let t = out.tensions().unwrap_or_else(|| panic!("{out:?}"));
    assert!((t.norm_squared() - 183.0).abs() < 1e-9, "{t}");
    assert!((&w * t + &we).amax() < 1e-12);
    // t1 + t2 + t3 + t4 = −10 with t ≥ 1: empty, not unbounded.
    let w = DMatrix::from_row_slice(1, 4, &[1.0; 4]);
    let we = DVector::from_vec(vec![10.0]);
    let b = TensionBounds::new(vec![1.0; 4], vec![f64::INFINITY; 4]).unwrap();
    let out = solve(Method::L2Max, &TensionProblem::new(&w, &we, &b));
    assert_eq!(out.infeasibility(), Some(&Infeasibility::NoFeasibleTension));
    // t1 + t2 − t3 − t4 = 0, t ≥ 1 (all t_max = ∞): t1 = t3 → ∞ is a ray: unbounded.
    let w = DMatrix::from_row_slice(1, 4, &[1.0, 1.0, -1.0, -1.0]);
    let we = DVector::from_vec(vec![0.0]);
    let out = solve(Method::L2Max, &TensionProblem::new(&w, &we, &b));
    assert!(
        matches!(out.infeasibility(), Some(Infeasibility::Unbounded { .. })),
        "{out:?}"
    );
}
