//! # cdpr-io
//!
//! Robot files of cable-driven parallel robots, beside the analysis stack of `cdpr`: a
//! [`RobotDescription`] is everything a file says about a robot — the kinematic
//! [`Robot`](cdpr_kinematics::Robot) (with swivel pulleys where the file has them), tension
//! bounds, workspace limits, platform mass properties and inertia, per-cable axial stiffness and
//! cable names. This crate needs neither plotting nor a command line, so other projects can
//! read robot files with it alone.
//!
//! Three formats, told apart by the file name ([`RobotFormat`]):
//! - cdpr TOML (`.toml`, read and written: [`RobotDescription::parse`], [`RobotDescription::to_toml`]);
//! - CASPR XML single-body models (`NAME_cables.xml` with `NAME_bodies.xml` beside it, read:
//!   [`RobotDescription::parse_caspr`]);
//! - WireCenter `.wcrfx` (read and written: [`RobotDescription::parse_wcrfx`],
//!   [`RobotDescription::to_wcrfx`]).
//!
//! and CASPR's joint-space trajectories (`NAME_trajectories.xml`: [`parse_caspr_trajectory`]).
//!
//! ```
//! use cdpr_io::RobotDescription;
//!
//! let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/robots/tdpm-4.toml");
//! let robot = RobotDescription::load(file).unwrap();
//! assert_eq!(robot.robot.cable_count(), 4);
//! ```
//!
//! ## References
//! - Lau, Eden, Tan & Oetomo, CASPR, IROS 2016 (the CASPR XML model files).
//! - Pott, *Cable-Driven Parallel Robots: Theory and Application*, Springer 2018 (WireCenter).

mod caspr;
mod caspr_trajectory;
mod toml_file;
mod toml_writer;
mod wirecenter;
mod xml;

pub use caspr::{CASPR_GRAVITY, pulley_frame};
pub use caspr_trajectory::{
    CasprTrajectory, caspr_trajectory_ids, load_caspr_trajectory, parse_caspr_trajectory,
};
pub use nalgebra;
pub use toml_file::{Encoders, Limits, RobotDescription, RobotFileError, pulley_toml};
pub use wirecenter::{WIRELIB_DEFAULT_BOUNDS, WIRELIB_DEFAULT_PULLEY_RADIUS, WIRELIB_GRAVITY};

use std::path::Path;

/// The format of a robot file, from its name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum RobotFormat {
    /// cdpr TOML (`.toml`).
    Toml,
    /// A CASPR model (`NAME_cables.xml` + `NAME_bodies.xml`).
    Caspr,
    /// A WireCenter robot file (`.wcrfx`).
    WireCenter,
}

impl RobotFormat {
    /// The format of `path` by its extension (`.toml`, `.xml`, `.wcrfx`, any case).
    pub fn from_path(path: impl AsRef<Path>) -> Result<Self, RobotFileError> {
        let path = path.as_ref();
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .unwrap_or_default();
        match ext.as_str() {
            "toml" => Ok(Self::Toml),
            "xml" => Ok(Self::Caspr),
            "wcrfx" => Ok(Self::WireCenter),
            _ => Err(RobotFileError::Format {
                file: path.to_path_buf(),
                message: "unknown robot file type: expected .toml (cdpr), NAME_cables.xml (CASPR) or .wcrfx (WireCenter)".into(),
            }),
        }
    }
}

/// Options of [`RobotDescription::load_with`].
#[derive(Debug, Clone, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct LoadOptions {
    /// The CASPR `<cable_set id>` to read (default: the file's `default_cable_set`); an error
    /// for the other formats, which have no cable sets.
    pub cable_set: Option<String>,
}

impl LoadOptions {
    /// Options that read the given CASPR cable set.
    pub fn cable_set(id: impl Into<String>) -> Self {
        Self {
            cable_set: Some(id.into()),
        }
    }
}

fn read(path: &Path) -> Result<String, RobotFileError> {
    std::fs::read_to_string(path).map_err(|source| RobotFileError::Io {
        file: path.to_path_buf(),
        source,
    })
}

impl RobotDescription {
    /// Reads and validates a robot file in any of the three formats (by extension).
    pub fn load(path: impl AsRef<Path>) -> Result<Self, RobotFileError> {
        Self::load_with(path, &LoadOptions::default())
    }

    /// [`RobotDescription::load`] with options (a CASPR cable set).
    pub fn load_with(
        path: impl AsRef<Path>,
        options: &LoadOptions,
    ) -> Result<Self, RobotFileError> {
        let path = path.as_ref();
        let format = RobotFormat::from_path(path)?;
        if options.cable_set.is_some() && format != RobotFormat::Caspr {
            return Err(RobotFileError::Format {
                file: path.to_path_buf(),
                message: "--cable-set applies to CASPR models only (NAME_cables.xml)".into(),
            });
        }
        match format {
            RobotFormat::Toml => Self::load_toml(path),
            RobotFormat::WireCenter => Self::parse_wcrfx(&read(path)?, path),
            RobotFormat::Caspr => {
                let (cables, bodies, _) = caspr::companion_paths(path)?;
                let cables_text = read(&cables)?;
                let bodies_text = read(&bodies)?;
                Self::parse_caspr(
                    &cables_text,
                    &cables,
                    &bodies_text,
                    &bodies,
                    options.cable_set.as_deref(),
                )
            }
        }
    }

    /// Writes the robot as TOML or `.wcrfx` (by extension; `header` becomes a TOML comment).
    /// Returns what the format could not hold (see [`RobotDescription::wcrfx_losses`]); fails
    /// when it cannot hold a modelled number, or for CASPR (read-only).
    pub fn save(
        &self,
        path: impl AsRef<Path>,
        header: &str,
    ) -> Result<Vec<String>, RobotFileError> {
        let path = path.as_ref();
        let (text, losses) = match RobotFormat::from_path(path)? {
            RobotFormat::Toml => (self.to_toml(header), Vec::new()),
            RobotFormat::WireCenter => (self.to_wcrfx(path)?, self.wcrfx_losses()),
            RobotFormat::Caspr => {
                return Err(RobotFileError::Unrepresentable {
                    file: path.to_path_buf(),
                    format: "CASPR XML",
                    message:
                        "cdpr reads CASPR models but does not write them: write .toml or .wcrfx"
                            .into(),
                });
            }
        };
        std::fs::write(path, text).map_err(|source| RobotFileError::Io {
            file: path.to_path_buf(),
            source,
        })?;
        Ok(losses)
    }
}

/// The README's examples (the crate's page on crates.io), compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
