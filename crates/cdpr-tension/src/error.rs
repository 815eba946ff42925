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
    #[error("{what} {index} is not a finite number ({value})")]
    NotFinite {
        /// Which input.
        what: &'static str,
        /// Index of the entry.
        index: usize,
        /// The value.
        value: f64,
    },
    /// t_min > t_max for a cable.
    #[error("cable {cable}: t_min = {min} exceeds t_max = {max}")]
    InvertedBounds {
        /// Cable index (0-based).
        cable: usize,
        /// t_min.
        min: f64,
        /// t_max.
        max: f64,
    },
}
