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

    #[test]
    fn rank_deficiency_is_detected() {
        let w = DMatrix::from_row_slice(2, 3, &[1.0, 2.0, 3.0, 2.0, 4.0, 6.0]);
        let mut ns = NullSpace::default();
        assert!(ns.compute(&w, &DVector::zeros(2)).is_err());
        let w = DMatrix::from_row_slice(2, 3, &[1.0, 2.0, 3.0, 0.0, 0.0, 0.0]);
        assert_eq!(ns.compute(&w, &DVector::zeros(2)), Err(f64::INFINITY));
    }
}
