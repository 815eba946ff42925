//! # Dense active-set solvers (redundancy r ≥ 3)
//!
//! On the null-space parametrisation t = t0 + N λ (N orthonormal n × r, see [`crate::null_space`])
//! the tension bounds become at most 2n linear inequalities in the r unknowns λ:
//!
//! ```text
//!   N_i λ ≥ t_min,i − t0_i,     −N_i λ ≥ t0_i − t_max,i   (the second only for finite t_max,i)
//! ```
//!
//! (a cable with N_i = 0 has t_i = t0_i on the whole equilibrium set: its bounds are checked
//! directly, with the certificate's tolerance since t0 carries the rounding of −W⁺ w_ext, and
//! it contributes no row; at r = 0 every cable is such a cable). Every row has norm ‖N_i‖ ≤ 1, so slacks are in tension
//! units. On these rows `a_jᵀ x ≥ b_j`:
//!
//! - **l2** (thesis eq. (6.17)): ‖t0 + N λ‖² = ‖t0‖² + 2 gᵀλ + ‖λ‖² with g = Nᵀ t0, a strictly
//!   convex QP with identity Hessian, solved by the dual active-set method of Goldfarb & Idnani
//!   (1983): start at the unconstrained minimum λ = −g, repeatedly pick the most violated
//!   constraint q and take the combined primal/dual step (z = the part of a_q orthogonal to the
//!   active normals, r = R⁻¹ Q₁ᵀ a_q from the QR of the active normals; partial steps drop the
//!   active constraint whose multiplier reaches 0 first). When no step is possible (z = 0 and no
//!   r_j > 0) the constraints are inconsistent; that verdict is confirmed by phase 1 below.
//! - **l1, l1-max** (eq. (6.19)): min ± (Nᵀ1)ᵀλ (Σ t = Σ t0 + (Nᵀ1)ᵀλ); **linf**: min s over
//!   (λ, s) with the extra rows s − N_i λ ≥ t0_i (s ≥ t_i). These LPs are solved by the primal
//!   active-set (simplex) method in inequality form: at a point x with a linearly independent
//!   working set W, if c has a component −p outside the span of the working normals, move along
//!   p; otherwise c = Σ_W μ_j a_j, and x is optimal when μ ≥ 0; else the constraint j with
//!   μ_j < 0 is released along p = Q₁ R⁻ᵀ e_j (A_W p = e_j, so cᵀp = μ_j < 0). The ratio test adds
//!   the first blocking row; none blocking means the LP is unbounded. At a vertex this is the
//!   simplex method on the slack form (the slacks of W are the non-basic variables, μ their
//!   reduced costs), and **Bland's rule** (release the smallest-index row with μ_j < 0, add the
//!   smallest-index row among ratio-test ties) prevents cycling.
//!   The LPs start from the l2 optimum: a feasible point whose active rows are an independent
//!   working set (about 30 % faster than starting from phase 1 below).
//! - **Phase 1** (feasibility): min σ over (λ, σ) subject to a_jᵀλ + σ ≥ b_j and σ ≥ 0, started
//!   from the feasible point λ = 0, σ = max(0, max_j b_j), by the same LP method. The feasible
//!   set is empty exactly when the optimum σ* > 0; when the row σ ≥ 0 enters the working set,
//!   the other working rows are an independent working set of a feasible point. Phase 1
//!   confirms every infeasibility verdict of the dual method (reported as
//!   [`Infeasibility::NoFeasibleTension`]); if it finds a feasible point instead, the dense
//!   path has failed numerically.
//!
//! Working-set normals are factored afresh each iteration by Gram–Schmidt with
//! re-orthogonalisation (r + 1 ≤ 7 columns: cheaper than updating, and no drift). Iterations are
//! capped (10·(rows + r) + 50); a cap, a numerically dependent working set or an inconsistent
//! verdict is a [`DenseEnd::Failed`] reason, on which [`crate::TensionSolver`] falls back to
//! Clarabel. All buffers are reused: no allocation after the first call for a problem size.
//!
//! ## References
//! - Goldfarb, D. & Idnani, A. (1983), *A numerically stable dual method for solving strictly
//!   convex quadratic programs*, Math. Programming 27, 1–33.
//! - Nocedal, J. & Wright, S. (2006), *Numerical Optimization*, 2nd ed., §13.3 (simplex pivots,
//!   degeneracy), §16.5 (active-set methods, Alg. 16.3).
//! - Bland, R. G. (1977), *New finite pivoting rules for the simplex method*, Math. Oper. Res. 2.
//! - Thesis eqs. (6.17), (6.19); Picard, Caro, Plestan & Claveau 2020, eq. (5).

