//! Integration tests of `cdpr-polytope`, compiled as one test binary (one link instead of
//! one per file). Each module is one former `tests/*.rs` file.

mod fuzz;
mod fuzz_regressions;
mod properties;
mod seed001;
