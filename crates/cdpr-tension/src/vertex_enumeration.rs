//! # Vertex enumeration by pivoting (l2-max at redundancy r ≥ 3)
//!
//! l2-max maximises the convex function ‖t‖₂² over the feasible polytope
//! P = {λ ∈ ℝʳ : t_min ≤ t0 + N λ ≤ t_max} (null-space form, module `null_space`). A convex
//! function attains its maximum over a polytope at a vertex, so the answer is the best vertex.
//! The former method tried every *candidate* basis — r cables at one of their bounds, at most
//! C(n, r)·2ʳ linear systems (59 136 for 12 cables in 6 DOF) — although a random polytope has
//! only a few hundred vertices.
//!
//! This module visits only the feasible bases, by pivoting along the edges of P (Balinski 1961:
//! the vertex graph of a polytope is connected; Avis & Fukuda 1992: so is the graph of its
//! feasible bases under simplex pivots, which lets a search reach every vertex from one):
//!
//! - a **basis** S is a set of r cables with independent rows N_i, each at its lower or upper
//!   bound; its point is λ_S = A_S⁻¹ b_S (A_S the rows N_i, b_i = bound − t0_i). It is *feasible*
//!   when every tension holds its bounds (to the relative tolerance 10⁻¹⁰ of the certificate);
//! - from a feasible basis, leaving cable k ∈ S along the edge d_k = ±A_S⁻¹ e_k (the sign moves
//!   t_k away from its bound) the first bound reached, at step θ* = min_i slack_i / |N_i d_k|
//!   (the ratio test of the simplex method), gives the neighbour S − k + i; every tie (a
//!   degenerate vertex) gives a neighbour, and cable k reaching its own other bound gives the
//!   basis with k's side flipped;
//! - a fixed cable (t_min = t_max) is an equality: it stays in every basis, so the search runs
//!   over the vertices of the face P ∩ {t_i = t_min,i}, which are the vertices of P.
//!
//! A basis reached by a pivot is not refactorised: its tensions and tableau T = N A_S⁻¹ follow
//! from its parent's by the pivot on T_ik of the revised simplex method (an O(n r) update);
//! every [`REFACTOR_EVERY`] pivots along a path, and for the answer, the basis is factorised
//! afresh.
//!
//! The search starts from one vertex, reached from a feasible point (an l1 solution) by moving
//! inside the null space of the bounds already active until r independent bounds are active.
//! Each basis is keyed by two bit masks (cables in S, cables at their upper bound) in a hash
//! set, which also records, per basis, the edges known to lead back to a visited basis only:
//! an edge walked from a simple vertex to a single neighbour is not tested again from that
//! neighbour, which nearly halves the ratio tests of a simple polytope
//! ([`VertexSearch::expand`]). The set must be bounded (checked by the caller); the search
//! falls back to the candidate enumeration when it cannot start (dependent fixed cables,
//! n > 64) or visits more than
//! [`MAX_BASES`] bases. The answer is the same vertex value as the candidate enumeration
//! (property test `l2_max_search_agrees_with_candidate_enumeration`, which keeps the former
//! method as its oracle).
//!
//! ## References
//! - M. L. Balinski, *An algorithm for finding all vertices of convex polyhedral sets*,
//!   J. SIAM 9(1), 1961.
//! - D. Avis, K. Fukuda, *A pivoting algorithm for convex hulls and vertex enumeration of
//!   arrangements and polyhedra*, Discrete Comput. Geom. 8, 1992.
//! - G. B. Dantzig, W. Orchard-Hays, *The product form for the inverse in the simplex method*,
//!   Math. Tables Aids Comput. 8, 1954 (the pivot update of the basis inverse).
//! - The thesis chapter on planar tendon-driven manipulators (ch. 6), §6.3.2 (maximal ‖t‖₂).

use crate::certificate::bound_violation;
use crate::null_space::NullSpace;
use crate::{Infeasibility, TensionBounds};

/// Bases visited before the search gives way to the candidate enumeration.
pub const MAX_BASES: usize = 200_000;

/// Relative feasibility tolerance of a vertex (as the candidate enumeration).
const FEASIBLE: f64 = 1e-10;

/// Whether the walk may pass through a vertex: each tension within [`FEASIBLE`] of its bound
/// (relative to the bound), or within the rounding of the vertex itself, 10⁻¹² · max_j |t_j|.
/// A vertex with tensions of 10⁷ N carries errors of 10⁻⁹ N, more than 10⁻¹⁰ of a 10 N bound;
/// rejecting it would cut the walk's graph there and miss the vertices behind it (soak problems
/// 295857 and 857204). The answer is certified by the caller, which falls back to the candidate
/// enumeration when it fails (soak problem 804927).
fn vertex_feasible(bounds: &TensionBounds, t: &[f64]) -> bool {
    let (lo, hi) = (
        &bounds.min().as_slice()[..t.len()],
        &bounds.max().as_slice()[..t.len()],
    );
    // Within [t_min, t_max] the violation is ≤ 0, so only tensions outside need the test (and
    // the vertex's scale, computed once when the first one is met).
    let mut scale = None;
    for (i, &v) in t.iter().enumerate() {
        if lo[i] <= v && v <= hi[i] {
            continue;
        }
        let scale =
            *scale.get_or_insert_with(|| 1e-12 * t.iter().fold(0.0_f64, |m, v| m.max(v.abs())));
        if !(bound_violation(lo[i], hi[i], v) <= FEASIBLE || (lo[i] - v).max(v - hi[i]) <= scale) {
            return false;
        }
    }
    true
}

