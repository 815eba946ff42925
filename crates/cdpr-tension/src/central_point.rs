//! # The central point of four problems in lanes (6 × 8, redundancy 2)
//!
//! `TensionSolver::is_feasible` with l2 at redundancy r = 2 first tries the central point
//! λ_c = Nᵀ t_mid − g, t_mid = (t_min + t_max)/2, the point of the affine set t = t0 + N λ
//! nearest the middle of the bounds (Picard, Caro, Plestan & Claveau 2020, eq. (5); N
//! orthonormal): when every t_i is inside its bounds by the margin
//! 10⁻⁶ (t_max,i − t_min,i) + 10⁻⁹ max(|t_min,i|, |t_max,i|) and the tensions pass the
//! certificate, the verdict is "feasible" (see `planar_active_set::central_point` and
//! `docs/algorithms.md`). [`four_6x8`] takes that step for four problems at once, from their
//! null spaces in lanes ([`crate::null_space::four_6x8`]), in SIMD lanes ([`F64x4`]: an AVX2
//! build chosen at run time, the portable build otherwise, the same bits):
//!
//! - λ_c, the tensions t_i and the margin test with the scalar operations in the same order
//!   (no fused multiply–adds), so each lane's t is the scalar t bit for bit and the margin
//!   verdict is the scalar one;
//! - the certificate of those tensions as `snap_and_certify` decides it: inside the margin,
//!   every t_i is strictly inside [t_min,i, t_max,i], so snapping changes nothing and the bound
//!   test passes; the residual w_ext,k + Σ_i W_ki t_i is summed in the order of the scalar test
//!   and compared with 10⁻⁹ max(1, ‖w_ext‖∞). A lane whose residual fails that first test is
//!   left to the scalar path (which then tries the full scale ‖W‖∞ max|t_i|).
//!
//! A lane is [`FourCentralPoints::certified`] only when its W and w_ext are finite, its null
//! space is regular (as `FourNullSpaces::write_lane` decides) and both tests pass: exactly
//! when the scalar path would answer "feasible" at the central point with the first residual
//! test. The other lanes go on problem by problem; [`FourCentralPoints::inside`] tells them
//! whether the scalar central point would fail its margin (then it need not be tried again), and
//! [`FourCentralPoints::finite`] whether W needs no validation.
//!
//! Its steps ([`nearest`], [`tensions`], [`inside_margin`], [`balanced`]) also test the second
//! candidate of the lanes whose central point fails (module `warm_point`).
//!
//! ## References
//! - Picard, Caro, Plestan & Claveau 2020, eqs. (5)–(6).
//! - Thesis eqs. (6.11), (6.21) (the certificate).

use crate::TensionBounds;
use crate::certificate::EQUILIBRIUM_TOLERANCE;
use crate::lanes::{F64x4, Portable};
use crate::null_space::{FourNullSpaces, LANES, SINGULARITY_RATIO};
use crate::planar_active_set::central_margin;

/// What [`four_6x8`] decided, bit l for problem l.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct FourCentralPoints {
    /// Every entry of W is finite.
    pub finite: u32,
    /// The central point is inside every bound by the margin: `central_point` returns it
    /// (meaningful for a regular null space).
    pub inside: u32,
    /// "Feasible", certified: W and w_ext finite, the null space regular, the central point
    /// inside the margin and its residual within 10⁻⁹ max(1, ‖w_ext‖∞).
    pub certified: u32,
}

/// The central points of four 6 × 8 problems (`columns[j][i][l]` = W(i, j) of problem l, their
/// null spaces `four`, one external wrench of length 6 and one set of 8 bounds), their margin
/// tests and certificates in lanes (see the module docs). AVX2 when the CPU has it.
pub(crate) fn four_6x8(
    four: &FourNullSpaces,
    columns: &[[[f64; LANES]; 6]; 8],
    w_ext: &[f64],
    bounds: &TensionBounds,
) -> FourCentralPoints {
    #[cfg(target_arch = "x86_64")]
    if let Some(v) = crate::lanes::Avx2::detect() {
        // SAFETY: `detect` found AVX2.
        return unsafe { four_6x8_avx2(v, four, columns, w_ext, bounds) };
    }
    four_6x8_lanes(Portable([0.0; LANES]), four, columns, w_ext, bounds)
}

