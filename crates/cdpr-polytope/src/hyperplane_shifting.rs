//! # Hyperplane shifting method
//!
//! The available wrench set AWS = {W t : t_min ≤ t ≤ t_max} is a zonotope: the Minkowski sum of
//! the segments [t_min,j w_j, t_max,j w_j]. Each of its facets is parallel to DOF − 1 linearly
//! independent columns of W. For every such subset S the unit normal **c** orthogonal to the
//! columns of S gives the two facets ±**c**, each shifted as far out as the box allows:
//!
//! ```text
//!     d₊(c) = Σ_j max(c·w_j t_min,j , c·w_j t_max,j)      facet  c·w ≤ d₊
//!     d₋(c) = Σ_j max(−c·w_j t_min,j , −c·w_j t_max,j)    facet −c·w ≤ d₋
//! ```
//!
//! (the sums run over all n columns; in exact arithmetic the columns of S contribute zero; they
//! are summed anyway when S is ill-conditioned, a pivot below 10⁻³, so that the half-space stays
//! supporting when c is orthogonal to them only up to round-off). d₊(c) is exactly the support function of the AWS in
//! direction c, so every half-space produced is a supporting one. The facets of the zonotope are
//! spanned by its *generators* w_j (t_max,j − t_min,j): a cable with t_min = t_max only
//! translates the set, so subsets are drawn from the other cables, and when those span the
//! wrench space every half-space is a true facet. (If they do not, the AWS is flat: a second pass
//! over all columns gives supporting half-spaces whose intersection is the flat set.) The method
//! enumerates C(n, DOF − 1) subsets: 56 for 8 cables in 6 DOF.
//!
//! **Implementation.** The normal is the null vector of the (DOF−1) × DOF matrix whose rows are
//! the subset's columns, found by Gaussian elimination with complete pivoting on fixed-size stack
//! arrays. Subsets are enumerated in lexicographic order and the eliminated rows of a common
//! prefix are reused, so each subset costs about one row elimination: no heap allocation at all.
//! Dependent subsets (parallel cables, singular poses) are skipped; if no subset yields a normal
//! with some column off its hyperplane, W has rank < DOF and [`PolytopeError::LowerDimensional`]
//! is returned. An infinite t_max is allowed: the half-spaces it pushes to infinity are dropped
//! (the AWS is then an unbounded polyhedron).
//!
//! ## References
//! - S. Bouchard, B. Moore, C. Gosselin, *On the ability of a cable-driven robot to generate a
//!   prescribed set of wrenches*, ASME IDETC 2008 (J. Mech. Robot. 2, 2010): hyperplane shifting.
//! - M. Gouttefarde, S. Krut, *Characterization of parallel manipulator available wrench set
//!   facets*, ARK 2010: facets of the AWS are parallel to DOF − 1 independent columns of W.
//! - Krut, Company & Pierrot 2004 eq. (3): the box of admissible tensions.

use crate::PolytopeError;
use crate::available_wrench_set::{AvailableWrenchSet, Facet};
use crate::input::{self, MAX_DOF};
use cdpr_tension::TensionBounds;
use nalgebra::{DMatrix, DVector};

/// Relative pivot below which a subset of columns counts as linearly dependent.
const PIVOT_TOL: f64 = 1e-10;
/// Smallest pivot (columns scaled to max|W_ij| = 1) for which a subset's own columns are left
/// out of the support sum (their |c · w_j| is then pure round-off, ~10⁻¹² max|W_ij|).
const WELL_CONDITIONED_PIVOT: f64 = 1e-3;
/// Relative |c·w_j| below which column j counts as lying in the hyperplane (exact zero).
const IN_PLANE_TOL: f64 = 1e-13;
/// Relative |c·w_j| a column must exceed to prove W has a direction off the hyperplane.
const OFF_PLANE_TOL: f64 = 1e-10;

