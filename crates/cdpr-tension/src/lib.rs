//! # cdpr-tension
//!
//! Cable tension distribution: given the wrench matrix W (DOF × n), an external wrench w_ext and
//! bounds t_min ≤ t ≤ t_max, find tensions with **W t + w_ext = 0** (thesis eq. (6.11),
//! Picard, Caro, Plestan & Claveau 2020, eq. (1)).
//!
//! Vocabulary: a [`TensionProblem`] (borrowing W, w_ext, [`TensionBounds`] and, for SOTDA,
//! [`StiffnessData`]) is solved by a [`TensionSolver`] for one [`Method`], giving a
//! [`TensionOutcome`]: `Feasible` tensions that passed the [`certify`] check (equilibrium
//! residual ≤ 10⁻⁹·scale, bounds within 10⁻⁹ relative), or `Infeasible` with an
//! [`Infeasibility`] reason. Bad input (NaN, wrong shapes) is a [`TensionError`].
//!
//! | method (CLI name) | what | module |
//! |---|---|---|
//! | `exact` | n = DOF: t = −W⁻¹ w_ext (6.12) | [`minimum_norm`] |
//! | `pinv` | t = −W⁺ w_ext (6.14), bounds checked | [`minimum_norm`] |
//! | `closed-form` | Algorithm 6.1, r = 1, min ‖t‖₁ | [`closed_form`] |
//! | `l1`, `l1-max` | min / max Σ t (6.19) | [`linear_program`] (r ≥ 3: active-set LP) |
//! | `l2`, `l2-max` | min / max ‖t‖₂² (6.17) | [`quadratic_program`] (r ≥ 3 l2: Goldfarb–Idnani; l2-max: vertex enumeration by pivoting) |
//! | `linf` | min max t | [`linear_program`] (r ≥ 2: active-set LP) |
//! | `improved-closed-form` | Pott 2014 | [`improved_closed_form`] |
//! | `barycenter` | centroid of the feasible polygon, r = 2 | [`barycenter`] |
//! | `sotda` | stiffness-oriented, r = 2 (Picard, Caro, Plestan & Claveau 2020) | [`sotda`] |
//! | `pott-closed-form`, `pott-closed-form-ee` | t = t_m − W⁺(w_ext + W t_m) (Pott, Bruckmann & Mikelsons 2009), energy-efficient shift | [`pott_closed_form`] |
//! | `puncture` | from t₀ towards an interior point into the bounds (Müller, Reichert & Bruckmann 2014) | [`puncture`] |
//! | `dykstra` | Dykstra's / alternating projections (Hassan & Khajepour 2007) | [`dykstra`] |
//! | `l2-mid` | min ‖t − t_m‖₂ (QP, exact) | [`l2_mid`] |
//! | `vertex-centroid` | mean of the feasible polytope's vertices, any r (Mikelsons et al. 2008) | [`vertex_centroid`] |
//! | `p-norm` | min Σ\|t_i − t_m,i\|^p, log barriers, Newton (Gosselin & Grenier 2011) | [`p_norm`] |
//! | `optimally-safe` | max margin s (LP, Borgstrom et al. 2009) | [`optimally_safe`] |
//!
//! Options of these methods ([`MethodOptions`]: `interior`, `alternating`, `p`, `alpha`) are
//! given with [`TensionSolver::with_options`]. Iterative methods stop by documented rules
//! ([`Infeasibility::GaveUp`], never an "infeasible" verdict).
//!
//! With heavy elastic cables (`cdpr_kinematics::catenary`) any of them runs inside the
//! fixed point of [`sagging_statics`] ([`SaggingStatics`]), certified with the catenary forces.
//!
//! The geometry behind them: every equilibrium is t = t0 + N λ with N an orthonormal null-space
//! basis; [`feasible_interval`] (r = 1) and [`FeasiblePolygon`] (r = 2) expose the feasible
//! λ-sets. r = n − DOF is the redundancy. For r ≥ 3 dense active-set solvers work on the same
//! parametrisation (see the [`solver`] module docs); Clarabel ([`interior_point()`]) is their
//! numerical fallback and the oracle of the tests.
//!
//! ```
//! use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
//! use cdpr_tension::{Method, TensionBounds, TensionProblem, TensionSolver};
//! use nalgebra::{DVector, Vector3};
//!
//! // The thesis' 4-cable planar robot (Tables 6.1, 6.2), load L1 (Table 6.3).
//! let s = 0.1 / 2f64.sqrt();
//! let cable = |c: [f64; 2], a: [f64; 2]| Cable {
//!     frame: Vector3::new(c[0], c[1], 0.0),
//!     platform: Vector3::new(a[0], a[1], 0.0),
//!     pulley: None,
//! };
//! let robot = Robot::new(MotionPattern::Planar, vec![
//!     cable([1.0, 0.5], [s, s]),
//!     cable([-1.0, 0.5], [-s, s]),
//!     cable([-1.0, -0.5], [-0.1, -0.1]),
//!     cable([1.0, -0.5], [0.1, -0.1]),
//! ]).unwrap();
//! let w = robot.inverse_kinematics(&Pose::planar(0.0, 0.0, 0.0)).unwrap().wrench_matrix();
//! let load = DVector::from_vec(vec![0.0, -10.0, 0.0]);
//! let bounds = TensionBounds::uniform(4, 5.0, 100.0).unwrap();
//! let problem = TensionProblem::new(&w, &load, &bounds);
//!
//! let l1 = TensionSolver::new(Method::L1).solve(&problem).unwrap();
//! let cf = TensionSolver::new(Method::ClosedForm).solve(&problem).unwrap();
//! let (t1, tc) = (l1.tensions().unwrap(), cf.tensions().unwrap());
//! assert!((t1.sum() - tc.sum()).abs() < 1e-9);       // Alg. 6.1 = the LP optimum
//! assert!((&w * t1 + &load).amax() < 1e-12);          // equilibrium
//! assert!(t1.iter().all(|&t| (5.0..=100.0).contains(&t)));
//! ```

