//! # Feasible polygon
//!
//! With t = t0 + N λ (Picard, Caro, Plestan & Claveau 2020, eq. (5), see the null-space parametrisation below), the bounds
//! t_min ≤ t0 + N λ ≤ t_max cut the λ-space into a convex set, the *feasible polygon*
//! 𝒜⁻¹(Λ) of Picard, Caro, Plestan & Claveau 2020, eq. (6) for redundancy r = 2, an interval for r = 1 and the single point
//! λ = 0 for r = 0. We build it by clipping a box that surely contains it with the 2n half-planes
//! (Sutherland–Hodgman, one half-plane at a time, buffers of capacity 2n + 4 reused across
//! calls). The box has half-width R = ‖(max(|t_min,i − t0,i|, |t_max,i − t0,i|))_i‖₂, because
//! N is orthonormal so ‖λ‖ = ‖t − t0‖. With an infinite t_max the box is artificial (10⁶ times the
//! data scale); answers that touch it are reported as unbounded.
//!
//! On the exact polygon, linear objectives (l1, l1-max) are optimal at a vertex, l2 is the
//! projection of −Nᵀt0 (≈ 0) onto the polygon, l2-max is the farthest vertex and the barycentre
//! is the area centroid (see the method modules).
//!
//! Null space basis: N = the last r columns of Q in the pivoted QR factorisation of Wᵀ
//! (orthonormal); any other basis gives the same polygon in tension space and the same answers
//! (an invertible linear map of λ-space maps vertices to vertices and area centroids to area
//! centroids).
//!
//! ## References
//! - Picard, Caro, Plestan & Claveau 2020, eqs. (5)–(6), Fig. 2.
//! - Lamaury & Gouttefarde (2013), *A tension distribution method with improved computational
//!   efficiency*, Cable-Driven Parallel Robots, pp. 71–85.
//! - Sutherland & Hodgman (1974), *Reentrant polygon clipping*, CACM 17(1).

use crate::certificate::SET_TOLERANCE;

/// A tension without null-space freedom (every cable at redundancy 0) is t0_i = (−W⁺ w_ext)_i,
/// whose rounding grows with the other tensions and the condition of W, not with its own bound:
/// the 10⁶-problem soak found fixed cables 1.5·10⁻¹⁰ (relative) off their bound at r = 0,
/// beyond the clipping tolerance, reported as empty sets. Such a constant constraint is kept
/// within the certificate's own bound tolerance (10 × the clipping tolerance, 10⁻⁹ relative);
/// the answer is certified afterwards.
const CONSTANT_ROW_SLACK: f64 = 10.0;
use crate::null_space::NullSpace;
use crate::outcome::validate;
use crate::{Infeasibility, TensionBounds, TensionError, TensionProblem};
use nalgebra::{DMatrix, DVector, Vector2};

/// A point of λ-space (λ₂ = 0 when r = 1; λ = 0 when r = 0).
pub(crate) type P2 = [f64; 2];

/// The feasible region in λ-space for r ≤ 2, as a convex polygon (counter-clockwise), possibly
/// degenerate (segment or point). Reusable buffers.
#[derive(Debug, Clone, Default)]
pub(crate) struct Region {
    pub verts: Vec<P2>,
    /// `edges[j]`: index into `lines` of the line carrying the edge `verts[j]` → `verts[j + 1]`
    /// ([`NO_LINE`] when unknown; then the edge is interpolated).
    edges: Vec<u32>,
    /// Lines a·λ = b of the box and of the clipping half-planes.
    lines: Vec<(P2, f64)>,
    tmp: Vec<P2>,
    tmp_edges: Vec<u32>,
    saved: Vec<P2>,
    saved_edges: Vec<u32>,
    saved_lines: usize,
    /// Scratch of [`Self::clip`]: a·λ − b at each vertex.
    depth: Vec<f64>,
    /// The polygon during a redundancy-2 build, and whether it lives there.
    fixed: FixedPolygon,
    in_fixed: bool,
    /// Half-width of the initial box.
    pub radius: f64,
    /// Data scale max(1, |t0_i|, |t_min,i|, finite |t_max,i|): the floor of the duplicate test.
    scale: f64,
    /// Whether the initial box is artificial (some t_max is infinite).
    pub artificial: bool,
}

/// No known supporting line.
const NO_LINE: u32 = u32::MAX;

/// Intersection of the lines e·λ = be and a·λ = b (Cramer), if they are not nearly parallel.
#[inline]
fn intersect(e: P2, be: f64, a: P2, b: f64) -> Option<P2> {
    let det = e[0] * a[1] - e[1] * a[0];
    let scale = (e[0].abs() + e[1].abs()) * (a[0].abs() + a[1].abs());
    if det.abs() <= 1e-6 * scale || det.is_nan() {
        return None;
    }
    Some([(be * a[1] - e[1] * b) / det, (e[0] * b - be * a[0]) / det])
}

/// The index after `j` in a cycle of `k` (no integer division: this is the clipping loop).
#[inline(always)]
fn next(j: usize, k: usize) -> usize {
    if j + 1 == k { 0 } else { j + 1 }
}

#[inline]
fn dot(a: P2, b: P2) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// max(a, b) for numbers that are not NaN (one `maxsd`; `f64::max` spends several instructions
/// on NaN, and this runs for every vertex of every clip).
#[inline(always)]
fn max_of(a: f64, b: f64) -> f64 {
    if a > b { a } else { b }
}

