//! # Krut's vertex projection method (operational force polytope)
//!
//! Seed 001 §III computes the operational force polytope {W t : t_min ≤ t ≤ t_max} (W = Jₘᵀ) by
//! projecting the 2ⁿ vertices of the tension box onto the range of W and keeping, among all
//! hyperplanes through DOF projected vertices, those with every projected vertex on one side:
//!
//! 1. SVD W = U [S 0] Vᵀ and the 2ⁿ box vertices τ_vertex (eq. (3));
//! 2. τ_s = Vᵀ τ_vertex, eq. (8);
//! 3. τ_r = P τ_s, the first DOF components, eq. (9);
//! 4. for each of the C(2ⁿ, DOF) choices of DOF projected vertices, the hyperplane τ_rᵀ u_k = 1
//!    through them, u_k = T_k⁻¹ [1 … 1]ᵀ, eqs. (10)–(14). When T_k is singular and the points
//!    are affinely independent the hyperplane passes through the origin (the paper's second
//!    situation, a singular posture or a non-frontier): it is kept as a candidate `a · τ_r = 0`;
//! 5. border test (15): all projected vertices on one side (type 1: τ_rᵀ u_k ≤ 1, type 2: ≥ 1);
//!    a type-2 border means the origin is outside the polytope (the pose cannot balance a null
//!    perturbation);
//! 6. mapping to the operational space, eqs. (17)–(18): f = U S τ_r, so τ_rᵀ u ≤ 1 becomes
//!    fᵀ (U v_k) ≤ 1 with v_k = S⁻¹ u_k (the paper's S' = S⁻¹ in the operational SVD base). The
//!    facet's unit normal is U v_k / ‖v_k‖ and its distance from the origin 1/‖v_k‖, the term of
//!    eq. (19).
//!
//! The result is stored with unit normals and *signed* offsets (a type-2 border gets normal
//! −U v_k/‖v_k‖ and offset −1/‖v_k‖), exactly as [`crate::hyperplane_shifting`] produces it.
//!
//! The cost is C(2ⁿ, DOF) small solves each followed by a 2ⁿ-point border test: the method is
//! refused for n > 10 or more than 10⁸ candidates ([`PolytopeError::TooLarge`]; e.g. 6 DOF with
//! 6 cables has 7.5·10⁷ candidates and takes seconds). Use hyperplane shifting beyond that.
//!
//! ## References
//! - S. Krut, O. Company, F. Pierrot, *Force performance indexes for parallel mechanisms with
//!   actuation redundancy, especially for parallel wire-driven manipulators*, IROS 2004 (seed 001),
//!   §III steps 1–6, eqs. (3), (8)–(18).

use crate::PolytopeError;
use crate::available_wrench_set::{AvailableWrenchSet, Facet, binomial, next_combination};
use crate::input;
use cdpr_tension::TensionBounds;
use nalgebra::{DMatrix, DVector, SMatrix, SVector};

/// Largest cable count accepted (2ⁿ box vertices).
pub const MAX_CABLES: usize = 10;
/// Largest number C(2ⁿ, DOF) of candidate hyperplanes accepted.
pub const MAX_CANDIDATES: f64 = 1e8;

type M6 = SMatrix<f64, 6, 6>;
type V6 = SVector<f64, 6>;

