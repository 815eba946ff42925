//! # Certificate of infeasibility
//!
//! Farkas' lemma for the tension distribution W t + w_ext = 0, t_min ≤ t ≤ t_max: no feasible
//! tension exists when some wrench-space direction y separates the zonotope
//! {W t + w_ext : t_min ≤ t ≤ t_max} from the origin,
//!
//! min_{t_min ≤ t ≤ t_max} yᵀ(W t + w_ext) = yᵀ w_ext + Σ_i min(c_i t_min,i, c_i t_max,i) > 0,
//! c = Wᵀ y.
//!
//! `TensionSolver::is_feasible` only answers "feasible" for tensions that pass
//! [`crate::certify`] (after snapping into the bounds, so t_min ≤ t ≤ t_max exactly), which
//! allows a residual ‖W t + w_ext‖∞ ≤ 10⁻⁹ S, S = max(1, ‖w_ext‖∞, ‖W‖∞ max|t_i|). Such a t
//! has yᵀ(W t + w_ext) ≤ ‖y‖₁ · 10⁻⁹ S (plus the rounding of the computed residual). The test
//! below therefore asks for
//!
//! computed min > 2·10⁻⁹ ‖y‖₁ S + 10⁻¹² E, E = Σ_k |y_k| (|w_ext,k| + Σ_i |W_ki| T_i),
//! T_i = max(|t_min,i|, |t_max,i|),
//!
//! where E bounds every product in both sums, so 10⁻¹² E exceeds the rounding of the computed
//! minimum and of the certificate's residual (n + m + 2 ≤ 20 roundings of 1.1·10⁻¹⁶ each) by
//! far. When the test holds, *no* tension passes the certificate, whatever y is and however it
//! was computed: the verdict "infeasible" is then the verdict of every method's solve. y only
//! decides how often the test succeeds.
//!
//! At redundancy r = 2 the direction comes from three half-planes s_j a_j·λ ≥ β_j of the feasible
//! polygon (Picard, Caro, Plestan & Claveau 2020, eq. (6); a_j = row of N) with an empty
//! intersection, which the l2 active set meets when it fails (module `planar_active_set`): with
//! the multipliers μ = (n₁ × n₂, n₂ × n₀, n₀ × n₁) ≥ 0 of Σ μ_j n_j = 0 (n_j = s_j a_j) and
//! Σ μ_j β_j > 0, the tension-space combination c = Σ_j μ_j s_j e_{i_j} is orthogonal to the
//! null space, so c = Wᵀ y for y = (W Wᵀ)⁻¹ W c (from the QR of Wᵀ that gave N:
//! y = P R⁻¹ (Qᵀ c)₁..ₘ, `NullSpace::row_space_solve`), and cᵀ t ≥ Σ μ_j (β_j + s_j t0_j)
//! on the bounds while −yᵀ w_ext = cᵀ t0: the minimum above is Σ μ_j β_j > 0 up to rounding
//! (Helly's theorem in the plane: an empty polygon always has such a triple).
//!
//! ## References
//! - Farkas (1902), *Theorie der einfachen Ungleichungen*, J. reine angew. Math. 124.
//! - Picard, Caro, Plestan & Claveau 2020, eqs. (5)–(6).

use crate::TensionBounds;
use crate::feasible_polygon::P2;
use crate::lanes::{F64x4, Portable};
use crate::null_space::{LANES, NullSpace};
use nalgebra::{DMatrix, DVector};

/// One bound of a cable as a half-plane of the feasible polygon: cable `cable`, `sign` +1 for
/// t ≥ t_min (normal a), −1 for t ≤ t_max (normal −a); `normal` and `beta` of normal·λ ≥ beta.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct HalfPlane {
    pub cable: usize,
    pub sign: f64,
    pub normal: P2,
    pub beta: f64,
}

