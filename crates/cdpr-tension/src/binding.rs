//! # Binding cables of an infeasible tension distribution
//!
//! When no admissible tension balances the wrench, *which* cables are in the way? The
//! balancing tensions that break the bounds the least,
//!
//! ```text
//!   min s   subject to   W t + w_ext = 0,   t_min,i − s ≤ t_i ≤ t_max,i + s,   s ≥ 0,
//! ```
//!
//! (s in N: the smallest uniform widening of every [t_min, t_max] that makes the set
//! non-empty), and the cables that break a bound by s* there: the *binding* cables. By LP
//! duality the multipliers of their bound rows are the Farkas certificate of emptiness of the
//! `infeasibility` module (a direction y with c = Wᵀ y that separates the zonotope of
//! {W t + w_ext} from the origin), so they are the bounds that certificate names. s* = 0 means
//! the feasible set is not empty (or touches only at its boundary): no binding cables.
//!
//! Solved by Clarabel (interior point): it allocates (~0.1 ms); for a message after a verdict,
//! not for grids.
//!
//! ## References
//! - Farkas (1902), *Theorie der einfachen Ungleichungen*, J. reine angew. Math. 124.
//! - Goulart & Chen (2024), *Clarabel: an interior-point solver for conic programs with
//!   quadratic objectives*, arXiv:2405.12762.

use crate::outcome::validate;
use crate::{TensionError, TensionProblem};
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus, ZeroConeT,
};
use nalgebra::DVector;
use std::fmt;

/// A cable whose bound the closest balancing tensions break by the largest amount.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BindingBound {
    /// Cable (0-based).
    pub cable: usize,
    /// Its tension in the closest balancing tensions (N).
    pub tension: f64,
    /// The bound it breaks: its t_min when `tension` is below it, else its t_max (N).
    pub bound: f64,
}

impl BindingBound {
    /// Whether the cable would need less than its t_min (else more than its t_max).
    pub fn below(&self) -> bool {
        self.tension < self.bound
    }
}

impl fmt::Display for BindingBound {
    /// "cable 3 would need 157 N, below its t_min of 200 N" (1-based, 6 significant digits).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let g = |v: f64| format!("{v:.5e}").parse().unwrap_or(v);
        write!(
            f,
            "cable {} would need {} N, {} its {} of {} N",
            self.cable + 1,
            g(self.tension),
            if self.below() { "below" } else { "above" },
            if self.below() { "t_min" } else { "t_max" },
            g(self.bound)
        )
    }
}

/// The balancing tensions closest to the bounds when there is no admissible one.
#[derive(Debug, Clone, PartialEq)]
pub struct ClosestBalance {
    /// t with W t + w_ext = 0 (to the solver's tolerance) and the smallest largest bound
    /// violation (N).
    pub tensions: DVector<f64>,
    /// That violation s* (N), > 0.
    pub violation: f64,
    /// The cables that break a bound by s* (to 10⁻⁶ relative), in cable order.
    pub binding: Vec<BindingBound>,
}

