//! # cdpr-wrench
//!
//! Wrenches and stiffness of cable-driven parallel robots, on top of `cdpr-kinematics`:
//! the gravity wrench of a [`Platform`] and the stiffness matrix K = Kp + Ka of Picard, Caro, Plestan & Claveau 2020
//! (Picard, Caro, Plestan & Claveau 2020, eqs. (3)–(4)) with k_i = E S / l_i.
//!
//! ```
//! use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
//! use cdpr_wrench::{stiffness_matrix, Platform};
//! use nalgebra::Vector3;
//!
//! let robot = Robot::new(MotionPattern::Point3, vec![
//!     Cable { frame: Vector3::new(1.0, 0.0, 1.0), platform: Vector3::zeros(), pulley: None },
//!     Cable { frame: Vector3::new(-1.0, 0.0, 1.0), platform: Vector3::zeros(), pulley: None },
//!     Cable { frame: Vector3::new(0.0, 1.0, 1.0), platform: Vector3::zeros(), pulley: None },
//!     Cable { frame: Vector3::new(0.0, -1.0, 1.0), platform: Vector3::zeros(), pulley: None },
//! ]).unwrap();
//! let pose = Pose::point(0.0, 0.0, 0.0);
//! let gravity = Platform { mass: 1.0, ..Platform::default() }.gravity_wrench(MotionPattern::Point3, &pose);
//! assert!((gravity[2] + 9.80665).abs() < 1e-12);
//! let kin = robot.inverse_kinematics(&pose).unwrap();
//! let k = stiffness_matrix(&kin, &[5.0; 4], &[6.0e4; 4]).unwrap();   // 3 × 3, N/m
//! assert!(k[(2, 2)] > 0.0);
//! ```

mod error;
mod external_wrench;
mod passive_springs;
mod stiffness;

pub use error::{WrenchError, require_enough_cables};
pub use external_wrench::{Platform, STANDARD_GRAVITY, wrench_from_slice};
/// The nalgebra this crate's API uses (vectors, matrices, rotations): use it through this
/// re-export (`cdpr_wrench::nalgebra::Vector3`) so that your types are the crate's types whatever
/// nalgebra version your own project pins.
pub use nalgebra;
pub use passive_springs::PassiveSprings;
pub use stiffness::{
    active_stiffness, passive_stiffness, stiffness_matrix, wrench_components,
    write_stiffness_matrix,
};

/// The README's examples (the crate's page on crates.io), compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
