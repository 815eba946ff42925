//! # cdpr-io
//!
//! Robot files of cable-driven parallel robots, beside the analysis stack of `cdpr`: a
//! [`RobotDescription`] is everything a file says about a robot — the kinematic
//! [`Robot`](cdpr_kinematics::Robot), tension bounds, workspace limits, platform mass
//! properties and per-cable axial stiffness. This crate needs neither plotting nor a command
//! line, so other projects can read robot files with it alone.
//!
//! ```
//! use cdpr_io::RobotDescription;
//!
//! let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/robots/tdpm-4.toml");
//! let robot = RobotDescription::load(file).unwrap();
//! assert_eq!(robot.robot.cable_count(), 4);
//! ```

mod toml_file;

pub use nalgebra;
pub use toml_file::{Limits, RobotDescription, RobotFileError, pulley_toml};