/// Whether two vertices coincide up to rounding (10⁻¹³ relative to their size and the data).
/// False whenever a coordinate is NaN (a comparison with NaN is false), whatever `max_of`
/// makes of it.
#[inline]
fn close(p: P2, q: P2, scale: f64) -> bool {
    let size = max_of(
        max_of(
            max_of(p[0].abs(), p[1].abs()),
            max_of(q[0].abs(), q[1].abs()),
        ),
        max_of(scale, 1e-300),
    );
    let eps = 1e-13 * size;
    (p[0] - q[0]).abs() <= eps && (p[1] - q[1]).abs() <= eps
}

/// What one clip did to the polygon.
enum Clipped {
    /// Every vertex already satisfies the constraint (the common case late in a build).
    Unchanged,
    /// Nothing is left.
    Empty,
    /// The polygon was cut; this many vertices are left.
    Cut(usize),
}

/// Borrowed storage of one clip: the polygon (`verts`, `edges`, room for 2k entries), scratch
/// for the unreduced output (2k), the vertex depths (k + 1) and the lines met so far. The same code
/// clips the reusable vectors of [`Region`] and the fixed arrays of [`FixedPolygon`].
struct PolygonMut<'a> {
    verts: &'a mut [P2],
    edges: &'a mut [u32],
    tmp: &'a mut [P2],
    tmp_edges: &'a mut [u32],
    depth: &'a mut [f64],
    lines: &'a [(P2, f64)],
}

impl PolygonMut<'_> {
    /// Sutherland–Hodgman step on the first `k` vertices: keeps a·λ ≥ b − tol. The new edge is
    /// carried by `line` (its index among the lines). See [`Region::clip`].
    #[inline(always)]
    fn clip(&mut self, k: usize, a: P2, b: f64, tol: f64, line: u32, scale: f64) -> Clipped {
        if a[0].abs() + a[1].abs() < 1e-14 {
            // Constant constraint (cable i has no null-space freedom): see
            // [`CONSTANT_ROW_SLACK`].
            return if 0.0 >= b - CONSTANT_ROW_SLACK * tol {
                Clipped::Unchanged
            } else {
                Clipped::Empty
            };
        }
        let (verts, edges) = (&mut self.verts[..2 * k], &mut self.edges[..2 * k]);
        let (tmp, tmp_edges) = (&mut self.tmp[..2 * k], &mut self.tmp_edges[..2 * k]);
        let depth = &mut self.depth[..k + 1];
        let mut inside = true;
        for (d, &p) in depth.iter_mut().zip(verts[..k].iter()) {
            *d = dot(a, p) - b;
            inside &= *d >= -tol;
        }
        // Nothing to cut: keep the region as it is.
        if inside {
            return Clipped::Unchanged;
        }
        // The first vertex again after the last (k ≥ 1, room for 2k), so edge j runs from
        // entry j to entry j + 1.
        verts[k] = verts[0];
        depth[k] = depth[0];
        let mut m = 0;
        for j in 0..k {
            let (p, q) = (verts[j], verts[j + 1]);
            let (dp, dq) = (depth[j], depth[j + 1]);
            let e = edges[j];
            let (ip, iq) = (dp >= -tol, dq >= -tol);
            if ip {
                tmp[m] = p;
                tmp_edges[m] = e;
                m += 1;
            }
            if ip != iq {
                let interpolated = || {
                    let s = (dp / (dp - dq)).clamp(0.0, 1.0);
                    [p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1])]
                };
                let exact = if e == NO_LINE {
                    None
                } else {
                    let (el, eb) = self.lines[e as usize];
                    // Must lie on the segment p q (up to rounding of p and q).
                    intersect(el, eb, a, b).filter(|x| {
                        let d = [q[0] - p[0], q[1] - p[1]];
                        let dd = dot(d, d);
                        let sx = dot([x[0] - p[0], x[1] - p[1]], d);
                        sx >= -1e-6 * dd && sx <= (1.0 + 1e-6) * dd
                    })
                };
                tmp[m] = exact.unwrap_or_else(interpolated);
                // Leaving the half-plane: the new edge runs along the clipping line.
                tmp_edges[m] = if ip { line } else { e };
                m += 1;
            }
        }
        // Drop consecutive duplicates (a dropped vertex passes its outgoing edge to the kept
        // one). The tolerance is relative to the vertices and the data, not to the box.
        let mut kept = 0;
        for (&p, &e) in tmp[..m].iter().zip(&tmp_edges[..m]) {
            if kept > 0 && close(p, verts[kept - 1], scale) {
                edges[kept - 1] = e;
                continue;
            }
            verts[kept] = p;
            edges[kept] = e;
            kept += 1;
        }
        while kept > 1 && close(verts[0], verts[kept - 1], scale) {
            kept -= 1;
        }
        if kept == 0 {
            Clipped::Empty
        } else {
            Clipped::Cut(kept)
        }
    }
}

/// Vertices a [`FixedPolygon`] may hold before a clip (its arrays hold twice as many).
const FIXED_VERTICES: usize = 32;
/// Cables up to which a redundancy-2 polygon is clipped in [`FixedPolygon`] (4 box lines plus
/// 2 lines per cable).
const FIXED_CABLES: usize = 16;
const FIXED_LINES: usize = 4 + 2 * FIXED_CABLES;

