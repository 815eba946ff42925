//! # Vertex centroid of the feasible polytope (Mikelsons et al. 2008)
//!
//! The mean of the vertices of the feasible polytope {t = t0 + N λ : t_min ≤ t ≤ t_max}, for
//! any redundancy r (WireLib's `weightedSum`; the *area* centroid of the polygon at r = 2 is
//! `barycenter`, a different point unless the polygon is regular). A convex combination of
//! feasible vertices, so feasible whenever the set is non-empty.
//!
//! Every vertex makes r bound constraints active with independent null-space rows: for each
//! set S of r cables (C(n, r) sets) whose rows N_S are independent (LU with partial pivoting,
//! smallest pivot above 10⁻¹⁰; the rows of N have norm ≤ 1), and each of the 2^r choices of a
//! bound per cable, N_S λ = b_S − t0_S gives a candidate; it is a vertex when every cable is
//! within its bounds (relative tolerance 10⁻¹⁰; for a cable whose null-space row is zero, whose
//! tension is t0_i on the whole equilibrium set, e.g. every cable at r = 0, the certificate's
//! 10⁻⁹, since t0 = −W⁺ w_ext carries its own rounding, as in the l2 active set). Degenerate vertices (more than r active
//! bounds) are found from several bases and kept once (entries equal within 10⁻⁹ relative), as
//! WireLib drops its doublets. The answer is their mean. For a bounded set (finite t_max) a
//! non-empty feasible set has at least one vertex; when none is found the solver confirms the
//! verdict before reporting it: at r = 2 with the clipped feasible polygon (module
//! `feasible_polygon`, the decider of l2 and the barycentre there), else — or when that polygon
//! is not empty — with the l2 dense active set. More than 2²⁰ candidate bases is
//! a documented give-up ([`crate::GiveUp::TooManyBases`]).
//!
//! ## Redundancy 2
//! At r = 2 the set is the feasible polygon of [`crate::FeasiblePolygon`] and the candidates are
//! the C(n, 2)·4 intersections of two of its 2n bound lines (112 for 8 cables). The r = 2 path
//! visits the same candidates in the same order with the same floating-point operations (the
//! 2 × 2 LU with partial pivoting written out), so it keeps the same vertices bit for bit —
//! degenerate vertices, coincident and parallel bound lines (a dependent pair, skipped by the
//! pivot test), fixed cables (segments, single points), zero null-space rows and the
//! tolerances above included — but it tests the four candidates of a pair of cables together
//! in one branch-free loop over the cables, and stores a candidate's tensions only when it is
//! within bounds (issue 26's fixture: 69 143 → see docs/benchmarks.md instructions per solve). Averaging the vertices of the clipped polygon instead would be cheaper
//! still, but its clipping tolerance and its merging of close vertices (10⁻¹³) differ from the
//! tolerances here, so near-degenerate sets would get a different vertex list. The general
//! enumeration stays for r ≠ 2 and as the reference of the tests (unit property test
//! `planar_path_is_the_enumeration`; all 20 000 poses of issue 26's fixture in
//! `benches/tests/issue_26.rs`).
//!
//! ## References
//! - Mikelsons, L., Bruckmann, T., Hiller, M. & Schramm, D. (2008), *A real-time capable force
//!   calculation algorithm for redundant tendon-based parallel manipulators*, ICRA 2008,
//!   pp. 3869–3874.
//! - WireLib (Pott, Fraunhofer IPA), `CForceDistribution::getDistributionAllVertices` and
//!   `getDistributionWeightedSum`.

use crate::active_set::ZERO_ROW;
use crate::certificate::{BOUND_TOLERANCE, SET_TOLERANCE};
use crate::null_space::NullSpace;
use crate::{GiveUp, Infeasibility, TensionBounds, TensionProblem};

/// Candidate bases above which the enumeration gives up.
pub(crate) const MAX_BASES: u128 = 1 << 20;
/// Smallest LU pivot of an independent N_S.
const PIVOT: f64 = 1e-10;
/// Relative distance under which two vertices are one.
const SAME: f64 = 1e-9;

