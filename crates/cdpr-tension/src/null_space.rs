//! # Null-space parametrisation of the equilibrium
//!
//! Every solution of W t + w_ext = 0 is t = t0 + N λ (Picard, Caro, Plestan & Claveau 2020, eq. (5)), with t0 = −W⁺ w_ext
//! the minimum-norm solution (thesis eq. (6.14)) and N an n × r basis of the null space of W,
//! r = n − DOF the redundancy.
//!
//! **How N is chosen.** We factor Wᵀ P = Q R by Householder QR with column pivoting (P permutes
//! the wrench rows, which does not change the null space), and take N = the last r columns of Q:
//! an *orthonormal* basis (Nᵀ N = I). Then ‖λ‖ = ‖t − t0‖ and t0 ⟂ N, so the minimum-‖t‖₂
//! problem becomes "project the origin onto the feasible set in λ-space". Any other basis N' = N M
//! (M invertible) gives the same tension sets and the same optimal tensions for every method
//! defined by an objective on t (l1, l2, linf, ...); the barycentre is an area centroid, which an
//! affine map preserves, so it does not depend on the basis either (tests check both).
//!
//! **Singularity.** With the QR, √det(W Wᵀ) = Π|R_kk|. We use the Hadamard ratio
//! ρ = √det(W Wᵀ) / Π_k ‖row_k(W)‖ ∈ [0, 1] (invariant to the scale of each wrench row, so to the
//! length unit), and report `condition = 1/ρ`; W counts as singular when ρ < 10⁻¹⁰.
//!
//! ## References
//! - Picard, Caro, Plestan & Claveau 2020, eqs. (5)–(6). Thesis eq. (6.14).
//! - Golub & Van Loan, *Matrix Computations*, §5.4.1 (QR with column pivoting).

use nalgebra::{DMatrix, DVector};

/// Hadamard ratios below this count as a singular wrench matrix (condition above 10¹⁰).
pub const SINGULARITY_RATIO: f64 = 1e-10;

/// Reusable buffers for t = t0 + N λ (no allocation once sized).
#[derive(Debug, Clone, Default)]
pub(crate) struct NullSpace {
    /// DOF (rows of W).
    pub m: usize,
    /// Cables (columns of W).
    pub n: usize,
    /// Householder vectors and R (n × m, column-major copy of Wᵀ).
    a: Vec<f64>,
    beta: Vec<f64>,
    rdiag: Vec<f64>,
    perm: Vec<usize>,
    /// t0 = −W⁺ w_ext.
    pub t0: Vec<f64>,
    /// N, n × r column-major.
    pub basis: Vec<f64>,
    /// g = Nᵀ t0 (zero up to rounding).
    pub g: Vec<f64>,
    /// Scratch of length n.
    x: Vec<f64>,
    rows: Vec<f64>,
    /// Hadamard ratio ρ of the last factorisation.
    pub ratio: f64,
}

impl NullSpace {
    /// Redundancy r = n − m (callers guarantee n ≥ m).
    pub fn r(&self) -> usize {
        self.n - self.m
    }

    /// Row `i` of N (entries for cable i), as (N_i1, N_i2) padded with zeros for r < 2.
    #[inline]
    pub fn row2(&self, i: usize) -> [f64; 2] {
        let r = self.r();
        let n = self.n;
        match r {
            0 => [0.0, 0.0],
            1 => [self.basis[i], 0.0],
            _ => [self.basis[i], self.basis[n + i]],
        }
    }

    /// Tension of cable `i` at λ (only the first min(r, 2) components of λ are used).
    #[inline]
    pub fn tension2(&self, i: usize, l: [f64; 2]) -> f64 {
        let a = self.row2(i);
        self.t0[i] + a[0] * l[0] + a[1] * l[1]
    }