/// The polygon of a redundancy-2 build in fixed arrays (issue 17: no vector bookkeeping in the
/// clipping loop, about 12 000 of the 17 500 instructions of an l2 solve on 8 cables before).
/// Same arithmetic as the vector path, so the same vertices bit for bit; a polygon that would
/// outgrow the arrays moves to the vectors.
#[derive(Debug, Clone)]
struct FixedPolygon {
    verts: [P2; 2 * FIXED_VERTICES],
    edges: [u32; 2 * FIXED_VERTICES],
    tmp: [P2; 2 * FIXED_VERTICES],
    tmp_edges: [u32; 2 * FIXED_VERTICES],
    depth: [f64; FIXED_VERTICES + 1],
    lines: [(P2, f64); FIXED_LINES],
    /// Vertices.
    k: usize,
    /// Lines.
    nl: usize,
}

impl Default for FixedPolygon {
    fn default() -> Self {
        Self {
            verts: [[0.0; 2]; 2 * FIXED_VERTICES],
            edges: [NO_LINE; 2 * FIXED_VERTICES],
            tmp: [[0.0; 2]; 2 * FIXED_VERTICES],
            tmp_edges: [NO_LINE; 2 * FIXED_VERTICES],
            depth: [0.0; FIXED_VERTICES + 1],
            lines: [([0.0; 2], 0.0); FIXED_LINES],
            k: 0,
            nl: 0,
        }
    }
}

impl FixedPolygon {
    /// [`Region::clip`] on the arrays; `None` when the polygon might outgrow them.
    #[inline(always)]
    fn clip(&mut self, a: P2, b: f64, tol: f64, scale: f64) -> Option<bool> {
        let k = self.k;
        if k > FIXED_VERTICES || self.nl >= FIXED_LINES {
            return None;
        }
        if k == 0 {
            return Some(false);
        }
        let line = self.nl as u32;
        let mut poly = PolygonMut {
            verts: &mut self.verts,
            edges: &mut self.edges,
            tmp: &mut self.tmp,
            tmp_edges: &mut self.tmp_edges,
            depth: &mut self.depth,
            lines: &self.lines[..self.nl],
        };
        self.k = match poly.clip(k, a, b, tol, line, scale) {
            Clipped::Unchanged => k,
            Clipped::Empty => 0,
            Clipped::Cut(kept) => {
                self.lines[self.nl] = (a, b);
                self.nl += 1;
                kept
            }
        };
        Some(self.k > 0)
    }
}

impl Region {
    /// Builds the feasible set of `ns` under `bounds`; false if it is empty.
    pub fn build(&mut self, ns: &NullSpace, bounds: &TensionBounds) -> bool {
        self.build_with(ns, bounds, true)
    }

    /// [`Self::build`]; `fixed`: clip a redundancy-2 polygon in [`FixedPolygon`] when it fits
    /// (false only in the test that compares both paths).
    fn build_with(&mut self, ns: &NullSpace, bounds: &TensionBounds, fixed: bool) -> bool {
        let nonempty = self.build_in_place(ns, bounds, fixed);
        if self.in_fixed {
            self.leave_fixed();
        }
        nonempty
    }

    /// Moves the polygon from the fixed arrays to the vectors.
    fn leave_fixed(&mut self) {
        let f = &self.fixed;
        self.verts.clear();
        self.verts.extend_from_slice(&f.verts[..f.k]);
        self.edges.clear();
        self.edges.extend_from_slice(&f.edges[..f.k]);
        self.lines.clear();
        self.lines.extend_from_slice(&f.lines[..f.nl]);
        self.in_fixed = false;
    }

    /// [`Self::clip`] during a build: in the fixed arrays while the polygon fits there.
    #[inline(always)]
    fn cut(&mut self, a: P2, b: f64, tol: f64) -> bool {
        if self.in_fixed {
            if let Some(nonempty) = self.fixed.clip(a, b, tol, self.scale) {
                return nonempty;
            }
            self.leave_fixed();
        }
        self.clip(a, b, tol)
    }

