//! Integration tests of `cdpr-tension`, compiled as one test binary (one link instead of
//! one per file). Each module is one former `tests/*.rs` file.

mod common;
mod dense_active_set;
mod fig_6_6;
mod fuzz_regressions;
mod improved_closed_form;
mod infinite_bounds;
mod input;
mod minimum_norm_vs_l2;
mod peers;
mod profile;
mod properties;
mod sagging_statics;
mod soak_regressions;
mod sotda;
mod thesis;
