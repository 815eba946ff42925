//! # Boundary mesh of a 3-D workspace
//!
//! The constant-orientation workspace (thesis eq. 6.23) of a robot moving in space (`point3`,
//! `spatial`) as a closed, consistently oriented triangle mesh of its boundary inside the box:
//! marching cubes over the (M+1)³ grid verdicts of Algorithm 6.2 (Lorensen & Cline 1987), every
//! vertex then bisected onto the boundary along its grid edge to ε = 10⁻⁸ of the box size; the
//! box faces close the mesh where the workspace reaches them. The volume enclosed by the mesh
//! follows from the divergence theorem (error O(h²) against the grid count's O(h)). Mesh files
//! (STL, PLY, OBJ) are renderings of the report in the front ends.
//!
//! ## References
//! - Thesis Algorithm 6.2 and eq. 6.23 (the grid and the constant-orientation workspace).
//! - Lorensen & Cline 1987 (marching cubes); `cdpr_workspace::boundary_mesh` for the rest.

use cdpr_workspace::{BoundaryMesh, BoxFace, MeshSettings, VolumeConvention, boundary_mesh};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::criteria::WorkspaceCriteria;
use crate::workspace::{PreparedWorkspace, box_numbers, orientation_or_default};
use crate::{ApiError, Robot};

/// The boundary mesh of the constant-orientation workspace (`cdpr workspace --boundary mesh`).
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
pub struct MeshRequest {
    /// The robot (moving in space: `point3` or `spatial`).
    pub robot: Robot,
    /// The criteria and their load.
    #[serde(flatten)]
    pub criteria: WorkspaceCriteria,
    /// Platform orientation: rx,ry,rz (rad, XYZ Euler angles, spatial); none for point robots.
    #[serde(default)]
    pub orientation: Option<Vec<f64>>,
    /// `XMIN,XMAX,YMIN,YMAX,ZMIN,ZMAX` (m); default: the frame anchors' bounding box (extended
    /// below anchors that span little height).
    #[serde(default, rename = "box")]
    pub area: Option<Vec<f64>>,
    /// M: intervals per side of the grid that seeds the mesh (default 20, at most 300).
    #[serde(default)]
    pub grid: Option<usize>,
    /// How the grid count (`grid_volume`, `area`) turns points into a volume: `cells` (default)
    /// or `points`.
    #[serde(default, with = "crate::workspace::convention_name")]
    #[schemars(with = "Option<String>")]
    pub volume_convention: VolumeConvention,
}

/// One closed, connected piece of the mesh.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct ShellReport {
    /// Signed enclosed volume (m³): > 0 around a region, < 0 around a cavity.
    pub volume: f64,
    /// Area of the shell (m², box caps included).
    pub area: f64,
    /// Genus from the Euler characteristic (tunnels through the region; 0 for a ball).
    pub genus: i64,
    /// Number of triangles.
    pub triangles: usize,
    /// Number of vertices.
    pub vertices: usize,
}

/// Which faces of the box the workspace reaches (there the box closes the mesh).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, JsonSchema)]
pub struct BoxFacesReport {
    /// x = XMIN.
    pub x_min: bool,
    /// x = XMAX.
    pub x_max: bool,
    /// y = YMIN.
    pub y_min: bool,
    /// y = YMAX.
    pub y_max: bool,
    /// z = ZMIN.
    pub z_min: bool,
    /// z = ZMAX.
    pub z_max: bool,
}

impl BoxFacesReport {
    /// From the flags in the order of [`BoxFace::ALL`].
    fn new(r: [bool; 6]) -> Self {
        let [x_min, x_max, y_min, y_max, z_min, z_max] = r;
        Self {
            x_min,
            x_max,
            y_min,
            y_max,
            z_min,
            z_max,
        }
    }

    /// The names (`x_min`, …) of the faces reached.
    pub fn reached(&self) -> Vec<&'static str> {
        let flags = [
            self.x_min, self.x_max, self.y_min, self.y_max, self.z_min, self.z_max,
        ];
        BoxFace::ALL
            .iter()
            .zip(flags)
            .filter(|(_, r)| *r)
            .map(|(f, _)| f.name())
            .collect()
    }
}

