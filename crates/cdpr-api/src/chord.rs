//! # Boundary curves by the chord method
//!
//! The exact boundary of a planar constant-orientation workspace (thesis §6.4.3, Algorithm 6.3):
//! closed polygons whose vertices lie on the boundary (bisection to ε^u = 10⁻⁸ m, or d/1000 for
//! chords under 10⁻⁵ m) a chord length d apart, every region and hole seeded by a coarse grid of
//! (M+1)² points, corners (bifurcation points) refined; the area is the sum of the polygons'
//! signed areas (counter-clockwise around regions, clockwise around holes). Robots moving in a
//! plane (`point2`, `planar`) only; [`crate::SectionRequest`] cuts a 3-D workspace by a plane.
//!
//! ## References
//! - Thesis §6.4.3 and Algorithm 6.3 (the chord method).

use cdpr_kinematics::MotionPattern;
use cdpr_workspace::{ChordSettings, ChordWorkspace, Polygon, chord_workspace};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::criteria::WorkspaceCriteria;
use crate::workspace::{PreparedWorkspace, box_numbers, orientation_or_default};
use crate::{ApiError, Robot};

/// The chord length d of the thesis (m).
pub const DEFAULT_CHORD: f64 = 0.05;

fn default_chord() -> f64 {
    DEFAULT_CHORD
}

/// The boundary curves of a planar workspace (`cdpr workspace --boundary chord`).
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
pub struct ChordRequest {
    /// The robot (moving in a plane: `point2` or `planar`).
    pub robot: Robot,
    /// The criteria and their load.
    #[serde(flatten)]
    pub criteria: WorkspaceCriteria,
    /// Platform orientation φ (rad, planar robots); none for point robots.
    #[serde(default)]
    pub orientation: Option<Vec<f64>>,
    /// `XMIN,XMAX,YMIN,YMAX` (m); default: the frame anchors' bounding box.
    #[serde(default, rename = "box")]
    pub area: Option<Vec<f64>>,
    /// M: intervals per side of the coarse grid that seeds the walks (default 50).
    #[serde(default)]
    pub grid: Option<usize>,
    /// Chord length d (m; default 0.05, the thesis' value).
    #[serde(default = "default_chord")]
    pub chord: f64,
}

/// The curves the chord method found (shared by [`ChordReport`] and [`crate::SectionReport`]).
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct CurvesReport {
    /// The sum of the polygons' signed areas (m²).
    pub area: f64,
    /// Closed polygons [[a, b], …] (m): counter-clockwise around regions, clockwise around
    /// holes.
    pub boundaries: Vec<Vec<[f64; 2]>>,
    /// Signed area of each polygon (m²).
    pub signed_areas: Vec<f64>,
    /// The bifurcation points (boundary corners) of each polygon (m).
    pub bifurcations: Vec<Vec<[f64; 2]>>,
    /// Walks abandoned (their curves are missing).
    pub abandoned: usize,
    /// Pose evaluations, coarse grid included.
    pub evaluations: usize,
}

impl CurvesReport {
    /// The report of a chord-method result.
    pub fn new(ws: &ChordWorkspace) -> Self {
        let b = &ws.boundaries;
        Self {
            area: ws.area,
            boundaries: b.iter().map(|p| p.vertices.clone()).collect(),
            signed_areas: b.iter().map(|p| p.signed_area()).collect(),
            bifurcations: b
                .iter()
                .map(|p| p.bifurcations.iter().map(|&k| p.vertices[k]).collect())
                .collect(),
            abandoned: ws.abandoned,
            evaluations: ws.evaluations,
        }
    }

    /// Perimeter of polygon `k` (m), the closing edge included.
    pub fn perimeter(&self, k: usize) -> f64 {
        Polygon {
            vertices: self.boundaries[k].clone(),
            bifurcations: Vec::new(),
        }
        .perimeter()
    }