/// The H-representation of the AWS by hyperplane shifting: unit normals, duplicates merged,
/// vertices for DOF 2 and 3 when every t_max is finite.
///
/// Returns the *available* set {W t}; use [`AvailableWrenchSet::can_balance`] for external
/// wrenches (W t + w_ext = 0 ⇔ −w_ext ∈ AWS).
///
/// ```
/// use cdpr_polytope::hyperplane_shifting::available_wrench_set;
/// use cdpr_tension::TensionBounds;
/// use nalgebra::{dmatrix, dvector};
/// // Two orthogonal cable pairs: the AWS is the square [−9, 9]².
/// let w = dmatrix![1.0, -1.0, 0.0, 0.0; 0.0, 0.0, 1.0, -1.0];
/// let aws = available_wrench_set(&w, &TensionBounds::uniform(4, 1.0, 10.0).unwrap()).unwrap();
/// assert_eq!(aws.facets().len(), 4);
/// assert!(aws.facets().iter().all(|f| (f.offset - 9.0).abs() < 1e-12));
/// assert!(aws.can_balance(&dvector![-9.0, 9.0]));
/// ```
pub fn available_wrench_set(
    w: &DMatrix<f64>,
    bounds: &TensionBounds,
) -> Result<AvailableWrenchSet, PolytopeError> {
    let (scale, _) = input::check(w, bounds)?;
    let dof = w.nrows();
    let mut raw = Vec::new();
    for_each_halfspace(w, bounds, |c, d| {
        raw.push(Facet {
            normal: DVector::from_column_slice(c),
            offset: d,
        })
    })?;
    let bounded = bounds.max().iter().all(|x| x.is_finite());
    Ok(AvailableWrenchSet::from_halfspaces(
        dof, raw, bounded, scale,
    ))
}

/// Calls `f(n, d)` for every supporting half-space `n · w ≤ d` of the AWS found by hyperplane
/// shifting (unit n, finite d, duplicates *not* merged), without allocating. Returns the number
/// of half-spaces visited.
///
/// This is the engine behind [`crate::CapacityMargin`] and [`crate::IsotropicForce`]; use it
/// for custom indices. If it returns an error, half-spaces already visited must be discarded.
/// For many poses with the same bounds, [`HyperplaneShifting`] checks the bounds only once.
pub fn for_each_halfspace<F: FnMut(&[f64], f64)>(
    w: &DMatrix<f64>,
    bounds: &TensionBounds,
    f: F,
) -> Result<usize, PolytopeError> {
    input::check_shape(w.nrows(), w.ncols(), bounds)?;
    run(w, bounds.min().as_slice(), bounds.max().as_slice(), f)
}

/// Hyperplane shifting with its wrench-space dimension and tension bounds checked once, for
/// sweeps over many poses: each call then only checks the shape and finiteness of W (one pass
/// over its entries) before the enumeration.
///
/// ```
/// use cdpr_polytope::hyperplane_shifting::HyperplaneShifting;
/// use cdpr_tension::TensionBounds;
/// use nalgebra::dmatrix;
/// let hs = HyperplaneShifting::new(2, &TensionBounds::uniform(4, 1.0, 10.0).unwrap()).unwrap();
/// let w = dmatrix![1.0, -1.0, 0.0, 0.0; 0.0, 0.0, 1.0, -1.0];
/// let mut radius = f64::INFINITY;
/// let count = hs.for_each_halfspace(&w, |_, d| radius = radius.min(d)).unwrap();
/// assert_eq!((count, radius), (8, 9.0)); // the square [−9, 9]², each facet found twice
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct HyperplaneShifting {
    dof: usize,
    min: Vec<f64>,
    max: Vec<f64>,
    bounded: bool,
}

impl HyperplaneShifting {
    /// An enumerator for DOF × n wrench matrices with these bounds (n = `bounds.len()`).
    /// Errors if DOF is not in 1..=6.
    pub fn new(dof: usize, bounds: &TensionBounds) -> Result<Self, PolytopeError> {
        input::check_shape(dof, bounds.len(), bounds)?;
        Ok(Self {
            dof,
            min: bounds.min().as_slice().to_vec(),
            max: bounds.max().as_slice().to_vec(),
            bounded: bounds.max().iter().all(|x| x.is_finite()),
        })
    }

    /// Rows of the wrench matrices accepted.
    pub fn dof(&self) -> usize {
        self.dof
    }

    /// Columns (cables) of the wrench matrices accepted.
    pub fn cables(&self) -> usize {
        self.min.len()
    }

    /// [`for_each_halfspace`] with the checked bounds; errors if W is not DOF × n.
    #[inline]
    pub fn for_each_halfspace<F: FnMut(&[f64], f64)>(
        &self,
        w: &DMatrix<f64>,
        f: F,
    ) -> Result<usize, PolytopeError> {
        self.for_each_pair(w, singles(f))
    }