/// The multipliers μ ≥ 0 of Σ μ_j n_j = 0 for three half-planes n_j·λ ≥ β_j of the polygon
/// when they prove its emptiness in the plane (Σ μ_j β_j > 0; module docs), else `None`.
/// Cheap: the test of a triple before any wrench-space work.
pub(crate) fn multipliers(planes: &[HalfPlane; 3]) -> Option<[f64; 3]> {
    let cross = |a: P2, b: P2| a[0] * b[1] - a[1] * b[0];
    let [p0, p1, p2] = planes;
    let mut mu = [
        cross(p1.normal, p2.normal),
        cross(p2.normal, p0.normal),
        cross(p0.normal, p1.normal),
    ];
    if mu.iter().all(|&m| m <= 0.0) {
        mu = mu.map(|m| -m);
    }
    if !mu.iter().all(|&m| m >= 0.0) {
        return None;
    }
    let gap = mu[0] * p0.beta + mu[1] * p1.beta + mu[2] * p2.beta;
    (gap > 0.0).then_some(mu)
}

/// Whether the wrench-space direction y = (W Wᵀ)⁻¹ W c of three half-planes with multipliers
/// `mu` ([`multipliers`]), c = Σ_j μ_j s_j e_{i_j}, proves that no tension passes the
/// certificate (module docs). `ns` is the null space of `w` and must hold its QR
/// ([`NullSpace::keep_qr`]); redundancy 2, m ≤ 6. The direction y when it proves emptiness
/// (padded with zeros to six components), `None` for "not proved", never "feasible".
pub(crate) fn direction_proves_empty(
    planes: &[HalfPlane; 3],
    mu: &[f64; 3],
    ns: &NullSpace,
    w: &DMatrix<f64>,
    w_ext: &DVector<f64>,
    bounds: &TensionBounds,
) -> Option<[f64; 6]> {
    let (m, n) = w.shape();
    if w_ext.len() != m || bounds.len() != n || ns.m != m || ns.n != n {
        return None;
    }
    let (ws, we) = (w.as_slice(), w_ext.as_slice());
    match (m, n) {
        (6, 8) => proves::<6, 8>(planes, mu, ns, ws, we, bounds),
        (5, 7) => proves::<5, 7>(planes, mu, ns, ws, we, bounds),
        (4, 6) => proves::<4, 6>(planes, mu, ns, ws, we, bounds),
        (3, 5) => proves::<3, 5>(planes, mu, ns, ws, we, bounds),
        (2, 4) => proves::<2, 4>(planes, mu, ns, ws, we, bounds),
        (1, 3) => proves::<1, 3>(planes, mu, ns, ws, we, bounds),
        _ => None,
    }
}

/// [`direction_proves_empty`] for W of M × N.
#[inline(always)]
fn proves<const M: usize, const N: usize>(
    planes: &[HalfPlane; 3],
    mu: &[f64; 3],
    ns: &NullSpace,
    ws: &[f64],
    we: &[f64],
    bounds: &TensionBounds,
) -> Option<[f64; 6]> {
    let mut c = [0.0; N];
    for (plane, &mj) in planes.iter().zip(mu) {
        if plane.cable >= N {
            return None;
        }
        c[plane.cable] += mj * plane.sign;
    }
    let y = ns.row_space_solve::<M, N>(&c)?;
    if !separates::<M, N>(ws, we, bounds, &y) {
        return None;
    }
    let mut padded = [0.0; 6];
    padded[..M].copy_from_slice(&y);
    Some(padded)
}

/// [`multipliers`] then [`direction_proves_empty`], factoring W again when its QR is not kept.
#[cfg(test)]
pub(crate) fn triple_proves_empty(
    planes: &[HalfPlane; 3],
    ns: &mut NullSpace,
    w: &DMatrix<f64>,
    w_ext: &DVector<f64>,
    bounds: &TensionBounds,
) -> bool {
    match multipliers(planes) {
        Some(mu) if ns.keep_qr(w, w_ext).is_ok() => {
            direction_proves_empty(planes, &mu, ns, w, w_ext, bounds).is_some()
        }
        _ => false,
    }
}

