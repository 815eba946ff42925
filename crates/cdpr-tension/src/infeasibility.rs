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
//! null space, so c = Wᵀ y for y = (W Wᵀ)⁻¹ W c (Cholesky), and cᵀ t ≥ Σ μ_j (β_j + s_j t0_j)
//! on the bounds while −yᵀ w_ext = cᵀ t0: the minimum above is Σ μ_j β_j > 0 up to rounding
//! (Helly's theorem in the plane: an empty polygon always has such a triple).
//!
//! ## References
//! - Farkas (1902), *Theorie der einfachen Ungleichungen*, J. reine angew. Math. 124.
//! - Picard, Caro, Plestan & Claveau 2020, eqs. (5)–(6).

use crate::TensionBounds;
use crate::feasible_polygon::P2;
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

/// Whether three half-planes of the polygon have an empty intersection (Farkas in the plane) and
/// the direction y they give proves that no tension passes the certificate (module docs).
/// `false` means "not proved", never "feasible".
pub(crate) fn triple_proves_empty(
    planes: &[HalfPlane; 3],
    w: &DMatrix<f64>,
    w_ext: &DVector<f64>,
    bounds: &TensionBounds,
) -> bool {
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
        return false;
    }
    let gap = mu[0] * p0.beta + mu[1] * p1.beta + mu[2] * p2.beta;
    if gap.is_nan() || gap <= 0.0 {
        return false;
    }
    let (m, n) = w.shape();
    if w_ext.len() != m || bounds.len() != n {
        return false;
    }
    let (ws, we) = (w.as_slice(), w_ext.as_slice());
    match m {
        6 => proves::<6>(planes, &mu, ws, n, we, bounds),
        5 => proves::<5>(planes, &mu, ws, n, we, bounds),
        4 => proves::<4>(planes, &mu, ws, n, we, bounds),
        3 => proves::<3>(planes, &mu, ws, n, we, bounds),
        2 => proves::<2>(planes, &mu, ws, n, we, bounds),
        1 => proves::<1>(planes, &mu, ws, n, we, bounds),
        _ => false,
    }
}

/// [`triple_proves_empty`] after the plane test, for M = m rows.
#[inline(always)]
fn proves<const M: usize>(
    planes: &[HalfPlane; 3],
    mu: &[f64; 3],
    ws: &[f64],
    n: usize,
    we: &[f64],
    bounds: &TensionBounds,
) -> bool {
    // W c with c = Σ_j μ_j s_j e_{i_j}.
    let mut wc = [0.0; M];
    for (plane, &mj) in planes.iter().zip(mu) {
        let column = &ws[plane.cable * M..(plane.cable + 1) * M];
        for (d, &v) in wc.iter_mut().zip(column) {
            *d += mj * plane.sign * v;
        }
    }
    let Some(y) = solve_normal_equations::<M>(ws, n, wc) else {
        return false;
    };
    separates::<M>(ws, n, we, bounds, &y)
}

/// y with (W Wᵀ) y = b (Cholesky of the M × M Gram matrix, `ws` column-major M × n), or `None`
/// when a pivot is not above 10⁻¹² of its diagonal entry (y may be any vector: it only has to
/// be a good direction, see [`separates`]).
// Triangular index loops read as the textbook Cholesky.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn solve_normal_equations<const M: usize>(ws: &[f64], n: usize, b: [f64; M]) -> Option<[f64; M]> {
    let mut g = [[0.0; M]; M];
    for column in ws.chunks_exact(M).take(n) {
        for r in 0..M {
            for c in 0..=r {
                g[r][c] += column[r] * column[c];
            }
        }
    }
    // G = L Lᵀ in the lower triangle.
    for j in 0..M {
        let mut d = g[j][j];
        for k in 0..j {
            d -= g[j][k] * g[j][k];
        }
        // A pivot lost to cancellation: W has (nearly) dependent rows.
        if d.is_nan() || d <= 1e-12 * g[j][j] {
            return None;
        }
        let d = d.sqrt();
        g[j][j] = d;
        for r in j + 1..M {
            let mut s = g[r][j];
            for k in 0..j {
                s -= g[r][k] * g[j][k];
            }
            g[r][j] = s / d;
        }
    }
    let mut y = b;
    for r in 0..M {
        for k in 0..r {
            y[r] -= g[r][k] * y[k];
        }
        y[r] /= g[r][r];
    }
    for r in (0..M).rev() {
        for k in r + 1..M {
            y[r] -= g[k][r] * y[k];
        }
        y[r] /= g[r][r];
    }
    Some(y)
}

