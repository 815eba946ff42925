//! # Largest origin-centred inscribed ellipse
//!
//! Krut, Company & Pierrot 2004, §IV-C proposes, after the isotropic force, a second index: the centred ellipse of
//! largest area inside the 2-D operational force polytope. Writing the ellipse as
//! E = {B u : ‖u‖ ≤ 1} with B symmetric positive definite, E lies in {f : n_k · f ≤ d_k} iff
//! h_E(n_k) = ‖B n_k‖ ≤ d_k for every facet, and its area is π det B. So
//!
//! ```text
//!     maximise log det B   subject to   ‖B n_k‖ ≤ d_k,  B = [a b; b c] ≻ 0.
//! ```
//!
//! For 2 × 2 matrices log det B = log(ac − b²) is maximised by maximising s subject to
//! ac ≥ b² + s² (a rotated second-order cone: ‖(2b, 2s, a − c)‖ ≤ a + c), which with the facet
//! cones ‖(a n₁ + b n₂, b n₁ + c n₂)‖ ≤ d_k is a second-order cone program with a linear
//! objective, solved exactly (to interior-point precision) by Clarabel. The result is scaled by
//! at most 1 + 1e-7 so that the returned ellipse is inside the polygon to rounding.
//!
//! No ellipse of positive area exists unless the origin is strictly inside (all d_k > 0): the
//! result is then `None`. The polytope may be the AWS or its mirror −AWS (the same ellipse up to
//! the sign of B u, i.e. the same set).
//!
//! ## References
//! - S. Krut, O. Company, F. Pierrot, IROS 2004 (Krut, Company & Pierrot 2004), §IV-C and Fig. 4.
//! - S. Boyd, L. Vandenberghe, *Convex Optimization*, 2004, §8.4.2 (maximum volume inscribed
//!   ellipsoid in a polyhedron).
//! - P. Goulart, Y. Chen, *Clarabel: an interior-point solver for conic programs*, 2024.

use crate::PolytopeError;
use crate::available_wrench_set::AvailableWrenchSet;
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT,
};
use nalgebra::{Matrix2, Vector2};

/// An origin-centred ellipse {B u : ‖u‖ ≤ 1}.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InscribedEllipse {
    /// The shape matrix B (symmetric positive definite).
    pub matrix: Matrix2<f64>,
    /// Semi-axes, major first (eigenvalues of B).
    pub semi_axes: [f64; 2],
    /// Angle of the major axis from the x axis, radians in (−π/2, π/2].
    pub angle: f64,
}

impl InscribedEllipse {
    /// Area π · a · b.
    pub fn area(&self) -> f64 {
        std::f64::consts::PI * self.semi_axes[0] * self.semi_axes[1]
    }

    /// Support function h(n) = ‖B n‖: the ellipse's extent along the unit vector n.
    pub fn support(&self, n: &Vector2<f64>) -> f64 {
        (self.matrix * n).norm()
    }
}

/// The largest-area origin-centred ellipse inside a 2-D AWS (point2 robots), or `None` when the
/// origin is not strictly inside. Errors if the set is not 2-D, unbounded, or the solver fails.
///
/// ```
/// use cdpr_polytope::{hyperplane_shifting::available_wrench_set, largest_inscribed_ellipse};
/// use cdpr_tension::TensionBounds;
/// use nalgebra::dmatrix;
/// // AWS = [−2, 2] × [−1, 1]: the ellipse is axis-aligned with semi-axes 2 and 1.
/// let w = dmatrix![2.0, -2.0, 0.0, 0.0; 0.0, 0.0, 1.0, -1.0];
/// let aws = available_wrench_set(&w, &TensionBounds::uniform(4, 0.0, 1.0).unwrap()).unwrap();
/// let e = largest_inscribed_ellipse(&aws).unwrap().unwrap();
/// assert!((e.semi_axes[0] - 2.0).abs() < 1e-6 && (e.semi_axes[1] - 1.0).abs() < 1e-6);
/// assert!(e.angle.abs() < 1e-6);
/// ```
pub fn largest_inscribed_ellipse(
    aws: &AvailableWrenchSet,
) -> Result<Option<InscribedEllipse>, PolytopeError> {
    if aws.dof() != 2 {
        return Err(PolytopeError::DimensionMismatch {
            what: "dimension of the polytope (the ellipse index is 2-D)",
            expected: 2,
            found: aws.dof(),
        });
    }
    let facets: Vec<(Vector2<f64>, f64)> = aws
        .facets()
        .iter()
        .map(|f| (Vector2::new(f.normal[0], f.normal[1]), f.offset))
        .collect();
    largest_inscribed_ellipse_of(&facets)
}

