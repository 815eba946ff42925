//! # Closed-form force distribution (Pott, Bruckmann & Mikelsons 2009)
//!
//! The tensions of equilibrium closest (in ‖·‖₂) to a reference t_ref, in closed form:
//!
//! ```text
//!   t = t_ref − W⁺ (w_ext + W t_ref),     W⁺ = Wᵀ (W Wᵀ)⁻¹                     (eq. (9))
//! ```
//!
//! with t_ref = t_m = (t_min + t_max)/2, the middle of the bounds. On the null-space
//! parametrisation t = t0 + N λ (N orthonormal, t0 = −W⁺ w_ext, module `null_space`) this is
//! t = t0 + N Nᵀ (t_ref − t0): W⁺ W = I − N Nᵀ. It exists for any redundancy r ≥ 0 and is
//! feasible exactly when it lies within the bounds (checked with the certificate's 10⁻⁹
//! tolerance); otherwise the answer is [`Infeasibility::BoundsViolated`] with those tensions
//! (the feasible set may still be non-empty: the closed form is a heuristic). The thesis'
//! `closed-form` (Algorithm 6.1, r = 1, min ‖t‖₁) is a different method.
//!
//! **Fast path.** Without the null-space basis: the L D Lᵀ factor of W Wᵀ of the improved
//! closed form (module `improved_closed_form`, whose first step is exactly eq. (9)) gives
//! y = (W Wᵀ)⁻¹ (w_ext + W t_m) and t = t_m − Wᵀ y, and for the energy-efficient variant
//! d = N Nᵀ 1 = (I − W⁺ W) 1 = 1 − Wᵀ (W Wᵀ)⁻¹ W 1 from the same factor. The normal equations
//! square W's condition, so poses whose Hadamard ratio is below 10⁻³ (and singular ones) take
//! the QR null space as before; the two paths agree to 10⁻⁹ relative
//! (`tests/it/pott_closed_form.rs`).
//!
//! **Energy-efficient variant** (`pott-closed-form-ee`, WireLib's `ClosedFormEnergyEfficient`):
//! lowering every entry of t_ref by δ moves the closed form along t(δ) = t − δ d with
//! d = N Nᵀ 1. When the closed form is above every t_min and every d_i ≥ 0 (no cable rises when
//! t_ref is lowered), t_ref is lowered by the largest δ that keeps all cables at or above
//! t_min: δ = min over d_i > 0 of (t_i − t_min,i)/d_i, so one cable reaches t_min. Otherwise
//! (a cable below t_min, or a d_i < 0) t_ref is not moved — WireLib's rule, whose shift is
//! positive only in that case.
//!
//! ## References
//! - Pott, Bruckmann & Mikelsons (2009), *Closed-form force distribution for parallel wire
//!   robots*, Computational Kinematics, Springer, pp. 25–34, eq. (9).
//! - Pott (2014), *An improved force distribution algorithm for over-constrained cable-driven
//!   parallel robots*, Computational Kinematics, pp. 139–146 (the mean tension t_m).
//! - WireLib (Pott, Fraunhofer IPA), `CForceDistribution::getDistributionClosedFormEnergyEfficient`.

use crate::certificate::{BOUND_TOLERANCE, bound_violation};
use crate::improved_closed_form::ImprovedClosedForm;
use crate::null_space::NullSpace;
use crate::{Infeasibility, TensionBounds, TensionProblem};

/// Directions below this (relative) are "no motion" in the energy-efficient shift.
const NEGLIGIBLE: f64 = 1e-12;

/// Buffers of the closed form (no allocation once sized).
#[derive(Debug, Clone, Default)]
pub(crate) struct PottClosedForm {
    lambda: Vec<f64>,
    t_ref: Vec<f64>,
    d: Vec<f64>,
}

/// t_m = (t_min + t_max)/2 into `t_m`.
#[inline]
pub(crate) fn middle(bounds: &TensionBounds, t_m: &mut [f64]) {
    for ((m, lo), hi) in t_m.iter_mut().zip(bounds.min()).zip(bounds.max()) {
        *m = 0.5 * (lo + hi);
    }
}

/// The cable with the largest relative bound violation above the certificate's tolerance.
#[inline]
pub(crate) fn worst_violation(bounds: &TensionBounds, t: &[f64]) -> Option<(usize, f64)> {
    let (lo, hi) = (bounds.min(), bounds.max());
    let mut worst: Option<(usize, f64)> = None;
    let mut amount = BOUND_TOLERANCE;
    for (i, &ti) in t.iter().enumerate() {
        let v = bound_violation(lo[i], hi[i], ti);
        if v > amount {
            amount = v;
            worst = Some((i, ti));
        }
    }
    worst
}

