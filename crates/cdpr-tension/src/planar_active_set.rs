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
//! l1 (min Σ t_i) and l1-max (max Σ t_i) are linear in λ: Σ t = Σ t0 + (Nᵀ1)·λ. They start at
//! the l2 optimum, a feasible point with its active constraints, and take simplex steps along
//! the polygon's edges (Dantzig 1963; in the plane every basis is a vertex, two lines) until the
//! multipliers prove optimality; an infinite t_max hands them to the polygon (unboundedness is
//! its verdict). Issue 17 (IPAnema 1, 20 000 poses): l2 7 800 and l1 8 200 instructions per
//! call against 17 700 and 17 400 through the polygon, the same tensions bit for bit.
//!
//! The barycentre needs the whole polygon: its vertices come from walking the edges
//! counter-clockwise from the l1 vertex (Lamaury & Gouttefarde 2013): along the line of the
//! constraint that leaves the current vertex to the first constraint met, until the edge that
//! ends at the first vertex. A polygon without area goes to the clipping (its vertex mean
//! depends on how often a vertex repeats). Barycentre 10 600 instructions per call against
//! 17 600.
//!
//! ## References
//! - Nocedal & Wright (2006), *Numerical Optimization*, 2nd ed., §16.5 (active-set methods for
//!   convex quadratic programs).
//! - Dantzig (1963), *Linear Programming and Extensions*, Princeton University Press.
//! - Lamaury & Gouttefarde (2013), *A tension distribution method with improved computational
//!   efficiency*, Cable-Driven Parallel Robots, pp. 71–85.
//! - Picard, Caro, Plestan & Claveau 2020, eqs. (5)–(6).

