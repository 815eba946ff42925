//! Errors of the polytope layer: bad input and degenerate geometry only.
//!
//! A pose whose available wrench set does not contain the origin is *not* an error: the indices
//! are signed and simply come out negative.

use thiserror::Error;

/// Bad input to a force-polytope computation.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum PolytopeError {
    /// Shapes of W, the bounds or a wrench do not agree.
    #[error("{what}: expected {expected}, found {found}")]
    DimensionMismatch {
        /// What was being compared.
        what: &'static str,
        /// Expected size.
        expected: usize,
        /// Size found.
        found: usize,
    },
    /// A NaN or infinite number where a finite one is needed.
    #[error("{what}: entry {} (counting from 1) is not a finite number ({value})", index + 1)]
    NotFinite {
        /// Which input.
        what: &'static str,
        /// Index of the entry (column-major for matrices).
        index: usize,
        /// The value.
        value: f64,
    },
    /// Only wrench spaces of dimension 1 to 6 are supported.
    #[error("wrench space of dimension {dof} is not supported (1 to 6)")]
    UnsupportedDof {
        /// Rows of W.
        dof: usize,
    },
    /// W has rank below DOF (singular pose, too few or dependent cables): the available wrench
    /// set is a lower-dimensional polytope with an empty interior, so no facet description in
    /// the full wrench space, no ball and no margin exist.
    #[error(
        "the wrench matrix has rank {rank} < {dof}: the available wrench set is lower-dimensional (singular pose)"
    )]
    LowerDimensional {
        /// Numerical rank of W.
        rank: usize,
        /// Rows of W.
        dof: usize,
    },
    /// The problem is too large for an exhaustive method (Krut's vertex projection).
    #[error(
        "{method}: {cables} cables in {dof} DOF give {candidates:e} candidate hyperplanes (limits: {max_cables} cables, {max_candidates:e} candidates)"
    )]
    TooLarge {
        /// The method refusing.
        method: &'static str,
        /// Number of cables n.
        cables: usize,
        /// Rows of W.
        dof: usize,
        /// C(2^n, DOF), the number of hyperplane candidates.
        candidates: f64,
        /// Largest n accepted.
        max_cables: usize,
        /// Largest candidate count accepted.
        max_candidates: f64,
    },
    /// This computation needs a finite t_max for every cable.
    #[error("cable {} has an infinite t_max: {what} needs finite tension bounds", cable + 1)]
    UnboundedTension {
        /// Cable index (0-based).
        cable: usize,
        /// What needed it.
        what: &'static str,
    },
    /// A parameter outside its domain (e.g. a negative radius or half-width).
    #[error("{what} must be {must}, found {value}")]
    InvalidParameter {
        /// The parameter.
        what: &'static str,
        /// The requirement, e.g. `"≥ 0"`.
        must: &'static str,
        /// The value found.
        value: f64,
    },
    /// A facet offset overflowed f64 (|W|·|t| beyond ~1.8e308): rescale W or the bounds.
    #[error("a facet offset overflows ({value}): |W|·|t| is beyond the range of f64")]
    Overflow {
        /// The non-finite offset.
        value: f64,
    },
    /// The polygon is unbounded, so the largest inscribed ellipse is unbounded too.
    #[error("the polygon is unbounded: no largest inscribed ellipse")]
    Unbounded,
    /// Inverse kinematics failed at the pose (degenerate cable, non-finite pose).
    #[error(transparent)]
    Kinematics(#[from] cdpr_kinematics::KinematicsError),
    /// The conic solver failed (numerical trouble).
    #[error("conic solver failure: {detail}")]
    SolverFailure {
        /// The solver's status.
        detail: String,
    },
}
