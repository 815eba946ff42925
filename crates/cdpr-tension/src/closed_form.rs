//! # Closed-form tension limits (Algorithm 6.1)
//!
//! For redundancy 1 (planar n = 4, spatial n = 7, point2 n = 3, point3 n = 4) partition
//! W = [A | b] into DOF dependent cables A and one independent cable t^B (eq. (6.15)); then
//! t^A(t^B) = M + N t^B with M = −A⁻¹ w_ext, N = −A⁻¹ b (eq. (6.16)). The bounds on t^A
//! (eq. (6.18)) and on t^B give the feasible interval [t^B_min, t^B_max] (eq. (6.20),
//! Algorithm 6.1); it is empty when t^B_min > t^B_max. Σ t is linear in t^B, so the minimum
//! (and maximum) ‖t‖₁ lies at an interval end: as the thesis says, both ends are evaluated and
//! compared.
//!
//! **Choice of the basis A.** The thesis takes the first DOF cables as A, which fails when they
//! are (nearly) dependent. We factor W by Gaussian elimination with complete pivoting, which picks
//! a well-conditioned A, and then improve the choice exactly: by Cramer's rule N_i =
//! ±det(A_i)/det(A), where A_i is the basis with cable i free instead, so if some |N_i| > 1 the
//! basis that frees cable i has a larger |det| and we switch to it (one re-parametrisation,
//! t^B ← t_i). The final A has the largest |det A| of the n possible choices; every N_i satisfies
//! |N_i| ≤ 1. The Hadamard ratio √det(W Wᵀ)/Π‖row_k(W)‖ = |det A|·‖(N, 1)‖/Π‖row_k‖ detects
//! singular poses with the same threshold as the other methods.
//!
//! **Small fast path.** For DOF ≤ 3 (point2 with 3 cables, planar and point3 with 4) the same
//! answer is computed in closed form without elimination: the null vector of W is the vector of
//! signed maximal minors d_j = (−1)^j det(W without column j) (generalised cross product), so
//! N = d / d_f with f = argmax |d_j| (the basis of largest |det A| = |d_f|, hence |N_i| ≤ 1), the
//! Hadamard ratio is ‖d‖ / Π‖row_k(W)‖ (Cauchy–Binet: det(W Wᵀ) = Σ d_j²), and M solves
//! A M_A = −w_ext by Cramer's rule with fixed-size 3 × 3 determinants. Both paths are compared on
//! random problems in the unit tests.
//!
//! ## References
//! - The thesis chapter on planar tendon-driven manipulators (ch. 6), eqs. (6.15)–(6.20), Algorithm 6.1.

use crate::certificate::{BOUND_TOLERANCE, bound_violation};
use crate::lanes::F64x4;
use crate::null_space::SINGULARITY_RATIO;
use crate::outcome::validate;
use crate::{Infeasibility, TensionBounds, TensionError, TensionProblem};
use nalgebra::DVector;

/// The feasible interval of a redundancy-1 problem (Algorithm 6.1).
///
/// Every equilibrium tension is t(λ) = M + N λ where λ = t^B is the tension of the independent
/// cable `free_cable` (so N has entry 1 there and M entry 0); feasible tensions are exactly those
/// with λ in `[lambda.0, lambda.1]`.
#[derive(Debug, Clone, PartialEq)]
pub struct FeasibleInterval {
    /// The independent cable (chosen for the best-conditioned dependent basis A).
    pub free_cable: usize,
    /// [t^B_min, t^B_max] of Algorithm 6.1.
    pub lambda: (f64, f64),
    /// M = −A⁻¹ w_ext, padded with 0 for the free cable.
    pub particular: DVector<f64>,
    /// N = −A⁻¹ b, padded with 1 for the free cable (a null vector of W).
    pub direction: DVector<f64>,
    /// t(t^B_min).
    pub tensions_low: DVector<f64>,
    /// t(t^B_max).
    pub tensions_high: DVector<f64>,
}

impl FeasibleInterval {
    /// t(λ) = M + N λ.
    pub fn tensions_at(&self, lambda: f64) -> DVector<f64> {
        &self.particular + &self.direction * lambda
    }
}

/// The feasible interval of a redundancy-1 problem, or why there is none (another redundancy
/// is the error [`TensionError::RedundancyMismatch`]).
///
/// ```
/// use cdpr_tension::{feasible_interval, TensionBounds, TensionProblem};
/// use nalgebra::{DMatrix, DVector};
/// // Two opposed cables on a point along x, holding a force of 3 to the left: t1 − t2 = 3.
/// let w = DMatrix::from_row_slice(1, 2, &[1.0, -1.0]);
/// let we = DVector::from_vec(vec![-3.0]);
/// let b = TensionBounds::uniform(2, 1.0, 10.0).unwrap();
/// let iv = feasible_interval(&TensionProblem::new(&w, &we, &b)).unwrap().unwrap();
/// assert!((iv.tensions_low - DVector::from_vec(vec![4.0, 1.0])).norm() < 1e-12);
/// assert!((iv.tensions_high - DVector::from_vec(vec![10.0, 7.0])).norm() < 1e-12);
/// ```
pub fn feasible_interval(
    problem: &TensionProblem,
) -> Result<Result<FeasibleInterval, Infeasibility>, TensionError> {
    validate(problem)?;
    let r = problem.redundancy();
    if r != 1 {
        return Err(TensionError::RedundancyMismatch {
            what: "feasible interval",
            needs: 1,
            redundancy: r,
        });
    }
    let mut s = ClosedForm::default();
    Ok(s.interval(problem).map(|(lo, hi)| {
        let particular = DVector::from_column_slice(&s.m_vec);
        let direction = DVector::from_column_slice(&s.n_vec);
        FeasibleInterval {
            free_cable: s.free,
            lambda: (lo, hi),
            tensions_low: &particular + &direction * lo,
            tensions_high: &particular + &direction * hi,
            particular,
            direction,
        }
    }))
}

/// Scratch buffers of Algorithm 6.1.
#[derive(Debug, Clone, Default)]
pub(crate) struct ClosedForm {
    /// [W | −w_ext], m × (n + 1), row-major.
    aug: Vec<f64>,
    perm: Vec<usize>,
    /// M and N of t = M + N t^B, per cable.
    pub m_vec: Vec<f64>,
    pub n_vec: Vec<f64>,
    x: Vec<f64>,
    y: Vec<f64>,
    rows: Vec<f64>,
    /// The free cable.
    pub free: usize,
}

/// det of the m × m matrix (m ≤ 3) whose columns are `a`, `b`, `c` (only the first m entries and
/// columns are used).
#[inline(always)]
fn det_small<const M: usize>(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3]) -> f64 {
    match M {
        1 => a[0],
        2 => a[0] * b[1] - a[1] * b[0],
        _ => {
            a[0] * (b[1] * c[2] - b[2] * c[1]) - b[0] * (a[1] * c[2] - a[2] * c[1])
                + c[0] * (a[1] * b[2] - a[2] * b[1])
        }
    }
}

impl ClosedForm {
    /// Eq. (6.16) with the basis choice described in the module docs.
    fn parametrise(&mut self, problem: &TensionProblem) -> Result<(), Infeasibility> {
        let (m, n) = problem.wrench_matrix.shape();
        match (m, n) {
            (1, 2) => self.parametrise_small::<1>(problem),
            (2, 3) => self.parametrise_small::<2>(problem),
            (3, 4) => self.parametrise_small::<3>(problem),
            _ => self.parametrise_general(problem),
        }
    }

    /// Eq. (6.16) for DOF ≤ 3 by signed minors and Cramer's rule (see the module docs), into
    /// the reusable vectors.
    fn parametrise_small<const M: usize>(
        &mut self,
        problem: &TensionProblem,
    ) -> Result<(), Infeasibility> {
        let mut s = Small::default();
        param_small::<M>(
            problem.wrench_matrix.as_slice(),
            problem.external_wrench.as_slice(),
            &mut s,
        )?;
        let n = M + 1;
        self.m_vec.clear();
        self.m_vec.extend_from_slice(&s.m[..n]);
        self.n_vec.clear();
        self.n_vec.extend_from_slice(&s.n[..n]);
        self.free = s.free;
        Ok(())
    }