    fn build_in_place(&mut self, ns: &NullSpace, bounds: &TensionBounds, fixed: bool) -> bool {
        let (n, r) = (ns.n, ns.r());
        debug_assert!(r <= 2);
        let cap = 2 * n + 8;
        if self.verts.capacity() < cap {
            self.verts.reserve(cap);
            self.edges.reserve(cap);
            self.tmp.reserve(cap);
            self.tmp_edges.reserve(cap);
            self.saved.reserve(cap);
            self.saved_edges.reserve(cap);
        }
        if self.lines.capacity() < 3 * n + 8 {
            self.lines.reserve(3 * n + 8);
        }
        let (lo, hi) = (bounds.min(), bounds.max());
        let mut rad2 = 0.0;
        let mut data_scale: f64 = 1.0;
        self.artificial = false;
        for i in 0..n {
            let t0 = ns.t0[i];
            data_scale = data_scale.max(t0.abs()).max(lo[i].abs());
            if hi[i].is_finite() {
                data_scale = data_scale.max(hi[i].abs());
                let d = (lo[i] - t0).abs().max((hi[i] - t0).abs());
                rad2 += d * d;
            } else {
                self.artificial = true;
            }
        }
        let radius = if self.artificial {
            1e6 * data_scale * (n as f64).sqrt()
        } else {
            rad2.sqrt() * (1.0 + 1e-6) + 1e-9 * data_scale
        };
        self.radius = radius;
        self.scale = data_scale;
        self.verts.clear();
        self.edges.clear();
        self.lines.clear();
        match r {
            0 => {
                self.verts.push([0.0, 0.0]);
                self.edges.push(NO_LINE);
            }
            1 => {
                // Both edges of the segment lie on λ₂ = 0.
                self.lines.push(([0.0, 1.0], 0.0));
                self.verts
                    .extend_from_slice(&[[-radius, 0.0], [radius, 0.0]]);
                self.edges.extend_from_slice(&[0, 0]);
            }
            _ => {
                // Counter-clockwise; edge j lies on line j (inside: a·λ ≥ b).
                self.lines.extend_from_slice(&[
                    ([0.0, 1.0], -radius),
                    ([-1.0, 0.0], -radius),
                    ([0.0, -1.0], -radius),
                    ([1.0, 0.0], -radius),
                ]);
                self.verts.extend_from_slice(&[
                    [-radius, -radius],
                    [radius, -radius],
                    [radius, radius],
                    [-radius, radius],
                ]);
                self.edges.extend_from_slice(&[0, 1, 2, 3]);
                // Fixed cables are cut by `clip_line`, which works on the vectors only.
                self.in_fixed = fixed && n <= FIXED_CABLES && (0..n).all(|i| lo[i] != hi[i]);
                if self.in_fixed {
                    let f = &mut self.fixed;
                    f.verts[..4].copy_from_slice(&self.verts);
                    f.edges[..4].copy_from_slice(&self.edges);
                    f.lines[..4].copy_from_slice(&self.lines);
                    (f.k, f.nl) = (4, 4);
                }
            }
        }
        // Two-sided constraints first, fixed cables (t_min = t_max) as one line each: while
        // the region is still the (possibly 10⁶ times too large) initial box, its vertices carry
        // an absolute error ε·R, and a strip narrower than that, clipped one side at a time,
        // would be lost (a soak finding: a fixed cable next to an infinite t_max).
        for pass in 0..2 {
            for i in 0..n {
                if hi[i].is_finite() != (pass == 0) {
                    continue;
                }
                let a = ns.row2(i);
                let t0 = ns.t0[i];
                let tol_lo = self.tolerance(lo[i]);
                if hi[i] == lo[i] && r == 1 {
                    // t0 + a·λ = t_min, kept as the band |a·λ − (t_min − t0)| ≤ tol (cut at
                    // the band's edges): λ is a scalar, so a fixed cable whose null-space row a
                    // is tiny pins λ only to ±tol/|a|, and a second fixed cable must be allowed
                    // to meet it anywhere in that band. Cutting at the line itself collapsed
                    // the segment to one point whose rounding, amplified by 1/|a|, made the
                    // second fixed cable miss it (three false "no feasible tension" in the
                    // 10⁶-problem soak, l2, l2-max and linf). The band's ends are within the
                    // clipping tolerance of t_min, so the certificate accepts them.
                    let b = lo[i] - t0;
                    if !self.cut(a, b - tol_lo, tol_lo)
                        || !self.cut([-a[0], -a[1]], -b - tol_lo, tol_lo)
                    {
                        return false;
                    }
                    continue;
                }
                if hi[i] == lo[i] {
                    // t0 + a·λ = t_min
                    if !self.clip_line(a, lo[i] - t0, tol_lo) {
                        return false;
                    }
                    continue;
                }
                // t0 + a·λ ≥ t_min  ⇔  a·λ ≥ t_min − t0
                if !self.cut(a, lo[i] - t0, tol_lo) {
                    return false;
                }
                if hi[i].is_finite() {
                    let tol = self.tolerance(hi[i]);
                    if !self.cut([-a[0], -a[1]], t0 - hi[i], tol) {
                        return false;
                    }
                }
            }
        }
        true
    }

    /// Clipping tolerance for a bound: 10⁻¹⁰ relative to the bound (a tenth of the certificate's
    /// bound tolerance, so a vertex kept by it still passes [`crate::certify`] after snapping) or
    /// the rounding of t0 = −W⁺ w_ext at the data scale, whichever is larger. A kept vertex is
    /// only a candidate: every answer is certified afterwards.
    #[inline]
    fn tolerance(&self, bound: f64) -> f64 {
        (SET_TOLERANCE * bound.abs().max(1.0)).max(1e-14 * self.scale)
    }

