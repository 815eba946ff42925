//! # Dynamic-Q
//!
//! Snyman and Hay's method of successive spherical quadratic approximations, as used by the
//! thesis for eq. (6.29). At iterate **x**^k (minimising f = −A) the objective is replaced by
//!
//! f̃(**x**) = f(**x**^k) + ∇f(**x**^k)ᵀ(**x** − **x**^k) + ½ a_k ‖**x** − **x**^k‖²,
//!
//! with the curvature a_k = 2 [f(**x**^{k−1}) − f(**x**^k) − ∇f(**x**^k)ᵀ(**x**^{k−1} − **x**^k)]
//! / ‖**x**^{k−1} − **x**^k‖² fitted to the previous iterate (a_0 = 0), the constraints by their
//! (here exact, piecewise linear) approximations, and the move limit |x_i − x_i^k| ≤ δ (δ_0 = ρ).
//! The subproblem's spherical objective makes it a Euclidean projection of **x**^k − ∇f / a_k
//! onto the linearised feasible set, solved exactly (the original solves it with LFOPC). A
//! non-convex fit (a_k ≤ 0) is replaced by a small positive curvature, as in the original.
//! Gradients are central differences with the wide interval Γ, which smooths the staircase of a
//! grid-based area.
//!
//! Safeguard (the original's "reduce the move limit on ascent" rule): a step that does not
//! decrease the merit φ = f + μ·(violation of eq. (6.29)) is rejected, the curvature is refitted
//! through the rejected point and δ is halved. The run stops when the step is shorter than
//! `step_tolerance`, δ falls below `min_move_limit`, the merit has stalled for
//! `stall_iterations` accepted steps, or the gradient budget is spent.
//!
//! ## References
//! - J. A. Snyman and A. M. Hay, "The Dynamic-Q optimization method: an alternative to SQP?",
//!   *Computers & Mathematics with Applications* 44 (2002) 1589–1598.
//! - J. A. Snyman, *Practical Mathematical Optimization*, Springer, 2005, §6.4.
//! - Thesis §6.6.2 (ρ = 0.1, Γ = 0.05 for 3 cables and 0.1 for 4, central differences).

use super::design::linear_separations;
use super::objective::{Merit, Objective};
use super::projection::{PairHalfSpace, Projector};
use super::{Evaluations, SynthesisError, SynthesisResult, Termination, invalid};

/// Settings of [`maximise`].
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicQSettings {
    /// Move limit ρ (rad): initial bound on |x_i − x_i^k| per step. Thesis: 0.1.
    pub move_limit: f64,
    /// Central finite-difference interval Γ (rad). Thesis: 0.05 (3 cables), 0.1 (4 cables).
    pub fd_interval: f64,
    /// Stop when the step ‖**x**^{k+1} − **x**^k‖ is shorter than this (rad).
    pub step_tolerance: f64,
    /// Stop when rejections have halved the move limit below this (rad).
    pub min_move_limit: f64,
    /// Stop after this many accepted steps without a strict decrease of the merit.
    pub stall_iterations: usize,
    /// Budget of gradient evaluations N^g.
    pub max_gradient_evaluations: usize,
}

impl Default for DynamicQSettings {
    fn default() -> Self {
        Self {
            move_limit: 0.1,
            fd_interval: 0.05,
            step_tolerance: 1e-4,
            min_move_limit: 2e-3,
            stall_iterations: 5,
            max_gradient_evaluations: 100,
        }
    }
}

impl DynamicQSettings {
    /// Checks every setting's domain.
    pub fn validate(&self) -> Result<(), SynthesisError> {
        let positive = |name, v: f64| {
            if v > 0.0 && v.is_finite() {
                Ok(())
            } else {
                Err(invalid(name, v, "need a finite value > 0"))
            }
        };
        positive("move_limit", self.move_limit)?;
        positive("fd_interval", self.fd_interval)?;
        positive("step_tolerance", self.step_tolerance)?;
        positive("min_move_limit", self.min_move_limit)?;
        if self.max_gradient_evaluations == 0 {
            return Err(invalid("max_gradient_evaluations", 0.0, "need at least 1"));
        }
        Ok(())
    }
}

