//! Errors of the kinematics layer.

use crate::PulleyDegeneracy;
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
    /// A cable's pulley parameters cannot describe a pulley (see [`crate::Pulley`]).
    #[error("cable {} pulley: {problem} ({value})", .cable + 1)]
    InvalidPulley {
        /// Cable index (0-based; the message counts from 1).
        cable: usize,
        /// What is wrong.
        problem: &'static str,
        /// The offending value.
        value: f64,
    },
    /// At this pose a pulley cable has no defined geometry (Pott 2018 swivel-pulley model).
    #[error("cable {} at this pose: {reason} (distance {distance:e} m)", .cable + 1)]
    DegeneratePulley {
        /// Cable index (0-based; the message counts from 1).
        cable: usize,
        /// Which degeneracy.
        reason: PulleyDegeneracy,
        /// The distance that vanished: from the attachment to the swivel axis (`OnSwivelAxis`) or
        /// to the pulley centre (`InsidePulley`, then ≤ the radius).
        distance: f64,
    },
    /// A solver setting is out of range.
    #[error("{what}: {value}")]
    InvalidSetting {
        /// Which setting and its valid range.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// Forward kinematics needs at least as many cables (measured lengths) as DOF.
    #[error(
        "forward kinematics needs at least {dof} cable lengths for {dof} DOF, the robot has {cables} cables"
    )]
    TooFewCables {
        /// Cables of the robot.
        cables: usize,
        /// DOF of its motion pattern.
        dof: usize,
    },
    /// Unknown motion pattern name.
    #[error("unknown motion pattern `{0}` (expected point2, planar, point3 or spatial)")]
    UnknownMotion(String),
}
