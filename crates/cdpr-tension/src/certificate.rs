//! # Certificate of a tension distribution
//!
//! The one check every method passes before it may answer `Feasible`: the equilibrium residual
//! ‖W t + w_ext‖∞ ≤ 10⁻⁹ · scale with scale = max(1, ‖w_ext‖∞, ‖W‖∞ · max|t_i|) (‖W‖∞: largest
//! absolute row sum, so ‖W t‖∞ ≤ ‖W‖∞ max|t_i|), and every bound
//! t_min,i − 10⁻⁹ max(1, |t_min,i|) ≤ t_i ≤ t_max,i + 10⁻⁹ max(1, |t_max,i|).
//!
//! ## References
//! - Thesis eqs. (6.11), (6.21); Picard, Caro, Plestan & Claveau 2020, eq. (1).

use crate::TensionBounds;
use nalgebra::{DMatrix, DVector};

/// Relative tolerance of the equilibrium residual.
pub const EQUILIBRIUM_TOLERANCE: f64 = 1e-9;
/// Relative tolerance of the tension bounds.
pub const BOUND_TOLERANCE: f64 = 1e-9;

/// Tolerance (relative to max(1, |bound|)) with which the feasible-set constructions (the
/// interval of Algorithm 6.1, the feasible polygon) keep a point on a bound: a tenth of
/// [`BOUND_TOLERANCE`], so a kept point passes the certificate after snapping.
pub(crate) const SET_TOLERANCE: f64 = 1e-10;

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
        in_equilibrium(self.residual, self.scale) && self.bound_violation <= BOUND_TOLERANCE
    }
}

/// The equilibrium test. The residual must be finite: an infinite tension (t_max = ∞) or an
/// overflowing W t makes both the residual and the scale infinite, and ∞ ≤ 10⁻⁹ · ∞ would
/// otherwise hold (a fuzz finding: closed-form answered t = (…, ∞, …) as feasible).
#[inline(always)]
fn in_equilibrium(residual: f64, scale: f64) -> bool {
    residual.is_finite() && residual <= EQUILIBRIUM_TOLERANCE * scale
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
#[inline]
pub fn certify(
    w: &DMatrix<f64>,
    w_ext: &DVector<f64>,
    bounds: &TensionBounds,
    t: &[f64],
) -> Certificate {
    debug_assert_eq!(w.ncols(), t.len());
    let mut bound: f64 = f64::NEG_INFINITY;
    for ((&ti, &lo), &hi) in t.iter().zip(bounds.min().iter()).zip(bounds.max().iter()) {
        bound = bound.max(bound_violation(lo, hi, ti));
    }
    let (residual, scale) = equilibrium_any(w, w_ext, t);
    Certificate {
        residual,
        scale,
        bound_violation: bound,
    }
}

/// (‖W t + w_ext‖∞, scale) for a DOF × n matrix `ws` (column-major), DOF = M: one fused pass
/// over the columns. Sums in the same order as the general loop (w_ext_k + Σ_i W_ki t_i).
#[inline(always)]
fn equilibrium<const M: usize>(ws: &[f64], we: &[f64], t: &[f64]) -> (f64, f64) {
    let mut res = [0.0f64; M];
    let mut rows = [0.0f64; M];
    res.copy_from_slice(&we[..M]);
    let mut t_max: f64 = 0.0;
    for (col, &ti) in ws.chunks_exact(M).zip(t) {
        for k in 0..M {
            res[k] += col[k] * ti;
            rows[k] += col[k].abs();
        }
        t_max = t_max.max(ti.abs());
    }
    finish(&res, &rows, we, t_max)
}

/// The equilibrium test `in_equilibrium(residual, scale)` of [`equilibrium`] and the residual,
/// residual first: it is tested against max(1, ‖w_ext‖∞), a lower bound of the scale (the
/// test is monotone in the scale), and only when that fails does a second pass over W
/// compute ‖W‖∞ · max|t_i|. The same residual (the same sums in the same order) and the same
/// verdict as the one-pass test, without the row norms in the usual case.
#[inline(always)]
fn equilibrium_test<const M: usize>(ws: &[f64], we: &[f64], t: &[f64]) -> (bool, f64) {
    let mut res = [0.0f64; M];
    res.copy_from_slice(&we[..M]);
    for (col, &ti) in ws.chunks_exact(M).zip(t) {
        for k in 0..M {
            res[k] += col[k] * ti;
        }
    }
    let (mut residual, mut we_max, mut nan) = (0.0f64, 0.0f64, false);
    for (&r, &e) in res.iter().zip(we) {
        residual = residual.max(r.abs());
        nan |= r.is_nan();
        we_max = we_max.max(e.abs());
    }
    if nan {
        residual = f64::INFINITY;
    }
    if in_equilibrium(residual, 1f64.max(we_max)) {
        return (true, residual);
    }
    full_scale_test::<M>(ws, we, t, residual)
}

/// The test against the full scale (see [`equilibrium_test`]).
#[cold]
#[inline(never)]
fn full_scale_test<const M: usize>(
    ws: &[f64],
    we: &[f64],
    t: &[f64],
    residual: f64,
) -> (bool, f64) {
    let (r, scale) = equilibrium::<M>(ws, we, t);
    debug_assert!(r.to_bits() == residual.to_bits());
    (in_equilibrium(residual, scale), residual)
}

/// [`equilibrium_test`] for DOF 6 (spatial robots), built for AVX2 when the CPU has it
/// (`is_x86_feature_detected!` caches its answer).
#[inline(always)]
fn equilibrium_test_6(ws: &[f64], we: &[f64], t: &[f64]) -> (bool, f64) {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU reports AVX2.
        return unsafe { equilibrium_test_6_avx2(ws, we, t) };
    }
    equilibrium_test::<6>(ws, we, t)
}

