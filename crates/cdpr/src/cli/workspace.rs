//! `cdpr workspace`: the constant-orientation workspace by discretisation (thesis Algorithm 6.2)
//! or by the chord method (§6.4.3). The pieces it shares with the other region commands are in
//! `criteria` (criteria from the command line) and `region` (boxes, grids with a progress bar,
//! plots).

use super::criteria::CriteriaArgs;
use super::region::is_html;
use super::{CliError, Numbers, request_robot};
use cdpr::api::{
    ChordRequest, MeshRequest, OrientationWorkspaceRequest, SectionRequest, WorkspaceCriteria,
    WorkspaceRequest,
};
use cdpr::workspace::VolumeConvention;
use std::path::PathBuf;

/// The long help of the command (`--help`), also its documentation.
const LONG_HELP: &str = "\
Constant-orientation workspace: the platform positions where every criterion holds at a fixed
orientation (thesis eq. 6.23).

Methods (--boundary):
  grid  (default) Algorithm 6.2: test the (M+1)² points of a regular grid (M intervals per
        side) over --box (default: the bounding box of the frame anchors, Alg. 6.2 step 2,
        extended to half the frame's width below the highest anchor when the anchors span less
        than a quarter of that width in height: suspended robots, docs/robots.md).
        The area counts each feasible point's cell clipped to the box (--volume-convention
        cells, the default: never more than the box) or feasible points × cell area
        (--volume-convention points, the thesis' convention). Robots moving in space (point3,
        spatial) use the (M+1)³ points of a 3-D grid; `volume` is then given and `area` is the
        same number (m³).
  chord the chord method (§6.4.3, Alg. 6.3): closed boundary polygons with vertices on the
        boundary (to 1e-8) a chord length --chord apart, every region and hole (seeded by a
        coarse grid of --grid M), corners refined; area = sum of the polygons' signed areas.
        Planar and point2 robots only.
  mesh  robots moving in space (point3, spatial): the boundary inside --box as a closed,
        consistently oriented triangle mesh: marching cubes over the (M+1)³ grid verdicts, every
        vertex then bisected onto the boundary along its grid edge to 1e-8 of the box size;
        the box faces close the mesh where the workspace reaches them. `volume` is the volume
        enclosed by the mesh (divergence theorem; error O(h²) against the grid count's O(h)),
        `grid_volume` the grid count. --mesh FILE.stl|.ply|.obj writes the mesh.

Sections (--section AXIS=VALUE, e.g. z=1.2; point3 and spatial robots): the exact boundary of
the workspace in that plane by the chord method (closed polygons to 1e-8, --chord, seeded by a
--grid M grid of the plane), in the plane's coordinates (y,z for x=…, x,z for y=…, x,y for z=…).

Criteria (--criteria, a comma list; default: tension, plus length and det when the robot file
gives min_cable_length / min_jacobian_det):
  tension         tensions within [t_min, t_max] balance w_ext (eq. 6.21), by --method
  length[:L]      every cable length ≥ l_min (eq. 6.22; L overrides the file's value)
  det[:D]         |det J| ≥ D_min (eq. 6.24; D overrides the file), only when n = DOF
  wrench-closure  the cables positively span the wrench space (no load, no bounds)
  capacity[:M]    capacity margin ≥ M (default 0) of the box --wrench-box around w_ext
  isotropic:F     maximum isotropic force ≥ F (N) on top of w_ext (Krut, Company & Pierrot
                  2004; force at zero moment if rotating): the platform, carrying its weight
                  and --wrench, resists an extra F newtons in every direction
  stiffness:KT,KR stiffness K = Kp + Ka (Picard, Caro, Plestan & Claveau 2020) at the tensions of the tension criterion:
                  for every small displacement δ = (δp, δθ), δᵀKδ ≥ KT‖δp‖² + KR‖δθ‖², i.e.
                  sym(K) − diag(KT·I, KR·I) positive semidefinite; KT in N/m, KR in N·m/rad
                  (point robots: stiffness:KT). Needs axial_stiffness in the robot file and
                  the tension criterion.
  stiffness:K     (older form) smallest eigenvalue of sym(K) ≥ K, K's entries compared as plain
                  SI numbers (N/m, N, N·m/rad: a length scale of 1 m); for point robots the
                  same as stiffness:KT
  interference[:D] every two cables at least D apart (m, default 0: they must not touch;
                  cables sharing an anchor or attachment are left out), and no cable through
                  the platform when the robot file gives `[platform] shape`

The external wrench w_ext is --wrench plus the platform's gravity from the robot file.

JSON (grid): `area` (m², in the convention `volume_convention`: \"cells\" or \"points\"),
`area_cells`, `area_points` (both conventions), `feasible_points`, `total_points`, `cell_area`
(m² or m³), `resolution`, `box` (m), `orientation` (rad), `external_wrench` (N, N·m),
`criteria`, `method`; 3-D grids add `volume` (m³, = `area`).
JSON (mesh): the grid fields (`area`, `area_cells`, `area_points`, `volume_convention`,
`feasible_points`, …; `grid_volume` = `area`, the grid count in --volume-convention) plus
`volume` (m³, enclosed by the mesh), `surface_area` (m², box caps included), `cap_area`
(m², the part on the box faces), `components`, `regions`, `cavities`, `shells` (volume m³, area
m², genus each), `box_faces_reached` ({x_min: bool, …}), `vertices` ([[x, y, z], …] m),
`triangles` ([[i, j, k], …], counter-clockwise seen from outside), `tolerance` (m),
`watertight`, `evaluations`.
JSON (section): the chord fields plus `section` ({axis, value (m), plane_axes}).
--points FILE.csv (grid and mesh) writes the grid verdicts: `x (m),y (m)[,z (m)],feasible`.
JSON (chord): `area`, `boundaries` (closed polygons [[x, y], …]: counter-clockwise around
regions, clockwise around holes), `signed_areas`, `bifurcations` (corner points per polygon),
`abandoned`, `evaluations`, `chord`.

Orientation workspaces (spatial robots): --orientations SET samples a set of orientations
(syntax below) and --kind picks the workspace: `total` (default; positions where every
orientation of the set is feasible; the limiting orientation — the first to fail going
outwards — is reported per boundary grid point) or `maximal` (some orientation feasible).
JSON adds `kind`, `orientation_set`, `orientation_count`, `angle_names`,
`limiting_orientations` ([{`point` (m, on the boundary to 1e-9 of a grid edge),
`angles_deg`}]) and `limiting_summary` ([{`angles_deg`, `boundary_points`}], most frequent
first). With --boundary mesh the workspace of the set is a certified boundary mesh instead
(JSON `volume` (m³), `surface_area` (m²), `components`, `vertices`, `triangles`, `watertight`,
and `limiting_summary` ([{`angles_deg`, `boundary_vertices`}]) per mesh vertex).
`cdpr orientations` gives the feasible orientations at one position.

--plot FILE.svg|png draws the frame anchors, the cables and platform at --draw-pose (default:
the centre of the box at the orientation), the feasible cells filled and the chord boundaries
outlined. Robots moving in space (point3, spatial): an isometric view of the workspace (the
surface of the feasible grid cells) with the anchors, the robot at the draw pose and the box,
plus its three sections x, y, z = the draw pose's coordinates, axes in m. --plot FILE.html
writes one self-contained page (no network needed): the same scene to orbit (drag), zoom
(wheel) and cut with a slider along x, y or z, with a legend giving the volume and settings.";

/// Arguments of the command; see [`LONG_HELP`].
#[derive(clap::Args)]
#[command(allow_negative_numbers = true, after_long_help = format!("{LONG_HELP}\n\n{}", super::orientations::SYNTAX_HELP))]
pub struct Args {
    /// Robot file: .toml, CASPR NAME_cables.xml or WireCenter .wcrfx.
    robot: PathBuf,
    /// Platform orientation: φ (rad) for planar robots, rx,ry,rz (XYZ Euler angles, rad) for
    /// spatial robots; point robots have none (default 0).
    #[arg(long, allow_hyphen_values = true)]
    orientation: Option<Numbers>,
    #[command(flatten)]
    criteria: CriteriaArgs,
    /// Method: `grid` (Algorithm 6.2), `chord` (the chord method, planar robots) or `mesh`
    /// (closed boundary mesh and its volume, robots moving in space).
    #[arg(long, default_value = "grid", value_parser = ["grid", "chord", "mesh"])]
    boundary: String,
    /// With --boundary mesh: write the mesh to FILE.stl (binary), FILE.ply (with per-vertex
    /// normals) or FILE.obj; coordinates in m.
    #[arg(long, value_name = "FILE")]
    mesh: Option<PathBuf>,
    /// Write the grid verdicts to a CSV file (header `x (m),y (m)[,z (m)],feasible`).
    #[arg(long, value_name = "FILE.csv")]
    points: Option<PathBuf>,
    /// Plane section of a 3-D workspace, AXIS=VALUE (m), e.g. z=1.2: its exact boundary by the
    /// chord method.
    #[arg(long, value_name = "AXIS=VALUE", allow_hyphen_values = true)]
    section: Option<String>,
    /// Chord length d of the chord method (the thesis uses 0.05, and 0.03 or 0.02 to resolve
    /// features narrower than 0.05).
    #[arg(long, default_value_t = 0.05, value_parser = super::positive)]
    chord: f64,
    /// Grid resolution M: M intervals per side, (M+1)² points (or (M+1)³ in space); with
    /// --boundary chord, the coarse grid that seeds the walks. Default 50 (thesis), 20 in space.
    #[arg(long, value_name = "M", value_parser = super::count)]
    grid: Option<usize>,
    /// Search box XMIN,XMAX,YMIN,YMAX (in space: XMIN,XMAX,YMIN,YMAX,ZMIN,ZMAX); default the
    /// bounding box of the frame anchors (extended below anchors that span little height).
    #[arg(
        long = "box",
        allow_hyphen_values = true,
        value_name = "XMIN,XMAX,YMIN,YMAX"
    )]
    area: Option<Numbers>,
    /// How feasible points become an area (volume): `cells` (default) counts each point's grid
    /// cell clipped to the box, so a fully feasible box reports exactly its own area; `points`
    /// is the thesis' feasible points × cell area (Algorithm 6.2), which its published areas
    /// follow and which can exceed the box by up to (1 + 1/M)^dim.
    #[arg(long, default_value = "cells", value_name = "cells|points")]
    volume_convention: VolumeConvention,
    /// Pose at which the robot is drawn in the plot (motion-pattern coordinates); default the
    /// centre of the box at --orientation.
    #[arg(long, allow_hyphen_values = true, requires = "plot")]
    draw_pose: Option<Numbers>,
    /// Write the workspace figure (.svg or .png).
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Spatial robots: a sampled orientation set (degrees), e.g.
    /// `euler:rx=-10..10,ry=-10..10,rz=-20..20,n=5` or `tilt:20,torsion=-30..30,n=5`; the
    /// workspace is then the total-orientation or maximal one (--kind).
    #[arg(long, conflicts_with = "orientation", value_parser = super::orientations::set_spec)]
    orientations: Option<String>,
    /// With --orientations: `total` (every orientation feasible; default) or `maximal` (some).
    #[arg(long, value_parser = ["total", "maximal"], requires = "orientations")]
    kind: Option<String>,
    /// Write one JSON object on stdout.
    #[arg(long)]
    json: bool,
}

/// Runs the command: parse → request → run → render (modules `workspace_grid`,
/// `workspace_mesh`, `workspace_chord`, `orientations`).
pub fn run(args: Args) -> Result<(), CliError> {
    super::workspace_mesh::check_options(
        &args.boundary,
        args.mesh.as_deref(),
        args.points.as_deref(),
        args.section.as_deref(),
    )?;
    if let Some(set) = &args.orientations {
        return run_orientations(&args, set);
    }
    let robot = request_robot(&args.robot)?;
    let (draw_pose, plot, json) = (args.draw_pose.as_deref(), args.plot.as_deref(), args.json);
    let chord_view = super::workspace_chord::View {
        draw_pose,
        plot,
        json,
    };
    if let Some(section) = &args.section {
        let mut request = SectionRequest::new(robot, section.parse()?);
        (request.criteria, request.orientation, request.area) = common(&args);
        (request.grid, request.chord) = (args.grid, args.chord);
        return super::workspace_chord::run_section(&request, &chord_view);
    }
    match args.boundary.as_str() {
        "mesh" => {
            let mut request = MeshRequest::new(robot);
            (request.criteria, request.orientation, request.area) = common(&args);
            (request.grid, request.volume_convention) = (args.grid, args.volume_convention);
            let view = super::workspace_mesh::View {
                draw_pose,
                plot,
                mesh: args.mesh.as_deref(),
                points: args.points.as_deref(),
                json,
            };
            super::workspace_mesh::run(&request, &view)
        }
        "chord" => {
            let mut request = ChordRequest::new(robot);
            (request.criteria, request.orientation, request.area) = common(&args);
            (request.grid, request.chord) = (args.grid, args.chord);
            super::workspace_chord::run_chord(&request, &chord_view)
        }
        _ => run_grid(&args, robot),
    }
}

/// The criteria, orientation and box of every request of the command.
fn common(args: &Args) -> (WorkspaceCriteria, Option<Vec<f64>>, Option<Vec<f64>>) {
    let numbers = |n: &Option<Numbers>| n.as_ref().map(|n| n.0.clone());
    (
        args.criteria.to_request(),
        numbers(&args.orientation),
        numbers(&args.area),
    )
}

/// `--boundary grid` (the default) at one orientation (module `workspace_grid`).
fn run_grid(args: &Args, robot: cdpr::api::Robot) -> Result<(), CliError> {
    if let Some(p) = args.plot.as_deref().filter(|p| is_html(p))
        && robot.robot.motion().space_dim() != 3
    {
        return Err(format!(
            "--plot {}: the HTML viewer shows 3-D workspaces (point3, spatial) on the grid; use \
             .svg or .png",
            p.display()
        )
        .into());
    }
    let mut request = WorkspaceRequest::new(robot);
    (request.criteria, request.orientation, request.area) = common(args);
    (request.grid, request.volume_convention) = (args.grid, args.volume_convention);
    let view = super::workspace_grid::View {
        draw_pose: args.draw_pose.as_deref(),
        plot: args.plot.as_deref(),
        points: args.points.as_deref(),
        json: args.json,
    };
    super::workspace_grid::run(&request, &view)
}

/// `--orientations`: the workspace over a set of orientations (an
/// `OrientationWorkspaceRequest`, rendered by module `orientations`).
fn run_orientations(args: &Args, set: &str) -> Result<(), CliError> {
    if args.boundary == "chord" {
        return Err(
            "--orientations runs on the grid or the boundary mesh (--boundary grid|mesh)".into(),
        );
    }
    if args.section.is_some() || args.points.is_some() || args.mesh.is_some() {
        return Err(
            "--section, --points and --mesh apply to one orientation, not --orientations".into(),
        );
    }
    let robot = request_robot(&args.robot)?;
    let mut request = OrientationWorkspaceRequest::new(robot, set);
    request.criteria = args.criteria.to_request();
    (request.kind, request.area) = (args.kind.clone(), common(args).2);
    (request.grid, request.volume_convention) = (args.grid, args.volume_convention);
    let view = super::orientations::View {
        plot: args.plot.as_deref(),
        draw_pose: args.draw_pose.as_deref(),
        json: args.json,
    };
    if args.boundary == "mesh" {
        return super::orientations::run_workspace_mesh(&request, &view);
    }
    super::orientations::run_workspace(&request, &view)
}
