//! # Minimum-norm approach
//!
//! For n = DOF the unique solution t = −W⁻¹ w_ext (seed 000 eq. (6.12)); for n > DOF the
//! minimum-norm solution t^mn = −W⁺ w_ext = −Wᵀ(W Wᵀ)⁻¹ w_ext (eq. (6.14), Fattah & Agrawal),
//! i.e. t^nul = 0 in eq. (6.13). The bounds are only checked: the thesis' Fig. 6.3 shows how much
//! workspace this loses compared with the constrained ℓ₂ approach (see
//! `tests/minimum_norm_vs_l2.rs`). Both are computed from the pivoted QR of Wᵀ (see the
//! null-space docs), which also detects singular poses.
//!
//! ## References
//! - Seed 000, eqs. (6.12)–(6.14). Fattah & Agrawal (2005).

use crate::certificate::bound_violation;
use crate::null_space::NullSpace;
use crate::{Infeasibility, TensionBounds, TensionProblem};

/// Eq. (6.12) (r = 0) or eq. (6.14) (r > 0) into `t`; checks the bounds.
pub(crate) fn minimum_norm(
    ns: &mut NullSpace,
    problem: &TensionProblem,
    t: &mut [f64],
) -> Result<(), Infeasibility> {
    ns.compute(problem.wrench_matrix, problem.external_wrench)
        .map_err(|condition| Infeasibility::SingularPose { condition })?;
    t.copy_from_slice(&ns.t0);
    check_bounds(problem.bounds, t)
}

/// `BoundsViolated` for the cable with the largest relative violation, if any exceeds the
/// certificate tolerance.
pub(crate) fn check_bounds(bounds: &TensionBounds, t: &[f64]) -> Result<(), Infeasibility> {
    let mut worst = (0, f64::NEG_INFINITY);
    for (i, &ti) in t.iter().enumerate() {
        let v = bound_violation(bounds.min()[i], bounds.max()[i], ti);
        if v > worst.1 {
            worst = (i, v);
        }
    }
    if worst.1 > crate::certificate::BOUND_TOLERANCE {
        return Err(Infeasibility::BoundsViolated {
            cable: worst.0,
            tension: t[worst.0],
        });
    }
    Ok(())
}
