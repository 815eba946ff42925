//! # cdpr-kinematics
//!
//! Geometry of cable-driven parallel robots: the bottom layer of the `cdpr` stack.
//!
//! A [`Robot`] is a [`MotionPattern`] and a list of [`Cable`]s (frame anchor **c**^i, platform
//! attachment **ā**^i). At a [`Pose`], [`Robot::inverse_kinematics`] gives every cable's vector,
//! length and unit vector ([`PoseKinematics`], thesis eqs. (6.2)–(6.4)), from which the
//! DOF × n wrench matrix W (the thesis' structure matrix S = Jᵀ, eq. (6.11)) follows, with the
//! sign convention **W t + w_ext = 0**.
//!
//! ```
//! use cdpr_kinematics::nalgebra::Vector2; // the nalgebra of this crate, re-exported
//! use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
//!
//! // The thesis' 3-cable planar manipulator (Tables 6.1, 6.2).
//! let s = 0.1 / 2f64.sqrt();
//! let cable = |c: [f64; 2], a: [f64; 2]| Cable::planar(Vector2::from(c), Vector2::from(a));
//! let robot = Robot::new(MotionPattern::Planar, vec![
//!     cable([1.0, 1.0], [s, s]),
//!     cable([-1.0, 1.0], [-s, s]),
//!     cable([0.0, -1.0], [0.0, -0.1]),
//! ]).unwrap();
//!
//! let kin = robot.inverse_kinematics(&Pose::planar(0.1, 0.0, 0.05)).unwrap();
//! let w = kin.wrench_matrix();              // 3 × 3
//! assert_eq!(w.shape(), (3, 3));
//! assert!(kin.min_length() > 0.1);          // l_min of eq. (6.22)
//! ```
//!
//! A cable may run over a swivel [`Pulley`] at the frame (Pott 2018; the WireCenter model): its
//! length is then the arc wrapped on the pulley plus the free segment, its unit vector that of
//! the free segment, and [`PulleyState`] reports the swivel and wrap angles. W keeps its form and
//! J = Wᵀ stays the derivative of the total length, so every layer above works unchanged.
//! [`ForwardKinematics`] goes back from measured lengths to the pose (Levenberg–Marquardt, with a
//! certificate) for either cable model.
//!
//! Real cables sag and stretch: [`ElasticCatenary`] (module [`catenary`], Irvine 1981) gives a
//! heavy elastic cable's unstrained length and end forces from its span and tension, and
//! [`SaggingCable`] places it between a frame point and a platform attachment in space.
//! [`ElastoGeometricForward`] goes back from the unstrained lengths the winches paid out to the
//! platform's equilibrium pose and its tensions.
//!
//! Enable the `proptest` feature for the `strategies` module (proptest strategies for robots
//! and poses) that every crate of the stack tests with.

mod batch;
mod cable_state;
pub mod catenary;
mod elasto_geometric;
mod error;
mod forward_kinematics;
pub mod interference;
mod inverse_kinematics;
pub mod lanes;
mod motion;
mod path;
mod pose;
mod pulley;
pub mod reference_robots;
mod robot;
#[cfg(feature = "proptest")]
pub mod strategies;
mod structure_matrix;

pub use cable_state::{CableState, PulleyState};
pub use catenary::{
    CableModel, CatenaryError, CatenarySolution, ElasticCatenary, RobotCatenaries, SaggingCable,
};
pub use elasto_geometric::{
    ElastoGeometricForward, ElastoGeometricSettings, ElastoGeometricSolution, ElastoGeometricStatus,
};
pub use error::KinematicsError;
pub use forward_kinematics::{
    ForwardKinematics, ForwardSettings, ForwardSolution, ForwardStatus, chi_square_quantile_999,
};
pub use interference::{
    ClosestCables, ConvexPolyhedron, PlatformInterference, Segment, SegmentDistance, cable_segment,
    closest_cables, min_cable_distance, platform_interference, segment_distance,
};
pub use inverse_kinematics::PoseKinematics;
pub use motion::MotionPattern;
/// The nalgebra this crate's API uses (vectors, matrices, rotations): use it through this
/// re-export (`cdpr_kinematics::nalgebra::Vector3`) so that your types are the crate's types whatever
/// nalgebra version your own project pins.
pub use nalgebra;
pub use path::{Path, PathSample, Sampling};
pub use pose::Pose;
pub use pulley::PulleyDegeneracy;
pub use robot::{Cable, Pulley, Robot};

/// The README's examples (the crate's page on crates.io), compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