/// Buffers (no allocation once sized, apart from the vertex list's growth).
#[derive(Debug, Clone, Default)]
pub(crate) struct VertexCentroid {
    cables: Vec<usize>,
    lu: Vec<f64>,
    piv: Vec<usize>,
    lambda: Vec<f64>,
    cand: Vec<f64>,
    /// Lowest and highest accepted tension of each cable.
    below: Vec<f64>,
    above: Vec<f64>,
    vertices: Vec<f64>,
    /// Distinct vertices found by the last solve.
    pub count: usize,
}

/// Which enumeration runs at r = 2.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Path {
    /// The general enumeration (the reference of the tests).
    General,
    /// The r = 2 path, in its AVX2 build when the CPU has it.
    Planar,
    /// The r = 2 path in the baseline build (for the test that compares both builds).
    #[cfg_attr(not(test), allow(dead_code))]
    PlanarPortable,
}

/// C(n, r)·2^r, saturating.
pub(crate) fn candidate_bases(n: usize, r: usize) -> u128 {
    let mut c: u128 = 1;
    for k in 0..r as u128 {
        c = c.saturating_mul(n as u128 - k) / (k + 1);
    }
    c.saturating_mul(1u128 << r.min(100))
}

impl VertexCentroid {
    /// The vertex centroid into `t`; `Err(NoFeasibleTension)` when no vertex was found
    /// (callers confirm it).
    pub fn solve(
        &mut self,
        ns: &NullSpace,
        bounds: &TensionBounds,
        t: &mut [f64],
    ) -> Result<(), Infeasibility> {
        self.solve_with(ns, bounds, t, Path::Planar)
    }

    /// [`Self::solve`] by the enumeration `path` at r = 2 (other r: the general one).
    fn solve_with(
        &mut self,
        ns: &NullSpace,
        bounds: &TensionBounds,
        t: &mut [f64],
        path: Path,
    ) -> Result<(), Infeasibility> {
        let (n, r) = (ns.n, ns.r());
        let bases = candidate_bases(n, r);
        if bases > MAX_BASES {
            return Err(Infeasibility::GaveUp {
                method: "vertex-centroid",
                reason: GiveUp::TooManyBases { bases },
            });
        }
        let (lo, hi) = (bounds.min(), bounds.max());
        self.cables.clear();
        self.cables.extend(0..r);
        self.lu.resize(r * r, 0.0);
        self.piv.resize(r, 0);
        self.lambda.resize(r, 0.0);
        self.cand.resize(n, 0.0);
        self.below.clear();
        self.above.clear();
        for i in 0..n {
            // A cable with a zero null-space row is at t0_i on every candidate: judged with
            // the certificate's tolerance (soak problem 203901: r = 0, a fixed cable 4.9·10⁻¹⁰
            // N off its bound of 3.29 N was "no vertex").
            let row2: f64 = (0..r).map(|j| ns.basis[j * n + i].powi(2)).sum();
            let tol = if row2 <= ZERO_ROW * ZERO_ROW {
                BOUND_TOLERANCE
            } else {
                SET_TOLERANCE
            };
            self.below.push(lo[i] - tol * lo[i].abs().max(1.0));
            self.above.push(hi[i] + tol * hi[i].abs().max(1.0));
        }
        self.vertices.clear();
        self.count = 0;
        let (lo, hi) = (&lo.as_slice()[..n], &hi.as_slice()[..n]);
        if r == 2 && path == Path::Planar {
            self.enumerate_planar(ns, lo, hi);
        } else if r == 2 && path == Path::PlanarPortable {
            self.enumerate_planar_here(ns, lo, hi);
        } else {
            self.enumerate(ns, lo, hi);
        }
        if self.count == 0 {
            return Err(Infeasibility::NoFeasibleTension);
        }
        t.fill(0.0);
        for v in self.vertices.chunks_exact(n) {
            for (ti, vi) in t.iter_mut().zip(v) {
                *ti += vi;
            }
        }
        let k = self.count as f64;
        for ti in t.iter_mut() {
            *ti /= k;
        }
        Ok(())
    }