    /// Eq. (6.16) by Gaussian elimination with complete pivoting (any DOF).
    fn parametrise_general(&mut self, problem: &TensionProblem) -> Result<(), Infeasibility> {
        let w = problem.wrench_matrix;
        let (m, n) = w.shape();
        let c = n + 1;
        self.aug.resize(m * c, 0.0);
        self.perm.resize(n, 0);
        self.m_vec.resize(n, 0.0);
        self.n_vec.resize(n, 0.0);
        self.x.resize(m, 0.0);
        self.y.resize(m, 0.0);
        self.rows.resize(m, 0.0);
        for k in 0..m {
            let mut s = 0.0;
            for i in 0..n {
                let v = w[(k, i)];
                self.aug[k * c + i] = v;
                s += v * v;
            }
            if s == 0.0 {
                return Err(Infeasibility::SingularPose {
                    condition: f64::INFINITY,
                });
            }
            self.rows[k] = s.sqrt();
            self.aug[k * c + n] = -problem.external_wrench[k];
        }
        for (i, p) in self.perm.iter_mut().enumerate() {
            *p = i;
        }
        // Gaussian elimination with complete pivoting over the n cable columns.
        // ρ = Π |pivot_k| / ‖row_k‖ · ‖(N, 1)‖, accumulated factor by factor (no overflow).
        let mut ratio = 1.0;
        for k in 0..m {
            let (mut pr, mut pc, mut best) = (k, k, -1.0);
            for r in k..m {
                for j in k..n {
                    let v = self.aug[r * c + j].abs();
                    if v > best {
                        (pr, pc, best) = (r, j, v);
                    }
                }
            }
            if best <= 0.0 {
                return Err(Infeasibility::SingularPose {
                    condition: f64::INFINITY,
                });
            }
            if pr != k {
                for j in 0..c {
                    self.aug.swap(k * c + j, pr * c + j);
                }
            }
            if pc != k {
                for r in 0..m {
                    self.aug.swap(r * c + k, r * c + pc);
                }
                self.perm.swap(k, pc);
            }
            let piv = self.aug[k * c + k];
            ratio *= piv.abs() / self.rows[k];
            for r in k + 1..m {
                let f = self.aug[r * c + k] / piv;
                if f != 0.0 {
                    for j in k..c {
                        self.aug[r * c + j] -= f * self.aug[k * c + j];
                    }
                }
            }
        }
        // Back substitution: U x = rhs, U y = −u_free (column m of the permuted matrix).
        for k in (0..m).rev() {
            let (mut sx, mut sy) = (self.aug[k * c + n], -self.aug[k * c + m]);
            for j in k + 1..m {
                sx -= self.aug[k * c + j] * self.x[j];
                sy -= self.aug[k * c + j] * self.y[j];
            }
            let piv = self.aug[k * c + k];
            self.x[k] = sx / piv;
            self.y[k] = sy / piv;
        }
        let free = self.perm[m];
        self.m_vec[free] = 0.0;
        self.n_vec[free] = 1.0;
        let mut nn = 1.0;
        for k in 0..m {
            self.m_vec[self.perm[k]] = self.x[k];
            self.n_vec[self.perm[k]] = self.y[k];
            nn += self.y[k] * self.y[k];
        }
        let ratio = (ratio * nn.sqrt()).min(1.0);
        if ratio.is_nan() || ratio < SINGULARITY_RATIO {
            return Err(Infeasibility::SingularPose {
                condition: 1.0 / ratio,
            });
        }
        // Switch to the basis with the largest |det A| (all |N_i| ≤ 1).
        let (mut best, mut bv) = (free, 1.0);
        for (i, &v) in self.n_vec.iter().enumerate() {
            if v.abs() > bv * (1.0 + 1e-12) {
                (best, bv) = (i, v.abs());
            }
        }
        if best != free {
            let (mb, nb) = (self.m_vec[best], self.n_vec[best]);
            for i in 0..n {
                let (mi, ni) = (self.m_vec[i], self.n_vec[i]);
                self.m_vec[i] = mi - ni * mb / nb;
                self.n_vec[i] = ni / nb;
            }
            self.m_vec[best] = 0.0;
            self.n_vec[best] = 1.0;
        }
        self.free = best;
        Ok(())
    }

    /// Algorithm 6.1: the feasible interval of t^B (callers ensure r = 1).
    pub fn interval(&mut self, problem: &TensionProblem) -> Result<(f64, f64), Infeasibility> {
        debug_assert_eq!(problem.redundancy(), 1);
        self.parametrise(problem)?;
        interval_of(&self.m_vec, &self.n_vec, problem).map(|iv| (iv.lo, iv.hi))
    }

    /// Minimum (or maximum) ‖t‖₁ = Σ t_i over the interval, comparing both ends (Alg. 6.1).
    /// For DOF ≤ 3 everything stays in fixed-size arrays (no scratch vectors are touched).
    #[inline]
    pub fn solve(
        &mut self,
        problem: &TensionProblem,
        maximize: bool,
        t: &mut [f64],
    ) -> Result<(), Infeasibility> {
        match problem.wrench_matrix.shape() {
            (1, 2) => return solve_small::<1>(problem, maximize, t),
            (2, 3) => return solve_small::<2>(problem, maximize, t),
            (3, 4) => return solve_small::<3>(problem, maximize, t),
            _ => {}
        }
        debug_assert_eq!(problem.redundancy(), 1);
        self.parametrise(problem)?;
        let iv = interval_of(&self.m_vec, &self.n_vec, problem)?;
        write_end(&self.m_vec, &self.n_vec, &iv, maximize, t)
    }
}

/// t = M + N t^B of a small problem (DOF = M ≤ 3, n = M + 1), padded to 4 cables.
#[derive(Debug, Clone, Copy, Default)]
struct Small {
    m: [f64; 4],
    n: [f64; 4],
    /// 1 / N_i = d_free / d_i, computed from the minors (in parallel with 1 / d_free rather
    /// than after it).
    inv_n: [f64; 4],
    free: usize,
}