use crate::certificate::{BOUND_TOLERANCE, bound_violation};
use crate::interior_point::Objective;
use crate::null_space::NullSpace;
use crate::{Infeasibility, TensionBounds};

/// Rows whose null-space row has a norm below this are "fixed" cables (t_i = t0_i).
pub(crate) const ZERO_ROW: f64 = 1e-13;
/// Relative feasibility tolerance of a row (slack ≥ −FEAS · scale of the row).
const FEAS: f64 = 1e-12;

/// What a row of the inequality system stands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Tag {
    /// t_i ≥ t_min,i.
    Lower(usize),
    /// t_i ≤ t_max,i.
    Upper(usize),
    /// s ≥ t_i (linf).
    Level,
    /// σ ≥ 0 (phase 1).
    Sigma,
}

/// How a dense solve ended.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum DenseEnd {
    /// Optimal tensions were written (not yet certified).
    Solved,
    /// A verdict: no tensions (empty feasible set, or unbounded objective).
    Infeasible(Infeasibility),
    /// Numerical trouble: the caller should use another solver.
    Failed(&'static str),
}

/// How an active-set LP run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum LpEnd {
    Optimal,
    Unbounded,
    /// The stop row entered the working set.
    Reached,
    Limit,
    Dependent,
}

/// Buffers of the dense active-set solvers.
#[derive(Debug, Clone, Default)]
pub(crate) struct ActiveSet {
    /// r (λ unknowns) of the current problem.
    r: usize,
    /// Bound rows in λ-space: `nb` rows × r, row-major, with right-hand sides, tolerances, tags.
    nb: usize,
    base_a: Vec<f64>,
    base_b: Vec<f64>,
    base_tol: Vec<f64>,
    base_tag: Vec<Tag>,
    /// The inequality system of the current run: `rows` × `d`, row-major.
    rows: usize,
    d: usize,
    a: Vec<f64>,
    b: Vec<f64>,
    tol: Vec<f64>,
    tag: Vec<Tag>,
    /// Objective (LP) and iterate.
    c: Vec<f64>,
    x: Vec<f64>,
    /// Working set (row indices) and membership; GI multipliers, parallel to `work`.
    work: Vec<usize>,
    in_work: Vec<bool>,
    u: Vec<f64>,
    /// Q₁ (d × k, column-major) and R (k × k, column-major, stride d) of the working normals.
    q: Vec<f64>,
    rr: Vec<f64>,
    /// Scratch vectors of length d.
    p: Vec<f64>,
    v: Vec<f64>,
    y: Vec<f64>,
}

#[inline]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

impl ActiveSet {
    /// Solves `objective` on the bound rows of `ns` (r ≥ 1), writing optimal tensions into `t`.
    pub fn solve(
        &mut self,
        ns: &NullSpace,
        bounds: &TensionBounds,
        objective: Objective,
        method: &'static str,
        t: &mut [f64],
    ) -> DenseEnd {
        if let Err(reason) = self.build_rows(ns, bounds) {
            return DenseEnd::Infeasible(reason);
        }
        let r = self.r;
        match objective {
            Objective::L2 => {
                if let Err(end) = self.feasible_start(&ns.g) {
                    return end;
                }
            }
            Objective::L1 | Objective::L1Max => {
                if let Err(end) = self.feasible_start(&ns.g) {
                    return end;
                }
                // λ and the working set of the l2 optimum (independent active bound rows).
                self.load_rows(r, 0);
                let sign = if objective == Objective::L1 {
                    1.0
                } else {
                    -1.0
                };
                for j in 0..r {
                    let col = &ns.basis[j * ns.n..(j + 1) * ns.n];
                    self.c[j] = sign * col.iter().sum::<f64>();
                }
                match self.lp(None) {
                    LpEnd::Optimal => {}
                    LpEnd::Unbounded if objective == Objective::L1Max => {
                        return DenseEnd::Infeasible(Infeasibility::Unbounded { method });
                    }
                    LpEnd::Unbounded => return DenseEnd::Failed("active-set LP: l1 unbounded"),
                    LpEnd::Reached | LpEnd::Limit => {
                        return DenseEnd::Failed("active-set LP: iteration limit");
                    }
                    LpEnd::Dependent => {
                        return DenseEnd::Failed("active-set LP: dependent working set");
                    }
                }
            }
            Objective::Linf => {
                if let Err(end) = self.feasible_start(&ns.g) {
                    return end;
                }
                self.load_linf(ns);
                match self.lp(None) {
                    LpEnd::Optimal => {}
                    LpEnd::Unbounded => return DenseEnd::Failed("active-set LP: linf unbounded"),
                    LpEnd::Reached | LpEnd::Limit => {
                        return DenseEnd::Failed("active-set LP: iteration limit");
                    }
                    LpEnd::Dependent => {
                        return DenseEnd::Failed("active-set LP: dependent working set");
                    }
                }
            }
        }
        self.write_tensions(ns, bounds, t);
        DenseEnd::Solved
    }

