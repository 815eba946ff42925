//! Errors of the tension layer: bad input only. Infeasibility is a result, see `TensionOutcome`.

use crate::Method;
use crate::method::RequiredRedundancy;
use thiserror::Error;

/// "a, b, c" or "none".
fn list(methods: &[Method]) -> String {
    if methods.is_empty() {
        return "none".to_string();
    }
    methods
        .iter()
        .map(|m| m.name())
        .collect::<Vec<_>>()
        .join(", ")
}

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
        "unknown tension distribution method {0:?} (expected one of: exact, pinv, closed-form, l1, l1-max, l2, l2-max, linf, improved-closed-form, barycenter, sotda, pott-closed-form, pott-closed-form-ee, puncture, dykstra, l2-mid, vertex-centroid, p-norm, optimally-safe)"
    )]
    UnknownMethod(String),
    /// The method is not defined at this redundancy r = n − DOF (a usage error, not an
    /// infeasibility: no tensions were looked for).
    #[error(
        "method {method} needs redundancy {needs}; this robot has n − DOF = {redundancy}; methods that apply: {}",
        list(applicable)
    )]
    MethodNotApplicable {
        /// The method asked for.
        method: Method,
        /// The redundancy it needs.
        needs: RequiredRedundancy,
        /// r = n − DOF of the problem.
        redundancy: isize,
        /// The methods that apply at this redundancy.
        applicable: Vec<Method>,
    },
    /// The method needs finite upper bounds (the improved closed form starts from the mean
    /// tension (t_min + t_max)/2).
    #[error("method {method} needs a finite t_max for every cable; cable {} has t_max = ∞", cable + 1)]
    NeedsFiniteBounds {
        /// The method asked for.
        method: Method,
        /// The first cable with t_max = ∞ (0-based).
        cable: usize,
    },
    /// A geometric construction defined for one redundancy only (the feasible interval: 1;
    /// the feasible polygon: 2).
    #[error("the {what} needs redundancy {needs}; this robot has n − DOF = {redundancy}")]
    RedundancyMismatch {
        /// What was asked for.
        what: &'static str,
        /// The redundancy it needs.
        needs: usize,
        /// r = n − DOF of the problem.
        redundancy: isize,
    },
    /// [`crate::Method::Sotda`] needs [`crate::StiffnessData`] in the problem.
    #[error("the sotda method needs stiffness data (pose kinematics and axial stiffness E·S)")]
    MissingStiffness,
    /// An invalid option of a method (`p`, `alpha`, `interior`, `max_iterations`).
    #[error("invalid option {option}: {detail}")]
    InvalidOption {
        /// The option's name.
        option: &'static str,
        /// The value and what was expected.
        detail: String,
    },
    /// Invalid SOTDA settings (ν outside [0, 1], zero or non-finite direction).
    #[error("invalid sotda settings: {0}")]
    InvalidSettings(&'static str),
    /// The stiffness computation of `cdpr-wrench` rejected its input.
    #[error(transparent)]
    Wrench(#[from] cdpr_wrench::WrenchError),
}
