//! # Workspaces over a set of orientations
//!
//! The total-orientation workspace (positions where every orientation of a sampled set is
//! feasible) and the maximal workspace (positions where at least one is) of a `spatial` robot,
//! Merlet's definitions, on a grid of (M+1)³ points or as the boundary mesh of that grid
//! (marching cubes, vertices bisected onto the boundary). The set is an Euler box or a tilt cone
//! with torsion (Bonev, Zlatanov & Gosselin 2002), sampled: verdicts at the samples are exact,
//! nothing is claimed between them. Each orientation has its own evaluator (the gravity moment
//! follows the platform). For a total-orientation workspace, the limiting orientation at every
//! boundary point is the one that fails first along the edge to an infeasible neighbour.
//!
//! ## References
//! - Merlet, "Parallel Robots" (2006), §6 (total-orientation and maximal workspaces).
//! - Bonev, Zlatanov & Gosselin 2002 (tilt-and-torsion angles).

use cdpr_io::RobotDescription;
use cdpr_kinematics::MotionPattern;
use cdpr_workspace::{
    BoundaryMesh, Grid, GridWorkspace, MeshSettings, OrientationSet, OrientationTest,
    OrientationWorkspaceKind, SampledOrientation, VolumeConvention, orientation_boundary_mesh,
    orientation_workspace,
};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::criteria::{CriteriaSetup, WorkspaceCriteria, default_method};
use crate::workspace::box_numbers;
use crate::{ApiError, Robot, region};

/// The workspace over a set of orientations (`cdpr workspace --orientations SET --kind …`): on
/// the grid with [`OrientationWorkspaceRequest::run`], as a boundary mesh with
/// [`OrientationWorkspaceRequest::run_mesh`].
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
pub struct OrientationWorkspaceRequest {
    /// The robot (`spatial`).
    pub robot: Robot,
    /// The criteria and their load.
    #[serde(flatten)]
    pub criteria: WorkspaceCriteria,
    /// The orientation set, e.g. `tilt:20,torsion=-30..30,n=5` or
    /// `euler:rx=-10..10,ry=-10..10,rz=-20..20,n=5` (degrees).
    pub orientations: String,
    /// `total` (default: every orientation feasible) or `maximal` (at least one).
    #[serde(default)]
    pub kind: Option<String>,
    /// `XMIN,XMAX,YMIN,YMAX,ZMIN,ZMAX` (m); default: the frame anchors' bounding box.
    #[serde(default, rename = "box")]
    pub area: Option<Vec<f64>>,
    /// M: intervals per side of the grid (default 20).
    #[serde(default)]
    pub grid: Option<usize>,
    /// How the grid count turns points into a volume: `cells` (default) or `points`.
    #[serde(default, with = "crate::workspace::convention_name")]
    #[schemars(with = "Option<String>")]
    pub volume_convention: VolumeConvention,
}

/// Where a total-orientation workspace ends and which orientation ends it.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct LimitingReport {
    /// A point of the boundary (m).
    pub point: [f64; 3],
    /// The orientation that fails first there (degrees, in `angle_names`).
    pub angles_deg: [f64; 3],
}

/// How often one orientation is the limiting one on the grid.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct LimitingCountReport {
    /// The orientation (degrees, in `angle_names`).
    pub angles_deg: [f64; 3],
    /// Boundary grid points it limits.
    pub boundary_points: usize,
}

/// How often one orientation is the limiting one on the mesh.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct LimitingVerticesReport {
    /// The orientation (degrees, in `angle_names`).
    pub angles_deg: [f64; 3],
    /// Boundary vertices it limits.
    pub boundary_vertices: usize,
}

/// The JSON of `cdpr workspace --orientations SET --json` (grid).
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct OrientationWorkspaceReport {
    /// Robot name.
    pub robot: String,
    /// `grid`.
    pub method: String,
    /// `total` or `maximal`.
    pub kind: String,
    /// The set, as parsed (degrees).
    pub orientation_set: String,
    /// Sampled orientations.
    pub orientation_count: usize,
    /// The names of the three angles.
    pub angle_names: [String; 3],
    /// Criterion labels.
    pub criteria: Vec<String>,
    /// Tension method of the tension criterion.
    pub tension_method: String,
    /// `XMIN,XMAX,YMIN,YMAX,ZMIN,ZMAX` (m).
    #[serde(rename = "box")]
    pub area_box: Vec<f64>,
    /// M.
    pub resolution: usize,
    /// 3.
    pub dimension: usize,
    /// Grid points in the workspace.
    pub feasible_points: usize,
    /// (M+1)³.
    pub total_points: usize,
    /// Volume of one cell (m³).
    pub cell_area: f64,
    /// Total-orientation workspaces: every boundary point with its limiting orientation.
    pub limiting_orientations: Vec<LimitingReport>,
    /// The limiting orientations, most frequent first.
    pub limiting_summary: Vec<LimitingCountReport>,
    /// The volume in `volume_convention` (m³).
    pub area: f64,
    /// The volume in the `cells` convention (m³).
    pub area_cells: f64,
    /// The volume in the `points` convention (m³).
    pub area_points: f64,
    /// `cells` or `points`.
    pub volume_convention: String,
    /// The volume (m³, = `area`).
    pub volume: f64,
    /// The grid and its verdicts (for plots; not in JSON).
    #[serde(skip)]
    pub workspace: GridWorkspace,
}