/// Relative slack within which two bounds count as reached together (a degenerate vertex).
const TIE: f64 = 1e-9;

/// A basis: cables in S (bit i) and cables of S at their upper bound.
type Key = (u64, u64);

/// The visited bases: an open-addressing set of keys with linear probing and a multiplicative
/// hash (a general hash set spent a tenth of the search). The empty slot is the key (0, 0),
/// which is no basis (S has r ≥ 1 cables). Each key carries the cables of S whose edge is known
/// to lead back to a visited basis only (see [`VertexSearch::expand`]). Cleared through the
/// list of its filled slots, so a search pays for the slots it used, not for the table; it
/// allocates only to grow.
#[derive(Debug, Default, Clone)]
struct VisitedBases {
    slots: Vec<(Key, u64)>,
    filled: Vec<usize>,
}

impl VisitedBases {
    fn clear(&mut self) {
        for &i in &self.filled {
            self.slots[i] = ((0, 0), 0);
        }
        self.filled.clear();
    }

    /// The slot where `key`'s probe sequence starts (`mask` = table size − 1).
    fn home(key: Key, mask: usize) -> usize {
        let h = (key.0 ^ key.1.rotate_left(29)).wrapping_mul(0x9e37_79b9_7f4a_7c15);
        (h >> 32) as usize & mask
    }

    /// The slot of `key`, or of the empty slot where it would go.
    #[inline]
    fn probe(&self, key: Key) -> usize {
        let mask = self.slots.len() - 1;
        let mut i = Self::home(key, mask);
        while self.slots[i].0 != key && self.slots[i].0 != (0, 0) {
            i = (i + 1) & mask;
        }
        i
    }

    /// Inserts `key`: its slot, and whether it was new.
    #[inline]
    fn insert(&mut self, key: Key) -> (usize, bool) {
        if 2 * (self.filled.len() + 1) > self.slots.len() {
            self.grow();
        }
        let i = self.probe(key);
        if self.slots[i].0 == key {
            return (i, false);
        }
        self.slots[i] = (key, 0);
        self.filled.push(i);
        (i, true)
    }

    /// The cables of the visited basis `key` whose edges need no ratio test.
    #[inline]
    fn done(&self, key: Key) -> u64 {
        if self.slots.is_empty() {
            return 0;
        }
        self.slots[self.probe(key)].1
    }

    /// Doubles the table (at least 256 slots) and re-inserts the keys with their marks.
    fn grow(&mut self) {
        let entries: Vec<(Key, u64)> = self.filled.iter().map(|&i| self.slots[i]).collect();
        let size = (2 * self.slots.len()).max(256);
        self.slots.clear();
        self.slots.resize(size, ((0, 0), 0));
        self.filled.clear();
        for (key, done) in entries {
            let (i, _) = self.insert(key);
            self.slots[i].1 = done;
        }
    }
}

/// Reusable buffers of the search (no allocation once sized, apart from the hash set's growth).
#[derive(Debug, Default, Clone)]
pub(crate) struct VertexSearch {
    visited: VisitedBases,
    /// r × r LU factors of A_S, row-major, and the row permutation.
    lu: Vec<f64>,
    piv: Vec<usize>,
    /// Cables of S in order, their bounds' right-hand sides, λ, t, A_S⁻¹ column scratch.
    cables: Vec<usize>,
    rhs: Vec<f64>,
    lambda: Vec<f64>,
    t: Vec<f64>,
    dir: Vec<f64>,
    best: Vec<f64>,
    /// A_S⁻¹ (r × r, column-major), the tableau N A_S⁻¹ (n × r, column-major), and ‖N_i‖ per
    /// cable.
    inv: Vec<f64>,
    tab: Vec<f64>,
    norms: Vec<f64>,
    /// Per cable: the rate below which an edge does not move it (10⁻¹² ‖N_i‖, times ‖d‖),
    /// the tie slack TIE·max(|bound|, 1) at each bound, and the ratio test's candidates.
    negligible: Vec<f64>,
    tie_lo: Vec<f64>,
    tie_hi: Vec<f64>,
    found: Vec<(usize, f64)>,
    /// Orthonormalised rows and a row being orthogonalised (start-up only).
    q: Vec<f64>,
    row: Vec<f64>,
    /// The search stack: bases to visit, and the (t, T, cables) blocks of those reached by a
    /// pivot (in stack order, so a popped node's block is the last one).
    nodes: Vec<Node>,
    pool: Vec<f64>,
    pool_cables: Vec<usize>,
    /// Bases evaluated by the last search (for tests and benches).
    pub evaluated: usize,
    /// Ratio tests run by the last search.
    pub ratio_tests: usize,
    /// Run the ratio test of every edge, the done ones too (tests: the same walk).
    test_every_edge: bool,
}