/// [`equilibrium_test`] for DOF 6 compiled for AVX2: the same source without fused
/// multiply–adds (Rust never contracts `a * b + c`), so the same bits as the portable build.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn equilibrium_test_6_avx2(ws: &[f64], we: &[f64], t: &[f64]) -> (bool, f64) {
    equilibrium_test::<6>(ws, we, t)
}

/// [`equilibrium_test`] by DOF (the one-pass test beyond 6).
#[inline(always)]
fn equilibrium_test_any(w: &DMatrix<f64>, w_ext: &DVector<f64>, t: &[f64]) -> (bool, f64) {
    let (ws, we) = (w.as_slice(), w_ext.as_slice());
    match w.nrows() {
        1 => equilibrium_test::<1>(ws, we, t),
        2 => equilibrium_test::<2>(ws, we, t),
        3 => equilibrium_test::<3>(ws, we, t),
        4 => equilibrium_test::<4>(ws, we, t),
        5 => equilibrium_test::<5>(ws, we, t),
        6 => equilibrium_test_6(ws, we, t),
        _ => {
            let (residual, scale) = equilibrium_dyn(w, w_ext, t);
            (in_equilibrium(residual, scale), residual)
        }
    }
}

#[inline(always)]
fn finish(res: &[f64], rows: &[f64], we: &[f64], t_max: f64) -> (f64, f64) {
    let (mut residual, mut w_norm, mut we_max) = (0.0f64, 0.0f64, 0.0f64);
    let mut nan = false;
    for ((&r, &row), &e) in res.iter().zip(rows).zip(we) {
        residual = residual.max(r.abs());
        nan |= r.is_nan();
        w_norm = w_norm.max(row);
        we_max = we_max.max(e.abs());
    }
    if nan {
        residual = f64::INFINITY;
    }
    (residual, 1f64.max(we_max).max(w_norm * t_max))
}

/// The same for any DOF, row by row (no allocation).
fn equilibrium_dyn(w: &DMatrix<f64>, w_ext: &DVector<f64>, t: &[f64]) -> (f64, f64) {
    let (mut residual, mut w_norm, mut nan) = (0.0f64, 0.0f64, false);
    for k in 0..w.nrows() {
        let mut s = w_ext[k];
        let mut row = 0.0;
        for (i, ti) in t.iter().enumerate() {
            let v = w[(k, i)];
            s += v * ti;
            row += v.abs();
        }
        residual = residual.max(s.abs());
        nan |= s.is_nan();
        w_norm = w_norm.max(row);
    }
    if nan {
        residual = f64::INFINITY;
    }
    let t_max = t.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let we_max = w_ext.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    (residual, 1f64.max(we_max).max(w_norm * t_max))
}

