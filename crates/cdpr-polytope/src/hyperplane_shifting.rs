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
//! (the sums run over all n columns; the columns of S contribute zero). d₊(c) is exactly the
//! support function of the AWS in direction c, so every half-space produced is a supporting one;
//! when W has rank DOF each is a true facet. The method enumerates C(n, DOF − 1) subsets:
//! 56 for 8 cables in 6 DOF.
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
//! - Seed 001 (Krut et al. 2004) eq. (3): the box of admissible tensions.

use crate::PolytopeError;
use crate::available_wrench_set::{AvailableWrenchSet, Facet};
use crate::input::{self, MAX_DOF};
use cdpr_tension::TensionBounds;
use nalgebra::{DMatrix, DVector};

/// Relative pivot below which a subset of columns counts as linearly dependent.
const PIVOT_TOL: f64 = 1e-10;
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
pub fn for_each_halfspace<F: FnMut(&[f64], f64)>(
    w: &DMatrix<f64>,
    bounds: &TensionBounds,
    f: F,
) -> Result<usize, PolytopeError> {
    let (_, wmax) = input::check(w, bounds)?;
    let (m, n) = w.shape();
    let k = m - 1; // columns per subset
    let ws = w.as_slice();
    let (tmin, tmax) = (bounds.min().as_slice(), bounds.max().as_slice());
    if k > n || wmax == 0.0 {
        return Err(PolytopeError::LowerDimensional {
            rank: input::numerical_rank(w),
            dof: m,
        });
    }

    let (visited, proper) = match m {
        1 => engine::<1, F>(ws, n, tmin, tmax, wmax, f),
        2 => engine::<2, F>(ws, n, tmin, tmax, wmax, f),
        3 => engine::<3, F>(ws, n, tmin, tmax, wmax, f),
        4 => engine::<4, F>(ws, n, tmin, tmax, wmax, f),
        5 => engine::<5, F>(ws, n, tmin, tmax, wmax, f),
        _ => engine::<MAX_DOF, F>(ws, n, tmin, tmax, wmax, f),
    };
    if !proper {
        return Err(PolytopeError::LowerDimensional {
            rank: input::numerical_rank(w).min(m - 1),
            dof: m,
        });
    }
    Ok(visited)
}

/// The enumeration for a wrench space of dimension M (fixed so that loops unroll). Returns the
/// number of half-spaces visited and whether some subset had a column off its hyperplane.
#[inline]
fn engine<const M: usize, F: FnMut(&[f64], f64)>(
    ws: &[f64],
    n: usize,
    tmin: &[f64],
    tmax: &[f64],
    wmax: f64,
    mut f: F,
) -> (usize, bool) {
    let k = M - 1;
    let pivot_tol = PIVOT_TOL * wmax;
    let in_plane = IN_PLANE_TOL * wmax;
    let off_plane = OFF_PLANE_TOL * wmax;
    let mut visited = 0usize;
    let mut proper = false;
    let mut idx = [0usize; M];
    for (i, x) in idx.iter_mut().enumerate().take(k) {
        *x = i;
    }
    // red[l]: column idx[l] reduced by the rows above it; piv[l]: its pivot component.
    let mut red = [[0.0f64; M]; M];
    let mut piv = [0usize; M];
    let mut valid = 0usize; // leading levels reduced and independent for the current idx
    let mut first_changed = 0usize;
    loop {
        let start = valid.min(first_changed);
        let mut ok = true;
        for l in start..k {
            let col = &ws[idx[l] * M..idx[l] * M + M];
            let mut r = [0.0f64; M];
            r.copy_from_slice(col);
            for i in 0..l {
                let p = piv[i];
                let factor = r[p] / red[i][p];
                if factor != 0.0 {
                    for (x, y) in r.iter_mut().zip(red[i].iter()) {
                        *x -= factor * y;
                    }
                }
                r[p] = 0.0;
            }
            let mut best = 0usize;
            let mut best_abs = -1.0f64;
            for (j, &x) in r.iter().enumerate() {
                if !piv[..l].contains(&j) && x.abs() > best_abs {
                    best = j;
                    best_abs = x.abs();
                }
            }
            if best_abs <= pivot_tol {
                ok = false;
                valid = l;
                break;
            }
            red[l] = r;
            piv[l] = best;
        }
        if ok {
            valid = k;
            // Null vector: the remaining (free) component set to 1, back substitution.
            let mut c = [0.0f64; M];
            let free = (0..M).find(|j| !piv[..k].contains(j)).unwrap_or(0);
            c[free] = 1.0;
            for i in (0..k).rev() {
                let p = piv[i];
                let mut s = 0.0;
                for j in 0..M {
                    if j != p {
                        s += red[i][j] * c[j];
                    }
                }
                c[p] = -s / red[i][p];
            }
            let norm = c.iter().map(|x| x * x).sum::<f64>().sqrt();
            for x in c.iter_mut() {
                *x /= norm;
            }
            // Shifted offsets over all columns.
            let (mut dp, mut dm) = (0.0f64, 0.0f64);
            let mut off = 0.0f64;
            for (j, col) in ws.chunks_exact(M).enumerate() {
                let mut p = 0.0;
                for (a, b) in c.iter().zip(col) {
                    p += a * b;
                }
                if p.abs() <= in_plane {
                    continue;
                }
                off = off.max(p.abs());
                if p > 0.0 {
                    dp += p * tmax[j];
                    dm -= p * tmin[j];
                } else {
                    dp += p * tmin[j];
                    dm -= p * tmax[j];
                }
            }
            if off > off_plane {
                proper = true;
                if dp.is_finite() {
                    f(&c[..], dp);
                    visited += 1;
                }
                if dm.is_finite() {
                    for x in c.iter_mut() {
                        *x = -*x;
                    }
                    f(&c[..], dm);
                    visited += 1;
                }
            }
        }
        match next_combination(&mut idx[..k], n) {
            Some(i) => first_changed = i,
            None => break,
        }
    }
    (visited, proper)
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
