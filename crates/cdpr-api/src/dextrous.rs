//! # Dextrous workspace
//!
//! The positions where every orientation of a range is feasible (thesis eq. 6.28): the
//! intersection of the constant-orientation workspaces of M_SL regularly spaced orientations
//! φ_min … φ_max (endpoints included) on one grid of (M+1)² points ((M+1)³ in space), Algorithm
//! 6.2 with step 4 tested for every orientation: the extremes first, then the central
//! orientation, then the others. Planar robots rotate about z, spatial robots by
//! `orientation · R(axis, φ)`; point robots have no orientation (the result is the
//! constant-orientation workspace). Every orientation has its own evaluator, so the gravity
//! moment of an offset centre of mass follows the platform. The §6.5 check (Du Plessis &
//! Snyman): the two-extremes estimate is valid when the central orientation's workspace
//! contains the intersection of the two extreme ones.
//!
//! ## References
//! - Thesis eq. 6.28 and §6.5 (the dextrous workspace and the central-orientation check).

use cdpr_io::RobotDescription;
use cdpr_kinematics::{MotionPattern, Pose, Robot as Geometry};
use cdpr_workspace::{
    CentralCheck, Grid, GridWorkspace, LeanScratch, OrientationRange, PlanarSlice, PoseEvaluator,
    VolumeConvention, dextrous_verdicts_lean,
};
use nalgebra::{Rotation3, Unit, Vector3};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::criteria::{CriteriaSetup, WorkspaceCriteria, default_method};
use crate::rows::{map_row_blocks, map_rows};
use crate::workspace::box_numbers;
use crate::{ApiError, Robot, region};

/// The orientation range φ_min … φ_max (rad) in M_SL slices, endpoints included.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RangeReport {
    /// φ_min (rad).
    pub min: f64,
    /// φ_max (rad).
    pub max: f64,
    /// M_SL ≥ 2 (1 when min = max).
    pub slices: usize,
}

/// The dextrous workspace over a range of orientations (`cdpr dextrous`).
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
pub struct DextrousRequest {
    /// The robot.
    pub robot: Robot,
    /// The criteria and their load.
    #[serde(flatten)]
    pub criteria: WorkspaceCriteria,
    /// The orientation range (rad).
    pub orientations: RangeReport,
    /// Spatial robots: the rotation axis X,Y,Z of the range (default 0,0,1).
    #[serde(default)]
    pub axis: Option<Vec<f64>>,
    /// Spatial robots: the base orientation rx,ry,rz (rad, XYZ Euler angles) the range rotates
    /// from.
    #[serde(default)]
    pub orientation: Option<Vec<f64>>,
    /// `XMIN,XMAX,YMIN,YMAX[,ZMIN,ZMAX]` (m); default: the frame anchors' bounding box.
    #[serde(default, rename = "box")]
    pub area: Option<Vec<f64>>,
    /// M: intervals per side of the grid (default 50 in the plane, 20 in space).
    #[serde(default)]
    pub grid: Option<usize>,
    /// How the grid count turns points into an area: `cells` (default) or `points`.
    #[serde(default, with = "crate::workspace::convention_name")]
    #[schemars(with = "Option<String>")]
    pub volume_convention: VolumeConvention,
}

/// The §6.5 check on the grid.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, JsonSchema)]
pub struct CentralCheckReport {
    /// The central orientation's workspace contains the two extremes' intersection.
    pub holds: bool,
    /// Grid points feasible at both extremes but not at the central orientation.
    pub violations: usize,
    /// Grid points feasible at both extremes.
    pub extremes_points: usize,
}