    /// Keeps the part of the region on the line a·λ = b (within `tol`): a fixed cable
    /// (t_min = t_max). The result is a segment, a point, or empty (false). The crossing points
    /// are intersections with the edges' lines (as in [`Self::clip`]), so they carry no error
    /// from the size of the region.
    pub fn clip_line(&mut self, a: P2, b: f64, tol: f64) -> bool {
        if self.verts.is_empty() {
            return false;
        }
        if a[0].abs() + a[1].abs() < 1e-14 {
            // A constant tension t0_i (no null-space freedom): see [`CONSTANT_ROW_SLACK`].
            if b.abs() <= CONSTANT_ROW_SLACK * tol {
                return true;
            }
            self.verts.clear();
            self.edges.clear();
            return false;
        }
        let k = self.verts.len();
        if self.verts.iter().all(|&p| (dot(a, p) - b).abs() <= tol) {
            return true;
        }
        if self.edges.len() != k {
            self.edges.clear();
            self.edges.resize(k, NO_LINE);
        }
        let line = self.lines.len() as u32;
        self.lines.push((a, b));
        // Direction along the line; the segment runs between the extreme crossing points.
        let dir = [-a[1], a[0]];
        let (mut lo, mut hi): (Option<P2>, Option<P2>) = (None, None);
        let mut keep = |x: P2| {
            let s = dot(dir, x);
            if lo.is_none_or(|l| s < dot(dir, l)) {
                lo = Some(x);
            }
            if hi.is_none_or(|h| s > dot(dir, h)) {
                hi = Some(x);
            }
        };
        let mut dq = dot(a, self.verts[0]) - b;
        let edges = if k == 1 { 0 } else { k };
        if k == 1 && dq.abs() <= tol {
            keep(self.verts[0]);
        }
        for j in 0..edges {
            let p = self.verts[j];
            let q = self.verts[next(j, k)];
            let dp = dq;
            dq = dot(a, q) - b;
            if dp.abs() <= tol {
                keep(p);
                continue;
            }
            if (dp > tol && dq < -tol) || (dp < -tol && dq > tol) {
                let e = self.edges[j];
                let exact = if e == NO_LINE {
                    None
                } else {
                    let (el, eb) = self.lines[e as usize];
                    intersect(el, eb, a, b)
                };
                let x = exact.unwrap_or_else(|| {
                    let s = (dp / (dp - dq)).clamp(0.0, 1.0);
                    [p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1])]
                });
                keep(x);
            }
        }
        self.verts.clear();
        self.edges.clear();
        let (Some(lo), Some(hi)) = (lo, hi) else {
            return false;
        };
        self.verts.push(lo);
        self.edges.push(line);
        if !close(lo, hi, self.scale) {
            self.verts.push(hi);
            self.edges.push(line);
        }
        true
    }

    /// Keeps the part of the region where a·λ ≥ b − tol; false if nothing is left.
    ///
    /// A new vertex is the intersection of the clipping line with the line carrying the cut edge,
    /// solved directly (2 × 2 Cramer) rather than interpolated along the edge: interpolation
    /// along an edge of the (possibly 10⁶ times too large, artificial) initial box would carry
    /// an absolute error ε·R into the vertices. Interpolation remains the fallback for nearly
    /// parallel lines or an unknown edge line.
    pub fn clip(&mut self, a: P2, b: f64, tol: f64) -> bool {
        if self.verts.is_empty() {
            return false;
        }
        let k = self.verts.len();
        if self.edges.len() != k {
            self.edges.clear();
            self.edges.resize(k, NO_LINE);
        }
        self.verts.resize(2 * k, [0.0; 2]);
        self.edges.resize(2 * k, NO_LINE);
        self.tmp.resize(2 * k, [0.0; 2]);
        self.tmp_edges.resize(2 * k, NO_LINE);
        self.depth.resize(k + 1, 0.0);
        let line = self.lines.len() as u32;
        let mut poly = PolygonMut {
            verts: &mut self.verts,
            edges: &mut self.edges,
            tmp: &mut self.tmp,
            tmp_edges: &mut self.tmp_edges,
            depth: &mut self.depth,
            lines: &self.lines,
        };
        let kept = match poly.clip(k, a, b, tol, line, self.scale) {
            Clipped::Unchanged => k,
            Clipped::Empty => 0,
            Clipped::Cut(kept) => {
                self.lines.push((a, b));
                kept
            }
        };
        self.verts.truncate(kept);
        self.edges.truncate(kept);
        kept > 0
    }

    /// Saves the current vertices (for bisection).
    pub fn save(&mut self) {
        self.saved.clear();
        self.saved.extend_from_slice(&self.verts);
        self.saved_edges.clear();
        self.saved_edges.extend_from_slice(&self.edges);
        self.saved_lines = self.lines.len();
    }

    /// Restores the saved vertices.
    pub fn restore(&mut self) {
        self.verts.clear();
        self.verts.extend_from_slice(&self.saved);
        self.edges.clear();
        self.edges.extend_from_slice(&self.saved_edges);
        self.lines.truncate(self.saved_lines);
    }

    /// The vertex minimising (or, with `maximize`, maximising) `f`; first one on ties.
    pub fn best_vertex(&self, f: impl Fn(P2) -> f64, maximize: bool) -> P2 {
        let mut best = self.verts[0];
        let mut fb = f(best);
        for &v in &self.verts[1..] {
            let fv = f(v);
            if (maximize && fv > fb) || (!maximize && fv < fb) {
                best = v;
                fb = fv;
            }
        }
        best
    }

    /// Twice the signed area (shoelace).
    pub fn double_area(&self) -> f64 {
        double_area(&self.verts)
    }

    /// Area centroid; for a (numerically) degenerate polygon, the mean of its vertices.
    pub fn centroid(&self) -> P2 {
        centroid(&self.verts)
    }

    /// Whether `c` lies in a polygon with positive area (counter-clockwise).
    ///
    /// An edge shorter than 10⁻⁹ of the polygon's size joins two vertices that are one point up to
    /// rounding (clipping can leave such a pair); its direction is rounding noise, so it is not
    /// tested: its neighbours bound the polygon there.
    pub fn contains(&self, c: P2) -> bool {
        let k = self.verts.len();
        if k < 3 || self.double_area() <= 0.0 {
            return false;
        }
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for v in &self.verts {
            for a in 0..2 {
                lo[a] = lo[a].min(v[a]);
                hi[a] = hi[a].max(v[a]);
            }
        }
        let short = (1e-9 * (hi[0] - lo[0]).max(hi[1] - lo[1])).powi(2);
        (0..k).all(|j| {
            let p = self.verts[j];
            let q = self.verts[next(j, k)];
            let d = [q[0] - p[0], q[1] - p[1]];
            dot(d, d) <= short || d[0] * (c[1] - p[1]) - d[1] * (c[0] - p[0]) >= 0.0
        })
    }

    /// Euclidean projection of `c` onto the region (exact: c itself if inside, else the closest
    /// point of the boundary edges).
    pub fn project(&self, c: P2) -> P2 {
        if self.contains(c) {
            return c;
        }
        let k = self.verts.len();
        if k == 1 {
            return self.verts[0];
        }
        let mut best = self.verts[0];
        let mut bd = f64::INFINITY;
        for j in 0..k {
            let p = self.verts[j];
            let q = self.verts[next(j, k)];
            let d = [q[0] - p[0], q[1] - p[1]];
            let dd = dot(d, d);
            let s = if dd > 0.0 {
                (dot([c[0] - p[0], c[1] - p[1]], d) / dd).clamp(0.0, 1.0)
            } else {
                0.0
            };
            // Step from the nearer end (an edge may be 10⁶ times longer than the data on an
            // artificial box; p + s·d with s ≈ 1 would carry an error ε·‖d‖).
            let x = if s == 0.0 {
                p
            } else if s == 1.0 {
                q
            } else if s <= 0.5 {
                [p[0] + s * d[0], p[1] + s * d[1]]
            } else {
                let u = (dot([c[0] - q[0], c[1] - q[1]], d) / dd).clamp(-1.0, 0.0);
                [q[0] + u * d[0], q[1] + u * d[1]]
            };
            let dist = (x[0] - c[0]).powi(2) + (x[1] - c[1]).powi(2);
            if dist < bd {
                bd = dist;
                best = x;
            }
        }
        best
    }

    /// Whether λ lies on the artificial box (so the true feasible set is unbounded there).
    pub fn on_artificial_box(&self, l: P2) -> bool {
        self.artificial && l[0].abs().max(l[1].abs()) >= self.radius * (1.0 - 1e-9)
    }

    /// Whether any vertex lies on the artificial box.
    pub fn is_unbounded(&self) -> bool {
        self.verts.iter().any(|&v| self.on_artificial_box(v))
    }
}