/// Pivots after which a basis is factorised afresh instead of updated (bounds the rounding
/// that the tableau updates accumulate along a path of the search).
const REFACTOR_EVERY: u32 = 48;

/// A basis on the search stack: `depth` pivots since its path's last factorisation; `pivoted`
/// when its tensions and tableau wait in the pool (else it is factorised when visited).
#[derive(Debug, Clone, Copy)]
struct Node {
    key: Key,
    depth: u32,
    pivoted: bool,
}

/// Why the search gave way (the caller falls back to the candidate enumeration).
#[derive(Debug)]
pub(crate) struct GaveUp;

impl VertexSearch {
    /// The largest ‖t‖² over the vertices of the bounded, non-empty set
    /// {t0 + N λ : bounds}, starting from the feasible tensions in `t`; writes the best
    /// vertex's tensions to `t` (`t` is untouched when the search gives way). Allocates
    /// nothing once its buffers have grown (the hash set keeps its capacity).
    pub fn l2_max(
        &mut self,
        ns: &NullSpace,
        bounds: &TensionBounds,
        t: &mut [f64],
    ) -> Result<Result<(), Infeasibility>, GaveUp> {
        let (n, r) = (ns.n, ns.r());
        if n > 64 || r == 0 {
            return Err(GaveUp);
        }
        self.lu.resize(r * r, 0.0);
        self.piv.resize(r, 0);
        self.cables.clear();
        self.rhs.resize(r, 0.0);
        self.lambda.resize(r, 0.0);
        self.t.resize(n, 0.0);
        self.dir.resize(r, 0.0);
        self.best.resize(n, 0.0);
        self.norms.clear();
        self.norms.extend((0..n).map(|i| {
            (0..r)
                .map(|j| ns.basis[i + n * j].powi(2))
                .sum::<f64>()
                .sqrt()
        }));
        let (lo, hi) = (bounds.min(), bounds.max());
        self.negligible.clear();
        self.negligible.extend(self.norms.iter().map(|v| 1e-12 * v));
        self.tie_lo.clear();
        self.tie_lo
            .extend(lo.iter().map(|b| TIE * b.abs().max(1.0)));
        self.tie_hi.clear();
        self.tie_hi
            .extend(hi.iter().map(|b| TIE * b.abs().max(1.0)));
        self.found.resize(n, (0, 0.0));
        self.visited.clear();
        self.nodes.clear();
        self.pool.clear();
        self.pool_cables.clear();
        self.evaluated = 0;
        self.ratio_tests = 0;
        let first = self.first_basis(ns, bounds, t)?;
        self.visited.insert(first);
        self.nodes.push(Node {
            key: first,
            depth: 0,
            pivoted: false,
        });
        self.tab.resize(n * r, 0.0);
        let (mut best, mut best_key) = (f64::NEG_INFINITY, None);
        while let Some(node) = self.nodes.pop() {
            self.evaluated += 1;
            if self.evaluated > MAX_BASES {
                return Err(GaveUp);
            }
            if node.pivoted {
                let at = self.pool.len() - n * (r + 1);
                self.t.copy_from_slice(&self.pool[at..at + n]);
                self.tab.copy_from_slice(&self.pool[at + n..]);
                self.pool.truncate(at);
                let at = self.pool_cables.len() - r;
                self.cables.clear();
                self.cables.extend_from_slice(&self.pool_cables[at..]);
                self.pool_cables.truncate(at);
                if !vertex_feasible(bounds, &self.t) {
                    continue;
                }
            } else {
                if !self.evaluate(ns, bounds, node.key) {
                    continue;
                }
                self.tableau(ns, node.key);
            }
            let f: f64 = self.t.iter().map(|v| v * v).sum();
            if f > best {
                best = f;
                best_key = Some(node.key);
            }
            let done = self.visited.done(node.key);
            self.expand(bounds, node, done);
        }
        // The best vertex afresh from its factorisation (not from a chain of updates).
        match best_key {
            Some(key) if self.evaluate(ns, bounds, key) => {
                t.copy_from_slice(&self.t);
                Ok(Ok(()))
            }
            _ => Err(GaveUp),
        }
    }

    /// Factor A_S, solve λ_S and t = t0 + N λ_S; false when A_S is singular or λ_S infeasible.
    fn evaluate(&mut self, ns: &NullSpace, bounds: &TensionBounds, key: Key) -> bool {
        let (n, r) = (ns.n, ns.r());
        self.cables.clear();
        let mut m = key.0;
        while m != 0 {
            self.cables.push(m.trailing_zeros() as usize);
            m &= m - 1;
        }
        for (k, &c) in self.cables.iter().enumerate() {
            for j in 0..r {
                self.lu[k * r + j] = ns.basis[c + n * j];
            }
            let b = if key.1 >> c & 1 == 1 {
                bounds.max()[c]
            } else {
                bounds.min()[c]
            };
            self.rhs[k] = b - ns.t0[c];
        }
        if !lu_factor(&mut self.lu, &mut self.piv, r) {
            return false;
        }
        // X = A_S⁻¹ (column k in inv[k r..]), λ = X b.
        self.inv.resize(r * r, 0.0);
        self.lambda.iter_mut().for_each(|v| *v = 0.0);
        for k in 0..r {
            let col = &mut self.inv[k * r..(k + 1) * r];
            lu_unit_column(&self.lu, &self.piv, r, k, col);
            for (l, x) in self.lambda.iter_mut().zip(col.iter()) {
                *l += x * self.rhs[k];
            }
        }
        tensions(ns, &self.lambda, &mut self.t);
        vertex_feasible(bounds, &self.t)
    }

