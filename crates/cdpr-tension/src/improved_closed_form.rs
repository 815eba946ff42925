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
//! Needs finite t_max. Each step solves one DOF × DOF Cholesky system on reused buffers.
//!
//! ## References
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
    rhs: Vec<f64>,
    aat: Vec<f64>,
    y: Vec<f64>,
}

impl ImprovedClosedForm {
    /// Pott (2014) into `t` (callers ensure r ≥ 0 and finite t_max, see
    /// [`crate::TensionError::NeedsFiniteBounds`]).
    pub fn solve(&mut self, problem: &TensionProblem, t: &mut [f64]) -> Result<(), Infeasibility> {
        const METHOD: &str = "improved-closed-form";
        let w = problem.wrench_matrix;
        let (m, n) = w.shape();
        let (lo, hi) = (problem.bounds.min(), problem.bounds.max());
        self.active.clear();
        self.active.resize(n, true);
        self.rhs.resize(m, 0.0);
        self.aat.resize(m * m, 0.0);
        self.y.resize(m, 0.0);
        for i in 0..n {
            t[i] = 0.5 * (lo[i] + hi[i]);
        }
        let mut remaining = n;
        let mut first = true;
        loop {
            // rhs = w_ext + W t (saturated cables at their bound, free ones at t_m).
            for k in 0..m {
                let mut s = problem.external_wrench[k];
                for (i, ti) in t.iter().enumerate() {
                    s += w[(k, i)] * ti;
                }
                self.rhs[k] = s;
            }
            // A Aᵀ over the free cables, lower triangle.
            for r in 0..m {
                for c in 0..=r {
                    let mut s = 0.0;
                    for i in 0..n {
                        if self.active[i] {
                            s += w[(r, i)] * w[(c, i)];
                        }
                    }
                    self.aat[r * m + c] = s;
                }
            }
            for k in 0..m {
                self.y[k] = self.aat[k * m + k].sqrt();
            }
            if !cholesky(&mut self.aat, m) {
                return Err(if first {
                    Infeasibility::SingularPose {
                        condition: f64::INFINITY,
                    }
                } else {
                    Infeasibility::Inconclusive { method: METHOD }
                });
            }
            let ratio: f64 = (0..m).map(|k| self.aat[k * m + k] / self.y[k]).product();
            if ratio.is_nan() || ratio < SINGULARITY_RATIO {
                return Err(if first {
                    Infeasibility::SingularPose {
                        condition: 1.0 / ratio,
                    }
                } else {
                    Infeasibility::Inconclusive { method: METHOD }
                });
            }
            first = false;
            // (A Aᵀ) y = rhs; t_free −= Aᵀ y.
            self.y.copy_from_slice(&self.rhs);
            cholesky_solve(&self.aat, m, &mut self.y);
            for i in 0..n {
                if self.active[i] {
                    let mut s = 0.0;
                    for k in 0..m {
                        s += w[(k, i)] * self.y[k];
                    }
                    t[i] -= s;
                }
            }
            // The free cable with the largest violation of its limits, in force units (Pott
            // 2014); a tension counts as violating beyond the certificate's relative tolerance.
            let (mut worst, mut wv) = (n, 0.0);
            for i in 0..n {
                if self.active[i]
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
            self.active[worst] = false;
            remaining -= 1;
            for i in 0..n {
                if self.active[i] {
                    t[i] = 0.5 * (lo[i] + hi[i]);
                }
            }
        }
    }
}

/// In-place Cholesky of the lower triangle of an m × m row-major matrix; false if not SPD.
fn cholesky(a: &mut [f64], m: usize) -> bool {
    for j in 0..m {
        let mut d = a[j * m + j];
        for k in 0..j {
            d -= a[j * m + k] * a[j * m + k];
        }
        if d.is_nan() || d <= 0.0 {
            return false;
        }
        let d = d.sqrt();
        a[j * m + j] = d;
        for i in j + 1..m {
            let mut s = a[i * m + j];
            for k in 0..j {
                s -= a[i * m + k] * a[j * m + k];
            }
            a[i * m + j] = s / d;
        }
    }
    true
}

/// Solves L Lᵀ x = b in place.
fn cholesky_solve(l: &[f64], m: usize, x: &mut [f64]) {
    for i in 0..m {
        let mut s = x[i];
        for k in 0..i {
            s -= l[i * m + k] * x[k];
        }
        x[i] = s / l[i * m + i];
    }
    for i in (0..m).rev() {
        let mut s = x[i];
        for k in i + 1..m {
            s -= l[k * m + i] * x[k];
        }
        x[i] = s / l[i * m + i];
    }
}