    /// min ½‖λ‖² + gᵀλ on the bound rows of `ns` for a given g (l2-mid: g = Nᵀ(t0 − t_m), so
    /// that the objective is ½‖t − t_m‖² up to a constant), by the dual active set with the
    /// phase-1 confirmation of infeasibility, writing the optimal tensions into `t`.
    pub fn solve_l2_with(
        &mut self,
        ns: &NullSpace,
        bounds: &TensionBounds,
        g: &[f64],
        t: &mut [f64],
    ) -> DenseEnd {
        if let Err(reason) = self.build_rows(ns, bounds) {
            return DenseEnd::Infeasible(reason);
        }
        if let Err(end) = self.feasible_start(g) {
            return end;
        }
        self.write_tensions(ns, bounds, t);
        DenseEnd::Solved
    }

    /// The optimally safe LP (Borgstrom et al. 2009): max s over (λ, s) subject to
    /// t_i − t_min,i ≥ s and t_max,i − t_i ≥ α s (finite t_max only), t = t0 + N λ, by the
    /// primal active-set method from λ = 0 and the largest s there. Writes t and returns s*
    /// with [`DenseEnd::Solved`] (s* < 0: the feasible set is empty; callers decide).
    pub fn optimally_safe(
        &mut self,
        ns: &NullSpace,
        bounds: &TensionBounds,
        alpha: f64,
        t: &mut [f64],
    ) -> (DenseEnd, f64) {
        let (n, r) = (ns.n, ns.r());
        let (lo, hi) = (bounds.min(), bounds.max());
        let d = r + 1;
        let rows = n + hi.iter().filter(|h| h.is_finite()).count();
        self.r = r;
        self.work.clear();
        self.u.clear();
        self.size(rows, d);
        let mut k = 0;
        let (mut s0, mut top) = (f64::INFINITY, 0);
        for i in 0..n {
            let scale = 1f64.max(ns.t0[i].abs());
            for (coef, sign, b, tol) in [
                (1.0, 1.0, lo[i] - ns.t0[i], FEAS * scale.max(lo[i].abs())),
                (alpha, -1.0, ns.t0[i] - hi[i], FEAS * scale.max(hi[i].abs())),
            ] {
                if !b.is_finite() {
                    continue;
                }
                for j in 0..r {
                    self.a[k * d + j] = sign * ns.basis[j * n + i];
                }
                self.a[k * d + r] = -coef;
                self.b[k] = b;
                self.tol[k] = tol;
                self.tag[k] = Tag::Level;
                // At λ = 0: s ≤ −b / coef.
                if -b / coef < s0 {
                    (s0, top) = (-b / coef, k);
                }
                k += 1;
            }
        }
        self.x.fill(0.0);
        self.x[r] = s0;
        self.c.fill(0.0);
        self.c[r] = -1.0;
        self.work.push(top);
        self.in_work[top] = true;
        let end = match self.lp(None) {
            LpEnd::Optimal => DenseEnd::Solved,
            LpEnd::Unbounded => DenseEnd::Infeasible(Infeasibility::Unbounded {
                method: "optimally-safe",
            }),
            LpEnd::Reached | LpEnd::Limit => DenseEnd::Failed("active-set LP: iteration limit"),
            LpEnd::Dependent => DenseEnd::Failed("active-set LP: dependent working set"),
        };
        ns.tensions(&self.x[..r], t);
        (end, self.x[r])
    }