/// The test of the module docs: whether y separates the zonotope of W over the bounds, shifted
/// by w_ext, from the origin by more than the certificate's residual tolerance and rounding.
#[inline(always)]
fn separates<const M: usize>(
    ws: &[f64],
    n: usize,
    we: &[f64],
    bounds: &TensionBounds,
    y: &[f64; M],
) -> bool {
    let (lo, hi) = (bounds.min().as_slice(), bounds.max().as_slice());
    let mut value = 0.0;
    let mut error = 0.0;
    let mut y1 = 0.0;
    let mut we_max: f64 = 0.0;
    for (&yk, &e) in y.iter().zip(we) {
        value += yk * e;
        error += yk.abs() * e.abs();
        y1 += yk.abs();
        we_max = we_max.max(e.abs());
    }
    let mut rows = [0.0; M];
    let mut t_max: f64 = 0.0;
    for (i, column) in ws.chunks_exact(M).take(n).enumerate() {
        let (l, h) = (lo[i], hi[i]);
        if !(l.is_finite() && h.is_finite()) {
            return false;
        }
        let ti = l.abs().max(h.abs());
        t_max = t_max.max(ti);
        let mut c = 0.0;
        let mut size = 0.0;
        for ((&v, &yk), row) in column.iter().zip(y).zip(&mut rows) {
            c += v * yk;
            size += v.abs() * yk.abs();
            *row += v.abs();
        }
        value += (c * l).min(c * h);
        error += size * ti;
    }
    let w_norm = rows.iter().fold(0.0f64, |a, &r| a.max(r));
    let scale = 1f64.max(we_max).max(w_norm * t_max);
    // NaN anywhere fails the comparison: not proved.
    value > 2e-9 * y1 * scale + 1e-12 * error
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
        assert!(separates::<1>(w.as_slice(), 2, &we, &b, &[-1.0]));
        // The other direction does not separate.
        assert!(!separates::<1>(w.as_slice(), 2, &we, &b, &[1.0]));
        // t ∈ [0, 2.5]: the sum reaches 5 exactly (a feasible problem), no direction proves
        // anything, not even by rounding.
        let b = TensionBounds::uniform(2, 0.0, 2.5).unwrap();
        assert!(!separates::<1>(w.as_slice(), 2, &we, &b, &[-1.0]));
        // A gap within the certificate's tolerance (10⁻⁹ · 5) is not enough either.
        let b = TensionBounds::uniform(2, 0.0, 2.5 - 1e-9).unwrap();
        assert!(!separates::<1>(w.as_slice(), 2, &we, &b, &[-1.0]));
        let b = TensionBounds::uniform(2, 0.0, 2.5 - 1e-7).unwrap();
        assert!(separates::<1>(w.as_slice(), 2, &we, &b, &[-1.0]));
    }

    #[test]
    fn normal_equations_are_solved() {
        // W = [[1, 0, 1], [0, 2, 0]]: W Wᵀ = diag(2, 4).
        let w = DMatrix::from_row_slice(2, 3, &[1.0, 0.0, 1.0, 0.0, 2.0, 0.0]);
        let y = solve_normal_equations::<2>(w.as_slice(), 3, [4.0, 8.0]).unwrap();
        assert!(
            (y[0] - 2.0).abs() < 1e-15 && (y[1] - 2.0).abs() < 1e-15,
            "{y:?}"
        );
        // A rank-deficient W has no Cholesky factor.
        let w = DMatrix::from_row_slice(2, 3, &[1.0, 0.0, 1.0, 2.0, 0.0, 2.0]);
        assert!(solve_normal_equations::<2>(w.as_slice(), 3, [4.0, 8.0]).is_none());
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
                && triple_proves_empty(&triple.planes(&ns, &b), &w, &we, &b)
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
