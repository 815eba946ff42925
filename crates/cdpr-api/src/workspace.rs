//! # Constant-orientation workspace on a grid
//!
//! Thesis Algorithm 6.2: the verdict of every criterion ([`crate::criteria`]) at each of the
//! (M+1)² points of a regular grid over a box (the (M+1)³ points of a 3-D grid for robots moving
//! in space) at one platform orientation, under w_ext = w_e + the robot file's load at that
//! orientation (eq. 6.23). The measure is the feasible points' cells clipped to the box
//! (`cells`, never more than the box) or feasible points × cell area (`points`, the thesis'
//! convention). Rows of the grid run in parallel with the `parallel` feature.
//!
//! ## References
//! - Thesis Algorithm 6.2 and eq. 6.23 (the constant-orientation workspace).

use cdpr_kinematics::{MotionPattern, Pose};
use cdpr_workspace::{Grid, GridWorkspace, PoseEvaluator, Region, VolumeConvention};
use nalgebra::Rotation3;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::criteria::{CriteriaSetup, WorkspaceCriteria, default_method};
use crate::{ApiError, Robot, region};

/// The constant-orientation workspace on a grid (`cdpr workspace`, `--boundary grid`).
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
pub struct WorkspaceRequest {
    /// The robot.
    pub robot: Robot,
    /// The criteria and their load.
    #[serde(flatten)]
    pub criteria: WorkspaceCriteria,
    /// Platform orientation: φ (rad, planar), rx,ry,rz (rad, spatial); none for point robots.
    #[serde(default)]
    pub orientation: Option<Vec<f64>>,
    /// `XMIN,XMAX,YMIN,YMAX[,ZMIN,ZMAX]` (m); default: the frame anchors' bounding box (extended
    /// below anchors that span little height).
    #[serde(default, rename = "box")]
    pub area: Option<Vec<f64>>,
    /// M: intervals per side (default 50 in the plane, 20 in space).
    #[serde(default)]
    pub grid: Option<usize>,
    /// `cells` (default) or `points`.
    #[serde(default, with = "convention_name")]
    #[schemars(with = "Option<String>")]
    pub volume_convention: VolumeConvention,
}

/// The JSON of `cdpr workspace --json` (grid).
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct WorkspaceReport {
    /// Robot name.
    pub robot: String,
    /// `grid`.
    pub method: String,
    /// Platform orientation (rad; empty for point robots).
    pub orientation: Vec<f64>,
    /// w_ext = w_e + the robot file's load (N, N·m).
    pub external_wrench: Vec<f64>,
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
    /// Feasible grid points.
    pub feasible_points: usize,
    /// (M+1)^dimension.
    pub total_points: usize,
    /// Area (m²) or volume (m³) of one cell.
    pub cell_area: f64,
    /// The measure in `volume_convention` (m² or m³).
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
    /// The grid and its verdicts (for plots and point files; not in JSON).
    #[serde(skip)]
    pub workspace: GridWorkspace,
}

/// Serde of a [`VolumeConvention`] as its name.
pub(crate) mod convention_name {
    use cdpr_workspace::VolumeConvention;
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(c: &VolumeConvention, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(c.name())
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<VolumeConvention, D::Error> {
        Option::<String>::deserialize(d)?.map_or(Ok(VolumeConvention::Cells), |s| {
            s.parse().map_err(serde::de::Error::custom)
        })
    }
}

/// What [`WorkspaceRequest::prepare`] checks and builds.
pub struct PreparedWorkspace {
    /// The criteria, checked.
    pub setup: CriteriaSetup,
    /// The orientation.
    pub rotation: Rotation3<f64>,
    /// The grid.
    pub grid: Grid,
    /// The evaluator at that orientation.
    pub evaluator: PoseEvaluator,
}

impl PreparedWorkspace {
    /// Checks what every region analysis at one orientation needs (criteria with their
    /// default method, orientation, box, resolution M) and builds its evaluator and grid.
    pub fn new(
        robot: &Robot,
        criteria: &WorkspaceCriteria,
        orientation: Option<&[f64]>,
        area: Option<&[f64]>,
        grid: Option<usize>,
    ) -> Result<Self, ApiError> {
        let desc = robot.description();
        let motion = desc.robot.motion();
        let dim = motion.space_dim();
        let method = criteria
            .method
            .unwrap_or_else(|| default_method(&desc.robot));
        let setup = CriteriaSetup::new(criteria, desc, method)?;
        let rotation = region::rotation(motion, orientation)?;
        let area = region::region(&desc.robot, area, "--box")?;
        let m = region::resolution(grid, dim, 50)?;
        let evaluator = setup.evaluator(desc, desc.robot.clone(), &rotation)?;
        let grid = Grid::new(m, area);
        grid.validate(dim)?;
        Ok(Self {
            setup,
            rotation,
            grid,
            evaluator,
        })
    }
}

/// The orientation of a report: as given, else zeros (φ = 0 in the plane, rx = ry = rz = 0 in
/// space), empty for point robots.
pub fn orientation_or_default(motion: MotionPattern, given: Option<&[f64]>) -> Vec<f64> {
    match (given, motion) {
        (Some(o), _) => o.to_vec(),
        (None, MotionPattern::Planar) => vec![0.0],
        (None, MotionPattern::Spatial) => vec![0.0; 3],
        (None, _) => vec![],
    }
}

/// The box's bounds XMIN, XMAX, YMIN, YMAX[, ZMIN, ZMAX] (m).
pub fn box_numbers(r: &Region, dim: usize) -> Vec<f64> {
    let mut b = vec![r.min.x, r.max.x, r.min.y, r.max.y];
    if dim == 3 {
        b.extend([r.min.z, r.max.z]);
    }
    b
}

impl WorkspaceRequest {
    /// A request with the default criteria, orientation, box and grid.
    pub fn new(robot: Robot) -> Self {
        Self {
            robot,
            criteria: WorkspaceCriteria::default(),
            orientation: None,
            area: None,
            grid: None,
            volume_convention: VolumeConvention::Cells,
        }
    }

