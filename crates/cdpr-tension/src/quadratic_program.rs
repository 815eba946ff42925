//! # Constrained ℓ₂ approach (quadratic programs)
//!
//! - **l2** (thesis eq. (6.17)): minimise ‖t‖₂² subject to W t + w_ext = 0 and the bounds.
//!   Without bounds this is the minimum-norm solution (6.14) (thesis Appendix E).
//! - **l2-max**: maximise ‖t‖₂² ("maximal stiffness", §6.3.2). This is a concave maximisation:
//!   its maximum is attained at a vertex of the feasible polytope, so we enumerate vertices.
//!
//! With the orthonormal null-space basis, ‖t0 + N λ‖² = ‖t0‖² + 2 gᵀλ + ‖λ‖² (g = Nᵀ t0 = 0 up to
//! rounding, since t0 is the minimum-norm solution), so for r ≤ 2 the l2 optimum is the exact
//! Euclidean projection of −g onto the feasible interval / polygon (at r = 2 found first by a
//! planar active set without building the polygon, module `planar_active_set`), and l2-max is
//! the vertex farthest from −g. For r ≥ 3, l2 is the same projection, computed by the dual active-set
//! method of Goldfarb & Idnani (module `active_set`), and l2-max visits the vertices of the
//! feasible set by pivoting along its edges (module `vertex_enumeration`), falling back to the
//! candidates {λ : r independent bounds active} (at most C(n, r)·2^r, capped at 2·10⁵).
//!
//! ## References
//! - The thesis chapter on planar tendon-driven manipulators (ch. 6), §6.3.2, eq. (6.17) and Appendix E.

use crate::active_set::{ActiveSet, DenseEnd};
use crate::certificate::{bound_violation, snap_and_certify};
use crate::feasible_polygon::Region;
use crate::linear_program::write_tensions;
use crate::null_space::NullSpace;
use crate::vertex_enumeration::{GaveUp, VertexSearch};
use crate::{Infeasibility, Method, Objective, TensionBounds, TensionProblem, TensionSolver};
use nalgebra::{DMatrix, DVector};

/// l2 (`maximize = false`) or l2-max on a built, non-empty region (r ≤ 2).
pub(crate) fn solve_on_region(
    maximize: bool,
    ns: &NullSpace,
    region: &Region,
    method: &'static str,
    t: &mut [f64],
) -> Result<(), Infeasibility> {
    let g = [
        ns.g.first().copied().unwrap_or(0.0),
        ns.g.get(1).copied().unwrap_or(0.0),
    ];
    let lambda = if maximize {
        if region.is_unbounded() {
            return Err(Infeasibility::Unbounded { method });
        }
        region.best_vertex(
            |l| 2.0 * (g[0] * l[0] + g[1] * l[1]) + l[0] * l[0] + l[1] * l[1],
            true,
        )
    } else {
        region.project([-g[0], -g[1]])
    };
    if region.on_artificial_box(lambda) {
        return Err(Infeasibility::Unbounded { method });
    }
    write_tensions(ns, lambda, t);
    Ok(())
}

/// Maximum cap on the number of vertex candidates for r ≥ 3.
const MAX_CANDIDATES: f64 = 2e5;

/// Whether the feasible set {t = t0 + N λ : t_min ≤ t ≤ t_max} is unbounded, decided from the
/// set (issue 13): a closed convex set is unbounded exactly when its recession cone
/// {d ∈ null(W) : d ≥ 0, d_i = 0 where t_max,i < ∞} has a non-zero ray. The largest Σ d over
/// that cone cut by d ≤ 1 is an LP (l1-max on a tension problem with w_ext = 0 and bounds
/// [0, 0] or [0, 1]); the set is unbounded iff its optimum is positive. Callers ensure the set is
/// non-empty and some t_max is infinite. `None` when the LP itself fails.
fn has_recession_ray(w: &DMatrix<f64>, bounds: &TensionBounds) -> Option<bool> {
    let n = w.ncols();
    let hi: Vec<f64> = bounds
        .max()
        .iter()
        .map(|v| if v.is_finite() { 0.0 } else { 1.0 })
        .collect();
    let cone = TensionBounds::new(vec![0.0; n], hi).ok()?;
    let zero = DVector::zeros(w.nrows());
    let problem = TensionProblem::new(w, &zero, &cone);
    match TensionSolver::new(Method::L1Max).solve(&problem).ok()? {
        crate::TensionOutcome::Feasible(s) => Some(s.tensions.sum() > 1e-9 * n as f64),
        crate::TensionOutcome::Infeasible(_) => None,
    }
}