/// Eq. (6.16) for DOF ≤ 3 by signed minors and Cramer's rule (see the module docs), into `out`
/// (an out-parameter: returning the 104-byte struct inside a `Result` costs a copy on the hot
/// path). `ws` is W column-major (M × (M + 1)), `we` is w_ext.
#[inline(always)]
fn param_small<const M: usize>(
    ws: &[f64],
    we: &[f64],
    out: &mut Small,
) -> Result<(), Infeasibility> {
    let n = M + 1;
    let (ws, we) = (&ws[..M * (M + 1)], &we[..M]);
    // Columns of W (zero-padded to 3 rows) and −w_ext as column 4, read element by element.
    let mut cols = [[0.0f64; 3]; 5];
    let mut row_norm = [0.0f64; 3];
    for (j, col) in cols.iter_mut().enumerate().take(n) {
        for k in 0..M {
            let v = ws[j * M + k];
            col[k] = v;
            row_norm[k] += v * v;
        }
    }
    for k in 0..M {
        cols[4][k] = -we[k];
    }
    // Π ‖row_k‖².
    let mut rows2 = 1.0;
    let mut zero_row = false;
    for &r in &row_norm[..M] {
        zero_row |= r == 0.0;
        rows2 *= r;
    }
    if zero_row {
        return Err(Infeasibility::SingularPose {
            condition: f64::INFINITY,
        });
    }
    // Signed maximal minors: W d = 0. `others[j]`: the columns other than j, in order.
    const OTHERS: [[usize; 3]; 4] = [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]];
    let mut d = [0.0f64; 4];
    let mut dn = 0.0;
    for j in 0..n {
        let o = OTHERS[j];
        // Entries beyond M are unused by det_small (for M < 3, o[M..] may name column M + 1,
        // which is zero-padded data of no consequence).
        let det = det_small::<M>(&cols[o[0]], &cols[o[1]], &cols[o[2]]);
        d[j] = if j % 2 == 0 { det } else { -det };
        dn += det * det;
    }
    // The basis of largest |det A| (ties to the first), by selects rather than branches.
    let (mut free, mut best, mut d_free) = (0, d[0].abs(), d[0]);
    for (j, &dj) in d[..n].iter().enumerate() {
        let better = dj.abs() > best * (1.0 + 1e-12);
        free = if better { j } else { free };
        best = if better { dj.abs() } else { best };
        d_free = if better { dj } else { d_free };
    }
    // Hadamard ratio √(dn / rows2) ≥ SINGULARITY_RATIO, tested without the square root.
    if !(d_free != 0.0 && dn >= SINGULARITY_RATIO * SINGULARITY_RATIO * rows2) {
        let ratio = (dn / rows2).sqrt().min(1.0);
        return Err(Infeasibility::SingularPose {
            condition: 1.0 / ratio,
        });
    }
    let inv_free = 1.0 / d_free;
    out.free = free;
    for (((inv_n, nj), mj), &dj) in out
        .inv_n
        .iter_mut()
        .zip(&mut out.n)
        .zip(&mut out.m)
        .zip(&d[..n])
    {
        *inv_n = d_free / dj;
        *nj = dj * inv_free;
        *mj = 0.0;
    }
    // M_A = A⁻¹ (−w_ext) by Cramer's rule; A = the columns other than `free`, in order,
    // det A = (−1)^free d_free.
    let o = OTHERS[free];
    let inv_a = if free % 2 == 0 { inv_free } else { -inv_free };
    let rhs = &cols[4];
    out.m[o[0]] = det_small::<M>(rhs, &cols[o[1]], &cols[o[2]]) * inv_a;
    if M >= 2 {
        out.m[o[1]] = det_small::<M>(&cols[o[0]], rhs, &cols[o[2]]) * inv_a;
    }
    if M >= 3 {
        out.m[o[2]] = det_small::<M>(&cols[o[0]], &cols[o[1]], rhs) * inv_a;
    }
    Ok(())
}

/// Algorithm 6.1 + the choice of the end for DOF = M ≤ 3, on the stack: the same answer as
/// [`interval_of`] + [`write_end`], written with selects instead of data-dependent branches
/// (the ends and the cables defining them are tracked by index).
#[inline(always)]
pub(crate) fn solve_small<const M: usize>(
    problem: &TensionProblem,
    maximize: bool,
    t: &mut [f64],
) -> Result<(), Infeasibility> {
    solve_small_slices::<M>(
        problem.wrench_matrix.as_slice(),
        problem.external_wrench.as_slice(),
        problem.bounds,
        maximize,
        t,
    )
}

/// [`solve_small`] on W given as its column-major values (M × (M + 1)) and w_ext as a slice.
#[inline(always)]
pub(crate) fn solve_small_slices<const M: usize>(
    ws: &[f64],
    we: &[f64],
    bounds: &TensionBounds,
    maximize: bool,
    t: &mut [f64],
) -> Result<(), Infeasibility> {
    let n = M + 1;
    let mut s = Small::default();
    param_small::<M>(ws, we, &mut s)?;
    let tmin = &bounds.min().as_slice()[..n];
    let tmax = &bounds.max().as_slice()[..n];
    let t = &mut t[..n];
    // Eq. (6.18) per cable; `n` (out of range) marks "no defining cable".
    let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
    let (mut i_lo, mut b_lo, mut i_hi, mut b_hi) = (n, 0.0, n, 0.0);
    let mut slope = 0.0;
    for i in 0..n {
        let (mi, ni, tl, th) = (s.m[i], s.n[i], tmin[i], tmax[i]);
        slope += ni;
        if ni.abs() <= 1e-14 {
            // t_i does not depend on t^B: it must satisfy its bounds by itself.
            if bound_violation(tl, th, mi) > BOUND_TOLERANCE {
                return Err(Infeasibility::NoFeasibleTension);
            }
            continue;
        }
        let a = (tl - mi) * s.inv_n[i];
        let b = (th - mi) * s.inv_n[i]; // ±∞ for an infinite t_max
        let pos = ni > 0.0;
        let (l, bl) = if pos { (a, tl) } else { (b, th) };
        let (h, bh) = if pos { (b, th) } else { (a, tl) };
        let up = l > lo;
        lo = if up { l } else { lo };
        i_lo = if up { i } else { i_lo };
        b_lo = if up { bl } else { b_lo };
        let down = h < hi;
        hi = if down { h } else { hi };
        i_hi = if down { i } else { i_hi };
        b_hi = if down { bh } else { b_hi };
    }
    if lo > hi {
        // Empty, unless only by rounding (see `interval_of`).
        let mid = 0.5 * (lo + hi);
        let worst = (0..n)
            .map(|i| bound_violation(tmin[i], tmax[i], s.m[i] + s.n[i] * mid))
            .fold(f64::NEG_INFINITY, f64::max);
        if worst > BOUND_TOLERANCE {
            return Err(Infeasibility::NoFeasibleTension);
        }
        (lo, hi, i_lo, i_hi) = (mid, mid, n, n);
    }
    if maximize && !hi.is_finite() {
        return Err(Infeasibility::Unbounded {
            method: "closed-form",
        });
    }
    let take_hi = hi.is_finite() && if maximize { slope > 0.0 } else { slope < 0.0 };
    let (tb, at, bound) = if take_hi {
        (hi, i_hi, b_hi)
    } else {
        (lo, i_lo, b_lo)
    };
    for (i, ti) in t.iter_mut().enumerate() {
        *ti = if i == at { bound } else { s.m[i] + s.n[i] * tb };
    }
    Ok(())
}
/// Whether the planar r = 1 problem (DOF 3, 4 cables) has certified tensions by Algorithm 6.1:
/// the verdict of [`crate::TensionSolver::is_feasible`] with `ClosedForm` or `L1` (`maximize`
/// false: the smaller-Σt end) or `L1Max` (`maximize` true) on the same W, w_ext and bounds —
/// the same fixed-size arithmetic and certificate, without the `DMatrix` problem and the
/// method dispatch. For loops over millions of poses (the dextrous workspace of the thesis
/// chapter on planar tendon-driven manipulators, Table 6.10). Errors on non-finite W or w_ext
/// and on bounds that are not for 4 cables, as the solver does.
///
/// ```
/// use cdpr_tension::{Method, TensionBounds, TensionProblem, TensionSolver, closed_form};
/// use nalgebra::{DMatrix, Matrix3x4, Vector3};
/// let w = Matrix3x4::new(1.0, 0.0, -1.0, 0.0, 0.0, 1.0, 0.0, -1.0, 0.1, -0.1, 0.1, -0.1);
/// let we = Vector3::new(0.0, -10.0, 0.0);
/// let b = TensionBounds::uniform(4, 1.0, 100.0).unwrap();
/// let lean = closed_form::is_feasible_planar(&w, &we, &b, false).unwrap();
/// let (wd, wed) = (DMatrix::from_column_slice(3, 4, w.as_slice()), we.as_slice().to_vec().into());
/// let full = TensionSolver::new(Method::L1).is_feasible(&TensionProblem::new(&wd, &wed, &b));
/// assert_eq!(lean, full.unwrap());
/// assert!(lean);
/// ```
pub fn is_feasible_planar(
    w: &nalgebra::Matrix3x4<f64>,
    w_ext: &nalgebra::Vector3<f64>,
    bounds: &TensionBounds,
    maximize: bool,
) -> Result<bool, TensionError> {
    if bounds.len() != 4 {
        return Err(TensionError::DimensionMismatch {
            what: "tension bounds vs wrench matrix columns",
            expected: 4,
            found: bounds.len(),
        });
    }
    let (ws, we) = (w.as_slice(), w_ext.as_slice());
    if !ws.iter().chain(we).all(|v| v.is_finite()) {
        return Err(not_finite(ws, we));
    }
    let mut t = [0.0; 4];
    Ok(
        solve_small_slices::<3>(ws, we, bounds, maximize, &mut t).is_ok()
            && crate::certificate::snap_and_certify_fixed_ok::<3>(ws, we, bounds, &mut t),
    )
}

