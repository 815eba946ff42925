//! Integration tests of `cdpr-io`, compiled as one test binary (one link instead of
//! one per file). Each module is one former `tests/*.rs` file.

mod caspr_trajectories;
mod corpus;
mod encoders;
mod linear_density;
mod platform_shape;
mod pulley_keys;
mod pulley_reference;
mod readers;
mod winch;
