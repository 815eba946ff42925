//! # The puncture method (Müller, Reichert & Bruckmann 2014)
//!
//! Every point of the line through the minimum-norm solution t₀ = −W⁺ w_ext and an interior
//! estimate t_int (both in equilibrium) balances the wrench:
//!
//! ```text
//!   t(s) = t₀ + s (t_int − t₀),     s ∈ ℝ
//! ```
//!
//! Cable i stays in its bounds for s in the slab [min(a_i, b_i), max(a_i, b_i)] with
//! a_i = (t_min,i − t₀,i)/d_i, b_i = (t_max,i − t₀,i)/d_i, d = t_int − t₀ (a cable with d_i = 0
//! keeps t₀,i, which must be in its bounds). The method "punctures" the feasible set: it takes
//! the first point of the line inside every slab, s* = max_i min(a_i, b_i), feasible when
//! s* ≤ min_i max(a_i, b_i) (from t₀ towards t_int, the point where the last cable enters its
//! bounds, in particular rises above t_min). Cables whose |d_i| is below 10⁻¹²·max(1, |t₀,i|)
//! count as d_i = 0.
//!
//! The interior estimate (`--interior`): `icf`, the improved closed form (Pott 2014; CASPR
//! `id_cf_ipm`, WireLib's `getDistributionPuncture`), the default; or `cf`, the closed form of
//! Pott, Bruckmann & Mikelsons 2009 (CASPR `id_cf_pm`). When the improved closed form finds no
//! feasible tensions, the closed form is the interior estimate. With `icf` the line start t₀
//! comes from the improved closed form's first L D Lᵀ factor of W Wᵀ, t₀ = −Wᵀ (W Wᵀ)⁻¹ w_ext,
//! without a null-space basis (the QR null space where that factor's Hadamard ratio is below
//! 10⁻³, as for `pott-closed-form`). The answer depends only on the
//! line: when the line misses the feasible set the verdict is
//! [`Infeasibility::Inconclusive`] (the set may be non-empty elsewhere). WireLib shrinks the
//! bounds by 10⁻⁶ N first; here the certificate's 10⁻⁹ relative tolerance decides instead.
//!
//! ## References
//! - Müller, Reichert & Bruckmann (2014), *Analysis of a real-time capable cable force
//!   computation method*, Cable-Driven Parallel Robots (CableCon 2014), Springer, pp. 227–238.
//! - CASPR (Lau et al.): `IDSolverClosedForm`, methods `id_cf_pm` and `id_cf_ipm`.
//! - Pott (2014), *An improved force distribution algorithm for over-constrained cable-driven
//!   parallel robots*, Computational Kinematics, pp. 139–146.

use crate::{Infeasibility, TensionBounds};

/// Relative size below which a direction entry counts as zero.
const NEGLIGIBLE: f64 = 1e-12;

/// The puncture point of the line t₀ → t_int into `t` (module docs).
pub(crate) fn solve(
    t0: &[f64],
    interior: &[f64],
    bounds: &TensionBounds,
    t: &mut [f64],
) -> Result<(), Infeasibility> {
    let (lo, hi) = (bounds.min(), bounds.max());
    let (mut enter, mut leave) = (f64::NEG_INFINITY, f64::INFINITY);
    let mut moves = false;
    for i in 0..t0.len() {
        let d = interior[i] - t0[i];
        if d.abs() <= NEGLIGIBLE * t0[i].abs().max(1.0) {
            let tol = crate::certificate::BOUND_TOLERANCE;
            if crate::certificate::bound_violation(lo[i], hi[i], t0[i]) > tol {
                return Err(Infeasibility::Inconclusive { method: "puncture" });
            }
            continue;
        }
        moves = true;
        let a = (lo[i] - t0[i]) / d;
        let b = (hi[i] - t0[i]) / d;
        enter = enter.max(a.min(b));
        leave = leave.min(a.max(b));
    }
    let s = if moves { enter } else { 0.0 };
    // A cable's slab may be a point (t_min = t_max): allow the certificate's rounding.
    let slack = leave + 1e-12 * s.abs().max(1.0) - s;
    if moves && (slack.is_nan() || slack < 0.0) {
        return Err(Infeasibility::Inconclusive { method: "puncture" });
    }
    for i in 0..t0.len() {
        t[i] = t0[i] + s * (interior[i] - t0[i]);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One equation t1 − t2 = 1 (t₀ = (0.5, −0.5)), bounds [1, 10]: along t₀ → t_int =
    /// (6, 5) (d = (5.5, 5.5)), cable 2 enters its bounds last, at s = 1.5/5.5: t = (2, 1).
    #[test]
    fn hand_derived_puncture_point() {
        let b = TensionBounds::uniform(2, 1.0, 10.0).unwrap();
        let mut t = [0.0; 2];
        solve(&[0.5, -0.5], &[6.0, 5.0], &b, &mut t).unwrap();
        assert!(
            (t[0] - 2.0).abs() < 1e-14 && (t[1] - 1.0).abs() < 1e-14,
            "{t:?}"
        );
        // A line that misses the box: t₀ = (0.5, −0.5) towards (0.5, 20.0) keeps cable 1 at 0.5.
        assert_eq!(
            solve(&[0.5, -0.5], &[0.5, 20.0], &b, &mut t),
            Err(Infeasibility::Inconclusive { method: "puncture" })
        );
    }
}
