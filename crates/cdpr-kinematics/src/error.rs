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
    /// A path sampled with fewer samples than its two ends.
    #[error("a path needs at least {needed} samples (its two ends), got {found}")]
    TooFewSamples {
        /// Samples asked for.
        found: usize,
        /// The least number of samples (2).
        needed: usize,
    },
    /// At this pose a cable has (numerically) zero length: its direction, and so W, is undefined.
    /// Cables are numbered from 1 in the message; a length that is not a finite number (a
    /// coordinate so large that the length overflows) is said to be so, not "zero".
    #[error("{}", degenerate_cable_message(*cable, *length))]
    DegenerateCable {
        /// Cable index (0-based; the message counts from 1).
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
    /// A cable model that a pulley cable cannot take (e.g. the elastic catenary over a pulley
    /// whose swivel axis is not vertical).
    #[error("cable {}: {reason}", .cable + 1)]
    UnsupportedPulley {
        /// Cable index (0-based; the message counts from 1).
        cable: usize,
        /// What is not modelled, and what to use instead.
        reason: &'static str,
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
    /// A cable index that the robot does not have (e.g. in [`crate::Robot::permuted`]).
    #[error("no cable {} (the robot has {cables} cables, numbered from 1)", .cable + 1)]
    NoSuchCable {
        /// The index given (0-based; the message counts from 1).
        cable: usize,
        /// Cables of the robot.
        cables: usize,
    },
    /// One value per cable was expected (e.g. measured cable lengths).
    #[error("{what}: {found} values given, the robot has {cables} cables (one value per cable)")]
    WrongCableCount {
        /// What was given.
        what: String,
        /// Cables of the robot.
        cables: usize,
        /// Values given.
        found: usize,
    },
    /// A measured cable length below zero.
    #[error("length of cable {} is negative ({value} m): a cable length is ≥ 0", .cable + 1)]
    NegativeLength {
        /// Cable index (0-based; the message counts from 1).
        cable: usize,
        /// The value given (m).
        value: f64,
    },
    /// A cable's elastic-catenary model or solve failed (module [`crate::catenary`]).
    #[error("cable {}: {source}", .cable + 1)]
    Catenary {
        /// Cable index (0-based; the message counts from 1).
        cable: usize,
        /// What went wrong.
        #[source]
        source: crate::CatenaryError,
    },
    /// Unknown motion pattern name.
    #[error("unknown motion pattern `{0}` (expected point2, planar, point3 or spatial)")]
    UnknownMotion(String),
}

/// The message of [`KinematicsError::DegenerateCable`].
fn degenerate_cable_message(cable: usize, length: f64) -> String {
    let n = cable + 1;
    if length.is_finite() {
        format!(
            "cable {n} has zero length ({length:e} m) at this pose: its frame anchor and platform \
             attachment coincide"
        )
    } else {
        format!(
            "cable {n}: its length at this pose is not a finite number ({length}): a coordinate \
             is infinite or so large (beyond about 1e150 m) that the length overflows"
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 13 §2: cables are numbered from 1; an overflowing length is not "zero length".
    #[test]
    fn degenerate_cable_messages_count_from_one() {
        let zero = KinematicsError::DegenerateCable {
            cable: 0,
            length: 0.0,
        };
        assert!(
            zero.to_string().starts_with("cable 1 has zero length"),
            "{zero}"
        );
        let huge = KinematicsError::DegenerateCable {
            cable: 2,
            length: f64::INFINITY,
        };
        let msg = huge.to_string();
        assert!(
            msg.starts_with("cable 3:") && !msg.contains("zero"),
            "{msg}"
        );
    }
}