/// [`is_feasible_planar`] prepared for a loop over poses: w_ext, the bounds and the end are
/// fixed, only W changes. [`PlanarClosedForm::is_feasible`] performs the same floating-point
/// operations in the same order as [`is_feasible_planar`] (signed 3 × 3 minors d_j of W, the
/// basis of largest |d_f|, the Hadamard test, M by Cramer's rule, the interval of eq. (6.18),
/// the end of smaller or larger Σ t, the snap and the equilibrium certificate), hence the same
/// verdict bit for bit (test `planar_closed_form_agrees_with_is_feasible_planar`), without the
/// generic padding, the bounds' vectors and the `Result` plumbing of the general path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarClosedForm {
    /// −w_ext (the right-hand side of Cramer's rule) and w_ext (the residual's start).
    neg_we: [f64; 3],
    we: [f64; 3],
    tmin: [f64; 4],
    tmax: [f64; 4],
    /// max(1, ‖w_ext‖∞): the load part of the certificate's scale.
    we_scale: f64,
    maximize: bool,
}

impl PlanarClosedForm {
    /// The prepared test, or the error [`is_feasible_planar`] gives for these bounds and w_ext.
    pub fn new(
        w_ext: &nalgebra::Vector3<f64>,
        bounds: &TensionBounds,
        maximize: bool,
    ) -> Result<Self, TensionError> {
        if bounds.len() != 4 {
            return Err(TensionError::DimensionMismatch {
                what: "tension bounds vs wrench matrix columns",
                expected: 4,
                found: bounds.len(),
            });
        }
        let we = [w_ext[0], w_ext[1], w_ext[2]];
        if !we.iter().all(|v| v.is_finite()) {
            return Err(not_finite(&[], &we));
        }
        let we_max = we.iter().fold(0.0f64, |a, e| a.max(e.abs()));
        Ok(Self {
            neg_we: we.map(|v| -v),
            we,
            tmin: std::array::from_fn(|i| bounds.min()[i]),
            tmax: std::array::from_fn(|i| bounds.max()[i]),
            we_scale: 1f64.max(we_max),
            maximize,
        })
    }

