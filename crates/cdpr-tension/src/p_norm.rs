//! # p-norm tension distribution with log barriers (Gosselin & Grenier 2011)
//!
//! The tensions of equilibrium that minimise the p-norm of their distance to the middle of
//! the bounds t_m = (t_min + t_max)/2, inside the bounds:
//!
//! ```text
//!   min Σ_i |t_i − t_m,i|^p   subject to   W t + w_ext = 0,   t_min < t < t_max
//! ```
//!
//! (`--p`, default p = 4; p ≥ 2 keeps the objective twice differentiable. Large p approaches
//! the min-max tension deviation of Gosselin & Grenier.) With u_i = (t_i − t_m,i)/h,
//! h = max_i (t_max,i − t_min,i)/2 and c_i = (t_max,i − t_min,i)/(2h) ∈ (0, 1], the bounds
//! are −c_i < u_i < c_i. As Ueland, Sauder & Skjetne (2021) the bounds enter through
//! logarithmic barriers, and the barrier problems
//!
//! ```text
//!   min_λ  F_μ(λ) = Σ_i |u_i|^p − μ Σ_i [ln(c_i + u_i) + ln(c_i − u_i)],   u = (t0 + N λ − t_m)/h
//! ```
//!
//! are solved by Newton's method on their stationarity (KKT) condition ∇F_μ = 0, i.e.
//! (Nᵀ D H D N) Δλ = −Nᵀ D ∇_u F with D = I/h and H the diagonal Hessian
//! p(p−1)|u_i|^{p−2} + μ[(c_i + u_i)⁻² + (c_i − u_i)⁻²] (positive definite: the barrier terms),
//! with a backtracking line search that keeps every u_i strictly inside and decreases F_μ, for
//! μ = 1, 10⁻¹, …, 10⁻⁹ (the central path; each stage ends when the Newton decrement² is below
//! 10⁻¹⁴, when the line search finds no decrease above rounding, or after 50 steps). At μ = 10⁻⁹ the barrier answer is within 2nμ of the constrained optimum's objective
//! (in units of h^p). The start is the optimally safe point (module `optimally_safe`, α = 1):
//! its margin s* > 0 makes it strictly interior. Cables fixed at t_min = t_max (a zero-width
//! interval: no barrier exists) are moved into the load, w' = w_ext + Σ_fixed w_i t_i, and the
//! method runs on the other cables (`TensionSolver`; their terms |t_i − t_m,i|^p are 0 on the
//! whole feasible set, so the optimum is unchanged). A margin s* ≤ 10⁻⁹·h on the cables left
//! (no interior point: a set that only touches a bound) is the documented give-up
//! [`crate::GiveUp::EmptyInterior`], as are fewer free cables than DOF; s* < 0 proves the set empty; the
//! Newton steps are capped by `max_iterations` ([`crate::GiveUp::IterationLimit`]).
//!
//! ## References
//! - Gosselin, C. & Grenier, M. (2011), *On the determination of the force distribution in
//!   overconstrained cable-driven parallel mechanisms*, Meccanica 46(1), pp. 3–15.
//! - Ueland, E., Sauder, T. & Skjetne, R. (2021), *Optimal force allocation for
//!   overconstrained cable-driven parallel robots: continuously differentiable solutions with
//!   assessment of computational efficiency*, IEEE Transactions on Robotics 37(2), pp. 659–666.
//! - Boyd, S. & Vandenberghe, L. (2004), *Convex Optimization*, §11.3 (barrier method),
//!   §9.5 (Newton's method, backtracking).

use crate::active_set::ActiveSet;
use crate::null_space::NullSpace;
use crate::pott_closed_form::middle;
use crate::{GiveUp, Infeasibility, TensionBounds, optimally_safe};

/// The barrier weights of the central path, from the first to the last.
const MU_START: f64 = 1.0;
const MU_END: f64 = 1e-9;
/// Newton decrement² that ends a stage.
const DECREMENT: f64 = 1e-14;
/// Newton steps after which a stage hands over to the next μ (its iterate is strictly inside
/// whatever its accuracy; rounding can keep the decrement above [`DECREMENT`] near a bound).
const STAGE_STEPS: usize = 50;

/// Buffers (no allocation once sized).
#[derive(Debug, Clone, Default)]
pub(crate) struct PNorm {
    t_m: Vec<f64>,
    c: Vec<f64>,
    u: Vec<f64>,
    gu: Vec<f64>,
    hu: Vec<f64>,
    lambda: Vec<f64>,
    trial: Vec<f64>,
    step: Vec<f64>,
    grad: Vec<f64>,
    hess: Vec<f64>,
    /// Newton steps of the last solve.
    pub iterations: usize,
}