/// Twice the signed area (shoelace).
pub(crate) fn double_area(verts: &[P2]) -> f64 {
    let k = verts.len();
    if k < 3 {
        return 0.0;
    }
    let mut s = 0.0;
    for j in 0..k {
        let p = verts[j];
        let q = verts[next(j, k)];
        s += p[0] * q[1] - q[0] * p[1];
    }
    s
}

/// Whether a polygon has an area (at least 3 vertices, |area| above 10⁻¹² of its extent²);
/// otherwise it counts as degenerate (a segment or a point).
pub(crate) fn has_area(verts: &[P2]) -> bool {
    let k = verts.len();
    let a2 = double_area(verts);
    let (mut xmin, mut xmax, mut ymin, mut ymax) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for v in verts {
        xmin = xmin.min(v[0]);
        xmax = xmax.max(v[0]);
        ymin = ymin.min(v[1]);
        ymax = ymax.max(v[1]);
    }
    let extent = (xmax - xmin).max(ymax - ymin);
    k >= 3 && a2.abs() > 1e-12 * extent * extent
}

/// Area centroid; for a (numerically) degenerate polygon, the mean of its vertices.
pub(crate) fn centroid(verts: &[P2]) -> P2 {
    let k = verts.len();
    if has_area(verts) {
        // Shift to the first vertex for accuracy.
        let o = verts[0];
        let (mut cx, mut cy, mut s2) = (0.0, 0.0, 0.0);
        for j in 0..k {
            let p = [verts[j][0] - o[0], verts[j][1] - o[1]];
            let qv = verts[next(j, k)];
            let q = [qv[0] - o[0], qv[1] - o[1]];
            let c = p[0] * q[1] - q[0] * p[1];
            s2 += c;
            cx += (p[0] + q[0]) * c;
            cy += (p[1] + q[1]) * c;
        }
        [o[0] + cx / (3.0 * s2), o[1] + cy / (3.0 * s2)]
    } else {
        let (sx, sy) = verts
            .iter()
            .fold((0.0, 0.0), |(a, b), v| (a + v[0], b + v[1]));
        [sx / k as f64, sy / k as f64]
    }
}

/// The feasible polygon of a redundancy-2 problem (Picard, Caro, Plestan & Claveau 2020, eq. (6)), in λ-space and in
/// tension space.
#[derive(Debug, Clone, PartialEq)]
pub struct FeasiblePolygon {
    /// N (n × 2): orthonormal null-space basis of W (last columns of Q in Wᵀ P = Q R).
    pub null_space: DMatrix<f64>,
    /// t0 = −W⁺ w_ext, the particular (minimum-norm) solution of eq. (5).
    pub particular: DVector<f64>,
    /// Vertices λ_k, counter-clockwise (a degenerate polygon may have 1 or 2 vertices).
    pub vertices: Vec<Vector2<f64>>,
    /// The same vertices in tension space, t_k = t0 + N λ_k.
    pub tension_vertices: Vec<DVector<f64>>,
}

