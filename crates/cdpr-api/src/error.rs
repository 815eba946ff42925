//! # Errors of a request
//!
//! Everything that can go wrong between a request and its report: the request itself (a wrong
//! option, a missing number), its robot file, or the analysis (degenerate geometry, a method that
//! does not apply). Each message is the one the `cdpr` command prints today.
//!
//! ## References
//! - The `thiserror` conventions of the cdpr crates (docs/architecture.md).

use cdpr_calibration::CalibrationError;
use cdpr_dynamics::DynamicsError;
use cdpr_io::RobotFileError;
use cdpr_kinematics::KinematicsError;
use cdpr_polytope::PolytopeError;
use cdpr_tension::TensionError;
use cdpr_workspace::WorkspaceError;
use cdpr_workspace::synthesis::SynthesisError;
use cdpr_wrench::WrenchError;

/// Why a request has no report.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ApiError {
    /// The request itself is wrong (an option out of range, options that exclude each other,
    /// numbers of the wrong count): the message names the option as the command line spells it.
    #[error("{0}")]
    Invalid(String),
    /// The robot file in the request could not be read.
    #[error(transparent)]
    RobotFile(#[from] RobotFileError),
    /// Poses, inverse or forward kinematics.
    #[error(transparent)]
    Kinematics(#[from] KinematicsError),
    /// External wrenches, stiffness.
    #[error(transparent)]
    Wrench(#[from] WrenchError),
    /// Tension distribution.
    #[error(transparent)]
    Tension(#[from] TensionError),
    /// Available wrench sets, capacity margin, isotropic force.
    #[error(transparent)]
    Polytope(#[from] PolytopeError),
    /// Platform dynamics (the `dynamic` criterion).
    #[error(transparent)]
    Dynamics(#[from] DynamicsError),
    /// Regions, grids and pose evaluators.
    #[error(transparent)]
    Workspace(#[from] WorkspaceError),
    /// Dimensional synthesis (designs, optimiser settings).
    #[error(transparent)]
    Synthesis(#[from] SynthesisError),
    /// Kinematic calibration.
    #[error(transparent)]
    Calibration(#[from] CalibrationError),
}

impl ApiError {
    /// An [`ApiError::Invalid`] with this message.
    pub fn invalid(message: impl Into<String>) -> Self {
        Self::Invalid(message.into())
    }
}
