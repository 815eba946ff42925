//! # Improved closed-form force distribution (Pott 2014)
//!
//! The closed-form method of Pott (2009) takes the mean feasible tension t_m = (t_min + t_max)/2
//! and the minimum-norm correction towards equilibrium:
//!
//! ```text
//!   t = t_m − W⁺ (w_ext + W t_m),     W⁺ = Wᵀ (W Wᵀ)⁻¹
//! ```
//!
//! i.e. t = t_m + N λ with the smallest λ. The *improved* variant (Pott 2014) repairs
//! infeasible answers: the cable with the largest violation of its limits (in force units,
//! max(t_min,i − t_i, t_i − t_max,i); ties to the lower index) is saturated at that limit, its
//! force is moved into the wrench (w' = w_ext + w_i t_i), and the closed form is recomputed for
//! the remaining cables from their own mean tensions, while at least DOF cables remain (with
//! exactly DOF the system is square and solved exactly); the method stops when all remaining
//! tensions are within their bounds (feasible) or when a violation remains with only DOF cables
//! left ([`Infeasibility::Inconclusive`]: the feasible set may still be non-empty; it is a fast
//! heuristic, not a complete solver). A violation means more than the certificate's tolerance
//! (10⁻⁹ relative). This is the iteration of Pott (2014) as also implemented in CASPR
//! (`id_cf_icfm`, absolute violation, 10⁻⁶ absolute tolerance); cdpyr instead saturates the
//! violating cable of largest |t_i|. `tests/it/improved_closed_form.rs` compares this
//! implementation with a direct transcription of the iteration (pseudo-inverse per step).
//! Needs finite t_max. The first step factors A Aᵀ = L D Lᵀ (square-root-free Cholesky,
//! DOF × DOF, with the reciprocal pivots 1/D_k kept so that the solves only multiply); each
//! saturation downdates that factor by the removed column in O(DOF²) (Gill, Golub, Murray &
//! Saunders 1974, method C1) rather than rebuilding and refactoring it, with a fresh
//! factorisation when the downdate would cancel most of a pivot (more than 99 %). Without square
//! roots and with one division per pivot, the chain of dependent operations (what bounds the
//! speed of one 6 × 8 solve) is about half that of a Cholesky factor with divisions.
//!
//! ## References
//! - Gill, P. E., Golub, G. H., Murray, W. & Saunders, M. A. (1974), *Methods for modifying
//!   matrix factorizations*, Mathematics of Computation 28(126), pp. 505–535 (method C1).
//! - Golub, G. H. & Van Loan, C. F. (2013), *Matrix Computations*, 4th ed., §4.1 (L D Lᵀ).
//! - Pott, A. (2014), *An improved force distribution algorithm for over-constrained
//!   cable-driven parallel robots*, Computational Kinematics, pp. 139–146.
//! - Pott, Bruckmann & Mikelsons (2009), *Closed-form force distribution for parallel wire
//!   robots*, Computational Kinematics, pp. 25–34.

use crate::certificate::bound_violation;
use crate::null_space::SINGULARITY_RATIO;
use crate::{Infeasibility, TensionProblem};

/// Buffers of the improved closed form.
#[derive(Debug, Clone, Default)]
pub(crate) struct ImprovedClosedForm {
    active: Vec<bool>,
    /// A Aᵀ, rhs and y for DOF other than 6 and 3.
    buf: Vec<f64>,
}

impl ImprovedClosedForm {
    /// Pott (2014) into `t` (callers ensure r ≥ 0 and finite t_max, see
    /// [`crate::TensionError::NeedsFiniteBounds`]). DOF 6 and 3 (and 6 × 8, the common spatial
    /// robot) run a copy of the iteration with the sizes fixed at compile time (stack buffers,
    /// unrolled loops, the same arithmetic); 6 × 8 compiled for AVX2 when the CPU has it (the
    /// same bits).
    pub fn solve(&mut self, problem: &TensionProblem, t: &mut [f64]) -> Result<(), Infeasibility> {
        self.solve_with(problem, t, true, detected_path(), Step::ITERATE, &mut [])
    }