    /// Factor W and compute t0, N, g. Returns `Err(condition)` when W is singular
    /// (ρ < [`SINGULARITY_RATIO`]). Requires n ≥ m ≥ 1 and finite input.
    pub fn compute(&mut self, w: &DMatrix<f64>, w_ext: &DVector<f64>) -> Result<(), f64> {
        match w.shape() {
            (6, 8) => self.compute_fixed::<6, 8>(w, w_ext),
            (6, 7) => self.compute_fixed::<6, 7>(w, w_ext),
            (3, 5) => self.compute_fixed::<3, 5>(w, w_ext),
            (3, 4) => self.compute_fixed::<3, 4>(w, w_ext),
            _ => self.compute_dyn(w, w_ext),
        }
    }

    /// [`Self::compute`] for W of shape M × N known at compile time (the common spatial and
    /// planar shapes with r ≤ 2): the same Householder steps, the same sums in the same order
    /// (bit-identical results), on stack arrays the compiler can unroll.
    #[inline(never)]
    fn compute_fixed<const M: usize, const N: usize>(
        &mut self,
        w: &DMatrix<f64>,
        w_ext: &DVector<f64>,
    ) -> Result<(), f64> {
        debug_assert_eq!(w.shape(), (M, N));
        let r = N - M;
        self.m = M;
        self.n = N;
        self.t0.resize(N, 0.0);
        self.basis.resize(N * r, 0.0);
        self.g.resize(r, 0.0);
        let ws = w.as_slice();
        // a[k] = row k of W (column k of Wᵀ).
        let mut a = [[0.0f64; N]; M];
        let mut rows = [0.0f64; M];
        let mut perm = [0usize; M];
        let mut beta = [0.0f64; M];
        let mut rdiag = [0.0f64; M];
        for k in 0..M {
            let mut s = 0.0;
            for i in 0..N {
                let v = ws[i * M + k];
                a[k][i] = v;
                s += v * v;
            }
            if s == 0.0 {
                self.ratio = 0.0;
                return Err(f64::INFINITY);
            }
            rows[k] = s.sqrt();
            perm[k] = k;
        }
        let mut ratio = 1.0;
        for k in 0..M {
            let mut best = k;
            let mut best_norm = -1.0;
            for (j, col) in a.iter().enumerate().skip(k) {
                let s: f64 = col[k..].iter().map(|v| v * v).sum();
                if s > best_norm {
                    best_norm = s;
                    best = j;
                }
            }
            if best != k {
                a.swap(k, best);
                perm.swap(k, best);
            }
            let norm = best_norm.sqrt();
            if norm == 0.0 {
                self.ratio = 0.0;
                return Err(f64::INFINITY);
            }
            let x0 = a[k][k];
            let alpha = if x0 >= 0.0 { -norm } else { norm };
            a[k][k] = x0 - alpha;
            let vtv: f64 = a[k][k..].iter().map(|v| v * v).sum();
            let bk = 2.0 / vtv;
            beta[k] = bk;
            rdiag[k] = alpha;
            ratio *= norm / rows[k];
            let v = a[k];
            for col in a.iter_mut().skip(k + 1) {
                let mut s = 0.0;
                for i in k..N {
                    s += v[i] * col[i];
                }
                s *= bk;
                for i in k..N {
                    col[i] -= s * v[i];
                }
            }
        }
        self.ratio = ratio.min(1.0);
        if self.ratio.is_nan() || self.ratio < SINGULARITY_RATIO {
            return Err(1.0 / self.ratio);
        }
        // x ← Q x = H₀ H₁ ⋯ H_{M−1} x.
        let apply_q = |x: &mut [f64; N]| {
            for k in (0..M).rev() {
                let v = &a[k][k..];
                let xs = &mut x[k..];
                let s: f64 = v.iter().zip(xs.iter()).map(|(a, b)| a * b).sum::<f64>() * beta[k];
                for (xi, vi) in xs.iter_mut().zip(v) {
                    *xi -= s * vi;
                }
            }
        };
        let mut x = [0.0f64; N];
        for j in 0..M {
            let mut s = -w_ext[perm[j]];
            for i in 0..j {
                s -= a[j][i] * x[i];
            }
            x[j] = s / rdiag[j];
        }
        apply_q(&mut x);
        self.t0.copy_from_slice(&x);
        for c in 0..r {
            let mut x = [0.0f64; N];
            x[M + c] = 1.0;
            apply_q(&mut x);
            self.basis[c * N..(c + 1) * N].copy_from_slice(&x);
            self.g[c] = x.iter().zip(&self.t0).map(|(a, b)| a * b).sum();
        }
        Ok(())
    }

