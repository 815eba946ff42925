//! # cdpr-workspace
