//! Errors of the kinematics layer.

use thiserror::Error;

/// What can go wrong when describing a robot or computing its kinematics.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum KinematicsError {
    /// A robot needs at least one cable.
    #[error("a robot needs at least one cable")]
    NoCables,
    /// A number (anchor, attachment or pose coordinate) is NaN or infinite.
    #[error("{what} is not a finite number ({value})")]
    NotFinite {
        /// Which quantity, e.g. `"cable 2 frame anchor"` or `"pose coordinate 3"`.
        what: String,
        /// The offending value.
        value: f64,
    },
    /// A vector has the wrong number of components for the motion pattern.
    #[error("{what} has {found} components, the motion pattern `{motion}` needs {expected}")]
    WrongDimension {
        /// Which quantity.
        what: String,
        /// The motion pattern's name.
        motion: &'static str,
        /// Components expected.
        expected: usize,
        /// Components found.
        found: usize,
    },
    /// At this pose a cable has (numerically) zero length: its direction, and so W, is undefined.
    #[error(
        "cable {cable} has zero length ({length:e}) at this pose: its frame anchor and platform attachment coincide"
    )]
    DegenerateCable {
        /// Cable index (0-based).
        cable: usize,
        /// The length found.
        length: f64,
    },
    /// A platform shape without volume (fewer than 4 points, coplanar points, a zero side).
    #[error("degenerate platform shape: {reason}")]
    DegenerateShape {
        /// What is wrong.
        reason: String,
    },
    /// Unknown motion pattern name.
    #[error("unknown motion pattern `{0}` (expected point2, planar, point3 or spatial)")]
    UnknownMotion(String),
}
