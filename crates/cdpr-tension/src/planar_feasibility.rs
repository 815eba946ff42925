//! # Feasibility of the redundancy-2 polygon
//!
//! A *complete* tension distribution method (l1, l1-max, l2, l2-max, linf, the barycentre: each
//! finds tensions if and only if the feasible set is non-empty) answers "is this pose
//! wrench-feasible?" with the verdict of a two-dimensional feasibility problem: is the polygon
//! {λ : t_min ≤ t0 + N λ ≤ t_max} (see [`crate::FeasiblePolygon`]) non-empty? The optimum of
//! the method is not needed for that verdict, only a certified feasible point or a proof that
//! there is none.
//!
//! [`decide`] answers it by Seidel's incremental algorithm for linear programs in the plane
//! (Seidel 1991), deterministic order, on the 2n half-planes s·a_i·λ ≥ β (a_i = row i of N;
//! lower bounds first), from the minimum-norm tensions λ = −Nᵀt0 ≈ 0: the current point x
//! satisfies the half-planes seen so far; when the next one, h_k, is violated, x moves to its
//! boundary line, onto the interval that h_1 … h_{k−1} leave there (a one-dimensional LP; the
//! point of the interval nearest x). An empty interval proves {h_1 … h_k} empty: the segment
//! from x (in h_1 … h_{k−1}, outside h_k) to any point of h_1 … h_k would cross that line
//! inside h_1 … h_{k−1}. No objective is needed for the verdict.
//!
//! Tightened and relaxed bounds keep the verdicts those of the polygon clipping:
//!
//! 1. the run is on the bounds *tightened* by a margin δ_i = 10⁻⁷ · max(|t_min,i|, |t_max,i|,
//!    |t0_i|, 1): a point found there is checked directly (every t_i at least δ_i/2 inside its
//!    bounds) and then certified by [`crate::certify`] like every answer — "clearly feasible";
//! 2. when an interval comes out empty, the same line and the same x are tried with the bounds
//!    *relaxed* by δ_i (x is inside the relaxed h_1 … h_{k−1}; if it violates the relaxed h_k
//!    the argument above holds for the relaxed half-planes), else a second run on the relaxed
//!    bounds: an empty interval proves the polygon empty even with every bound widened by
//!    δ_i, a thousand times the clipping tolerance (10⁻¹⁰ relative, `feasible_polygon`), so
//!    the clipping finds it empty too — "clearly infeasible".
//!
//! Anything else (a polygon narrower than about δ, a failed check or certificate, a fixed
//! cable t_min = t_max, an infinite t_max, a null-space row ≈ 0, more than 16 cables) is
//! [`Decision::Undecided`], and the method's own solve decides as before. Issue 17 (8-cable
//! IPAnema 1 grid, 15 625 poses, l2 under a 10 kg load, 30 % of the poses infeasible): every
//! pose is decided here; the verdict after the null space costs about 2 950 instructions per
//! pose against 5 100 before (planar active set and certificate, then the polygon clipping for
//! each infeasible pose).
//!
//! ## References
//! - Seidel (1991), *Small-dimensional linear programming and convex hulls made easy*,
//!   Discrete & Computational Geometry 6, pp. 423–434.
//! - de Berg, Cheong, van Kreveld & Overmars (2008), *Computational Geometry*, 3rd ed., §4.3–4.4.

use crate::TensionBounds;
use crate::feasible_polygon::P2;
use crate::null_space::NullSpace;

/// Margin δ_i relative to max(|t_min,i|, |t_max,i|, |t0_i|, 1) (module docs).
const MARGIN: f64 = 1e-7;

/// Cables up to which the decision runs (fixed arrays).
const MAX_CABLES: usize = 16;

/// Verdict of [`decide`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Decision {
    /// λ with every tension at least δ_i/2 inside its bounds (still to be certified).
    Feasible(P2),
    /// The polygon is empty even with every bound relaxed by δ_i.
    Infeasible,
    /// Near the boundary or outside the assumptions: the method's own solve decides.
    Undecided,
}

