//! Integration tests of `cdpr-workspace`, compiled as one test binary (one link instead of
//! one per file). Each module is one former `tests/*.rs` file.

mod boundary_mesh;
mod chord;
mod common;
mod criteria;
mod dextrous;
mod discretisation;
mod orientation_workspace;
mod thesis;
mod vsd_rig;
