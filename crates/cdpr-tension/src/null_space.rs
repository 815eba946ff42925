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
//! **Four at a time.** `four_6x8` factors four 6 × 8 wrench matrices in SIMD lanes (AVX2
//! chosen at run time, a portable build otherwise) with the operations of the fixed-size path in
//! the same order, so each lane's t0, N, g and ρ are those of `NullSpace::compute` bit for bit
//! (workspace grids, `TensionSolver::is_feasible_four_6x8`). The lanes are those of
//! [`crate::lanes`].
//!
//! ## References
//! - Picard, Caro, Plestan & Claveau 2020, eqs. (5)–(6). Thesis eq. (6.14).
//! - Golub & Van Loan, *Matrix Computations*, §5.4.1 (QR with column pivoting).

#[cfg(target_arch = "x86_64")]
use crate::lanes::Avx2;
use crate::lanes::{F64x4, Portable};
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
    /// Whether `a`, `beta`, `rdiag` and `perm` hold the QR of the last factorisation (the
    /// dynamic path and [`FourNullSpaces::write_lane`]; the fixed-size path keeps it on the
    /// stack, see [`Self::keep_qr`]).
    qr: bool,
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

    /// t = t0 + N λ for any r (λ of length r).
    #[inline]
    pub fn tensions(&self, lambda: &[f64], t: &mut [f64]) {
        let n = self.n;
        t.copy_from_slice(&self.t0);
        for (j, &l) in lambda.iter().enumerate() {
            for (ti, nij) in t.iter_mut().zip(&self.basis[j * n..(j + 1) * n]) {
                *ti += nij * l;
            }
        }
    }

    /// λ = Nᵀ (x − t0) = Nᵀ x − g: the coordinates of the projection of x onto the
    /// equilibrium set t0 + range(N) (N orthonormal).
    #[inline]
    pub fn coordinates(&self, x: &[f64], lambda: &mut [f64]) {
        let n = self.n;
        for (j, l) in lambda.iter_mut().enumerate() {
            let col = &self.basis[j * n..(j + 1) * n];
            *l = col.iter().zip(x).map(|(a, b)| a * b).sum::<f64>() - self.g[j];
        }
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
        self.qr = false;
        self.t0.resize(N, 0.0);
        self.basis.resize(N * r, 0.0);
        self.g.resize(r, 0.0);
        let ws = w.as_slice();
        // qr.0[k] = row k of W (column k of Wᵀ), reduced in place; qr.1 the row permutation.
        let mut qr: FixedQr<M, N> = ([[0.0f64; N]; M], [0usize; M], [0.0; M], [0.0; M]);
        let mut rows = [0.0f64; M];
        for k in 0..M {
            let mut s = 0.0;
            for i in 0..N {
                let v = ws[i * M + k];
                qr.0[k][i] = v;
                s += v * v;
            }
            if s == 0.0 {
                self.ratio = 0.0;
                return Err(f64::INFINITY);
            }
            rows[k] = s.sqrt();
            qr.1[k] = k;
        }
        let mut ratio = 1.0;
        // The M steps, each with its K known at compile time (loops of fixed length, fully
        // unrolled); steps K ≥ M do nothing.
        const { assert!(M <= 6) };
        let regular = fixed_step::<0, M, N>(&mut qr, &rows, &mut ratio)
            && fixed_step::<1, M, N>(&mut qr, &rows, &mut ratio)
            && fixed_step::<2, M, N>(&mut qr, &rows, &mut ratio)
            && fixed_step::<3, M, N>(&mut qr, &rows, &mut ratio)
            && fixed_step::<4, M, N>(&mut qr, &rows, &mut ratio)
            && fixed_step::<5, M, N>(&mut qr, &rows, &mut ratio);
        let (a, perm, beta, rdiag) = (&qr.0, &qr.1, &qr.2, &qr.3);
        if !regular {
            self.ratio = 0.0;
            return Err(f64::INFINITY);
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
        self.qr = false;
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
        self.qr = true;
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

    /// Whether the QR of the last factorisation is stored ([`Self::row_space_solve`] applies).
    pub(crate) fn has_qr(&self) -> bool {
        self.qr
    }

    /// Makes the QR of `w` available to [`Self::row_space_solve`]: after the fixed-size path,
    /// factors `w` again by the dynamic path, which computes t0, N and g bit for bit as the
    /// fixed-size path did (tested), so nothing else changes. `w` and `w_ext` must be those of
    /// the last [`Self::compute`] (or `write_lane`) and that call must have succeeded.
    pub(crate) fn keep_qr(&mut self, w: &DMatrix<f64>, w_ext: &DVector<f64>) -> Result<(), f64> {
        if self.qr {
            return Ok(());
        }
        self.compute_dyn(w, w_ext)
    }

    /// y = (W Wᵀ)⁻¹ W c, the least-squares solution of Wᵀ y = c (exact for c in the row space
    /// of W, i.e. c ⟂ N), for W of M × N: with Wᵀ P = Q R, W Wᵀ = P Rᵀ R Pᵀ and
    /// W c = P Rᵀ Q₁ᵀ c, so y = P R⁻¹ (Qᵀ c)₁..ₘ: M Householder reflections and one back
    /// substitution, no Gram matrix. `None` without a stored QR of that shape
    /// ([`Self::keep_qr`]).
    // Triangular index loops read as the textbook back substitution.
    #[allow(clippy::needless_range_loop)]
    #[inline(always)]
    pub(crate) fn row_space_solve<const M: usize, const N: usize>(
        &self,
        c: &[f64; N],
    ) -> Option<[f64; M]> {
        if !self.qr || self.m != M || self.n != N {
            return None;
        }
        let (a, beta, rdiag, perm) = (
            &self.a[..M * N],
            &self.beta[..M],
            &self.rdiag[..M],
            &self.perm[..M],
        );
        // q = Qᵀ c = H_{M−1} ⋯ H₀ c.
        let mut q = *c;
        for k in 0..M {
            let mut s = 0.0;
            for i in k..N {
                s += a[k * N + i] * q[i];
            }
            let s = s * beta[k];
            for i in k..N {
                q[i] -= s * a[k * N + i];
            }
        }
        // R z = q₁..ₘ (R(i, j) = a[j N + i] above the diagonal), then y = P z.
        let mut z = [0.0; M];
        for j in (0..M).rev() {
            let mut s = q[j];
            for i in j + 1..M {
                s -= a[i * N + j] * z[i];
            }
            z[j] = s / rdiag[j];
        }
        let mut y = [0.0; M];
        for j in 0..M {
            y[perm[j]] = z[j];
        }
        Some(y)
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

/// The QR under way in [`NullSpace::compute_fixed`]: rows of W being reduced (`a[k]` = column k
/// of Wᵀ), row permutation, β and the diagonal of R.
type FixedQr<const M: usize, const N: usize> = ([[f64; N]; M], [usize; M], [f64; M], [f64; M]);

/// Step `K` of the Householder QR with column pivoting of [`NullSpace::compute_fixed`] (nothing
/// for K ≥ M): the pivot, the reflection and its application to the remaining columns, the
/// operations of the textbook loop in its order (the sums of `Iterator::sum` start at −0).
/// `false` for a zero pivot.
#[inline(always)]
fn fixed_step<const K: usize, const M: usize, const N: usize>(
    (a, perm, beta, rdiag): &mut FixedQr<M, N>,
    rows: &[f64; M],
    ratio: &mut f64,
) -> bool {
    if K >= M {
        return true;
    }
    // Pivot: the first remaining column with the largest norm below row K.
    let mut best = K;
    let mut best_norm = -1.0;
    for (j, col) in a.iter().enumerate().skip(K) {
        let s: f64 = col[K..].iter().map(|v| v * v).sum();
        if s > best_norm {
            best_norm = s;
            best = j;
        }
    }
    if best != K {
        a.swap(K, best);
        perm.swap(K, best);
    }
    let norm = best_norm.sqrt();
    if norm == 0.0 {
        return false;
    }
    let x0 = a[K][K];
    let alpha = if x0 >= 0.0 { -norm } else { norm };
    a[K][K] = x0 - alpha;
    let vtv: f64 = a[K][K..].iter().map(|v| v * v).sum();
    let bk = 2.0 / vtv;
    beta[K] = bk;
    rdiag[K] = alpha;
    *ratio *= norm / rows[K];
    let v = a[K];
    for col in a.iter_mut().skip(K + 1) {
        let mut s = 0.0;
        for i in K..N {
            s += v[i] * col[i];
        }
        s *= bk;
        for i in K..N {
            col[i] -= s * v[i];
        }
    }
    true
}

/// Poses per group of `four_6x8` and `TensionSolver::is_feasible_four_6x8` (four f64 lanes: one
/// AVX2 register).
pub const LANES: usize = 4;

/// One f64 per pose of a group.
type Lanes = [f64; LANES];

/// One all-ones (true) or all-zeros (false) word per lane.
type Mask = [u64; LANES];

/// The all-ones word for `true`, zero for `false`.
#[inline(always)]
fn mask(b: bool) -> u64 {
    0u64.wrapping_sub(u64::from(b))
}

/// What [`four_6x8`] computed for each of four 6 × 8 wrench matrices, lane by lane: what
/// [`NullSpace::compute`] computes for each alone.
pub(crate) struct FourNullSpaces {
    /// t0, one lane per pose.
    pub(crate) t0: [Lanes; 8],
    /// The two columns of N.
    pub(crate) basis: [[Lanes; 8]; 2],
    /// g = Nᵀ t0.
    pub(crate) g: [Lanes; 2],
    /// Hadamard ratio (0 after a zero row or pivot).
    pub(crate) ratio: Lanes,
    /// A zero row or pivot (condition ∞).
    pub(crate) zero: Mask,
}

/// The QR of Wᵀ that [`four_6x8`] computed, lane by lane, as `NullSpace` stores it:
/// Householder vectors and R (`a[k][i]`), β, the diagonal of R and the pivot column chosen at
/// each step. Kept apart from [`FourNullSpaces`] because only a proof of infeasibility reads it
/// ([`FourQr::write_lane`]).
#[derive(Debug, Clone, Default)]
pub(crate) struct FourQr {
    a: [[Lanes; 8]; 6],
    beta: [Lanes; 6],
    rdiag: [Lanes; 6],
    pivots: [Lanes; 6],
}

impl FourQr {
    /// Writes the QR of lane `l` into `ns`, whose t0, N and g are that lane's
    /// ([`FourNullSpaces::write_lane`] succeeded): then [`NullSpace::row_space_solve`] applies.
    pub(crate) fn write_lane(&self, l: usize, ns: &mut NullSpace) {
        ns.a.resize(48, 0.0);
        ns.beta.resize(6, 0.0);
        ns.rdiag.resize(6, 0.0);
        ns.perm.resize(6, 0);
        for (k, row) in self.a.iter().enumerate() {
            for (d, x) in ns.a[k * 8..k * 8 + 8].iter_mut().zip(row) {
                *d = x[l];
            }
            ns.beta[k] = self.beta[k][l];
            ns.rdiag[k] = self.rdiag[k][l];
            ns.perm[k] = k;
        }
        // The exchanges of the pivoting, in order (as `compute_fixed` applies them).
        for k in 0..6 {
            ns.perm.swap(k, self.pivots[k][l] as usize);
        }
        ns.qr = true;
    }
}

impl FourNullSpaces {
    /// Writes lane `l` into `ns`, as [`NullSpace::compute`] would have: `Err(condition)` for a
    /// singular W.
    pub(crate) fn write_lane(&self, l: usize, ns: &mut NullSpace) -> Result<(), f64> {
        ns.m = 6;
        ns.n = 8;
        ns.qr = false;
        ns.t0.resize(8, 0.0);
        ns.basis.resize(16, 0.0);
        ns.g.resize(2, 0.0);
        if self.zero[l] != 0 {
            ns.ratio = 0.0;
            return Err(f64::INFINITY);
        }
        ns.ratio = self.ratio[l];
        if ns.ratio.is_nan() || ns.ratio < SINGULARITY_RATIO {
            return Err(1.0 / ns.ratio);
        }
        for i in 0..8 {
            ns.t0[i] = self.t0[i][l];
            ns.basis[i] = self.basis[0][i][l];
            ns.basis[8 + i] = self.basis[1][i][l];
        }
        ns.g[0] = self.g[0][l];
        ns.g[1] = self.g[1][l];
        Ok(())
    }
}

/// Whether [`four_6x8`] runs its AVX2 build (checked once).
fn avx2() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        static AVX2: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
        *AVX2.get_or_init(|| std::arch::is_x86_feature_detected!("avx2"))
    }
    #[cfg(not(target_arch = "x86_64"))]
    false
}

/// [`NullSpace::compute`] of four 6 × 8 wrench matrices at once, `columns[j][i][l]` = W(i, j)
/// of pose l (the layout of `Robot::wrench_matrix_lanes`), for one external wrench: the
/// operations of the fixed-size path, in the same order, on the four poses in SIMD lanes, hence
/// the same bits (no fused multiply–adds, which Rust never forms; square roots and divisions
/// are correctly rounded). Each lane keeps its own column pivots: exchanges are bitwise blends.
/// The AVX2 build is chosen at run time; [`four_6x8_portable`] is the same code for baseline
/// x86-64.
pub(crate) fn four_6x8(
    columns: &[[Lanes; 6]; 8],
    w_ext: &[f64],
    qr: &mut FourQr,
) -> FourNullSpaces {
    #[cfg(target_arch = "x86_64")]
    if avx2() {
        // SAFETY: the CPU supports AVX2 (run-time detection).
        return unsafe { four_6x8_avx2(columns, w_ext, qr) };
    }
    four_6x8_portable(columns, w_ext, qr)
}

/// [`four_6x8`] compiled for AVX2.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn four_6x8_avx2(
    columns: &[[Lanes; 6]; 8],
    w_ext: &[f64],
    qr: &mut FourQr,
) -> FourNullSpaces {
    // SAFETY: the CPU supports AVX2 (this function's contract).
    four_6x8_body(unsafe { Avx2::new_unchecked() }, columns, w_ext, qr)
}