/// The JSON of `cdpr workspace --boundary mesh --json`.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct MeshReport {
    /// Robot name.
    pub robot: String,
    /// `mesh`.
    pub method: String,
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
    /// M.
    pub resolution: usize,
    /// 3.
    pub dimension: usize,
    /// Feasible grid points.
    pub feasible_points: usize,
    /// (M+1)³.
    pub total_points: usize,
    /// Volume of one grid cell (m³).
    pub cell_area: f64,
    /// The grid count in `volume_convention` (m³, = `area`).
    pub grid_volume: f64,
    /// The grid count in `volume_convention` (m³).
    pub area: f64,
    /// The grid count in the `cells` convention (m³).
    pub area_cells: f64,
    /// The grid count in the `points` convention (m³).
    pub area_points: f64,
    /// `cells` or `points`.
    pub volume_convention: String,
    /// The volume enclosed by the mesh (m³, divergence theorem).
    pub volume: f64,
    /// Area of the closed mesh (m², box caps included).
    pub surface_area: f64,
    /// Area of the part on the box faces (m²).
    pub cap_area: f64,
    /// Connected pieces of the mesh.
    pub components: usize,
    /// Shells of positive volume.
    pub regions: usize,
    /// Shells of negative volume (holes inside a region).
    pub cavities: usize,
    /// The connected pieces, in order of their first triangle.
    pub shells: Vec<ShellReport>,
    /// Which box faces the workspace reaches.
    pub box_faces_reached: BoxFacesReport,
    /// Bisection tolerance ε (m): every boundary vertex lies within ε/2 of a boundary point on
    /// its grid edge.
    pub tolerance: f64,
    /// Every edge shared by exactly two triangles traversed in opposite directions.
    pub watertight: bool,
    /// Pose evaluations (grid and bisections).
    pub evaluations: usize,
    /// Wall-clock time of the run (s), measured by the front end (absent without a clock).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seconds: Option<f64>,
    /// Vertices (m).
    pub vertices: Vec<[f64; 3]>,
    /// Triangles (indices into `vertices`, counter-clockwise seen from outside).
    pub triangles: Vec<[u32; 3]>,
    /// The mesh and its grid verdicts (for mesh and point files and plots; not in JSON).
    #[serde(skip)]
    pub mesh: BoundaryMesh,
}

impl MeshRequest {
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
        let motion = self.robot.robot.motion();
        if motion.space_dim() != 3 {
            return Err(ApiError::invalid(format!(
                "--boundary mesh builds the boundary surface of a workspace in space; this robot \
                 is `{}` (moving in a plane): use --boundary chord, the chord method, for its \
                 exact boundary curves",
                motion.name()
            )));
        }
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

    /// Builds the mesh.
    pub fn run(&self) -> Result<MeshReport, ApiError> {
        let p = self.prepare()?;
        let desc = self.robot.description();
        let mesh = boundary_mesh(&p.evaluator, &p.rotation, &p.grid, &MeshSettings::default())?;
        let w_ext = p.setup.external_wrench(desc, &p.rotation)?;
        let ws = &mesh.grid;
        let convention = self.volume_convention;
        let measure = ws.measure(convention);
        Ok(MeshReport {
            robot: desc.name.clone(),
            method: "mesh".into(),
            orientation: orientation_or_default(desc.robot.motion(), self.orientation.as_deref()),
            external_wrench: w_ext.as_slice().to_vec(),
            criteria: p.setup.labels(),
            tension_method: p.setup.method.name().into(),
            area_box: box_numbers(&p.grid.region, 3),
            resolution: p.grid.resolution,
            dimension: 3,
            feasible_points: ws.feasible_points,
            total_points: ws.total_points,
            cell_area: ws.cell_area,
            grid_volume: measure,
            area: measure,
            area_cells: ws.clipped_area,
            area_points: ws.area,
            volume_convention: convention.name().into(),
            volume: mesh.volume,
            surface_area: mesh.surface_area,
            cap_area: mesh.cap_area,
            components: mesh.components,
            regions: mesh.regions(),
            cavities: mesh.cavities(),
            shells: mesh.shells.iter().map(shell_report).collect(),
            box_faces_reached: BoxFacesReport::new(mesh.box_faces_reached),
            tolerance: mesh.tolerance,
            watertight: mesh.edge_defects() == 0,
            evaluations: mesh.evaluations,
            seconds: None,
            vertices: mesh.vertices.clone(),
            triangles: mesh.triangles.clone(),
            mesh,
        })
    }
}

/// A shell as reported.
fn shell_report(s: &cdpr_workspace::Shell) -> ShellReport {
    ShellReport {
        volume: s.volume,
        area: s.area,
        genus: s.genus,
        triangles: s.triangles,
        vertices: s.vertices,
    }
}