    /// The l2 optimum (dual active set): a feasible λ in `x[..r]` with an independent working
    /// set of active bound rows in `work`, the start of the LPs. An infeasibility verdict of the
    /// dual method is confirmed by phase 1.
    fn feasible_start(&mut self, g: &[f64]) -> Result<(), DenseEnd> {
        match self.goldfarb_idnani(g) {
            Err(DenseEnd::Infeasible(reason)) => match self.phase1() {
                Err(DenseEnd::Infeasible(_)) => Err(DenseEnd::Infeasible(reason)),
                Err(other) => Err(other),
                Ok(()) => Err(DenseEnd::Failed(
                    "dual active set: infeasible, phase 1 feasible",
                )),
            },
            other => other,
        }
    }

    /// The bound rows N_i λ ≥ t_min,i − t0_i, −N_i λ ≥ t0_i − t_max,i; fixed cables are checked.
    fn build_rows(&mut self, ns: &NullSpace, bounds: &TensionBounds) -> Result<(), Infeasibility> {
        let (n, r) = (ns.n, ns.r());
        let (lo, hi) = (bounds.min(), bounds.max());
        self.r = r;
        self.base_a.clear();
        self.base_b.clear();
        self.base_tol.clear();
        self.base_tag.clear();
        self.base_a.reserve(2 * n * r);
        for buf in [&mut self.base_b, &mut self.base_tol] {
            buf.reserve(2 * n);
        }
        self.base_tag.reserve(2 * n);
        for i in 0..n {
            let t0 = ns.t0[i];
            let mut norm2 = 0.0;
            for j in 0..r {
                norm2 += ns.basis[j * n + i] * ns.basis[j * n + i];
            }
            if norm2 <= ZERO_ROW * ZERO_ROW {
                // t_i = t0_i on the whole equilibrium set (every cable at r = 0). t0 carries
                // the rounding of −W⁺ w_ext (≈ κ(W) ε ‖t‖, 10⁻¹³–10⁻⁹ relative), so the
                // cable is judged with the certificate's tolerance, which snaps it onto its
                // bound, not with FEAS: a fixed cable (t_min = t_max) 10⁻¹² off its bound was
                // "no feasible tension" (soak problems 37673 and 51618, l2-mid at r = 0).
                if bound_violation(lo[i], hi[i], t0) > BOUND_TOLERANCE {
                    return Err(Infeasibility::NoFeasibleTension);
                }
                continue;
            }
            let scale = 1f64.max(t0.abs());
            for j in 0..r {
                self.base_a.push(ns.basis[j * n + i]);
            }
            self.base_b.push(lo[i] - t0);
            self.base_tol.push(FEAS * scale.max(lo[i].abs()));
            self.base_tag.push(Tag::Lower(i));
            if hi[i].is_finite() {
                for j in 0..r {
                    self.base_a.push(-ns.basis[j * n + i]);
                }
                self.base_b.push(t0 - hi[i]);
                self.base_tol.push(FEAS * scale.max(hi[i].abs()));
                self.base_tag.push(Tag::Upper(i));
            }
        }
        self.nb = self.base_b.len();
        Ok(())
    }

    /// Sizes the system buffers for `rows` × `d` (no allocation once large enough).
    fn size(&mut self, rows: usize, d: usize) {
        self.rows = rows;
        self.d = d;
        self.a.resize(rows * d, 0.0);
        self.b.resize(rows, 0.0);
        self.tol.resize(rows, 0.0);
        self.tag.resize(rows, Tag::Level);
        self.in_work.clear();
        self.in_work.resize(rows, false);
        for &k in &self.work {
            self.in_work[k] = true;
        }
        self.c.resize(d, 0.0);
        self.x.resize(d, 0.0);
        self.q.resize(d * d, 0.0);
        self.rr.resize(d * d, 0.0);
        self.p.resize(d, 0.0);
        self.v.resize(d, 0.0);
        self.y.resize(d, 0.0);
        self.work.reserve(d + 1);
        self.u.reserve(d + 1);
    }

    /// The bound rows with `extra` zero columns appended (x keeps its first r entries, the
    /// working set keeps its rows, which are bound rows).
    fn load_rows(&mut self, d: usize, extra_rows: usize) {
        let (nb, r) = (self.nb, self.r);
        // x[..r] and the working set survive `size` (resize keeps the leading entries).
        self.size(nb + extra_rows, d);
        for k in 0..nb {
            for j in 0..d {
                self.a[k * d + j] = if j < r { self.base_a[k * r + j] } else { 0.0 };
            }
            self.b[k] = self.base_b[k];
            self.tol[k] = self.base_tol[k];
            self.tag[k] = self.base_tag[k];
        }
        for j in r..d {
            self.x[j] = 0.0;
        }
        self.c.fill(0.0);
    }