    /// Only the first step: Pott, Bruckmann & Mikelsons (2009) eq. (9),
    /// t = t_m − Wᵀ (W Wᵀ)⁻¹ (w_ext + W t_m), from the same L D Lᵀ factor of W Wᵀ, into `t`
    /// (not checked against the bounds). With `d` of length n (else empty) also
    /// d = (I − W⁺ W) 1 = 1 − Wᵀ (W Wᵀ)⁻¹ (W 1), the energy-efficient shift's direction
    /// (module `pott_closed_form`). `Err` (nothing to rely on) when the factor fails or the
    /// Hadamard ratio ρ is below [`PLAIN_RATIO`]: the normal equations square the condition of
    /// W, so such poses go to the QR null space instead (the caller's fallback).
    pub fn first_step(
        &mut self,
        problem: &TensionProblem,
        t: &mut [f64],
        d: &mut [f64],
    ) -> Result<(), Infeasibility> {
        let step = Step {
            first_only: true,
            ratio_floor: PLAIN_RATIO,
            minimum_norm: false,
        };
        self.solve_with(problem, t, true, detected_path(), step, d)
    }

    /// [`Self::solve`], and the minimum-norm tensions t0 = −W⁺ w_ext = −Wᵀ (W Wᵀ)⁻¹ w_ext from
    /// the first step's factor into `t0` (length n): puncture's line start without a null-space
    /// basis. `t0` is NaN where that factor's Hadamard ratio is below [`PLAIN_RATIO`] (or when
    /// the first factor fails): then compute it on the QR null space.
    pub fn solve_and_minimum_norm(
        &mut self,
        problem: &TensionProblem,
        t: &mut [f64],
        t0: &mut [f64],
    ) -> Result<(), Infeasibility> {
        t0.fill(f64::NAN);
        let step = Step {
            minimum_norm: true,
            ..Step::ITERATE
        };
        self.solve_with(problem, t, true, detected_path(), step, t0)
    }

    /// [`Self::solve`] with the factor updated (`update`) or refactorised at every step, 6 × 8
    /// problems through the build `path`.
    fn solve_with(
        &mut self,
        problem: &TensionProblem,
        t: &mut [f64],
        update: bool,
        path: Path,
        step: Step,
        d: &mut [f64],
    ) -> Result<(), Infeasibility> {
        let (m, n) = problem.wrench_matrix.shape();
        self.active.clear();
        self.active.resize(n, true);
        let active = &mut self.active;
        match (m, n) {
            (6, 8) => match path {
                // SAFETY: `Avx2` is chosen only when the CPU reports AVX2 (`detected_path`, or
                // a test that checks it first).
                #[cfg(target_arch = "x86_64")]
                Path::Avx2 => unsafe { iterate_6x8_avx2(problem, active, t, update, step, d) },
                Path::Portable => {
                    let mut buf = [0.0; 6 * 6 + 4 * 6];
                    iterate::<6, 8>(problem, active, &mut buf, t, update, step, d)
                }
            },
            (6, _) => {
                let mut buf = [0.0; 6 * 6 + 4 * 6];
                iterate::<6, 0>(problem, active, &mut buf, t, update, step, d)
            }
            (3, _) => {
                let mut buf = [0.0; 3 * 3 + 4 * 3];
                iterate::<3, 0>(problem, active, &mut buf, t, update, step, d)
            }
            _ => {
                self.buf.resize(m * m + 4 * m, 0.0);
                iterate::<0, 0>(problem, active, &mut self.buf, t, update, step, d)
            }
        }
    }
}

/// Hadamard ratio below which [`ImprovedClosedForm::first_step`] declines (condition of W
/// roughly above 10³, so rounding in W Wᵀ stays below 10⁻¹⁰ relative): Pott's closed form then
/// runs on the QR null space, which decides singularity with [`SINGULARITY_RATIO`].
pub(crate) const PLAIN_RATIO: f64 = 1e-3;

/// How much of the iteration runs, and the Hadamard ratio it accepts.
#[derive(Debug, Clone, Copy)]
struct Step {
    /// Stop after the first closed form (Pott 2009), without checking the bounds.
    first_only: bool,
    /// Ratios below this are singular (first step) or inconclusive (later steps).
    ratio_floor: f64,
    /// Also write the minimum-norm tensions t0 = −Wᵀ (W Wᵀ)⁻¹ w_ext of the first factor into
    /// the side buffer (NaN there when its Hadamard ratio is below [`PLAIN_RATIO`]).
    minimum_norm: bool,
}