/// The test of the module docs: whether y separates the zonotope of W (M × N, column-major)
/// over the bounds, shifted by w_ext, from the origin by more than the certificate's residual
/// tolerance and rounding.
#[inline(always)]
fn separates<const M: usize, const N: usize>(
    ws: &[f64],
    we: &[f64],
    bounds: &TensionBounds,
    y: &[f64; M],
) -> bool {
    let (ws, we) = (&ws[..M * N], &we[..M]);
    let (lo, hi) = (&bounds.min().as_slice()[..N], &bounds.max().as_slice()[..N]);
    let mut value = 0.0;
    let mut error = 0.0;
    let mut y1 = 0.0;
    let mut we_max: f64 = 0.0;
    let mut y_abs = [0.0; M];
    for k in 0..M {
        y_abs[k] = y[k].abs();
        value += y[k] * we[k];
        error += y_abs[k] * we[k].abs();
        y1 += y_abs[k];
        we_max = we_max.max(we[k].abs());
    }
    let mut rows = [0.0; M];
    let mut t_max: f64 = 0.0;
    for i in 0..N {
        let (l, h) = (lo[i], hi[i]);
        if !(l.is_finite() && h.is_finite()) {
            return false;
        }
        let ti = l.abs().max(h.abs());
        t_max = t_max.max(ti);
        let column = &ws[i * M..i * M + M];
        let mut c = 0.0;
        let mut size = 0.0;
        for k in 0..M {
            let v = column[k];
            c += v * y[k];
            size += v.abs() * y_abs[k];
            rows[k] += v.abs();
        }
        value += (c * l).min(c * h);
        error += size * ti;
    }
    let w_norm = rows.iter().fold(0.0f64, |a, &r| a.max(r));
    let scale = 1f64.max(we_max).max(w_norm * t_max);
    // NaN anywhere fails the comparison: not proved.
    value > 2e-9 * y1 * scale + 1e-12 * error
}

/// [`separates`] for four 6 × 8 problems at once (`columns[j][i][l]` = W(i, j) of problem l,
/// one w_ext, one set of bounds) and one direction `y`, in SIMD lanes (AVX2 when the CPU has
/// it): bit l when y proves problem l empty. The sums run in the order of the scalar test, so
/// each lane's verdict is the scalar one (tested); a lane with a non-finite W entry is never
/// proved. Grids try the direction of the last proof on the next four poses before any null
/// space: the test is rigorous for any y (module docs), so it cannot change a verdict.
pub(crate) fn four_6x8_separated(
    columns: &[[[f64; LANES]; 6]; 8],
    w_ext: &[f64],
    bounds: &TensionBounds,
    y: &[f64; 6],
) -> u32 {
    if w_ext.len() != 6 || bounds.len() != 8 {
        return 0;
    }
    #[cfg(target_arch = "x86_64")]
    if let Some(v) = crate::lanes::Avx2::detect() {
        // SAFETY: `detect` found AVX2.
        return unsafe { four_6x8_separated_avx2(v, columns, w_ext, bounds, y) };
    }
    four_6x8_separated_lanes(Portable([0.0; LANES]), columns, w_ext, bounds, y)
}

/// [`four_6x8_separated`] compiled for AVX2.
///
/// # Safety
/// The CPU must support AVX2 (an [`crate::lanes::Avx2`] value is the proof).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn four_6x8_separated_avx2(
    v: crate::lanes::Avx2,
    columns: &[[[f64; LANES]; 6]; 8],
    w_ext: &[f64],
    bounds: &TensionBounds,
    y: &[f64; 6],
) -> u32 {
    four_6x8_separated_lanes(v, columns, w_ext, bounds, y)
}