/// [`four_6x8`] compiled for AVX2.
///
/// # Safety
/// The CPU must support AVX2 (an [`crate::lanes::Avx2`] value is the proof).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn four_6x8_avx2(
    v: crate::lanes::Avx2,
    four: &FourNullSpaces,
    columns: &[[[f64; LANES]; 6]; 8],
    w_ext: &[f64],
    bounds: &TensionBounds,
) -> FourCentralPoints {
    four_6x8_lanes(v, four, columns, w_ext, bounds)
}

/// [`four_6x8`] on the lanes of `v` (portable or AVX2: the same bits).
#[inline(always)]
pub(crate) fn four_6x8_lanes<V: F64x4>(
    v: V,
    four: &FourNullSpaces,
    columns: &[[[f64; LANES]; 6]; 8],
    w_ext: &[f64],
    bounds: &TensionBounds,
) -> FourCentralPoints {
    debug_assert_eq!((w_ext.len(), bounds.len()), (6, 8));
    let (lo, hi) = (&bounds.min().as_slice()[..8], &bounds.max().as_slice()[..8]);
    let we: &[f64; 6] = w_ext[..6].try_into().expect("six components");
    let zero = v.splat(0.0);
    // W finite: Σ W_ki · 0 is ±0 when every entry is finite, NaN otherwise.
    let mut nan = zero;
    for column in columns {
        for row in column {
            nan = nan.add(v.load(*row).mul(zero));
        }
    }
    let finite = V::bits(nan.eq(zero));
    let regular = regular(v, four);
    // λ_c = −g + Σ_i N_i mid_i (`central_point`, the same order).
    let mut mid = [zero; 8];
    for i in 0..8 {
        mid[i] = v.splat(0.5 * (lo[i] + hi[i]));
    }
    let l = nearest(v, four, &mid);
    // t_i = t0_i + N_i1 λ1 + N_i2 λ2 (`NullSpace::tension2`) and the margin test.
    let t = tensions(v, four, l);
    let inside = inside_margin(v, &t, bounds);
    let balanced = balanced(v, columns, we, &t);
    let we_finite = we.iter().all(|e| e.is_finite());
    let certified = if we_finite {
        finite & regular & inside & balanced
    } else {
        0
    };
    FourCentralPoints {
        finite,
        inside,
        certified,
    }
}

/// Lanes whose null space is regular, as `FourNullSpaces::write_lane` decides: singular for a
/// zero row or pivot, a NaN ratio or one below the threshold.
#[inline(always)]
pub(crate) fn regular<V: F64x4>(v: V, four: &FourNullSpaces) -> u32 {
    let not_zero: u32 = (0..LANES).map(|l| u32::from(four.zero[l] == 0) << l).sum();
    not_zero & V::bits(v.load(four.ratio).ge(v.splat(SINGULARITY_RATIO)))
}

/// λ = Nᵀ target − g = −g + Σ_i N_i target_i of each lane (`central_point`'s order), the point
/// of the affine set t = t0 + N λ nearest `target` (N orthonormal).
#[inline(always)]
pub(crate) fn nearest<V: F64x4>(v: V, four: &FourNullSpaces, target: &[V; 8]) -> [V; 2] {
    let (n1, n2) = (&four.basis[0], &four.basis[1]);
    let mut l0 = v.load(four.g[0]).neg();
    let mut l1 = v.load(four.g[1]).neg();
    for i in 0..8 {
        l0 = l0.add(v.load(n1[i]).mul(target[i]));
        l1 = l1.add(v.load(n2[i]).mul(target[i]));
    }
    [l0, l1]
}

/// t_i = t0_i + N_i1 λ1 + N_i2 λ2 of each lane, as `NullSpace::tension2`.
#[inline(always)]
pub(crate) fn tensions<V: F64x4>(v: V, four: &FourNullSpaces, l: [V; 2]) -> [V; 8] {
    let (n1, n2) = (&four.basis[0], &four.basis[1]);
    let mut t = [l[0]; 8];
    for i in 0..8 {
        t[i] = v
            .load(four.t0[i])
            .add(v.load(n1[i]).mul(l[0]))
            .add(v.load(n2[i]).mul(l[1]));
    }
    t
}