use crate::TensionBounds;
use crate::feasible_polygon::{P2, has_area};
use crate::infeasibility::HalfPlane;
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
        if self.0.is_multiple_of(2) {
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
    let n = ns.n;
    let (lo, hi) = (&bounds.min().as_slice()[..n], &bounds.max().as_slice()[..n]);
    let (n1, n2, t0) = (&ns.basis[..n], &ns.basis[n..2 * n], &ns.t0[..n]);
    // Best violation v and squared row norm q, compared as v²/q.
    let (mut best, mut bv, mut bq) = (None, 0.0f64, 1.0f64);
    for i in 0..n {
        // `ns.row2(i)` at r = 2.
        let a = [n1[i], n2[i]];
        let t = t0[i] + a[0] * l[0] + a[1] * l[1];
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
    if j.0.is_multiple_of(2) {
        let lo = bounds.min()[i];
        lo - t <= VIOLATION * lo.abs().max(1.0)
    } else {
        let hi = bounds.max()[i];
        t - hi <= VIOLATION * hi.abs().max(1.0)
    }
}

/// Margin, relative to each cable's range t_max,i − t_min,i, by which [`central_point`] must be
/// inside every bound (plus 10⁻⁹ of the bound's size, ten times the clipping tolerance).
const CENTRAL_MARGIN: f64 = 1e-6;

/// The margin of [`central_point`] for cable bounds [lo, hi]:
/// 10⁻⁶ (hi − lo) + 10⁻⁹ max(|lo|, |hi|) (∞ for an infinite hi). Shared with the four-lane
/// build (`central_point::four_6x8`), which must decide as this one does.
#[inline(always)]
pub(crate) fn central_margin(lo: f64, hi: f64) -> f64 {
    CENTRAL_MARGIN * (hi - lo) + 1e-9 * lo.abs().max(hi.abs())
}

/// A point of the feasible polygon well inside every bound, or `None`: λ = Nᵀ(t_mid − t0)
/// = Nᵀ t_mid − g with t_mid = (t_min + t_max)/2, the tension closest to the middle of the
/// bounds on the affine set t = t0 + N λ (N orthonormal). It serves only the verdict of
/// `TensionSolver::is_feasible`: a feasibility verdict does not depend on which feasible point
/// proves it. Each t_i must be at least
/// 10⁻⁶ (t_max,i − t_min,i) + 10⁻⁹ max(|t_min,i|, |t_max,i|) inside its bounds, far more than
/// the polygon's clipping tolerance and the rounding of t_i, so the polygon (and every method's
/// solve) finds a non-empty set there too; an infinite t_max gives `None`.
pub(crate) fn central_point(ns: &NullSpace, bounds: &TensionBounds) -> Option<P2> {
    debug_assert_eq!(ns.r(), 2);
    let n = ns.n;
    let (lo, hi) = (&bounds.min().as_slice()[..n], &bounds.max().as_slice()[..n]);
    let (n1, n2, t0) = (&ns.basis[..n], &ns.basis[n..2 * n], &ns.t0[..n]);
    let mut l = [-ns.g[0], -ns.g[1]];
    for i in 0..n {
        let mid = 0.5 * (lo[i] + hi[i]);
        l[0] += n1[i] * mid;
        l[1] += n2[i] * mid;
    }
    for i in 0..n {
        let margin = central_margin(lo[i], hi[i]);
        // As `NullSpace::tension2`.
        let t = t0[i] + n1[i] * l[0] + n2[i] * l[1];
        // NaN and an infinite t_max fail here.
        if !(t - lo[i] > margin && hi[i] - t > margin) {
            return None;
        }
    }
    Some(l)
}

/// The l2 optimum λ (the projection of −g onto the feasible polygon) by the active set of the
/// module docs, or `None` when the polygon must decide.
pub(crate) fn l2_projection(ns: &NullSpace, bounds: &TensionBounds) -> Option<P2> {
    l2_active_set(ns, bounds).ok().map(|(l, _)| l)
}

/// [`l2_projection`], or when it fails, the three constraints it ended with if it failed
/// because no pair of them (nor one) could be kept: the candidates of a proof of emptiness
/// ([`crate::infeasibility::multipliers`], [`crate::infeasibility::direction_proves_empty`],
/// through [`Triple::planes`]).
pub(crate) fn l2_search(ns: &NullSpace, bounds: &TensionBounds) -> Result<P2, Option<Triple>> {
    match l2_active_set(ns, bounds) {
        Ok((l, _)) => Ok(l),
        Err(triple) => Err(triple.map(Triple)),
    }
}

/// Three constraints of the polygon (see [`l2_search`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Triple([Constraint; 3]);

impl Triple {
    /// Whether every constraint of the triple is one of a problem with `n` cables.
    pub(crate) fn fits(&self, n: usize) -> bool {
        self.0.iter().all(|j| j.0 / 2 < n)
    }

    /// The half-planes of the three constraints.
    pub(crate) fn planes(&self, ns: &NullSpace, bounds: &TensionBounds) -> [HalfPlane; 3] {
        self.0.map(|j| {
            let (normal, beta) = j.line(ns, bounds);
            HalfPlane {
                cable: j.0 / 2,
                sign: if j.0 % 2 == 0 { 1.0 } else { -1.0 },
                normal,
                beta,
            }
        })
    }
}

/// [`l2_projection`] with its final working set (the constraints active at λ); on failure, the
/// working set and the violated constraint that could not join it (see [`l2_search`]).
fn l2_active_set(
    ns: &NullSpace,
    bounds: &TensionBounds,
) -> Result<(P2, Working), Option<[Constraint; 3]>> {
    let n = ns.n;
    debug_assert_eq!(ns.r(), 2);
    let (lo, hi) = (&bounds.min().as_slice()[..n], &bounds.max().as_slice()[..n]);
    let (n1, n2) = (&ns.basis[..n], &ns.basis[n..2 * n]);
    let mut unbounded = false;
    for i in 0..n {
        let a = [n1[i], n2[i]];
        if lo[i] == hi[i] || a[0].abs() + a[1].abs() < 1e-12 {
            return Err(None);
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
                return Err(None);
            }
            return Ok((l, Working { set: working, size }));
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
                let (v, mp, mq) = vertex(np, bp, nq, bq, c).ok_or(None)?;
                if mp >= 0.0 && mq >= 0.0 {
                    l = v;
                    (working[1], size) = (q, 2);
                } else {
                    let (x, mu) = onto_line(c, nq, bq);
                    if mu < 0.0 {
                        return Err(None);
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
                let (v, keep) = next.ok_or(Some([p0, p1, q]))?;
                (l, working) = (v, [keep, q]);
            }
        }
    }
    Err(None)
}

/// Constraints active at a point of the polygon (the first `size` of `set`).
#[derive(Debug, Clone, Copy)]
struct Working {
    set: [Constraint; 2],
    size: usize,
}

/// The optimum λ of the linear objective min Σ t_i (l1; `maximize`: max Σ t_i, l1-max) on the
/// feasible polygon, by the simplex method in the plane from the l2 optimum (a feasible point
/// with its active constraints), or `None` when the polygon must decide (l2 handed back, an
/// infinite t_max, a cap of 4 + 2n steps).
///
/// Σ t_i = Σ t0_i + d·λ with d = Nᵀ1. At a vertex (constraints p, q active) the multipliers of
/// d = μ_p s_p a_p + μ_q s_q a_q prove optimality when both are ≥ 0; otherwise the constraint
/// with μ < 0 is released and λ moves along the other line, downhill, to the first constraint
/// it meets (ratio test). On one line (or none) λ moves downhill along it (or along −d) the
/// same way. Vertices are computed from their two lines in the polygon's clipping order (the
/// lower constraint first), as the clipping computes them.
pub(crate) fn l1_vertex(ns: &NullSpace, bounds: &TensionBounds, maximize: bool) -> Option<P2> {
    let mut d = [0.0; 2];
    for i in 0..ns.n {
        let a = ns.row2(i);
        d[0] += a[0];
        d[1] += a[1];
    }
    if maximize {
        d = [-d[0], -d[1]];
    }
    simplex(ns, bounds, d).map(|(l, _)| l)
}

/// min d·λ on the polygon by the simplex steps of [`l1_vertex`], with the constraints active
/// at the answer.
fn simplex(ns: &NullSpace, bounds: &TensionBounds, d: P2) -> Option<(P2, Working)> {
    if bounds.max().iter().any(|h| !h.is_finite()) {
        // Unbounded directions and answers beyond the artificial box: the polygon reports them.
        return None;
    }
    let (mut l, mut w) = l2_active_set(ns, bounds).ok()?;
    let n = ns.n;
    for _ in 0..4 + 2 * n {
        let u = match w.size {
            2 => {
                let (p, q) = (w.set[0], w.set[1]);
                let ((np, _), (nq, _)) = (p.line(ns, bounds), q.line(ns, bounds));
                let det = np[0] * nq[1] - np[1] * nq[0];
                let (mp, mq) = multipliers(np, nq, det, d);
                if mp >= 0.0 && mq >= 0.0 {
                    return Some((l, w));
                }
                // Release the constraint with the more negative multiplier; move along the
                // other line, away from the released one.
                let (keep, (nk, nr)) = if mp < mq {
                    (q, (nq, np))
                } else {
                    (p, (np, nq))
                };
                let u = [-nk[1], nk[0]];
                w = Working {
                    set: [keep, keep],
                    size: 1,
                };
                if dot(nr, u) < 0.0 { [-u[0], -u[1]] } else { u }
            }
            1 => {
                let (nq, _) = w.set[0].line(ns, bounds);
                let mu = dot(d, nq) / dot(nq, nq);
                let along = [d[0] - mu * nq[0], d[1] - mu * nq[1]];
                if along[0].abs() + along[1].abs() <= 1e-12 * (d[0].abs() + d[1].abs()) {
                    if mu >= 0.0 {
                        return Some((l, w));
                    }
                    w.size = 0;
                    [-d[0], -d[1]]
                } else {
                    [-along[0], -along[1]]
                }
            }
            _ => [-d[0], -d[1]],
        };
        let (j, step) = first_met(ns, bounds, l, u, &w.set[..w.size])?;
        if w.size == 0 {
            l = [l[0] + step * u[0], l[1] + step * u[1]];
            w = Working {
                set: [j, j],
                size: 1,
            };
            continue;
        }
        let k = w.set[0];
        l = corner(ns, bounds, k, j)?;
        w = Working {
            set: [k, j],
            size: 2,
        };
    }
    None
}

/// The first constraint met from λ along u (ratio test; those in `skip` excluded), with the
/// step length; `None` when nothing blocks.
#[inline(always)]
fn first_met(
    ns: &NullSpace,
    bounds: &TensionBounds,
    l: P2,
    u: P2,
    skip: &[Constraint],
) -> Option<(Constraint, f64)> {
    let (lo, hi) = (bounds.min().as_slice(), bounds.max().as_slice());
    let mut hit: Option<(Constraint, f64)> = None;
    for i in 0..ns.n {
        let a = ns.row2(i);
        let rate = dot(a, u);
        if rate == 0.0 {
            continue;
        }
        let t = ns.t0[i] + a[0] * l[0] + a[1] * l[1];
        // Falling tensions meet t_min, rising ones t_max.
        let (j, step) = if rate < 0.0 {
            (Constraint(2 * i), (t - lo[i]).max(0.0) / -rate)
        } else {
            (Constraint(2 * i + 1), (hi[i] - t).max(0.0) / rate)
        };
        if skip.contains(&j) {
            continue;
        }
        if hit.is_none_or(|(_, s)| step < s) {
            hit = Some((j, step));
        }
    }
    hit
}

/// The vertex where the lines of constraints p and q meet, computed from the lower constraint
/// first (as the clipping computes it); `None` for nearly parallel lines.
#[inline(always)]
fn corner(ns: &NullSpace, bounds: &TensionBounds, p: Constraint, q: Constraint) -> Option<P2> {
    let (first, second) = if p.0 < q.0 { (p, q) } else { (q, p) };
    let ((n1, b1), (n2, b2)) = (first.line(ns, bounds), second.line(ns, bounds));
    let det = n1[0] * n2[1] - n1[1] * n2[0];
    let size = (n1[0].abs() + n1[1].abs()) * (n2[0].abs() + n2[1].abs());
    if det.abs() <= 1e-9 * size || det.is_nan() {
        return None;
    }
    Some([
        (b1 * n2[1] - n1[1] * b2) / det,
        (n1[0] * b2 - b1 * n2[0]) / det,
    ])
}

/// Most vertices [`polygon_walk`] collects.
pub(crate) const WALK_VERTICES: usize = 40;

/// The vertices of the feasible polygon, counter-clockwise, by walking its edges (Lamaury &
/// Gouttefarde 2013) from the l1 vertex: along the line of the constraint that leaves the
/// current vertex, to the first constraint met (ratio test), until the walk is back at its
/// start. Returns the vertex count, or `None` when the clipping must decide (what
/// [`l1_vertex`] hands back, an l1 optimum on an edge, parallel lines, a polygon without
/// area, more than 2n + 2 steps).
pub(crate) fn polygon_walk(
    ns: &NullSpace,
    bounds: &TensionBounds,
    verts: &mut [P2; WALK_VERTICES],
) -> Option<usize> {
    let (mut d, mut size) = ([0.0; 2], 0.0);
    for i in 0..ns.n {
        let a = ns.row2(i);
        d[0] += a[0];
        d[1] += a[1];
        size += a[0].abs() + a[1].abs();
    }
    if d[0].abs() + d[1].abs() <= 1e-12 * size {
        // Σ t is constant on the polygon (1 lies in the row space of W): any direction will do.
        d = [1.0, 0.0];
    }
    // The edge along constraint c runs in direction (n_c,2, −n_c,1): its inside (n_c) on the
    // left, so the walk goes counter-clockwise.
    let edge = |c: Constraint| {
        let (nc, _) = c.line(ns, bounds);
        ([nc[1], -nc[0]], nc)
    };
    let (mut v0, w) = simplex(ns, bounds, d)?;
    let (p, q) = match w.size {
        2 => (w.set[0], w.set[1]),
        1 => {
            // The optimum is a whole edge: go on along it to its end.
            let c = w.set[0];
            let (j, _) = first_met(ns, bounds, v0, edge(c).0, &[c])?;
            v0 = corner(ns, bounds, c, j)?;
            (c, j)
        }
        _ => return None,
    };
    let ((up, np), (uq, nq)) = (edge(p), edge(q));
    let (start, mut along, mut u) = if dot(nq, up) > 0.0 {
        (q, p, up)
    } else if dot(np, uq) > 0.0 {
        (p, q, uq)
    } else {
        return None;
    };
    let mut l = v0;
    verts[0] = v0;
    let mut k = 1;
    for _ in 0..2 * ns.n + 2 {
        let (j, _) = first_met(ns, bounds, l, u, &[along])?;
        if k == WALK_VERTICES {
            return None;
        }
        l = corner(ns, bounds, along, j)?;
        verts[k] = l;
        k += 1;
        if j == start {
            // The edge along `start` ends at the first vertex. A degenerate polygon (segment,
            // point) has its vertex mean as barycentre, which depends on how often the walk
            // repeats a vertex: the clipping decides it.
            return has_area(&verts[..k]).then_some(k);
        }
        along = j;
        u = edge(j).0;
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

    /// t1 + t2 + t3 = s with t ∈ [0, 1]³: the point of the plane nearest the middle
    /// (½, ½, ½) of the bounds is (s/3, s/3, s/3), accepted only 1.001·10⁻⁶ inside the bounds.
    #[test]
    fn central_point_by_hand() {
        let w = DMatrix::from_row_slice(1, 3, &[1.0, 1.0, 1.0]);
        let b = TensionBounds::uniform(3, 0.0, 1.0).unwrap();
        let mut ns = NullSpace::default();
        for (s, inside) in [
            (1.2, true),
            (2.9, true),
            (3.0 - 3e-5, true),
            (3.0e-5, true),
            (3.0 - 3e-6, false),
            (3.0e-6, false),
            (3.0, false),
            (3.0 + 2.4e-9, false),
            (-1.0, false),
        ] {
            ns.compute(&w, &DVector::from_vec(vec![-s])).unwrap();
            let got = central_point(&ns, &b);
            assert_eq!(got.is_some(), inside, "s = {s}");
            if let Some(l) = got {
                for i in 0..3 {
                    assert!((ns.tension2(i, l) - s / 3.0).abs() < 1e-14, "s = {s}");
                }
            }
        }
        // No middle for an infinite t_max.
        let open = TensionBounds::new(vec![0.0; 3], vec![1.0, f64::INFINITY, 1.0]).unwrap();
        ns.compute(&w, &DVector::from_vec(vec![-1.0])).unwrap();
        assert_eq!(central_point(&ns, &open), None);
    }

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

    /// t1 + t2 + 2 t3 = 4, t ∈ [0, 3] with t2 ≥ 0.5: min Σ t puts the cheap cable 3 as high as
    /// it goes, t = (0, 0.5, 1.75) (Σ = 2.25); max Σ t needs t3 = 0 and t1 + t2 = 4 (Σ = 4, an
    /// edge of optima).
    #[test]
    fn l1_and_l1_max_by_hand() {
        let w = DMatrix::from_row_slice(1, 3, &[1.0, 1.0, 2.0]);
        let we = DVector::from_vec(vec![-4.0]);
        let mut ns = NullSpace::default();
        ns.compute(&w, &we).unwrap();
        let bounds = TensionBounds::new(vec![0.0, 0.5, 0.0], vec![3.0; 3]).unwrap();
        let l = l1_vertex(&ns, &bounds, false).expect("an l1 vertex");
        for (i, e) in [0.0, 0.5, 1.75].iter().enumerate() {
            assert!((ns.tension2(i, l) - e).abs() < 1e-14, "t{i}");
        }
        let l = l1_vertex(&ns, &bounds, true).expect("an l1-max vertex");
        let t: Vec<f64> = (0..3).map(|i| ns.tension2(i, l)).collect();
        assert!((t.iter().sum::<f64>() - 4.0).abs() < 1e-14, "{t:?}");
        assert!(t[2].abs() < 1e-14 && t[0] <= 3.0 + 1e-14 && t[1] >= 1.0 - 1e-14);
        // An infinite t_max: the polygon decides.
        let bounds = TensionBounds::new(vec![0.0; 3], vec![3.0, 3.0, f64::INFINITY]).unwrap();
        assert_eq!(l1_vertex(&ns, &bounds, false), None);
    }

    /// t1 + t2 + t3 = 3 with t ∈ [0, 3]: the polygon is the triangle of the three points where
    /// one cable holds everything; its centroid is t = (1, 1, 1) (Σ t is constant here, so the
    /// walk starts from another direction). With two identical cables
    /// (t1 = t2 interchangeable, both in [0, 1]) the polygon is a parallelogram walked in four
    /// vertices, and the centroid has t1 = t2 = 1/2 by symmetry (a walk that closed one
    /// vertex early gave 1/3 and 2/3).
    #[test]
    fn walks_by_hand() {
        let w = DMatrix::from_row_slice(1, 3, &[1.0, 1.0, 1.0]);
        let we = DVector::from_vec(vec![-3.0]);
        let mut ns = NullSpace::default();
        ns.compute(&w, &we).unwrap();
        let bounds = TensionBounds::new(vec![0.0; 3], vec![3.0; 3]).unwrap();
        let mut verts = [[0.0; 2]; WALK_VERTICES];
        // Three bounds meet at each corner: the walk may pass a corner twice (a zero-length
        // edge, no area).
        let k = polygon_walk(&ns, &bounds, &mut verts).expect("a walk");
        assert!((3..=6).contains(&k), "{k}");
        let c = crate::feasible_polygon::centroid(&verts[..k]);
        for i in 0..3 {
            assert!((ns.tension2(i, c) - 1.0).abs() < 1e-14);
        }
        // Cables 1 and 2 identical; cable 3 the other way; cable 4 pulls up.
        let w = DMatrix::from_row_slice(2, 4, &[1.0, 1.0, 0.5, -1.0, 0.0, 0.0, 1.0, 0.2]);
        // Balanced by t = (0.5, 0.5, 1, 1); then t1 + t2 = 1.1 t4 − 0.1 and t3 = 1.2 − 0.2 t4:
        // the square t1, t2 ∈ [0, 1], no other bound active.
        let we = DVector::from_vec(vec![-0.5, -1.2]);
        ns.compute(&w, &we).unwrap();
        let bounds = TensionBounds::new(vec![0.0; 4], vec![1.0, 1.0, 20.0, 20.0]).unwrap();
        let k = polygon_walk(&ns, &bounds, &mut verts).expect("a walk");
        assert_eq!(k, 4);
        let c = crate::feasible_polygon::centroid(&verts[..k]);
        assert!((ns.tension2(0, c) - 0.5).abs() < 1e-13);
        assert!((ns.tension2(1, c) - 0.5).abs() < 1e-13);
    }
}
