//! # cdpr-workspace
//!
//! Workspace analysis and dimensional synthesis of cable-driven parallel robots (the thesis
//! chapter on planar tendon-driven manipulators, §§6.4–6.6).
//!
//! **Vocabulary.**
//! - [`Criterion`]: one condition on a pose: tensions within bounds for a load under a chosen
//!   tension method (eq. (6.21)), minimum cable length (6.22), Jacobian determinant floor (6.24),
//!   wrench closure, capacity margin, isotropic force, stiffness floor, or a user closure.
//! - [`PoseEvaluator`]: a robot, its tension bounds and a list of criteria (all must hold,
//!   eq. (6.23)); tests poses without allocating.
//! - [`Region`] and [`Grid`]: the box searched (by default the frame anchors' bounding box) and
//!   its (m+1)² (or (m+1)³) points.
//!
//! **Methods** (one module each):
//! - [`discretisation`]: Algorithm 6.2, constant-orientation workspace on a grid
//!   ([`constant_orientation_workspace`], [`planar_workspace`]), parallel and deterministic.
//! - [`chord`]: the chord method of §6.4.3 and Algorithm 6.3: boundary polygons of every region
//!   and hole, bifurcation points, shoelace areas ([`chord_workspace`]).
//! - [`boundary_mesh`](mod@boundary_mesh): the boundary of a 3-D workspace as a closed triangle
//!   mesh (marching cubes over the grid verdicts, vertices bisected onto the boundary), its
//!   volume by the divergence theorem ([`boundary_mesh()`]).
//! - [`dextrous`]: eq. (6.28), the intersection over m_sl orientations, with the §6.5 check of
//!   the two-extremes shortcut ([`dextrous_workspace`]).
//! - [`wrench_closure`]: positive spanning of W (null-space tests, LP fallback).
//! - [`orientation_workspace`](mod@orientation_workspace): total-orientation, maximal and
//!   at-a-position orientation workspaces of spatial robots over an [`OrientationSet`] (Euler
//!   box or tilt cone).
//! - [`synthesis`]: dimensional synthesis for maximal dextrous workspace (§6.6).
//!
//! ```
//! use cdpr_kinematics::{Cable, MotionPattern, Robot};
//! use cdpr_tension::{Method, TensionBounds};
//! use cdpr_workspace::{
//!     chord_workspace, dextrous_workspace, planar_workspace, ChordSettings, Criterion, Grid,
//!     OrientationRange, PoseEvaluator, Region,
//! };
//! use nalgebra::{DVector, Vector3};
//!
//! // The thesis' 4-cable robot (Tables 6.1, 6.2), limits of Table 6.4, load L1 (Table 6.3).
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
//! ])?;
//! let eval = PoseEvaluator::new(
//!     robot,
//!     TensionBounds::uniform(4, 5.0, 100.0)?,
//!     vec![
//!         Criterion::TensionFeasible { method: Method::L2, wrench: DVector::from_vec(vec![0.0, -10.0, 0.0]) },
//!         Criterion::MinCableLength(0.1),
//!     ],
//! )?;
//!
//! // Algorithm 6.2 with m = 50 over the anchors' bounding box, at φ = 0.
//! let grid = Grid::over_frame(eval.robot(), 50);
//! let ws = planar_workspace(&eval, 0.0, &grid)?;
//! assert_eq!(ws.total_points, 51 * 51);
//!
//! // The chord method maps the same workspace's boundary (d = 0.05, ε = 1e-8).
//! let chord = chord_workspace(&eval, 0.0, &grid.region, &ChordSettings::default())?;
//! assert!((chord.area - ws.area).abs() < 0.05 * chord.area);
//!
//! // Dextrous workspace for φ ∈ [−0.1, 0.1], three slices, with the §6.5 check.
//! let dex = dextrous_workspace(&eval, &OrientationRange { min: -0.1, max: 0.1, slices: 3 }, &grid)?;
//! assert!(dex.workspace.is_subset_of(&ws));
//! assert!(dex.central_check.holds);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod boundary_mesh;
pub mod chord;
mod criteria;
mod criteria_spec;
pub mod dextrous;
pub mod discretisation;
mod dynamic;
mod error;
mod evaluator;
mod mesh_files;
pub mod orientation_workspace;
mod parallel;
mod region;
pub mod synthesis;
pub mod wrench_closure;

pub use boundary_mesh::{
    BoundaryMesh, BoxFace, MeshSettings, MeshVertex, Shell, boundary_mesh, boundary_mesh_of,
};
pub use chord::{
    ChordSettings, ChordWorkspace, InteriorPoint, Polygon, Section, chord_section, chord_workspace,
};
pub use criteria::{Criterion, CustomCriterion, CustomTest, PoseContext};
pub use criteria_spec::{CriteriaError, CriterionSpec, parse_criteria};
pub use dextrous::{
    CentralCheck, DextrousWorkspace, LeanScratch, OrientationIndex, OrientationRange, PlanarSlice,
    dextrous_verdicts_lean, dextrous_workspace, dextrous_workspace_about_axis,
    dextrous_workspace_over, euler_box,
};
pub use discretisation::{
    Grid, GridWorkspace, VolumeConvention, constant_orientation_workspace, planar_workspace,
};
pub use dynamic::dynamic_criterion;
pub use error::WorkspaceError;
pub use evaluator::PoseEvaluator;
/// The nalgebra this crate's API uses (vectors, matrices, rotations): use it through this
/// re-export (`cdpr_workspace::nalgebra::Vector3`) so that your types are the crate's types whatever
/// nalgebra version your own project pins.
pub use nalgebra;
pub use orientation_workspace::{
    LimitingOrientation, OrientationGridWorkspace, OrientationMesh, OrientationSet,
    OrientationSyntaxError, OrientationTest, OrientationWorkspaceKind, SampledOrientation,
    orientation_boundary_mesh, orientation_workspace, tilt_torsion_rotation,
};
pub use region::Region;

/// The README's examples (the crate's page on crates.io), compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