/// The JSON of `cdpr dextrous --json`.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct DextrousReport {
    /// Robot name.
    pub robot: String,
    /// The orientation range (rad).
    pub orientations: RangeReport,
    /// The sampled angles φ (rad).
    pub angles: Vec<f64>,
    /// Criterion labels.
    pub criteria: Vec<String>,
    /// Tension method of the tension criterion.
    pub tension_method: String,
    /// `XMIN,XMAX,YMIN,YMAX[,ZMIN,ZMAX]` (m).
    #[serde(rename = "box")]
    pub area_box: Vec<f64>,
    /// M.
    pub resolution: usize,
    /// 2 (plane) or 3 (space).
    pub dimension: usize,
    /// Grid points feasible at every orientation.
    pub feasible_points: usize,
    /// (M+1)^dimension.
    pub total_points: usize,
    /// Area (m²) or volume (m³) of one cell.
    pub cell_area: f64,
    /// The §6.5 check.
    pub central_check: CentralCheckReport,
    /// The dextrous area A_d (m², or the volume in m³) in `volume_convention`.
    pub area: f64,
    /// The measure in the `cells` convention (m² or m³).
    pub area_cells: f64,
    /// The measure in the `points` convention (m² or m³).
    pub area_points: f64,
    /// `cells` or `points`.
    pub volume_convention: String,
    /// 3-D grids: the volume (m³, = `area`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub volume: Option<f64>,
    /// The rotation axis of the range (not in JSON).
    #[serde(skip)]
    pub axis: Vector3<f64>,
    /// The central orientation (not in JSON).
    #[serde(skip)]
    pub central_rotation: Rotation3<f64>,
    /// w_ext at the central orientation (N, N·m; not in JSON).
    #[serde(skip)]
    pub central_wrench: Vec<f64>,
    /// The grid and its verdicts (for plots; not in JSON).
    #[serde(skip)]
    pub workspace: GridWorkspace,
}

/// A dextrous workspace on a grid (eq. 6.28) with the §6.5 check.
pub struct Dextrous {
    /// Points feasible at every sampled orientation.
    pub workspace: GridWorkspace,
    /// The check of the two-extremes shortcut.
    pub central_check: CentralCheck,
    /// Sampled angles (rad).
    pub angles: Vec<f64>,
}

/// The base orientation and the axis of a request's range.
fn base_and_axis(
    motion: MotionPattern,
    axis: Option<&[f64]>,
    orientation: Option<&[f64]>,
) -> Result<(Rotation3<f64>, Unit<Vector3<f64>>), ApiError> {
    if motion != MotionPattern::Spatial {
        if axis.is_some() || orientation.is_some() {
            return Err(ApiError::invalid(format!(
                "--axis and --orientation apply to spatial robots; a `{}` robot rotates about z",
                motion.name()
            )));
        }
        return Ok((Rotation3::identity(), Vector3::z_axis()));
    }
    let axis = match axis {
        None => Vector3::z_axis(),
        Some([x, y, z]) => Unit::try_new(Vector3::new(*x, *y, *z), 1e-12)
            .filter(|a| a.iter().all(|v| v.is_finite()))
            .ok_or_else(|| ApiError::invalid("--axis must be a finite non-zero vector X,Y,Z"))?,
        Some(a) => {
            return Err(ApiError::invalid(format!(
                "--axis needs 3 numbers X,Y,Z, got {}",
                a.len()
            )));
        }
    };
    Ok((region::rotation(motion, orientation)?, axis))
}

impl DextrousRequest {
    /// A request for `range` with the default criteria, axis, box and grid.
    pub fn new(robot: Robot, orientations: RangeReport) -> Self {
        Self {
            robot,
            criteria: WorkspaceCriteria::default(),
            orientations,
            axis: None,
            orientation: None,
            area: None,
            grid: None,
            volume_convention: VolumeConvention::Cells,
        }
    }

    /// Checks the request.
    pub fn validate(&self) -> Result<(), ApiError> {
        self.prepare().map(|_| ())
    }