impl Step {
    /// Pott (2014): the whole iteration, singular below [`SINGULARITY_RATIO`].
    const ITERATE: Step = Step {
        first_only: false,
        ratio_floor: SINGULARITY_RATIO,
        minimum_norm: false,
    };
}

/// Which build of the 6 × 8 iteration runs: both compile the same source without fused
/// multiply–adds (Rust never contracts `a * b + c`), so they give the same bits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Path {
    /// Compiled for AVX2 (chosen at run time when the CPU has it).
    #[cfg(target_arch = "x86_64")]
    Avx2,
    /// Compiled for the baseline target (SSE2 on x86-64).
    Portable,
}

/// The fastest build this CPU runs (`is_x86_feature_detected!` caches its answer).
#[inline]
fn detected_path() -> Path {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        return Path::Avx2;
    }
    Path::Portable
}

/// [`iterate`] for 6 × 8 compiled for AVX2 (4-lane vectors; no FMA, the same bits).
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn iterate_6x8_avx2(
    problem: &TensionProblem,
    active: &mut [bool],
    t: &mut [f64],
    update: bool,
    step: Step,
    d: &mut [f64],
) -> Result<(), Infeasibility> {
    let mut buf = [0.0; 6 * 6 + 4 * 6];
    iterate::<6, 8>(problem, active, &mut buf, t, update, step, d)
}

/// Relative size of the downdated pivot below which the factor is recomputed instead:
/// D'_k / D_k ≥ 10⁻² (in Cholesky terms (L'_kk / L_kk)² ≥ 10⁻²) bounds the growth of rounding
/// in one step of the downdate by D_k / D'_k ≤ 100 (see [`downdate`]).
const DOWNDATE_MIN_RATIO: f64 = 1e-2;

