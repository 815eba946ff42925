//! Integration tests of `cdpr-kinematics`, compiled as one test binary (one link instead of
//! one per file). Each module is one former `tests/*.rs` file.

mod batch;
mod catenary;
mod elastic_pulley;
mod elasto_geometric_fuzz;
mod forward_kinematics;
mod jacobian;
mod pulley;