/// The JSON of `cdpr workspace --orientations SET --boundary mesh --json`.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct OrientationMeshReport {
    /// Robot name.
    pub robot: String,
    /// `mesh`.
    pub method: String,
    /// `total` or `maximal`.
    pub kind: String,
    /// The set, as parsed (degrees).
    pub orientation_set: String,
    /// Sampled orientations.
    pub orientation_count: usize,
    /// The names of the three angles.
    pub angle_names: [String; 3],
    /// Criterion labels.
    pub criteria: Vec<String>,
    /// Tension method of the tension criterion.
    pub tension_method: String,
    /// `XMIN,XMAX,YMIN,YMAX,ZMIN,ZMAX` (m).
    #[serde(rename = "box")]
    pub area_box: Vec<f64>,
    /// M of the grid that seeds the mesh.
    pub resolution: usize,
    /// 3.
    pub dimension: usize,
    /// The volume enclosed by the mesh (m³, divergence theorem).
    pub volume: f64,
    /// Area of the closed mesh (m², box caps included).
    pub surface_area: f64,
    /// Connected pieces of the mesh.
    pub components: usize,
    /// Number of vertices.
    pub vertices: usize,
    /// Number of triangles.
    pub triangles: usize,
    /// Bisection tolerance ε (m).
    pub tolerance: f64,
    /// Every edge shared by exactly two triangles traversed in opposite directions.
    pub watertight: bool,
    /// Feasible grid points.
    pub feasible_points: usize,
    /// (M+1)³.
    pub total_points: usize,
    /// The limiting orientations at the boundary vertices, most frequent first.
    pub limiting_summary: Vec<LimitingVerticesReport>,
    /// The mesh (for plots; not in JSON).
    #[serde(skip)]
    pub mesh: BoundaryMesh,
}

/// What both runs need.
struct Prepared {
    setup: CriteriaSetup,
    set: OrientationSet,
    kind: OrientationWorkspaceKind,
    test: OrientationTest,
    samples: Vec<SampledOrientation>,
    grid: Grid,
}

/// The orientation test of a `spatial` robot: one evaluator per sampled orientation.
pub fn orientation_test(
    desc: &RobotDescription,
    setup: &CriteriaSetup,
    set: &OrientationSet,
    kind: OrientationWorkspaceKind,
) -> Result<(OrientationTest, Vec<SampledOrientation>), ApiError> {
    let motion = desc.robot.motion();
    if motion != MotionPattern::Spatial {
        return Err(ApiError::invalid(format!(
            "--orientations samples platform orientations in space: `spatial` robots only, this \
             one is `{motion}` (planar robots: `cdpr dextrous`)"
        )));
    }
    let samples = set.orientations()?;
    let evals = samples
        .iter()
        .map(|o| setup.evaluator(desc, desc.robot.clone(), &o.rotation))
        .collect::<Result<Vec<_>, _>>()?;
    let test = OrientationTest::new(kind, samples.iter().map(|o| o.rotation).collect(), evals)?;
    Ok((test, samples))
}

/// An orientation's angles in degrees.
pub fn degrees(o: &SampledOrientation) -> [f64; 3] {
    o.angles.map(f64::to_degrees)
}

/// How often each of `count` sampled orientations is the limiting one: `(orientation, times)`
/// for those that are, most frequent first (ties by index).
fn rank_limiting(limiting: impl Iterator<Item = usize>, count: usize) -> Vec<(usize, usize)> {
    let mut per = vec![0usize; count];
    for k in limiting {
        per[k] += 1;
    }
    let mut ranked: Vec<(usize, usize)> = per
        .into_iter()
        .enumerate()
        .filter(|&(_, n)| n > 0)
        .collect();
    ranked.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    ranked
}

impl OrientationWorkspaceRequest {
    /// A request for the total-orientation workspace of the set `orientations` with the default
    /// criteria, box and grid.
    pub fn new(robot: Robot, orientations: impl Into<String>) -> Self {
        Self {
            robot,
            criteria: WorkspaceCriteria::default(),
            orientations: orientations.into(),
            kind: None,
            area: None,
            grid: None,
            volume_convention: VolumeConvention::Cells,
        }
    }