impl FeasiblePolygon {
    /// The feasible polygon of `problem`, or why there is none (empty, singular W, or
    /// unbounded because of an infinite t_max). Errors on bad input and r ≠ 2.
    ///
    /// ```
    /// use cdpr_tension::{FeasiblePolygon, TensionBounds, TensionProblem};
    /// use nalgebra::{DMatrix, DVector};
    /// // One force balanced by three collinear cables: t1 + t2 + t3 = 3, 0 ≤ t ≤ 3: a triangle.
    /// let w = DMatrix::from_row_slice(1, 3, &[1.0, 1.0, 1.0]);
    /// let we = DVector::from_vec(vec![-3.0]);
    /// let b = TensionBounds::uniform(3, 0.0, 3.0).unwrap();
    /// let poly = FeasiblePolygon::compute(&TensionProblem::new(&w, &we, &b)).unwrap().unwrap();
    /// assert_eq!(poly.vertices.len(), 3);
    /// assert!((poly.barycenter() - DVector::from_vec(vec![1.0; 3])).norm() < 1e-12);
    /// ```
    pub fn compute(problem: &TensionProblem) -> Result<Result<Self, Infeasibility>, TensionError> {
        validate(problem)?;
        let r = problem.redundancy();
        if r != 2 {
            return Err(TensionError::RedundancyMismatch {
                what: "feasible polygon",
                needs: 2,
                redundancy: r,
            });
        }
        let mut ns = NullSpace::default();
        if let Err(condition) = ns.compute(problem.wrench_matrix, problem.external_wrench) {
            return Ok(Err(Infeasibility::SingularPose { condition }));
        }
        let mut region = Region::default();
        if !region.build(&ns, problem.bounds) {
            return Ok(Err(Infeasibility::NoFeasibleTension));
        }
        if region.is_unbounded() {
            return Ok(Err(Infeasibility::Unbounded {
                method: "feasible polygon",
            }));
        }
        let n = ns.n;
        let null_space = DMatrix::from_column_slice(n, 2, &ns.basis);
        let particular = DVector::from_column_slice(&ns.t0);
        let vertices: Vec<_> = region
            .verts
            .iter()
            .map(|v| Vector2::new(v[0], v[1]))
            .collect();
        let tension_vertices = vertices
            .iter()
            .map(|l| &particular + &null_space * l)
            .collect();
        Ok(Ok(Self {
            null_space,
            particular,
            vertices,
            tension_vertices,
        }))
    }

    /// Tensions t = t0 + N λ (eq. (5)).
    pub fn tensions_at(&self, lambda: &Vector2<f64>) -> DVector<f64> {
        &self.particular + &self.null_space * lambda
    }

    /// Area of the polygon in λ-space (equal to its area in tension space: N is orthonormal).
    pub fn area(&self) -> f64 {
        self.region().double_area() / 2.0
    }

    /// Area centroid in λ-space (vertex mean for a degenerate polygon).
    pub fn barycenter_lambda(&self) -> Vector2<f64> {
        let c = self.region().centroid();
        Vector2::new(c[0], c[1])
    }

    /// The barycentre tensions t0 + N λ_c (Lamaury & Gouttefarde 2013).
    pub fn barycenter(&self) -> DVector<f64> {
        self.tensions_at(&self.barycenter_lambda())
    }

    /// Whether λ lies in the polygon (within 10⁻⁹ relative on every bound).
    pub fn contains(&self, lambda: &Vector2<f64>, bounds: &TensionBounds) -> bool {
        let t = self.tensions_at(lambda);
        (0..t.len()).all(|i| {
            crate::certificate::bound_violation(bounds.min()[i], bounds.max()[i], t[i]) <= 1e-9
        })
    }