/// ‖W t + w_ext‖∞ and the scale, by DOF.
#[inline(always)]
fn equilibrium_any(w: &DMatrix<f64>, w_ext: &DVector<f64>, t: &[f64]) -> (f64, f64) {
    let (ws, we) = (w.as_slice(), w_ext.as_slice());
    match w.nrows() {
        1 => equilibrium::<1>(ws, we, t),
        2 => equilibrium::<2>(ws, we, t),
        3 => equilibrium::<3>(ws, we, t),
        4 => equilibrium::<4>(ws, we, t),
        5 => equilibrium::<5>(ws, we, t),
        6 => equilibrium::<6>(ws, we, t),
        _ => equilibrium_dyn(w, w_ext, t),
    }
}

/// Snaps `t` onto its bounds where it violates them by at most the tolerance (as
/// `snap_to_bounds`, a test helper) and certifies it ([`certify`]) in one pass: `Ok(residual)` exactly when
/// `certify` of the snapped tensions is valid. After snapping, a tension is either inside
/// [t_min, t_max] or violates a bound by more than the tolerance, so the bound test needs no
/// division; the full [`certify`] runs only to describe a failure.
#[inline]
pub(crate) fn snap_and_certify(
    w: &DMatrix<f64>,
    w_ext: &DVector<f64>,
    bounds: &TensionBounds,
    t: &mut [f64],
) -> Result<f64, Certificate> {
    let inside = snap_all(bounds, t);
    let (balanced, residual) = equilibrium_test_any(w, w_ext, t);
    if inside && balanced {
        Ok(residual)
    } else {
        Err(certify_cold(w, w_ext, bounds, t))
    }
}

/// The verdict of [`snap_and_certify_fixed`] without the failure's description, for W given
/// as its column-major values (M rows): the same snapping, the same sums in the same order.
#[inline(always)]
pub(crate) fn snap_and_certify_fixed_ok<const M: usize>(
    ws: &[f64],
    we: &[f64],
    bounds: &TensionBounds,
    t: &mut [f64],
) -> bool {
    let inside = snap_all(bounds, t);
    inside && equilibrium_test::<M>(ws, we, t).0
}

/// [`snap_and_certify`] for a DOF = M known at compile time (W is M × t.len()): the same
/// snapping, the same sums in the same order, the same verdict.
#[inline(always)]
pub(crate) fn snap_and_certify_fixed<const M: usize>(
    w: &DMatrix<f64>,
    w_ext: &DVector<f64>,
    bounds: &TensionBounds,
    t: &mut [f64],
) -> Result<f64, Certificate> {
    debug_assert_eq!(w.nrows(), M);
    let inside = snap_all(bounds, t);
    let (balanced, residual) = equilibrium_test::<M>(w.as_slice(), w_ext.as_slice(), t);
    if inside && balanced {
        Ok(residual)
    } else {
        Err(certify_cold(w, w_ext, bounds, t))
    }
}

/// [`certify`] off the hot path (it only describes a failure).
#[cold]
#[inline(never)]
fn certify_cold(
    w: &DMatrix<f64>,
    w_ext: &DVector<f64>,
    bounds: &TensionBounds,
    t: &[f64],
) -> Certificate {
    certify(w, w_ext, bounds, t)
}

/// Snaps every tension within the tolerance of a bound onto it; false if one stays outside.
#[inline(always)]
fn snap_all(bounds: &TensionBounds, t: &mut [f64]) -> bool {
    let (lo, hi) = (bounds.min().as_slice(), bounds.max().as_slice());
    let mut inside = true;
    for ((ti, &l), &h) in t.iter_mut().zip(lo).zip(hi) {
        if !(*ti >= l && *ti <= h) {
            inside &= snap_one(l, h, ti);
        }
    }
    inside
}

/// Snaps one tension outside [lo, hi] (or NaN) onto the bound it violates by at most the
/// tolerance; false if it stays outside.
#[cold]
fn snap_one(lo: f64, hi: f64, t: &mut f64) -> bool {
    if bound_violation(lo, hi, *t) > BOUND_TOLERANCE {
        return false;
    }
    *t = if *t < lo { lo } else { hi };
    true
}