    /// The linf system in (λ, s): bound rows, then s − N_i λ ≥ t0_i for every cable; started
    /// at s = max_i t_i(λ) with that cable's level row added to the working set.
    fn load_linf(&mut self, ns: &NullSpace) {
        let (n, r, nb) = (ns.n, self.r, self.nb);
        let d = r + 1;
        self.load_rows(d, n);
        let (mut s, mut top) = (f64::NEG_INFINITY, nb);
        for i in 0..n {
            let k = nb + i;
            let mut ti = ns.t0[i];
            for j in 0..r {
                let v = ns.basis[j * n + i];
                self.a[k * d + j] = -v;
                ti += v * self.x[j];
            }
            self.a[k * d + r] = 1.0;
            self.b[k] = ns.t0[i];
            self.tol[k] = FEAS * 1f64.max(ns.t0[i].abs());
            self.tag[k] = Tag::Level;
            if ti > s {
                (s, top) = (ti, k);
            }
        }
        self.x[r] = s;
        self.c[r] = 1.0;
        self.work.push(top);
        self.in_work[top] = true;
    }

    /// Phase 1: a feasible λ (in `x[..r]`) and an independent working set of bound rows active
    /// there (in `work`), or the verdict that the feasible set is empty.
    fn phase1(&mut self) -> Result<(), DenseEnd> {
        let (nb, r) = (self.nb, self.r);
        let d = r + 1;
        self.work.clear();
        self.size(nb + 1, d);
        let (mut sigma, mut top) = (0.0f64, nb);
        let mut tight = true;
        for k in 0..nb {
            for j in 0..r {
                self.a[k * d + j] = self.base_a[k * r + j];
            }
            self.a[k * d + r] = 1.0;
            self.b[k] = self.base_b[k];
            self.tol[k] = self.base_tol[k];
            self.tag[k] = self.base_tag[k];
            tight &= self.base_b[k] <= self.base_tol[k];
            if self.base_b[k] > sigma {
                (sigma, top) = (self.base_b[k], k);
            }
        }
        // σ ≥ 0.
        for j in 0..d {
            self.a[nb * d + j] = if j == r { 1.0 } else { 0.0 };
        }
        self.b[nb] = 0.0;
        self.tol[nb] = 0.0;
        self.tag[nb] = Tag::Sigma;
        self.x.fill(0.0);
        if tight {
            // λ = 0 is feasible (within the tolerances): empty working set.
            return Ok(());
        }
        self.x[r] = sigma;
        self.work.push(top);
        self.in_work[top] = true;
        self.c.fill(0.0);
        self.c[r] = 1.0;
        match self.lp(Some(nb)) {
            LpEnd::Reached => {
                // σ = 0: drop the σ row; the others are independent in λ alone.
                self.x[r] = 0.0;
                self.in_work[nb] = false;
                self.work.retain(|&k| k != nb);
                Ok(())
            }
            LpEnd::Optimal => {
                let tol = self.base_tol.iter().fold(0.0f64, |a, &b| a.max(b));
                if self.x[r] <= tol {
                    // Feasible up to rounding: restart phase 2 from an empty working set.
                    for &k in &self.work {
                        self.in_work[k] = false;
                    }
                    self.work.clear();
                    Ok(())
                } else {
                    Err(DenseEnd::Infeasible(Infeasibility::NoFeasibleTension))
                }
            }
            LpEnd::Unbounded => Err(DenseEnd::Failed("phase 1: unbounded")),
            LpEnd::Limit => Err(DenseEnd::Failed("phase 1: iteration limit")),
            LpEnd::Dependent => Err(DenseEnd::Failed("phase 1: dependent working set")),
        }
    }

