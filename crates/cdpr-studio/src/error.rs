//! # Errors of the studio
//!
//! Every bad input the page can send becomes one of these, shown to the user as its message:
//! the lower crates' errors pass through unchanged (file, line and key for robot files).

use cdpr_io::RobotFileError;
use cdpr_kinematics::KinematicsError;
use cdpr_tension::TensionError;
use cdpr_workspace::WorkspaceError;
use cdpr_wrench::WrenchError;

/// What went wrong in a studio request.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum StudioError {
    /// A robot file could not be read.
    #[error(transparent)]
    File(#[from] RobotFileError),
    /// The files given do not make one robot (none, an unknown type, a CASPR file alone).
    #[error("{0}")]
    Files(String),
    /// A pose, wrench or robot is not valid for the kinematics.
    #[error(transparent)]
    Kinematics(#[from] KinematicsError),
    /// A request of the request/report layer failed (the command line's message).
    #[error(transparent)]
    Api(#[from] cdpr_api::ApiError),
    /// A wrench does not fit the motion pattern.
    #[error(transparent)]
    Wrench(#[from] WrenchError),
    /// The tension method does not apply or failed.
    #[error(transparent)]
    Tension(#[from] TensionError),
    /// The workspace could not be computed.
    #[error(transparent)]
    Workspace(#[from] WorkspaceError),
    /// An unknown tension method name.
    #[error("unknown tension method `{name}` (one of: {known})")]
    UnknownMethod {
        /// The name given.
        name: String,
        /// The names known.
        known: String,
    },
    /// A request that does not apply to this robot.
    #[error("{what} needs {needs}; this robot is {motion}")]
    NotApplicable {
        /// The request.
        what: &'static str,
        /// What it needs.
        needs: &'static str,
        /// The robot's motion pattern.
        motion: &'static str,
    },
    /// A malformed JSON request from the page.
    #[error("request: {0}")]
    Request(#[from] serde_json::Error),
    /// A value in the robot table is out of range.
    #[error("robot table: {field} of {row}: {problem}")]
    Table {
        /// The column.
        field: &'static str,
        /// The row (e.g. "cable 3", "platform").
        row: String,
        /// What is wrong.
        problem: String,
    },
}
