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
    /// A passive spring with K ≤ 0 or l₀ < 0.
    #[error("passive spring {}: {what} = {value} is out of range (K > 0, l0 ≥ 0)", spring + 1)]
    NonPositiveSpring {
        /// Spring index (0-based).
        spring: usize,
        /// Which parameter.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// An analysis that balances wrenches (tensions, wrench closure, feasibility, capacity)
    /// asked of a robot with fewer cables than degrees of freedom: W (DOF × n) cannot have
    /// rank DOF, so no wrench set is spanned. Kinematics (lengths, W) still applies.
    #[error(
        "{analysis} needs at least as many cables as degrees of freedom (n ≥ DOF); this {motion} robot has n = {cables} cables for DOF = {dof} (its cable lengths and W are still computed by `kinematics`)"
    )]
    TooFewCables {
        /// What was asked for ("tension distribution", "wrench closure", …).
        analysis: &'static str,
        /// The motion pattern's name.
        motion: &'static str,
        /// Cables n.
        cables: usize,
        /// Degrees of freedom.
        dof: usize,
    },
}

/// `Ok` when `robot` has at least as many cables as degrees of freedom, else
/// [`WrenchError::TooFewCables`] naming `analysis`: the usage check of every analysis that
/// balances a wrench with cable tensions (W t + w = 0 needs rank W = DOF, so n ≥ DOF).
///
/// ```
/// use cdpr_kinematics::{Cable, MotionPattern, Robot};
/// use cdpr_wrench::{require_enough_cables, WrenchError};
/// use nalgebra::Vector2;
/// let robot = Robot::new(MotionPattern::Planar, vec![
///     Cable::planar(Vector2::new(1.0, 0.0), Vector2::zeros()),
///     Cable::planar(Vector2::new(-1.0, 0.0), Vector2::zeros()),
/// ]).unwrap();
/// let e = require_enough_cables(&robot, "tension distribution").unwrap_err();
/// assert!(matches!(e, WrenchError::TooFewCables { cables: 2, dof: 3, .. }));
/// ```
pub fn require_enough_cables(
    robot: &cdpr_kinematics::Robot,
    analysis: &'static str,
) -> Result<(), WrenchError> {
    let (cables, dof) = (robot.cable_count(), robot.dof());
    if cables < dof {
        return Err(WrenchError::TooFewCables {
            analysis,
            motion: robot.motion().name(),
            cables,
            dof,
        });
    }
    Ok(())
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