/// Moves tensions that violate a bound by at most the tolerance onto the bound (so returned
/// tensions lie inside [t_min, t_max] exactly whenever they are certified).
#[cfg(test)]
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
/// strictly inside their bounds. A step that pushes a free cable across a bound is followed by
/// another pass (the cable is snapped and becomes active), up to 8 passes; the result is clamped
/// to the bounds. Allocates; used on the interior-point path only.
pub(crate) fn polish(
    w: &DMatrix<f64>,
    w_ext: &DVector<f64>,
    bounds: &TensionBounds,
    t: &mut [f64],
) {
    let n = t.len();
    let (lo, hi) = (bounds.min(), bounds.max());
    let inside = |i: usize, v: f64| v >= lo[i] && v <= hi[i];
    let mut clean_steps = 0;
    for _ in 0..8 {
        for (i, ti) in t.iter_mut().enumerate() {
            *ti = ti.clamp(lo[i], hi[i]);
        }
        let tv = DVector::from_column_slice(t);
        let res = w * &tv + w_ext;
        if res.amax() == 0.0 {
            return;
        }
        // Free cables: not (numerically) at a bound. Tolerances are relative to each bound
        // (not to t_max − t_min, which is ∞ for an infinite t_max).
        let free: Vec<usize> = (0..n)
            .filter(|&i| {
                t[i] > lo[i] + 1e-9 * lo[i].abs().max(1.0)
                    && (!hi[i].is_finite() || t[i] < hi[i] - 1e-9 * hi[i].abs().max(1.0))
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
        if free.iter().all(|&i| inside(i, t[i])) {
            clean_steps += 1;
            if clean_steps == 2 {
                return;
            }
        }
    }
    for (i, ti) in t.iter_mut().enumerate() {
        *ti = ti.clamp(lo[i], hi[i]);
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// Uniform numbers in [0, 1) from a xorshift generator (also for other modules' tests).
    pub(crate) fn uniform(mut state: u64) -> impl FnMut() -> f64 {
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// The fused snap-and-certify agrees with snap_to_bounds + certify, including at the
    /// tolerance margins, for NaN, and for every DOF (fixed and dynamic sizes).
    #[test]
    fn fused_check_agrees_with_snap_then_certify() {
        let mut rnd = uniform(0x2545_f491_4f6c_dd1d);
        let mut failures = 0;
        for case in 0..4000 {
            let m = [1, 2, 3, 4, 6, 7][case % 6];
            let n = m + case % 4;
            let w = DMatrix::from_fn(m, n, |_, _| 2.0 * rnd() - 1.0);
            let lo: Vec<f64> = (0..n).map(|_| 10.0 * rnd()).collect();
            let hi: Vec<f64> = lo
                .iter()
                .map(|l| {
                    if rnd() < 0.2 {
                        f64::INFINITY
                    } else {
                        l + 100.0 * rnd()
                    }
                })
                .collect();
            let bounds = TensionBounds::new(lo.clone(), hi.clone()).unwrap();
            let mut t: Vec<f64> = (0..n)
                .map(|i| {
                    let u = rnd();
                    let h = if hi[i].is_finite() {
                        hi[i]
                    } else {
                        lo[i] + 50.0
                    };
                    let s = lo[i].abs().max(1.0);
                    match case % 7 {
                        // Within, exactly at, and just beyond the bound tolerance.
                        0 => lo[i] - s * 1e-9 * u,
                        1 => lo[i] - s * 1e-9,
                        2 => lo[i] - s * 1.000001e-9,
                        3 => h + h.abs().max(1.0) * 1e-9 * u,
                        4 if u < 0.1 => f64::NAN,
                        _ => lo[i] + u * (h - lo[i]),
                    }
                })
                .collect();
            let t_true = DVector::from_column_slice(&t);
            // Equilibrium exact up to rounding, or off by a perturbation.
            let mut we = -(&w * &t_true);
            if case % 3 == 0 {
                we[0] += 1e-6 * rnd();
            }
            let mut t2 = t.clone();
            snap_to_bounds(&bounds, &mut t2);
            let reference = certify(&w, &we, &bounds, &t2);
            let fused = snap_and_certify(&w, &we, &bounds, &mut t);
            assert_eq!(
                t.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                t2.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
            );
            match fused {
                Ok(r) => {
                    assert!(reference.is_valid(), "case {case}: {reference:?}");
                    assert_eq!(r, reference.residual);
                }
                Err(c) => {
                    assert!(!reference.is_valid(), "case {case}: {reference:?}");
                    assert_eq!(c, reference);
                    failures += 1;
                }
            }
        }
        assert!(failures > 500 && failures < 3500, "{failures}");
    }

    /// A residual above 10⁻⁹ max(1, ‖w_ext‖∞) but within 10⁻⁹ ‖W‖∞ max|t_i| is certified (the
    /// second pass of the residual-first test), one beyond it is not, for fixed and dynamic DOF.
    #[test]
    fn residual_within_the_full_scale_is_certified() {
        for m in [1, 6, 7] {
            // Row k: 10³ t_1 − 10³ t_2 (+ 0 t_3); t = (1000, 1000, 0): ‖W‖∞ max|t| = 2·10⁶,
            // tolerance 2·10⁻³ N against 10⁻⁹ N from w_ext alone.
            let w = DMatrix::from_fn(m, 3, |_, c| [1e3, -1e3, 0.0][c]);
            let b = TensionBounds::uniform(3, 0.0, 2000.0).unwrap();
            for (offset, valid) in [(1e-4, true), (1.9e-3, true), (2.1e-3, false)] {
                let we = DVector::from_element(m, offset);
                let mut t = [1000.0, 1000.0, 0.0];
                let c = certify(&w, &we, &b, &t);
                assert_eq!(c.is_valid(), valid, "{m} {offset} {c:?}");
                match snap_and_certify(&w, &we, &b, &mut t) {
                    Ok(r) => assert!(valid && r == c.residual, "{m} {offset}"),
                    Err(e) => assert!(!valid && e == c, "{m} {offset}"),
                }
            }
        }
    }

    /// The AVX2 build of the DOF-6 equilibrium test gives the bits of the portable build.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn avx2_equilibrium_gives_the_portable_bits() {
        if !std::arch::is_x86_feature_detected!("avx2") {
            return;
        }
        let mut rnd = uniform(0x9e37_79b9_7f4a_7c15);
        let mut valid = 0;
        for case in 0..2000 {
            let n = 6 + case % 7;
            let ws: Vec<f64> = (0..6 * n).map(|_| 2.0 * rnd() - 1.0).collect();
            let t: Vec<f64> = (0..n).map(|_| 1000.0 * rnd()).collect();
            // Balanced up to rounding, or off by up to 10⁻⁵ N (either side of the tolerance).
            let mut we = vec![0.0; 6];
            for (col, ti) in ws.chunks_exact(6).zip(&t) {
                for k in 0..6 {
                    we[k] -= col[k] * ti;
                }
            }
            we[case % 6] += 1e-5 * rnd() * (case % 2) as f64;
            let portable = equilibrium_test::<6>(&ws, &we, &t);
            // SAFETY: the CPU reports AVX2.
            let avx2 = unsafe { equilibrium_test_6_avx2(&ws, &we, &t) };
            assert_eq!(portable.0, avx2.0, "{case}");
            assert_eq!(portable.1.to_bits(), avx2.1.to_bits(), "{case}");
            valid += portable.0 as usize;
        }
        assert!(valid > 1000 && valid < 2000, "{valid}");
    }

    /// The fixed-size residual sums in the same order as a plain row loop.
    #[test]
    fn fixed_size_certificate_matches_row_loop() {
        let w = DMatrix::from_row_slice(
            3,
            4,
            &[
                0.3, -1.0, 0.7, 0.1, 1.0, 0.2, -0.4, 0.9, -0.05, 0.08, 0.1, -0.02,
            ],
        );
        let we = DVector::from_vec(vec![0.25, -1.5, 0.01]);
        let b = TensionBounds::uniform(4, 0.0, 10.0).unwrap();
        let t = [1.0, 2.0, 3.0, 4.0];
        let c = certify(&w, &we, &b, &t);
        let mut residual: f64 = 0.0;
        let mut norm: f64 = 0.0;
        for k in 0..3 {
            let mut s = we[k];
            let mut row = 0.0;
            for i in 0..4 {
                s += w[(k, i)] * t[i];
                row += w[(k, i)].abs();
            }
            residual = residual.max(s.abs());
            norm = norm.max(row);
        }
        assert_eq!(c.residual, residual);
        assert_eq!(c.scale, 1f64.max(1.5).max(norm * 4.0));
        assert_eq!(c.bound_violation, -0.6); // t_4 = 4: (4 − 10)/10
    }
}
