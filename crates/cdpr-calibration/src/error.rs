//! # Errors of the calibration

use cdpr_kinematics::KinematicsError;

/// Why a calibration could not be set up (bad input). Numerical outcomes (not identifiable,
/// not converged) are reported in [`crate::Calibration`], not as errors.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CalibrationError {
    /// An unknown name in the list of unknowns.
    #[error("unknown parameter group `{0}` (expected frame, platform, offsets or gains)")]
    UnknownGroup(String),
    /// No parameter group to calibrate.
    #[error("no unknowns: give at least one of frame, platform, offsets, gains")]
    NoUnknowns,
    /// `platform` asked of a point robot, which has no platform attachments.
    #[error("the motion pattern `{0}` has no platform attachments to calibrate")]
    NoPlatform(&'static str),
    /// The samples do not have one reading per cable, or the poses are not one per sample.
    #[error("{what}: expected {expected} values, found {found}")]
    WrongCount {
        /// What was counted.
        what: String,
        /// Expected count.
        expected: usize,
        /// Count found.
        found: usize,
    },
    /// A reading or pose coordinate that is NaN or infinite.
    #[error("sample {} ({what}) is not a finite number ({value})", .sample + 1)]
    NotFinite {
        /// Sample index (0-based; the message counts from 1).
        sample: usize,
        /// Which value.
        what: String,
        /// The value.
        value: f64,
    },
    /// A nominal offset or gain that is NaN or infinite.
    #[error("nominal {what}: not a finite number ({value})")]
    NotFiniteNominal {
        /// Offsets or gains.
        what: &'static str,
        /// The value.
        value: f64,
    },
    /// No samples at all.
    #[error("no samples")]
    NoSamples,
    /// Self-calibration (unknown poses) of a robot with swivel pulleys, which this crate does
    /// not do: the pulley axes stay fixed in the base frame, so rotating the frame and the poses
    /// together changes the lengths (through the pulley radii only): the gauge is no longer the
    /// rigid motions, and those rotations are barely determined. Known poses work with pulleys.
    #[error(
        "self-calibration (unknown poses) of a robot with swivel pulleys is not supported: the \
         pulley axes are fixed in the base frame, so a rotation of the frame and the poses \
         together is no longer a gauge freedom but a direction the lengths see only through the \
         pulley radii (barely determined); calibrate from known poses (a tracker), or calibrate \
         the robot without its pulleys"
    )]
    Pulleys,
    /// The anchors (or attachments) do not span the space the gauge needs.
    #[error("cannot fix the gauge: the {what} are {reason}")]
    DegenerateGauge {
        /// Anchors or attachments.
        what: &'static str,
        /// Coincident, collinear, …
        reason: &'static str,
    },
    /// A combination this crate does not handle.
    #[error("not supported: {0}")]
    Unsupported(&'static str),
    /// The kinematics failed (degenerate pose, bad robot).
    #[error(transparent)]
    Kinematics(#[from] KinematicsError),
}