/// Lanes whose every t_i is inside its bounds by `central_margin`, as the test of
/// `planar_active_set::central_point` (NaN and an infinite t_max fail).
#[inline(always)]
pub(crate) fn inside_margin<V: F64x4>(v: V, t: &[V; 8], bounds: &TensionBounds) -> u32 {
    let (lo, hi) = (&bounds.min().as_slice()[..8], &bounds.max().as_slice()[..8]);
    let mut inside = (1u32 << LANES) - 1;
    for i in 0..8 {
        let margin = v.splat(central_margin(lo[i], hi[i]));
        let (lo_i, hi_i) = (v.splat(lo[i]), v.splat(hi[i]));
        inside &= V::bits(t[i].sub(lo_i).gt(margin)) & V::bits(hi_i.sub(t[i]).gt(margin));
    }
    inside
}

/// Lanes whose residual passes the first test of `snap_and_certify` against
/// max(1, ‖w_ext‖∞) (`equilibrium_test`): max_k |r_k| is finite and ≤ tol exactly when every
/// |r_k| ≤ tol (tol is finite for a finite w_ext; a NaN r_k fails both). The caller checks
/// that w_ext is finite.
#[inline(always)]
pub(crate) fn balanced<V: F64x4>(
    v: V,
    columns: &[[[f64; LANES]; 6]; 8],
    we: &[f64; 6],
    t: &[V; 8],
) -> u32 {
    let we_max = we.iter().fold(0.0f64, |m, e| m.max(e.abs()));
    let tol = v.splat(EQUILIBRIUM_TOLERANCE * 1f64.max(we_max));
    let mut balanced = (1u32 << LANES) - 1;
    for (k, &we_k) in we.iter().enumerate() {
        let mut r = v.splat(we_k);
        for (column, &ti) in columns.iter().zip(t) {
            r = r.add(v.load(column[k]).mul(ti));
        }
        balanced &= V::bits(r.abs().le(tol));
    }
    balanced
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::certificate::snap_and_certify;
    use crate::certificate::tests::uniform;
    use crate::linear_program::write_tensions;
    use crate::null_space::{NullSpace, four_6x8 as null_spaces};
    use crate::planar_active_set::central_point;
    use nalgebra::{DMatrix, DVector};

    /// What the scalar path decides for lane `l`: (W finite, central point inside its margin
    /// for a regular null space, "feasible" at the central point with the residual test
    /// against max(1, ‖w_ext‖∞)).
    fn scalar(
        four: &crate::null_space::FourNullSpaces,
        w: &DMatrix<f64>,
        we: &DVector<f64>,
        b: &TensionBounds,
        l: usize,
    ) -> (bool, Option<bool>, bool) {
        let finite = w.iter().all(|v| v.is_finite());
        let mut ns = NullSpace::default();
        if four.write_lane(l, &mut ns).is_err() {
            return (finite, None, false);
        }
        let Some(lambda) = central_point(&ns, b) else {
            return (finite, Some(false), false);
        };
        let mut t = vec![0.0; 8];
        write_tensions(&ns, lambda, &mut t);
        let we_max = we.iter().fold(0.0f64, |m, e| m.max(e.abs()));
        let certified = match snap_and_certify(w, we, b, &mut t) {
            Ok(residual) => residual <= EQUILIBRIUM_TOLERANCE * 1f64.max(we_max),
            Err(_) => false,
        };
        let valid = finite && we.iter().all(|e| e.is_finite());
        (finite, Some(true), valid && certified)
    }

    /// The four-lane central point decides every lane as the scalar path does (margin,
    /// certificate, finiteness, singular W), in the portable and (where the CPU has it) the
    /// AVX2 build, on random problems built to put the central point on either side of its
    /// margin, with W scaled up so that the residual fails the first test, NaN and ∞ in W or
    /// w_ext, singular W and an infinite t_max.
    #[test]
    fn four_lanes_decide_as_the_scalar_central_point() {
        let mut rnd = uniform(0x5deece66d_u64 ^ 0x2545_f491_4f6c_dd1d);
        let (mut certified, mut outside, mut refused) = (0, 0, 0);
        for case in 0..3000 {
            let mut lo: Vec<f64> = (0..8).map(|_| 20.0 * rnd() - 5.0).collect();
            let mut hi: Vec<f64> = lo.iter().map(|l| l + 10.0 + 500.0 * rnd()).collect();
            // Tensions around the middle of the bounds, by a random amount: the central point
            // lands on either side of its margin.
            let push = 0.6 * rnd();
            let tc = DVector::from_fn(8, |i, _| {
                lo[i] + (hi[i] - lo[i]) * (0.5 + push * (rnd() - 0.5))
            });
            let mut base = DMatrix::from_fn(6, 8, |_, _| 2.0 * rnd() - 1.0);
            // Unloaded with t_c in the null space: the central point is inside, and W scaled
            // by 10⁷ leaves a residual above 10⁻⁹ max(1, ‖w_ext‖∞) but within the full scale.
            let unloaded = case % 5 == 0;
            let mut we = if unloaded {
                let p = DMatrix::identity(8, 8) - &tc * tc.transpose() / tc.norm_squared();
                base = &base * p;
                DVector::zeros(6)
            } else {
                -(&base * &tc)
            };
            if case % 7 == 1 && !unloaded {
                // Cable k's bounds shifted so that the central point of `base` (lane 0) lies
                // on its margin up to rounding, below or above (Newton steps on the shift δ:
                // t_k moves by (N Nᵀ)_kk δ).
                let mut ns = NullSpace::default();
                if ns.compute(&base, &we).is_ok() {
                    let k = case % 8;
                    let pkk = ns.basis[k].powi(2) + ns.basis[8 + k].powi(2);
                    for _ in 0..3 {
                        let mut l = [-ns.g[0], -ns.g[1]];
                        for i in 0..8 {
                            let mid = 0.5 * (lo[i] + hi[i]);
                            l[0] += ns.basis[i] * mid;
                            l[1] += ns.basis[8 + i] * mid;
                        }
                        let t = ns.tension2(k, l);
                        let margin = central_margin(lo[k], hi[k]);
                        let delta = if case % 2 == 0 {
                            (t - lo[k] - margin) / (1.0 - pkk)
                        } else {
                            (margin - (hi[k] - t)) / (1.0 - pkk)
                        };
                        lo[k] += delta;
                        hi[k] += delta;
                    }
                }
            }
            if case % 37 == 0 {
                hi[3] = f64::INFINITY;
            }
            let b = TensionBounds::new(lo, hi).unwrap();
            if case % 53 == 0 {
                we[2] = [f64::NAN, f64::INFINITY][case % 2];
            }
            let mut columns = [[[0.0; LANES]; 6]; 8];
            let mut ws = Vec::new();
            for l in 0..LANES {
                let eps = [0.0, 1e-3, 1e-2, 0.1][l];
                let mut w = &base + DMatrix::from_fn(6, 8, |_, _| eps * (2.0 * rnd() - 1.0));
                match (case + l) % 13 {
                    // The residual, rounding only, against 10⁻⁹: either side.
                    0 | 5 if unloaded => w *= 10f64.powf(3.0 + 3.0 * rnd()),
                    1 => w[(2, 5)] = f64::NAN,
                    2 => w[(4, 1)] = f64::INFINITY,
                    3 => {
                        let row = w.row(0).into_owned();
                        w.row_mut(5).copy_from(&row);
                    }
                    _ => {}
                }
                for j in 0..8 {
                    for i in 0..6 {
                        columns[j][i][l] = w[(i, j)];
                    }
                }
                ws.push(w);
            }
            let four = null_spaces(&columns, we.as_slice(), &mut Default::default());
            let portable =
                four_6x8_lanes(Portable([0.0; LANES]), &four, &columns, we.as_slice(), &b);
            #[cfg(target_arch = "x86_64")]
            if let Some(v) = crate::lanes::Avx2::detect() {
                // SAFETY: `detect` found AVX2.
                let avx2 = unsafe { four_6x8_avx2(v, &four, &columns, we.as_slice(), &b) };
                assert_eq!(avx2, portable, "case {case}");
            }
            for (l, w) in ws.iter().enumerate() {
                let (finite, inside, ok) = scalar(&four, w, &we, &b, l);
                assert_eq!(
                    portable.finite >> l & 1 == 1,
                    finite,
                    "case {case} lane {l}"
                );
                if let Some(inside) = inside {
                    assert_eq!(
                        portable.inside >> l & 1 == 1,
                        inside,
                        "case {case} lane {l}"
                    );
                    outside += usize::from(!inside);
                }
                assert_eq!(portable.certified >> l & 1 == 1, ok, "case {case} lane {l}");
                certified += usize::from(ok);
                refused += usize::from(inside == Some(true) && !ok);
            }
        }
        // Every kind of lane occurs often.
        assert!(
            certified > 3000 && outside > 2000 && refused > 150,
            "{certified} {outside} {refused}"
        );
    }
}