    /// The tableau T = N A_S⁻¹ (n × r, column k in tab[k n..]: the rate of every tension along
    /// edge k) from X = A_S⁻¹ of [`Self::evaluate`]; the rows of the cables in S are e_k.
    fn tableau(&mut self, ns: &NullSpace, key: Key) {
        let (n, r) = (ns.n, ns.r());
        for k in 0..r {
            let x = &self.inv[k * r..(k + 1) * r];
            let out = &mut self.tab[k * n..(k + 1) * n];
            for (i, o) in out.iter_mut().enumerate() {
                *o = if key.0 >> i & 1 == 1 {
                    0.0
                } else {
                    x.iter()
                        .enumerate()
                        .map(|(j, xj)| ns.basis[i + n * j] * xj)
                        .sum()
                };
            }
            out[self.cables[k]] = 1.0;
        }
    }

    /// Pushes the unvisited neighbours of the visited basis `node` (tensions in `t`, tableau
    /// in `tab`, cables in `cables`): one ratio test per edge, except the edges of the cables
    /// in `done`. A neighbour S − c + i gets its tensions and tableau by the pivot of the
    /// revised simplex method on T_ik (an O(n r) update), or, every [`REFACTOR_EVERY`] pivots,
    /// a fresh factorisation when visited.
    ///
    /// Each edge of the polytope would be tested from both ends. When the vertex v of S is
    /// simple (no cable outside S within 10·TIE of a bound) and the edge leaving c reaches a
    /// single neighbour S' = S − c + i, the edge of S' leaving i is the same segment walked
    /// back, and its ratio test can only stop at v with S (a tie there needs a cable outside S
    /// at a bound at v): it is marked done in S', which then skips it. The walk visits the same
    /// bases in the same order, with about half the ratio tests.
    fn expand(&mut self, bounds: &TensionBounds, node: Node, done: u64) {
        let (n, r) = (self.t.len(), self.cables.len());
        let (lo, hi) = (bounds.min().as_slice(), bounds.max().as_slice());
        let (lo, hi) = (&lo[..n], &hi[..n]);
        let (negligible, tie_lo, tie_hi) =
            (&self.negligible[..n], &self.tie_lo[..n], &self.tie_hi[..n]);
        let key = node.key;
        let simple = {
            let t = &self.t[..n];
            (0..n).all(|j| {
                key.0 >> j & 1 == 1
                    || (t[j] - lo[j] > 10.0 * tie_lo[j] && hi[j] - t[j] > 10.0 * tie_hi[j])
            })
        };
        for k in 0..r {
            let c = self.cables[k];
            if lo[c] == hi[c] || (done >> c & 1 == 1 && !self.test_every_edge) {
                continue; // an equality never leaves the basis; a done edge leads back only
            }
            self.ratio_tests += 1;
            // Edge d = σ A_S⁻¹ e_k: N_c d = σ, N_j d = 0 for the other cables of S; N is
            // orthonormal, so ‖d‖ = ‖T e_k‖.
            let sigma = if key.1 >> c & 1 == 1 { -1.0 } else { 1.0 };
            let rates = &self.tab[k * n..(k + 1) * n];
            let t = &self.t[..n];
            let dnorm = rates.iter().map(|v| v * v).sum::<f64>().sqrt();
            // Ratio test: the smallest step θ* to a bound, then every bound reached within TIE
            // ((θ_i − θ*)|rate_i| ≤ TIE·scale_i). One pass keeps the candidates that can still
            // tie with the running minimum (≥ θ*, so no tie is lost), in cable order, over the
            // cables outside S − c.
            let others = key.0 & !(1u64 << c);
            let mut theta = f64::INFINITY;
            let mut found = 0;
            for i in 0..n {
                if others >> i & 1 == 1 {
                    continue;
                }
                let rate = sigma * rates[i];
                let a = rate.abs();
                if a <= negligible[i] * dnorm {
                    continue;
                }
                let up = rate > 0.0;
                let bound = if up { hi[i] } else { lo[i] };
                let tol = if up { tie_hi[i] } else { tie_lo[i] };
                let s = ((bound - t[i]) / rate).max(0.0);
                if (s - theta) * a <= tol {
                    self.found[found] = (i, s);
                    found += 1;
                    theta = theta.min(s);
                }
            }
            if !theta.is_finite() {
                continue; // numerically unbounded edge of a bounded set: nothing to reach
            }
            // The bounds reached within TIE of θ*, kept in cable order at the front of `found`.
            let mut reached = 0;
            for f in 0..found {
                let (i, step_i) = self.found[f];
                let rate = sigma * rates[i];
                let tol = if rate > 0.0 { tie_hi[i] } else { tie_lo[i] };
                if !step_i.is_finite() || (step_i - theta) * rate.abs() > tol {
                    continue;
                }
                self.found[reached] = (i, step_i);
                reached += 1;
            }
            let single = simple && reached == 1;
            for f in 0..reached {
                let (i, step_i) = self.found[f];
                let rate = sigma * rates[i];
                let upper = rate > 0.0;
                let bound = if upper { hi[i] } else { lo[i] };
                let cables = others | 1u64 << i;
                let mut uppers = key.1 & !(1u64 << c);
                if upper {
                    uppers |= 1u64 << i;
                }
                let next = (cables, uppers);
                let (slot, new) = self.visited.insert(next);
                if single {
                    self.visited.slots[slot].1 |= 1u64 << i;
                }
                if !new {
                    continue;
                }
                let depth = node.depth + 1;
                if depth >= REFACTOR_EVERY {
                    self.nodes.push(Node {
                        key: next,
                        depth: 0,
                        pivoted: false,
                    });
                    continue;
                }
                // The vertex of S − c + i: step θ_i along the edge, t_i exactly on its bound.
                let at = self.pool.len();
                self.pool.resize(at + n * (r + 1), 0.0);
                let (next_t, next_tab) = self.pool[at..].split_at_mut(n);
                let step = sigma * step_i;
                for ((o, ti), d) in next_t.iter_mut().zip(t).zip(rates) {
                    *o = ti + step * d;
                }
                next_t[i] = bound;
                // Pivot on T_ik: column k ← T e_k / T_ik, column j ← T e_j − T_ij column k,
                // and row i ← e_k exactly.
                let pivot = rates[i];
                for j in 0..r {
                    let col = &self.tab[j * n..(j + 1) * n];
                    let out = &mut next_tab[j * n..(j + 1) * n];
                    if j == k {
                        for (o, d) in out.iter_mut().zip(col) {
                            *o = d / pivot;
                        }
                        out[i] = 1.0;
                    } else {
                        let f = col[i] / pivot;
                        for ((o, a), d) in out.iter_mut().zip(col).zip(rates) {
                            *o = a - f * d;
                        }
                        out[i] = 0.0;
                    }
                }
                self.pool_cables.extend_from_slice(&self.cables);
                let last = self.pool_cables.len() - r;
                self.pool_cables[last + k] = i;
                self.nodes.push(Node {
                    key: next,
                    depth,
                    pivoted: true,
                });
            }
        }
    }