    /// The pairs of opposite half-spaces, see [`for_each_pair`].
    #[inline]
    pub(crate) fn for_each_pair<F: FnMut(&[f64], f64, f64) -> usize>(
        &self,
        w: &DMatrix<f64>,
        f: F,
    ) -> Result<usize, PolytopeError> {
        if w.nrows() != self.dof {
            return Err(PolytopeError::DimensionMismatch {
                what: "rows of W vs the prepared enumerator",
                expected: self.dof,
                found: w.nrows(),
            });
        }
        if w.ncols() != self.min.len() {
            return Err(PolytopeError::DimensionMismatch {
                what: "columns of W vs the prepared tension bounds",
                expected: self.min.len(),
                found: w.ncols(),
            });
        }
        for_each_pair(w, &self.min, &self.max, self.bounded, f)
    }
}

/// Adapts a pair callback (see [`for_each_pair`]) to single half-spaces, dropping those at
/// infinity.
#[inline(always)]
fn singles<F: FnMut(&[f64], f64)>(mut f: F) -> impl FnMut(&[f64], f64, f64) -> usize {
    move |c: &[f64], dp: f64, dm: f64| {
        let mut visited = 0;
        if dp < f64::INFINITY {
            f(c, dp);
            visited += 1;
        }
        if dm < f64::INFINITY {
            let mut neg = [0.0f64; MAX_DOF];
            for (x, y) in neg.iter_mut().zip(c) {
                *x = -y;
            }
            f(&neg[..c.len()], dm);
            visited += 1;
        }
        visited
    }
}

/// The enumeration on checked shapes: finiteness of W, rank test, dispatch on DOF.
#[inline]
fn run<F: FnMut(&[f64], f64)>(
    w: &DMatrix<f64>,
    tmin: &[f64],
    tmax: &[f64],
    f: F,
) -> Result<usize, PolytopeError> {
    let bounded = tmax.iter().all(|x| x.is_finite());
    for_each_pair(w, tmin, tmax, bounded, singles(f))
}

/// The engine's interface: calls `f(c, d₊, d₋)` once per independent subset of DOF − 1
/// columns with a column off its hyperplane, for the pair of half-spaces `c · w ≤ d₊` and
/// `−c · w ≤ d₋` (unit c); an offset pushed to infinity by an infinite t_max is passed as +∞.
/// `f` returns how many half-spaces it counted; the sum is returned. `bounded` must be true
/// iff every t_max is finite (shapes are checked by the caller).
#[inline]
pub(crate) fn for_each_pair<F: FnMut(&[f64], f64, f64) -> usize>(
    w: &DMatrix<f64>,
    tmin: &[f64],
    tmax: &[f64],
    bounded: bool,
    f: F,
) -> Result<usize, PolytopeError> {
    let wmax = input::finite_amax(w.as_slice())?;
    let (m, n) = w.shape();
    if m - 1 > n || wmax == 0.0 {
        return Err(PolytopeError::LowerDimensional {
            rank: input::numerical_rank(w),
            dof: m,
        });
    }
    let ws = w.as_slice();
    // A cable with t_min = t_max is a zero generator: it translates the zonotope but spans no
    // facet. First pass: subsets of generators only (the exact facets when they span the
    // wrench space). If they do not (a lower-dimensional AWS), no half-space was reported and
    // a second pass over all columns gives supporting half-spaces of the flat set.
    let has_fixed = tmin.iter().zip(tmax).any(|(lo, hi)| hi <= lo);
    let mut f = f;
    let mut tally = dispatch(m, bounded, ws, tmin, tmax, wmax, has_fixed, &mut f);
    if has_fixed && !tally.proper && tally.overflow.is_none() {
        tally = flat_pass(m, bounded, ws, tmin, tmax, wmax, &mut f);
    }
    if let Some(value) = tally.overflow {
        return Err(PolytopeError::Overflow { value });
    }
    if !tally.proper {
        return Err(PolytopeError::LowerDimensional {
            rank: input::numerical_rank(w).min(m - 1),
            dof: m,
        });
    }
    Ok(tally.visited)
}

