//! # Optimally safe tension distribution (Borgstrom et al. 2009)
//!
//! The tensions farthest from their bounds, as a linear program in (t, s):
//!
//! ```text
//!   max s   subject to   W t + w_ext = 0,   t − t_min ≥ s 1,   t_max − t ≥ α s 1
//! ```
//!
//! (`--alpha` weights the upper margin, default α = 1; cables with t_max = ∞ have no upper
//! row). On t = t0 + N λ it is an LP in r + 1 unknowns, solved by the primal active-set
//! (simplex) method of module `active_set` with Bland's rule, from λ = 0 and the largest s
//! there (any r). The optimum s* is the margin: s* < 0 means the feasible set is empty
//! ([`Infeasibility::NoFeasibleTension`], with a tolerance of 10⁻⁹ max(1, |t_min|, |t_max|));
//! otherwise the optimal tensions are certified as usual. An unbounded s (no finite t_max and
//! a null-space direction raising every cable) is [`Infeasibility::Unbounded`].
//!
//! ## References
//! - Borgstrom, P. H., Jordan, B. L., Sukhatme, G. S., Batalin, M. A. & Kaiser, W. J. (2009),
//!   *Rapid computation of optimally safe tension distributions for parallel cable-driven
//!   robots*, IEEE Transactions on Robotics 25(6), pp. 1271–1281.
//! - CASPR (Lau et al.): `IDSolverOptimallySafe`.

use crate::active_set::{ActiveSet, DenseEnd};
use crate::certificate::BOUND_TOLERANCE;
use crate::null_space::NullSpace;
use crate::{Infeasibility, TensionBounds};

/// The optimally safe tensions into `t` and the margin s* (not yet certified).
pub(crate) fn solve(
    ns: &NullSpace,
    bounds: &TensionBounds,
    alpha: f64,
    dense: &mut ActiveSet,
    t: &mut [f64],
) -> Result<f64, Infeasibility> {
    let (end, s) = dense.optimally_safe(ns, bounds, alpha, t);
    match end {
        DenseEnd::Solved => {}
        DenseEnd::Infeasible(reason) => return Err(reason),
        DenseEnd::Failed(why) => {
            return Err(Infeasibility::SolverFailure {
                detail: format!("optimally-safe, dense active set: {why}"),
            });
        }
    }
    let scale = bounds
        .min()
        .iter()
        .chain(bounds.max().iter().filter(|h| h.is_finite()))
        .fold(1f64, |m, b| m.max(b.abs()));
    if s < -BOUND_TOLERANCE * scale {
        return Err(Infeasibility::NoFeasibleTension);
    }
    Ok(s)
}