mod active_set;
pub mod barycenter;
pub mod binding;
mod bounds;
mod central_point;
pub mod certificate;
pub mod closed_form;
pub mod dykstra;
mod error;
pub mod feasible_polygon;
pub mod improved_closed_form;
mod infeasibility;
pub mod interior_point;
pub mod l2_mid;
/// Four f64 lanes (SIMD): the module of `cdpr-kinematics`, re-exported where it was first
/// defined.
pub use cdpr_kinematics::lanes;
pub mod linear_program;
mod method;
pub mod minimum_norm;
pub mod null_space;
pub mod optimally_safe;
mod outcome;
pub mod p_norm;
mod planar_active_set;
pub mod pott_closed_form;
pub mod profile;
pub mod puncture;
pub mod quadratic_program;
pub mod sagging_statics;
pub mod solver;
pub mod sotda;
pub mod vertex_centroid;
mod vertex_enumeration;
mod warm_point;

pub use binding::{BindingBound, ClosestBalance, closest_balancing_tensions};
pub use bounds::TensionBounds;
pub use certificate::{Certificate, certify};
pub use closed_form::{FeasibleInterval, feasible_interval};
pub use error::TensionError;
pub use feasible_polygon::FeasiblePolygon;
pub use interior_point::{Objective, interior_point};
pub use method::{Method, MethodOptions, PunctureInterior, RequiredRedundancy};
/// The nalgebra this crate's API uses (vectors, matrices, rotations): use it through this
/// re-export (`cdpr_tension::nalgebra::Vector3`) so that your types are the crate's types whatever
/// nalgebra version your own project pins.
pub use nalgebra;
pub use outcome::{
    GiveUp, Infeasibility, StiffnessData, TensionOutcome, TensionProblem, TensionSolution,
};
pub use sagging_statics::{SaggingOutcome, SaggingSettings, SaggingSolution, SaggingStatics};
pub use solver::TensionSolver;
pub use sotda::{SotdaSettings, SotdaVariant, sotda_displacement};

/// The README's examples (the crate's page on crates.io), compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
