//! # Active sets on the feasible polygon (redundancy 2)
//!
//! At redundancy r = 2 the l2 optimum is the Euclidean projection of c = −Nᵀt0 (≈ 0) onto the
//! feasible polygon {λ : t_min ≤ t0 + N λ ≤ t_max} (see [`crate::FeasiblePolygon`]), whose
//! 2n half-planes are s·a_i·λ ≥ β (a_i = row i of N; s = +1, β = t_min,i − t0,i for the lower
//! bound; s = −1, β = t0,i − t_max,i for the upper one). The projection is found without
//! building the polygon, by a primal active set of at most two constraints (Nocedal & Wright
//! 2006, §16.5, in the plane):
//!
//! 1. λ = c; while some constraint q is violated at λ (the farthest one in λ-space first),
//!    add q to the working set 𝒲;
//! 2. 𝒲 = {q}: λ is the projection of c onto the line of q; 𝒲 = {p, q}: λ is the intersection
//!    of both lines, and the multipliers μ of λ − c = Σ_{j∈𝒲} μ_j s_j a_j must be ≥ 0, else the
//!    constraint with μ < 0 leaves 𝒲 (with three candidates, the pair or single constraint whose
//!    multipliers are ≥ 0 and that satisfies the one left out is kept).
//!
//! The loop stops at a point that violates no constraint (beyond 10⁻¹² relative) with
//! multipliers ≥ 0: the Karush–Kuhn–Tucker conditions of the strictly convex problem, so that
//! point *is* the projection. Anything else (a cap of 4 + 2n steps, parallel lines, a fixed cable
//! t_min = t_max, a null-space row ≈ 0, an answer far out on an infinite t_max, a failed
//! certificate) hands the problem back to the polygon, which also decides every infeasible
//! problem: a verdict of this path is only ever "feasible", and it is certified.
//!
//! ## References
//! - Nocedal & Wright (2006), *Numerical Optimization*, 2nd ed., §16.5 (active-set methods for
//!   convex quadratic programs).
//! - Picard, Caro, Plestan & Claveau 2020, eqs. (5)–(6).

use crate::TensionBounds;
use crate::feasible_polygon::P2;
use crate::null_space::NullSpace;

/// Relative violation below which a constraint counts as satisfied (a hundredth of the
/// polygon's clipping tolerance: the answer is certified with 10⁻⁹).
const VIOLATION: f64 = 1e-12;

/// Constraint j of the polygon: j = 2i is t_i ≥ t_min,i, j = 2i + 1 is t_i ≤ t_max,i.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Constraint(usize);

impl Constraint {
    /// Inward normal s·a_i and right-hand side β of s·a_i·λ ≥ β.
    #[inline(always)]
    fn line(self, ns: &NullSpace, bounds: &TensionBounds) -> (P2, f64) {
        let i = self.0 / 2;
        let a = ns.row2(i);
        if self.0 % 2 == 0 {
            (a, bounds.min()[i] - ns.t0[i])
        } else {
            ([-a[0], -a[1]], ns.t0[i] - bounds.max()[i])
        }
    }
}

#[inline(always)]
fn dot(a: P2, b: P2) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// The constraint violated farthest (distance in λ-space) at λ, outside the working set.
#[inline(always)]
fn most_violated(
    ns: &NullSpace,
    bounds: &TensionBounds,
    l: P2,
    working: &[Constraint],
) -> Option<Constraint> {
    let (lo, hi) = (bounds.min().as_slice(), bounds.max().as_slice());
    // Best violation v and squared row norm q, compared as v²/q.
    let (mut best, mut bv, mut bq) = (None, 0.0f64, 1.0f64);
    for i in 0..ns.n {
        let a = ns.row2(i);
        let t = ns.t0[i] + a[0] * l[0] + a[1] * l[1];
        let (below, above) = (lo[i] - t, t - hi[i]);
        let (j, v, tol) = if below > 0.0 {
            (2 * i, below, VIOLATION * lo[i].abs().max(1.0))
        } else if above > 0.0 {
            (2 * i + 1, above, VIOLATION * hi[i].abs().max(1.0))
        } else {
            continue;
        };
        if v <= tol || working.contains(&Constraint(j)) {
            continue;
        }
        let q = dot(a, a);
        if best.is_none() || v * v * bq > bv * bv * q {
            (best, bv, bq) = (Some(Constraint(j)), v, q);
        }
    }
    best
}

