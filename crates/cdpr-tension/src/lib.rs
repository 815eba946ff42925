//! # cdpr-tension
//!
//! Cable tension distribution: given the wrench matrix W (DOF × n), an external wrench w_ext and
//! bounds t_min ≤ t ≤ t_max, find tensions with W t + w_ext = 0.

mod bounds;
mod error;

pub use bounds::TensionBounds;
pub use error::TensionError;