/// l2-max at r ≥ 3: first whether the set is empty (the dense l1 LP on the same null space),
/// then, with an infinite t_max, whether it is unbounded ([`has_recession_ray`]); the bounded set's
/// best vertex is then found by pivoting from the l1 solution
/// ([`crate::vertex_enumeration`]), or, when that search gives way, among the candidates of
/// [`l2_max_by_vertices`] (an infinite bound is never active at a vertex).
pub(crate) fn l2_max_high_redundancy(
    problem: &TensionProblem,
    ns: &NullSpace,
    dense: &mut ActiveSet,
    search: &mut VertexSearch,
    t: &mut [f64],
) -> Result<(), Infeasibility> {
    match dense.solve(ns, problem.bounds, Objective::L1, "l2-max", t) {
        DenseEnd::Infeasible(reason) => return Err(reason),
        DenseEnd::Solved => {}
        DenseEnd::Failed(_) => {
            // The l1 LP by the full solver (Clarabel fallback included).
            let l1 = TensionSolver::new(Method::L1).solve(problem).map_err(|e| {
                Infeasibility::SolverFailure {
                    detail: format!("l2-max: feasibility test: {e}"),
                }
            })?;
            match l1 {
                crate::TensionOutcome::Infeasible(reason) => return Err(reason),
                crate::TensionOutcome::Feasible(s) => t.copy_from_slice(s.tensions.as_slice()),
            }
        }
    }
    if problem.bounds.max().iter().any(|v| !v.is_finite()) {
        match has_recession_ray(problem.wrench_matrix, problem.bounds) {
            Some(true) => return Err(Infeasibility::Unbounded { method: "l2-max" }),
            Some(false) => {}
            None => {
                return Err(Infeasibility::SolverFailure {
                    detail: "l2-max: the recession-cone LP failed".to_string(),
                });
            }
        }
    }
    match search.l2_max(ns, problem.bounds, t) {
        // The walk passes through vertices feasible within their own rounding; an answer
        // that misses the certificate is left to the candidate enumeration.
        Ok(Ok(()))
            if snap_and_certify(
                problem.wrench_matrix,
                problem.external_wrench,
                problem.bounds,
                t,
            )
            .is_err() =>
        {
            l2_max_by_vertices(ns, problem.bounds, t)
        }
        Ok(answer) => answer,
        Err(GaveUp) => l2_max_by_vertices(ns, problem.bounds, t),
    }
}

/// l2-max for any redundancy r ≥ 1 by candidate enumeration in λ-space (allocates): every
/// choice of r cables at one of their bounds, C(n, r)·2ʳ linear systems. The fallback of the
/// pivoting search, and its test oracle. The set must
/// be bounded (see [`l2_max_high_redundancy`]); an infinite t_max is never a vertex's bound.
pub(crate) fn l2_max_by_vertices(
    ns: &NullSpace,
    bounds: &TensionBounds,
    t: &mut [f64],
) -> Result<(), Infeasibility> {
    let (n, r) = (ns.n, ns.r());
    let mut count = 2f64.powi(r as i32);
    for k in 0..r {
        count *= (n - k) as f64 / (k + 1) as f64;
    }
    if count > MAX_CANDIDATES {
        return Err(Infeasibility::SolverFailure {
            detail: format!("l2-max: {count:.0} vertex candidates exceed the cap"),
        });
    }
    let nmat = DMatrix::from_column_slice(n, r, &ns.basis);
    let t0 = DVector::from_column_slice(&ns.t0);
    let mut subset: Vec<usize> = (0..r).collect();
    let mut best: Option<(f64, DVector<f64>)> = None;
    loop {
        let a = DMatrix::from_fn(r, r, |i, j| nmat[(subset[i], j)]);
        if let Some(lu) = Some(a.lu()).filter(|lu| lu.is_invertible()) {
            for mask in 0..(1usize << r) {
                if (0..r).any(|i| mask >> i & 1 == 1 && !bounds.max()[subset[i]].is_finite()) {
                    continue;
                }
                let rhs = DVector::from_fn(r, |i, _| {
                    let c = subset[i];
                    let b = if mask >> i & 1 == 1 {
                        bounds.max()[c]
                    } else {
                        bounds.min()[c]
                    };
                    b - t0[c]
                });
                let Some(l) = lu.solve(&rhs) else { continue };
                let tv = &t0 + &nmat * l;
                let ok = (0..n)
                    .all(|i| bound_violation(bounds.min()[i], bounds.max()[i], tv[i]) <= 1e-10);
                if ok {
                    let f = tv.norm_squared();
                    if best.as_ref().is_none_or(|(fb, _)| f > *fb) {
                        best = Some((f, tv));
                    }
                }
            }
        }
        // Next r-subset of 0..n in lexicographic order.
        let mut k = r;
        while k > 0 && subset[k - 1] == n - r + k - 1 {
            k -= 1;
        }
        if k == 0 {
            break;
        }
        subset[k - 1] += 1;
        for j in k..r {
            subset[j] = subset[j - 1] + 1;
        }
    }
    match best {
        Some((_, tv)) => {
            t.copy_from_slice(tv.as_slice());
            Ok(())
        }
        None => Err(Infeasibility::NoFeasibleTension),
    }
}