    /// Checks the request and builds its criteria, rotations, range and grid.
    #[allow(clippy::type_complexity)]
    fn prepare(
        &self,
    ) -> Result<
        (
            CriteriaSetup,
            Rotation3<f64>,
            Unit<Vector3<f64>>,
            OrientationRange,
            Grid,
        ),
        ApiError,
    > {
        let desc = self.robot.description();
        let motion = desc.robot.motion();
        let dim = motion.space_dim();
        let method = self
            .criteria
            .method
            .unwrap_or_else(|| default_method(&desc.robot));
        let setup = CriteriaSetup::new(&self.criteria, desc, method)?;
        let (base, axis) =
            base_and_axis(motion, self.axis.as_deref(), self.orientation.as_deref())?;
        let o = self.orientations;
        let range = OrientationRange {
            min: o.min,
            max: o.max,
            slices: o.slices,
        };
        range.validate()?;
        let area = region::region(&desc.robot, self.area.as_deref(), "--box")?;
        let m = region::resolution(self.grid, dim, 50)?;
        let grid = Grid::new(m, area);
        grid.validate(dim)?;
        Ok((setup, base, axis, range, grid))
    }

    /// Maps the dextrous workspace; `row_done` after every grid row.
    pub fn run_with_progress(
        &self,
        row_done: &(dyn Fn() + Sync),
    ) -> Result<DextrousReport, ApiError> {
        let (setup, base, axis, range, grid) = self.prepare()?;
        let desc = self.robot.description();
        let robot = &desc.robot;
        let dim = robot.motion().space_dim();
        let dex = dextrous(&setup, desc, robot, &base, &axis, &range, &grid, row_done)?;
        let central = slice_rotation(robot.motion(), &base, &axis, range.central());
        let central_wrench = setup.external_wrench(desc, &central)?.as_slice().to_vec();
        let (ws, check, conv) = (dex.workspace, dex.central_check, self.volume_convention);
        let measure = ws.measure(conv);
        Ok(DextrousReport {
            robot: desc.name.clone(),
            orientations: self.orientations,
            angles: dex.angles,
            criteria: setup.labels(),
            tension_method: setup.method.name().into(),
            area_box: box_numbers(&grid.region, dim),
            resolution: grid.resolution,
            dimension: dim,
            feasible_points: ws.feasible_points,
            total_points: ws.total_points,
            cell_area: ws.cell_area,
            central_check: CentralCheckReport {
                holds: check.holds,
                violations: check.violations,
                extremes_points: check.extremes_points,
            },
            area: measure,
            area_cells: ws.clipped_area,
            area_points: ws.area,
            volume_convention: conv.name().into(),
            volume: (dim == 3).then_some(measure),
            axis: axis.into_inner(),
            central_rotation: central,
            central_wrench,
            workspace: ws,
        })
    }

    /// Maps the dextrous workspace.
    pub fn run(&self) -> Result<DextrousReport, ApiError> {
        self.run_with_progress(&|| {})
    }
}

/// The orientation `base · R(axis, φ)` (identity for point robots).
fn slice_rotation(
    motion: MotionPattern,
    base: &Rotation3<f64>,
    axis: &Unit<Vector3<f64>>,
    phi: f64,
) -> Rotation3<f64> {
    match motion {
        MotionPattern::Point2 | MotionPattern::Point3 => Rotation3::identity(),
        _ => base * Rotation3::from_axis_angle(axis, phi),
    }
}

/// One evaluator per sampled orientation (each with the gravity moment of that orientation).
#[derive(Clone)]
struct Slices {
    evals: Vec<PoseEvaluator>,
    rotations: Vec<Rotation3<f64>>,
    /// Index of the central orientation among the slices, or its own evaluator.
    central: Result<usize, (Box<PoseEvaluator>, Rotation3<f64>)>,
}

impl Slices {
    /// The evaluators of `range`'s orientations and of its central one.
    fn new(
        setup: &CriteriaSetup,
        desc: &RobotDescription,
        robot: &Geometry,
        rot: impl Fn(f64) -> Rotation3<f64>,
        range: &OrientationRange,
    ) -> Result<Self, ApiError> {
        let angles = range.angles();
        let rotations: Vec<Rotation3<f64>> = angles.iter().map(|&a| rot(a)).collect();
        let evals = rotations
            .iter()
            .map(|r| setup.evaluator(desc, robot.clone(), r))
            .collect::<Result<Vec<_>, _>>()?;
        let c = range.central();
        let central = match angles.iter().position(|&a| a == c) {
            Some(k) => Ok(k),
            None => {
                let r = rot(c);
                Err((Box::new(setup.evaluator(desc, robot.clone(), &r)?), r))
            }
        };
        Ok(Self {
            evals,
            rotations,
            central,
        })
    }

