//! # Errors of the dynamics layer

use cdpr_kinematics::KinematicsError;
use cdpr_tension::TensionError;

/// What can go wrong in a dynamics computation. Infeasible samples are answers, not errors.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum DynamicsError {
    /// The inertia tensor about the centre of mass is not symmetric positive definite.
    #[error("inertia {inertia:?} (kg·m²) is not symmetric positive definite: {why}")]
    InertiaNotPositiveDefinite {
        /// The tensor, row by row.
        inertia: [[f64; 3]; 3],
        /// Which test failed.
        why: &'static str,
    },
    /// A mass that is not finite and positive.
    #[error("mass = {mass} kg must be finite and positive")]
    BadMass {
        /// The mass (kg).
        mass: f64,
    },
    /// A setting out of its domain: `key` names it as the CLI and files do.
    #[error("{key} = {value}: {why}")]
    BadSetting {
        /// Flag or file key (`duration`, `dt`, `max-velocity`, `waypoints[2].time`, …).
        key: String,
        /// The offending value.
        value: f64,
        /// What it must be.
        why: String,
    },
    /// A vector with the wrong number of components.
    #[error("{what}: expected {expected} numbers, found {found}")]
    DimensionMismatch {
        /// What the vector is.
        what: &'static str,
        /// Expected length.
        expected: usize,
        /// Found length.
        found: usize,
    },
    /// The simulation left the finite numbers or the robot's geometry.
    #[error("the simulation diverged at t = {time} s: {why}")]
    Diverged {
        /// Simulated time at which it happened (s).
        time: f64,
        /// What was seen.
        why: String,
    },
    /// A paid-out length L a layered winch cannot give: negative, not finite, or more than the
    /// `winch.cable_length` C wound on it (the drum would be empty).
    #[error("{}", paid_out_message(*cable, *time, *length, *cable_length))]
    PaidOutLength {
        /// The cable (1-based), when known.
        cable: Option<usize>,
        /// The sample's time (s), when known.
        time: Option<f64>,
        /// L (m).
        length: f64,
        /// C (m).
        cable_length: f64,
    },
    /// A kinematics error (e.g. a cable of zero length).
    #[error(transparent)]
    Kinematics(#[from] KinematicsError),
    /// A tension-distribution error.
    #[error(transparent)]
    Tension(#[from] TensionError),
}

/// A setting error naming `key` and `value`.
pub(crate) fn bad(key: impl Into<String>, value: f64, why: impl Into<String>) -> DynamicsError {
    DynamicsError::BadSetting {
        key: key.into(),
        value,
        why: why.into(),
    }
}

/// The message of [`DynamicsError::PaidOutLength`].
fn paid_out_message(cable: Option<usize>, time: Option<f64>, length: f64, c: f64) -> String {
    let who = cable.map_or(String::new(), |i| format!("cable {i}: "));
    let when = time.map_or(String::new(), |t| format!(" at t = {t} s"));
    if length > c {
        format!(
            "{who}paid-out length {length} m{when} exceeds winch.cable_length = {c} m \
             (the drum would be empty)"
        )
    } else if length < 0.0 {
        format!("{who}paid-out length {length} m{when} is negative")
    } else {
        format!("{who}paid-out length {length} m{when} is not a finite number")
    }
}
