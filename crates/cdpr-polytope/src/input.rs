//! Input validation shared by every method.

use crate::PolytopeError;
use cdpr_tension::TensionBounds;
use nalgebra::DMatrix;

/// Largest supported wrench-space dimension (spatial robots).
pub(crate) const MAX_DOF: usize = 6;

/// Checks W (DOF × n, finite, 1 ≤ DOF ≤ 6) against the bounds; returns the scale max|W_ij|·max|t|
/// used for wrench tolerances, and max|W_ij|.
pub(crate) fn check(w: &DMatrix<f64>, bounds: &TensionBounds) -> Result<(f64, f64), PolytopeError> {
    let (dof, n) = w.shape();
    if dof == 0 || dof > MAX_DOF {
        return Err(PolytopeError::UnsupportedDof { dof });
    }
    if bounds.len() != n {
        return Err(PolytopeError::DimensionMismatch {
            what: "tension bounds vs columns of W",
            expected: n,
            found: bounds.len(),
        });
    }
    let mut wmax = 0.0f64;
    for (i, &x) in w.as_slice().iter().enumerate() {
        if !x.is_finite() {
            return Err(PolytopeError::NotFinite {
                what: "wrench matrix entry",
                index: i,
                value: x,
            });
        }
        wmax = wmax.max(x.abs());
    }
    let mut tmax = 0.0f64;
    for (&lo, &hi) in bounds.min().iter().zip(bounds.max().iter()) {
        tmax = tmax.max(lo.abs());
        if hi.is_finite() {
            tmax = tmax.max(hi.abs());
        }
    }
    Ok((wmax * tmax.max(1.0), wmax))
}

/// Numerical rank of W (singular values above 1e-10 σ_max): for error reports only.
pub(crate) fn numerical_rank(w: &DMatrix<f64>) -> usize {
    let s = w.singular_values();
    let smax = s.iter().copied().fold(0.0, f64::max);
    s.iter().filter(|&&x| x > 1e-10 * smax).count()
}

/// Checks a wrench-like vector of length `dof`.
pub(crate) fn check_vector(what: &'static str, v: &[f64], dof: usize) -> Result<(), PolytopeError> {
    if v.len() != dof {
        return Err(PolytopeError::DimensionMismatch {
            what,
            expected: dof,
            found: v.len(),
        });
    }
    if let Some((i, &x)) = v.iter().enumerate().find(|(_, x)| !x.is_finite()) {
        return Err(PolytopeError::NotFinite {
            what,
            index: i,
            value: x,
        });
    }
    Ok(())
}
