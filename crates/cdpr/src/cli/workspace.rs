//! `cdpr workspace`: the constant-orientation workspace by discretisation (thesis Algorithm 6.2)
//! or by the chord method (§6.4.3). The pieces it shares with the other region commands are in
//! `criteria` (criteria from the command line) and `region` (boxes, grids with a progress bar,
//! plots).

use super::criteria::{CriteriaArgs, CriteriaSetup, default_method};
use super::region::{
    box_json, draw_pose, is_html, plot_title, region, resolution, rotation, save_plot,
    workspace_plot,
};
use super::workspace_mesh::Context;
use super::{CliError, Numbers, load_robot, print_json, request_robot};
use cdpr::RobotDescription;
use cdpr::api::WorkspaceRequest;
use cdpr::kinematics::{MotionPattern, Pose};
use cdpr::workspace::{
    ChordSettings, ChordWorkspace, OrientationSet, OrientationWorkspaceKind, Region,
    VolumeConvention, chord_workspace,
};
use serde_json::json;
use std::path::{Path, PathBuf};

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
    #[arg(long, conflicts_with = "orientation")]
    orientations: Option<OrientationSet>,
    /// With --orientations: `total` (every orientation feasible; default) or `maximal` (some).
    #[arg(long, value_parser = ["total", "maximal"], requires = "orientations")]
    kind: Option<String>,
    /// Write one JSON object on stdout.
    #[arg(long)]
    json: bool,
}

/// The options that `--boundary mesh` and `--section` check.
fn args_mesh_view(args: &Args) -> super::workspace_mesh::Options<'_> {
    super::workspace_mesh::Options {
        boundary: &args.boundary,
        mesh: args.mesh.as_deref(),
        points: args.points.as_deref(),
        section: args.section.as_deref(),
    }
}

/// Runs the command.
pub fn run(args: Args) -> Result<(), CliError> {
    if args.boundary == "grid" && args.section.is_none() && args.orientations.is_none() {
        return run_grid(&args);
    }
    let desc = load_robot(&args.robot)?;
    let robot = &desc.robot;
    let motion = robot.motion();
    let dim = motion.space_dim();
    let method = args
        .criteria
        .method
        .unwrap_or_else(|| default_method(robot));
    let setup = super::criteria::setup(&args.criteria, &desc, method)?;
    let rot = rotation(motion, args.orientation.as_deref())?;
    let region = region(robot, args.area.as_deref(), "--box")?;
    let m = resolution(args.grid, dim, 50)?;
    super::workspace_mesh::check_options(&args_mesh_view(&args), motion)?;
    if let Some(set) = &args.orientations {
        return run_orientations(&args, &desc, &setup, set, &region, m);
    }
    let eval = setup.evaluator(&desc, robot.clone(), &rot)?;
    let w_ext = setup.external_wrench(&desc, &rot)?;
    let orientation = match (&args.orientation, motion) {
        (Some(o), _) => o.0.clone(),
        (None, MotionPattern::Planar) => vec![0.0],
        (None, MotionPattern::Spatial) => vec![0.0; 3],
        (None, _) => vec![],
    };
    if let Some(p) = &args.plot
        && is_html(p)
        && (dim != 3 || args.boundary == "chord")
    {
        return Err(format!(
            "--plot {}: the HTML viewer shows 3-D workspaces (point3, spatial) on the grid; \
                 use .svg or .png",
            p.display()
        )
        .into());
    }
    let context = super::workspace_mesh::Context {
        desc: &desc,
        setup: &setup,
        eval: &eval,
        rotation: &rot,
        orientation: &orientation,
        w_ext: w_ext.as_slice(),
        region: &region,
        m,
        volume_convention: args.volume_convention,
        draw_pose: args.draw_pose.as_deref(),
        plot: args.plot.as_deref(),
        json: args.json,
    };
    if let Some(section) = &args.section {
        let section = super::workspace_mesh::parse_section(section, &region)?;
        return super::workspace_mesh::run_section(&context, section, args.chord);
    }
    if args.boundary == "mesh" {
        return super::workspace_mesh::run_mesh(
            &context,
            args.mesh.as_deref(),
            args.points.as_deref(),
        );
    }
    let pose = if args.plot.is_some() {
        Some(draw_pose(robot, args.draw_pose.as_deref(), &region, &rot)?)
    } else {
        None
    };
    run_chord(&args, &context, pose.as_ref())?;
    if let (Some(p), false) = (&args.plot, args.json) {
        println!("plot written to {}", p.display());
    }
    Ok(())
}

/// `--boundary grid` (the default) at one orientation: parse → request → run → render
/// (module `workspace_grid`).
fn run_grid(args: &Args) -> Result<(), CliError> {
    let robot = request_robot(&args.robot)?;
    let motion = robot.robot.motion();
    super::workspace_mesh::check_options(&args_mesh_view(args), motion)?;
    if let Some(p) = &args.plot
        && is_html(p)
        && motion.space_dim() != 3
    {
        return Err(format!(
            "--plot {}: the HTML viewer shows 3-D workspaces (point3, spatial) on the grid; \
                 use .svg or .png",
            p.display()
        )
        .into());
    }
    let numbers = |n: &Option<Numbers>| n.as_ref().map(|n| n.0.clone());
    let request = WorkspaceRequest {
        robot,
        criteria: args.criteria.to_request(),
        orientation: numbers(&args.orientation),
        area: numbers(&args.area),
        grid: args.grid,
        volume_convention: args.volume_convention,
    };
    let view = super::workspace_grid::View {
        draw_pose: args.draw_pose.as_deref(),
        plot: args.plot.as_deref(),
        points: args.points.as_deref(),
        json: args.json,
    };
    super::workspace_grid::run(&request, &view)
}