/// The same for a polygon given directly as unit normals and offsets `n_k · f ≤ d_k`.
pub fn largest_inscribed_ellipse_of(
    facets: &[(Vector2<f64>, f64)],
) -> Result<Option<InscribedEllipse>, PolytopeError> {
    for (i, (n, d)) in facets.iter().enumerate() {
        if !(n.iter().all(|x| x.is_finite()) && d.is_finite()) {
            return Err(PolytopeError::NotFinite {
                what: "polygon facet",
                index: i,
                value: *d,
            });
        }
        if (n.norm() - 1.0).abs() > 1e-9 {
            return Err(PolytopeError::InvalidParameter {
                what: "facet normal length",
                must: "1",
                value: n.norm(),
            });
        }
    }
    if facets.iter().any(|(_, d)| *d <= 0.0) {
        return Ok(None);
    }
    // A centred ellipse only feels P ∩ −P = {|n_k · f| ≤ d_k}: bounded iff the normals span R².
    let spans = facets.iter().any(|(n, _)| {
        facets
            .iter()
            .any(|(m, _)| (n[0] * m[1] - n[1] * m[0]).abs() > 1e-9)
    });
    if !spans {
        return Err(PolytopeError::Unbounded);
    }
    // Scale offsets to O(1) for the interior-point method.
    let scale = facets.iter().map(|(_, d)| *d).fold(0.0, f64::max);

    // Variables x = (a, b, c, s); minimise −s.  Constraints A x + z = rhs, z ∈ cones.
    let (mut rows, mut cols, mut vals) = (Vec::new(), Vec::new(), Vec::new());
    let mut rhs = Vec::new();
    let mut push = |r: usize, c: usize, v: f64| {
        if v != 0.0 {
            rows.push(r);
            cols.push(c);
            vals.push(v);
        }
    };
    // Rotated cone ac ≥ b² + s²: z = (a + c, 2b, 2s, a − c) ∈ SOC(4).
    push(0, 0, -1.0);
    push(0, 2, -1.0);
    push(1, 1, -2.0);
    push(2, 3, -2.0);
    push(3, 0, -1.0);
    push(3, 2, 1.0);
    rhs.extend([0.0; 4]);
    let mut cones = vec![SupportedConeT::SecondOrderConeT(4)];
    // Facet k: z = (d_k, a n1 + b n2, b n1 + c n2) ∈ SOC(3).
    for (k, (n, d)) in facets.iter().enumerate() {
        let r = 4 + 3 * k;
        rhs.push(d / scale);
        push(r + 1, 0, -n[0]);
        push(r + 1, 1, -n[1]);
        push(r + 2, 1, -n[0]);
        push(r + 2, 2, -n[1]);
        rhs.extend([0.0; 2]);
        cones.push(SupportedConeT::SecondOrderConeT(3));
    }
    let m = rhs.len();
    let a = CscMatrix::new_from_triplets(m, 4, rows, cols, vals);
    let p = CscMatrix::zeros((4, 4));
    let q = [0.0, 0.0, 0.0, -1.0];
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .tol_gap_abs(1e-10)
        .tol_gap_rel(1e-10)
        .tol_feas(1e-10)
        .build()
        .map_err(|e| PolytopeError::SolverFailure {
            detail: format!("{e:?}"),
        })?;
    let mut solver = DefaultSolver::new(&p, &q, &a, &rhs, &cones, settings).map_err(|e| {
        PolytopeError::SolverFailure {
            detail: format!("{e:?}"),
        }
    })?;
    solver.solve();
    match solver.solution.status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => {}
        status => {
            return Err(PolytopeError::SolverFailure {
                detail: format!("{status:?}"),
            });
        }
    }
    let x = &solver.solution.x;
    let mut bmat = Matrix2::new(x[0], x[1], x[1], x[2]) * scale;
    // Guarantee containment to rounding: shrink by the worst constraint ratio if above 1.
    let worst = facets
        .iter()
        .map(|(n, d)| (bmat * n).norm() / d)
        .fold(0.0, f64::max);
    if worst > 1.0 {
        bmat /= worst;
    }
    let eig = bmat.symmetric_eigen();
    let (i_max, i_min) = if eig.eigenvalues[0] >= eig.eigenvalues[1] {
        (0, 1)
    } else {
        (1, 0)
    };
    let (l1, l2) = (eig.eigenvalues[i_max], eig.eigenvalues[i_min]);
    if l2.is_nan() || l2 <= 0.0 {
        return Err(PolytopeError::SolverFailure {
            detail: format!("non-positive-definite solution (eigenvalues {l1}, {l2})"),
        });
    }
    let v = eig.eigenvectors.column(i_max);
    let mut angle = v[1].atan2(v[0]);
    if angle <= -std::f64::consts::FRAC_PI_2 {
        angle += std::f64::consts::PI;
    } else if angle > std::f64::consts::FRAC_PI_2 {
        angle -= std::f64::consts::PI;
    }
    Ok(Some(InscribedEllipse {
        matrix: bmat,
        semi_axes: [l1, l2],
        angle,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn polygon(normals_deg: &[f64], offsets: &[f64]) -> Vec<(Vector2<f64>, f64)> {
        normals_deg
            .iter()
            .zip(offsets)
            .map(|(a, d)| (Vector2::new(a.to_radians().cos(), a.to_radians().sin()), *d))
            .collect()
    }

    #[test]
    fn square_gives_the_inscribed_circle() {
        let sq = polygon(&[0.0, 90.0, 180.0, 270.0], &[1.5; 4]);
        let e = largest_inscribed_ellipse_of(&sq).unwrap().unwrap();
        assert_relative_eq!(e.semi_axes[0], 1.5, epsilon = 1e-6);
        assert_relative_eq!(e.semi_axes[1], 1.5, epsilon = 1e-6);
    }

    #[test]
    fn rotated_rectangle_gives_a_rotated_ellipse() {
        // Rectangle with half-widths 3 (along 30°) and 1 (along 120°).
        let r = polygon(&[30.0, 120.0, 210.0, 300.0], &[3.0, 1.0, 3.0, 1.0]);
        let e = largest_inscribed_ellipse_of(&r).unwrap().unwrap();
        assert_relative_eq!(e.semi_axes[0], 3.0, epsilon = 1e-6);
        assert_relative_eq!(e.semi_axes[1], 1.0, epsilon = 1e-6);
        assert_relative_eq!(e.angle, 30f64.to_radians(), epsilon = 1e-6);
    }

    #[test]
    fn origin_outside_or_on_the_boundary_gives_none() {
        let r = polygon(&[0.0, 90.0, 180.0, 270.0], &[1.0, 1.0, 1.0, 0.0]);
        assert_eq!(largest_inscribed_ellipse_of(&r).unwrap(), None);
        let r = polygon(&[0.0, 90.0, 180.0, 270.0], &[1.0, 1.0, 1.0, -0.5]);
        assert_eq!(largest_inscribed_ellipse_of(&r).unwrap(), None);
    }

    #[test]
    fn unbounded_polygon_is_an_error() {
        // A centred ellipse only feels P ∩ −P: two half-planes x ≤ 1, y ≤ 1 bound it (the unit
        // circle), a single one (or parallel ones) does not.
        let r = polygon(&[0.0, 90.0], &[1.0, 1.0]);
        let e = largest_inscribed_ellipse_of(&r).unwrap().unwrap();
        assert_relative_eq!(e.semi_axes[0], 1.0, epsilon = 1e-6);
        assert_relative_eq!(e.semi_axes[1], 1.0, epsilon = 1e-6);
        let r = polygon(&[0.0, 180.0], &[1.0, 2.0]);
        assert_eq!(
            largest_inscribed_ellipse_of(&r),
            Err(PolytopeError::Unbounded)
        );
        assert_eq!(
            largest_inscribed_ellipse_of(&[]),
            Err(PolytopeError::Unbounded)
        );
    }
}