/// Available wrench set {W t : t_min ≤ t ≤ t_max} by Krut's steps 1–6 (unit normals, signed
/// offsets, duplicates merged, vertices for DOF 2 and 3).
///
/// Needs finite t_max, rank(W) = DOF, n ≤ [`MAX_CABLES`]; a polytope with an empty interior (e.g. a
/// zero-width tension box) is [`PolytopeError::LowerDimensional`].
///
/// ```
/// use cdpr_polytope::krut_vertex_projection::available_wrench_set;
/// use cdpr_tension::TensionBounds;
/// use nalgebra::dmatrix;
/// let w = dmatrix![1.0, -1.0, 0.0, 0.0; 0.0, 0.0, 1.0, -1.0];
/// let aws = available_wrench_set(&w, &TensionBounds::uniform(4, 1.0, 10.0).unwrap()).unwrap();
/// assert_eq!(aws.facets().len(), 4); // the square [−9, 9]²
/// assert_eq!(aws.vertices().unwrap().len(), 4);
/// ```
pub fn available_wrench_set(
    w: &DMatrix<f64>,
    bounds: &TensionBounds,
) -> Result<AvailableWrenchSet, PolytopeError> {
    let (scale, _) = input::check(w, bounds)?;
    let (dof, n) = w.shape();
    if let Some(j) = bounds.max().iter().position(|x| !x.is_finite()) {
        return Err(PolytopeError::UnboundedTension {
            cable: j,
            what: "Krut's vertex projection",
        });
    }
    let candidates = if n <= 30 {
        binomial((1u64 << n) as f64, dof)
    } else {
        f64::INFINITY
    };
    if n > MAX_CABLES || candidates > MAX_CANDIDATES {
        return Err(PolytopeError::TooLarge {
            method: "Krut's vertex projection",
            cables: n,
            dof,
            candidates,
            max_cables: MAX_CABLES,
            max_candidates: MAX_CANDIDATES,
        });
    }
    if n < dof {
        return Err(PolytopeError::LowerDimensional {
            rank: input::numerical_rank(w),
            dof,
        });
    }

    // Step 1: SVD W = U Σ Vᵀ (thin: U DOF × DOF, Vᵀ DOF × n).
    let svd = w.clone().svd(true, true);
    let (u, vt) = match (svd.u.as_ref(), svd.v_t.as_ref()) {
        (Some(u), Some(vt)) => (u, vt),
        _ => {
            return Err(PolytopeError::SolverFailure {
                detail: "SVD of W did not converge".into(),
            });
        }
    };
    let s = &svd.singular_values;
    let smax = s.max();
    if smax <= 0.0 || s.iter().any(|&x| x <= 1e-10 * smax) {
        return Err(PolytopeError::LowerDimensional {
            rank: s.iter().filter(|&&x| x > 1e-10 * smax).count(),
            dof,
        });
    }
    // Steps 1–3: box vertices (eq. (3)), τ_s = Vᵀ τ (eq. (8)), τ_r = P τ_s (eq. (9)). With the
    // thin Vᵀ the projection P is implicit: its rows are the first DOF rows of the full Vᵀ.
    let vertex_count = 1usize << n;
    let mut tau_r: Vec<V6> = Vec::with_capacity(vertex_count);
    let (tmin, tmax) = (bounds.min(), bounds.max());
    for bits in 0..vertex_count {
        let tau = DVector::from_fn(n, |j, _| {
            if (bits >> j) & 1 == 1 {
                tmax[j]
            } else {
                tmin[j]
            }
        });
        let r = vt * tau;
        let mut p = V6::zeros();
        p.rows_mut(0, dof).copy_from(&r);
        tau_r.push(p);
    }
    let pmax = tau_r.iter().map(|p| p.norm()).fold(0.0, f64::max);

    // Steps 4–5: candidate hyperplanes a · τ_r = b (b = 1 for Cramer systems, b = 0 through
    // the origin) and the border test (15).
    let mut borders: Vec<(V6, f64)> = Vec::new();
    let mut idx: Vec<usize> = (0..dof).collect();
    loop {
        if let Some((a, b)) = candidate_hyperplane(&tau_r, &idx, dof, pmax) {
            let tol = 1e-9 * (b.abs() + a.norm() * pmax);
            // BorderType1: all ≤ b; BorderType2: all ≥ b. Early exit once both fail.
            let (mut type1, mut type2) = (true, true);
            for p in &tau_r {
                let x = a.dot(p);
                type1 &= x <= b + tol;
                type2 &= x >= b - tol;
                if !type1 && !type2 {
                    break;
                }
            }
            if type1 && !type2 {
                borders.push((a, b));
            } else if type2 && !type1 {
                // Origin test: the origin lies on the far side of this border; store it as
                // (−a)·τ_r ≤ −b so that every border reads a·τ_r ≤ b.
                borders.push((-a, -b));
            }
        }
        if !next_combination(&mut idx, vertex_count) {
            break;
        }
    }

    // No border at all: the projected vertices lie in a hyperplane (e.g. a zero-width tension
    // box, or the cables with t_min < t_max do not span the wrench space), so the polytope has
    // an empty interior and no hyperplane through DOF affinely independent vertices exists.
    if borders.is_empty() {
        let p0 = tau_r[0];
        let spread = DMatrix::from_fn(dof, vertex_count, |i, j| tau_r[j][i] - p0[i]);
        return Err(PolytopeError::LowerDimensional {
            rank: input::numerical_rank(&spread).min(dof - 1),
            dof,
        });
    }

    // Step 6: f = U S τ_r, so a·τ_r ≤ b ⇔ (U S⁻¹ a)·f ≤ b, eqs. (17)–(18).
    let mut raw = Vec::with_capacity(borders.len());
    for (a, b) in borders {
        let v = DVector::from_fn(dof, |i, _| a[i] / s[i]); // v_k = S⁻¹ u_k, eq. (17)
        let g = u * v;
        let norm = g.norm();
        raw.push(Facet {
            normal: g / norm,
            offset: b / norm, // 1/‖v_k‖ for a type-1 border: the term of eq. (19)
        });
    }
    Ok(AvailableWrenchSet::from_halfspaces(dof, raw, true, scale))
}

