//! # cdpr-api
//!
//! One typed request and one report per analysis of cable-driven parallel robots: the layer
//! under every front end. The `cdpr` command parses its arguments into a request, runs it and
//! renders the report (its `--json` output is the serialised report); Python builds the same
//! requests from keyword arguments; a browser builds them from a form and sends them as JSON.
//! The crate sits beside the analysis stack, above every analysis crate and `cdpr-io`; it needs
//! no file system, no command line and no plotting (it builds for `wasm32-unknown-unknown`
//! without its default `parallel` feature).
//!
//! | request | report | analysis |
//! |---|---|---|
//! | [`KinematicsRequest`] | [`KinematicsReport`] | inverse kinematics, wrench matrix W |
//! | [`ForwardRequest`] | [`ForwardReport`] | forward kinematics from cable lengths |
//! | [`TensionRequest`] | [`TensionReport`] | tension distribution by any method |
//! | [`StiffnessRequest`] | [`StiffnessReport`] | stiffness K = Kp + Ka |
//! | [`CapacityRequest`] | [`CapacityReport`] | capacity margin of a required wrench set |
//! | [`IsotropicRequest`] | [`IsotropicReport`] | isotropic force, force polytope, ellipse |
//! | [`IsotropicMapRequest`] | [`IsotropicMapReport`] | isotropic force over a grid |
//! | [`WorkspaceRequest`] | [`WorkspaceReport`] | constant-orientation workspace on a grid |
//! | [`MeshRequest`] | [`MeshReport`] | boundary mesh of a 3-D workspace and its volume |
//! | [`SectionRequest`] | [`SectionReport`] | plane section of a 3-D workspace (chord method) |
//! | [`ChordRequest`] | [`ChordReport`] | boundary curves of a planar workspace (chord method) |
//! | [`StiffnessMapRequest`] | [`StiffnessMapReport`] | displacement over the feasible polygon (SOTDA study) |
//! | [`OrientationsRequest`] | [`OrientationsReport`] | feasible orientations of a set at one position |
//! | [`OrientationWorkspaceRequest`] | [`OrientationWorkspaceReport`], [`OrientationMeshReport`] | total-orientation or maximal workspace of an orientation set |
//! | [`DextrousRequest`] | [`DextrousReport`] | dextrous workspace over a range of orientations |
//! | [`SynthesisRequest`] | [`SynthesisReport`] | anchor placement for maximal dextrous area (planar) |
//! | [`CalibrationRequest`] | [`CalibrationReport`] | kinematic calibration from cable-length readings |
//! | [`sagging::SaggingKinematicsRequest`] | [`sagging::SaggingKinematicsReport`] | inverse kinematics with elastic or sagging cables |
//! | [`sagging::SaggingTensionRequest`] | [`sagging::SaggingTensionReport`] | statics with elastic or sagging cables |
//! | [`sagging::ElastoGeometricRequest`] | [`sagging::ElastoGeometricReport`] | elasto-geometric forward kinematics from unstrained lengths |
//!
//! Each request is `serde` (de)serialisable and has `validate()` (the checks, with the messages
//! the command line prints) and `run()`; each report is `serde` serialisable and has a JSON
//! Schema ([`schema`]). The robot travels as a robot file's text ([`RobotSource`]).
//!
//! ```
//! use cdpr_api::{Method, Robot, RobotSource, TensionRequest};
//!
//! let text = std::fs::read_to_string(concat!(
//!     env!("CARGO_MANIFEST_DIR"),
//!     "/../../examples/robots/tdpm-4.toml"
//! ))
//! .unwrap();
//! let robot = Robot::from_source(RobotSource::toml(text)).unwrap();
//! let request = TensionRequest::new(robot, vec![0.0, 0.0, 0.0], Method::L2);
//! let report = request.run().unwrap();
//! assert!(report.feasible);
//! assert_eq!(report.tensions.unwrap().len(), 4);
//! ```
//!
//! ## References
//! - docs/architecture.md, "Requests and reports".

pub mod cable_model;
mod calibration;
mod capacity;
mod chord;
pub mod criteria;
mod dextrous;
mod error;
mod forward;
pub mod inputs;
mod isotropic;
mod isotropic_map;
mod kinematics;
mod mesh;
mod orientation_map;
mod orientation_set;
pub mod region;
mod robot;
pub mod rows;
pub mod sagging;
pub mod schema;
mod section;
pub mod simulate;
mod stiffness;
mod stiffness_map;
mod synthesis;
mod tension;
pub mod timed;
pub mod trajectory;
mod workspace;

pub use calibration::{
    CalibrationReport, CalibrationRequest, SamplesSource, SigmaReport, parse_samples_csv,
    pose_columns,
};
pub use capacity::{CapacityReport, CapacityRequest, FacetReport, RequiredReport};
pub use chord::{ChordReport, ChordRequest, CurvesReport, DEFAULT_CHORD, chord_settings};
pub use criteria::{CriteriaSetup, WorkspaceCriteria, default_method};
pub use dextrous::{
    CentralCheckReport, Dextrous, DextrousReport, DextrousRequest, RangeReport, dextrous,
};
pub use error::ApiError;
pub use forward::{ForwardReport, ForwardRequest, ForwardSolutionReport};
pub use isotropic::{EllipseReport, IsotropicReport, IsotropicRequest, definition};
pub use isotropic_map::{
    IsotropicMapReport, IsotropicMapRequest, MapGridReport, MapStatsReport, SliceReport,
};
pub use kinematics::{
    KinematicsReport, KinematicsRequest, PassiveSpringsReport, PlatformInterferenceReport,
};
pub use mesh::{BoxFacesReport, MeshReport, MeshRequest, ShellReport};
pub use orientation_map::{
    FractionMapReport, OrientationsReport, OrientationsRequest, SampleReport,
};
pub use orientation_set::{
    LimitingCountReport, LimitingReport, LimitingVerticesReport, OrientationMeshReport,
    OrientationWorkspaceReport, OrientationWorkspaceRequest, degrees, orientation_test,
};
pub use robot::{KinematicsModel, Robot, RobotFileFormat, RobotSource};
pub use section::{Axis, SectionPlane, SectionPlaneReport, SectionReport, SectionRequest};
pub use stiffness::{StiffnessReport, StiffnessRequest};
pub use stiffness_map::{
    DISPLACEMENT_UNIT, LambdaGridReport, MapReport, StiffnessMapReport, StiffnessMapRequest,
};
pub use synthesis::{
    EvaluationsReport, SynthesisOptimizer, SynthesisReport, SynthesisRequest, synthesis_method,
};
pub use tension::{
    BindingCable, BindingReport, PeerOptions, PolygonReport, SotdaReport, SotdaSearch,
    TensionReport, TensionRequest, sotda_settings,
};
pub use tension::{MethodSettings, refuse_sotda_options};
pub use workspace::{
    PreparedWorkspace, WorkspaceReport, WorkspaceRequest, box_numbers, orientation_or_default,
};

/// The nalgebra of the whole stack.
pub use nalgebra;

/// A loaded robot file ([`Robot::from_description`]).
pub use cdpr_io::RobotDescription;
/// The tension distribution methods a request names.
pub use cdpr_tension::Method;

/// The README's examples (the crate's page on crates.io), compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