    /// Checks the request.
    pub fn validate(&self) -> Result<(), ApiError> {
        self.prepare().map(|_| ())
    }

    fn prepare(&self) -> Result<Prepared, ApiError> {
        let desc = self.robot.description();
        let robot = &desc.robot;
        let method = self
            .criteria
            .method
            .unwrap_or_else(|| default_method(robot));
        let setup = CriteriaSetup::new(&self.criteria, desc, method)?;
        let set: OrientationSet = self
            .orientations
            .parse()
            .map_err(|e| ApiError::invalid(format!("--orientations {}: {e}", self.orientations)))?;
        let kind = match self.kind.as_deref() {
            None | Some("total") => OrientationWorkspaceKind::Total,
            Some("maximal") => OrientationWorkspaceKind::Maximal,
            Some(k) => {
                return Err(ApiError::invalid(format!(
                    "--kind `{k}` is not total or maximal"
                )));
            }
        };
        let area = region::region(robot, self.area.as_deref(), "--box")?;
        let m = region::resolution(self.grid, robot.motion().space_dim(), 50)?;
        let (test, samples) = orientation_test(desc, &setup, &set, kind)?;
        let grid = Grid::new(m, area);
        grid.validate(3)?;
        Ok(Prepared {
            setup,
            set,
            kind,
            test,
            samples,
            grid,
        })
    }

    /// The workspace on the grid, with the limiting orientations of a total-orientation one.
    pub fn run(&self) -> Result<OrientationWorkspaceReport, ApiError> {
        let p = self.prepare()?;
        let ws = orientation_workspace(&p.test, &p.grid)?;
        let ranked = rank_limiting(ws.limiting.iter().map(|l| l.orientation), p.samples.len());
        let (w, conv) = (ws.workspace, self.volume_convention);
        let angles = |k: usize| degrees(&p.samples[k]);
        Ok(OrientationWorkspaceReport {
            robot: self.robot.description().name.clone(),
            method: "grid".into(),
            kind: p.kind.name().into(),
            orientation_set: p.set.to_string(),
            orientation_count: p.samples.len(),
            angle_names: p.set.angle_names().map(String::from),
            criteria: p.setup.labels(),
            tension_method: p.setup.method.name().into(),
            area_box: box_numbers(&p.grid.region, 3),
            resolution: p.grid.resolution,
            dimension: 3,
            feasible_points: w.feasible_points,
            total_points: w.total_points,
            cell_area: w.cell_area,
            limiting_orientations: ws
                .limiting
                .iter()
                .map(|l| LimitingReport {
                    point: l.boundary_point.into(),
                    angles_deg: angles(l.orientation),
                })
                .collect(),
            limiting_summary: ranked
                .iter()
                .map(|&(k, n)| LimitingCountReport {
                    angles_deg: angles(k),
                    boundary_points: n,
                })
                .collect(),
            area: w.measure(conv),
            area_cells: w.clipped_area,
            area_points: w.area,
            volume_convention: conv.name().into(),
            volume: w.measure(conv),
            workspace: w,
        })
    }

    /// The boundary mesh of the workspace, with the limiting orientation at every boundary
    /// vertex of a total-orientation one.
    pub fn run_mesh(&self) -> Result<OrientationMeshReport, ApiError> {
        let p = self.prepare()?;
        let om = orientation_boundary_mesh(&p.test, &p.grid, &MeshSettings::default())?;
        let ranked = rank_limiting(om.limiting.iter().flatten().copied(), p.samples.len());
        let mesh = om.mesh;
        Ok(OrientationMeshReport {
            robot: self.robot.description().name.clone(),
            method: "mesh".into(),
            kind: p.kind.name().into(),
            orientation_set: p.set.to_string(),
            orientation_count: p.samples.len(),
            angle_names: p.set.angle_names().map(String::from),
            criteria: p.setup.labels(),
            tension_method: p.setup.method.name().into(),
            area_box: box_numbers(&p.grid.region, 3),
            resolution: p.grid.resolution,
            dimension: 3,
            volume: mesh.volume,
            surface_area: mesh.surface_area,
            components: mesh.components,
            vertices: mesh.vertices.len(),
            triangles: mesh.triangles.len(),
            tolerance: mesh.tolerance,
            watertight: mesh.edge_defects() == 0,
            feasible_points: mesh.grid.feasible_points,
            total_points: mesh.grid.total_points,
            limiting_summary: ranked
                .iter()
                .map(|&(k, n)| LimitingVerticesReport {
                    angles_deg: degrees(&p.samples[k]),
                    boundary_vertices: n,
                })
                .collect(),
            mesh,
        })
    }
}