impl PNorm {
    /// The barrier solution into `t` (module docs); callers ensure finite bounds.
    #[allow(clippy::too_many_arguments)]
    pub fn solve(
        &mut self,
        ns: &NullSpace,
        bounds: &TensionBounds,
        p: f64,
        max_iterations: usize,
        dense: &mut ActiveSet,
        t: &mut [f64],
    ) -> Result<(), Infeasibility> {
        let (n, r) = (ns.n, ns.r());
        let (lo, hi) = (bounds.min(), bounds.max());
        let h = (0..n).fold(0f64, |m, i| m.max(0.5 * (hi[i] - lo[i])));
        // Strictly interior start: the optimally safe point.
        let s = optimally_safe::solve(ns, bounds, 1.0, dense, t)?;
        // (A NaN margin is no interior point either.)
        if s.is_nan() || s <= 1e-9 * h.max(1.0) || h <= 0.0 {
            return Err(Infeasibility::GaveUp {
                method: "p-norm",
                reason: GiveUp::EmptyInterior,
            });
        }
        self.t_m.resize(n, 0.0);
        middle(bounds, &mut self.t_m);
        self.c.clear();
        self.c.extend((0..n).map(|i| 0.5 * (hi[i] - lo[i]) / h));
        for buf in [&mut self.u, &mut self.gu, &mut self.hu] {
            buf.resize(n, 0.0);
        }
        for buf in [
            &mut self.lambda,
            &mut self.trial,
            &mut self.step,
            &mut self.grad,
        ] {
            buf.resize(r, 0.0);
        }
        self.hess.resize(r * r, 0.0);
        self.iterations = 0;
        // λ of the start.
        ns.coordinates(t, &mut self.lambda);
        let mut mu = MU_START;
        loop {
            // Newton on F_μ.
            let mut steps = 0;
            loop {
                steps += 1;
                if steps > STAGE_STEPS {
                    break;
                }
                if self.iterations >= max_iterations {
                    return Err(Infeasibility::GaveUp {
                        method: "p-norm",
                        reason: GiveUp::IterationLimit {
                            iterations: max_iterations,
                        },
                    });
                }
                self.iterations += 1;
                ns.tensions(&self.lambda, t);
                let f0 = self.derivatives(t, h, p, mu);
                // grad = Nᵀ gu / h, hess = Nᵀ diag(hu) N / h².
                for j in 0..r {
                    let cj = &ns.basis[j * n..(j + 1) * n];
                    self.grad[j] = cj.iter().zip(&self.gu).map(|(a, g)| a * g).sum::<f64>() / h;
                    for k in 0..=j {
                        let ck = &ns.basis[k * n..(k + 1) * n];
                        let v = (0..n).map(|i| cj[i] * self.hu[i] * ck[i]).sum::<f64>() / (h * h);
                        self.hess[j * r + k] = v;
                        self.hess[k * r + j] = v;
                    }
                }
                if !cholesky_solve(&mut self.hess, &self.grad, &mut self.step, r) {
                    return Err(Infeasibility::SolverFailure {
                        detail: "p-norm: Newton matrix not positive definite".to_string(),
                    });
                }
                // Newton decrement² = gradᵀ H⁻¹ grad; step = −H⁻¹ grad.
                let dec: f64 = self.grad.iter().zip(&self.step).map(|(g, s)| g * s).sum();
                if dec <= DECREMENT {
                    break;
                }
                let mut a = 1.0;
                loop {
                    for j in 0..r {
                        self.trial[j] = self.lambda[j] - a * self.step[j];
                    }
                    ns.tensions(&self.trial, t);
                    let f1 = self.value(t, h, p, mu);
                    if f1.is_finite() && f1 <= f0 - 0.25 * a * dec {
                        break;
                    }
                    a *= 0.5;
                    if a < 1e-12 {
                        break;
                    }
                }
                if a < 1e-12 {
                    // No decrease at rounding level: the stage has converged.
                    break;
                }
                self.lambda.copy_from_slice(&self.trial);
            }
            if mu <= MU_END {
                break;
            }
            mu = (mu * 0.1).max(MU_END);
        }
        ns.tensions(&self.lambda, t);
        Ok(())
    }

    /// F_μ at t (∞ outside the bounds).
    fn value(&mut self, t: &[f64], h: f64, p: f64, mu: f64) -> f64 {
        let mut f = 0.0;
        for (i, &ti) in t.iter().enumerate() {
            let u = (ti - self.t_m[i]) / h;
            let (a, b) = (self.c[i] + u, self.c[i] - u);
            if !(a > 0.0 && b > 0.0) {
                return f64::INFINITY;
            }
            f += u.abs().powf(p) - mu * (a.ln() + b.ln());
        }
        f
    }

    /// F_μ, and its gradient and diagonal Hessian in u (into `gu`, `hu`).
    fn derivatives(&mut self, t: &[f64], h: f64, p: f64, mu: f64) -> f64 {
        let mut f = 0.0;
        for (i, &ti) in t.iter().enumerate() {
            let u = (ti - self.t_m[i]) / h;
            let (a, b) = (self.c[i] + u, self.c[i] - u);
            let au = u.abs();
            f += au.powf(p) - mu * (a.ln() + b.ln());
            self.gu[i] = p * au.powf(p - 1.0) * u.signum() - mu * (1.0 / a - 1.0 / b);
            self.hu[i] = p * (p - 1.0) * au.powf(p - 2.0) + mu * (1.0 / (a * a) + 1.0 / (b * b));
        }
        f
    }
}

/// Solves H x = g by Cholesky (H r × r, symmetric positive definite; overwritten by its
/// factor); false when H is not positive definite.
fn cholesky_solve(hm: &mut [f64], g: &[f64], x: &mut [f64], r: usize) -> bool {
    for j in 0..r {
        let mut d = hm[j * r + j];
        for k in 0..j {
            d -= hm[j * r + k] * hm[j * r + k];
        }
        if d.is_nan() || d <= 0.0 {
            return false;
        }
        let d = d.sqrt();
        hm[j * r + j] = d;
        for i in j + 1..r {
            let mut s = hm[i * r + j];
            for k in 0..j {
                s -= hm[i * r + k] * hm[j * r + k];
            }
            hm[i * r + j] = s / d;
        }
    }
    for i in 0..r {
        let mut s = g[i];
        for k in 0..i {
            s -= hm[i * r + k] * x[k];
        }
        x[i] = s / hm[i * r + i];
    }
    for i in (0..r).rev() {
        let mut s = x[i];
        for k in i + 1..r {
            s -= hm[k * r + i] * x[k];
        }
        x[i] = s / hm[i * r + i];
    }
    true
}
