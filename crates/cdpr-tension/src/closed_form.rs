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
//! ## References
//! - Seed 000 (thesis ch. 6), eqs. (6.15)–(6.20), Algorithm 6.1.

use crate::certificate::bound_violation;
use crate::null_space::SINGULARITY_RATIO;
use crate::outcome::validate;
use crate::{Infeasibility, TensionError, TensionProblem};
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

/// The feasible interval of a redundancy-1 problem, or why there is none.
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

impl ClosedForm {
    /// Eq. (6.16) with the basis choice described in the module docs.
    fn parametrise(&mut self, problem: &TensionProblem) -> Result<(), Infeasibility> {
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
        let r = problem.redundancy();
        if r != 1 {
            return Err(Infeasibility::NotApplicable {
                method: "closed-form",
                redundancy: r,
            });
        }
        self.parametrise(problem)?;
        let (tmin, tmax) = (problem.bounds.min(), problem.bounds.max());
        let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
        for i in 0..self.n_vec.len() {
            let (mi, ni) = (self.m_vec[i], self.n_vec[i]);
            if ni.abs() <= 1e-14 {
                // t_i does not depend on t^B: it must satisfy its bounds by itself.
                if bound_violation(tmin[i], tmax[i], mi) > 1e-12 {
                    return Err(Infeasibility::NoFeasibleTension);
                }
                continue;
            }
            let a = (tmin[i] - mi) / ni;
            let b = (tmax[i] - mi) / ni; // ±∞ for an infinite t_max
            let (l, h) = if ni > 0.0 { (a, b) } else { (b, a) };
            lo = lo.max(l);
            hi = hi.min(h);
        }
        if lo > hi {
            // Empty, unless only by rounding: accept the midpoint if it violates no bound by
            // more than 10⁻¹² (relative), the tolerance of the polygon clipping too.
            let mid = 0.5 * (lo + hi);
            let worst = (0..self.n_vec.len())
                .map(|i| bound_violation(tmin[i], tmax[i], self.m_vec[i] + self.n_vec[i] * mid))
                .fold(f64::NEG_INFINITY, f64::max);
            if worst > 1e-12 {
                return Err(Infeasibility::NoFeasibleTension);
            }
            return Ok((mid, mid));
        }
        Ok((lo, hi))
    }

    /// Minimum (or maximum) ‖t‖₁ = Σ t_i over the interval, comparing both ends (Alg. 6.1).
    pub fn solve(
        &mut self,
        problem: &TensionProblem,
        maximize: bool,
        t: &mut [f64],
    ) -> Result<(), Infeasibility> {
        let (lo, hi) = self.interval(problem)?;
        if maximize && !hi.is_finite() {
            return Err(Infeasibility::Unbounded {
                method: "closed-form",
            });
        }
        let sum_at = |tb: f64| -> f64 {
            self.m_vec
                .iter()
                .zip(&self.n_vec)
                .map(|(m, n)| m + n * tb)
                .sum()
        };
        let tb = if !hi.is_finite() {
            lo
        } else {
            let (s_lo, s_hi) = (sum_at(lo), sum_at(hi));
            if (maximize && s_hi > s_lo) || (!maximize && s_hi < s_lo) {
                hi
            } else {
                lo
            }
        };
        for (i, ti) in t.iter_mut().enumerate() {
            *ti = self.m_vec[i] + self.n_vec[i] * tb;
        }
        Ok(())
    }
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
}
