//! # Plane sections of a 3-D workspace
//!
//! The exact boundary of the constant-orientation workspace (thesis eq. 6.23) of a robot moving
//! in space in one coordinate plane x = c, y = c or z = c, by the chord method of thesis §6.4.3
//! (Algorithm 6.3) walked in that plane: closed polygons with vertices on the boundary (to
//! ε^u = 10⁻⁸ m) a chord length d apart, seeded by an (M+1)² grid of the plane's part of the
//! box, in the plane's coordinates (y, z for x = c; x, z for y = c; x, y for z = c).
//!
//! ## References
//! - Thesis §6.4.3 and Algorithm 6.3 (the chord method), eq. 6.23.

use std::fmt;
use std::str::FromStr;

use cdpr_workspace::{ChordSettings, Section, chord_section};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::chord::{CurvesReport, DEFAULT_CHORD, chord_settings};
use crate::criteria::WorkspaceCriteria;
use crate::workspace::{PreparedWorkspace, box_numbers, orientation_or_default};
use crate::{ApiError, Robot};

/// A coordinate axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Axis {
    /// x.
    X,
    /// y.
    Y,
    /// z.
    Z,
}

impl Axis {
    /// 0, 1 or 2.
    pub fn index(self) -> usize {
        self as usize
    }

    /// `x`, `y` or `z`.
    pub fn name(self) -> &'static str {
        ["x", "y", "z"][self as usize]
    }

    /// The axis of index 0, 1 or 2.
    fn of(k: usize) -> Self {
        [Axis::X, Axis::Y, Axis::Z][k.min(2)]
    }
}

/// The plane of a section: `axis` = `value` (m), e.g. z = 1.2.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SectionPlane {
    /// The axis normal to the plane.
    pub axis: Axis,
    /// The plane's coordinate along that axis (m).
    pub value: f64,
}

impl fmt::Display for SectionPlane {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}={}", self.axis.name(), self.value)
    }
}

impl FromStr for SectionPlane {
    type Err = ApiError;

    /// `AXIS=VALUE` as the command line writes it (`z=1.2`).
    fn from_str(s: &str) -> Result<Self, ApiError> {
        let (axis, value) = s.split_once('=').ok_or_else(|| {
            ApiError::invalid(format!("--section {s}: expected AXIS=VALUE, e.g. z=1.2"))
        })?;
        let axis = match axis.trim() {
            "x" => Axis::X,
            "y" => Axis::Y,
            "z" => Axis::Z,
            a => {
                return Err(ApiError::invalid(format!(
                    "--section {s}: axis `{a}` is not x, y or z"
                )));
            }
        };
        let value = value
            .trim()
            .parse()
            .map_err(|_| ApiError::invalid(format!("--section {s}: `{value}` is not a number")))?;
        Ok(Self { axis, value })
    }
}

/// A plane section of a 3-D workspace (`cdpr workspace --section AXIS=VALUE`).
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
pub struct SectionRequest {
    /// The robot (moving in space: `point3` or `spatial`).
    pub robot: Robot,
    /// The criteria and their load.
    #[serde(flatten)]
    pub criteria: WorkspaceCriteria,
    /// Platform orientation: rx,ry,rz (rad, XYZ Euler angles, spatial); none for point robots.
    #[serde(default)]
    pub orientation: Option<Vec<f64>>,
    /// `XMIN,XMAX,YMIN,YMAX,ZMIN,ZMAX` (m); default: the frame anchors' bounding box (extended
    /// below anchors that span little height). The plane must cross it.
    #[serde(default, rename = "box")]
    pub area: Option<Vec<f64>>,
    /// M: intervals per side of the grid of the plane that seeds the walks (default 20).
    #[serde(default)]
    pub grid: Option<usize>,
    /// The plane.
    pub section: SectionPlane,
    /// Chord length d (m; default 0.05, the thesis' value).
    #[serde(default = "default_chord")]
    pub chord: f64,
}

fn default_chord() -> f64 {
    DEFAULT_CHORD
}