/// [`four_6x8`] for baseline x86-64 (and the reference of the AVX2 build in tests).
pub(crate) fn four_6x8_portable(
    columns: &[[Lanes; 6]; 8],
    w_ext: &[f64],
    qr: &mut FourQr,
) -> FourNullSpaces {
    four_6x8_body(Portable([0.0; LANES]), columns, w_ext, qr)
}

/// The body of [`four_6x8`] on the lanes of `V` (`v` witnesses that its instructions are
/// available): one lane operation per scalar operation, no closures.
#[inline(always)]
fn four_6x8_body<V: F64x4>(
    v: V,
    columns: &[[Lanes; 6]; 8],
    w_ext: &[f64],
    qr: &mut FourQr,
) -> FourNullSpaces {
    const M: usize = 6;
    const N: usize = 8;
    // a[k] = row k of W; wp[k] = w_ext at the row now in place k (pivot exchanges).
    let mut a = [[v.splat(0.0); N]; M];
    let mut rows = [v.splat(0.0); M];
    let mut wp = [v.splat(0.0); M];
    let mut zero = v.mask(false);
    for k in 0..M {
        let mut s = v.splat(0.0);
        for i in 0..N {
            let x = v.load(columns[i][k]);
            a[k][i] = x;
            s = s.add(x.mul(x));
        }
        zero = V::or(zero, s.eq(v.splat(0.0)));
        rows[k] = s.sqrt();
        wp[k] = v.splat(w_ext[k]);
    }
    let mut beta = [v.splat(0.0); M];
    let mut rdiag = [v.splat(0.0); M];
    let mut ratio = v.splat(1.0);
    let p0 = householder_step::<0, V>(
        &mut a, &mut wp, &rows, &mut beta, &mut rdiag, &mut ratio, &mut zero,
    );
    let p1 = householder_step::<1, V>(
        &mut a, &mut wp, &rows, &mut beta, &mut rdiag, &mut ratio, &mut zero,
    );
    let p2 = householder_step::<2, V>(
        &mut a, &mut wp, &rows, &mut beta, &mut rdiag, &mut ratio, &mut zero,
    );
    let p3 = householder_step::<3, V>(
        &mut a, &mut wp, &rows, &mut beta, &mut rdiag, &mut ratio, &mut zero,
    );
    let p4 = householder_step::<4, V>(
        &mut a, &mut wp, &rows, &mut beta, &mut rdiag, &mut ratio, &mut zero,
    );
    let p5 = householder_step::<5, V>(
        &mut a, &mut wp, &rows, &mut beta, &mut rdiag, &mut ratio, &mut zero,
    );
    // `f64::min(ratio, 1.0)`, NaN included (see `F64x4::min`).
    let ratio = ratio.min(v.splat(1.0));
    let mut t0 = [v.splat(0.0); N];
    for j in 0..M {
        let mut s = wp[j].neg();
        for i in 0..j {
            s = s.sub(a[j][i].mul(t0[i]));
        }
        t0[j] = s.div(rdiag[j]);
    }
    apply_q(v, &a, &beta, &mut t0);
    let mut basis = [[v.splat(0.0); N]; 2];
    let mut g = [v.splat(0.0); 2];
    for c in 0..2 {
        let x = &mut basis[c];
        x[M + c] = v.splat(1.0);
        apply_q(v, &a, &beta, x);
        let mut s = v.splat(-0.0);
        for i in 0..N {
            s = s.add(x[i].mul(t0[i]));
        }
        g[c] = s;
    }
    let mut out = FourNullSpaces {
        t0: [[0.0; LANES]; N],
        basis: [[[0.0; LANES]; N]; 2],
        g: [g[0].to_array(), g[1].to_array()],
        ratio: ratio.to_array(),
        zero: [0; LANES],
    };
    // Loops, not `array::map`: a closure would lose this kernel's target features.
    let pivots = [p0, p1, p2, p3, p4, p5];
    for k in 0..M {
        for (dst, x) in qr.a[k].iter_mut().zip(&a[k]) {
            *dst = x.to_array();
        }
        qr.beta[k] = beta[k].to_array();
        qr.rdiag[k] = rdiag[k].to_array();
        qr.pivots[k] = pivots[k].to_array();
    }
    for i in 0..N {
        out.t0[i] = t0[i].to_array();
        out.basis[0][i] = basis[0][i].to_array();
        out.basis[1][i] = basis[1][i].to_array();
    }
    for (z, is) in out.zero.iter_mut().zip(V::to_bools(zero)) {
        *z = mask(is);
    }
    out
}