    /// Every candidate basis of any r: [`Self::factor`], [`Self::lu_solve`], all n tensions
    /// (the reference of the planar path).
    fn enumerate(&mut self, ns: &NullSpace, lo: &[f64], hi: &[f64]) {
        let (n, r) = (ns.n, ns.r());
        loop {
            if self.factor(ns) {
                for pattern in 0..1usize << r {
                    for (k, &i) in self.cables.iter().enumerate() {
                        let b = if pattern >> k & 1 == 1 { hi[i] } else { lo[i] };
                        self.lambda[k] = b - ns.t0[i];
                    }
                    self.lu_solve(r);
                    ns.tensions(&self.lambda, &mut self.cand);
                    let feasible = (0..n).all(|i| {
                        let c = self.cand[i];
                        c >= self.below[i] && c <= self.above[i]
                    });
                    if feasible && !self.known(n) {
                        self.vertices.extend_from_slice(&self.cand);
                        self.count += 1;
                    }
                }
            }
            if !next_combination(&mut self.cables, n) {
                break;
            }
        }
    }

    /// The candidates of r = 2 in the order of [`Self::enumerate`] (cable pairs i < j
    /// lexicographically, then the bound patterns (t_min,i, t_min,j), (t_max,i, t_min,j),
    /// (t_min,i, t_max,j), (t_max,i, t_max,j)), with the same floating-point operations in the
    /// same order, so the same vertices bit for bit: the LU of the 2 × 2 N_S with partial
    /// pivoting written out, and each tension t_k = (t0_k + N_k1 λ1) + N_k2 λ2 of the four
    /// candidates of a pair tested in one branch-free loop over the cables; all n tensions are
    /// stored only for a candidate within bounds. The vertex list, the duplicate test and the
    /// mean are shared. Compiled for AVX2 as well, taken when the CPU has it: without fused
    /// multiply–adds (Rust does not contract `a * b + c`) both builds give the same bits.
    fn enumerate_planar(&mut self, ns: &NullSpace, lo: &[f64], hi: &[f64]) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU reports AVX2.
            return unsafe { self.enumerate_planar_avx2(ns, lo, hi) };
        }
        self.enumerate_planar_here(ns, lo, hi);
    }

    /// [`Self::enumerate_planar_here`] compiled for AVX2 (the four candidates of a pair in
    /// one 4-lane vector).
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn enumerate_planar_avx2(&mut self, ns: &NullSpace, lo: &[f64], hi: &[f64]) {
        self.enumerate_planar_here(ns, lo, hi);
    }

    /// The body of [`Self::enumerate_planar`], inlined into each build.
    #[inline(always)]
    fn enumerate_planar_here(&mut self, ns: &NullSpace, lo: &[f64], hi: &[f64]) {
        let n = ns.n;
        let (n0, n1) = ns.basis[..2 * n].split_at(n);
        let t0 = &ns.t0[..n];
        // Taken out of `self` while the vertex list grows (put back below; no allocation).
        let (below_v, above_v) = (
            std::mem::take(&mut self.below),
            std::mem::take(&mut self.above),
        );
        let (below, above) = (&below_v[..n], &above_v[..n]);
        for i in 0..n {
            for j in i + 1..n {
                // Rows (a, b) of cable i and (c, d) of cable j; the larger |first entry| leads.
                let (a, b, c, d) = (n0[i], n1[i], n0[j], n1[j]);
                let swap = c.abs() > a.abs();
                let (u00, u01, l10, a11) = if swap { (c, d, a, b) } else { (a, b, c, d) };
                if u00.abs() < PIVOT {
                    continue;
                }
                let f = l10 / u00;
                let u11 = a11 - f * u01;
                if u11.abs() < PIVOT {
                    continue;
                }
                // λ of the four bound patterns (the substitutions of [`Self::lu_solve`]).
                let (ri, rj) = (
                    [lo[i] - t0[i], hi[i] - t0[i]],
                    [lo[j] - t0[j], hi[j] - t0[j]],
                );
                let (mut x0, mut x1) = ([0.0; 4], [0.0; 4]);
                for pattern in 0..4 {
                    let (mut y0, mut y1) = (ri[pattern & 1], rj[pattern >> 1]);
                    if swap {
                        std::mem::swap(&mut y0, &mut y1);
                    }
                    y1 -= f * y0;
                    y1 /= u11;
                    y0 -= u01 * y1;
                    y0 /= u00;
                    (x0[pattern], x1[pattern]) = (y0, y1);
                }
                // Every cable for the four candidates at once, without early exits: a
                // branch-free loop (the exits mispredicted at nearly every candidate).
                let mut ok = [true; 4];
                for ((((&t, &p), &q), &below), &above) in
                    t0.iter().zip(n0).zip(n1).zip(below).zip(above)
                {
                    for s in 0..4 {
                        let c = t + p * x0[s] + q * x1[s];
                        ok[s] &= (c >= below) & (c <= above);
                    }
                }
                for pattern in 0..4 {
                    if ok[pattern] {
                        ns.tensions(&[x0[pattern], x1[pattern]], &mut self.cand);
                        if !self.known(n) {
                            self.vertices.extend_from_slice(&self.cand);
                            self.count += 1;
                        }
                    }
                }
            }
        }
        (self.below, self.above) = (below_v, above_v);
    }

    /// Whether the candidate equals a kept vertex.
    fn known(&self, n: usize) -> bool {
        self.vertices.chunks_exact(n).any(|v| {
            v.iter()
                .zip(&self.cand)
                .all(|(a, b)| (a - b).abs() <= SAME * a.abs().max(1.0))
        })
    }

    /// LU with partial pivoting of N_S (rows N_i, i ∈ S); false when dependent.
    fn factor(&mut self, ns: &NullSpace) -> bool {
        let (n, r) = (ns.n, ns.r());
        for (k, &i) in self.cables.iter().enumerate() {
            for j in 0..r {
                self.lu[k * r + j] = ns.basis[j * n + i];
            }
        }
        for col in 0..r {
            let mut p = col;
            for row in col + 1..r {
                if self.lu[row * r + col].abs() > self.lu[p * r + col].abs() {
                    p = row;
                }
            }
            if self.lu[p * r + col].abs() < PIVOT {
                return false;
            }
            self.piv[col] = p;
            if p != col {
                for j in 0..r {
                    self.lu.swap(p * r + j, col * r + j);
                }
            }
            let d = self.lu[col * r + col];
            for row in col + 1..r {
                let f = self.lu[row * r + col] / d;
                self.lu[row * r + col] = f;
                for j in col + 1..r {
                    self.lu[row * r + j] -= f * self.lu[col * r + j];
                }
            }
        }
        true
    }

    /// Solves N_S λ = `lambda` in place with the factors of [`Self::factor`].
    fn lu_solve(&mut self, r: usize) {
        let x = &mut self.lambda;
        for col in 0..r {
            x.swap(col, self.piv[col]);
        }
        for row in 0..r {
            for j in 0..row {
                x[row] -= self.lu[row * r + j] * x[j];
            }
        }
        for row in (0..r).rev() {
            for j in row + 1..r {
                x[row] -= self.lu[row * r + j] * x[j];
            }
            x[row] /= self.lu[row * r + row];
        }
    }
}