    /// The verdict of [`is_feasible_planar`] for W with columns `w` (false when an entry is not
    /// finite, where [`is_feasible_planar`] errs).
    #[inline]
    pub fn is_feasible(&self, w: &[[f64; 3]; 4]) -> bool {
        // v · 0 is 0 for a finite v and NaN otherwise: all entries are finite iff the sum is 0.
        let mut zero = 0.0;
        // Π ‖row_k‖² (a zero row is singular).
        let mut row_norm = [0.0f64; 3];
        for col in w {
            for k in 0..3 {
                zero += col[k] * 0.0;
                row_norm[k] += col[k] * col[k];
            }
        }
        if zero != 0.0 || row_norm[0] == 0.0 || row_norm[1] == 0.0 || row_norm[2] == 0.0 {
            return false;
        }
        let rows2 = 1.0 * row_norm[0] * row_norm[1] * row_norm[2];
        // Signed maximal minors: W d = 0.
        let det = |a: &[f64; 3], b: &[f64; 3], c: &[f64; 3]| det_small::<3>(a, b, c);
        let e = [
            det(&w[1], &w[2], &w[3]),
            det(&w[0], &w[2], &w[3]),
            det(&w[0], &w[1], &w[3]),
            det(&w[0], &w[1], &w[2]),
        ];
        let d = [e[0], -e[1], e[2], -e[3]];
        let dn = e[0] * e[0] + e[1] * e[1] + e[2] * e[2] + e[3] * e[3];
        // The basis of largest |det A| (ties to the first).
        let (mut free, mut best, mut d_free) = (0, d[0].abs(), d[0]);
        for (j, &dj) in d.iter().enumerate().skip(1) {
            if dj.abs() > best * (1.0 + 1e-12) {
                (free, best, d_free) = (j, dj.abs(), dj);
            }
        }
        if !(d_free != 0.0 && dn >= SINGULARITY_RATIO * SINGULARITY_RATIO * rows2) {
            return false;
        }
        let inv_free = 1.0 / d_free;
        let n = d.map(|dj| dj * inv_free);
        // M_A = A⁻¹ (−w_ext) by Cramer's rule, det A = (−1)^free d_free.
        const OTHERS: [[usize; 3]; 4] = [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]];
        let o = OTHERS[free];
        let inv_a = if free % 2 == 0 { inv_free } else { -inv_free };
        let rhs = &self.neg_we;
        let mut m = [0.0f64; 4];
        m[o[0]] = det(rhs, &w[o[1]], &w[o[2]]) * inv_a;
        m[o[1]] = det(&w[o[0]], rhs, &w[o[2]]) * inv_a;
        m[o[2]] = det(&w[o[0]], &w[o[1]], rhs) * inv_a;
        // Eq. (6.18) per cable; 4 marks "no defining cable".
        let (tmin, tmax) = (&self.tmin, &self.tmax);
        let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
        let (mut i_lo, mut b_lo, mut i_hi, mut b_hi) = (4, 0.0, 4, 0.0);
        let mut slope = 0.0;
        for i in 0..4 {
            let (mi, ni, tl, th) = (m[i], n[i], tmin[i], tmax[i]);
            slope += ni;
            if ni.abs() <= 1e-14 {
                if bound_violation(tl, th, mi) > BOUND_TOLERANCE {
                    return false;
                }
                continue;
            }
            let inv_n = d_free / d[i];
            let a = (tl - mi) * inv_n;
            let b = (th - mi) * inv_n;
            let ((l, bl), (h, bh)) = if ni > 0.0 {
                ((a, tl), (b, th))
            } else {
                ((b, th), (a, tl))
            };
            if l > lo {
                (lo, i_lo, b_lo) = (l, i, bl);
            }
            if h < hi {
                (hi, i_hi, b_hi) = (h, i, bh);
            }
        }
        if lo > hi {
            // Empty, unless only by rounding (see `interval_of`).
            let mid = 0.5 * (lo + hi);
            let worst = (0..4)
                .map(|i| bound_violation(tmin[i], tmax[i], m[i] + n[i] * mid))
                .fold(f64::NEG_INFINITY, f64::max);
            if worst > BOUND_TOLERANCE {
                return false;
            }
            (lo, hi, i_lo, i_hi) = (mid, mid, 4, 4);
        }
        if self.maximize && !hi.is_finite() {
            return false;
        }
        let take_hi = hi.is_finite()
            && if self.maximize {
                slope > 0.0
            } else {
                slope < 0.0
            };
        let (tb, at, bound) = if take_hi {
            (hi, i_hi, b_hi)
        } else {
            (lo, i_lo, b_lo)
        };
        // The certificate: snap onto violated bounds within the tolerance, then
        // ‖W t + w_ext‖∞ ≤ EQUILIBRIUM_TOLERANCE · max(1, ‖w_ext‖∞, ‖W‖∞ max|t_i|).
        let mut res = self.we;
        let mut rows = [0.0f64; 3];
        let mut t_max: f64 = 0.0;
        for i in 0..4 {
            let mut ti = if i == at { bound } else { m[i] + n[i] * tb };
            let (l, h) = (tmin[i], tmax[i]);
            if !(ti >= l && ti <= h) {
                if bound_violation(l, h, ti) > BOUND_TOLERANCE {
                    return false;
                }
                ti = if ti < l { l } else { h };
            }
            for k in 0..3 {
                res[k] += w[i][k] * ti;
                rows[k] += w[i][k].abs();
            }
            t_max = t_max.max(ti.abs());
        }
        if res.iter().any(|r| r.is_nan()) {
            return false;
        }
        let residual = res[0].abs().max(res[1].abs()).max(res[2].abs());
        let w_norm = rows[0].max(rows[1]).max(rows[2]);
        let scale = self.we_scale.max(w_norm * t_max);
        residual.is_finite() && residual <= crate::certificate::EQUILIBRIUM_TOLERANCE * scale
    }

    /// [`PlanarClosedForm::is_feasible`] of four problems at once, one per lane of the entries
    /// of `w` (`w[i][k]`: row k of column i): bit l of the result is lane l's verdict. Every
    /// lane performs the scalar operations in the same order; the scalar branches become
    /// selects of both sides (the basis `free` chooses the columns of Cramer's rule by blends,
    /// the interval ends and their cables are tracked by index). Lanes with a cable whose t_i
    /// does not depend on t^B (|N_i| ≤ 10⁻¹⁴, a measure-zero case) are decided by the scalar
    /// test. The same verdicts bit for bit (test `planar_closed_form_lanes_agree_with_scalar`).
    #[inline(always)]
    pub fn is_feasible_lanes<V: F64x4>(&self, w: &[[V; 3]; 4]) -> u32 {
        // No closures here: they would not inherit the caller's target features.
        let v = w[0][0];
        let zero = v.splat(0.0);
        // Finiteness (v · 0 is 0 or NaN) and Π ‖row_k‖².
        let mut finite = zero;
        let mut row_norm = [zero; 3];
        for col in w {
            for k in 0..3 {
                finite = finite.add(col[k].mul(zero));
                row_norm[k] = row_norm[k].add(col[k].mul(col[k]));
            }
        }
        let mut alive = V::and(
            V::and(finite.eq(zero), row_norm[0].ne(zero)),
            V::and(row_norm[1].ne(zero), row_norm[2].ne(zero)),
        );
        let rows2 = v
            .splat(1.0)
            .mul(row_norm[0])
            .mul(row_norm[1])
            .mul(row_norm[2]);
        let e = [
            det_lanes(&w[1], &w[2], &w[3]),
            det_lanes(&w[0], &w[2], &w[3]),
            det_lanes(&w[0], &w[1], &w[3]),
            det_lanes(&w[0], &w[1], &w[2]),
        ];
        let d = [e[0], e[1].neg(), e[2], e[3].neg()];
        let dn = e[0]
            .mul(e[0])
            .add(e[1].mul(e[1]))
            .add(e[2].mul(e[2]))
            .add(e[3].mul(e[3]));
        // The basis of largest |det A| (ties to the first); `free` as 0.0 … 3.0.
        let (mut free, mut best, mut d_free) = (zero, d[0].abs(), d[0]);
        let margin = v.splat(1.0 + 1e-12);
        for (j, &dj) in d.iter().enumerate().skip(1) {
            let better = dj.abs().gt(best.mul(margin));
            free = V::select(better, v.splat(j as f64), free);
            best = V::select(better, dj.abs(), best);
            d_free = V::select(better, dj, d_free);
        }
        alive = V::and(
            alive,
            V::and(
                d_free.ne(zero),
                dn.ge(v.splat(SINGULARITY_RATIO * SINGULARITY_RATIO).mul(rows2)),
            ),
        );
        if V::bits(alive) == 0 {
            return 0;
        }
        let inv_free = v.splat(1.0).div(d_free);
        let n = [
            d[0].mul(inv_free),
            d[1].mul(inv_free),
            d[2].mul(inv_free),
            d[3].mul(inv_free),
        ];
        // M_A = A⁻¹ (−w_ext) by Cramer's rule: A's columns OTHERS[free] chosen by blends.
        let (is0, is1, is2) = (free.eq(zero), free.eq(v.splat(1.0)), free.eq(v.splat(2.0)));
        let (upto1, upto2) = (free.le(v.splat(1.0)), free.le(v.splat(2.0)));
        let (c0, c1, c2) = (
            pick_lanes::<V>(is0, &w[1], &w[0]),
            pick_lanes::<V>(upto1, &w[2], &w[1]),
            pick_lanes::<V>(upto2, &w[3], &w[2]),
        );
        let odd = V::or(is1, free.eq(v.splat(3.0)));
        let inv_a = V::select(odd, inv_free.neg(), inv_free);
        let rhs = splat3(v, &self.neg_we);
        let x0 = det_lanes(&rhs, &c1, &c2).mul(inv_a);
        let x1 = det_lanes(&c0, &rhs, &c2).mul(inv_a);
        let x2 = det_lanes(&c0, &c1, &rhs).mul(inv_a);
        let m = [
            V::select(is0, zero, x0),
            V::select(is0, x0, V::select(is1, zero, x1)),
            V::select(upto1, x1, V::select(is2, zero, x2)),
            V::select(upto2, x2, zero),
        ];
        // Eq. (6.18) per cable; 4.0 marks "no defining cable".
        let (tmin, tmax) = (splat4(v, &self.tmin), splat4(v, &self.tmax));
        let (mut lo, mut hi) = (v.splat(f64::NEG_INFINITY), v.splat(f64::INFINITY));
        let (mut i_lo, mut b_lo, mut i_hi, mut b_hi) = (v.splat(4.0), zero, v.splat(4.0), zero);
        let mut slope = zero;
        let mut fixed = V::and_not(alive, alive);
        for i in 0..4 {
            let (mi, ni, tl, th) = (m[i], n[i], tmin[i], tmax[i]);
            slope = slope.add(ni);
            fixed = V::or(fixed, ni.abs().le(v.splat(1e-14)));
            let inv_n = d_free.div(d[i]);
            let a = tl.sub(mi).mul(inv_n);
            let b = th.sub(mi).mul(inv_n);
            let pos = ni.gt(zero);
            let (l, bl) = (V::select(pos, a, b), V::select(pos, tl, th));
            let (h, bh) = (V::select(pos, b, a), V::select(pos, th, tl));
            let up = l.gt(lo);
            lo = V::select(up, l, lo);
            i_lo = V::select(up, v.splat(i as f64), i_lo);
            b_lo = V::select(up, bl, b_lo);
            let down = h.lt(hi);
            hi = V::select(down, h, hi);
            i_hi = V::select(down, v.splat(i as f64), i_hi);
            b_hi = V::select(down, bh, b_hi);
        }
        let tolerance = v.splat(BOUND_TOLERANCE);
        let empty = lo.gt(hi);
        if V::bits(V::and(alive, empty)) != 0 {
            // Empty, unless only by rounding (see `interval_of`).
            let mid = v.splat(0.5).mul(lo.add(hi));
            let mut worst = v.splat(f64::NEG_INFINITY);
            for i in 0..4 {
                worst = bound_violation_lanes(self.tmin[i], self.tmax[i], m[i].add(n[i].mul(mid)))
                    .max(worst);
            }
            alive = V::and_not(alive, V::and(empty, worst.gt(tolerance)));
            (lo, hi) = (V::select(empty, mid, lo), V::select(empty, mid, hi));
            i_lo = V::select(empty, v.splat(4.0), i_lo);
            i_hi = V::select(empty, v.splat(4.0), i_hi);
        }
        let hi_finite = hi.abs().lt(v.splat(f64::INFINITY));
        if self.maximize {
            alive = V::and(alive, hi_finite);
        }
        let take_hi = V::and(
            hi_finite,
            if self.maximize {
                slope.gt(zero)
            } else {
                slope.lt(zero)
            },
        );
        let tb = V::select(take_hi, hi, lo);
        let at = V::select(take_hi, i_hi, i_lo);
        let bound = V::select(take_hi, b_hi, b_lo);
        // The certificate (see `is_feasible`).
        let mut res = splat3(v, &self.we);
        let mut rows = [zero; 3];
        let mut t_max = zero;
        for i in 0..4 {
            let (l, h) = (tmin[i], tmax[i]);
            let mut ti = V::select(at.eq(v.splat(i as f64)), bound, m[i].add(n[i].mul(tb)));
            let inside = V::and(ti.ge(l), ti.le(h));
            if V::bits(V::and_not(alive, inside)) != 0 {
                let out = V::and_not(alive, inside);
                alive = V::and_not(
                    alive,
                    V::and(
                        out,
                        bound_violation_lanes(self.tmin[i], self.tmax[i], ti).gt(tolerance),
                    ),
                );
                ti = V::select(inside, ti, V::select(ti.lt(l), l, h));
            }
            for k in 0..3 {
                res[k] = res[k].add(w[i][k].mul(ti));
                rows[k] = rows[k].add(w[i][k].abs());
            }
            t_max = ti.abs().max(t_max);
        }
        let nan = V::or(
            V::or(res[0].ne(res[0]), res[1].ne(res[1])),
            res[2].ne(res[2]),
        );
        let residual = res[0].abs().max(res[1].abs()).max(res[2].abs());
        let w_norm = rows[0].max(rows[1]).max(rows[2]);
        let scale = w_norm.mul(t_max).max(v.splat(self.we_scale));
        let certified = V::and(
            residual.lt(v.splat(f64::INFINITY)),
            residual.le(v
                .splat(crate::certificate::EQUILIBRIUM_TOLERANCE)
                .mul(scale)),
        );
        let mut verdicts = V::bits(V::and_not(V::and(alive, certified), nan));
        // Lanes with a fixed cable: the scalar test (its early exit is not a select).
        let fixed = V::bits(fixed);
        if fixed != 0 {
            self.fixed_lanes(w, fixed, &mut verdicts);
        }
        verdicts
    }

    /// The scalar verdicts of the lanes set in `lanes` (rare: kept out of the inlined kernel).
    #[cold]
    #[inline(never)]
    fn fixed_lanes<V: F64x4>(&self, w: &[[V; 3]; 4], lanes: u32, verdicts: &mut u32) {
        let entries = w.map(|col| col.map(V::to_array));
        for l in (0..4).filter(|l| lanes >> l & 1 == 1) {
            let wl = entries.map(|col| col.map(|v| v[l]));
            *verdicts = (*verdicts & !(1 << l)) | (self.is_feasible(&wl) as u32) << l;
        }
    }
}