    /// Feasibility at slice `k` (`None`: the central orientation).
    fn feasible(&mut self, k: Option<usize>, u: &Vector3<f64>) -> bool {
        let k = match (k, &mut self.central) {
            (Some(k), _) => k,
            (None, Ok(k)) => *k,
            (None, Err((ev, r))) => return ev.is_feasible(&Pose::new(*u, *r)),
        };
        self.evals[k].is_feasible(&Pose::new(*u, self.rotations[k]))
    }

    /// (dextrous, feasible at both extremes, the central orientation fails there) at `u`.
    fn verdict(&mut self, u: Vector3<f64>) -> (bool, bool, bool) {
        let n = self.evals.len();
        if !self.feasible(Some(0), &u) || (n > 1 && !self.feasible(Some(n - 1), &u)) {
            return (false, false, false);
        }
        let central_index = self.central.as_ref().ok().copied();
        let central_ok = self.feasible(None, &u);
        let others_ok = (1..n.saturating_sub(1))
            .filter(|&k| Some(k) != central_index)
            .all(|k| self.feasible(Some(k), &u));
        let dextrous = (central_ok || central_index.is_none()) && others_ok;
        (dextrous, true, !central_ok)
    }
}

/// Eq. (6.28) for rotations `base · R(axis, φ)`, φ over `range`, on `grid`: the points feasible
/// at every sampled orientation, tested as `cdpr_workspace::dextrous_workspace_about_axis` does
/// (extremes first, then the central orientation, then the others), but with one evaluator per
/// orientation so that the gravity moment of an offset centre of mass follows the platform;
/// `row_done` after every grid row.
#[allow(clippy::too_many_arguments)]
pub fn dextrous(
    setup: &CriteriaSetup,
    desc: &RobotDescription,
    robot: &Geometry,
    base: &Rotation3<f64>,
    axis: &Unit<Vector3<f64>>,
    range: &OrientationRange,
    grid: &Grid,
    row_done: &(dyn Fn() + Sync),
) -> Result<Dextrous, ApiError> {
    range.validate()?;
    let motion = robot.motion();
    let dim = motion.space_dim();
    grid.validate(dim)?;
    let rot = |phi: f64| slice_rotation(motion, base, axis, phi);
    let slices = Slices::new(setup, desc, robot, rot, range)?;
    // The lean planar r = 1 path of every orientation, if all have it (the same verdicts).
    let lean = slices
        .evals
        .iter()
        .zip(&slices.rotations)
        .map(|(e, r)| PlanarSlice::new(e, r))
        .collect::<Option<Vec<_>>>()
        .and_then(|l| match &slices.central {
            Ok(_) => Some((l, None)),
            Err((e, r)) => PlanarSlice::new(e, r).map(|c| (l, Some(c))),
        });
    let verdicts = if let Some((lean, central_lean)) = &lean {
        // Row by row, four points at a time, orientation by orientation.
        let central = match &slices.central {
            Ok(k) => Ok(*k),
            Err(_) => Err(central_lean
                .as_ref()
                .expect("built with the central evaluator")),
        };
        let state = (slices, LeanScratch::default());
        map_row_blocks(&state, grid, dim, row_done, |(s, scratch), points, out| {
            dextrous_verdicts_lean(lean, central, points, out, scratch, |k, u| s.feasible(k, u))
        })
    } else {
        map_rows(&slices, grid, dim, row_done, |s, u| s.verdict(u))
    };
    let violations = verdicts.iter().filter(|v| v.2).count();
    Ok(Dextrous {
        workspace: GridWorkspace::from_verdicts(*grid, dim, verdicts.iter().map(|v| v.0).collect()),
        central_check: CentralCheck {
            holds: violations == 0,
            violations,
            extremes_points: verdicts.iter().filter(|v| v.1).count(),
        },
        angles: range.angles(),
    })
}
