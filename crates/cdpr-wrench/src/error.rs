//! Errors of the wrench layer.

use thiserror::Error;

/// Bad input to a wrench or stiffness computation.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum WrenchError {
    /// A slice has the wrong length (one entry per cable, or per wrench component).
    #[error("{what}: expected {expected} values, found {found}")]
    DimensionMismatch {
        /// What was passed.
        what: &'static str,
        /// Expected length.
        expected: usize,
        /// Length found.
        found: usize,
    },
    /// A NaN or infinite input.
    #[error("{what}: entry {} (counting from 1) is not a finite number ({value})", index + 1)]
    NotFinite {
        /// What was passed.
        what: &'static str,
        /// Index of the entry.
        index: usize,
        /// The value.
        value: f64,
    },
    /// Axial stiffness E·S must be positive.
    #[error("cable {}: axial stiffness E·S = {value} N must be positive", cable + 1)]
    NonPositiveStiffness {
        /// Cable index (0-based).
        cable: usize,
        /// The value given.
        value: f64,
    },
}

pub(crate) fn check_slice(
    what: &'static str,
    v: &[f64],
    expected: usize,
) -> Result<(), WrenchError> {
    if v.len() != expected {
        return Err(WrenchError::DimensionMismatch {
            what,
            expected,
            found: v.len(),
        });
    }
    if let Some((index, &value)) = v.iter().enumerate().find(|(_, x)| !x.is_finite()) {
        return Err(WrenchError::NotFinite { what, index, value });
    }
    Ok(())
}