/// The iteration of Pott (2014) for DOF m = M and n = N cables (0: read from W at run time).
/// `buf` holds A Aᵀ (m × m, row-major, lower triangle; then its factor L D Lᵀ, see [`ldl`]),
/// then rhs, y, the diagonal of A Aᵀ and the reciprocal pivots 1/D_k (m each).
///
/// When a cable j is saturated, A loses column w_j: A' A'ᵀ = A Aᵀ − w_j w_jᵀ, so (with
/// `update`) the factor is downdated in O(m²) instead of rebuilt (O(n m²)) and refactorised
/// (O(m³)), and rhs = w_ext + W t moves by w_j (t_j − t_m,j). A downdate that would cancel
/// more than [`DOWNDATE_MIN_RATIO`] of a pivot, or that fails, falls back to the fresh
/// factorisation of the reduced A Aᵀ, so near-singular steps keep the rounding of the plain
/// iteration. Answers move by rounding only; the verdict and the singularity rule are those of
/// the plain iteration (compared on random problems in the unit tests).
#[inline(always)]
fn iterate<const M: usize, const N: usize>(
    problem: &TensionProblem,
    active: &mut [bool],
    buf: &mut [f64],
    t: &mut [f64],
    update: bool,
    step: Step,
    d: &mut [f64],
) -> Result<(), Infeasibility> {
    const METHOD: &str = "improved-closed-form";
    let w = problem.wrench_matrix;
    let n = if N > 0 { N } else { w.ncols() };
    let m = if M > 0 { M } else { w.nrows() };
    debug_assert_eq!((w.nrows(), w.ncols()), (m, n));
    // Column-major W: W_ki = ws[i·m + k].
    let ws = &w.as_slice()[..m * n];
    let we = &problem.external_wrench.as_slice()[..m];
    let (aat, rest) = buf.split_at_mut(m * m);
    let (rhs, rest) = rest.split_at_mut(m);
    let (y, rest) = rest.split_at_mut(m);
    let (diag, inv_d) = rest.split_at_mut(m);
    let (y, diag, inv_d) = (&mut y[..m], &mut diag[..m], &mut inv_d[..m]);
    let (lo, hi) = (
        problem.bounds.min().as_slice(),
        problem.bounds.max().as_slice(),
    );
    let (lo, hi, t, active) = (&lo[..n], &hi[..n], &mut t[..n], &mut active[..n]);
    for i in 0..n {
        t[i] = 0.5 * (lo[i] + hi[i]);
    }
    let mut remaining = n;
    let mut first = true;
    // The cable saturated at the end of the last step, if its column is to be downdated.
    let mut saturated: Option<usize> = None;
    loop {
        let updated = match saturated {
            Some(j) => downdate(aat, m, &ws[j * m..j * m + m], y, diag, inv_d),
            None => false,
        };
        if updated {
            // rhs += w_j (t_j − t_m,j): the saturated cable's force moved into the wrench.
            let j = saturated.unwrap_or_default();
            let dt = t[j] - 0.5 * (lo[j] + hi[j]);
            for k in 0..m {
                rhs[k] += ws[j * m + k] * dt;
            }
        } else {
            factorise::<M>(ws, we, t, active, m, aat, rhs, diag);
            if !ldl(aat, m, inv_d) {
                return Err(if first {
                    Infeasibility::SingularPose {
                        condition: f64::INFINITY,
                    }
                } else {
                    Infeasibility::Inconclusive { method: METHOD }
                });
            }
        }
        // ρ = Π_k L_kk / √diag_k of the Cholesky factor, L_kk² = D_k.
        let ratio: f64 = (0..m)
            .map(|k| aat[k * m + k] / diag[k])
            .product::<f64>()
            .sqrt();
        if ratio.is_nan() || ratio < step.ratio_floor {
            return Err(if first {
                Infeasibility::SingularPose {
                    condition: 1.0 / ratio,
                }
            } else {
                Infeasibility::Inconclusive { method: METHOD }
            });
        }
        if first && step.minimum_norm && d.len() == n {
            // t0 = −Wᵀ (W Wᵀ)⁻¹ w_ext from the first factor (all cables free), trusted only
            // above the plain-closed-form ratio (the normal equations square W's condition).
            if ratio >= PLAIN_RATIO {
                y.copy_from_slice(we);
                ldl_solve(aat, inv_d, m, y);
                d.fill(0.0);
                subtract_at_y::<N>(ws, m, y, active, d);
            } else {
                d.fill(f64::NAN);
            }
        }
        first = false;
        // (A Aᵀ) y = rhs; t_free −= Aᵀ y.
        y.copy_from_slice(rhs);
        ldl_solve(aat, inv_d, m, y);
        subtract_at_y::<N>(ws, m, y, active, t);
        if step.first_only {
            if d.len() == n {
                // d = 1 − Wᵀ (W Wᵀ)⁻¹ (W 1): y ← (W Wᵀ)⁻¹ W 1 (row sums of W).
                for k in 0..m {
                    y[k] = (0..n).map(|i| ws[i * m + k]).sum();
                }
                ldl_solve(aat, inv_d, m, y);
                d.fill(1.0);
                subtract_at_y::<N>(ws, m, y, active, d);
            }
            return Ok(());
        }
        // The free cable with the largest violation of its limits, in force units (Pott
        // 2014); a tension counts as violating beyond the certificate's relative tolerance.
        let (mut worst, mut wv) = (n, 0.0);
        for i in 0..n {
            // Inside [lo, hi] the violation is ≤ 0: the division only for tensions outside
            // (or NaN), the same decision.
            if active[i]
                && !(t[i] >= lo[i] && t[i] <= hi[i])
                && bound_violation(lo[i], hi[i], t[i]) > crate::certificate::BOUND_TOLERANCE
            {
                let v = (lo[i] - t[i]).max(t[i] - hi[i]);
                if v > wv {
                    (worst, wv) = (i, v);
                }
            }
        }
        if worst == n {
            return Ok(());
        }
        if remaining <= m {
            return Err(Infeasibility::Inconclusive { method: METHOD });
        }
        // Saturate it and restart the free cables from their mean tension.
        t[worst] = if t[worst] < lo[worst] {
            lo[worst]
        } else {
            hi[worst]
        };
        active[worst] = false;
        remaining -= 1;
        saturated = update.then_some(worst);
        for i in 0..n {
            if active[i] {
                t[i] = 0.5 * (lo[i] + hi[i]);
            }
        }
    }
}

/// t_i −= w_iᵀ y for the free cables. With n = N fixed at compile time, two cables at a
/// time (each dot product summed over k in order, as in the scalar loop: the same bits).
#[inline(always)]
fn subtract_at_y<const N: usize>(ws: &[f64], m: usize, y: &[f64], active: &[bool], t: &mut [f64]) {
    if N > 0 && N.is_multiple_of(2) {
        for i in (0..N).step_by(2) {
            let (a, b) = (&ws[i * m..i * m + m], &ws[(i + 1) * m..(i + 1) * m + m]);
            let mut s = [0.0; 2];
            for k in 0..m {
                s[0] += a[k] * y[k];
                s[1] += b[k] * y[k];
            }
            if active[i] {
                t[i] -= s[0];
            }
            if active[i + 1] {
                t[i + 1] -= s[1];
            }
        }
        return;
    }
    for ((col, ti), &free) in ws.chunks_exact(m).zip(t.iter_mut()).zip(active.iter()) {
        if free {
            let mut s = 0.0;
            for k in 0..m {
                s += col[k] * y[k];
            }
            *ti -= s;
        }
    }
}