    /// Factors the working normals (the columns a_k, k ∈ W) as Q₁ R by Gram–Schmidt with
    /// re-orthogonalisation; false if they are numerically dependent.
    fn factor(&mut self) -> bool {
        let d = self.d;
        for (col, &k) in self.work.iter().enumerate() {
            let row = &self.a[k * d..(k + 1) * d];
            let norm0 = dot(row, row).sqrt();
            self.v.copy_from_slice(row);
            for i in 0..=col {
                self.rr[col * d + i] = 0.0;
            }
            for _ in 0..2 {
                for i in 0..col {
                    let qi = &self.q[i * d..(i + 1) * d];
                    let s = dot(qi, &self.v);
                    self.rr[col * d + i] += s;
                    for (vj, qj) in self.v.iter_mut().zip(qi) {
                        *vj -= s * qj;
                    }
                }
            }
            let nv = dot(&self.v, &self.v).sqrt();
            if nv.is_nan() || nv <= 1e-12 * norm0 {
                return false;
            }
            self.rr[col * d + col] = nv;
            for (qj, vj) in self.q[col * d..(col + 1) * d].iter_mut().zip(&self.v) {
                *qj = vj / nv;
            }
        }
        true
    }

    /// v ← v − Q₁ Q₁ᵀ v (twice, for accuracy).
    fn project_out(q: &[f64], d: usize, k: usize, v: &mut [f64]) {
        for _ in 0..2 {
            for i in 0..k {
                let qi = &q[i * d..(i + 1) * d];
                let s = dot(qi, v);
                for (vj, qj) in v.iter_mut().zip(qi) {
                    *vj -= s * qj;
                }
            }
        }
    }

    /// Solves R z = y in place (back substitution; R is k × k with stride d).
    fn solve_r(rr: &[f64], d: usize, k: usize, y: &mut [f64]) {
        for i in (0..k).rev() {
            let mut s = y[i];
            for j in i + 1..k {
                s -= rr[j * d + i] * y[j];
            }
            y[i] = s / rr[i * d + i];
        }
    }

    /// Solves Rᵀ z = y in place (forward substitution).
    fn solve_rt(rr: &[f64], d: usize, k: usize, y: &mut [f64]) {
        for i in 0..k {
            let mut s = y[i];
            for j in 0..i {
                s -= rr[i * d + j] * y[j];
            }
            y[i] = s / rr[i * d + i];
        }
    }

    /// Slack a_kᵀ x − b_k of row k.
    #[inline]
    fn slack(&self, k: usize) -> f64 {
        let d = self.d;
        dot(&self.a[k * d..(k + 1) * d], &self.x) - self.b[k]
    }

    /// The primal active-set (simplex) method in inequality form, from `x` and `work` (see the
    /// module docs), with Bland's rule. Stops early when row `stop` enters the working set.
    fn lp(&mut self, stop: Option<usize>) -> LpEnd {
        let d = self.d;
        let cn = dot(&self.c, &self.c).sqrt();
        let max_iter = 10 * (self.rows + d) + 50;
        for _ in 0..max_iter {
            if !self.factor() {
                return LpEnd::Dependent;
            }
            let k = self.work.len();
            // Steepest descent within the working set's null space.
            for j in 0..d {
                self.p[j] = -self.c[j];
            }
            Self::project_out(&self.q, d, k, &mut self.p);
            let mut release = None;
            if dot(&self.p, &self.p).sqrt() <= 1e-12 * cn {
                // c = Σ μ_j a_j: R μ = Q₁ᵀ c.
                for i in 0..k {
                    self.y[i] = dot(&self.q[i * d..(i + 1) * d], &self.c);
                }
                Self::solve_r(&self.rr, d, k, &mut self.y);
                // Bland: the smallest row index with μ < 0.
                let tol = 1e-12 * cn;
                let mut best: Option<usize> = None;
                for pos in 0..k {
                    if self.y[pos] < -tol && best.is_none_or(|b| self.work[pos] < self.work[b]) {
                        best = Some(pos);
                    }
                }
                let Some(pos) = best else {
                    return LpEnd::Optimal;
                };
                // p = Q₁ z with Rᵀ z = e_pos: A_W p = e_pos.
                self.y[..k].fill(0.0);
                self.y[pos] = 1.0;
                Self::solve_rt(&self.rr, d, k, &mut self.y);
                self.p.fill(0.0);
                for i in 0..k {
                    let yi = self.y[i];
                    for (pj, qj) in self.p.iter_mut().zip(&self.q[i * d..(i + 1) * d]) {
                        *pj += yi * qj;
                    }
                }
                release = Some(pos);
            }
            // Ratio test; Bland: the smallest row index among (near-)ties.
            let pn = dot(&self.p, &self.p).sqrt();
            let mut amin = f64::INFINITY;
            for k in 0..self.rows {
                if self.in_work[k] {
                    continue;
                }
                let ap = dot(&self.a[k * d..(k + 1) * d], &self.p);
                if ap < -1e-11 * pn {
                    amin = amin.min(self.slack(k).max(0.0) / -ap);
                }
            }
            if amin == f64::INFINITY {
                return LpEnd::Unbounded;
            }
            let xs = self.x.iter().fold(1f64, |m, v| m.max(v.abs()));
            let band = amin + 1e-13 * xs;
            let mut enter = self.rows;
            for k in 0..self.rows {
                if self.in_work[k] {
                    continue;
                }
                let ap = dot(&self.a[k * d..(k + 1) * d], &self.p);
                if ap < -1e-11 * pn && self.slack(k).max(0.0) / -ap <= band {
                    enter = k;
                    break;
                }
            }
            if enter == self.rows {
                // Cannot happen with finite data (the row giving amin is in the band); with
                // non-finite round-off, report a numerical failure rather than index past the end.
                return LpEnd::Dependent;
            }
            for (xj, pj) in self.x.iter_mut().zip(&self.p) {
                *xj += amin * pj;
            }
            if let Some(pos) = release {
                let k = self.work.remove(pos);
                self.in_work[k] = false;
            }
            self.work.push(enter);
            self.in_work[enter] = true;
            if stop == Some(enter) {
                return LpEnd::Reached;
            }
        }
        LpEnd::Limit
    }

