//! # Constrained ℓ₁ and ℓ∞ approaches (linear programs)
//!
//! - **l1** (thesis eq. (6.19)): minimise ‖t‖₁ = Σ t_i subject to W t + w_ext = 0,
//!   t_min ≤ t ≤ t_max (Σ t_i = ‖t‖₁ because the thesis' bounds satisfy 0 ≤ t_min; with negative
//!   t_min the objective is still Σ t_i).
//! - **l1-max**: maximise Σ t_i (the thesis' "maximum allowable cable tensions").
//! - **linf**: minimise max_i t_i (CASPR / WireX parity).
//!
//! For redundancy r ≤ 2 we solve l1 and l1-max exactly on the feasible interval / polygon in
//! λ-space: Σ t_i = Σ t0_i + (Nᵀ 1)·λ is linear, so its optimum is at a vertex (at r = 2 found
//! first by simplex steps from the l2 optimum without building the polygon, module
//! `planar_active_set`; the polygon decides what that path hands back). linf at r ≤ 1:
//! max_i t_i is convex and piecewise linear, minimised by bisection on the level s (clip the
//! interval with t_i ≤ s until the bracket is below 10⁻¹⁴ relative). For r ≥ 3, and for linf
//! already at r = 2 (exact, and about 3.5 times cheaper than the bisection on the polygon: issue
//! 17), the dense active-set LP (phase 1, then the simplex method in inequality form with
//! Bland's rule) solves it in λ-space without allocating (module `active_set`).
//!
//! ## References
//! - The thesis chapter on planar tendon-driven manipulators (ch. 6), §6.3.3, eq. (6.19).
//! - Bland, R. G. (1977), *New finite pivoting rules for the simplex method*.

use crate::feasible_polygon::{P2, Region};
use crate::null_space::NullSpace;
use crate::{Infeasibility, TensionBounds};

/// A linear objective on the region.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Linear {
    /// min Σ t.
    MinSum,
    /// max Σ t.
    MaxSum,
    /// min max t.
    MinMax,
}

/// Solves on a built, non-empty region (r ≤ 2), writing t.
pub(crate) fn solve_on_region(
    kind: Linear,
    ns: &NullSpace,
    region: &mut Region,
    bounds: &TensionBounds,
    method: &'static str,
    t: &mut [f64],
) -> Result<(), Infeasibility> {
    let n = ns.n;
    let lambda = match kind {
        Linear::MinSum | Linear::MaxSum => {
            let mut c = [0.0; 2];
            for i in 0..n {
                let a = ns.row2(i);
                c[0] += a[0];
                c[1] += a[1];
            }
            let maximize = kind == Linear::MaxSum;
            if maximize && region.is_unbounded() {
                return Err(Infeasibility::Unbounded { method });
            }
            region.best_vertex(|l| c[0] * l[0] + c[1] * l[1], maximize)
        }
        Linear::MinMax => min_max(ns, region, bounds),
    };
    if region.on_artificial_box(lambda) {
        return Err(Infeasibility::Unbounded { method });
    }
    write_tensions(ns, lambda, t);
    Ok(())
}

/// t = t0 + N λ for r ≤ 2.
pub(crate) fn write_tensions(ns: &NullSpace, l: P2, t: &mut [f64]) {
    for (i, ti) in t.iter_mut().enumerate() {
        *ti = ns.tension2(i, l);
    }
}

fn max_tension(ns: &NullSpace, l: P2) -> f64 {
    (0..ns.n)
        .map(|i| ns.tension2(i, l))
        .fold(f64::NEG_INFINITY, f64::max)
}

/// min over the region of max_i t_i(λ), by bisection on the level s.
fn min_max(ns: &NullSpace, region: &mut Region, bounds: &TensionBounds) -> P2 {
    let mut best = region.best_vertex(|l| max_tension(ns, l), false);
    let mut s_hi = max_tension(ns, best);
    let mut s_lo = bounds
        .min()
        .iter()
        .fold(f64::NEG_INFINITY, |a, &b| a.max(b));
    region.save();
    for _ in 0..200 {
        if s_hi - s_lo <= 1e-14 * s_hi.abs().max(1.0) {
            break;
        }
        let s = 0.5 * (s_lo + s_hi);
        region.restore();
        let mut nonempty = true;
        for i in 0..ns.n {
            let a = ns.row2(i);
            // t_i ≤ s  ⇔  −a·λ ≥ t0_i − s
            if !region.clip([-a[0], -a[1]], ns.t0[i] - s, 0.0) {
                nonempty = false;
                break;
            }
        }
        if nonempty {
            let k = region.verts.len() as f64;
            let (sx, sy) = region
                .verts
                .iter()
                .fold((0.0, 0.0), |(a, b), v| (a + v[0], b + v[1]));
            let c = [sx / k, sy / k];
            if max_tension(ns, c) <= max_tension(ns, best) {
                best = c;
            }
            s_hi = s;
        } else {
            s_lo = s;
        }
    }
    region.restore();
    best
}
