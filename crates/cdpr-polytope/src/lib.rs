//! # cdpr-polytope