    /// Checks the request and builds its criteria, grid and evaluator.
    pub fn prepare(&self) -> Result<PreparedWorkspace, ApiError> {
        PreparedWorkspace::new(
            &self.robot,
            &self.criteria,
            self.orientation.as_deref(),
            self.area.as_deref(),
            self.grid,
        )
    }

    /// Checks the request.
    pub fn validate(&self) -> Result<(), ApiError> {
        self.prepare().map(|_| ())
    }

    /// Maps the workspace.
    pub fn run(&self) -> Result<WorkspaceReport, ApiError> {
        self.run_with_progress(&|| {})
    }

    /// Maps the workspace, calling `row_done` after each row of M + 1 points (a progress bar).
    pub fn run_with_progress(
        &self,
        row_done: &(dyn Fn() + Sync),
    ) -> Result<WorkspaceReport, ApiError> {
        let p = self.prepare()?;
        let desc = self.robot.description();
        let motion = desc.robot.motion();
        let dim = motion.space_dim();
        let ws = verdicts(&p.evaluator, &p.rotation, &p.grid, dim, row_done);
        let w_ext = p.setup.external_wrench(desc, &p.rotation)?;
        let orientation = orientation_or_default(motion, self.orientation.as_deref());
        let convention = self.volume_convention;
        let area_box = box_numbers(&p.grid.region, dim);
        let measure = ws.measure(convention);
        Ok(WorkspaceReport {
            robot: desc.name.clone(),
            method: "grid".into(),
            orientation,
            external_wrench: w_ext.as_slice().to_vec(),
            criteria: p.setup.labels(),
            tension_method: p.setup.method.name().into(),
            area_box,
            resolution: p.grid.resolution,
            dimension: dim,
            feasible_points: ws.feasible_points,
            total_points: ws.total_points,
            cell_area: ws.cell_area,
            area: measure,
            area_cells: ws.clipped_area,
            area_points: ws.area,
            volume_convention: convention.name().into(),
            volume: (dim == 3).then_some(measure),
            workspace: ws,
        })
    }
}

/// The verdict at every grid point (x fastest), rows of M + 1 points in parallel.
fn verdicts(
    eval: &PoseEvaluator,
    rotation: &Rotation3<f64>,
    grid: &Grid,
    dim: usize,
    row_done: &(dyn Fn() + Sync),
) -> GridWorkspace {
    let row = grid.points_per_axis();
    let total = grid.point_count(dim);
    let r = *rotation;
    let one_row = |ev: &mut PoseEvaluator, k: usize| -> Vec<bool> {
        let out = (k * row..((k + 1) * row).min(total))
            .map(|idx| ev.is_feasible(&Pose::new(grid.point(dim, idx), r)))
            .collect();
        row_done();
        out
    };
    #[cfg(feature = "parallel")]
    let rows: Vec<Vec<bool>> = {
        use rayon::prelude::*;
        (0..total.div_ceil(row))
            .into_par_iter()
            .map_init(|| eval.clone(), |ev, k| one_row(ev, k))
            .collect()
    };
    #[cfg(not(feature = "parallel"))]
    let rows: Vec<Vec<bool>> = {
        let mut ev = eval.clone();
        (0..total.div_ceil(row))
            .map(|k| one_row(&mut ev, k))
            .collect()
    };
    GridWorkspace::from_verdicts(*grid, dim, rows.concat())
}
