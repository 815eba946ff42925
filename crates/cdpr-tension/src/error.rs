//! Errors of the tension layer: bad input only. Infeasibility is a result, see `TensionOutcome`.

use thiserror::Error;

/// Bad input to a tension distribution method.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum TensionError {
    /// Shapes of W, the wrench or the bounds do not agree.
    #[error("{what}: expected {expected}, found {found}")]
    DimensionMismatch {
        /// What was being compared.
        what: &'static str,
        /// Expected size.
        expected: usize,
        /// Size found.
        found: usize,
    },
    /// A NaN or infinite number in the input.
    #[error("{what}: entry {} (counting from 1) is not a finite number ({value})", index + 1)]
    NotFinite {
        /// Which input.
        what: &'static str,
        /// Index of the entry.
        index: usize,
        /// The value.
        value: f64,
    },
    /// t_min > t_max for a cable.
    #[error("cable {}: t_min = {min} N exceeds t_max = {max} N", cable + 1)]
    InvertedBounds {
        /// Cable index (0-based).
        cable: usize,
        /// t_min.
        min: f64,
        /// t_max.
        max: f64,
    },
    /// A method name that is not one of [`crate::Method::ALL`].
    #[error(
        "unknown tension distribution method {0:?} (expected one of: exact, pinv, closed-form, l1, l1-max, l2, l2-max, linf, improved-closed-form, barycenter, sotda)"
    )]
    UnknownMethod(String),
    /// [`crate::Method::Sotda`] needs [`crate::StiffnessData`] in the problem.
    #[error("the sotda method needs stiffness data (pose kinematics and axial stiffness E·S)")]
    MissingStiffness,
    /// Invalid SOTDA settings (ν outside [0, 1], zero or non-finite direction).
    #[error("invalid sotda settings: {0}")]
    InvalidSettings(&'static str),
    /// The stiffness computation of `cdpr-wrench` rejected its input.
    #[error(transparent)]
    Wrench(#[from] cdpr_wrench::WrenchError),
}