/// Projection of c onto the line n·λ = β, and its multiplier μ (λ − c = μ n).
#[inline(always)]
fn onto_line(c: P2, n: P2, beta: f64) -> (P2, f64) {
    let mu = (beta - dot(n, c)) / dot(n, n);
    ([c[0] + mu * n[0], c[1] + mu * n[1]], mu)
}

/// Intersection of the lines n_p·λ = β_p and n_q·λ = β_q, and the multipliers (μ_p, μ_q) of
/// d = μ_p n_p + μ_q n_q; `None` for nearly parallel lines.
#[inline(always)]
fn vertex(np: P2, bp: f64, nq: P2, bq: f64, c: P2) -> Option<(P2, f64, f64)> {
    let det = np[0] * nq[1] - np[1] * nq[0];
    let size = (np[0].abs() + np[1].abs()) * (nq[0].abs() + nq[1].abs());
    if det.abs() <= 1e-9 * size || det.is_nan() {
        return None;
    }
    let v = [
        (bp * nq[1] - np[1] * bq) / det,
        (np[0] * bq - bp * nq[0]) / det,
    ];
    let (mp, mq) = multipliers(np, nq, det, [v[0] - c[0], v[1] - c[1]]);
    Some((v, mp, mq))
}

/// (μ_p, μ_q) with d = μ_p n_p + μ_q n_q (Cramer; det = n_p × n_q).
#[inline(always)]
fn multipliers(np: P2, nq: P2, det: f64, d: P2) -> (f64, f64) {
    (
        (d[0] * nq[1] - d[1] * nq[0]) / det,
        (np[0] * d[1] - np[1] * d[0]) / det,
    )
}

/// Whether λ satisfies constraint j (within [`VIOLATION`]).
#[inline(always)]
fn satisfies(ns: &NullSpace, bounds: &TensionBounds, j: Constraint, l: P2) -> bool {
    let i = j.0 / 2;
    let t = ns.tension2(i, l);
    if j.0 % 2 == 0 {
        let lo = bounds.min()[i];
        lo - t <= VIOLATION * lo.abs().max(1.0)
    } else {
        let hi = bounds.max()[i];
        t - hi <= VIOLATION * hi.abs().max(1.0)
    }
}