    /// Regions (counter-clockwise boundaries) and holes (clockwise).
    pub fn regions_and_holes(&self) -> (usize, usize) {
        let regions = self.signed_areas.iter().filter(|&&a| a > 0.0).count();
        (regions, self.signed_areas.len() - regions)
    }
}

/// The JSON of `cdpr workspace --boundary chord --json`.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct ChordReport {
    /// Robot name.
    pub robot: String,
    /// `chord`.
    pub method: String,
    /// Platform orientation (rad; empty for point robots).
    pub orientation: Vec<f64>,
    /// w_ext = w_e + the robot file's load (N, N·m).
    pub external_wrench: Vec<f64>,
    /// Criterion labels.
    pub criteria: Vec<String>,
    /// Tension method of the tension criterion.
    pub tension_method: String,
    /// `XMIN,XMAX,YMIN,YMAX` (m).
    #[serde(rename = "box")]
    pub area_box: Vec<f64>,
    /// Chord length d (m).
    pub chord: f64,
    /// The curves.
    #[serde(flatten)]
    pub curves: CurvesReport,
    /// Bisection tolerance ε^u of the boundary points (m; not in JSON).
    #[serde(skip)]
    pub tolerance: f64,
}

/// The settings of the chord method for chord length `chord` and a seed grid of M = `m`: the
/// bisection tolerance ε^u stays below d/100 (10⁻⁸ m, smaller for chords under 10⁻⁶ m; the
/// user sets d only, so no tolerance of theirs is at fault).
pub fn chord_settings(chord: f64, m: usize) -> Result<ChordSettings, ApiError> {
    if !(chord.is_finite() && chord > 0.0) {
        return Err(ApiError::invalid(format!(
            "--chord must be a finite number > 0 (m), got {chord}"
        )));
    }
    let defaults = ChordSettings::default();
    Ok(ChordSettings {
        chord,
        seed_resolution: m,
        tolerance: defaults.tolerance.min(chord * 1e-3),
        ..defaults
    })
}

impl ChordRequest {
    /// A request with the default criteria, orientation, box, grid and chord.
    pub fn new(robot: Robot) -> Self {
        Self {
            robot,
            criteria: WorkspaceCriteria::default(),
            orientation: None,
            area: None,
            grid: None,
            chord: DEFAULT_CHORD,
        }
    }

    /// Checks the request and builds its criteria, seed grid and evaluator.
    pub fn prepare(&self) -> Result<(PreparedWorkspace, ChordSettings), ApiError> {
        let motion = self.robot.robot.motion();
        if motion.space_dim() != 2 {
            return Err(ApiError::invalid(format!(
                "--boundary chord maps boundary curves in the plane; this robot is `{}` (use \
                 --boundary grid)",
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
        let settings = chord_settings(self.chord, p.grid.resolution)?;
        Ok((p, settings))
    }

    /// Checks the request.
    pub fn validate(&self) -> Result<(), ApiError> {
        self.prepare().map(|_| ())
    }

    /// Walks the boundaries.
    pub fn run(&self) -> Result<ChordReport, ApiError> {
        let (p, settings) = self.prepare()?;
        let desc = self.robot.description();
        let motion = desc.robot.motion();
        let orientation = orientation_or_default(motion, self.orientation.as_deref());
        let phi = match motion {
            MotionPattern::Planar => orientation.first().copied().unwrap_or(0.0),
            _ => 0.0,
        };
        let ws = chord_workspace(&p.evaluator, phi, &p.grid.region, &settings)?;
        let w_ext = p.setup.external_wrench(desc, &p.rotation)?;
        Ok(ChordReport {
            robot: desc.name.clone(),
            method: "chord".into(),
            orientation,
            external_wrench: w_ext.as_slice().to_vec(),
            criteria: p.setup.labels(),
            tension_method: p.setup.method.name().into(),
            area_box: box_numbers(&p.grid.region, 2),
            chord: self.chord,
            curves: CurvesReport::new(&ws),
            tolerance: settings.tolerance,
        })
    }
}
