//! # cdpr-polytope
//!
//! Force capabilities of a cable robot at a pose, from its wrench matrix W (DOF × n) and the
//! tension bounds t_min ≤ t ≤ t_max: the **available wrench set** (the operational force
//! polytope of Krut, Company & Pierrot 2004), the **maximum isotropic force**, the **capacity margin** of a required
//! wrench set and the **largest inscribed ellipse**.
//!
//! ## Vocabulary and sign convention
//! Equilibrium is W t + w_ext = 0. The *available wrench set* AWS = {W t : t_min ≤ t ≤ t_max}
//! is what the cables apply to the platform; an external wrench w_ext is balanced iff
//! −w_ext ∈ AWS. [`AvailableWrenchSet`] stores the AWS as unit-normal facets `n_k · w ≤ d_k`
//! (d_k = signed distance from the origin); [`AvailableWrenchSet::can_balance`] tests external
//! wrenches; [`RequiredWrenchSet`] is always a set of *external* wrenches (e.g. gravity).
//!
//! | module | method |
//! |---|---|
//! | [`hyperplane_shifting`] | AWS facets for any n (Bouchard et al. 2008; Gouttefarde & Krut 2010) |
//! | [`krut_vertex_projection`] | AWS by Krut, Company & Pierrot's (2004) steps 1–6, eqs. (8)–(18), n ≤ 10; its candidate hyperplanes (Fig. 8) |
//! | [`isotropic_force`](mod@isotropic_force) | maximum isotropic force, eq. (19), signed |
//! | [`capacity_margin`](mod@capacity_margin) | capacity margin (Guay et al. 2014) |
//! | [`ellipse`] | largest-area centred ellipse (Krut, Company & Pierrot 2004, §IV-C) |
//!
//! The indices come in two flavours: functions of an [`AvailableWrenchSet`] (facets built and
//! kept, vertices for plotting), and allocation-free evaluators for sweeps over many poses
//! ([`IsotropicForce`], [`CapacityMarginEvaluator`], [`CapacityMargin`],
//! [`isotropic_force_of`], and [`LimitingFacet`]: the limiting facet's index without the set,
//! in buffers reused from pose to pose), built on [`hyperplane_shifting::HyperplaneShifting`], which checks
//! the tension bounds once.
//!
//! ```
//! use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
//! use cdpr_polytope::{hyperplane_shifting, isotropic_force, capacity_margin, RequiredWrenchSet};
//! use cdpr_tension::TensionBounds;
//! use nalgebra::{dvector, Vector3};
//!
//! // Krut, Company & Pierrot 2004, §IV-B: three motors at 1000 mm, 30°, 150°, 270°; tensions in [50, 500] N.
//! let motor = |deg: f64| Cable {
//!     frame: Vector3::new(1000.0 * deg.to_radians().cos(), 1000.0 * deg.to_radians().sin(), 0.0),
//!     platform: Vector3::zeros(),
//!     pulley: None,
//! };
//! let robot = Robot::new(MotionPattern::Point2, vec![motor(30.0), motor(150.0), motor(270.0)])?;
//! let bounds = TensionBounds::uniform(3, 50.0, 500.0)?;
//! let w = robot.inverse_kinematics(&Pose::point(0.0, 0.0, 0.0))?.wrench_matrix();
//!
//! let aws = hyperplane_shifting::available_wrench_set(&w, &bounds)?;
//! assert_eq!(aws.facets().len(), 6);                      // a hexagon
//! assert_eq!(aws.vertices().unwrap().len(), 6);
//! let f = isotropic_force(&aws, MotionPattern::Point2)?;
//! assert!((f - 225.0 * 3f64.sqrt()).abs() < 1e-9);        // ≈ 389.71 N in every direction
//!
//! // A 100 N load pulling down (an external wrench): the margin is what is left of the
//! // polytope around the tensions that balance it.
//! let load = RequiredWrenchSet::point(dvector![0.0, -100.0])?;
//! let m = capacity_margin(&aws, &load)?;
//! assert!(m > 0.0 && m < f);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod available_wrench_set;
pub mod capacity_margin;
pub mod ellipse;
mod error;
pub mod hyperplane_shifting;
mod input;
pub mod isotropic_force;
pub mod krut_vertex_projection;

pub use available_wrench_set::{AvailableWrenchSet, Face, Facet};
pub use capacity_margin::{
    CapacityMargin, CapacityMarginEvaluator, LimitingFacet, RequiredWrenchSet, capacity_margin,
    limiting_facet,
};
pub use ellipse::{InscribedEllipse, largest_inscribed_ellipse};
pub use error::PolytopeError;
pub use isotropic_force::{
    IsotropicForce, isotropic_force, isotropic_force_of, isotropic_force_of_under_load,
    isotropic_force_under_load, isotropic_wrench_radius, isotropic_wrench_radius_of,
};
/// The nalgebra this crate's API uses (vectors, matrices, rotations): use it through this
/// re-export (`cdpr_polytope::nalgebra::Vector3`) so that your types are the crate's types whatever
/// nalgebra version your own project pins.
pub use nalgebra;

/// The README's examples (the crate's page on crates.io), compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