/// The engine for the wrench-space dimension m (fixed-size arrays per dimension).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn dispatch<F: FnMut(&[f64], f64, f64) -> usize>(
    m: usize,
    bounded: bool,
    ws: &[f64],
    tmin: &[f64],
    tmax: &[f64],
    wmax: f64,
    generators_only: bool,
    f: &mut F,
) -> Tally {
    let g = generators_only;
    match (m, bounded) {
        (1, true) => engine::<1, true, F>(ws, tmin, tmax, wmax, g, f),
        (2, true) => engine::<2, true, F>(ws, tmin, tmax, wmax, g, f),
        (3, true) => engine::<3, true, F>(ws, tmin, tmax, wmax, g, f),
        (4, true) => engine::<4, true, F>(ws, tmin, tmax, wmax, g, f),
        (5, true) => engine::<5, true, F>(ws, tmin, tmax, wmax, g, f),
        (_, true) => engine::<MAX_DOF, true, F>(ws, tmin, tmax, wmax, g, f),
        (1, false) => engine::<1, false, F>(ws, tmin, tmax, wmax, g, f),
        (2, false) => engine::<2, false, F>(ws, tmin, tmax, wmax, g, f),
        (3, false) => engine::<3, false, F>(ws, tmin, tmax, wmax, g, f),
        (4, false) => engine::<4, false, F>(ws, tmin, tmax, wmax, g, f),
        (5, false) => engine::<5, false, F>(ws, tmin, tmax, wmax, g, f),
        (_, false) => engine::<MAX_DOF, false, F>(ws, tmin, tmax, wmax, g, f),
    }
}

/// The second pass over all columns for a flat AWS (rare: kept out of line so that the hot
/// path holds one copy of the engine per dimension).
#[cold]
#[inline(never)]
fn flat_pass<F: FnMut(&[f64], f64, f64) -> usize>(
    m: usize,
    bounded: bool,
    ws: &[f64],
    tmin: &[f64],
    tmax: &[f64],
    wmax: f64,
    f: &mut F,
) -> Tally {
    dispatch(m, bounded, ws, tmin, tmax, wmax, false, f)
}

/// What one enumeration found.
struct Tally {
    /// Half-spaces counted by the callback.
    visited: usize,
    /// Some subset had a column off its hyperplane (W has rank DOF).
    proper: bool,
    /// A non-finite offset caused by overflow of |W|·|t| (not by an infinite t_max).
    overflow: Option<f64>,
}

