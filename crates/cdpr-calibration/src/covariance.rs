//! # Covariance, rank and conditioning of a least-squares fit
//!
//! At the least-squares solution of r(θ) with Jacobian J (N residuals, P free unknowns), the
//! first-order covariance of the estimate is
//!
//! ```text
//!   Cov θ = σ̂² (JᵀJ)⁻¹,     σ̂² = ‖r‖² / (N − P)
//! ```
//!
//! (the length noise σ estimated from the residual, unbiased for independent errors of equal
//! variance), and the expected residual is ‖r‖²/N ≈ σ² (1 − P/N). With unknown poses the
//! parameter block of (JᵀJ)⁻¹ is the inverse of the Schur complement
//! S = V − Σ_k W_kᵀ U_k⁻¹ W_k ([`crate::self_calibration`]).
//!
//! Rank and conditioning are read on the Jacobi-scaled matrix D^{-1/2} S D^{-1/2}
//! (D = diag S, every parameter on the same footing whatever its unit): its eigenvalues
//! λ₁ ≤ … ≤ λ_P give the condition number √(λ_P / λ₁) of the scaled Jacobian, and the rank
//! deficiency counts the λ_i ≤ 10⁻¹² λ_P (singular values below 10⁻⁶ of the largest:
//! combinations of parameters that the lengths do not determine).
//!
//! ## References
//! - Björck 1996, *Numerical Methods for Least Squares Problems*, SIAM, §1.1 (covariance of
//!   the least-squares estimate), §2.7 (column scaling).
//! - van der Sluis 1969, *Condition numbers and equilibration of matrices*, Numer. Math. 14.

use cdpr_kinematics::nalgebra::{DMatrix, DVector};

/// Relative eigenvalue below which a direction counts as undetermined.
pub const RANK_THRESHOLD: f64 = 1e-12;

/// Rank, conditioning and covariance of a symmetric positive semi-definite normal matrix.
#[derive(Debug, Clone, PartialEq)]
pub struct NormalAnalysis {
    /// √(λ_max / λ_min) of the Jacobi-scaled matrix (∞ when singular).
    pub condition_number: f64,
    /// Eigenvalues at or below [`RANK_THRESHOLD`] × λ_max.
    pub rank_deficiency: usize,
    /// S⁻¹ (`None` when rank deficient).
    pub inverse: Option<DMatrix<f64>>,
}

/// Analyses the normal matrix `s` (P × P): condition, rank deficiency and s⁻¹.
///
/// ```
/// use cdpr_calibration::covariance::analyse_normal_matrix;
/// use cdpr_calibration::nalgebra::DMatrix;
/// let s = DMatrix::from_row_slice(2, 2, &[4.0, 0.0, 0.0, 1.0]);
/// let a = analyse_normal_matrix(&s);
/// assert_eq!(a.rank_deficiency, 0);
/// assert!((a.inverse.unwrap()[(0, 0)] - 0.25).abs() < 1e-15);
/// assert!((a.condition_number - 1.0).abs() < 1e-12); // scaled: the identity
/// let singular = DMatrix::from_row_slice(2, 2, &[1.0, 1.0, 1.0, 1.0]);
/// assert_eq!(analyse_normal_matrix(&singular).rank_deficiency, 1);
/// ```
pub fn analyse_normal_matrix(s: &DMatrix<f64>) -> NormalAnalysis {
    let p = s.nrows();
    if p == 0 {
        return NormalAnalysis {
            condition_number: 1.0,
            rank_deficiency: 0,
            inverse: Some(DMatrix::zeros(0, 0)),
        };
    }
    let scale = DVector::from_fn(p, |i, _| {
        let d = s[(i, i)];
        if d > 0.0 && d.is_finite() {
            1.0 / d.sqrt()
        } else {
            0.0
        }
    });
    let scaled = DMatrix::from_fn(p, p, |i, j| s[(i, j)] * scale[i] * scale[j]);
    let eigen = scaled.clone().symmetric_eigen();
    let max = eigen.eigenvalues.max();
    let min = eigen.eigenvalues.min();
    let rank_deficiency = eigen
        .eigenvalues
        .iter()
        .filter(|&&l| l <= RANK_THRESHOLD * max)
        .count();
    let condition_number = if rank_deficiency == 0 && min > 0.0 {
        (max / min).sqrt()
    } else {
        f64::INFINITY
    };
    let inverse = (rank_deficiency == 0).then(|| {
        // S⁻¹ = D^{-1/2} (scaled)⁻¹ D^{-1/2}, (scaled)⁻¹ = Q Λ⁻¹ Qᵀ.
        let q = &eigen.eigenvectors;
        let qs = DMatrix::from_fn(p, p, |i, k| q[(i, k)] / eigen.eigenvalues[k]);
        let inv = qs * q.transpose();
        DMatrix::from_fn(p, p, |i, j| inv[(i, j)] * scale[i] * scale[j])
    });
    NormalAnalysis {
        condition_number,
        rank_deficiency,
        inverse,
    }
}
