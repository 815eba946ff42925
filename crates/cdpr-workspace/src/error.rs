//! Errors of the workspace layer: bad input only. An empty workspace is a result, not an error.

use cdpr_kinematics::KinematicsError;
use cdpr_polytope::PolytopeError;
use cdpr_tension::TensionError;
use cdpr_wrench::WrenchError;
use thiserror::Error;

/// Bad input to a workspace computation.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum WorkspaceError {
    /// The robot or a pose is invalid.
    #[error(transparent)]
    Kinematics(#[from] KinematicsError),
    /// A tension problem is malformed (wrong sizes, non-finite numbers).
    #[error(transparent)]
    Tension(#[from] TensionError),
    /// A stiffness computation failed (bad axial stiffness E·S).
    #[error(transparent)]
    Wrench(#[from] WrenchError),
    /// A force-polytope index failed (bad sizes or numbers).
    #[error(transparent)]
    Polytope(#[from] PolytopeError),
    /// Two sizes that must agree do not.
    #[error("{what}: expected {expected}, found {found}")]
    DimensionMismatch {
        /// What was being compared.
        what: &'static str,
        /// Expected size.
        expected: usize,
        /// Size found.
        found: usize,
    },
    /// A number that must be finite is NaN or infinite.
    #[error("{what} is not a finite number ({value})")]
    NotFinite {
        /// Which quantity.
        what: &'static str,
        /// The value.
        value: f64,
    },
    /// A setting is out of its valid range.
    #[error("{what} = {value} is out of range: {expected}")]
    InvalidSetting {
        /// Which setting.
        what: &'static str,
        /// Its value.
        value: f64,
        /// What is required.
        expected: &'static str,
    },
    /// A box with min ≥ max along an axis the robot moves in.
    #[error("region is empty or degenerate along axis {axis}: min = {min}, max = {max}")]
    EmptyRegion {
        /// Axis index (0 = x, 1 = y, 2 = z).
        axis: usize,
        /// Lower corner coordinate.
        min: f64,
        /// Upper corner coordinate.
        max: f64,
    },
    /// A criterion needs the axial stiffness E·S of the cables, which was not given
    /// (see [`crate::PoseEvaluator::with_axial_stiffness`]).
    #[error("criterion `{criterion}` needs the cables' axial stiffness E·S (with_axial_stiffness)")]
    MissingAxialStiffness {
        /// The criterion (or tension method) that needs it.
        criterion: &'static str,
    },
    /// The stiffness criterion uses the tensions of a tension-feasibility criterion; none is given.
    #[error("the stiffness criterion needs a TensionFeasible criterion to supply the tensions")]
    StiffnessNeedsTensions,
    /// A criterion or method that has no version with sagging or elastic cables.
    #[error("{what} has no version with elastic or sagging cables (use --cable-model straight)")]
    NoSaggingModel {
        /// What was asked.
        what: &'static str,
    },
    /// A planar orientation was required (rotation about z only) but another rotation was given.
    #[error("a planar robot's orientation must be a rotation about z")]
    NotPlanarRotation,
    /// The method only applies to robots moving in a plane (`point2`, `planar`).
    #[error("{method} needs a robot moving in a plane, not `{motion}`")]
    NotPlanar {
        /// The method.
        method: &'static str,
        /// The robot's motion pattern.
        motion: &'static str,
    },
    /// The method only applies to robots moving in space (`point3`, `spatial`).
    #[error("{method} needs a robot moving in space (point3 or spatial), not `{motion}`")]
    NotSpatial {
        /// The method.
        method: &'static str,
        /// The robot's motion pattern.
        motion: &'static str,
    },
    /// The method only applies to `spatial` robots (six degrees of freedom, with orientation).
    #[error("{method} needs a `spatial` robot, not `{motion}`")]
    NotSixDof {
        /// The method.
        method: &'static str,
        /// The robot's motion pattern.
        motion: &'static str,
    },
    /// The chord walk did not return to its first point within the allowed number of points.
    #[error("chord walk did not close after {points} boundary points")]
    ChordDidNotClose {
        /// Points generated before giving up.
        points: usize,
    },
}
