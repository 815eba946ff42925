//! # cdpr-studio
//!
//! The cdpr studio: one static page (`cargo xtask studio` → `target/studio/`) that runs the cdpr
//! crates themselves in the browser, compiled to WebAssembly, offline, with nothing installed.
//! This crate is the Rust half of the page: a [`Studio`] session holds the robot the user opened
//! and answers the page's questions with JSON, computed by the library crates (the page computes
//! nothing itself; it draws).
//!
//! - [`Studio::open`]: a robot file by name and text (cdpr TOML, CASPR `NAME_cables.xml` with
//!   `NAME_bodies.xml`, WireCenter `.wcrfx`; [`cdpr_io`] reads them);
//! - [`Studio::state`]: the state at a pose for a tension method and an external wrench — cable
//!   lengths (m), tensions (N), feasibility and its reason, capacity margin and isotropic force;
//!   the same numbers as `cdpr kinematics` and `cdpr tension --json`;
//! - [`Studio::scene`]: anchors, cables and platform faces at a pose, for the 3-D view;
//! - [`Studio::edit`], [`Studio::to_toml`], [`Studio::to_wcrfx`]: the robot table and downloads;
//! - [`Studio::workspace_grid`]: the constant-orientation workspace on a grid (cdpr-api's
//!   workspace request, `cdpr workspace --json`) and its feasible points;
//! - [`Studio::workspace_mesh`]: the boundary mesh of the constant-orientation workspace, its
//!   volume, STL file;
//! - [`Studio::trajectory`]: a path or timed trajectory (`cdpr trajectory --json`);
//! - [`Studio::workspace_section`]: a plane section of that workspace by the chord method.
//!
//! The JavaScript bindings (`wasm-bindgen`) are compiled only for `wasm32`; natively the crate is
//! the plain session logic, tested with `cargo test -p cdpr-studio`.
//!
//! ```
//! use cdpr_studio::{RobotFileText, Studio};
//!
//! let text = std::fs::read_to_string(concat!(
//!     env!("CARGO_MANIFEST_DIR"),
//!     "/../../examples/robots/tdpm-4.toml"
//! ))?;
//! let studio = Studio::open(&[RobotFileText { name: "tdpm-4.toml".into(), text }])?;
//! let state = studio.state(&[0.0, 0.0, 0.0], "l2", None)?;
//! assert_eq!(state.lengths.len(), 4);
//! assert!(state.feasible);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## References
//! - Lau, Eden, Tan & Oetomo 2016 (CASPR files); Pott 2018 (WireCenter files).
//! - The methods' references: [`cdpr_tension::Method::summary`].

#[cfg(target_arch = "wasm32")]
mod bindings;
mod error;
mod files;
mod grid;
mod mesh;
mod robot_table;
mod scene;
mod section;
mod state;
mod trajectory;

pub use error::StudioError;
pub use files::RobotFileText;
pub use grid::GridReport;
pub use mesh::MeshReport;
pub use robot_table::RobotTable;
pub use scene::SceneData;
pub use section::{SectionReport, SectionSettings};
pub use state::State;
pub use trajectory::PathSettings;

use cdpr_io::RobotDescription;

/// One studio session: the robot the page shows.
#[derive(Debug, Clone)]
pub struct Studio {
    desc: RobotDescription,
}

impl Studio {
    /// Opens a robot from the texts of its file(s) (see [`files`](RobotFileText)).
    pub fn open(files: &[RobotFileText]) -> Result<Self, StudioError> {
        Ok(Self {
            desc: files::parse(files)?,
        })
    }

    /// The robot as read (cdpr-io's description).
    pub fn description(&self) -> &RobotDescription {
        &self.desc
    }
}

#[cfg(test)]
mod test_support {
    use crate::{RobotFileText, Studio};

    /// A shipped example robot (`examples/robots/NAME`), opened as the page opens a file.
    pub fn open(name: &str) -> Studio {
        let path = format!(
            "{}/../../examples/robots/{name}",
            env!("CARGO_MANIFEST_DIR")
        );
        Studio::open(&[RobotFileText {
            name: name.into(),
            text: std::fs::read_to_string(path).unwrap(),
        }])
        .unwrap()
    }
}