/// Eqs. (12)–(14): the hyperplane through the chosen projected vertices, as (a, b) with
/// a·τ_r = b. `None` if the points do not determine a hyperplane.
fn candidate_hyperplane(tau_r: &[V6], idx: &[usize], dof: usize, pmax: f64) -> Option<(V6, f64)> {
    // T_k padded with an identity block to a fixed 6 × 6 system (det unchanged).
    let mut t = M6::identity();
    let mut rhs = V6::zeros();
    let mut hadamard = 1.0;
    for (r, &i) in idx.iter().enumerate() {
        let p = &tau_r[i];
        for c in 0..dof {
            t[(r, c)] = p[c];
        }
        rhs[r] = 1.0;
        hadamard *= p.norm();
    }
    if hadamard == 0.0 {
        return None; // a projected vertex at the origin: not a Cramer system
    }
    let lu = t.lu();
    if lu.determinant().abs() > 1e-10 * hadamard {
        // Eq. (14): u_k = T_k⁻¹ [1 … 1]ᵀ.
        return lu.solve(&rhs).map(|u| (u, 1.0));
    }
    // Singular T_k: identical projections give no hyperplane; affinely independent points
    // aligned with the origin give a hyperplane through O (seed 001, after eq. (14)).
    let mut d = M6::zeros();
    let p0 = tau_r[idx[0]];
    for (r, &i) in idx.iter().enumerate().skip(1) {
        let diff = tau_r[i] - p0;
        for c in 0..dof {
            d[(r - 1, c)] = diff[c];
        }
    }
    let block = d.view((0, 0), (dof, dof)).into_owned();
    let svd = block.svd(false, true);
    let vt = svd.v_t?;
    let sv = &svd.singular_values;
    // Smallest singular value's right vector is the normal; the others must be non-zero.
    let mut order: Vec<usize> = (0..dof).collect();
    order.sort_by(|&a, &b| sv[a].total_cmp(&sv[b]));
    if dof > 1 && sv[order[1]] <= 1e-9 * pmax.max(f64::MIN_POSITIVE) {
        return None;
    }
    let mut a = V6::zeros();
    for c in 0..dof {
        a[c] = vt[(order[0], c)];
    }
    let b = a.dot(&p0);
    (b.abs() <= 1e-9 * pmax).then_some((a, 0.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use nalgebra::dmatrix;

    #[test]
    fn square_and_signed_offsets() {
        // x = t1 − t2 ∈ [−9, 9]; y = t3 ∈ [1, 10]: the facet −y ≤ −1 has the origin outside.
        let w = dmatrix![1.0, -1.0, 0.0; 0.0, 0.0, 1.0];
        let b = TensionBounds::uniform(3, 1.0, 10.0).unwrap();
        let aws = available_wrench_set(&w, &b).unwrap();
        assert_eq!(aws.facets().len(), 4);
        let down = aws
            .facets()
            .iter()
            .find(|f| f.normal[1] < -0.5)
            .expect("facet −y");
        assert_relative_eq!(down.offset, -1.0, epsilon = 1e-10);
        let up = aws.facets().iter().find(|f| f.normal[1] > 0.5).unwrap();
        assert_relative_eq!(up.offset, 10.0, epsilon = 1e-10);
    }

    #[test]
    fn hyperplane_through_the_origin_is_found() {
        // y = t3 ∈ [0, 1]: the facet −y ≤ 0 passes through the origin (non-Cramer T_k).
        let w = dmatrix![1.0, -1.0, 0.0; 0.0, 0.0, 1.0];
        let b = TensionBounds::new(vec![0.0, 0.0, 0.0], vec![1.0, 1.0, 1.0]).unwrap();
        let aws = available_wrench_set(&w, &b).unwrap();
        assert_eq!(aws.facets().len(), 4);
        let down = aws.facets().iter().find(|f| f.normal[1] < -0.5).unwrap();
        assert!(down.offset.abs() < 1e-10);
    }

    #[test]
    fn guards() {
        let w = DMatrix::from_fn(2, 11, |i, j| if i == 0 { 1.0 } else { j as f64 });
        let b = TensionBounds::uniform(11, 1.0, 2.0).unwrap();
        assert!(matches!(
            available_wrench_set(&w, &b),
            Err(PolytopeError::TooLarge { cables: 11, .. })
        ));
        let w = dmatrix![1.0, 0.0; 0.0, 1.0];
        let b = TensionBounds::new(vec![0.0, 0.0], vec![1.0, f64::INFINITY]).unwrap();
        assert!(matches!(
            available_wrench_set(&w, &b),
            Err(PolytopeError::UnboundedTension { cable: 1, .. })
        ));
        let w = dmatrix![1.0, 2.0, -1.0; 0.0, 0.0, 0.0];
        let b = TensionBounds::uniform(3, 1.0, 2.0).unwrap();
        assert!(matches!(
            available_wrench_set(&w, &b),
            Err(PolytopeError::LowerDimensional { rank: 1, dof: 2 })
        ));
    }
}