/// The vertex centroid of `p` and the number of distinct vertices, by the r = 2 path
/// (`planar`) or by the general enumeration (the reference); `None` when the null space cannot
/// be computed or no vertex is found. For the tests comparing both paths (also on issue 26's
/// fixture, `benches/tests/issue_26.rs`); the solver's answer is [`crate::Method::VertexCentroid`].
#[doc(hidden)]
pub fn vertex_centroid_by(p: &TensionProblem, planar: bool) -> Option<(Vec<f64>, usize)> {
    let mut ns = NullSpace::default();
    ns.compute(p.wrench_matrix, p.external_wrench).ok()?;
    let mut vc = VertexCentroid::default();
    let mut t = vec![0.0; ns.n];
    let path = if planar { Path::Planar } else { Path::General };
    vc.solve_with(&ns, p.bounds, &mut t, path).ok()?;
    Some((t, vc.count))
}

/// The next r-subset of 0..n in lexicographic order; false after the last.
fn next_combination(c: &mut [usize], n: usize) -> bool {
    let r = c.len();
    let mut k = r;
    while k > 0 {
        k -= 1;
        if c[k] < n - r + k {
            c[k] += 1;
            for j in k + 1..r {
                c[j] = c[j - 1] + 1;
            }
            return true;
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;
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

    /// A problem at redundancy 2 (n = m + 2 cables, m = 1…8), of one of the degenerate kinds:
    /// 0 random; 1 integer W, tensions and bounds (degenerate vertices: 3+ lines through a
    /// point); 2 repeated and scaled columns of W (coincident and parallel constraints);
    /// 3 fixed cables (t_min = t_max: segments, single points) and infinite t_max; 4 a cable
    /// alone in a row of W (a zero null-space row: its tension is fixed); 5 tight bounds (thin
    /// polygons, points). The wrench is balanced by tensions within the bounds, or pushed away
    /// (empty sets).
    fn planar_problem(seed: u64) -> (DMatrix<f64>, DVector<f64>, TensionBounds) {
        let mut g = Rng(seed);
        let m = 1 + g.below(8);
        let n = m + 2;
        let kind = g.below(6);
        let mut w = if kind == 1 {
            DMatrix::from_fn(m, n, |_, _| g.below(3) as f64 - 1.0)
        } else {
            DMatrix::from_fn(m, n, |_, _| g.range(-1.0, 1.0))
        };
        if kind == 2 && n >= 3 {
            let (a, b) = (g.below(n), g.below(n));
            let s = if g.unit() < 0.5 {
                1.0
            } else {
                g.range(-3.0, 3.0)
            };
            let col = w.column(a) * s;
            w.set_column(b, &col);
        }
        if kind == 4 {
            let (row, k) = (g.below(m), g.below(n));
            for j in 0..n {
                w[(row, j)] = if j == k { g.range(0.5, 2.0) } else { 0.0 };
            }
        }
        let (mut lo, mut hi) = (Vec::new(), Vec::new());
        for _ in 0..n {
            let l = if kind == 1 { 1.0 } else { g.range(0.5, 20.0) };
            lo.push(l);
            hi.push(match kind {
                1 => 4.0 + g.below(2) as f64,
                5 => l * (1.0 + g.range(0.001, 0.1)),
                _ => l + g.range(10.0, 1000.0),
            });
        }
        if kind == 3 {
            for _ in 0..1 + g.below(2) {
                let i = g.below(n);
                hi[i] = lo[i];
            }
            if g.unit() < 0.5 {
                hi[g.below(n)] = f64::INFINITY;
            }
        }
        let t = DVector::from_fn(n, |i, _| {
            if kind == 1 {
                1.0 + g.below(4) as f64
            } else if hi[i].is_finite() {
                g.range(lo[i], hi[i])
            } else {
                lo[i] + g.range(0.0, 2000.0)
            }
        });
        let mut we = -(&w * &t);
        if g.unit() < 0.25 {
            let mag = we.amax().max(10.0) * g.range(0.01, 1.0);
            we.iter_mut().for_each(|v| *v += mag * g.range(-1.0, 1.0));
        }
        (w, we, TensionBounds::new(lo, hi).unwrap())
    }

    /// Both paths on one problem: the same verdict, the same number of distinct vertices and
    /// the same centroid bit for bit.
    /// The baseline and the AVX2 build of the r = 2 path give the same bits (on a CPU without
    /// AVX2 both runs take the baseline build).
    fn planar_builds_agree() {
        for seed in 0..3000u64 {
            let (w, we, b) = planar_problem(seed);
            let p = TensionProblem::new(&w, &we, &b);
            let mut ns = NullSpace::default();
            if ns.compute(p.wrench_matrix, p.external_wrench).is_err() {
                continue;
            }
            let run = |path| {
                let mut vc = VertexCentroid::default();
                let mut t = vec![0.0; ns.n];
                let ok = vc.solve_with(&ns, p.bounds, &mut t, path).is_ok();
                (
                    ok,
                    vc.count,
                    t.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                )
            };
            assert_eq!(run(Path::Planar), run(Path::PlanarPortable), "seed {seed}");
        }
    }

    fn same_on(w: &DMatrix<f64>, we: &DVector<f64>, b: &TensionBounds) -> Result<(), String> {
        let p = TensionProblem::new(w, we, b);
        let (fast, reference) = (vertex_centroid_by(&p, true), vertex_centroid_by(&p, false));
        let bits = |x: &Option<(Vec<f64>, usize)>| {
            x.as_ref()
                .map(|(t, k)| (t.iter().map(|v| v.to_bits()).collect::<Vec<_>>(), *k))
        };
        if bits(&fast) == bits(&reference) {
            Ok(())
        } else {
            Err(format!("planar {fast:?} vs enumeration {reference:?}"))
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(600))]

        /// The r = 2 path gives the enumeration's vertices and centroid, bit for bit.
        #[test]
        fn planar_path_is_the_enumeration(seed in any::<u64>()) {
            let (w, we, b) = planar_problem(seed);
            prop_assert!(same_on(&w, &we, &b).is_ok(), "seed {seed}: {:?}", same_on(&w, &we, &b));
        }
    }

    /// Every kind of problem occurs with vertices, and with empty sets; both paths agree.
    #[test]
    fn planar_path_on_every_kind() {
        planar_builds_agree();
        let (mut found, mut empty) = (0, 0);
        for seed in 0..3000u64 {
            let (w, we, b) = planar_problem(seed);
            same_on(&w, &we, &b).unwrap_or_else(|e| panic!("seed {seed}: {e}"));
            match vertex_centroid_by(&TensionProblem::new(&w, &we, &b), true) {
                Some(_) => found += 1,
                None => empty += 1,
            }
        }
        assert!(
            found > 1000 && empty > 300,
            "{found} with vertices, {empty} without"
        );
    }

    /// t1 + t2 + t3 = 6 in [1, 4]: the triangle (4, 1, 1), (1, 4, 1), (1, 1, 4), each corner
    /// degenerate (three bounds active at r = 2, found from three pairs of cables) and kept
    /// once: the centroid is (2, 2, 2).
    #[test]
    fn degenerate_triangle_by_hand() {
        let w = DMatrix::from_row_slice(1, 3, &[1.0, 1.0, 1.0]);
        let we = DVector::from_element(1, -6.0);
        let b = TensionBounds::uniform(3, 1.0, 4.0).unwrap();
        for planar in [true, false] {
            let (t, k) = vertex_centroid_by(&TensionProblem::new(&w, &we, &b), planar).unwrap();
            assert_eq!(k, 3);
            for v in t {
                assert!((v - 2.0).abs() <= 1e-12, "{v}");
            }
        }
    }

    #[test]
    fn combinations_and_counts() {
        let mut c = vec![0, 1];
        let mut seen = 1;
        while next_combination(&mut c, 5) {
            seen += 1;
        }
        assert_eq!(seen, 10);
        assert_eq!(candidate_bases(8, 2), 28 * 4);
        assert_eq!(candidate_bases(6, 0), 1);
        let mut none: Vec<usize> = vec![];
        assert!(!next_combination(&mut none, 3));
    }
}