/// Half-plane n·λ ≥ β with its margin δ (tension units), as n·λ ≥ β + δ (tightened) and
/// n·λ ≥ β − δ (relaxed).
#[derive(Debug, Clone, Copy)]
struct HalfPlane {
    n: P2,
    tight: f64,
    relaxed: f64,
}

impl HalfPlane {
    /// β ± δ.
    #[inline(always)]
    fn beta<const TIGHT: bool>(&self) -> f64 {
        if TIGHT { self.tight } else { self.relaxed }
    }
}

#[inline(always)]
fn dot(a: P2, b: P2) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// Whether the polygon of `ns` under `bounds` (redundancy 2) is clearly non-empty, clearly
/// empty, or undecided (module docs). No allocation.
pub(crate) fn decide(ns: &NullSpace, bounds: &TensionBounds) -> Decision {
    let n = ns.n;
    debug_assert_eq!(ns.r(), 2);
    if n > MAX_CABLES {
        return Decision::Undecided;
    }
    let (lo, hi) = (bounds.min().as_slice(), bounds.max().as_slice());
    let empty = HalfPlane {
        n: [0.0; 2],
        tight: 0.0,
        relaxed: 0.0,
    };
    let mut h = [empty; 2 * MAX_CABLES];
    for i in 0..n {
        let (a, t0) = (ns.row2(i), ns.t0[i]);
        // Bounds are finite or +∞ and t_min ≤ t_max (`TensionBounds`).
        if lo[i] >= hi[i] || !hi[i].is_finite() || a[0].abs() + a[1].abs() < 1e-12 {
            return Decision::Undecided;
        }
        let delta = MARGIN * lo[i].abs().max(hi[i].abs()).max(t0.abs()).max(1.0);
        let (b_lo, b_hi) = (lo[i] - t0, t0 - hi[i]);
        h[i] = HalfPlane {
            n: a,
            tight: b_lo + delta,
            relaxed: b_lo - delta,
        };
        h[n + i] = HalfPlane {
            n: [-a[0], -a[1]],
            tight: b_hi + delta,
            relaxed: b_hi - delta,
        };
    }
    let h = &h[..2 * n];
    // The minimum-norm tensions (λ = −g ≈ 0) as the start.
    let start = [-ns.g[0], -ns.g[1]];
    let (k, x) = match seidel::<true>(h, start) {
        Ok(x) => {
            if (0..n).all(|i| {
                let t = ns.tension2(i, x);
                // δ_i/2 = (tightened − relaxed)/4.
                let m = 0.25 * (h[i].tight - h[i].relaxed);
                t >= lo[i] + m && t <= hi[i] - m
            }) {
                return Decision::Feasible(x);
            }
            return Decision::Undecided;
        }
        Err(fail) => fail,
    };
    // x lies in the tightened h_1 … h_{k−1}, inside the relaxed ones: if it violates the relaxed
    // h_k too, an empty relaxed interval on that line proves the relaxed polygon empty.
    if dot(h[k].n, x) < h[k].relaxed && interval::<false>(h, k, x).is_none() {
        return Decision::Infeasible;
    }
    if seidel::<false>(h, start).is_err() {
        return Decision::Infeasible;
    }
    Decision::Undecided
}

/// Seidel's incremental algorithm (module docs) on the tightened (`TIGHT`) or relaxed
/// half-planes from `x` (any point):
/// a point of every half-plane (up to rounding), or `Err((k, x))` when the interval on the line
/// of half-plane k came out empty, x being the point (in h_1 … h_{k−1}, outside h_k) that left it.
#[inline(always)]
fn seidel<const TIGHT: bool>(h: &[HalfPlane], mut x: P2) -> Result<P2, (usize, P2)> {
    for (k, hk) in h.iter().enumerate() {
        if dot(hk.n, x) >= hk.beta::<TIGHT>() {
            continue;
        }
        // The point of the line n_k·λ = β_k nearest x, p = x + (β_k − n_k·x)/|n_k|² n_k, and
        // the direction u along the line: λ = p + s u, moved as little as the interval allows.
        match interval::<TIGHT>(h, k, x) {
            Some((p, u, s_lo, s_hi)) => {
                let s = 0.0f64.max(s_lo).min(s_hi);
                x = [p[0] + s * u[0], p[1] + s * u[1]];
            }
            None => return Err((k, x)),
        }
    }
    Ok(x)
}

