//! # Certificate of a tension distribution
//!
//! The one check every method passes before it may answer `Feasible`: the equilibrium residual
//! ‖W t + w_ext‖∞ ≤ 10⁻⁹ · scale with scale = max(1, ‖w_ext‖∞, ‖W‖∞ · max|t_i|) (‖W‖∞: largest
//! absolute row sum, so ‖W t‖∞ ≤ ‖W‖∞ max|t_i|), and every bound
//! t_min,i − 10⁻⁹ max(1, |t_min,i|) ≤ t_i ≤ t_max,i + 10⁻⁹ max(1, |t_max,i|).
//!
//! ## References
//! - Seed 000 eqs. (6.11), (6.21); seed 002 eq. (1).

use crate::TensionBounds;
use nalgebra::{DMatrix, DVector};

/// Relative tolerance of the equilibrium residual.
pub const EQUILIBRIUM_TOLERANCE: f64 = 1e-9;
/// Relative tolerance of the tension bounds.
pub const BOUND_TOLERANCE: f64 = 1e-9;

/// What [`certify`] measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Certificate {
    /// ‖W t + w_ext‖∞.
    pub residual: f64,
    /// max(1, ‖w_ext‖∞, ‖W‖∞ · max|t_i|).
    pub scale: f64,
    /// Largest bound violation, relative to max(1, |bound|) (≤ 0 when all bounds hold).
    pub bound_violation: f64,
}

impl Certificate {
    /// Whether equilibrium and bounds both hold within the tolerances.
    pub fn is_valid(&self) -> bool {
        self.residual <= EQUILIBRIUM_TOLERANCE * self.scale
            && self.bound_violation <= BOUND_TOLERANCE
    }
}

/// Relative violation of cable i's bounds by tension `t` (≤ 0 inside; NaN counts as +∞).
#[inline]
pub(crate) fn bound_violation(lo: f64, hi: f64, t: f64) -> f64 {
    if t.is_nan() {
        return f64::INFINITY;
    }
    let below = (lo - t) / lo.abs().max(1.0);
    let above = if hi.is_finite() {
        (t - hi) / hi.abs().max(1.0)
    } else {
        f64::NEG_INFINITY
    };
    below.max(above)
}

/// Measures equilibrium and bounds of `t` (no allocation). Shapes must agree.
///
/// ```
/// use cdpr_tension::{certify, TensionBounds};
/// use nalgebra::{DMatrix, DVector};
/// let w = DMatrix::from_row_slice(1, 2, &[1.0, -1.0]);
/// let we = DVector::from_vec(vec![-1.0]);
/// let b = TensionBounds::uniform(2, 0.0, 10.0).unwrap();
/// assert!(certify(&w, &we, &b, &[4.0, 3.0]).is_valid()); // t1 − t2 − 1 = 0
/// assert!(!certify(&w, &we, &b, &[3.0, 3.0]).is_valid()); // not in equilibrium
/// assert!(!certify(&w, &we, &b, &[12.0, 11.0]).is_valid()); // above t_max
/// ```
pub fn certify(
    w: &DMatrix<f64>,
    w_ext: &DVector<f64>,
    bounds: &TensionBounds,
    t: &[f64],
) -> Certificate {
    let (m, n) = w.shape();
    debug_assert_eq!(n, t.len());
    let mut residual: f64 = 0.0;
    let mut w_norm: f64 = 0.0;
    for k in 0..m {
        let mut s = w_ext[k];
        let mut row = 0.0;
        for (i, ti) in t.iter().enumerate() {
            let v = w[(k, i)];
            s += v * ti;
            row += v.abs();
        }
        residual = residual.max(s.abs());
        if s.is_nan() {
            residual = f64::INFINITY;
        }
        w_norm = w_norm.max(row);
    }
    let t_max = t.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let we_max = w_ext.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let scale = 1f64.max(we_max).max(w_norm * t_max);
    let mut bound: f64 = f64::NEG_INFINITY;
    for (i, &ti) in t.iter().enumerate() {
        bound = bound.max(bound_violation(bounds.min()[i], bounds.max()[i], ti));
    }
    Certificate {
        residual,
        scale,
        bound_violation: bound,
    }
}

/// Moves tensions that violate a bound by at most the tolerance onto the bound (so returned
/// tensions lie inside [t_min, t_max] exactly whenever they are certified).
pub(crate) fn snap_to_bounds(bounds: &TensionBounds, t: &mut [f64]) {
    for (i, ti) in t.iter_mut().enumerate() {
        let (lo, hi) = (bounds.min()[i], bounds.max()[i]);
        if *ti < lo && bound_violation(lo, hi, *ti) <= BOUND_TOLERANCE {
            *ti = lo;
        } else if *ti > hi && bound_violation(lo, hi, *ti) <= BOUND_TOLERANCE {
            *ti = hi;
        }
    }
}

/// Polishes an approximate solution from an iterative solver: snaps near-active tensions onto
/// their bounds and corrects the equilibrium residual with a minimum-norm step on the cables
/// strictly inside their bounds (two passes). Allocates; used on the interior-point path only.
pub(crate) fn polish(
    w: &DMatrix<f64>,
    w_ext: &DVector<f64>,
    bounds: &TensionBounds,
    t: &mut [f64],
) {
    let n = t.len();
    for _ in 0..2 {
        for (i, ti) in t.iter_mut().enumerate() {
            *ti = ti.clamp(bounds.min()[i], bounds.max()[i]);
        }
        let tv = DVector::from_column_slice(t);
        let res = w * &tv + w_ext;
        if res.amax() == 0.0 {
            return;
        }
        // Free cables: not (numerically) at a bound.
        let free: Vec<usize> = (0..n)
            .filter(|&i| {
                let (lo, hi) = (bounds.min()[i], bounds.max()[i]);
                let tol = 1e-9 * (hi - lo).abs().max(1.0);
                t[i] > lo + tol && (!hi.is_finite() || t[i] < hi - tol)
            })
            .collect();
        if free.is_empty() {
            return;
        }
        let wf = DMatrix::from_fn(w.nrows(), free.len(), |r, c| w[(r, free[c])]);
        let Some(pinv) = wf.pseudo_inverse(1e-12).ok() else {
            return;
        };
        let step = pinv * res;
        for (c, &i) in free.iter().enumerate() {
            t[i] -= step[c];
        }
    }
}
