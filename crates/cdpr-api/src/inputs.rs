//! # Inputs shared by the requests
//!
//! Poses and wrenches from motion-pattern coordinates, the external wrench the cables balance
//! (given w_e + gravity w_g + passive springs w_s, Picard, Caro, Plestan & Claveau 2020, eq. (1)),
//! the check that a tension distribution method applies to a robot, and the serde spelling of a
//! [`Method`] (its command-line name).
//!
//! ## References
//! - Picard, Caro, Plestan & Claveau 2020 (the external wrench, eq. (1)).

use cdpr_io::RobotDescription;
use cdpr_kinematics::Pose;
use cdpr_tension::{Method, TensionError};
use nalgebra::DVector;

use crate::ApiError;

/// A pose for the robot's motion pattern from its coordinates (m, rad).
pub fn pose(robot: &RobotDescription, q: &[f64]) -> Result<Pose, ApiError> {
    Ok(Pose::from_coordinates(robot.robot.motion(), q)?)
}

/// A wrench for the robot's motion pattern (N, N·m; zero if absent).
pub fn wrench(robot: &RobotDescription, w: Option<&[f64]>) -> Result<DVector<f64>, ApiError> {
    let m = robot.robot.motion();
    match w {
        Some(w) => Ok(cdpr_wrench::wrench_from_slice(m, w)?),
        None => Ok(DVector::zeros(m.dof())),
    }
}

/// The external wrench at `pose`: the given w_e plus the platform's gravity w_g plus the passive
/// springs' wrench w_s ([`RobotDescription::load_wrench`]).
pub fn external_wrench(
    robot: &RobotDescription,
    pose: &Pose,
    w: Option<&[f64]>,
) -> Result<DVector<f64>, ApiError> {
    Ok(wrench(robot, w)? + robot.load_wrench(pose)?)
}

/// An error when `method` does not apply to the robot: too few cables, its redundancy n − DOF,
/// or an infinite t_max for the improved closed form.
pub fn check_method(robot: &RobotDescription, method: Method) -> Result<(), ApiError> {
    cdpr_wrench::require_enough_cables(&robot.robot, "tension distribution")?;
    let r = robot.robot.cable_count() as isize - robot.robot.dof() as isize;
    method.check_redundancy(r)?;
    if method == Method::ImprovedClosedForm
        && let Some(cable) = robot.bounds.max().iter().position(|v| !v.is_finite())
    {
        return Err(TensionError::NeedsFiniteBounds { method, cable }.into());
    }
    Ok(())
}

/// Serde of a [`Method`] as its name (`"l2"`, `"closed-form"`, …): `#[serde(with = "method_name")]`.
pub mod method_name {
    use cdpr_tension::Method;
    use serde::{Deserialize, Deserializer, Serializer};

    /// Writes the method's name.
    pub fn serialize<S: Serializer>(m: &Method, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(m.name())
    }

    /// Reads a method by name.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Method, D::Error> {
        let s = String::deserialize(d)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

/// Serde of an optional [`Method`] by name.
pub mod option_method_name {
    use cdpr_tension::Method;
    use serde::{Deserialize, Deserializer, Serializer};

    /// Writes the method's name or null.
    pub fn serialize<S: Serializer>(m: &Option<Method>, s: S) -> Result<S::Ok, S::Error> {
        match m {
            Some(m) => s.serialize_some(m.name()),
            None => s.serialize_none(),
        }
    }

    /// Reads a method by name, or null.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<Method>, D::Error> {
        Option::<String>::deserialize(d)?
            .map(|s| s.parse().map_err(serde::de::Error::custom))
            .transpose()
    }
}

/// Rows of a matrix as JSON arrays.
pub fn matrix_rows(m: &nalgebra::DMatrix<f64>) -> Vec<Vec<f64>> {
    m.row_iter().map(|r| r.iter().copied().collect()).collect()
}