    /// The dual active-set method of Goldfarb & Idnani for min ½‖λ‖² + gᵀλ on the bound rows.
    fn goldfarb_idnani(&mut self, g: &[f64]) -> Result<(), DenseEnd> {
        let r = self.r;
        self.work.clear();
        self.u.clear();
        self.load_rows(r, 0);
        for (xj, gj) in self.x.iter_mut().zip(g) {
            *xj = -gj;
        }
        let d = r;
        let max_iter = 10 * (self.rows + d) + 50;
        let mut iter = 0;
        loop {
            // The most violated row (the smallest index among equals).
            let (mut q, mut worst) = (self.rows, 0.0);
            for k in 0..self.rows {
                if self.in_work[k] {
                    continue;
                }
                let s = self.slack(k);
                if s < -self.tol[k] && s < worst {
                    (q, worst) = (k, s);
                }
            }
            if q == self.rows {
                return Ok(());
            }
            let mut u_plus = 0.0;
            loop {
                iter += 1;
                if iter > max_iter {
                    return Err(DenseEnd::Failed("dual active set: iteration limit"));
                }
                if !self.factor() {
                    return Err(DenseEnd::Failed("dual active set: dependent working set"));
                }
                let k = self.work.len();
                // a_q = Q₁ v + z with z ⟂ the active normals; r = R⁻¹ v (stored in y).
                let aq = &self.a[q * d..(q + 1) * d];
                let aq_norm = dot(aq, aq).sqrt();
                self.p.copy_from_slice(aq);
                for i in 0..k {
                    self.y[i] = dot(&self.q[i * d..(i + 1) * d], aq);
                }
                Self::project_out(&self.q, d, k, &mut self.p);
                Self::solve_r(&self.rr, d, k, &mut self.y);
                // Partial (dual) step: the active multiplier that reaches 0 first.
                let (mut t1, mut l) = (f64::INFINITY, k);
                for pos in 0..k {
                    if self.y[pos] > 1e-12 {
                        let ratio = self.u[pos] / self.y[pos];
                        // (l < k: a ratio that overflowed to +∞ ties with "no partial step"
                        // and must not be compared with a working row that does not exist.)
                        if ratio < t1 || (l < k && ratio == t1 && self.work[pos] < self.work[l]) {
                            (t1, l) = (ratio, pos);
                        }
                    }
                }
                // Full (primal) step: make row q active.
                let zn = dot(&self.p, &self.p).sqrt();
                let t2 = if zn > 1e-10 * aq_norm {
                    -self.slack(q) / dot(&self.p, &self.a[q * d..(q + 1) * d])
                } else {
                    f64::INFINITY
                };
                if t1 == f64::INFINITY && t2 == f64::INFINITY {
                    return Err(DenseEnd::Infeasible(Infeasibility::NoFeasibleTension));
                }
                let t = t1.min(t2).max(0.0);
                if t2 < f64::INFINITY {
                    for (xj, zj) in self.x.iter_mut().zip(&self.p) {
                        *xj += t * zj;
                    }
                }
                for pos in 0..k {
                    self.u[pos] = (self.u[pos] - t * self.y[pos]).max(0.0);
                }
                u_plus += t;
                if t2 <= t1 {
                    self.work.push(q);
                    self.in_work[q] = true;
                    self.u.push(u_plus);
                    break;
                }
                let row = self.work.remove(l);
                self.u.remove(l);
                self.in_work[row] = false;
            }
        }
    }

