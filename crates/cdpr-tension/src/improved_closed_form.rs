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
    /// A Aᵀ, rhs and y for DOF other than 6 and 3.
    buf: Vec<f64>,
}

impl ImprovedClosedForm {
    /// Pott (2014) into `t` (callers ensure r ≥ 0 and finite t_max, see
    /// [`crate::TensionError::NeedsFiniteBounds`]). DOF 6 and 3 run a copy of the iteration
    /// with the DOF fixed at compile time (stack buffers, unrolled loops, the same arithmetic).
    pub fn solve(&mut self, problem: &TensionProblem, t: &mut [f64]) -> Result<(), Infeasibility> {
        let (m, n) = problem.wrench_matrix.shape();
        self.active.clear();
        self.active.resize(n, true);
        match m {
            6 => {
                let mut buf = [0.0; 6 * 6 + 2 * 6];
                iterate::<6>(problem, &mut self.active, &mut buf, t)
            }
            3 => {
                let mut buf = [0.0; 3 * 3 + 2 * 3];
                iterate::<3>(problem, &mut self.active, &mut buf, t)
            }
            _ => {
                self.buf.resize(m * m + 2 * m, 0.0);
                iterate::<0>(problem, &mut self.active, &mut self.buf, t)
            }
        }
    }
}

/// The iteration of Pott (2014) for DOF m = M (M = 0: m read from W at run time). `buf` holds
/// A Aᵀ (m × m, row-major), then rhs and y (m each).
#[inline(always)]
fn iterate<const M: usize>(
    problem: &TensionProblem,
    active: &mut [bool],
    buf: &mut [f64],
    t: &mut [f64],
) -> Result<(), Infeasibility> {
    const METHOD: &str = "improved-closed-form";
    let w = problem.wrench_matrix;
    let n = w.ncols();
    let m = if M > 0 { M } else { w.nrows() };
    debug_assert_eq!(w.nrows(), m);
    // Column-major W: W_ki = ws[i·m + k].
    let ws = &w.as_slice()[..m * n];
    let we = &problem.external_wrench.as_slice()[..m];
    let (aat, rest) = buf.split_at_mut(m * m);
    let (rhs, y) = rest.split_at_mut(m);
    let y = &mut y[..m];
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
    loop {
        // rhs = w_ext + W t (saturated cables at their bound, free ones at t_m).
        rhs.copy_from_slice(we);
        for (col, &ti) in ws.chunks_exact(m).zip(t.iter()) {
            for k in 0..m {
                rhs[k] += col[k] * ti;
            }
        }
        // A Aᵀ over the free cables, lower triangle: one outer product per free cable (each
        // entry sums over the cables in the same order as an entry-by-entry loop, so the same
        // bits, without a branch per entry and cable).
        if M > 0 {
            // DOF known at compile time: the triangle in a local array the compiler unrolls.
            let mut acc = [[0.0; M]; M];
            for (col, &free) in ws.chunks_exact(M).zip(active.iter()) {
                if free {
                    for r in 0..M {
                        let cr = col[r];
                        for c in 0..=r {
                            acc[r][c] += cr * col[c];
                        }
                    }
                }
            }
            for r in 0..M {
                aat[r * M..r * M + r + 1].copy_from_slice(&acc[r][..=r]);
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
            y[k] = aat[k * m + k].sqrt();
        }
        if !cholesky(aat, m) {
            return Err(if first {
                Infeasibility::SingularPose {
                    condition: f64::INFINITY,
                }
            } else {
                Infeasibility::Inconclusive { method: METHOD }
            });
        }
        let ratio: f64 = (0..m).map(|k| aat[k * m + k] / y[k]).product();
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
        y.copy_from_slice(rhs);
        cholesky_solve(aat, m, y);
        for ((col, ti), &free) in ws.chunks_exact(m).zip(t.iter_mut()).zip(active.iter()) {
            if free {
                let mut s = 0.0;
                for k in 0..m {
                    s += col[k] * y[k];
                }
                *ti -= s;
            }
        }
        // The free cable with the largest violation of its limits, in force units (Pott
        // 2014); a tension counts as violating beyond the certificate's relative tolerance.
        let (mut worst, mut wv) = (n, 0.0);
        for i in 0..n {
            if active[i]
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
        for i in 0..n {
            if active[i] {
                t[i] = 0.5 * (lo[i] + hi[i]);
            }
        }
    }
}

/// In-place Cholesky of the lower triangle of an m × m row-major matrix; false if not SPD.
#[inline(always)]
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
#[inline(always)]
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