    fn region(&self) -> Region {
        Region {
            verts: self.vertices.iter().map(|v| [v.x, v.y]).collect(),
            ..Region::default()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// CAROCA with swivel pulleys (CASPR model) at its home pose, 150 kg, t ∈ [0, 1000] N: the
    /// clipped polygon ends in two vertices 1.7·10⁻¹⁰ apart. The edge between them has a direction
    /// made of rounding, and the cross-product test used to put the interior point λ = 0 (the
    /// minimum-norm tensions, all in bounds) outside it: l2 then projected it onto the boundary and
    /// returned t = (0, 328.6, 630.9, …) N, ‖t‖² = 1.23·10⁶ N², instead of t0 (‖t0‖² = 8.33·10⁵ N²).
    #[test]
    fn a_vertex_pair_made_of_rounding_does_not_exclude_interior_points() {
        let r = Region {
            verts: vec![
                [-4.2819356678132845, -903.3303178308754],
                [910.5910843651232, 36.93305996002893],
                [2.994385269499825, 920.8728464442395],
                [-912.4974251177787, -12.1812992430009],
                [-912.4974251177941, -12.181299242833234],
            ],
            ..Region::default()
        };
        assert!(r.double_area() > 0.0);
        for c in [[0.0, 0.0], [100.0, -200.0], [-900.0, -12.0], [1.0, 900.0]] {
            assert!(r.contains(c), "{c:?}");
            assert_eq!(r.project(c), c);
        }
        // Points outside stay outside, including beyond the short edge.
        for c in [[-913.0, -12.18], [0.0, 1000.0], [920.0, 40.0]] {
            assert!(!r.contains(c), "{c:?}");
        }
    }

    #[test]
    fn square_clipped_to_triangle() {
        let mut r = Region {
            verts: vec![[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]],
            radius: 1.0,
            ..Region::default()
        };
        // x + y ≤ 0  ⇔  −x − y ≥ 0
        assert!(r.clip([-1.0, -1.0], 0.0, 0.0));
        assert_eq!(r.verts.len(), 3);
        assert!((r.double_area() - 4.0).abs() < 1e-15); // area 2
        let c = r.centroid();
        assert!((c[0] + 1.0 / 3.0).abs() < 1e-15 && (c[1] + 1.0 / 3.0).abs() < 1e-15);
        // Projection of (1, 1) onto the triangle is (0, 0).
        let p = r.project([1.0, 1.0]);
        assert!(p[0].abs() < 1e-15 && p[1].abs() < 1e-15);
        // Clipping away everything.
        assert!(!r.clip([1.0, 0.0], 2.0, 0.0));
    }

    /// Regression (infinite t_max): vertices cut from a huge artificial box are exact
    /// intersections of their lines, not interpolations with error ε·R along box edges.
    #[test]
    fn vertices_cut_from_a_huge_box_are_exact() {
        let radius = 2e8;
        let mut r = Region {
            radius,
            scale: 1.0,
            ..Region::default()
        };
        r.lines.extend_from_slice(&[
            ([0.0, 1.0], -radius),
            ([-1.0, 0.0], -radius),
            ([0.0, -1.0], -radius),
            ([1.0, 0.0], -radius),
        ]);
        r.verts = vec![
            [-radius, -radius],
            [radius, -radius],
            [radius, radius],
            [-radius, radius],
        ];
        r.edges = vec![0, 1, 2, 3];
        // 0.6 λ₁ + 0.8 λ₂ ≥ 1.3 and 0.8 λ₁ − 0.6 λ₂ ≥ −0.7: corner at (0.22, 1.46)
        // (0.6·0.22 + 0.8·1.46 = 1.3, 0.8·0.22 − 0.6·1.46 = −0.7).
        assert!(r.clip([0.6, 0.8], 1.3, 0.0));
        assert!(r.clip([0.8, -0.6], -0.7, 0.0));
        let corner = r
            .verts
            .iter()
            .copied()
            .min_by(|a, b| (a[0].abs() + a[1].abs()).total_cmp(&(b[0].abs() + b[1].abs())))
            .unwrap();
        assert!((corner[0] - 0.22).abs() < 1e-15, "{corner:?}");
        assert!((corner[1] - 1.46).abs() < 1e-15, "{corner:?}");
        // The segment case (r = 1): λ₁ ≥ 503.2447700885809 on [−R, R] is exact too.
        let mut s = Region {
            radius,
            scale: 1.0,
            ..Region::default()
        };
        s.lines.push(([0.0, 1.0], 0.0));
        s.verts = vec![[-radius, 0.0], [radius, 0.0]];
        s.edges = vec![0, 0];
        assert!(s.clip([0.2, 0.0], 0.2 * 503.2447700885809, 0.0));
        let x = s.verts.iter().map(|v| v[0]).fold(f64::INFINITY, f64::min);
        assert!((x - 503.2447700885809).abs() <= 1e-13, "{x}");
        // Projection onto that long segment returns its end exactly.
        assert_eq!(s.project([0.0, 0.0])[0], x);
    }

    /// The fixed arrays give the vector path's polygon bit for bit (same steps), on random
    /// redundancy-2 problems with finite, infinite and nearly violated bounds.
    #[test]
    fn fixed_arrays_match_the_vectors_bit_for_bit() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut nonempty = 0;
        for (m, n) in [(6, 8), (3, 5), (1, 3), (10, 12), (14, 16)] {
            for case in 0..300 {
                let w = DMatrix::from_fn(m, n, |_, _| 2.0 * next() - 1.0);
                let we = DVector::from_fn(m, |_, _| 4.0 * (2.0 * next() - 1.0));
                let lo: Vec<f64> = (0..n).map(|_| next()).collect();
                let hi: Vec<f64> = (0..n)
                    .map(|i| match case % 3 {
                        0 if i == 0 => f64::INFINITY,
                        _ => lo[i] + 1.0 + 5.0 * next(),
                    })
                    .collect();
                let bounds = TensionBounds::new(lo, hi).unwrap();
                let mut ns = NullSpace::default();
                if ns.compute(&w, &we).is_err() {
                    continue;
                }
                let (mut a, mut b) = (Region::default(), Region::default());
                let ka = a.build_with(&ns, &bounds, true);
                let kb = b.build_with(&ns, &bounds, false);
                assert_eq!(ka, kb, "{m}x{n} case {case}");
                let bits = |r: &Region| {
                    r.verts
                        .iter()
                        .flat_map(|v| [v[0].to_bits(), v[1].to_bits()])
                        .collect::<Vec<_>>()
                };
                assert_eq!(bits(&a), bits(&b), "{m}x{n} case {case}");
                assert_eq!(a.edges, b.edges, "{m}x{n} case {case}");
                assert_eq!(a.lines, b.lines, "{m}x{n} case {case}");
                nonempty += ka as usize;
            }
        }
        // Both outcomes occur (the test is not vacuous).
        assert!(nonempty > 100 && nonempty < 1400, "{nonempty}");
    }

    /// A polygon with more vertices than the fixed arrays take before a clip moves to the
    /// vectors and is clipped there, as if it had been there all along.
    #[test]
    fn a_polygon_too_large_for_the_arrays_moves_to_the_vectors() {
        let k = FIXED_VERTICES + 8;
        let gon: Vec<P2> = (0..k)
            .map(|j| {
                let a = std::f64::consts::TAU * j as f64 / k as f64;
                [a.cos(), a.sin()]
            })
            .collect();
        let mut vectors = Region {
            verts: gon.clone(),
            edges: vec![NO_LINE; k],
            scale: 1.0,
            ..Region::default()
        };
        let mut fixed = Region {
            scale: 1.0,
            in_fixed: true,
            ..Region::default()
        };
        fixed.fixed.verts[..k].copy_from_slice(&gon);
        fixed.fixed.k = k;
        // λ₁ + λ₂ ≤ 0.5 cuts off about a third of the 40-gon.
        assert!(vectors.clip([-1.0, -1.0], -0.5, 0.0));
        assert!(fixed.cut([-1.0, -1.0], -0.5, 0.0));
        assert!(!fixed.in_fixed);
        assert_eq!(fixed.verts, vectors.verts);
        assert_eq!(fixed.edges, vectors.edges);
        assert!(vectors.verts.len() < k && vectors.verts.len() > k / 2);
    }
}