impl PottClosedForm {
    /// t = t0 + N Nᵀ (t_ref − t0) with t_ref in `self.t_ref` (eq. (9)).
    fn project(&mut self, ns: &NullSpace, t: &mut [f64]) {
        self.lambda.resize(ns.r(), 0.0);
        ns.coordinates(&self.t_ref, &mut self.lambda);
        ns.tensions(&self.lambda, t);
    }

    /// The closed form from t_m (`energy_efficient`: then lowered, see the module docs) into
    /// `t`; [`Infeasibility::BoundsViolated`] when it breaks a bound (callers ensure finite
    /// t_max).
    pub fn solve(
        &mut self,
        ns: &NullSpace,
        bounds: &TensionBounds,
        energy_efficient: bool,
        t: &mut [f64],
    ) -> Result<(), Infeasibility> {
        let n = ns.n;
        self.t_ref.resize(n, 0.0);
        middle(bounds, &mut self.t_ref);
        self.project(ns, t);
        if energy_efficient {
            self.lower(ns, bounds, t);
        }
        verdict(bounds, t)
    }

    /// The fast path: the same closed form from the first step of the improved closed form's
    /// L D Lᵀ factor of W Wᵀ (no null-space basis; d = (I − W⁺W) 1 from the same factor for
    /// the energy-efficient shift). `None` when that step declines (W singular or
    /// ill-conditioned, see [`ImprovedClosedForm::first_step`]): the caller then takes
    /// [`Self::solve`] on the QR null space.
    pub fn solve_fast(
        &mut self,
        icf: &mut ImprovedClosedForm,
        problem: &TensionProblem,
        energy_efficient: bool,
        t: &mut [f64],
    ) -> Option<Result<(), Infeasibility>> {
        let n = t.len();
        self.d.resize(if energy_efficient { n } else { 0 }, 0.0);
        icf.first_step(problem, t, &mut self.d).ok()?;
        if energy_efficient {
            shift(&self.d, problem.bounds, t);
        }
        Some(verdict(problem.bounds, t))
    }
}

/// Feasible when `t` is within the bounds (the certificate's tolerance), else the worst
/// violation.
#[inline]
fn verdict(bounds: &TensionBounds, t: &[f64]) -> Result<(), Infeasibility> {
    match worst_violation(bounds, t) {
        None => Ok(()),
        Some((cable, tension)) => Err(Infeasibility::BoundsViolated {
            cable,
            tension,
            bound: if tension < bounds.min()[cable] {
                bounds.min()[cable]
            } else {
                bounds.max()[cable]
            },
            tensions: Default::default(),
        }),
    }
}

impl PottClosedForm {
    /// The energy-efficient shift t ← t − δ N Nᵀ 1 (module docs).
    fn lower(&mut self, ns: &NullSpace, bounds: &TensionBounds, t: &mut [f64]) {
        let (n, r) = (ns.n, ns.r());
        if below_a_minimum(bounds, t) {
            return;
        }
        // d = N Nᵀ 1.
        self.d.clear();
        self.d.resize(n, 0.0);
        for j in 0..r {
            let col = &ns.basis[j * n..(j + 1) * n];
            let s: f64 = col.iter().sum();
            for (di, c) in self.d.iter_mut().zip(col) {
                *di += c * s;
            }
        }
        shift(&self.d, bounds, t);
    }
}

/// Whether some cable is at or below its t_min (then the shift does not apply).
#[inline]
fn below_a_minimum(bounds: &TensionBounds, t: &[f64]) -> bool {
    t.iter().zip(bounds.min()).any(|(ti, l)| ti <= l)
}

/// t ← t − δ d with the largest δ ≥ 0 that keeps every cable at or above t_min, when every
/// cable is above its t_min and every d_i ≥ 0 (module docs); `t` unchanged otherwise.
#[inline]
fn shift(d: &[f64], bounds: &TensionBounds, t: &mut [f64]) {
    if below_a_minimum(bounds, t) {
        return;
    }
    let lo = bounds.min();
    let mut delta = f64::INFINITY;
    for (i, &di) in d.iter().enumerate() {
        if di < -NEGLIGIBLE {
            return;
        }
        if di > NEGLIGIBLE {
            delta = delta.min((t[i] - lo[i]) / di);
        }
    }
    if delta.is_finite() && delta > 0.0 {
        for (ti, di) in t.iter_mut().zip(d) {
            *ti -= delta * di;
        }
    }
}
