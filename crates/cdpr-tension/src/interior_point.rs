//! # Interior-point formulation (Clarabel)
//!
//! The constrained problems in tension space, solved by Clarabel: the fallback of the dense
//! active-set solvers (redundancy r ≥ 3) on numerical failure, and the independent oracle of
//! the tests. It allocates (~50–80 µs per solve at r = 5). Variables x = t (and s for linf):
//!
//! ```text
//!   W t = −w_ext                    (zero cone)
//!   t ≤ t_max,  −t ≤ −t_min         (non-negative cone; rows with t_max = ∞ dropped)
//!   l1: min 1ᵀt   l1-max: min −1ᵀt   l2: min ½ tᵀ(2I)t   linf: min s, t_i − s ≤ 0
//! ```
//!
//! When the QP or the ℓ∞ LP is declared infeasible, the ℓ₁ LP decides; if it finds tensions,
//! the objective is re-solved in units of their largest tension (Clarabel misjudges sets that
//! lie ~10⁵ times above the data scale).
//!
//! The returned tensions are polished (near-active tensions snapped to their bounds, then a
//! minimum-norm equilibrium correction on the free cables) so that they pass the certificate.
//!
//! ## References
//! - Goulart & Chen (2024), *Clarabel: an interior-point solver for conic programs with
//!   quadratic objectives*, arXiv:2405.12762.
//! - Thesis eqs. (6.17), (6.19).

use crate::certificate::polish;
use crate::outcome::validate;
use crate::{Infeasibility, TensionError, TensionProblem};
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus, ZeroConeT,
};
use nalgebra::DVector;

/// The objective of an interior-point solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Objective {
    /// min Σ t_i.
    L1,
    /// max Σ t_i.
    L1Max,
    /// min ‖t‖₂².
    L2,
    /// min max_i t_i.
    Linf,
}

/// Solves `problem` with Clarabel (any redundancy). Returns polished tensions (not yet
/// certified: [`crate::TensionSolver`] certifies them) or why there are none.
///
/// ```
/// use cdpr_tension::{interior_point, Objective, TensionBounds, TensionProblem};
/// use nalgebra::{DMatrix, DVector};
/// let w = DMatrix::from_row_slice(1, 2, &[1.0, -1.0]);
/// let we = DVector::from_vec(vec![-3.0]);
/// let b = TensionBounds::uniform(2, 1.0, 10.0).unwrap();
/// let t = interior_point(&TensionProblem::new(&w, &we, &b), Objective::L2).unwrap().unwrap();
/// assert!((t[0] - 4.0).abs() < 1e-7 && (t[1] - 1.0).abs() < 1e-7);
/// ```
pub fn interior_point(
    problem: &TensionProblem,
    objective: Objective,
) -> Result<Result<DVector<f64>, Infeasibility>, TensionError> {
    validate(problem)?;
    let first = solve_scaled(problem, objective, 1.0)?;
    // Clarabel can call a non-empty set infeasible when it is reached only at tensions many
    // orders of magnitude above the data (e.g. a pure moment on small moment arms with
    // t_max = ∞: ~10⁵). Then the LP decides, and the objective is re-solved in units of the LP
    // answer's largest tension.
    if objective != Objective::L1
        && matches!(first, Err(Infeasibility::NoFeasibleTension))
        && let Ok(t1) = solve_scaled(problem, Objective::L1, 1.0)?
    {
        let sigma = t1.amax();
        if sigma > 1.0 {
            return Ok(match solve_scaled(problem, objective, sigma)? {
                Err(Infeasibility::NoFeasibleTension) => Err(Infeasibility::SolverFailure {
                    detail: format!(
                        "clarabel: {} infeasible, l1 feasible (max tension {sigma:.3e})",
                        objective_name(objective)
                    ),
                }),
                other => other,
            });
        }
    }
    Ok(first)
}

fn objective_name(objective: Objective) -> &'static str {
    match objective {
        Objective::L1 => "l1",
        Objective::L1Max => "l1-max",
        Objective::L2 => "l2",
        Objective::Linf => "linf",
    }
}

/// One Clarabel solve in the variables x = t / σ (σ > 0), returning polished t.
fn solve_scaled(
    problem: &TensionProblem,
    objective: Objective,
    sigma: f64,
) -> Result<Result<DVector<f64>, Infeasibility>, TensionError> {
    let w = problem.wrench_matrix;
    let (m, n) = w.shape();
    let (lo, hi) = (problem.bounds.min(), problem.bounds.max());
    let nv = if objective == Objective::Linf {
        n + 1
    } else {
        n
    };
    let (mut ri, mut ci, mut vals) = (Vec::new(), Vec::new(), Vec::new());
    let mut b = Vec::new();
    for k in 0..m {
        for i in 0..n {
            if w[(k, i)] != 0.0 {
                ri.push(k);
                ci.push(i);
                vals.push(w[(k, i)]);
            }
        }
        b.push(-problem.external_wrench[k] / sigma);
    }
    let mut row = m;
    for i in 0..n {
        if hi[i].is_finite() {
            ri.push(row);
            ci.push(i);
            vals.push(1.0);
            b.push(hi[i] / sigma);
            row += 1;
        }
        ri.push(row);
        ci.push(i);
        vals.push(-1.0);
        b.push(-lo[i] / sigma);
        row += 1;
        if objective == Objective::Linf {
            ri.push(row);
            ci.push(i);
            vals.push(1.0);
            ri.push(row);
            ci.push(n);
            vals.push(-1.0);
            b.push(0.0);
            row += 1;
        }
    }
    let a = CscMatrix::new_from_triplets(row, nv, ri, ci, vals);
    let p = if objective == Objective::L2 {
        CscMatrix::new_from_triplets(n, n, (0..n).collect(), (0..n).collect(), vec![2.0; n])
    } else {
        CscMatrix::zeros((nv, nv))
    };
    let q: Vec<f64> = match objective {
        Objective::L1 => vec![1.0; n],
        Objective::L1Max => vec![-1.0; n],
        Objective::L2 => vec![0.0; n],
        Objective::Linf => {
            let mut q = vec![0.0; n + 1];
            q[n] = 1.0;
            q
        }
    };
    let cones = [ZeroConeT(m), NonnegativeConeT(row - m)];
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .tol_gap_abs(1e-10)
        .tol_gap_rel(1e-10)
        .tol_feas(1e-10)
        .max_iter(200)
        .build()
        .map_err(|e| TensionError::InvalidSettings(leak_free(e.to_string())))?;
    let mut solver = match DefaultSolver::new(&p, &q, &a, &b, &cones, settings) {
        Ok(s) => s,
        Err(e) => {
            return Ok(Err(Infeasibility::SolverFailure {
                detail: format!("clarabel setup: {e}"),
            }));
        }
    };
    solver.solve();
    let status = solver.solution.status;
    match status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => {
            let mut t: Vec<f64> = solver.solution.x[..n].iter().map(|x| x * sigma).collect();
            polish(w, problem.external_wrench, problem.bounds, &mut t);
            Ok(Ok(DVector::from_vec(t)))
        }
        SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => {
            Ok(Err(Infeasibility::NoFeasibleTension))
        }
        SolverStatus::DualInfeasible | SolverStatus::AlmostDualInfeasible => {
            Ok(Err(Infeasibility::Unbounded {
                method: objective_name(objective),
            }))
        }
        other => Ok(Err(Infeasibility::SolverFailure {
            detail: format!("clarabel: {other:?}"),
        })),
    }
}

fn leak_free(_s: String) -> &'static str {
    "clarabel settings"
}