/// The l2 optimum λ (the projection of −g onto the feasible polygon) by the active set of the
/// module docs, or `None` when the polygon must decide.
pub(crate) fn l2_projection(ns: &NullSpace, bounds: &TensionBounds) -> Option<P2> {
    let n = ns.n;
    debug_assert_eq!(ns.r(), 2);
    let (lo, hi) = (bounds.min().as_slice(), bounds.max().as_slice());
    let mut unbounded = false;
    for i in 0..n {
        let a = ns.row2(i);
        if lo[i] == hi[i] || a[0].abs() + a[1].abs() < 1e-12 {
            return None;
        }
        unbounded |= !hi[i].is_finite();
    }
    let c = [-ns.g[0], -ns.g[1]];
    let mut working: [Constraint; 2] = [Constraint(0); 2];
    let mut size = 0;
    let mut l = c;
    for _ in 0..4 + 2 * n {
        let Some(q) = most_violated(ns, bounds, l, &working[..size]) else {
            if unbounded && far_out(ns, bounds, l) {
                return None;
            }
            return Some(l);
        };
        let (nq, bq) = q.line(ns, bounds);
        match size {
            0 => {
                // μ > 0: q is violated at c.
                (l, _) = onto_line(c, nq, bq);
                (working[0], size) = (q, 1);
            }
            1 => {
                let (np, bp) = working[0].line(ns, bounds);
                let (v, mp, mq) = vertex(np, bp, nq, bq, c)?;
                if mp >= 0.0 && mq >= 0.0 {
                    l = v;
                    (working[1], size) = (q, 2);
                } else {
                    let (x, mu) = onto_line(c, nq, bq);
                    if mu < 0.0 {
                        return None;
                    }
                    (l, working[0]) = (x, q);
                }
            }
            _ => {
                // Keep q with one or none of the two: the candidate whose multipliers are ≥ 0
                // and that satisfies what it leaves out.
                let (p0, p1) = (working[0], working[1]);
                let (x, mu) = onto_line(c, nq, bq);
                if mu >= 0.0 && satisfies(ns, bounds, p0, x) && satisfies(ns, bounds, p1, x) {
                    (l, working[0], size) = (x, q, 1);
                    continue;
                }
                let mut next = None;
                for (keep, out) in [(p0, p1), (p1, p0)] {
                    let (np, bp) = keep.line(ns, bounds);
                    if let Some((v, mp, mq)) = vertex(np, bp, nq, bq, c)
                        && mp >= 0.0
                        && mq >= 0.0
                        && satisfies(ns, bounds, out, v)
                    {
                        next = Some((v, keep));
                        break;
                    }
                }
                let (v, keep) = next?;
                (l, working) = (v, [keep, q]);
            }
        }
    }
    None
}

/// Whether λ lies so far out (10⁵ times the data) that the polygon's artificial box of an
/// infinite t_max might hold it (then the polygon reports it).
#[cold]
fn far_out(ns: &NullSpace, bounds: &TensionBounds, l: P2) -> bool {
    let mut scale: f64 = 1.0;
    for i in 0..ns.n {
        scale = scale.max(ns.t0[i].abs()).max(bounds.min()[i].abs());
        if bounds.max()[i].is_finite() {
            scale = scale.max(bounds.max()[i].abs());
        }
    }
    l[0].abs().max(l[1].abs()) >= 1e5 * scale
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};

    /// t1 + t2 + t3 = 3 (one force, three collinear cables): min ‖t‖ is (1, 1, 1) inside the
    /// bounds [0, 3], (1.5, 0.75, 0.75) on the edge t1 = 1.5 when t1 ≥ 1.5, and
    /// (1.5, 1.2, 0.3) at the vertex t1 = 1.5, t2 = 1.2 when also t2 ≥ 1.2.
    #[test]
    fn interior_edge_and_vertex_answers_by_hand() {
        let w = DMatrix::from_row_slice(1, 3, &[1.0, 1.0, 1.0]);
        let we = DVector::from_vec(vec![-3.0]);
        let mut ns = NullSpace::default();
        ns.compute(&w, &we).unwrap();
        for (lo, expected) in [
            ([0.0, 0.0, 0.0], [1.0, 1.0, 1.0]),
            ([1.5, 0.0, 0.0], [1.5, 0.75, 0.75]),
            ([1.5, 1.2, 0.0], [1.5, 1.2, 0.3]),
        ] {
            let bounds = TensionBounds::new(lo.to_vec(), vec![3.0; 3]).unwrap();
            let l = l2_projection(&ns, &bounds).expect("a projection");
            for (i, e) in expected.iter().enumerate() {
                let t = ns.tension2(i, l);
                assert!((t - e).abs() < 1e-14, "{lo:?}: t{i} = {t}, expected {e}");
            }
        }
        // Infeasible (t ≥ 1.5 everywhere): the polygon decides.
        let bounds = TensionBounds::new(vec![1.5; 3], vec![3.0; 3]).unwrap();
        assert_eq!(l2_projection(&ns, &bounds), None);
        // A fixed cable: the polygon decides.
        let bounds = TensionBounds::new(vec![1.0, 0.0, 0.0], vec![1.0, 3.0, 3.0]).unwrap();
        assert_eq!(l2_projection(&ns, &bounds), None);
    }
}