    /// Step along `dir` at which cable i reaches a bound: (θ ≥ 0, upper bound?).
    fn step(&self, ns: &NullSpace, bounds: &TensionBounds, i: usize) -> Option<(f64, bool)> {
        let (n, r) = (ns.n, ns.r());
        let rate: f64 = (0..r).map(|j| ns.basis[i + n * j] * self.dir[j]).sum();
        if rate.abs() <= 1e-12 * self.norms[i] {
            return None;
        }
        let ti = self.t[i];
        if rate > 0.0 {
            let h = bounds.max()[i];
            h.is_finite().then(|| (((h - ti) / rate).max(0.0), true))
        } else {
            Some((((bounds.min()[i] - ti) / rate).max(0.0), false))
        }
    }

    /// One feasible basis near `start`: the fixed cables, then the bounds active at the
    /// point, then moves within the null space of the active rows until r rows are active.
    fn first_basis(
        &mut self,
        ns: &NullSpace,
        bounds: &TensionBounds,
        start: &[f64],
    ) -> Result<Key, GaveUp> {
        let (n, r) = (ns.n, ns.r());
        let (lo, hi) = (bounds.min(), bounds.max());
        // λ = Nᵀ (t − t0) (N orthonormal).
        for j in 0..r {
            self.lambda[j] = (0..n)
                .map(|i| ns.basis[i + n * j] * (start[i] - ns.t0[i]))
                .sum();
        }
        tensions(ns, &self.lambda, &mut self.t);
        self.q.clear();
        let (mut cables, mut uppers) = (0u64, 0u64);
        let mut rank = 0;
        // Fixed cables first (all must enter), then active bounds (greedy).
        for pass in 0..2 {
            for i in 0..n {
                if rank == r {
                    break;
                }
                let fixed = lo[i] == hi[i];
                let (active, upper) = if pass == 0 {
                    (fixed, false)
                } else if fixed {
                    (false, false)
                } else {
                    let tol = TIE * 10.0;
                    if (self.t[i] - lo[i]) <= tol * lo[i].abs().max(1.0) {
                        (true, false)
                    } else if hi[i].is_finite() && hi[i] - self.t[i] <= tol * hi[i].abs().max(1.0) {
                        (true, true)
                    } else {
                        (false, false)
                    }
                };
                if !active {
                    continue;
                }
                if self.orthogonalise(ns, i) {
                    rank += 1;
                    cables |= 1 << i;
                    if upper {
                        uppers |= 1 << i;
                    }
                } else if pass == 0 {
                    return Err(GaveUp); // dependent or zero equality rows
                }
            }
        }
        // Move inside the null space of the active rows until a new bound is reached.
        while rank < r {
            // d = the component of the objective's gradient λ + g (or of a unit vector)
            // orthogonal to the active rows.
            let mut found = false;
            for attempt in 0..=r {
                for j in 0..r {
                    self.dir[j] = if attempt == 0 {
                        self.lambda[j] + ns.g.get(j).copied().unwrap_or(0.0)
                    } else if j == attempt - 1 {
                        1.0
                    } else {
                        0.0
                    };
                }
                let before = self.dir.iter().map(|v| v * v).sum::<f64>().sqrt();
                for q in self.q.chunks(r) {
                    let p: f64 = q.iter().zip(&self.dir).map(|(a, b)| a * b).sum();
                    self.dir.iter_mut().zip(q).for_each(|(d, a)| *d -= p * a);
                }
                let after = self.dir.iter().map(|v| v * v).sum::<f64>().sqrt();
                if after > 1e-6 * before && after > 0.0 {
                    self.dir.iter_mut().for_each(|v| *v /= after);
                    found = true;
                    break;
                }
            }
            if !found {
                return Err(GaveUp);
            }
            let mut reached = None;
            for sign in [1.0, -1.0] {
                if sign < 0.0 {
                    self.dir.iter_mut().for_each(|v| *v = -*v);
                }
                let mut best: Option<(f64, usize, bool)> = None;
                for i in 0..n {
                    if cables >> i & 1 == 1 {
                        continue;
                    }
                    if let Some((s, upper)) = self.step(ns, bounds, i)
                        && best.is_none_or(|b| s < b.0)
                    {
                        best = Some((s, i, upper));
                    }
                }
                if best.is_some() {
                    reached = best;
                    break;
                }
            }
            let Some((s, i, upper)) = reached else {
                return Err(GaveUp);
            };
            for j in 0..r {
                self.lambda[j] += s * self.dir[j];
            }
            tensions(ns, &self.lambda, &mut self.t);
            if !self.orthogonalise(ns, i) {
                return Err(GaveUp);
            }
            rank += 1;
            cables |= 1 << i;
            if upper {
                uppers |= 1 << i;
            }
        }
        Ok((cables, uppers))
    }