/// The line of half-plane k through the point p nearest x, its direction u, and the interval
/// [s_lo, s_hi] of p + s u inside h_1 … h_{k−1} (tightened or relaxed); `None` when
/// empty.
#[inline(always)]
fn interval<const TIGHT: bool>(h: &[HalfPlane], k: usize, x: P2) -> Option<(P2, P2, f64, f64)> {
    let hk = h[k];
    let nk = hk.n;
    let step = (hk.beta::<TIGHT>() - dot(nk, x)) / dot(nk, nk);
    let p = [x[0] + step * nk[0], x[1] + step * nk[1]];
    let u = [-nk[1], nk[0]];
    let (mut s_lo, mut s_hi) = (f64::NEG_INFINITY, f64::INFINITY);
    for hj in &h[..k] {
        let den = dot(hj.n, u);
        let num = hj.beta::<TIGHT>() - dot(hj.n, p);
        if den > 0.0 {
            s_lo = s_lo.max(num / den);
        } else if den < 0.0 {
            s_hi = s_hi.min(num / den);
        } else if num > 0.0 {
            return None;
        }
    }
    // `s_lo <= s_hi` is false for NaN too.
    (s_lo <= s_hi).then_some((p, u, s_lo, s_hi))
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};

    fn ns_of(w: &DMatrix<f64>, we: &DVector<f64>) -> NullSpace {
        let mut ns = NullSpace::default();
        ns.compute(w, we).unwrap();
        ns
    }

    /// One DOF, three cables pulling +1, +1, −1: t1 + t2 − t3 = −w.
    fn line_problem(w_ext: f64) -> (DMatrix<f64>, DVector<f64>) {
        (
            DMatrix::from_row_slice(1, 3, &[1.0, 1.0, -1.0]),
            DVector::from_vec(vec![w_ext]),
        )
    }

    #[test]
    fn hand_derived_verdicts() {
        // t_i ∈ [1, 10]: t1 + t2 − t3 ranges over [2 − 10, 20 − 1] = [−8, 19].
        let b = TensionBounds::uniform(3, 1.0, 10.0).unwrap();
        for (w_ext, expected) in [
            (-2.0, true),
            (7.0, true),
            (8.0 + 1e-3, false),
            (-19.0 + 1e-3, true),
            (-20.0, false),
        ] {
            let (w, we) = line_problem(w_ext);
            let ns = ns_of(&w, &we);
            match decide(&ns, &b) {
                Decision::Feasible(l) => {
                    assert!(expected, "w_ext {w_ext}");
                    let t: Vec<f64> = (0..3).map(|i| ns.tension2(i, l)).collect();
                    assert!((t[0] + t[1] - t[2] + w_ext).abs() < 1e-9, "{t:?}");
                    assert!(t.iter().all(|&v| (1.0..=10.0).contains(&v)), "{t:?}");
                }
                Decision::Infeasible => assert!(!expected, "w_ext {w_ext}"),
                Decision::Undecided => panic!("undecided at w_ext {w_ext}"),
            }
        }
        // Exactly on the boundary (the polygon is the point t = (10, 10, 1)): undecided.
        let (w, we) = line_problem(-19.0);
        assert_eq!(decide(&ns_of(&w, &we), &b), Decision::Undecided);
    }

    #[test]
    fn fixed_and_unbounded_cables_are_undecided() {
        let (w, we) = line_problem(-2.0);
        let ns = ns_of(&w, &we);
        let fixed = TensionBounds::new(vec![1.0, 1.0, 1.0], vec![10.0, 1.0, 10.0]).unwrap();
        assert_eq!(decide(&ns, &fixed), Decision::Undecided);
        let open =
            TensionBounds::new(vec![1.0, 1.0, 1.0], vec![10.0, f64::INFINITY, 10.0]).unwrap();
        assert_eq!(decide(&ns, &open), Decision::Undecided);
    }
}