/// The enumeration for a wrench space of dimension M (fixed so that loops unroll); BOUNDED:
/// every t_max is finite (then the offsets are accumulated without branches).
///
/// Subsets of M − 1 columns are visited in lexicographic order; `red[l]` holds column idx[l]
/// scaled by 1/max|W_ij| (so that the elimination neither overflows nor underflows) and reduced
/// by the rows above it, `piv[l]` its pivot component and `inv[l]` the pivot's reciprocal. Rows
/// of a prefix shared with the previous subset are kept. The offsets d± then need one dot
/// product per column outside the subset (and inside it too for an ill-conditioned subset).
/// `generators_only`: cables with t_min = t_max neither enter a subset nor
/// count as off the hyperplane.
#[inline(always)]
fn engine<const M: usize, const BOUNDED: bool, F: FnMut(&[f64], f64, f64) -> usize>(
    ws: &[f64],
    tmin: &[f64],
    tmax: &[f64],
    wmax: f64,
    generators_only: bool,
    f: &mut F,
) -> Tally {
    let k = M - 1;
    let n = tmin.len();
    let scale = {
        let s = 1.0 / wmax;
        if s.is_finite() { s } else { 2f64.powi(1022) }
    };
    let pivot_tol = PIVOT_TOL * (wmax * scale);
    let in_plane = IN_PLANE_TOL * wmax;
    let off_plane = OFF_PLANE_TOL * wmax;
    let mut tally = Tally {
        visited: 0,
        proper: false,
        overflow: None,
    };
    let mut idx = [0usize; M];
    for (i, x) in idx.iter_mut().enumerate().take(k) {
        *x = i;
    }
    let mut red = [[0.0f64; M]; M];
    let mut inv = [0.0f64; M];
    let mut piv = [0usize; M];
    // min_pivot[l]: the smallest pivot of levels < l (columns scaled to max|W_ij| = 1).
    let mut min_pivot = [1.0f64; M];
    // used[l]: bit mask of the pivot components of levels < l.
    let mut used = [0u32; 8];
    let mut valid = 0usize; // leading levels reduced and independent for the current idx
    let mut first_changed = 0usize;
    loop {
        let start = valid.min(first_changed);
        let mut ok = true;
        for l in start..k {
            if generators_only && tmax[idx[l]] <= tmin[idx[l]] {
                ok = false; // a fixed cable spans no facet
                valid = l;
                break;
            }
            let base = idx[l] * M;
            let mut r = [0.0f64; M];
            for (x, y) in r.iter_mut().zip(&ws[base..base + M]) {
                *x = y * scale;
            }
            for i in 0..l {
                let p = piv[i];
                let factor = r[p] * inv[i];
                // r[p] becomes exactly 0; selected rather than stored at index p (see below).
                for (j, (x, y)) in r.iter_mut().zip(red[i].iter()).enumerate() {
                    *x = if j == p { 0.0 } else { *x - factor * y };
                }
            }
            let mask = used[l];
            let mut best = 0usize;
            let mut best_abs = -1.0f64;
            for (j, &x) in r.iter().enumerate() {
                if mask & (1 << j) == 0 && x.abs() > best_abs {
                    best = j;
                    best_abs = x.abs();
                }
            }
            // Written so that a NaN pivot also counts as dependent.
            if best_abs.partial_cmp(&pivot_tol) != Some(std::cmp::Ordering::Greater) {
                ok = false;
                valid = l;
                break;
            }
            red[l] = r;
            piv[l] = best;
            min_pivot[l + 1] = min_pivot[l].min(best_abs);
            inv[l] = 1.0 / r[best];
            used[l + 1] = mask | (1 << best);
        }
        if ok {
            valid = k;
            // Null vector: the free component (the one never pivoted) set to 1, back substitution.
            // c[piv[i]] is still 0 when row i is summed, so the sum may run over all components.
            // Components are written by comparison, not by a computed index: a store at a
            // run-time index followed by a vector load of c stalls store forwarding.
            let free = (!used[k]).trailing_zeros() as usize;
            let mut c = [0.0f64; M];
            for (j, x) in c.iter_mut().enumerate() {
                *x = if j == free { 1.0 } else { 0.0 };
            }
            for i in (0..k).rev() {
                let mut s = 0.0;
                for j in 0..M {
                    s += red[i][j] * c[j];
                }
                let value = -s * inv[i];
                for (j, x) in c.iter_mut().enumerate() {
                    if j == piv[i] {
                        *x = value;
                    }
                }
            }
            let mut norm2 = 0.0;
            for x in c {
                norm2 += x * x;
            }
            // norm2 ≥ 1; a non-finite one (extreme round-off) skips the subset.
            if norm2.is_finite() {
                let inv_norm = 1.0 / norm2.sqrt();
                for x in c.iter_mut() {
                    *x *= inv_norm;
                }
                // Shifted offsets d± over *every* column, eq. of the module docs. The subset's
                // own columns contribute only round-off, but c from an ill-conditioned subset is
                // orthogonal to them only approximately: leaving them out would make the
                // half-space cut off box corners. The off-plane test looks at the other columns
                // (generators with a range, on the first pass) only.
                // With every pivot ≥ 10⁻³ (scaled columns), |c · w_j| of an own column is below
                // ~10⁻¹² max|W_ij|, far under the 10⁻⁹ tolerance of membership: skip the dot.
                let sum_own = min_pivot[k] < WELL_CONDITIONED_PIVOT;
                let (mut dp, mut dm, mut off) = (0.0f64, 0.0f64, 0.0f64);
                let (mut unbounded_p, mut unbounded_m) = (false, false);
                let mut in_subset = 0usize;
                for j in 0..n {
                    let own = in_subset < k && idx[in_subset] == j;
                    if own {
                        in_subset += 1;
                        if !sum_own {
                            continue;
                        }
                    }
                    let col = &ws[j * M..j * M + M];
                    let mut p = 0.0;
                    for i in 0..M {
                        p += c[i] * col[i];
                    }
                    let (lo, hi) = (tmin[j], tmax[j]);
                    if !own && (!generators_only || hi > lo) {
                        off = fmax(off, p.abs());
                    }
                    if BOUNDED {
                        // Branch-free: an in-plane column (|p| ~ round-off) adds round-off only.
                        let (a, b) = (p * hi, p * lo);
                        dp += fmax(a, b);
                        dm -= fmin(a, b);
                    } else {
                        if hi == f64::INFINITY && (own || p.abs() <= in_plane) {
                            // In the plane up to round-off: only the finite end counts.
                            dp += fmax(p * lo, 0.0);
                            dm += fmax(-p * lo, 0.0);
                            continue;
                        }
                        if p > 0.0 {
                            dp += p * hi;
                            dm -= p * lo;
                            unbounded_p |= hi == f64::INFINITY;
                        } else {
                            dp += p * lo;
                            dm -= p * hi;
                            unbounded_m |= hi == f64::INFINITY;
                        }
                    }
                }
                if off > off_plane {
                    tally.proper = true;
                    if unbounded_p {
                        dp = f64::INFINITY; // pushed to infinity by an infinite t_max
                    } else if !dp.is_finite() {
                        tally.overflow = Some(dp);
                        return tally;
                    }
                    if unbounded_m {
                        dm = f64::INFINITY;
                    } else if !dm.is_finite() {
                        tally.overflow = Some(dm);
                        return tally;
                    }
                    tally.visited += f(&c[..], dp, dm);
                }
            }
        }
        match next_combination(&mut idx[..k], n) {
            Some(i) => first_changed = i,
            None => break,
        }
    }
    tally
}

