//! The improved closed form against a direct transcription of Pott's (2014) iteration: start
//! from t = t_m − W⁺(w_ext + W t_m); while a free tension violates its bounds, saturate the free
//! cable with the largest violation (force units) at that bound, move its force into the wrench
//! and recompute the closed form for the remaining cables from their mean tensions, as long as at
//! least DOF cables remain. Here every step uses nalgebra's pseudo-inverse of the reduced W
//! (the library uses a Cholesky factor of the reduced W Wᵀ).

use cdpr_tension::{Infeasibility, Method, TensionBounds, TensionProblem, TensionSolver};
use nalgebra::{DMatrix, DVector};

/// A violation beyond the certificate's relative tolerance (the same test as the library).
fn violates(lo: f64, hi: f64, t: f64) -> bool {
    (lo - t) / lo.abs().max(1.0) > 1e-9 || (t - hi) / hi.abs().max(1.0) > 1e-9
}

/// Pott (2014) by pseudo-inverses; `None` when a reduced W is (nearly) rank-deficient, where the
/// library's singularity rule decides instead.
fn reference(
    w: &DMatrix<f64>,
    we: &DVector<f64>,
    lo: &[f64],
    hi: &[f64],
) -> Option<Result<DVector<f64>, ()>> {
    let (m, n) = w.shape();
    let mut free: Vec<usize> = (0..n).collect();
    let mut t = DVector::from_fn(n, |i, _| 0.5 * (lo[i] + hi[i]));
    let mut wrench = we.clone();
    loop {
        let a = DMatrix::from_fn(m, free.len(), |r, c| w[(r, free[c])]);
        let sv = a.clone().svd(false, false).singular_values;
        if sv.min() < 1e-8 * sv.max() {
            return None;
        }
        let tm = DVector::from_fn(free.len(), |c, _| 0.5 * (lo[free[c]] + hi[free[c]]));
        let x = &tm - a.clone().pseudo_inverse(1e-14).unwrap() * (&wrench + &a * &tm);
        for (c, &i) in free.iter().enumerate() {
            t[i] = x[c];
        }
        // The free cable with the largest violation (force units), ties to the lower index.
        let mut worst: Option<(usize, f64)> = None;
        for &i in &free {
            if violates(lo[i], hi[i], t[i]) {
                let v = (lo[i] - t[i]).max(t[i] - hi[i]);
                if worst.is_none_or(|(_, wv)| v > wv) {
                    worst = Some((i, v));
                }
            }
        }
        let Some((i, _)) = worst else {
            return Some(Ok(t));
        };
        if free.len() <= m {
            return Some(Err(()));
        }
        t[i] = if t[i] < lo[i] { lo[i] } else { hi[i] };
        wrench += w.column(i) * t[i];
        free.retain(|&j| j != i);
    }
}

#[test]
fn matches_a_direct_transcription_of_the_iteration() {
    let mut state = 0x0123_4567_89ab_cdefu64;
    let mut rnd = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let (mut feasible, mut inconclusive, mut saturating) = (0, 0, 0);
    for case in 0..3000 {
        let m = 1 + case % 6;
        let n = m + 1 + (case / 6) % 5;
        let w = DMatrix::from_fn(m, n, |_, _| 2.0 * rnd() - 1.0);
        let lo: Vec<f64> = (0..n).map(|_| 10.0 * rnd()).collect();
        let hi: Vec<f64> = lo.iter().map(|l| l + 1.0 + 150.0 * rnd()).collect();
        let tr = DVector::from_fn(n, |i, _| lo[i] + rnd() * (hi[i] - lo[i]));
        // A third of the loads are pushed off the feasible set (inconclusive answers).
        let push = if case % 3 == 0 { 40.0 } else { 0.0 };
        let we = -(&w * tr) + DVector::from_fn(m, |_, _| push * (2.0 * rnd() - 1.0));
        let b = TensionBounds::new(lo.clone(), hi.clone()).unwrap();
        let out = TensionSolver::new(Method::ImprovedClosedForm)
            .solve(&TensionProblem::new(&w, &we, &b))
            .unwrap();
        let Some(expected) = reference(&w, &we, &lo, &hi) else {
            continue;
        };
        match (&expected, out.tensions()) {
            (Ok(te), Some(t)) => {
                let tm = DVector::from_fn(n, |i, _| 0.5 * (lo[i] + hi[i]));
                let plain = &tm - w.clone().pseudo_inverse(1e-14).unwrap() * (&we + &w * &tm);
                saturating += (0..n).any(|i| violates(lo[i], hi[i], plain[i])) as usize;
                assert!(
                    (t - te).amax() <= 1e-8 * te.amax().max(1.0),
                    "case {case}: {t} vs {te}"
                );
                feasible += 1;
            }
            (Err(()), None) => {
                assert_eq!(
                    out.infeasibility(),
                    Some(&Infeasibility::Inconclusive {
                        method: "improved-closed-form"
                    }),
                    "case {case}"
                );
                inconclusive += 1;
            }
            (e, t) => panic!("case {case}: reference {e:?}, library {t:?}"),
        }
    }
    // Every kind of outcome occurs, including answers that needed saturated cables.
    assert!(
        feasible > 1000 && inconclusive > 100 && saturating > 300,
        "{feasible} {inconclusive} {saturating}"
    );
}

/// A 2-DOF example where the published rule (largest violation in force units) and a relative
/// rule (violation / max(1, |bound|)) saturate different cables and end differently.
/// W = [[−1, −2, −2, 0], [2, −2, 0, 1]], w_ext = (30, −10), t ∈ [0, (10, 100, 20, 2)].
/// The closed form from t_m = (5, 50, 10, 1) gives t ≈ (14.68, 14.73, −7.06, 10.10): cable 1 is
/// 4.68 above, cable 3 7.06 below, cable 4 8.10 above its limit. By force, cable 4 is saturated
/// at 2 (a relative rule would pick cable 3: 7.06 > 8.10 / 2, and end inconclusive). Then
/// t ≈ (17.06, 13.06, −6.59, 2): cable 1 (7.06 above) is saturated at 10, and the square rest
/// gives −2 t2 − 2 t3 = −20, −2 t2 = −12: t = (10, 6, 4, 2), feasible.
#[test]
fn hand_derived_saturation_sequence() {
    let w = DMatrix::from_row_slice(2, 4, &[-1.0, -2.0, -2.0, 0.0, 2.0, -2.0, 0.0, 1.0]);
    let we = DVector::from_vec(vec![30.0, -10.0]);
    let b = TensionBounds::new(vec![0.0; 4], vec![10.0, 100.0, 20.0, 2.0]).unwrap();
    let out = TensionSolver::new(Method::ImprovedClosedForm)
        .solve(&TensionProblem::new(&w, &we, &b))
        .unwrap();
    let t = out.tensions().unwrap();
    for (a, e) in t.iter().zip([10.0, 6.0, 4.0, 2.0]) {
        assert!((a - e).abs() < 1e-12, "{t}");
    }
}
