//! # cdpr
//!
//! Analysis and design of cable-driven parallel robots (CDPRs): the facade of the `cdpr` crate
//! stack. It re-exports the layers, reads robot files, draws plots, and provides the `cdpr`
//! command-line program.
//!
//! | layer | crate | owns |
//! |---|---|---|
//! | [`kinematics`] | `cdpr-kinematics` | robots, poses, inverse kinematics, wrench matrix W |
//! | [`wrench`] | `cdpr-wrench` | external wrenches, stiffness K = Kp + Ka |
//! | [`tension`] | `cdpr-tension` | tension distribution (closed form, ℓ1, ℓ2, barycentre, SOTDA, …) |
//! | [`polytope`] | `cdpr-polytope` | available wrench set, isotropic force, capacity margin |
//! | [`dynamics`] | `cdpr-dynamics` | mass matrix, time laws, inverse and forward dynamics |
//! | [`workspace`] | `cdpr-workspace` | grid and chord workspaces, dextrous workspace, synthesis |
//! | [`api`] | `cdpr-api` | one typed request and report per analysis (the CLI's JSON) |
//!
//! ```
//! use cdpr::RobotDescription;
//! use cdpr::kinematics::Pose;
//!
//! let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/robots/tdpm-4.toml");
//! let robot = RobotDescription::load(file).unwrap();
//! let kin = robot.robot.inverse_kinematics(&Pose::planar(0.0, 0.0, 0.0)).unwrap();
//! assert_eq!(kin.wrench_matrix().shape(), (3, 4));
//! ```

pub mod plot;

/// Typed requests and reports of every analysis (the `--json` output is the serialised report).
pub use cdpr_api as api;
pub use cdpr_calibration as calibration;
pub use cdpr_dynamics as dynamics;
pub use cdpr_io as io;
pub use cdpr_io::{Limits, RobotDescription, RobotFileError};
pub use cdpr_kinematics as kinematics;
pub use cdpr_polytope as polytope;
pub use cdpr_tension as tension;
pub use cdpr_workspace as workspace;
pub use cdpr_wrench as wrench;
/// The nalgebra of the whole stack (`cdpr::nalgebra::Vector3`): no need to pin its version.
pub use nalgebra;

/// The README's examples (the crate's page on crates.io), compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