    /// [`Self::compute`] for any shape, on the reused heap buffers.
    fn compute_dyn(&mut self, w: &DMatrix<f64>, w_ext: &DVector<f64>) -> Result<(), f64> {
        let (m, n) = w.shape();
        self.m = m;
        self.n = n;
        let r = n - m;
        self.a.resize(n * m, 0.0);
        self.beta.resize(m, 0.0);
        self.rdiag.resize(m, 0.0);
        self.perm.resize(m, 0);
        self.t0.resize(n, 0.0);
        self.basis.resize(n * r, 0.0);
        self.g.resize(r, 0.0);
        self.x.resize(n, 0.0);
        self.rows.resize(m, 0.0);
        // a = Wᵀ, column k = row k of W.
        for k in 0..m {
            let mut s = 0.0;
            for i in 0..n {
                let v = w[(k, i)];
                self.a[k * n + i] = v;
                s += v * v;
            }
            if s == 0.0 {
                self.ratio = 0.0;
                return Err(f64::INFINITY);
            }
            self.rows[k] = s.sqrt();
            self.perm[k] = k;
        }
        let mut ratio = 1.0;
        for k in 0..m {
            // Pivot: the remaining column with the largest norm below row k.
            let mut best = k;
            let mut best_norm = -1.0;
            for j in k..m {
                let col = &self.a[j * n + k..j * n + n];
                let s: f64 = col.iter().map(|v| v * v).sum();
                if s > best_norm {
                    best_norm = s;
                    best = j;
                }
            }
            if best != k {
                for i in 0..n {
                    self.a.swap(k * n + i, best * n + i);
                }
                self.perm.swap(k, best);
            }
            let norm = best_norm.sqrt();
            if norm == 0.0 {
                self.ratio = 0.0;
                return Err(f64::INFINITY);
            }
            let x0 = self.a[k * n + k];
            let alpha = if x0 >= 0.0 { -norm } else { norm };
            self.a[k * n + k] = x0 - alpha;
            let vtv: f64 = self.a[k * n + k..k * n + n].iter().map(|v| v * v).sum();
            let beta = 2.0 / vtv;
            self.beta[k] = beta;
            self.rdiag[k] = alpha;
            ratio *= norm / self.rows[k];
            for j in k + 1..m {
                let mut s = 0.0;
                for i in k..n {
                    s += self.a[k * n + i] * self.a[j * n + i];
                }
                s *= beta;
                for i in k..n {
                    self.a[j * n + i] -= s * self.a[k * n + i];
                }
            }
        }
        self.ratio = ratio.min(1.0);
        if self.ratio.is_nan() || self.ratio < SINGULARITY_RATIO {
            return Err(1.0 / self.ratio);
        }
        // Rᵀ y = −(Pᵀ w_ext): forward substitution; y goes into x[0..m].
        for j in 0..m {
            let mut s = -w_ext[self.perm[j]];
            for i in 0..j {
                s -= self.a[j * n + i] * self.x[i];
            }
            self.x[j] = s / self.rdiag[j];
        }
        for v in &mut self.x[m..] {
            *v = 0.0;
        }
        self.apply_q();
        self.t0.copy_from_slice(&self.x);
        for c in 0..r {
            self.x.fill(0.0);
            self.x[m + c] = 1.0;
            self.apply_q();
            self.basis[c * n..(c + 1) * n].copy_from_slice(&self.x);
            self.g[c] = self.x.iter().zip(&self.t0).map(|(a, b)| a * b).sum();
        }
        Ok(())
    }