/// The closest balancing tensions and the binding cables of an infeasible problem (module
/// docs); `Ok(None)` when the bounds can be met (s* ≤ 10⁻⁹·max(1, max|t_min|, max|t_max|)) or
/// when no tension balances the wrench at all (W t = −w_ext has no solution: a singular pose).
///
/// ```
/// use cdpr_tension::{closest_balancing_tensions, TensionBounds, TensionProblem};
/// use nalgebra::{DMatrix, DVector};
/// // t1 − t2 = 10 with both tensions in [0, 5]: t1 = 7.5 and t2 = −2.5 break their bounds by 2.5 N.
/// let w = DMatrix::from_row_slice(1, 2, &[1.0, -1.0]);
/// let w_ext = DVector::from_vec(vec![-10.0]);
/// let b = TensionBounds::uniform(2, 0.0, 5.0)?;
/// let c = closest_balancing_tensions(&TensionProblem::new(&w, &w_ext, &b))?.unwrap();
/// assert!((c.violation - 2.5).abs() < 1e-6);
/// assert_eq!(c.binding[0].to_string(), "cable 1 would need 7.5 N, above its t_max of 5 N");
/// assert_eq!(c.binding[1].to_string(), "cable 2 would need -2.5 N, below its t_min of 0 N");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn closest_balancing_tensions(
    problem: &TensionProblem,
) -> Result<Option<ClosestBalance>, TensionError> {
    validate(problem)?;
    let w = problem.wrench_matrix;
    let (m, n) = w.shape();
    let (lo, hi) = (problem.bounds.min(), problem.bounds.max());
    let scale = lo
        .iter()
        .chain(hi.iter())
        .filter(|v| v.is_finite())
        .fold(1.0f64, |a, v| a.max(v.abs()));
    // Variables x = (t, s), in units of `scale` (Clarabel's tolerances are absolute).
    let (mut ri, mut ci, mut vals, mut b) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for k in 0..m {
        for i in 0..n {
            if w[(k, i)] != 0.0 {
                ri.push(k);
                ci.push(i);
                vals.push(w[(k, i)]);
            }
        }
        b.push(-problem.external_wrench[k] / scale);
    }
    let mut row = m;
    let mut push_row = |entries: &[(usize, f64)], rhs: f64, b: &mut Vec<f64>| {
        for &(c, v) in entries {
            ri.push(row);
            ci.push(c);
            vals.push(v);
        }
        b.push(rhs);
        row += 1;
    };
    for i in 0..n {
        if hi[i].is_finite() {
            push_row(&[(i, 1.0), (n, -1.0)], hi[i] / scale, &mut b); // t_i − s ≤ t_max
        }
        push_row(&[(i, -1.0), (n, -1.0)], -lo[i] / scale, &mut b); // −t_i − s ≤ −t_min
    }
    push_row(&[(n, -1.0)], 0.0, &mut b); // s ≥ 0
    let a = CscMatrix::new_from_triplets(row, n + 1, ri, ci, vals);
    let p = CscMatrix::zeros((n + 1, n + 1));
    let mut q = vec![0.0; n + 1];
    q[n] = 1.0;
    let cones = [ZeroConeT(m), NonnegativeConeT(row - m)];
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .tol_gap_abs(1e-10)
        .tol_gap_rel(1e-10)
        .tol_feas(1e-10)
        .max_iter(200)
        .build()
        .map_err(|_| TensionError::InvalidSettings("clarabel settings"))?;
    let Ok(mut solver) = DefaultSolver::new(&p, &q, &a, &b, &cones, settings) else {
        return Ok(None);
    };
    solver.solve();
    if !matches!(
        solver.solution.status,
        SolverStatus::Solved | SolverStatus::AlmostSolved
    ) {
        return Ok(None);
    }
    let x = &solver.solution.x;
    let violation = x[n] * scale;
    if violation.is_nan() || violation <= 1e-9 * scale {
        return Ok(None);
    }
    let tensions = DVector::from_fn(n, |i, _| x[i] * scale);
    let binding = (0..n)
        .filter_map(|i| {
            let t = tensions[i];
            let (below, above) = (lo[i] - t, t - hi[i]);
            let near = |v: f64| v >= violation * (1.0 - 1e-6) - 1e-9 * scale;
            if near(below) {
                Some(BindingBound {
                    cable: i,
                    tension: t,
                    bound: lo[i],
                })
            } else if near(above) {
                Some(BindingBound {
                    cable: i,
                    tension: t,
                    bound: hi[i],
                })
            } else {
                None
            }
        })
        .collect();
    Ok(Some(ClosestBalance {
        tensions,
        violation,
        binding,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Method, TensionBounds, TensionOutcome, TensionSolver};
    use nalgebra::DMatrix;

    /// Three cables at 90°, 210°, 330° (point2) holding a load L straight down. By hand: the x
    /// balance gives t₂ = t₃ = τ, the y balance (sin 30° = ½) t₁ − τ = L. With L = 100 N and
    /// bounds [200, 250] N: t₁ = τ + 100 ≤ 250 + s and τ ≥ 200 − s give s* = 25, t₁ = 275,
    /// τ = 175: cable 1 above its t_max, cables 2 and 3 below their t_min.
    #[test]
    fn symmetric_point2_load_binds_every_cable_by_hand() {
        let (c, s) = (30f64.to_radians().cos(), 0.5);
        let w = DMatrix::from_row_slice(2, 3, &[0.0, -c, c, 1.0, -s, -s]);
        let w_ext = DVector::from_vec(vec![0.0, -100.0]);
        let b = TensionBounds::uniform(3, 200.0, 250.0).unwrap();
        let p = TensionProblem::new(&w, &w_ext, &b);
        assert!(matches!(
            TensionSolver::new(Method::Pinv).solve(&p).unwrap(),
            TensionOutcome::Infeasible(_)
        ));
        let cb = closest_balancing_tensions(&p).unwrap().unwrap();
        assert!((cb.violation - 25.0).abs() < 1e-6, "{cb:?}");
        assert!((&w * &cb.tensions + &w_ext).amax() < 1e-6);
        assert_eq!(cb.binding.len(), 3);
        assert!(!cb.binding[0].below() && (cb.binding[0].tension - 275.0).abs() < 1e-6);
        assert!(cb.binding[1].below() && (cb.binding[1].tension - 175.0).abs() < 1e-6);
        // Feasible problems have no binding cables.
        let wide = TensionBounds::uniform(3, 10.0, 500.0).unwrap();
        assert!(
            closest_balancing_tensions(&TensionProblem::new(&w, &w_ext, &wide))
                .unwrap()
                .is_none()
        );
    }

    /// Only the cables the certificate needs are named: a cable that balances its own
    /// component within its bounds is not binding.
    #[test]
    fn slack_cables_are_not_named() {
        // t1 + t2 = 50 with t1, t2 ∈ [0, 10]: s = 15 (t1 = t2 = 25); t3 = 5 ∈ [0, 100].
        let w = DMatrix::from_row_slice(2, 3, &[1.0, 1.0, 0.0, 0.0, 0.0, 1.0]);
        let w_ext = DVector::from_vec(vec![-50.0, -5.0]);
        let b = TensionBounds::new(vec![0.0, 0.0, 0.0], vec![10.0, 10.0, 100.0]).unwrap();
        let cb = closest_balancing_tensions(&TensionProblem::new(&w, &w_ext, &b))
            .unwrap()
            .unwrap();
        assert!((cb.violation - 15.0).abs() < 1e-6, "{cb:?}");
        let cables: Vec<usize> = cb.binding.iter().map(|b| b.cable).collect();
        assert_eq!(cables, vec![0, 1]);
        assert_eq!(
            cb.binding[0].to_string(),
            "cable 1 would need 25 N, above its t_max of 10 N"
        );
    }
}