/// Central-difference gradient of f = −A at `x` (2n evaluations); writes into `g`.
fn gradient<O: Objective + ?Sized>(
    merit: &mut Merit<'_, O>,
    x: &[f64],
    interval: f64,
    probe: &mut Vec<f64>,
    g: &mut [f64],
) {
    probe.clear();
    probe.extend_from_slice(x);
    for i in 0..x.len() {
        probe[i] = x[i] + interval;
        let plus = -merit.area(probe);
        probe[i] = x[i] - interval;
        let minus = -merit.area(probe);
        probe[i] = x[i];
        let d = (plus - minus) / (2.0 * interval);
        // A failed evaluation gives no slope information.
        g[i] = if d.is_finite() { d } else { 0.0 };
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Maximises `objective` from `start` subject to eq. (6.29) with separation β_min
/// (`min_separation`, rad); `penalty` is μ of the merit φ = −A + μ·violation that decides whether
/// a step is accepted. Settings are assumed valid ([`DynamicQSettings::validate`]).
pub fn maximise<O: Objective + ?Sized>(
    objective: &mut O,
    start: &[f64],
    min_separation: f64,
    penalty: f64,
    settings: &DynamicQSettings,
) -> SynthesisResult {
    let n = start.len();
    let mut merit = Merit::new(objective, start, min_separation, penalty);
    let mut projector = Projector::default();
    let mut probe = Vec::with_capacity(n);

    let mut x = start.to_vec();
    let mut area = merit.area(&x);
    let mut phi = merit.merit(&x, area);
    let mut g = vec![0.0; n];
    gradient(&mut merit, &x, settings.fd_interval, &mut probe, &mut g);
    let mut gradients = 1;

    let mut curvature: f64 = 0.0;
    let mut delta = settings.move_limit;
    let mut stalled = 0;
    let mut iterations = 0;
    let mut y = vec![0.0; n];
    let mut step = vec![0.0; n];
    let mut trial = vec![0.0; n];
    let mut g_trial = vec![0.0; n];
    let mut halfspaces: Vec<PairHalfSpace> = Vec::with_capacity(n);

    let termination = loop {
        iterations += 1;
        // Subproblem: min gᵀs + ½ a ‖s‖² s.t. linearised eq. (6.29), |s_i| ≤ δ.
        // a is floored so that the unconstrained minimiser stays within 10³ move limits
        // (the LP limit a → 0⁺ of the original, without overflow).
        let g_norm = dot(&g, &g).sqrt();
        let floor = (g_norm / (1e3 * delta)).max(1e-12);
        let a = curvature.max(floor);
        for (yi, gi) in y.iter_mut().zip(&g) {
            *yi = -gi / a;
        }
        halfspaces.clear();
        halfspaces.extend(linear_separations(&x).into_iter().map(|l| PairHalfSpace {
            i: l.i,
            j: l.j,
            sign: l.sign,
            rhs: min_separation - l.value,
        }));
        projector.project(&y, delta, &halfspaces, &mut step);
        let step_norm = dot(&step, &step).sqrt();
        if step_norm < settings.step_tolerance {
            break Termination::Converged;
        }
        for ((t, xi), si) in trial.iter_mut().zip(&x).zip(&step) {
            *t = xi + si;
        }
        let trial_area = merit.area(&trial);
        let trial_phi = merit.merit(&trial, trial_area);
        if trial_phi <= phi {
            if gradients >= settings.max_gradient_evaluations {
                // Accept the improvement, but no budget remains for its gradient.
                x.copy_from_slice(&trial);
                area = trial_area;
                break Termination::Budget;
            }
            gradient(
                &mut merit,
                &trial,
                settings.fd_interval,
                &mut probe,
                &mut g_trial,
            );
            gradients += 1;
            // a_k fitted through the previous iterate with the new gradient.
            let back: f64 = -dot(&g_trial, &step);
            curvature = 2.0 * ((-area) - (-trial_area) - back) / (step_norm * step_norm);
            stalled = if trial_phi < phi { 0 } else { stalled + 1 };
            x.copy_from_slice(&trial);
            g.copy_from_slice(&g_trial);
            area = trial_area;
            phi = trial_phi;
            if stalled >= settings.stall_iterations {
                break Termination::Converged;
            }
        } else {
            // Refit the curvature through the rejected point and shrink the move limit.
            if trial_area.is_finite() {
                curvature =
                    2.0 * ((-trial_area) - (-area) - dot(&g, &step)) / (step_norm * step_norm);
            } else {
                curvature *= 2.0;
            }
            delta *= 0.5;
            if delta < settings.min_move_limit {
                break Termination::Converged;
            }
        }
        if gradients >= settings.max_gradient_evaluations {
            break Termination::Budget;
        }
    };
    let constraint_violation = super::design::separation_violation(&x, min_separation);
    SynthesisResult {
        design: x,
        area,
        constraint_violation,
        evaluations: Evaluations {
            function: merit.evaluations,
            gradient: gradients,
        },
        iterations,
        termination,
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_functions::*;
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn spherical_quadratic_is_solved_in_a_few_gradients() {
        // Three move-limited steps of ρ = 0.1, then the fitted curvature is exact.
        let c = [0.5, 2.5, 4.5];
        let r = maximise(
            &mut bowl(&c),
            &[0.2, 2.8, 4.2],
            BETA_MIN,
            1e3,
            &DynamicQSettings::default(),
        );
        for (d, e) in r.design.iter().zip(&c) {
            assert!((d - e).abs() < 1e-6, "{:?}", r.design);
        }
        assert!(r.evaluations.gradient <= 6, "{:?}", r.evaluations);
        assert_eq!(r.termination, Termination::Converged);
        assert_eq!(
            r.evaluations.function,
            r.evaluations.gradient * 6 + r.iterations
        );
    }

    #[test]
    fn gradient_budget_is_respected() {
        let s = DynamicQSettings {
            max_gradient_evaluations: 2,
            ..DynamicQSettings::default()
        };
        let r = maximise(
            &mut bowl(&[0.5, 2.5, 4.5]),
            &[-1.0, 1.0, 3.0],
            BETA_MIN,
            1e3,
            &s,
        );
        assert_eq!(r.termination, Termination::Budget);
        assert_eq!(r.evaluations.gradient, 2);
        // Two accepted steps of at most ρ per coordinate.
        assert!((r.design[0] + 1.0).abs() <= 0.2 + 1e-12);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(32))]
        #[test]
        fn finds_feasible_maxima_and_ends_feasible(
            first in 0.0..1.0f64,
            gaps in proptest::collection::vec(0.3..2.0f64, 3),
            offset in proptest::collection::vec(-0.12..0.12f64, 4),
        ) {
            // Four anchors with separations ≥ 0.3 > β_min (the wrap gap too); the start keeps
            // their cyclic order (no continuous path under eq. (6.29) changes it) but may be
            // infeasible (gaps down to 0.06).
            let mut c = vec![first];
            for g in &gaps { c.push(c.last().unwrap() + g); }
            prop_assume!(std::f64::consts::TAU - (c[3] - c[0]) >= 0.3);
            let start: Vec<f64> = c.iter().zip(&offset).map(|(a, b)| a + b).collect();
            let r = maximise(&mut staircase(&c, 0.005), &start, BETA_MIN, 1e3, &DynamicQSettings::default());
            prop_assert!(r.constraint_violation < 1e-9);
            for (d, e) in r.design.iter().zip(&c) {
                prop_assert!((d - e).abs() < 0.01, "{:?} vs {:?}", r.design, c);
            }
        }
    }
}