/// `det_small::<3>` lane by lane (the same operations in the same order).
#[inline(always)]
fn det_lanes<V: F64x4>(a: &[V; 3], b: &[V; 3], c: &[V; 3]) -> V {
    a[0].mul(b[1].mul(c[2]).sub(b[2].mul(c[1])))
        .sub(b[0].mul(a[1].mul(c[2]).sub(a[2].mul(c[1]))))
        .add(c[0].mul(a[1].mul(b[2]).sub(a[2].mul(b[1]))))
}

/// `if m { a } else { b }` for 3-vectors of lanes.
#[inline(always)]
fn pick_lanes<V: F64x4>(m: V::Mask, a: &[V; 3], b: &[V; 3]) -> [V; 3] {
    [
        V::select(m, a[0], b[0]),
        V::select(m, a[1], b[1]),
        V::select(m, a[2], b[2]),
    ]
}

#[inline(always)]
fn splat3<V: F64x4>(v: V, a: &[f64; 3]) -> [V; 3] {
    [v.splat(a[0]), v.splat(a[1]), v.splat(a[2])]
}

#[inline(always)]
fn splat4<V: F64x4>(v: V, a: &[f64; 4]) -> [V; 4] {
    [v.splat(a[0]), v.splat(a[1]), v.splat(a[2]), v.splat(a[3])]
}

/// [`bound_violation`]`(lo, hi, t)` lane by lane (the same operations).
#[inline(always)]
fn bound_violation_lanes<V: F64x4>(lo: f64, hi: f64, t: V) -> V {
    let below = t.splat(lo).sub(t).div(t.splat(lo.abs().max(1.0)));
    let above = if hi.is_finite() {
        t.sub(t.splat(hi)).div(t.splat(hi.abs().max(1.0)))
    } else {
        t.splat(f64::NEG_INFINITY)
    };
    V::select(t.ne(t), t.splat(f64::INFINITY), below.max(above))
}

/// The first non-finite entry of W (column-major) or w_ext, as the solver reports it.
#[cold]
fn not_finite(ws: &[f64], we: &[f64]) -> TensionError {
    match ws.iter().position(|v| !v.is_finite()) {
        Some(index) => TensionError::NotFinite {
            what: "wrench matrix entry (column-major index)",
            index,
            value: ws[index],
        },
        None => {
            let index = we.iter().position(|v| !v.is_finite()).unwrap_or(0);
            TensionError::NotFinite {
                what: "external wrench component",
                index,
                value: we[index],
            }
        }
    }
}

/// A feasible interval [lo, hi] of t^B with the cables whose bounds define its ends.
#[derive(Debug, Clone, Copy)]
struct Interval {
    lo: f64,
    hi: f64,
    /// (cable, bound) defining `lo` / `hi`, if the interval is not a rounding-collapsed point.
    at_lo: Option<(usize, f64)>,
    at_hi: Option<(usize, f64)>,
}

/// Algorithm 6.1: intersect the intervals of t^B allowed by each cable's bounds (eq. (6.18)).
#[inline(always)]
fn interval_of(m: &[f64], n: &[f64], problem: &TensionProblem) -> Result<Interval, Infeasibility> {
    let (tmin, tmax) = (
        problem.bounds.min().as_slice(),
        problem.bounds.max().as_slice(),
    );
    let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
    let (mut at_lo, mut at_hi) = (None, None);
    for (i, (((&mi, &ni), &tl), &th)) in m.iter().zip(n).zip(tmin).zip(tmax).enumerate() {
        if ni.abs() <= 1e-14 {
            // t_i does not depend on t^B: it must satisfy its bounds by itself.
            if bound_violation(tl, th, mi) > BOUND_TOLERANCE {
                return Err(Infeasibility::NoFeasibleTension);
            }
            continue;
        }
        let inv = 1.0 / ni;
        let a = (tl - mi) * inv;
        let b = (th - mi) * inv; // ±∞ for an infinite t_max
        let ((l, bl), (h, bh)) = if ni > 0.0 {
            ((a, tl), (b, th))
        } else {
            ((b, th), (a, tl))
        };
        if l > lo {
            lo = l;
            at_lo = Some((i, bl));
        }
        if h < hi {
            hi = h;
            at_hi = Some((i, bh));
        }
    }
    if lo > hi {
        // Empty, unless only by rounding: accept the midpoint if it violates no bound by
        // more than `BOUND_TOLERANCE` (relative), the certificate's own tolerance, which
        // decides afterwards. Two fixed cables give two zero-width intervals whose ends differ
        // by the rounding of M and N, which grows with the other tensions, not with the fixed
        // bounds: the 10⁶-problem soak found them 10⁻¹⁰ (relative) apart, beyond the clipping
        // tolerance `SET_TOLERANCE`.
        let mid = 0.5 * (lo + hi);
        let worst = (0..n.len())
            .map(|i| bound_violation(tmin[i], tmax[i], m[i] + n[i] * mid))
            .fold(f64::NEG_INFINITY, f64::max);
        if worst > BOUND_TOLERANCE {
            return Err(Infeasibility::NoFeasibleTension);
        }
        return Ok(Interval {
            lo: mid,
            hi: mid,
            at_lo: None,
            at_hi: None,
        });
    }
    Ok(Interval {
        lo,
        hi,
        at_lo,
        at_hi,
    })
}