/// x ← Q x = H₀ H₁ ⋯ H₅ x, lane by lane (the sums of `Iterator::sum`, which start at −0).
#[inline(always)]
fn apply_q<V: F64x4>(v: V, a: &[[V; 8]; 6], beta: &[V; 6], x: &mut [V; 8]) {
    for k in (0..6).rev() {
        let mut s = v.splat(-0.0);
        for i in k..8 {
            s = s.add(a[k][i].mul(x[i]));
        }
        let s = s.mul(beta[k]);
        for i in k..8 {
            x[i] = x[i].sub(s.mul(a[k][i]));
        }
    }
}

/// Step `K` of the Householder QR with column pivoting of [`NullSpace::compute_fixed`] (6 × 8),
/// lane by lane (any lane value, here `rows[0]`, witnesses `V`'s instructions); returns the
/// pivot column exchanged with column `K`.
#[inline(always)]
fn householder_step<const K: usize, V: F64x4>(
    a: &mut [[V; 8]; 6],
    wp: &mut [V; 6],
    rows: &[V; 6],
    beta: &mut [V; 6],
    rdiag: &mut [V; 6],
    ratio: &mut V,
    zero: &mut V::Mask,
) -> V {
    let w = rows[0];
    // Pivot: the first remaining column with the largest norm below row K (`>`, as the scan).
    let mut best = w.splat(K as f64);
    let mut best_norm = w.splat(-1.0);
    for (j, col) in a.iter().enumerate().skip(K) {
        let mut s = w.splat(-0.0);
        for x in &col[K..] {
            s = s.add(x.mul(*x));
        }
        let take = s.gt(best_norm);
        best_norm = V::select(take, s, best_norm);
        best = V::select(take, w.splat(j as f64), best);
    }
    for j in K + 1..6 {
        let m = best.eq(w.splat(j as f64));
        let (head, tail) = a.split_at_mut(j);
        for (p, q) in head[K].iter_mut().zip(tail[0].iter_mut()) {
            let (x, y) = (*p, *q);
            *p = V::select(m, y, x);
            *q = V::select(m, x, y);
        }
        let (x, y) = (wp[K], wp[j]);
        wp[K] = V::select(m, y, x);
        wp[j] = V::select(m, x, y);
    }
    let norm = best_norm.sqrt();
    *zero = V::or(*zero, norm.eq(w.splat(0.0)));
    let x0 = a[K][K];
    let nonneg = x0.ge(w.splat(0.0));
    let alpha = V::select(nonneg, norm.neg(), norm);
    a[K][K] = x0.sub(alpha);
    let mut vtv = w.splat(-0.0);
    for x in &a[K][K..] {
        vtv = vtv.add(x.mul(*x));
    }
    let bk = w.splat(2.0).div(vtv);
    beta[K] = bk;
    rdiag[K] = alpha;
    *ratio = ratio.mul(norm.div(rows[K]));
    let v = a[K];
    for col in a.iter_mut().skip(K + 1) {
        let mut s = w.splat(0.0);
        for i in K..8 {
            s = s.add(v[i].mul(col[i]));
        }
        let s = s.mul(bk);
        for i in K..8 {
            col[i] = col[i].sub(s.mul(v[i]));
        }
    }
    best
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

    use proptest::prelude::*;

    /// An entry of W: mostly random, with small integers (ties among the pivot norms), signed
    /// zeros and tiny values.
    fn entry() -> impl Strategy<Value = f64> {
        prop_oneof![
            8 => -1.0f64..1.0,
            4 => (-2i32..=2).prop_map(f64::from),
            1 => Just(-0.0),
            1 => (-1.0f64..1.0).prop_map(|v| v * 1e-160),
        ]
    }

    /// Four 6 × 8 matrices in lanes (`columns[j][i][l]`), each made singular, rank-deficient,
    /// tied or non-finite in one of several ways by `shape[l]`, and an external wrench.
    fn four_problems() -> impl Strategy<Value = ([[[f64; LANES]; 6]; 8], Vec<f64>)> {
        (
            prop::collection::vec(entry(), 4 * 48),
            prop::collection::vec(0u8..12, 4),
            prop::collection::vec(prop_oneof![-100.0f64..100.0, Just(0.0), Just(-0.0)], 6),
            prop::bool::weighted(0.25),
        )
            .prop_map(|(values, shape, we, unloaded)| {
                // No load: t0 = ±0, whose signs reach g.
                let we = if unloaded {
                    we.iter().map(|v| v.signum() * 0.0).collect()
                } else {
                    we
                };
                let mut columns = [[[0.0; LANES]; 6]; 8];
                for l in 0..LANES {
                    let mut w: [[f64; 8]; 6] = std::array::from_fn(|i| {
                        std::array::from_fn(|j| values[l * 48 + i * 8 + j])
                    });
                    match shape[l] {
                        1 => w[5] = w[0],                   // two equal rows
                        2 => w[3] = w[1].map(|v| -2.0 * v), // proportional rows
                        3 => w[2] = [0.0; 8],               // a zero row
                        4 => w[4] = [-0.0; 8],
                        5 => {
                            // Rows that permute the same integers: equal norms, ties in the
                            // first pivot choice.
                            let base = w[0].map(|v| (3.0 * v).round());
                            w = std::array::from_fn(|k| std::array::from_fn(|j| base[(j + k) % 8]));
                        }
                        6 => w[1][3] = f64::NAN,
                        7 => w[4][6] = f64::NEG_INFINITY,
                        8 => w[0][0] = 1e300, // overflowing sums
                        _ => {}
                    }
                    for (i, row) in w.iter().enumerate() {
                        for (j, v) in row.iter().enumerate() {
                            columns[j][i][l] = *v;
                        }
                    }
                }
                (columns, we)
            })
    }

    /// The bits of a value; every NaN counts as one (the builds may differ in a NaN's sign,
    /// which no comparison sees).
    fn b(x: f64) -> u64 {
        if x.is_nan() {
            f64::NAN.to_bits()
        } else {
            x.to_bits()
        }
    }

    fn bits(v: &[f64]) -> Vec<u64> {
        v.iter().map(|&x| b(x)).collect()
    }

    /// Every output of a lane build, as bits.
    fn lane_bits((f, q): (&FourNullSpaces, &FourQr)) -> Vec<u64> {
        let mut out = Vec::new();
        for l in 0..LANES {
            out.extend(f.t0.iter().map(|v| b(v[l])));
            out.extend(f.basis.iter().flatten().map(|v| b(v[l])));
            out.extend(f.g.iter().map(|v| b(v[l])));
            out.push(b(f.ratio[l]));
            out.push(f.zero[l]);
            out.extend(q.a.iter().flatten().map(|v| b(v[l])));
            for x in [&q.beta, &q.rdiag, &q.pivots] {
                out.extend(x.iter().map(|v| b(v[l])));
            }
        }
        out
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2048))]

        /// The four-lane null space (AVX2 where the CPU has it, and the portable build) is
        /// bit for bit the single-problem one, verdicts and ratio included; the AVX2 build
        /// equals the portable one in every lane value.
        #[test]
        #[allow(clippy::needless_range_loop)]
        fn four_at_a_time_equals_one_at_a_time((columns, we) in four_problems()) {
            let (mut dispatched_qr, mut portable_qr) = (FourQr::default(), FourQr::default());
            let dispatched = four_6x8(&columns, &we, &mut dispatched_qr);
            let portable = four_6x8_portable(&columns, &we, &mut portable_qr);
            prop_assert_eq!(
                lane_bits((&dispatched, &dispatched_qr)),
                lane_bits((&portable, &portable_qr))
            );
            let we = DVector::from_vec(we);
            for l in 0..LANES {
                let w = DMatrix::from_fn(6, 8, |i, j| columns[j][i][l]);
                let mut one = NullSpace::default();
                let expected = one.compute(&w, &we);
                for (four, qr) in [(&dispatched, &dispatched_qr), (&portable, &portable_qr)] {
                    let mut ns = NullSpace::default();
                    let got = four.write_lane(l, &mut ns);
                    prop_assert_eq!(got.map_err(b), expected.map_err(b));
                    prop_assert_eq!(b(ns.ratio), b(one.ratio));
                    if expected.is_ok() {
                        prop_assert_eq!(bits(&ns.t0), bits(&one.t0));
                        prop_assert_eq!(bits(&ns.basis), bits(&one.basis));
                        prop_assert_eq!(bits(&ns.g), bits(&one.g));
                        // The QR the lanes hand over is the one `keep_qr` computes.
                        let mut kept = one.clone();
                        kept.keep_qr(&w, &we).unwrap();
                        prop_assert!(!ns.qr);
                        qr.write_lane(l, &mut ns);
                        prop_assert!(ns.qr && kept.qr);
                        prop_assert_eq!(bits(&ns.a), bits(&kept.a));
                        prop_assert_eq!(bits(&ns.beta), bits(&kept.beta));
                        prop_assert_eq!(bits(&ns.rdiag), bits(&kept.rdiag));
                        prop_assert_eq!(&ns.perm, &kept.perm);
                    }
                }
            }
        }
    }

    /// `keep_qr` after the fixed-size path changes no bit of t0, N and g, and
    /// `row_space_solve` returns y = (W Wᵀ)⁻¹ W c, checked against the normal equations
    /// solved by nalgebra's LU (an independent route), for c in the row space (Wᵀ y = c) and
    /// for a c off it.
    #[test]
    fn row_space_solve_is_the_least_squares_solution() {
        let mut next = crate::certificate::tests::uniform(0x2545_f491_4f6c_dd1d);
        for shape in [(6, 8), (3, 5), (2, 4)] {
            for _ in 0..200 {
                let w = DMatrix::from_fn(shape.0, shape.1, |_, _| 2.0 * next() - 1.0);
                let we = DVector::from_fn(shape.0, |_, _| 2.0 * next() - 1.0);
                let mut ns = NullSpace::default();
                if ns.compute(&w, &we).is_err() {
                    continue;
                }
                let (t0, basis, g) = (bits(&ns.t0), bits(&ns.basis), bits(&ns.g));
                let solve = |ns: &NullSpace, c: &[f64]| match shape {
                    (6, 8) => ns
                        .row_space_solve::<6, 8>(c.try_into().unwrap())
                        .map(|y| y.to_vec()),
                    (3, 5) => ns
                        .row_space_solve::<3, 5>(c.try_into().unwrap())
                        .map(|y| y.to_vec()),
                    _ => ns
                        .row_space_solve::<2, 4>(c.try_into().unwrap())
                        .map(|y| y.to_vec()),
                };
                let kept = solve(&ns, &vec![1.0; shape.1]).is_some();
                assert_eq!(kept, shape == (2, 4), "only the dynamic path keeps its QR");
                ns.keep_qr(&w, &we).unwrap();
                assert_eq!((bits(&ns.t0), bits(&ns.basis), bits(&ns.g)), (t0, basis, g));
                let y_true = DVector::from_fn(shape.0, |_, _| 2.0 * next() - 1.0);
                let off = DVector::from_fn(shape.1, |_, _| 2.0 * next() - 1.0);
                for c in [w.transpose() * &y_true, off] {
                    let y = solve(&ns, c.as_slice()).unwrap();
                    let reference = (&w * w.transpose()).lu().solve(&(&w * &c)).unwrap();
                    assert_eq!(y.len(), shape.0);
                    for k in 0..shape.0 {
                        assert!((y[k] - reference[k]).abs() < 1e-9, "{y:?} {reference}");
                    }
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
