//! Input validation shared by every method.

use crate::PolytopeError;
use cdpr_tension::TensionBounds;
use nalgebra::DMatrix;

/// Largest supported wrench-space dimension (spatial robots).
pub(crate) const MAX_DOF: usize = 6;

/// Checks W (DOF × n, finite, 1 ≤ DOF ≤ 6) against the bounds; returns the scale max|W_ij|·max|t|
/// used for wrench tolerances, and max|W_ij|.
pub(crate) fn check(w: &DMatrix<f64>, bounds: &TensionBounds) -> Result<(f64, f64), PolytopeError> {
    check_shape(w.nrows(), w.ncols(), bounds)?;
    let wmax = finite_amax(w.as_slice())?;
    let mut tmax = 0.0f64;
    for (&lo, &hi) in bounds.min().iter().zip(bounds.max().iter()) {
        tmax = tmax.max(lo.abs());
        if hi.is_finite() {
            tmax = tmax.max(hi.abs());
        }
    }
    // Clamped so that tolerances stay finite when |W|·|t| overflows.
    Ok(((wmax * tmax.max(1.0)).min(f64::MAX), wmax))
}

/// Checks the shape DOF × n of W against the supported DOF range and the bounds.
#[inline]
pub(crate) fn check_shape(
    dof: usize,
    n: usize,
    bounds: &TensionBounds,
) -> Result<(), PolytopeError> {
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
    Ok(())
}

/// Numerical rank of W for error reports: Gaussian elimination with complete pivoting on W
/// divided by its largest |entry|, pivots above 1e-10 counting. Terminates on any finite input
/// (unlike an iterative SVD, which offers no such guarantee on subnormal or extreme entries).
pub(crate) fn numerical_rank(w: &DMatrix<f64>) -> usize {
    let wmax = w.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if !(wmax > 0.0 && wmax.is_finite()) {
        return 0;
    }
    let mut a = w.map(|x| x / wmax);
    let (m, n) = a.shape();
    let mut rank = 0;
    for step in 0..m.min(n) {
        let (mut bi, mut bj, mut bv) = (step, step, 0.0f64);
        for j in step..n {
            for i in step..m {
                let v = a[(i, j)].abs();
                if v > bv {
                    (bi, bj, bv) = (i, j, v);
                }
            }
        }
        if bv <= 1e-10 {
            break;
        }
        a.swap_rows(step, bi);
        a.swap_columns(step, bj);
        let p = a[(step, step)];
        for i in step + 1..m {
            let f = a[(i, step)] / p;
            for j in step..n {
                let x = a[(step, j)];
                a[(i, j)] -= f * x;
            }
        }
        rank += 1;
    }
    rank
}

/// Scans W once: `Err` on the first non-finite entry, else max |W_ij|.
#[inline]
pub(crate) fn finite_amax(w: &[f64]) -> Result<f64, PolytopeError> {
    let mut wmax = 0.0f64;
    let mut bad = false;
    for &x in w {
        bad |= !x.is_finite();
        wmax = wmax.max(x.abs());
    }
    if bad {
        for (i, &x) in w.iter().enumerate() {
            if !x.is_finite() {
                return Err(PolytopeError::NotFinite {
                    what: "wrench matrix entry",
                    index: i,
                    value: x,
                });
            }
        }
    }
    Ok(wmax)
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