    /// Adds row N_i to the orthonormal rows `q` if it is independent of them.
    fn orthogonalise(&mut self, ns: &NullSpace, i: usize) -> bool {
        let (n, r) = (ns.n, ns.r());
        let mut v = std::mem::take(&mut self.row);
        v.clear();
        v.extend((0..r).map(|j| ns.basis[i + n * j]));
        let norm0 = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        for _ in 0..2 {
            for q in self.q.chunks(r) {
                let p: f64 = q.iter().zip(&v).map(|(a, b)| a * b).sum();
                v.iter_mut().zip(q).for_each(|(x, a)| *x -= p * a);
            }
        }
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let independent = norm0 != 0.0 && norm > 1e-9 * norm0;
        if independent {
            self.q.extend(v.iter().map(|x| x / norm));
        }
        self.row = v;
        independent
    }
}

/// t = t0 + N λ.
fn tensions(ns: &NullSpace, lambda: &[f64], t: &mut [f64]) {
    let n = ns.n;
    t.copy_from_slice(&ns.t0);
    for (j, l) in lambda.iter().enumerate() {
        for (ti, a) in t.iter_mut().zip(&ns.basis[n * j..n * (j + 1)]) {
            *ti += a * l;
        }
    }
}

/// In-place LU with partial pivoting of the r × r row-major `a`; false when singular
/// (a pivot below 10⁻¹² of the largest entry).
fn lu_factor(a: &mut [f64], piv: &mut [usize], r: usize) -> bool {
    let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if scale == 0.0 || !scale.is_finite() {
        return false;
    }
    for (k, p) in piv.iter_mut().enumerate() {
        *p = k;
    }
    for k in 0..r {
        let (mut p, mut pv) = (k, a[k * r + k].abs());
        for i in k + 1..r {
            if a[i * r + k].abs() > pv {
                (p, pv) = (i, a[i * r + k].abs());
            }
        }
        if pv <= 1e-12 * scale {
            return false;
        }
        if p != k {
            for j in 0..r {
                a.swap(k * r + j, p * r + j);
            }
            piv.swap(k, p);
        }
        let d = a[k * r + k];
        for i in k + 1..r {
            let f = a[i * r + k] / d;
            a[i * r + k] = f;
            for j in k + 1..r {
                a[i * r + j] -= f * a[k * r + j];
            }
        }
    }
    true
}

/// Solves A x = e_k (a column of A⁻¹) with the factors of [`lu_factor`] (P A = L U).
fn lu_unit_column(lu: &[f64], piv: &[usize], r: usize, k: usize, x: &mut [f64]) {
    for (i, xi) in x.iter_mut().enumerate() {
        *xi = if piv[i] == k { 1.0 } else { 0.0 };
    }
    for i in 0..r {
        let row = &lu[i * r..i * r + i];
        let s: f64 = row.iter().zip(&x[..i]).map(|(a, b)| a * b).sum();
        x[i] -= s;
    }
    for i in (0..r).rev() {
        let row = &lu[i * r + i + 1..(i + 1) * r];
        let s: f64 = row.iter().zip(&x[i + 1..r]).map(|(a, b)| a * b).sum();
        x[i] = (x[i] - s) / lu[i * r + i];
    }
}