/// rhs = w_ext + W t and the lower triangle of A Aᵀ over the free cables (into `aat`, its
/// diagonal also into `diag`): one outer product per free cable (each entry sums over the
/// cables in the same order as an entry-by-entry loop, so the same bits, without a branch per
/// entry and cable).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn factorise<const M: usize>(
    ws: &[f64],
    we: &[f64],
    t: &[f64],
    active: &[bool],
    m: usize,
    aat: &mut [f64],
    rhs: &mut [f64],
    diag: &mut [f64],
) {
    if M > 0 {
        // In a local array (kept in registers, two rows per vector), same order of sums.
        let mut acc = [0.0; 8];
        acc[..M].copy_from_slice(we);
        for (col, &ti) in ws.chunks_exact(M).zip(t.iter()) {
            for k in 0..M {
                acc[k] += col[k] * ti;
            }
        }
        rhs.copy_from_slice(&acc[..M]);
    } else {
        rhs.copy_from_slice(we);
        for (col, &ti) in ws.chunks_exact(m).zip(t.iter()) {
            for k in 0..m {
                rhs[k] += col[k] * ti;
            }
        }
    }
    if M > 0 {
        // DOF known at compile time (M ≤ 7): the triangle in pairs of adjacent entries,
        // acc[r][p] = (entry (r, 2p), entry (r, 2p + 1)), which the compiler keeps in vector
        // registers (for M = 6, 12 pairs instead of 21 scalars that spill). Every entry is the
        // same sum in the same order; the entries past the diagonal are computed and dropped.
        let mut acc = [[[0.0; 2]; 4]; M];
        for (col, &free) in ws.chunks_exact(M).zip(active.iter()) {
            if free {
                let mut pad = [0.0; 8];
                pad[..M].copy_from_slice(col);
                for r in 0..M {
                    let cr = col[r];
                    for p in 0..=r / 2 {
                        acc[r][p][0] += cr * pad[2 * p];
                        acc[r][p][1] += cr * pad[2 * p + 1];
                    }
                }
            }
        }
        for r in 0..M {
            for c in 0..=r {
                aat[r * M + c] = acc[r][c / 2][c % 2];
            }
        }
    } else {
        for r in 0..m {
            aat[r * m..r * m + r + 1].fill(0.0);
        }
        for (col, &free) in ws.chunks_exact(m).zip(active.iter()) {
            if free {
                for r in 0..m {
                    let cr = col[r];
                    for c in 0..=r {
                        aat[r * m + c] += cr * col[c];
                    }
                }
            }
        }
    }
    for k in 0..m {
        diag[k] = aat[k * m + k];
    }
}

/// Rank-one downdate L' D' L'ᵀ = L D Lᵀ − x xᵀ in place (Gill, Golub, Murray & Saunders 1974,
/// method C1 with α = −1): for each column j, with p = x_j, D'_j = D_j + α p², β = α p / D'_j,
/// α ← α D_j / D'_j, then x_i ← x_i − p L_ij and L_ij ← L_ij + β x_i below the diagonal. `x` is
/// the removed column w_j (copied into `scratch`); `diag` (the diagonal of A Aᵀ) loses x_k², and
/// `inv_d` gets the new 1/D'_j. False, with the factor left partly updated, if some
/// D'_j < [`DOWNDATE_MIN_RATIO`] D_j (too much cancellation, or A' A'ᵀ not positive definite):
/// the caller then refactorises.
#[inline(always)]
fn downdate(
    l: &mut [f64],
    m: usize,
    x: &[f64],
    scratch: &mut [f64],
    diag: &mut [f64],
    inv_d: &mut [f64],
) -> bool {
    let z = &mut scratch[..m];
    z.copy_from_slice(&x[..m]);
    let mut alpha = -1.0;
    for j in 0..m {
        let dj = l[j * m + j];
        let p = z[j];
        let d_new = dj + alpha * (p * p);
        if d_new.is_nan() || d_new < DOWNDATE_MIN_RATIO * dj {
            return false;
        }
        let inv = 1.0 / d_new;
        let beta = alpha * p * inv;
        alpha *= dj * inv;
        l[j * m + j] = d_new;
        inv_d[j] = inv;
        for i in j + 1..m {
            z[i] -= p * l[i * m + j];
            l[i * m + j] += beta * z[i];
        }
    }
    for k in 0..m {
        diag[k] -= x[k] * x[k];
    }
    true
}