/// max(a, b) as one instruction (NaN handling left to the callers' finiteness checks).
#[inline(always)]
fn fmax(a: f64, b: f64) -> f64 {
    if a > b { a } else { b }
}

/// min(a, b) as one instruction.
#[inline(always)]
fn fmin(a: f64, b: f64) -> f64 {
    if a < b { a } else { b }
}

/// Next k-combination in lexicographic order; returns the first position that changed.
#[inline]
fn next_combination(idx: &mut [usize], n: usize) -> Option<usize> {
    let k = idx.len();
    let mut i = k;
    while i > 0 {
        i -= 1;
        if idx[i] < n - k + i {
            idx[i] += 1;
            for j in i + 1..k {
                idx[j] = idx[j - 1] + 1;
            }
            return Some(i);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use nalgebra::dmatrix;

    #[test]
    fn square_from_two_cable_pairs() {
        // Hand-derived: columns ±e_x, ±e_y with t ∈ [1, 10]: x = t1 − t2 ∈ [−9, 9], same for y.
        let w = dmatrix![1.0, -1.0, 0.0, 0.0; 0.0, 0.0, 1.0, -1.0];
        let b = TensionBounds::uniform(4, 1.0, 10.0).unwrap();
        let aws = available_wrench_set(&w, &b).unwrap();
        assert_eq!(aws.facets().len(), 4);
        for f in aws.facets() {
            assert_relative_eq!(f.offset, 9.0, epsilon = 1e-12);
        }
        assert_eq!(aws.vertices().unwrap().len(), 4);
    }

    #[test]
    fn unsymmetric_per_cable_bounds_shift_the_facets() {
        // One cable per direction pair: t1 ∈ [0, 5] along +x, t2 ∈ [2, 3] along −x,
        // t3 ∈ [1, 4] along y: x ∈ [−3, 3], y ∈ [1, 4]. Offsets: +x: 3, −x: 3, +y: 4, −y: −1.
        let w = dmatrix![1.0, -1.0, 0.0; 0.0, 0.0, 1.0];
        let b = TensionBounds::new(vec![0.0, 2.0, 1.0], vec![5.0, 3.0, 4.0]).unwrap();
        let aws = available_wrench_set(&w, &b).unwrap();
        let offset = |nx: f64, ny: f64| {
            aws.facets()
                .iter()
                .find(|f| (f.normal[0] - nx).abs() < 1e-12 && (f.normal[1] - ny).abs() < 1e-12)
                .map(|f| f.offset)
        };
        assert_relative_eq!(offset(1.0, 0.0).unwrap(), 3.0, epsilon = 1e-12);
        assert_relative_eq!(offset(-1.0, 0.0).unwrap(), 3.0, epsilon = 1e-12);
        assert_relative_eq!(offset(0.0, 1.0).unwrap(), 4.0, epsilon = 1e-12);
        assert_relative_eq!(offset(0.0, -1.0).unwrap(), -1.0, epsilon = 1e-12);
        assert_eq!(aws.facets().len(), 4);
    }

    #[test]
    fn rank_deficient_w_is_reported() {
        // All columns along x: the AWS is a segment of the x axis.
        let w = dmatrix![1.0, -1.0, 2.0; 0.0, 0.0, 0.0];
        let b = TensionBounds::uniform(3, 1.0, 2.0).unwrap();
        assert_eq!(
            available_wrench_set(&w, &b),
            Err(PolytopeError::LowerDimensional { rank: 1, dof: 2 })
        );
        // 3-D: all columns in the xy plane.
        let w = dmatrix![1.0, 0.0, -1.0, 1.0; 0.0, 1.0, -1.0, 1.0; 0.0, 0.0, 0.0, 0.0];
        let b = TensionBounds::uniform(4, 1.0, 2.0).unwrap();
        assert_eq!(
            available_wrench_set(&w, &b),
            Err(PolytopeError::LowerDimensional { rank: 2, dof: 3 })
        );
        // Zero matrix and too few columns.
        let b2 = TensionBounds::uniform(2, 1.0, 2.0).unwrap();
        assert!(matches!(
            available_wrench_set(&DMatrix::zeros(3, 2), &b2),
            Err(PolytopeError::LowerDimensional { rank: 0, .. })
        ));
        let w = dmatrix![1.0; 0.0; 0.0; 0.0];
        let b1 = TensionBounds::uniform(1, 1.0, 2.0).unwrap();
        assert!(matches!(
            available_wrench_set(&w, &b1),
            Err(PolytopeError::LowerDimensional { .. })
        ));
    }

    #[test]
    fn dependent_subsets_are_skipped_and_duplicates_merged() {
        // Two parallel cables along +x (a dependent pair in 3-D subsets) plus a basis.
        let w = dmatrix![1.0, 2.0, 0.0, 0.0, -1.0;
                         0.0, 0.0, 1.0, 0.0, -1.0;
                         0.0, 0.0, 0.0, 1.0, -1.0];
        let b = TensionBounds::uniform(5, 0.0, 1.0).unwrap();
        let aws = available_wrench_set(&w, &b).unwrap();
        // Every facet normal is unique and every box corner maps inside.
        for (i, f) in aws.facets().iter().enumerate() {
            for g in &aws.facets()[i + 1..] {
                assert!((&f.normal - &g.normal).amax() > 1e-6);
            }
        }
        for bits in 0..32u32 {
            let t = DVector::from_fn(5, |j, _| f64::from((bits >> j) & 1));
            assert!(aws.contains(&(&w * t)));
        }
    }

    #[test]
    fn infinite_t_max_drops_facets() {
        // Two cables at ±45° upward, t ≥ 1: the AWS is the cone with apex (0, √2).
        let s = 0.5f64.sqrt();
        let w = dmatrix![s, -s; s, s];
        let b = TensionBounds::new(vec![1.0, 1.0], vec![f64::INFINITY, f64::INFINITY]).unwrap();
        let aws = available_wrench_set(&w, &b).unwrap();
        assert_eq!(aws.facets().len(), 2);
        for f in aws.facets() {
            // Outward normals (±1, −1)/√2 and offset apex · n = −1.
            assert_relative_eq!(f.normal[1], -s, epsilon = 1e-12);
            assert_relative_eq!(f.offset, -1.0, epsilon = 1e-12);
        }
        assert!(aws.vertices().is_none());
    }

    #[test]
    fn one_dof_is_an_interval() {
        let w = dmatrix![1.0, -2.0];
        let b = TensionBounds::uniform(2, 1.0, 3.0).unwrap();
        let aws = available_wrench_set(&w, &b).unwrap();
        // t1 − 2 t2 ∈ [1 − 6, 3 − 2] = [−5, 1].
        assert_eq!(aws.facets().len(), 2);
        assert_relative_eq!(aws.facets()[0].offset, 5.0, epsilon = 1e-12); // normal −1
        assert_relative_eq!(aws.facets()[1].offset, 1.0, epsilon = 1e-12); // normal +1
    }

    #[test]
    fn bad_input_is_an_error() {
        let b = TensionBounds::uniform(2, 1.0, 3.0).unwrap();
        assert!(matches!(
            available_wrench_set(&dmatrix![1.0, f64::NAN; 0.0, 1.0], &b),
            Err(PolytopeError::NotFinite { index: 2, .. })
        ));
        assert!(matches!(
            available_wrench_set(&DMatrix::zeros(2, 3), &b),
            Err(PolytopeError::DimensionMismatch { .. })
        ));
        assert!(matches!(
            available_wrench_set(&DMatrix::zeros(7, 2), &b),
            Err(PolytopeError::UnsupportedDof { dof: 7 })
        ));
    }
}
