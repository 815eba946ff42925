//! # The robot of a request
//!
//! A request carries its robot as data, never as a path (the browser has no file system): the
//! text of a robot file and its format ([`RobotSource`]), parsed by `cdpr-io` when the request is
//! deserialised. In JSON:
//!
//! ```json
//! { "format": "toml", "text": "name = \"tdpm-4\"\nmotion = \"planar\"\n…" }
//! ```
//!
//! `format` is `toml` (cdpr TOML), `caspr` (`text` is NAME_cables.xml, `bodies` is
//! NAME_bodies.xml; `cable_set` picks a `<cable_set id>`) or `wcrfx` (WireCenter). `file` is the
//! name shown in error messages; `kinematics` is `pulley` or `standard` (`standard` drops the
//! pulleys, as `cdpr --kinematics standard`). A front end that has already loaded the robot
//! (the command line) wraps it with [`Robot::from_description`]; such a robot serialises as the
//! cdpr TOML of [`RobotDescription::to_toml`].
//!
//! ## References
//! - docs/robot-file.md (the three formats).

use cdpr_io::RobotDescription;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::borrow::Cow;

use crate::ApiError;

/// The format of a robot file's text.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum RobotFileFormat {
    /// cdpr TOML (docs/robot-file.md).
    Toml,
    /// A CASPR single-body model: `text` is NAME_cables.xml, `bodies` NAME_bodies.xml.
    Caspr,
    /// A WireCenter `.wcrfx` file.
    Wcrfx,
}

/// The cable model: pulleys or straight cables (`cdpr --kinematics`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum KinematicsModel {
    /// Cables over their swivel pulleys (Pott 2018): length = wrapped arc + free segment.
    Pulley,
    /// Straight cables from each `frame` point; pulleys in the robot file are ignored.
    Standard,
}

impl KinematicsModel {
    /// The name on the command line and in JSON output.
    pub fn name(self) -> &'static str {
        match self {
            Self::Pulley => "pulley",
            Self::Standard => "standard",
        }
    }

    /// The model in force for a loaded robot: `pulley` when any cable has a pulley.
    pub fn of(robot: &RobotDescription) -> Self {
        if robot.robot.has_pulleys() {
            Self::Pulley
        } else {
            Self::Standard
        }
    }
}

/// A robot file as data: its format and text (see the module documentation).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct RobotSource {
    /// The file's format.
    pub format: RobotFileFormat,
    /// The file's text (CASPR: NAME_cables.xml).
    pub text: String,
    /// CASPR only: the text of NAME_bodies.xml.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bodies: Option<String>,
    /// The file name used in error messages (default `robot.toml`, `robot_cables.xml`,
    /// `robot.wcrfx`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// CASPR only: the `<cable_set id>` to read (default: the file's `default_cable_set`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cable_set: Option<String>,
    /// `standard` drops the pulleys (straight cables from each `frame` point); default: the
    /// file's own model.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kinematics: Option<KinematicsModel>,
}

impl RobotSource {
    /// A cdpr TOML robot file's text.
    pub fn toml(text: impl Into<String>) -> Self {
        Self {
            format: RobotFileFormat::Toml,
            text: text.into(),
            bodies: None,
            file: None,
            cable_set: None,
            kinematics: None,
        }
    }

    /// Parses the text (cdpr-io) and applies `kinematics`.
    pub fn parse(&self) -> Result<RobotDescription, ApiError> {
        let file = |default: &str| self.file.clone().unwrap_or_else(|| default.to_string());
        if self.cable_set.is_some() && self.format != RobotFileFormat::Caspr {
            return Err(ApiError::invalid(
                "cable_set applies to CASPR models only (NAME_cables.xml)",
            ));
        }
        let mut robot = match self.format {
            RobotFileFormat::Toml => RobotDescription::parse(&self.text, file("robot.toml"))?,
            RobotFileFormat::Wcrfx => {
                RobotDescription::parse_wcrfx(&self.text, file("robot.wcrfx"))?
            }
            RobotFileFormat::Caspr => {
                let bodies = self.bodies.as_deref().ok_or_else(|| {
                    ApiError::invalid("a CASPR model needs `bodies`, the text of NAME_bodies.xml")
                })?;
                RobotDescription::parse_caspr(
                    &self.text,
                    file("robot_cables.xml"),
                    bodies,
                    "robot_bodies.xml",
                    self.cable_set.as_deref(),
                )?
            }
        };
        if self.kinematics == Some(KinematicsModel::Standard) {
            robot.robot = robot.robot.without_pulleys();
        }
        Ok(robot)
    }
}

/// The robot of a request: a parsed [`RobotDescription`] and the source it came from. In JSON it
/// is a [`RobotSource`], parsed when the request is deserialised (a malformed file fails there,
/// with the file, line and key).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(try_from = "RobotSource", into = "RobotSource")]
pub struct Robot {
    description: RobotDescription,
    source: Option<RobotSource>,
}

impl Robot {
    /// Parses a robot file's text.
    pub fn from_source(source: RobotSource) -> Result<Self, ApiError> {
        Ok(Self {
            description: source.parse()?,
            source: Some(source),
        })
    }

    /// Wraps a robot already loaded (and with `--kinematics`/`--cable-set` applied) by the
    /// caller; it serialises as its cdpr TOML.
    pub fn from_description(description: RobotDescription) -> Self {
        Self {
            description,
            source: None,
        }
    }

    /// The parsed robot.
    pub fn description(&self) -> &RobotDescription {
        &self.description
    }

    /// The cable model in force: `pulley` when any cable has a pulley.
    pub fn kinematics_model(&self) -> KinematicsModel {
        KinematicsModel::of(&self.description)
    }
}

impl std::ops::Deref for Robot {
    type Target = RobotDescription;
    fn deref(&self) -> &RobotDescription {
        &self.description
    }
}

impl TryFrom<RobotSource> for Robot {
    type Error = ApiError;
    fn try_from(source: RobotSource) -> Result<Self, ApiError> {
        Self::from_source(source)
    }
}

impl From<Robot> for RobotSource {
    fn from(robot: Robot) -> Self {
        robot
            .source
            .unwrap_or_else(|| RobotSource::toml(robot.description.to_toml("")))
    }
}

impl JsonSchema for Robot {
    fn schema_name() -> Cow<'static, str> {
        RobotSource::schema_name()
    }

    fn json_schema(generator: &mut schemars::SchemaGenerator) -> schemars::Schema {
        RobotSource::json_schema(generator)
    }
}
