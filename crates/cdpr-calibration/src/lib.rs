//! # cdpr-calibration
//!
//! Kinematic calibration of cable-driven parallel robots from cable-length readings: the layer
//! above the forward kinematics of `cdpr-kinematics`.
//!
//! A robot is built, then measured badly: its anchors c_i are off by centimetres, its encoders
//! count from an unknown zero (offset o_i) at an uncertain scale (gain g_i). From k samples of
//! the n readings ρ_ki ([`Samples`]; true length = g_i ρ_ki + o_i, [`model`]) this crate
//! estimates the [`Unknowns`] chosen among frame anchors, platform attachments, offsets and
//! gains:
//!
//! - with the poses measured by a tracker: per-cable least squares ([`known_poses`]);
//! - without: self-calibration, poses and parameters together with the gauge fixed
//!   ([`self_calibration`], [`gauge`]) — possible only with more cables than DOF, by the
//!   counting rule k (n − d) ≥ p − g ([`identifiability`]).
//!
//! Every answer says whether the samples identify the unknowns (counting rule, rank of the
//! Jacobian, its condition number) and how well: standard deviations from σ̂² (JᵀJ)⁻¹
//! ([`covariance`]).
//!
//! ```
//! use cdpr_calibration::{Readings, Samples, Unknowns, calibrate};
//! use cdpr_calibration::nalgebra::Vector3;
//! use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
//!
//! // A 4-cable point robot whose true anchors differ from the nominal ones.
//! let anchors = [[2.0, 2.0, 3.0], [-2.0, 2.0, 3.0], [-2.0, -2.0, 3.0], [2.0, -2.0, 2.5]];
//! let robot = |shift: f64| Robot::new(MotionPattern::Point3, anchors.iter().enumerate().map(|(i, a)| {
//!     Cable::point3(Vector3::from(*a) + Vector3::new(shift * i as f64, 0.0, 0.0))
//! }).collect()).unwrap();
//! let (truth, nominal) = (robot(0.01), robot(0.0));
//! let poses: Vec<Pose> = (0..12).map(|k| {
//!     let t = k as f64;
//!     Pose::point(0.8 * (0.9 * t).sin(), 0.8 * (1.7 * t).cos(), 1.0 + 0.5 * (0.6 * t).sin())
//! }).collect();
//! let readings: Vec<f64> = poses.iter()
//!     .flat_map(|p| truth.inverse_kinematics(p).unwrap().lengths().collect::<Vec<_>>())
//!     .collect();
//! let samples = Samples { readings, poses: Some(poses) };
//! let unknowns = Unknowns::parse("frame").unwrap();
//! let cal = calibrate(&nominal, &samples, unknowns, &Readings::Absolute).unwrap();
//! assert!(cal.identifiable);
//! assert!((cal.parameters.frame[3] - truth.cables()[3].frame).norm() < 1e-9);
//! ```

pub mod adjustment;
pub mod covariance;
mod error;
pub mod gauge;
pub mod identifiability;
pub mod known_poses;
pub mod model;
mod report;
pub mod self_calibration;

/// The nalgebra of this crate's API (re-exported from `cdpr-kinematics`).
pub use cdpr_kinematics::nalgebra;
pub use error::CalibrationError;
pub use known_poses::calibrate_known_poses;
pub use model::{Parameters, Readings, Samples, Unknowns};
pub use report::{CONDITION_WARNING, Calibration, ParameterSigma};
pub use self_calibration::self_calibrate;

use cdpr_kinematics::Robot;

/// Calibrates: from known poses when `samples.poses` is given ([`calibrate_known_poses`]),
/// else self-calibration ([`self_calibrate`]).
pub fn calibrate(
    robot: &Robot,
    samples: &Samples,
    unknowns: Unknowns,
    readings: &Readings,
) -> Result<Calibration, CalibrationError> {
    if samples.poses.is_some() {
        calibrate_known_poses(robot, samples, unknowns, readings)
    } else {
        self_calibrate(robot, samples, unknowns, readings)
    }
}

/// [`calibrate`] a robot whose encoders were calibrated before: the nominal offsets o_i and
/// gains g_i (one per cable, e.g. a robot file's `offset` and `gain` keys) instead of 0 and 1.
/// Groups not among the unknowns keep these values; the others start from them.
///
/// ```
/// use cdpr_calibration::{Readings, Samples, Unknowns, calibrate_with_encoders};
/// use cdpr_calibration::nalgebra::Vector3;
/// use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
///
/// let anchors = [[2.0, 2.0, 3.0], [-2.0, 2.0, 3.0], [-2.0, -2.0, 3.0], [2.0, -2.0, 2.5]];
/// let robot = Robot::new(MotionPattern::Point3,
///     anchors.iter().map(|a| Cable::point3(Vector3::from(*a))).collect()).unwrap();
/// let offsets = [0.01, -0.02, 0.03, 0.0];
/// let poses: Vec<Pose> = (0..8).map(|k| {
///     let t = k as f64;
///     Pose::point(0.5 * t.cos(), 0.5 * t.sin(), 1.0 + 0.1 * t)
/// }).collect();
/// // Readings ρ = l − o: with the offsets known, the anchors fit exactly.
/// let readings = poses.iter().flat_map(|p| {
///     robot.inverse_kinematics(p).unwrap().lengths().zip(offsets).map(|(l, o)| l - o)
///         .collect::<Vec<_>>()
/// }).collect();
/// let samples = Samples { readings, poses: Some(poses) };
/// let cal = calibrate_with_encoders(&robot, &offsets, &[1.0; 4], &samples,
///     Unknowns::parse("frame").unwrap(), &Readings::Absolute).unwrap();
/// assert!(cal.identifiable && cal.residual_rms < 1e-12);
/// assert_eq!(cal.parameters.offsets, offsets); // held: not among the unknowns
/// ```
pub fn calibrate_with_encoders(
    robot: &Robot,
    offsets: &[f64],
    gains: &[f64],
    samples: &Samples,
    unknowns: Unknowns,
    readings: &Readings,
) -> Result<Calibration, CalibrationError> {
    let n = robot.cable_count();
    for (what, v) in [
        ("offsets (one per cable)", offsets),
        ("gains (one per cable)", gains),
    ] {
        if v.len() != n {
            return Err(CalibrationError::WrongCount {
                what: what.into(),
                expected: n,
                found: v.len(),
            });
        }
        if let Some(&bad) = v.iter().find(|x| !x.is_finite()) {
            return Err(CalibrationError::NotFiniteNominal { what, value: bad });
        }
    }
    let nominal = Parameters {
        offsets: offsets.to_vec(),
        gains: gains.to_vec(),
        ..Parameters::nominal(robot)
    };
    if samples.poses.is_some() {
        known_poses::known_poses_from(robot, nominal, samples, unknowns, readings)
    } else {
        self_calibration::self_calibrate_from(robot, nominal, samples, unknowns, readings)
    }
}

/// Shared input checks; returns the number of samples k.
fn check_inputs(
    robot: &Robot,
    samples: &Samples,
    unknowns: Unknowns,
) -> Result<usize, CalibrationError> {
    unknowns.check(robot.motion())?;
    samples.check(robot.cable_count())
}

/// The cables' pulleys when the robot has any (the adjustment then uses the pulley model).
fn pulleys(robot: &Robot) -> Option<Vec<Option<cdpr_kinematics::Pulley>>> {
    robot
        .has_pulleys()
        .then(|| robot.cables().iter().map(|c| c.pulley).collect())
}

/// The README's examples (the crate's page on crates.io), compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