/// `--orientations`: the workspace over a set of orientations (module `orientations`).
fn run_orientations(
    args: &Args,
    desc: &RobotDescription,
    setup: &CriteriaSetup,
    set: &OrientationSet,
    region: &Region,
    m: usize,
) -> Result<(), CliError> {
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
    let kind = match args.kind.as_deref() {
        Some("maximal") => OrientationWorkspaceKind::Maximal,
        _ => OrientationWorkspaceKind::Total,
    };
    if args.boundary == "mesh" {
        return super::orientations::run_workspace_mesh(
            desc,
            setup,
            set,
            kind,
            region,
            m,
            args.plot.as_deref(),
            args.draw_pose.as_deref(),
            args.json,
        );
    }
    super::orientations::run_workspace(
        desc,
        setup,
        set,
        kind,
        region,
        m,
        args.plot.as_deref(),
        args.draw_pose.as_deref(),
        args.json,
        args.volume_convention,
    )
}

/// `--boundary chord`: boundary curves by the chord method (§6.4.3), planar robots only.
fn run_chord(args: &Args, c: &Context<'_>, pose: Option<&Pose>) -> Result<(), CliError> {
    let motion = c.desc.robot.motion();
    if motion.space_dim() != 2 {
        return Err(format!(
            "--boundary chord maps boundary curves in the plane; this robot is `{}` \
             (use --boundary grid)",
            motion.name()
        )
        .into());
    }
    let phi = if motion == MotionPattern::Planar {
        c.orientation.first().copied().unwrap_or(0.0)
    } else {
        0.0
    };
    // The bisection tolerance ε^u must stay below d/100: the default 1e-8 m, smaller for
    // chords under 1e-6 m (the user sets d only, so no tolerance of theirs is at fault).
    let defaults = ChordSettings::default();
    let settings = ChordSettings {
        chord: args.chord,
        seed_resolution: c.m,
        tolerance: defaults.tolerance.min(args.chord * 1e-3),
        ..defaults
    };
    let ws = chord_workspace(c.eval, phi, c.region, &settings)?;
    if let (Some(path), Some(pose)) = (&args.plot, pose) {
        save_chord_plot(args, c, pose, &ws, path)?;
    }
    if args.json {
        return print_json(&super::workspace_mesh::with_chord_fields(
            json!({
                "robot": c.desc.name,
                "method": "chord",
                "orientation": c.orientation,
                "external_wrench": c.w_ext,
                "criteria": c.setup.labels(),
                "tension_method": c.setup.method.name(),
                "box": box_json(c.region, 2),
                "chord": args.chord,
            }),
            &ws,
        ));
    }
    print_chord(args, c, &ws);
    Ok(())
}

/// Regions (counter-clockwise boundaries) and holes (clockwise) of a chord-method workspace.
fn regions_and_holes(ws: &ChordWorkspace) -> (usize, usize) {
    let regions = ws
        .boundaries
        .iter()
        .filter(|b| b.signed_area() > 0.0)
        .count();
    (regions, ws.boundaries.len() - regions)
}

/// The plot of `--boundary chord`: the robot and the boundary curves.
fn save_chord_plot(
    args: &Args,
    c: &Context<'_>,
    pose: &Pose,
    ws: &ChordWorkspace,
    path: &Path,
) -> Result<(), CliError> {
    let robot = &c.desc.robot;
    let polys: Vec<Vec<(f64, f64)>> = ws
        .boundaries
        .iter()
        .map(|b| b.vertices.iter().map(|v| (v[0], v[1])).collect())
        .collect();
    let (regions, holes) = regions_and_holes(ws);
    let (title, setting) = plot_title(
        &c.desc.name,
        "constant-orientation workspace (chord method)",
        robot.motion(),
        c.orientation,
        c.w_ext,
        c.setup.method,
    );
    let mut fig = workspace_plot(
        robot,
        pose,
        None,
        polys,
        title,
        vec![
            setting,
            format!(
                "area {:.4}, {regions} region(s), {holes} hole(s), chord d = {}; {}",
                ws.area,
                args.chord,
                c.setup.labels().join(", ")
            ),
        ],
    );
    fig.anchor_names = cdpr::plot::cable_names(&c.desc.cable_names);
    save_plot(&fig, path)
}

/// The text answer of `--boundary chord`.
fn print_chord(args: &Args, c: &Context<'_>, ws: &ChordWorkspace) {
    let (regions, holes) = regions_and_holes(ws);
    println!(
        "robot {}: chord-method workspace at orientation {} rad, w_ext {}",
        c.desc.name,
        super::nums(c.orientation),
        super::wrench_text(c.w_ext, c.desc.robot.motion().translation_dof())
    );
    println!(
        "criteria: {} (tensions: {})",
        c.setup.labels().join(", "),
        c.setup.method.name()
    );
    println!(
        "area {:.6} m²: {regions} region(s), {holes} hole(s), chord d = {} m, {} pose evaluations",
        ws.area, args.chord, ws.evaluations
    );
    for (k, b) in ws.boundaries.iter().enumerate() {
        println!(
            "  boundary {}: {} vertices, signed area {:+.6} m², perimeter {:.4} m, {} bifurcation point(s)",
            k + 1,
            b.vertices.len(),
            b.signed_area(),
            b.perimeter(),
            b.bifurcations.len()
        );
    }
    if ws.abandoned > 0 {
        println!(
            "warning: {} boundary walk(s) abandoned (curves missing)",
            ws.abandoned
        );
    }
}
