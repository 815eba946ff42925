//! Integration tests of `cdpr-wrench`, compiled as one test binary (one link instead of
//! one per file). Each module is one former `tests/*.rs` file.

mod stiffness_finite_difference;
mod stiffness_printed_eq4;