    /// x ← Q x = H₀ H₁ ⋯ H_{m−1} x.
    fn apply_q(&mut self) {
        let n = self.n;
        for k in (0..self.m).rev() {
            let v = &self.a[k * n + k..k * n + n];
            let xs = &mut self.x[k..];
            let s: f64 = v.iter().zip(xs.iter()).map(|(a, b)| a * b).sum::<f64>() * self.beta[k];
            for (xi, vi) in xs.iter_mut().zip(v) {
                *xi -= s * vi;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn null_space_is_orthonormal_and_t0_is_minimum_norm() {
        let w = DMatrix::from_row_slice(2, 4, &[1.0, -1.0, 0.5, 0.0, 0.2, 0.3, -1.0, 1.0]);
        let we = DVector::from_vec(vec![0.3, -2.0]);
        let mut ns = NullSpace::default();
        ns.compute(&w, &we).unwrap();
        let n = DMatrix::from_column_slice(4, 2, &ns.basis);
        assert!((n.transpose() * &n - DMatrix::identity(2, 2)).norm() < 1e-14);
        assert!((&w * &n).norm() < 1e-14);
        let t0 = DVector::from_column_slice(&ns.t0);
        assert!((&w * &t0 + &we).norm() < 1e-14);
        // Minimum norm: equals the pseudo-inverse solution computed independently.
        let pinv = w.clone().pseudo_inverse(1e-14).unwrap();
        assert!((t0 + pinv * we).norm() < 1e-13);
    }

    /// The fixed-size factorisation repeats the dynamic one bit for bit (same steps, same
    /// order of the sums), including the singularity verdicts.
    #[test]
    fn fixed_sizes_match_the_dynamic_path_bit_for_bit() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for (m, n) in [(6, 8), (6, 7), (3, 5), (3, 4)] {
            for case in 0..200 {
                let mut w = DMatrix::from_fn(m, n, |_, _| next());
                if case % 50 == 7 {
                    // A singular W: two equal rows.
                    let row = w.row(0).into_owned();
                    w.row_mut(m - 1).copy_from(&row);
                }
                let we = DVector::from_fn(m, |_, _| 100.0 * next());
                let (mut fixed, mut dynamic) = (NullSpace::default(), NullSpace::default());
                let a = fixed.compute(&w, &we);
                let b = dynamic.compute_dyn(&w, &we);
                assert_eq!(
                    a.map_err(f64::to_bits),
                    b.map_err(f64::to_bits),
                    "{m}x{n} {case}"
                );
                assert_eq!(fixed.ratio.to_bits(), dynamic.ratio.to_bits());
                if a.is_ok() {
                    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                    assert_eq!(bits(&fixed.t0), bits(&dynamic.t0), "{m}x{n} {case}");
                    assert_eq!(bits(&fixed.basis), bits(&dynamic.basis), "{m}x{n} {case}");
                    assert_eq!(bits(&fixed.g), bits(&dynamic.g), "{m}x{n} {case}");
                }
            }
        }
    }

    #[test]
    fn rank_deficiency_is_detected() {
        let w = DMatrix::from_row_slice(2, 3, &[1.0, 2.0, 3.0, 2.0, 4.0, 6.0]);
        let mut ns = NullSpace::default();
        assert!(ns.compute(&w, &DVector::zeros(2)).is_err());
        let w = DMatrix::from_row_slice(2, 3, &[1.0, 2.0, 3.0, 0.0, 0.0, 0.0]);
        assert_eq!(ns.compute(&w, &DVector::zeros(2)), Err(f64::INFINITY));
    }
}