#[cfg(test)]
mod tests {
    use crate::quadratic_program::l2_max_by_vertices;
    use crate::{Infeasibility, Method, TensionBounds, TensionOutcome, TensionProblem};
    use crate::{TensionSolver, null_space::NullSpace};
    use nalgebra::{DMatrix, DVector};
    use proptest::prelude::*;

    /// SplitMix64 in [0, 1).
    struct Rng(u64);
    impl Rng {
        fn unit(&mut self) -> f64 {
            self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
        }
        fn range(&mut self, a: f64, b: f64) -> f64 {
            a + (b - a) * self.unit()
        }
        fn below(&mut self, n: usize) -> usize {
            ((self.unit() * n as f64) as usize).min(n - 1)
        }
    }

    /// A random problem at redundancy ≥ 3 with the bound kinds of the soak: wide, tight, fixed
    /// cables, infinite t_max; the wrench balanced by tensions in the bounds, or pushed away.
    fn problem(seed: u64) -> (DMatrix<f64>, DVector<f64>, TensionBounds) {
        let mut g = Rng(seed);
        let (m, n) = if g.unit() < 0.5 {
            (6, 9 + g.below(4))
        } else {
            (3, 6 + g.below(3))
        };
        let w = DMatrix::from_fn(m, n, |_, _| g.range(-1.0, 1.0));
        let kind = g.below(4);
        let (mut lo, mut hi) = (Vec::new(), Vec::new());
        for _ in 0..n {
            let l = g.range(0.5, 20.0);
            lo.push(l);
            hi.push(match kind {
                0 => l + g.range(100.0, 2000.0),
                1 => l * (1.0 + g.range(0.01, 0.3)) + g.range(0.0, 1.0),
                _ => l + g.range(10.0, 1000.0),
            });
        }
        if kind == 2 {
            for _ in 0..1 + g.below(2) {
                let i = g.below(n);
                hi[i] = lo[i];
            }
        }
        if kind == 3 {
            for _ in 0..1 + g.below(n) {
                let i = g.below(n);
                hi[i] = f64::INFINITY;
            }
        }
        let t = DVector::from_fn(n, |i, _| {
            if hi[i].is_finite() {
                g.range(lo[i], hi[i])
            } else {
                lo[i] + g.range(0.0, 2000.0)
            }
        });
        let mut we = -(&w * &t);
        if g.unit() < 0.3 {
            let mag = we.amax().max(10.0) * g.range(0.01, 1.0);
            we.iter_mut().for_each(|v| *v += mag * g.range(-1.0, 1.0));
        }
        (w, we, TensionBounds::new(lo, hi).unwrap())
    }

    /// The former method on the same problem: every candidate basis.
    fn oracle(w: &DMatrix<f64>, we: &DVector<f64>, b: &TensionBounds) -> Option<f64> {
        let mut ns = NullSpace::default();
        ns.compute(w, we).ok()?;
        let mut t = vec![0.0; w.ncols()];
        l2_max_by_vertices(&ns, b, &mut t)
            .ok()
            .map(|_| t.iter().map(|v| v * v).sum())
    }