/// [`four_6x8_separated`] on the lanes of `v` (portable or AVX2: the same bits).
#[inline(always)]
fn four_6x8_separated_lanes<V: F64x4>(
    v: V,
    columns: &[[[f64; LANES]; 6]; 8],
    w_ext: &[f64],
    bounds: &TensionBounds,
    y: &[f64; 6],
) -> u32 {
    let (lo, hi) = (&bounds.min().as_slice()[..8], &bounds.max().as_slice()[..8]);
    let we = &w_ext[..6];
    // The parts of `separates` that do not depend on W, in its order.
    let mut value = 0.0;
    let mut error = 0.0;
    let mut y1 = 0.0;
    let mut we_max: f64 = 0.0;
    let mut y_abs = [0.0; 6];
    for k in 0..6 {
        y_abs[k] = y[k].abs();
        value += y[k] * we[k];
        error += y_abs[k] * we[k].abs();
        y1 += y_abs[k];
        we_max = we_max.max(we[k].abs());
    }
    let mut t_max: f64 = 0.0;
    for i in 0..8 {
        if !(lo[i].is_finite() && hi[i].is_finite()) {
            return 0;
        }
        t_max = t_max.max(lo[i].abs().max(hi[i].abs()));
    }
    // No closures here (`array::map`): they would lose the caller's target features.
    let mut ys = [v.splat(0.0); 6];
    let mut ys_abs = [v.splat(0.0); 6];
    for k in 0..6 {
        ys[k] = v.splat(y[k]);
        ys_abs[k] = v.splat(y_abs[k]);
    }
    let mut value = v.splat(value);
    let mut error = v.splat(error);
    let mut rows = [v.splat(0.0); 6];
    for i in 0..8 {
        let ti = v.splat(lo[i].abs().max(hi[i].abs()));
        let mut c = v.splat(0.0);
        let mut size = v.splat(0.0);
        for k in 0..6 {
            let w = v.load(columns[i][k]);
            c = c.add(w.mul(ys[k]));
            size = size.add(w.abs().mul(ys_abs[k]));
            rows[k] = rows[k].add(w.abs());
        }
        value = value.add(c.mul(v.splat(lo[i])).min(c.mul(v.splat(hi[i]))));
        error = error.add(size.mul(ti));
    }
    // ‖W‖∞ = max_k rows_k; a row that is not finite (an infinite or NaN entry) fails
    // `finite` (`max` would drop a NaN).
    let inf = v.splat(f64::INFINITY);
    let mut finite = V::bits(rows[0].lt(inf));
    let mut w_norm = v.splat(0.0);
    for row in rows {
        finite &= V::bits(row.lt(inf));
        w_norm = row.max(w_norm);
    }
    let scale = w_norm.mul(v.splat(t_max)).max(v.splat(1f64.max(we_max)));
    let needed = v.splat(2e-9 * y1).mul(scale).add(v.splat(1e-12).mul(error));
    finite & V::bits(value.gt(needed))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Method, TensionProblem, TensionSolver};

    /// One force balanced by two cables, t₁ + t₂ = 5 with t ∈ [0, 2]: the zonotope
    /// t₁ + t₂ − 5 ∈ [−5, −1] misses 0 by 1; y = −1 gives min = 5 − 4 = 1 > 0.
    #[test]
    fn a_separating_direction_is_accepted_and_a_weak_one_is_not() {
        let w = DMatrix::from_row_slice(1, 2, &[1.0, 1.0]);
        let we = [-5.0];
        let b = TensionBounds::uniform(2, 0.0, 2.0).unwrap();
        assert!(separates::<1, 2>(w.as_slice(), &we, &b, &[-1.0]));
        // The other direction does not separate.
        assert!(!separates::<1, 2>(w.as_slice(), &we, &b, &[1.0]));
        // t ∈ [0, 2.5]: the sum reaches 5 exactly (a feasible problem), no direction proves
        // anything, not even by rounding.
        let b = TensionBounds::uniform(2, 0.0, 2.5).unwrap();
        assert!(!separates::<1, 2>(w.as_slice(), &we, &b, &[-1.0]));
        // A gap within the certificate's tolerance (10⁻⁹ · 5) is not enough either.
        let b = TensionBounds::uniform(2, 0.0, 2.5 - 1e-9).unwrap();
        assert!(!separates::<1, 2>(w.as_slice(), &we, &b, &[-1.0]));
        let b = TensionBounds::uniform(2, 0.0, 2.5 - 1e-7).unwrap();
        assert!(separates::<1, 2>(w.as_slice(), &we, &b, &[-1.0]));
    }

    /// The lanes test of a direction is the scalar test lane by lane (AVX2 where the CPU has
    /// it and the portable build), on directions that prove random problems and on perturbed,
    /// non-finite and unrelated W; it proves some lanes and refuses others (not vacuous).
    #[test]
    fn four_problems_in_lanes_are_separated_as_one_at_a_time() {
        let mut next = crate::certificate::tests::uniform(0x1405_7b7e_f767_814f);
        let (mut proved, mut refused) = (0, 0);
        for case in 0..3000 {
            let w = DMatrix::from_fn(6, 8, |_, _| 2.0 * next() - 1.0);
            let we = DVector::from_fn(6, |_, _| 3.0 * (2.0 * next() - 1.0));
            let b = TensionBounds::uniform(8, 0.1 + next(), 2.0 + 3.0 * next()).unwrap();
            let mut ns = NullSpace::default();
            if ns.compute(&w, &we).is_err() {
                continue;
            }
            let Err(Some(triple)) = crate::planar_active_set::l2_search(&ns, &b) else {
                continue;
            };
            let planes = triple.planes(&ns, &b);
            let Some(mu) = multipliers(&planes) else {
                continue;
            };
            ns.keep_qr(&w, &we).unwrap();
            let Some(y) = direction_proves_empty(&planes, &mu, &ns, &w, &we, &b) else {
                continue;
            };
            // Lane 0: the problem; 1, 2: W perturbed by 10⁻³ and 0.3; 3: a non-finite entry
            // or an unrelated W.
            let mut lanes = [w.clone(), w.clone(), w.clone(), w.clone()];
            lanes[1] = w.map(|x| x + 1e-3 * (2.0 * next() - 1.0));
            lanes[2] = w.map(|x| x + 0.3 * (2.0 * next() - 1.0));
            lanes[3] = if case % 3 == 0 {
                let mut bad = w.clone();
                bad[(case % 6, case % 8)] = [f64::NAN, f64::INFINITY][case % 2];
                bad
            } else {
                DMatrix::from_fn(6, 8, |_, _| 2.0 * next() - 1.0)
            };
            let columns: [[[f64; LANES]; 6]; 8] = std::array::from_fn(|j| {
                std::array::from_fn(|i| [0, 1, 2, 3].map(|l| lanes[l][(i, j)]))
            });
            let scalar: u32 = (0..LANES)
                .map(|l| {
                    let finite = lanes[l].iter().all(|x| x.is_finite());
                    let s = separates::<6, 8>(lanes[l].as_slice(), we.as_slice(), &b, &y);
                    u32::from(finite && s) << l
                })
                .sum();
            assert_eq!(scalar & 1, 1, "the direction proves its own problem");
            let portable =
                four_6x8_separated_lanes(Portable([0.0; LANES]), &columns, we.as_slice(), &b, &y);
            assert_eq!(portable, scalar, "{w} {y:?}");
            assert_eq!(four_6x8_separated(&columns, we.as_slice(), &b, &y), scalar);
            proved += scalar.count_ones();
            refused += LANES as u32 - scalar.count_ones();
        }
        assert!(
            proved > 500 && refused > 200,
            "{proved} proved, {refused} refused"
        );
    }

    /// The proof never contradicts the solver: on random 6 × 8 problems, whenever a triple of
    /// the l2 active set's failure proves emptiness, `solve` finds no tension, and the proof
    /// does fire on some problems (not a vacuous test).
    #[test]
    fn proofs_agree_with_solve_on_random_problems() {
        let mut next = crate::certificate::tests::uniform(0x9e37_79b9_7f4a_7c15);
        let mut solver = TensionSolver::new(Method::L2);
        let (mut proved, mut infeasible) = (0, 0);
        for _ in 0..3000 {
            let w = DMatrix::from_fn(6, 8, |_, _| 2.0 * next() - 1.0);
            let we = DVector::from_fn(6, |_, _| 3.0 * (2.0 * next() - 1.0));
            let b = TensionBounds::uniform(8, 0.1 + next(), 2.0 + 3.0 * next()).unwrap();
            let mut ns = crate::null_space::NullSpace::default();
            if ns.compute(&w, &we).is_err() {
                continue;
            }
            let feasible = solver
                .solve(&TensionProblem::new(&w, &we, &b))
                .unwrap()
                .is_feasible();
            infeasible += !feasible as usize;
            if let Err(Some(triple)) = crate::planar_active_set::l2_search(&ns, &b)
                && triple_proves_empty(&triple.planes(&ns, &b), &mut ns, &w, &we, &b)
            {
                assert!(!feasible, "{w} {we} {b:?}");
                proved += 1;
            }
        }
        assert!(
            proved > infeasible / 4 && infeasible > 100,
            "{proved} of {infeasible}"
        );
    }
}