    /// t = t0 + N λ (λ = x[..r]), with the cables of active bound rows set onto their bound.
    fn write_tensions(&self, ns: &NullSpace, bounds: &TensionBounds, t: &mut [f64]) {
        let (n, r) = (ns.n, self.r);
        for (i, ti) in t.iter_mut().enumerate() {
            let mut s = ns.t0[i];
            for j in 0..r {
                s += ns.basis[j * n + i] * self.x[j];
            }
            *ti = s;
        }
        for &k in &self.work {
            match self.tag[k] {
                Tag::Lower(i) => t[i] = bounds.min()[i],
                Tag::Upper(i) => t[i] = bounds.max()[i],
                Tag::Level | Tag::Sigma => {}
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Chvátal's cycling example (Linear Programming, 1983, §3): max 10x₁ − 57x₂ − 9x₃ − 24x₄
    /// subject to 0.5x₁ − 5.5x₂ − 2.5x₃ + 9x₄ ≤ 0, 0.5x₁ − 1.5x₂ − 0.5x₃ + x₄ ≤ 0, x₁ ≤ 1,
    /// x ≥ 0. From the degenerate vertex x = 0 the largest-coefficient rule cycles (releasing
    /// the most negative μ instead of the smallest index makes this test hit the iteration
    /// limit); with Bland's rule the method reaches the optimum x = (1, 0, 1, 0), value 1.
    #[test]
    fn bland_rule_terminates_on_chvatal_cycling_example() {
        let rows: [[f64; 4]; 7] = [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
            [-0.5, 5.5, 2.5, -9.0],
            [-0.5, 1.5, 0.5, -1.0],
            [-1.0, 0.0, 0.0, 0.0],
        ];
        let b = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0];
        let mut s = ActiveSet::default();
        s.work.extend([0, 1, 2, 3]);
        s.size(7, 4);
        for (k, row) in rows.iter().enumerate() {
            s.a[k * 4..k * 4 + 4].copy_from_slice(row);
            s.b[k] = b[k];
            s.tol[k] = 0.0;
        }
        s.x.fill(0.0);
        s.c.copy_from_slice(&[-10.0, 57.0, 9.0, 24.0]);
        assert_eq!(s.lp(None), LpEnd::Optimal);
        for (x, e) in s.x.iter().zip([1.0, 0.0, 1.0, 0.0]) {
            assert!((x - e).abs() < 1e-14, "{:?}", s.x);
        }
    }

    /// Phase 1 reports an empty set, and finds a feasible point of a thin slab.
    #[test]
    fn phase1_verdicts() {
        // λ ∈ R³ with λ₁ ≥ 1 and −λ₁ ≥ 0 (λ₁ ≤ 0): empty.
        let mut s = ActiveSet {
            r: 3,
            nb: 2,
            base_a: vec![1.0, 0.0, 0.0, -1.0, 0.0, 0.0],
            base_b: vec![1.0, 0.0],
            base_tol: vec![1e-12; 2],
            base_tag: vec![Tag::Lower(0), Tag::Upper(0)],
            ..ActiveSet::default()
        };
        assert_eq!(
            s.phase1(),
            Err(DenseEnd::Infeasible(Infeasibility::NoFeasibleTension))
        );
        // 1 ≤ λ₁ + λ₂ ≤ 1 + 10⁻⁹, λ₃ ≥ 5: feasible; the point found satisfies every row.
        s.nb = 3;
        s.base_a = vec![1.0, 1.0, 0.0, -1.0, -1.0, 0.0, 0.0, 0.0, 1.0];
        s.base_b = vec![1.0, -1.0 - 1e-9, 5.0];
        s.base_tol = vec![1e-12; 3];
        s.base_tag = vec![Tag::Lower(0), Tag::Upper(0), Tag::Lower(1)];
        assert_eq!(s.phase1(), Ok(()));
        let (l1, l2, l3) = (s.x[0], s.x[1], s.x[2]);
        assert!(l1 + l2 >= 1.0 - 1e-12 && l1 + l2 <= 1.0 + 1e-9 + 1e-12 && l3 >= 5.0 - 1e-12);
    }
}