    // 400 cases in `cargo test`; `L2_MAX_CASES=3000` for a longer run by hand.
    proptest! {
        #![proptest_config(ProptestConfig::with_cases(
            std::env::var("L2_MAX_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(400)
        ))]

        /// The pivoting search finds the same largest ‖t‖² as the candidate enumeration, and
        /// says "infeasible" exactly when no candidate vertex is feasible.
        #[test]
        fn l2_max_search_agrees_with_candidate_enumeration(seed in any::<u64>()) {
            let (w, we, b) = problem(seed);
            let p = TensionProblem::new(&w, &we, &b);
            let out = TensionSolver::new(Method::L2Max).solve(&p).unwrap();
            let expected = oracle(&w, &we, &b);
            match (out, expected) {
                (TensionOutcome::Feasible(s), Some(f)) => {
                    let got = s.tensions.norm_squared();
                    prop_assert!((got - f).abs() <= 1e-7 * f, "‖t‖² {got} vs enumeration {f}");
                    // The pivoting search itself answered (not its fallback), from the l1
                    // solution as in the solver.
                    let start = TensionSolver::new(Method::L1).solve(&p).unwrap();
                    let mut ns = NullSpace::default();
                    ns.compute(&w, &we).unwrap();
                    let mut t = start.tensions().unwrap().as_slice().to_vec();
                    let mut search = super::VertexSearch::default();
                    let answer = search.l2_max(&ns, &b, &mut t);
                    prop_assert!(matches!(answer, Ok(Ok(()))), "the search gave way");
                    let direct: f64 = t.iter().map(|v| v * v).sum();
                    prop_assert!((direct - f).abs() <= 1e-7 * f, "search {direct} vs {f}");
                }
                (TensionOutcome::Infeasible(Infeasibility::Unbounded { .. }), _) => {}
                (TensionOutcome::Infeasible(_), None) => {}
                (out, expected) => prop_assert!(false, "{out:?} vs enumeration {expected:?}"),
            }
        }
    }

    /// Skipping the done edges changes nothing but the work: the same bases are evaluated and
    /// the same tensions returned, bit for bit, as with a ratio test on every edge; on the
    /// random problems and on integer ones, whose vertices are often degenerate.
    #[test]
    fn done_edges_lead_only_to_visited_bases() {
        let mut skipped_some = false;
        for seed in 0..400u64 {
            let (w, we, b) = if seed % 2 == 0 {
                problem(seed)
            } else {
                let mut g = Rng(seed);
                let (m, n) = (3 + 3 * g.below(2), 9 + g.below(4));
                let w = DMatrix::from_fn(m, n, |_, _| g.below(3) as f64 - 1.0);
                let t = DVector::from_fn(n, |_, _| 1.0 + g.below(4) as f64);
                let hi: Vec<f64> = (0..n).map(|_| 4.0 + g.below(2) as f64).collect();
                (
                    w.clone(),
                    -(&w * &t),
                    TensionBounds::new(vec![1.0; n], hi).unwrap(),
                )
            };
            if b.max().iter().any(|v| !v.is_finite()) {
                continue;
            }
            let p = TensionProblem::new(&w, &we, &b);
            let Ok(TensionOutcome::Feasible(start)) = TensionSolver::new(Method::L1).solve(&p)
            else {
                continue;
            };
            let mut ns = NullSpace::default();
            if ns.compute(&w, &we).is_err() || ns.r() < 3 {
                continue;
            }
            let mut walks = Vec::new();
            for every in [false, true] {
                let mut search = super::VertexSearch {
                    test_every_edge: every,
                    ..Default::default()
                };
                let mut t = start.tensions.as_slice().to_vec();
                let answer = search.l2_max(&ns, &b, &mut t).is_ok();
                let bits: Vec<u64> = t.iter().map(|v| v.to_bits()).collect();
                walks.push((answer, search.evaluated, bits, search.ratio_tests));
            }
            let (a, e) = (&walks[0], &walks[1]);
            assert_eq!((a.0, a.1, &a.2), (e.0, e.1, &e.2), "seed {seed}");
            skipped_some |= a.3 < e.3;
        }
        assert!(skipped_some, "no edge was ever skipped");
    }

    /// The visited-basis set answers as a general hash set through growth and clearing, on
    /// keys shaped like bases (r bits of n set, the upper-bound bits a subset).
    #[test]
    fn visited_bases_agree_with_a_hash_set() {
        let mut g = Rng(7);
        let mut set = super::VisitedBases::default();
        for round in 0..4 {
            set.clear();
            let mut oracle = std::collections::HashSet::new();
            // Few distinct keys, so that most inserts are repeats; up to 3000 of them (growth).
            let n = 6 + g.below(7);
            for _ in 0..500 + 1000 * round {
                let mut cables = 0u64;
                while cables.count_ones() < 3 {
                    cables |= 1 << g.below(n);
                }
                let uppers = cables & (g.unit() * (1u64 << n) as f64) as u64;
                let key = (cables, uppers);
                assert_eq!(set.insert(key).1, oracle.insert(key), "key {key:?}");
            }
            assert_eq!(set.filled.len(), oracle.len());
        }
    }

    /// 12 cables in 6 DOF: the search evaluates far fewer bases than the C(12, 6)·2⁶ = 59 136
    /// candidates of the enumeration, and finds the same vertex.
    #[test]
    fn search_visits_few_bases_at_twelve_cables() {
        let (mut visited, mut tests) = (Vec::new(), [0; 2]);
        for seed in 0..20u64 {
            let mut g = Rng(seed);
            let w = DMatrix::from_fn(6, 12, |_, _| g.range(-1.0, 1.0));
            let t = DVector::from_fn(12, |_, _| g.range(10.0, 900.0));
            let we = -(&w * &t);
            let b = TensionBounds::uniform(12, 1.0, 1000.0).unwrap();
            let mut ns = NullSpace::default();
            ns.compute(&w, &we).unwrap();
            let mut search = super::VertexSearch::default();
            let mut got = t.as_slice().to_vec();
            search.l2_max(&ns, &b, &mut got).unwrap().unwrap();
            let f: f64 = got.iter().map(|v| v * v).sum();
            let expected = oracle(&w, &we, &b).unwrap();
            assert!((f - expected).abs() <= 1e-9 * expected, "{f} vs {expected}");
            visited.push(search.evaluated);
            tests[0] += search.ratio_tests;
            search.test_every_edge = true;
            search
                .l2_max(&ns, &b, &mut t.as_slice().to_vec())
                .unwrap()
                .unwrap();
            tests[1] += search.ratio_tests;
        }
        let worst = *visited.iter().max().unwrap();
        assert!(worst < 59_136 / 4, "bases evaluated: {visited:?}");
        // The done edges spare nearly half of the ratio tests (each edge is tested once).
        println!(
            "ratio tests: {} skipping done edges, {} testing every edge",
            tests[0], tests[1]
        );
        assert!(tests[0] * 10 < tests[1] * 6, "ratio tests {tests:?}");
    }
}