/// In-place square-root-free Cholesky A = L D Lᵀ of the lower triangle of an m × m row-major
/// matrix (Golub & Van Loan §4.1): D_k on the diagonal, L (unit diagonal) below it, and
/// c_ik = L_ik D_k above it (transposed, at (k, i): the factorisation's scratch); `inv_d` gets
/// 1/D_k. Each column costs one division: L_ij = c_ij / D_j is a product with 1/D_j. False if
/// A is not positive definite (a pivot ≤ 0 or NaN).
#[inline(always)]
fn ldl(a: &mut [f64], m: usize, inv_d: &mut [f64]) -> bool {
    for j in 0..m {
        let mut d = a[j * m + j];
        for k in 0..j {
            d -= a[j * m + k] * a[k * m + j];
        }
        if d.is_nan() || d <= 0.0 {
            return false;
        }
        let inv = 1.0 / d;
        a[j * m + j] = d;
        inv_d[j] = inv;
        for i in j + 1..m {
            let mut c = a[i * m + j];
            for k in 0..j {
                c -= a[i * m + k] * a[k * m + j];
            }
            a[j * m + i] = c;
            a[i * m + j] = c * inv;
        }
    }
    true
}

/// Solves L D Lᵀ x = b in place (L unit lower triangular, 1/D_k in `inv_d`).
#[inline(always)]
fn ldl_solve(l: &[f64], inv_d: &[f64], m: usize, x: &mut [f64]) {
    for i in 0..m {
        let mut s = x[i];
        for k in 0..i {
            s -= l[i * m + k] * x[k];
        }
        x[i] = s;
    }
    for i in 0..m {
        x[i] *= inv_d[i];
    }
    for i in (0..m).rev() {
        let mut s = x[i];
        for k in i + 1..m {
            s -= l[k * m + i] * x[k];
        }
        x[i] = s;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::TensionBounds;
    use nalgebra::{DMatrix, DVector};
    use proptest::prelude::*;

    /// The factorisation, the solve and the downdate against hand-derived values: A Aᵀ of
    /// A = [[2, 1, 0], [0, 1, 1]] is [[5, 1], [1, 2]] = L D Lᵀ with L_21 = 1/5, D = (5, 9/5);
    /// without the column (1, 1) it is [[4, 0], [0, 1]]: L_21 = 0, D = (4, 1).
    #[test]
    fn downdate_matches_a_fresh_factorisation() {
        let (mut l, mut inv_d) = ([5.0, 0.0, 1.0, 2.0], [0.0; 2]);
        assert!(ldl(&mut l, 2, &mut inv_d));
        assert_eq!((l[0], l[2], inv_d[0]), (5.0, 0.2, 0.2));
        assert!((l[3] - 1.8).abs() < 1e-15 && (inv_d[1] - 1.0 / 1.8).abs() < 1e-15);
        // [[5, 1], [1, 2]] y = (7, 5): y = (1, 2).
        let mut y = [7.0, 5.0];
        ldl_solve(&l, &inv_d, 2, &mut y);
        assert!(
            (y[0] - 1.0).abs() < 1e-15 && (y[1] - 2.0).abs() < 1e-15,
            "{y:?}"
        );
        let mut diag = [5.0, 2.0];
        assert!(downdate(
            &mut l,
            2,
            &[1.0, 1.0],
            &mut [0.0; 2],
            &mut diag,
            &mut inv_d
        ));
        assert_eq!(diag, [4.0, 1.0]);
        for (got, e) in [
            (l[0], 4.0),
            (l[2], 0.0),
            (l[3], 1.0),
            (inv_d[0], 0.25),
            (inv_d[1], 1.0),
        ] {
            assert!((got - e).abs() < 1e-15, "{l:?} {inv_d:?}");
        }
        // Removing a column that carries a whole direction is refused (singular remainder).
        let (mut l, mut inv_d) = ([1.0, 0.0, 0.0, 1.0], [0.0; 2]);
        assert!(ldl(&mut l, 2, &mut inv_d));
        assert!(!downdate(
            &mut l,
            2,
            &[1.0, 0.0],
            &mut [0.0; 2],
            &mut [1.0, 1.0],
            &mut inv_d
        ));
        // Not positive definite.
        assert!(!ldl(&mut [1.0, 0.0, 2.0, 1.0], 2, &mut inv_d));
    }

    /// W, w_ext and bounds of a random problem with DOF `m` and `n` cables: loads from a
    /// feasible tension, pushed off it for some seeds (saturations and inconclusive answers).
    fn problem(m: usize, n: usize, seed: &[f64]) -> (DMatrix<f64>, DVector<f64>, TensionBounds) {
        let mut it = seed.iter().copied().cycle();
        let mut next = move || it.next().unwrap_or(0.5);
        let w = DMatrix::from_fn(m, n, |_, _| 2.0 * next() - 1.0);
        let lo: Vec<f64> = (0..n).map(|_| 10.0 * next()).collect();
        let hi: Vec<f64> = lo.iter().map(|l| l + 1.0 + 990.0 * next()).collect();
        let tr = DVector::from_fn(n, |i, _| lo[i] + next() * (hi[i] - lo[i]));
        let push = 300.0 * next() * next();
        let we = -(&w * tr) + DVector::from_fn(m, |_, _| push * (2.0 * next() - 1.0));
        (w, we, TensionBounds::new(lo, hi).unwrap())
    }

    proptest! {
        /// The AVX2 build of the 6 × 8 iteration gives the bits of the portable build (the
        /// same source without fused multiply–adds), on problems with and without saturations.
        #[cfg(target_arch = "x86_64")]
        #[test]
        fn avx2_build_gives_the_portable_bits(
            seed in proptest::collection::vec(0.0f64..1.0, 97),
        ) {
            if !std::arch::is_x86_feature_detected!("avx2") {
                return Ok(());
            }
            let (w, we, b) = problem(6, 8, &seed);
            let p = TensionProblem::new(&w, &we, &b);
            let (mut ta, mut tp) = (vec![0.0; 8], vec![0.0; 8]);
            let avx2 = ImprovedClosedForm::default().solve_with(&p, &mut ta, true, Path::Avx2, Step::ITERATE, &mut []);
            let portable =
                ImprovedClosedForm::default().solve_with(&p, &mut tp, true, Path::Portable, Step::ITERATE, &mut []);
            prop_assert_eq!(format!("{avx2:?}"), format!("{portable:?}"));
            let bits = |t: &[f64]| t.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
            prop_assert_eq!(bits(&ta), bits(&tp));
        }

        /// The downdated iteration gives the verdict of the plain one (factor rebuilt at every
        /// step) and tensions within 10⁻¹⁰ of the largest, for DOF 1–7 and up to 5 redundant
        /// cables (6 × 8 and DOF 6 and 3 through their fixed-size copies).
        #[test]
        fn downdate_keeps_the_plain_iteration(
            m in 1usize..8,
            r in 0usize..6,
            seed in proptest::collection::vec(0.0f64..1.0, 97),
        ) {
            let n = m + r;
            let (w, we, b) = problem(m, n, &seed);
            let p = TensionProblem::new(&w, &we, &b);
            let (mut tu, mut tp) = (vec![0.0; n], vec![0.0; n]);
            let up = ImprovedClosedForm::default().solve_with(&p, &mut tu, true, Path::Portable, Step::ITERATE, &mut []);
            let plain = ImprovedClosedForm::default().solve_with(&p, &mut tp, false, Path::Portable, Step::ITERATE, &mut []);
            // The same verdict (a singular pose's condition number may differ by rounding).
            prop_assert_eq!(
                up.as_ref().map_err(std::mem::discriminant),
                plain.as_ref().map_err(std::mem::discriminant)
            );
            if up.is_ok() {
                let scale = tp.iter().fold(1.0f64, |a, v| a.max(v.abs()));
                for (a, e) in tu.iter().zip(&tp) {
                    prop_assert!((a - e).abs() <= 1e-10 * scale, "{:?} vs {:?}", tu, tp);
                }
            }
        }
    }
}