/// Writes t at the end of the interval with the smaller (or larger) Σ t. Σ t = Σ M + (Σ N) t^B
/// is linear in t^B, so both ends are compared through the sign of Σ N; the cable whose bound
/// defines the chosen end is set exactly onto that bound (it differs from M_i + N_i t^B only by
/// rounding).
#[inline(always)]
fn write_end(
    m: &[f64],
    n: &[f64],
    iv: &Interval,
    maximize: bool,
    t: &mut [f64],
) -> Result<(), Infeasibility> {
    if maximize && !iv.hi.is_finite() {
        return Err(Infeasibility::Unbounded {
            method: "closed-form",
        });
    }
    let slope: f64 = n.iter().sum();
    let take_hi = iv.hi.is_finite() && if maximize { slope > 0.0 } else { slope < 0.0 };
    let (tb, at) = if take_hi {
        (iv.hi, iv.at_hi)
    } else {
        (iv.lo, iv.at_lo)
    };
    for ((ti, &mi), &ni) in t.iter_mut().zip(m).zip(n) {
        *ti = mi + ni * tb;
    }
    if let Some((i, bound)) = at {
        t[i] = bound;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::TensionBounds;
    use nalgebra::DMatrix;

    #[test]
    fn basis_has_maximal_determinant() {
        // Cable 0 and 1 nearly parallel: a poor basis {0, 1} must not be chosen.
        let w = DMatrix::from_row_slice(2, 3, &[1.0, 1.0, 0.0, 0.0, 1e-9, 1.0]);
        let we = DVector::from_vec(vec![-1.0, -1.0]);
        let b = TensionBounds::uniform(3, 0.0, 10.0).unwrap();
        let p = TensionProblem::new(&w, &we, &b);
        let mut cf = ClosedForm::default();
        cf.interval(&p).unwrap();
        assert!(cf.n_vec.iter().all(|v| v.abs() <= 1.0 + 1e-12));
        assert!(cf.free == 0 || cf.free == 1);
        // N is a null vector of W, M a solution.
        let n = DVector::from_column_slice(&cf.n_vec);
        let m = DVector::from_column_slice(&cf.m_vec);
        assert!((&w * n).norm() < 1e-15);
        assert!((&w * m + we).norm() < 1e-12);
    }

    /// Tensions at both interval ends from a parametrisation.
    fn ends(cf: &ClosedForm, p: &TensionProblem) -> Option<(Vec<f64>, Vec<f64>)> {
        let mut c = cf.clone();
        let (lo, hi) = c.interval(p).ok()?;
        let at = |l: f64| -> Vec<f64> {
            (0..c.m_vec.len())
                .map(|i| c.m_vec[i] + c.n_vec[i] * l)
                .collect()
        };
        Some((at(lo), at(hi)))
    }

    /// Deterministic pseudo-random numbers in [−1, 1) (xorshift64 from `state`).
    fn uniform_stream(mut state: u64) -> impl FnMut() -> f64 {
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        }
    }

    #[test]
    fn small_fast_path_agrees_with_elimination() {
        // Deterministic pseudo-random problems for DOF 1, 2, 3 (n = DOF + 1).
        let mut rnd = uniform_stream(0x9e37_79b9_7f4a_7c15u64);
        let mut compared = 0;
        for case in 0..600 {
            let m = 1 + case % 3;
            let n = m + 1;
            let w = DMatrix::from_fn(m, n, |_, _| rnd());
            let we = DVector::from_fn(m, |_, _| 3.0 * rnd());
            let b = TensionBounds::uniform(n, 0.5, 10.0).unwrap();
            let p = TensionProblem::new(&w, &we, &b);
            let (mut fast, mut slow) = (ClosedForm::default(), ClosedForm::default());
            let rf = match m {
                1 => fast.parametrise_small::<1>(&p),
                2 => fast.parametrise_small::<2>(&p),
                _ => fast.parametrise_small::<3>(&p),
            };
            let rs = slow.parametrise_general(&p);
            assert_eq!(rf.is_ok(), rs.is_ok(), "case {case}: {rf:?} vs {rs:?}");
            if rf.is_err() {
                continue;
            }
            // The same null direction (up to scale), both |N_i| ≤ 1, M solves W M = −w_ext.
            let nf = DVector::from_column_slice(&fast.n_vec);
            let mf = DVector::from_column_slice(&fast.m_vec);
            assert!(nf.amax() <= 1.0 + 1e-12);
            assert!((&w * &nf).amax() < 1e-12, "case {case}");
            assert!(
                (&w * &mf + &we).amax() < 1e-11 * (1.0 + mf.amax()),
                "case {case}"
            );
            let ns = DVector::from_column_slice(&slow.n_vec);
            assert!(((nf.dot(&ns)).abs() - nf.norm() * ns.norm()).abs() < 1e-10);
            // Same feasible set: the same tensions at the interval ends.
            match (ends(&fast, &p), ends(&slow, &p)) {
                (Some((fl, fh)), Some((sl, sh))) => {
                    let close = |a: &[f64], b: &[f64]| {
                        a.iter()
                            .zip(b)
                            .all(|(x, y)| (x - y).abs() < 1e-9 * (1.0 + y.abs()))
                    };
                    assert!(
                        (close(&fl, &sl) && close(&fh, &sh))
                            || (close(&fl, &sh) && close(&fh, &sl)),
                        "case {case}: {fl:?} {fh:?} vs {sl:?} {sh:?}"
                    );
                    compared += 1;
                }
                (None, None) => {}
                (a, b) => panic!("case {case}: feasibility differs: {a:?} vs {b:?}"),
            }
        }
        assert!(compared > 50, "only {compared} feasible cases");
    }

    #[test]
    fn small_fast_path_hand_values() {
        // Planar point held by 3 cables (m = 2): t1 (1, 0) + t2 (0, 1) + t3 (−1, −1) = (2, 1).
        // Null vector ∝ (1, 1, 1); with t3 free: t1 = 2 + t3, t2 = 1 + t3.
        let w = DMatrix::from_row_slice(2, 3, &[1.0, 0.0, -1.0, 0.0, 1.0, -1.0]);
        let we = DVector::from_vec(vec![-2.0, -1.0]);
        let b = TensionBounds::uniform(3, 1.0, 10.0).unwrap();
        let p = TensionProblem::new(&w, &we, &b);
        let mut cf = ClosedForm::default();
        let (lo, hi) = cf.interval(&p).unwrap();
        assert_eq!(cf.n_vec, vec![1.0, 1.0, 1.0]);
        // t3 ∈ [1, 9] (t1 = 2 + t3 ≤ 10) once the free cable is chosen: check via tensions.
        let t_lo: Vec<f64> = (0..3).map(|i| cf.m_vec[i] + cf.n_vec[i] * lo).collect();
        let t_hi: Vec<f64> = (0..3).map(|i| cf.m_vec[i] + cf.n_vec[i] * hi).collect();
        for (a, e) in t_lo.iter().zip([3.0, 2.0, 1.0]) {
            assert!((a - e).abs() < 1e-14);
        }
        for (a, e) in t_hi.iter().zip([10.0, 9.0, 8.0]) {
            assert!((a - e).abs() < 1e-14);
        }
        // A rank-deficient W is singular.
        let w = DMatrix::from_row_slice(2, 3, &[1.0, 2.0, 3.0, 2.0, 4.0, 6.0]);
        let p = TensionProblem::new(&w, &we, &b);
        assert!(matches!(
            cf.interval(&p),
            Err(Infeasibility::SingularPose { .. })
        ));
    }

    /// The fixed-size solver path (Algorithm 6.1 on the stack, active cable set exactly onto its
    /// bound) gives the general path's tensions, for min and max Σ t.
    #[test]
    fn small_solve_agrees_with_general_solve() {
        let mut rnd = uniform_stream(0x2545_f491_4f6c_dd1du64);
        let mut compared = 0;
        for case in 0..900 {
            let m = 1 + case % 3;
            let n = m + 1;
            let w = DMatrix::from_fn(m, n, |_, _| rnd());
            let we = DVector::from_fn(m, |_, _| 3.0 * rnd());
            let hi = if case % 4 == 0 { f64::INFINITY } else { 10.0 };
            let b = TensionBounds::uniform(n, 0.5, hi).unwrap();
            let p = TensionProblem::new(&w, &we, &b);
            for maximize in [false, true] {
                let mut fast = vec![0.0; n];
                let rf = ClosedForm::default().solve(&p, maximize, &mut fast);
                let mut cf = ClosedForm::default();
                let mut slow = vec![0.0; n];
                let rs = cf.parametrise_general(&p).and_then(|()| {
                    let iv = interval_of(&cf.m_vec, &cf.n_vec, &p)?;
                    write_end(&cf.m_vec, &cf.n_vec, &iv, maximize, &mut slow)
                });
                assert_eq!(rf.is_ok(), rs.is_ok(), "case {case}: {rf:?} vs {rs:?}");
                if rf.is_ok() {
                    compared += 1;
                    for (a, e) in fast.iter().zip(&slow) {
                        assert!((a - e).abs() <= 1e-9 * e.abs().max(1.0), "case {case}");
                    }
                    // Certified as is.
                    assert!(crate::certify(&w, &we, &b, &fast).is_valid(), "case {case}");
                }
            }
        }
        assert!(compared > 100, "{compared}");
    }

    /// The prepared planar test gives the verdict of `is_feasible_planar` (itself the solver's
    /// verdict) on random, near-singular, degenerate and near-boundary problems: tensions placed
    /// on or just across their bounds, fixed cables (t_min = t_max), no upper bound, zero and
    /// parallel columns, non-finite entries; both ends (l1 and l1-max).
    /// W of planar problem `case`: random, or with two parallel columns, a zero row, a
    /// near-dependent column (a cable whose tension does not depend on t^B), a non-finite entry.
    fn planar_matrix(case: usize, rnd: &mut impl FnMut() -> f64) -> nalgebra::Matrix3x4<f64> {
        let mut w = nalgebra::Matrix3x4::from_fn(|_, _| rnd());
        match case % 11 {
            1 => w.set_column(1, &(w.column(0) * (1.0 + 1e-13 * rnd()))),
            2 => w.row_mut(case % 3).fill(0.0),
            3 => w.set_column(3, &(w.column(0) * rnd() + w.column(1) * rnd())),
            4 => w[(case % 3, case % 4)] = [f64::NAN, f64::INFINITY][case % 2],
            _ => {}
        }
        w
    }

    /// Planar problem `case`: W ([`planar_matrix`]), bounds (some fixed cables, some infinite
    /// t_max) and w_ext = −W t for tensions t on, or just across, their bounds (or a random
    /// w_ext); `None` when w_ext is not finite.
    fn planar_problem(
        case: usize,
        rnd: &mut impl FnMut() -> f64,
    ) -> Option<(
        nalgebra::Matrix3x4<f64>,
        nalgebra::Vector3<f64>,
        TensionBounds,
    )> {
        use nalgebra::Vector3;
        let w = planar_matrix(case, rnd);
        let lo = 5.0 * (rnd() + 1.0);
        let mut hi = [lo + 100.0 * (rnd() + 1.0); 4];
        match case % 5 {
            1 => hi[case % 4] = lo,
            2 => hi[case % 4] = f64::INFINITY,
            _ => {}
        }
        let b = TensionBounds::new(vec![lo; 4], hi.to_vec()).unwrap();
        let t: Vec<f64> = (0..4)
            .map(|i| {
                let top = if hi[i].is_finite() { hi[i] } else { lo + 50.0 };
                let nudge = 1.0 + [0.0, 1e-10, -1e-10, 1e-8, 0.0][case % 5];
                match (case / 5 + i) % 4 {
                    0 => lo * nudge,
                    1 => top * nudge,
                    _ => lo + (top - lo) * 0.5 * (rnd() + 1.0),
                }
            })
            .collect();
        let mut we: Vector3<f64> = -(w * nalgebra::Vector4::from_row_slice(&t));
        if case.is_multiple_of(7) {
            we = Vector3::from_fn(|_, _| 200.0 * rnd());
        }
        we.iter().all(|v| v.is_finite()).then_some((w, we, b))
    }

    /// The four lanes of [`PlanarClosedForm::is_feasible_lanes`], in the portable build and (on
    /// a CPU with AVX2) the AVX2 build, give the scalar [`PlanarClosedForm::is_feasible`] verdict
    /// of each lane: one lane holds a problem of [`planar_problem`] (borderline tensions, fixed
    /// cables, infinite t_max, degenerate W, NaN), the others the same W perturbed by 10⁻¹²
    /// (borderline too) or another [`planar_matrix`].
    #[test]
    fn planar_closed_form_lanes_agree_with_scalar() {
        use crate::lanes::{F64x4, Portable};
        let mut rnd = uniform_stream(0x1405_7b7e_f767_814fu64);
        let (mut yes, mut no, mut fixed) = (0, 0, 0);
        for case in 0..100_000 {
            let Some((w0, we, b)) = planar_problem(case, &mut rnd) else {
                continue;
            };
            let mut ws = [w0; 4];
            ws[1] = w0.map(|v| v * (1.0 + 1e-12 * rnd()));
            ws[2] = planar_matrix(case / 3 + 5, &mut rnd);
            ws[3] = planar_matrix(case / 7 + 3, &mut rnd);
            ws.rotate_left(case % 4);
            let cols: [[[f64; 3]; 4]; 4] =
                ws.map(|w| std::array::from_fn(|i| [w[(0, i)], w[(1, i)], w[(2, i)]]));
            let lanes = |v: Portable| -> [[Portable; 3]; 4] {
                std::array::from_fn(|i| std::array::from_fn(|k| v.load(cols.map(|c| c[i][k]))))
            };
            for maximize in [false, true] {
                let cf = PlanarClosedForm::new(&we, &b, maximize).unwrap();
                let expected = (0..4)
                    .map(|l| (cf.is_feasible(&cols[l]) as u32) << l)
                    .sum::<u32>();
                let portable = cf.is_feasible_lanes(&lanes(Portable([0.0; 4])));
                assert_eq!(
                    portable, expected,
                    "case {case}, maximize {maximize}: {ws:?} {we} {b:?}"
                );
                #[cfg(target_arch = "x86_64")]
                if let Some(v) = crate::lanes::Avx2::detect() {
                    let w: [[crate::lanes::Avx2; 3]; 4] = std::array::from_fn(|i| {
                        std::array::from_fn(|k| v.load(cols.map(|c| c[i][k])))
                    });
                    assert_eq!(
                        cf.is_feasible_lanes(&w),
                        expected,
                        "AVX2, case {case}, maximize {maximize}"
                    );
                }
                yes += expected.count_ones();
                no += 4 - expected.count_ones();
                fixed += (case % 11 == 3) as u32;
            }
        }
        assert!(
            yes > 50_000 && no > 50_000 && fixed > 1000,
            "{yes} feasible, {no} infeasible"
        );
    }

    #[test]
    fn planar_closed_form_agrees_with_is_feasible_planar() {
        use nalgebra::Vector3;
        let mut rnd = uniform_stream(0x5851_f42d_4c95_7f2du64);
        let (mut yes, mut no) = (0, 0);
        for case in 0..200_000 {
            let Some((w, we, b)) = planar_problem(case, &mut rnd) else {
                continue;
            };
            for maximize in [false, true] {
                let lean = PlanarClosedForm::new(&we, &b, maximize).unwrap();
                let expected = is_feasible_planar(&w, &we, &b, maximize).unwrap_or(false);
                assert_eq!(
                    lean.is_feasible(&std::array::from_fn(|i| {
                        [w[(0, i)], w[(1, i)], w[(2, i)]]
                    })),
                    expected,
                    "case {case}, maximize {maximize}: {w} {we} {b:?}"
                );
                if expected { yes += 1 } else { no += 1 }
            }
        }
        assert!(
            yes > 20_000 && no > 20_000,
            "{yes} feasible, {no} infeasible"
        );
        // The errors of `is_feasible_planar`, at construction.
        let we = Vector3::new(0.0, f64::NAN, 0.0);
        assert!(
            PlanarClosedForm::new(&we, &TensionBounds::uniform(4, 1.0, 2.0).unwrap(), false)
                .is_err()
        );
        let we = Vector3::zeros();
        assert!(
            PlanarClosedForm::new(&we, &TensionBounds::uniform(3, 1.0, 2.0).unwrap(), false)
                .is_err()
        );
    }
}
