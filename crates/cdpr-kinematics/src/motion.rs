//! # Motion patterns
//!
//! The degrees of freedom a platform has, and so the size of every wrench (DOF) and pose.
//!
//! | pattern  | DOF | space | pose coordinates      | wrench rows               |
//! |----------|-----|-------|-----------------------|---------------------------|
//! | `point2` | 2   | 2-D   | x, y                  | f_x, f_y                  |
//! | `planar` | 3   | 2-D   | x, y, φ               | f_x, f_y, τ_z             |
//! | `point3` | 3   | 3-D   | x, y, z               | f_x, f_y, f_z             |
//! | `spatial`| 6   | 3-D   | x, y, z, r_x, r_y, r_z| f_x, f_y, f_z, τ_x, τ_y, τ_z |
//!
//! ## References
//! - The thesis chapter on planar tendon-driven manipulators (ch. 6) §6.2: the planar pattern; Krut, Company & Pierrot 2004, §II: the point pattern;
//!   Picard, Caro, Plestan & Claveau 2020, §2: the spatial pattern.

use crate::KinematicsError;
use std::fmt;
use std::str::FromStr;

/// The motion pattern of a platform (how many and which degrees of freedom it has).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MotionPattern {
    /// A point moving in a plane: 2 translations (Krut, Company & Pierrot 2004).
    Point2,
    /// A rigid body in a plane: x, y and the rotation φ about z (the thesis chapter on planar tendon-driven manipulators).
    Planar,
    /// A point in space: 3 translations.
    Point3,
    /// A rigid body in space: 3 translations and 3 rotations (Picard, Caro, Plestan & Claveau 2020).
    Spatial,
}

impl MotionPattern {
    /// All motion patterns, in order of increasing DOF.
    pub const ALL: [MotionPattern; 4] = [Self::Point2, Self::Planar, Self::Point3, Self::Spatial];

    /// Degrees of freedom: rows of the wrench matrix W and length of a wrench.
    pub const fn dof(self) -> usize {
        match self {
            Self::Point2 => 2,
            Self::Planar | Self::Point3 => 3,
            Self::Spatial => 6,
        }
    }

    /// Dimension of the space the cables live in (2 or 3): the length of an anchor vector.
    pub const fn space_dim(self) -> usize {
        match self {
            Self::Point2 | Self::Planar => 2,
            Self::Point3 | Self::Spatial => 3,
        }
    }

    /// Whether the platform has an orientation (and so cables have platform attachments).
    pub const fn has_orientation(self) -> bool {
        matches!(self, Self::Planar | Self::Spatial)
    }

    /// Number of translational DOF (the force part of a wrench).
    pub const fn translation_dof(self) -> usize {
        self.space_dim()
    }

    /// The name used in robot files and on the command line.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Point2 => "point2",
            Self::Planar => "planar",
            Self::Point3 => "point3",
            Self::Spatial => "spatial",
        }
    }
}

impl fmt::Display for MotionPattern {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for MotionPattern {
    type Err = KinematicsError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| KinematicsError::UnknownMotion(s.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_dofs() {
        for m in MotionPattern::ALL {
            assert_eq!(m.name().parse::<MotionPattern>().unwrap(), m);
        }
        assert_eq!(MotionPattern::Point2.dof(), 2);
        assert_eq!(MotionPattern::Planar.dof(), 3);
        assert_eq!(MotionPattern::Point3.dof(), 3);
        assert_eq!(MotionPattern::Spatial.dof(), 6);
        assert!("cartesian".parse::<MotionPattern>().is_err());
    }
}
