//! # cdpr-dynamics
//!
//! Cable robots in motion, on top of `cdpr-tension`: the platform's mass matrix M(x) and bias
//! b(x, ẋ) in twist coordinates ([`RigidBody`]), time laws along paths ([`Trajectory`]), the
//! inverse dynamics W t + w_ext + w_g = M ẍ + b at every sample ([`inverse_dynamics()`]), the
//! forward dynamics under given tensions or elastic cables (`forward_dynamics`), and the
//! dynamic feasibility of an acceleration box ([`DynamicFeasibility`]), and the drive train:
//! motor speeds and torques of the cables' winches ([`drive_train()`]), and CASPR's joint-space
//! spline trajectories ([`JointSpline`]).
//!
//! Vocabulary: a twist ẋ = [v; ω] (m/s, rad/s, base axes) and its rate ẍ; motion patterns keep
//! their components (planar: v_x, v_y, ω_z; points: v).
//!
//! ```
//! use cdpr_dynamics::{RigidBody, TimeLaw, Trajectory, TimingSettings, inverse_dynamics};
//! use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
//! use cdpr_tension::{Method, TensionBounds, TensionSolver};
//! use cdpr_wrench::Platform;
//! use nalgebra::{Vector2, Vector3};
//!
//! // A 1 kg point hanging from three anchors in a vertical plane (gravity −y).
//! let robot = Robot::new(MotionPattern::Point2, vec![
//!     Cable::point2(Vector2::new(-1.0, 1.0)),
//!     Cable::point2(Vector2::new(1.0, 1.0)),
//!     Cable::point2(Vector2::new(0.0, -1.0)),
//! ]).unwrap();
//! let body = RigidBody::point_mass(&Platform {
//!     mass: 1.0, gravity: Vector3::new(0.0, -9.81, 0.0), ..Platform::default()
//! }).unwrap();
//! let path = [Pose::point(-0.2, 0.0, 0.0), Pose::point(0.2, 0.0, 0.0)];
//! let traj = Trajectory::new(MotionPattern::Point2, &path,
//!     &TimingSettings::with_duration(TimeLaw::Quintic, 1.0)).unwrap();
//! let samples = traj.sample(0.01).unwrap();
//! let bounds = TensionBounds::uniform(3, 1.0, 100.0).unwrap();
//! let mut solver = TensionSolver::new(Method::L2);
//! let gravity = nalgebra::DVector::from_vec(vec![0.0, -9.81]);
//! let profile = inverse_dynamics(&robot, Some(&body), &samples, &bounds, &mut solver, None,
//!     |_, _| gravity.clone()).unwrap();
//! assert_eq!(profile.feasible_count(), samples.len());
//! ```

mod error;

pub mod drive_train;
pub mod dynamic_feasibility;
pub mod forward_dynamics;
pub mod inverse_dynamics;
pub mod joint_spline;
pub mod rigid_body;
pub mod time_law;

pub use drive_train::{DriveTrainProfile, DrumLayers, Winch, drive_train};
pub use dynamic_feasibility::DynamicFeasibility;
pub use error::DynamicsError;
pub use forward_dynamics::{Drive, Integrator, Simulation, Simulator, State};
pub use inverse_dynamics::{DynamicsProfile, inverse_dynamics};
pub use joint_spline::{JointSpline, SplineKind, SplinePoint};
/// The nalgebra of this crate's API.
pub use nalgebra;
pub use rigid_body::{RigidBody, euler_rate_matrix, twist_from_euler_rates};
pub use time_law::{TimeLaw, TimedSample, TimingSettings, Trajectory};

/// The README's examples (the crate's page on crates.io), compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