/// Where the section lies.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct SectionPlaneReport {
    /// The axis normal to the plane (`x`, `y` or `z`).
    pub axis: String,
    /// The plane's coordinate along it (m).
    pub value: f64,
    /// The in-plane axes, in the order of the boundary points' coordinates.
    pub plane_axes: [String; 2],
}

/// The JSON of `cdpr workspace --section AXIS=VALUE --json`.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct SectionReport {
    /// Robot name.
    pub robot: String,
    /// `chord`.
    pub method: String,
    /// The plane.
    pub section: SectionPlaneReport,
    /// Platform orientation (rad; empty for point robots).
    pub orientation: Vec<f64>,
    /// w_ext = w_e + the robot file's load (N, N·m).
    pub external_wrench: Vec<f64>,
    /// Criterion labels.
    pub criteria: Vec<String>,
    /// Tension method of the tension criterion.
    pub tension_method: String,
    /// `XMIN,XMAX,YMIN,YMAX,ZMIN,ZMAX` (m).
    #[serde(rename = "box")]
    pub area_box: Vec<f64>,
    /// Chord length d (m).
    pub chord: f64,
    /// The curves, in the plane's coordinates (`section.plane_axes`).
    #[serde(flatten)]
    pub curves: CurvesReport,
    /// Bisection tolerance ε^u of the boundary points (m; not in JSON).
    #[serde(skip)]
    pub tolerance: f64,
}

impl SectionRequest {
    /// A request for the plane `section` with the default criteria, orientation, box, grid and
    /// chord.
    pub fn new(robot: Robot, section: SectionPlane) -> Self {
        Self {
            robot,
            criteria: WorkspaceCriteria::default(),
            orientation: None,
            area: None,
            grid: None,
            section,
            chord: DEFAULT_CHORD,
        }
    }

    /// Checks the request and builds its criteria, seed grid, evaluator, plane and settings.
    pub fn prepare(&self) -> Result<(PreparedWorkspace, Section, ChordSettings), ApiError> {
        let motion = self.robot.robot.motion();
        if motion.space_dim() != 3 {
            return Err(ApiError::invalid(format!(
                "--section {} cuts a workspace in space; this robot is `{}` (moving in a plane): \
                 use --boundary chord for its exact boundary",
                self.section,
                motion.name()
            )));
        }
        let p = PreparedWorkspace::new(
            &self.robot,
            &self.criteria,
            self.orientation.as_deref(),
            self.area.as_deref(),
            self.grid,
        )?;
        let (axis, value) = (self.section.axis.index(), self.section.value);
        let section = Section { axis, value };
        let r = &p.grid.region;
        section.validate(r).map_err(|_| {
            ApiError::invalid(format!(
                "--section {}: {} = {value} is outside the box [{}, {}] (m)",
                self.section,
                self.section.axis.name(),
                r.min[axis],
                r.max[axis]
            ))
        })?;
        let settings = chord_settings(self.chord, p.grid.resolution)?;
        Ok((p, section, settings))
    }

    /// Checks the request.
    pub fn validate(&self) -> Result<(), ApiError> {
        self.prepare().map(|_| ())
    }

    /// Walks the boundaries in the plane.
    pub fn run(&self) -> Result<SectionReport, ApiError> {
        let (p, section, settings) = self.prepare()?;
        let desc = self.robot.description();
        let ws = chord_section(
            &p.evaluator,
            &p.rotation,
            section,
            &p.grid.region,
            &settings,
        )?;
        let w_ext = p.setup.external_wrench(desc, &p.rotation)?;
        let [a, b] = section.in_plane_axes();
        Ok(SectionReport {
            robot: desc.name.clone(),
            method: "chord".into(),
            section: SectionPlaneReport {
                axis: self.section.axis.name().into(),
                value: self.section.value,
                plane_axes: [Axis::of(a).name().into(), Axis::of(b).name().into()],
            },
            orientation: orientation_or_default(desc.robot.motion(), self.orientation.as_deref()),
            external_wrench: w_ext.as_slice().to_vec(),
            criteria: p.setup.labels(),
            tension_method: p.setup.method.name().into(),
            area_box: box_numbers(&p.grid.region, 3),
            chord: self.chord,
            curves: CurvesReport::new(&ws),
            tolerance: settings.tolerance,
        })
    }
}
