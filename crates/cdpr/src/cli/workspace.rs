//! `cdpr workspace`: the constant-orientation workspace by discretisation (thesis Algorithm 6.2)
//! or by the chord method (§6.4.3), and the helpers shared with `cdpr dextrous` and
//! `cdpr synthesize` (criteria from the command line, grids with a progress bar, plots).

use super::{CliError, Numbers, check_method, external_wrench, load_robot, print_json};
use cdpr::RobotDescription;
use cdpr::kinematics::{MotionPattern, Pose, Robot};
use cdpr::plot::{Figure, Panels, WorkspacePlot};
use cdpr::polytope::RequiredWrenchSet;
use cdpr::tension::Method;
use cdpr::workspace::{
    CentralCheck, ChordSettings, Criterion, Grid, GridWorkspace, LeanScratch, OrientationRange,
    OrientationSet, OrientationWorkspaceKind, PlanarSlice, PoseEvaluator, Region, VolumeConvention,
    chord_workspace, dextrous_verdicts_lean,
};
use indicatif::ProgressBar;
use nalgebra::{DVector, Rotation3, Unit, Vector3};
use rayon::prelude::*;
use serde_json::{Value, json};
use std::io::IsTerminal;
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

/// Workspace criteria and load, shared by `workspace`, `dextrous` and `synthesize`.
#[derive(clap::Args, Clone)]
pub struct CriteriaArgs {
    /// External wrench w_e on the platform (DOF numbers; default zero), e.g. --wrench 0,-10,0 for
    /// the thesis' load L1. The platform's gravity from the robot file is added.
    #[arg(long, allow_hyphen_values = true)]
    pub wrench: Option<Numbers>,
    /// Tension distribution method of the `tension` criterion: exact (n = DOF, eq. 6.12),
    /// closed-form (Alg. 6.1, n = DOF + 1), l1 (eq. 6.19), l2 (eq. 6.17), pinv (eq. 6.14: bounds
    /// only checked, smaller workspace), linf, improved-closed-form, barycenter, sotda, …
    /// Default: exact when n = DOF, else l2 (the thesis' workspace figures); synthesize: exact,
    /// closed-form or l1 (the thesis' constrained minimum ℓ1).
    #[arg(long)]
    pub method: Option<Method>,
    /// Comma list of criteria that must all hold: tension, length[:L] (m), det[:D],
    /// wrench-closure, capacity[:M], isotropic:F (N), stiffness:KT,KR (N/m, N·m/rad) or
    /// stiffness:K, interference[:D] (m) (see `cdpr workspace --help`). Default: tension, plus
    /// length and det when the robot file gives their limits.
    #[arg(long, value_name = "LIST")]
    pub criteria: Option<String>,
    /// Half-widths of the required wrench box of the `capacity` criterion (DOF numbers ≥ 0),
    /// centred on the external wrench.
    #[arg(long, allow_hyphen_values = true)]
    pub wrench_box: Option<Numbers>,
}

/// One criterion as read from the command line (the wrench is bound per orientation later).
pub use cdpr::workspace::CriterionSpec as Spec;

/// The criteria of a command, ready to build an evaluator at any orientation.
#[derive(Debug, Clone)]
pub struct CriteriaSetup {
    /// The criteria.
    pub specs: Vec<Spec>,
    /// Tension method of the tension criterion.
    pub method: Method,
    /// w_e from the command line (gravity is added per orientation).
    pub wrench: Option<Vec<f64>>,
    /// Half-widths of the capacity box.
    pub wrench_box: Option<Vec<f64>>,
}

/// Default tension method of the workspace commands: exact when n = DOF, else constrained ℓ2.
pub fn default_method(robot: &Robot) -> Method {
    if robot.cable_count() == robot.dof() {
        Method::Exact
    } else {
        Method::L2
    }
}

impl CriteriaSetup {
    /// Reads the criteria options against the robot file.
    pub fn from_args(
        args: &CriteriaArgs,
        desc: &RobotDescription,
        method: Method,
    ) -> Result<Self, CliError> {
        check_method(desc, method)?;
        desc.require_no_passive_springs("the workspace")?;
        let dof = desc.robot.dof();
        let limits = desc.limits;
        let specs = cdpr::workspace::parse_criteria(
            args.criteria.as_deref().map(|c| [c]),
            desc.robot.motion(),
            limits.min_cable_length,
            limits.min_jacobian_det,
        )
        .map_err(|e| format!("--criteria: {e}"))?;
        let wrench_box = args.wrench_box.as_ref().map(|b| b.0.clone());
        if specs.iter().any(|s| matches!(s, Spec::Capacity(_))) {
            match &wrench_box {
                None => {
                    return Err(
                        "--criteria capacity needs --wrench-box (half-widths per component)".into(),
                    );
                }
                Some(b) if b.len() != dof => {
                    return Err(format!(
                        "--wrench-box needs {dof} half-widths (one per wrench component), got {}",
                        b.len()
                    )
                    .into());
                }
                Some(_) => {}
            }
        }
        let stiffness_spec = |s: &Spec| matches!(s, Spec::Stiffness(_) | Spec::StiffnessFloor(..));
        let needs_stiffness = specs.iter().any(stiffness_spec)
            || (method == Method::Sotda && specs.contains(&Spec::Tension));
        if needs_stiffness && desc.axial_stiffness.is_none() {
            return Err(
                "the stiffness criterion and the sotda method need `axial_stiffness` (E·S, N) on \
                 every cable of the robot file"
                    .into(),
            );
        }
        if specs.iter().any(stiffness_spec) && !specs.contains(&Spec::Tension) {
            return Err(
                "--criteria stiffness:K needs the tension criterion too (K uses its tensions)"
                    .into(),
            );
        }
        Ok(Self {
            specs,
            method,
            wrench: args.wrench.as_ref().map(|w| w.0.clone()),
            wrench_box,
        })
    }

    /// Criterion labels.
    pub fn labels(&self) -> Vec<String> {
        self.specs.iter().map(Spec::label).collect()
    }

    /// The external wrench (w_e + gravity) at orientation `rotation`.
    pub fn external_wrench(
        &self,
        desc: &RobotDescription,
        rotation: &Rotation3<f64>,
    ) -> Result<DVector<f64>, CliError> {
        external_wrench(
            desc,
            &Pose::new(Vector3::zeros(), *rotation),
            self.wrench.as_deref(),
        )
    }

    /// An evaluator for `robot` (the file's, or a synthesised one with as many cables) at the
    /// orientation `rotation` (which fixes the gravity moment of an offset centre of mass).
    pub fn evaluator(
        &self,
        desc: &RobotDescription,
        robot: Robot,
        rotation: &Rotation3<f64>,
    ) -> Result<PoseEvaluator, CliError> {
        let w_ext = self.external_wrench(desc, rotation)?;
        let criteria = self
            .specs
            .iter()
            .map(|s| {
                Ok(match s {
                    Spec::Tension => Criterion::TensionFeasible {
                        method: self.method,
                        wrench: w_ext.clone(),
                    },
                    Spec::Length(l) => Criterion::MinCableLength(*l),
                    Spec::Det(d) => Criterion::MinJacobianDeterminant(*d),
                    Spec::WrenchClosure => Criterion::WrenchClosure,
                    Spec::Capacity(m) => Criterion::CapacityMargin {
                        required: RequiredWrenchSet::boxed(
                            w_ext.clone(),
                            DVector::from_column_slice(
                                self.wrench_box.as_deref().unwrap_or_default(),
                            ),
                        )?,
                        min_margin: *m,
                    },
                    Spec::Isotropic(f) => Criterion::IsotropicForceUnderLoad {
                        min: *f,
                        wrench: w_ext.clone(),
                    },
                    Spec::Stiffness(k) => Criterion::Stiffness { min_eigenvalue: *k },
                    Spec::StiffnessFloor(kt, kr) => Criterion::StiffnessFloor {
                        translational: *kt,
                        rotational: *kr,
                    },
                    Spec::Interference(d) => Criterion::Interference {
                        min_distance: *d,
                        platform: desc.platform_shape.clone().map(std::sync::Arc::new),
                    },
                })
            })
            .collect::<Result<Vec<_>, CliError>>()?;
        let mut eval = PoseEvaluator::new(robot, desc.bounds.clone(), criteria)?;
        if let Some(es) = &desc.axial_stiffness {
            eval = eval.with_axial_stiffness(es.clone())?;
        }
        eval.validate()?;
        Ok(eval)
    }
}

/// The platform orientation from command-line numbers: φ (planar), rx,ry,rz (spatial), none
/// (point robots; zeros are accepted).
pub fn rotation(motion: MotionPattern, q: Option<&[f64]>) -> Result<Rotation3<f64>, CliError> {
    let q = q.unwrap_or(&[]);
    if let Some(v) = q.iter().find(|v| !v.is_finite()) {
        return Err(format!("--orientation: {v} is not a finite number").into());
    }
    match motion {
        MotionPattern::Point2 | MotionPattern::Point3 => {
            if q.iter().any(|&v| v != 0.0) {
                return Err(format!(
                    "a `{}` robot has no orientation: omit --orientation",
                    motion.name()
                )
                .into());
            }
            Ok(Rotation3::identity())
        }
        MotionPattern::Planar => match q {
            [] => Ok(Rotation3::identity()),
            [phi] => Ok(Rotation3::from_axis_angle(&Vector3::z_axis(), *phi)),
            _ => Err(format!(
                "--orientation needs 1 number (φ) for a planar robot, got {}",
                q.len()
            )
            .into()),
        },
        MotionPattern::Spatial => match q {
            [] => Ok(Rotation3::identity()),
            [rx, ry, rz] => Ok(Pose::spatial(Vector3::zeros(), *rx, *ry, *rz).rotation),
            _ => Err(format!(
                "--orientation needs 3 numbers (rx,ry,rz) for a spatial robot, got {}",
                q.len()
            )
            .into()),
        },
    }
}

/// The search box: 4 numbers in the plane, 6 in space; default [`Region::default_for`] (the
/// frame anchors' bounding box, extended below anchors that span little height).
pub fn region(robot: &Robot, q: Option<&[f64]>, option: &str) -> Result<Region, CliError> {
    let dim = robot.motion().space_dim();
    let r = match q {
        None => Region::default_for(robot),
        Some(b) if dim == 2 && b.len() == 4 => Region::planar(b[0], b[1], b[2], b[3]),
        Some(b) if dim == 3 && b.len() == 6 => Region::cuboid(
            Vector3::new(b[0], b[2], b[4]),
            Vector3::new(b[1], b[3], b[5]),
        ),
        Some(b) => {
            return Err(format!(
                "{option} needs {} numbers ({}) for a `{}` robot, got {}",
                2 * dim,
                if dim == 2 {
                    "XMIN,XMAX,YMIN,YMAX"
                } else {
                    "XMIN,XMAX,YMIN,YMAX,ZMIN,ZMAX"
                },
                robot.motion().name(),
                b.len()
            )
            .into());
        }
    };
    if q.is_some() {
        for (k, axis) in ["x", "y", "z"].iter().enumerate().take(dim) {
            let (lo, hi) = (r.min[k], r.max[k]);
            let (a, b) = (axis.to_uppercase(), axis.to_uppercase());
            if !(lo.is_finite() && hi.is_finite()) {
                return Err(format!(
                    "{option}: the {axis} bounds {a}MIN = {lo}, {b}MAX = {hi} must be finite numbers (m)"
                )
                .into());
            }
            if lo >= hi {
                return Err(format!(
                    "{option}: along {axis}, {a}MIN = {lo} m must be less than {b}MAX = {hi} m"
                )
                .into());
            }
        }
    }
    r.validate(dim)?;
    Ok(r)
}

/// Grid resolution: default 50 in the plane (the thesis), 20 in space; bounded to keep the
/// point count reasonable.
pub fn resolution(m: Option<usize>, dim: usize, default_2d: usize) -> Result<usize, CliError> {
    let max = if dim == 2 { 4000 } else { 300 };
    let m = m.unwrap_or(if dim == 2 { default_2d } else { 20 });
    if !(1..=max).contains(&m) {
        return Err(format!("--grid M must lie in [1, {max}] for a {dim}-D grid").into());
    }
    Ok(m)
}

/// A progress bar on stderr counting `len` chunks, hidden unless stderr is a terminal.
pub fn progress(len: usize) -> ProgressBar {
    if std::io::stderr().is_terminal() {
        ProgressBar::new(len as u64)
    } else {
        ProgressBar::hidden()
    }
}

/// Evaluates `f` at every point of `grid` in parallel (grid order: x fastest), one clone of
/// `state` per rayon task; `bar` counts rows of the grid (chunks of M + 1 points).
pub fn map_rows<S, T, F>(state: &S, grid: &Grid, dim: usize, bar: &ProgressBar, f: F) -> Vec<T>
where
    S: Clone + Send + Sync,
    T: Send,
    F: Fn(&mut S, Vector3<f64>) -> T + Sync,
{
    let row = grid.points_per_axis();
    let total = grid.point_count(dim);
    let rows: Vec<Vec<T>> = (0..total.div_ceil(row))
        .into_par_iter()
        .map_init(
            || state.clone(),
            |s, r| {
                let out = (r * row..((r + 1) * row).min(total))
                    .map(|idx| f(s, grid.point(dim, idx)))
                    .collect();
                bar.inc(1);
                out
            },
        )
        .collect();
    rows.into_iter().flatten().collect()
}

/// [`map_rows`] a row at a time: `f(state, points, verdicts)` fills the verdicts of one row's
/// points (`T::default()` on entry).
pub fn map_row_blocks<S, T, F>(
    state: &S,
    grid: &Grid,
    dim: usize,
    bar: &ProgressBar,
    f: F,
) -> Vec<T>
where
    S: Clone + Send + Sync,
    T: Send + Copy + Default,
    F: Fn(&mut S, &[Vector3<f64>], &mut [T]) + Sync,
{
    let row = grid.points_per_axis();
    let total = grid.point_count(dim);
    let rows: Vec<Vec<T>> = (0..total.div_ceil(row))
        .into_par_iter()
        .map_init(
            || (state.clone(), Vec::new()),
            |(s, points), r| {
                points.clear();
                points
                    .extend((r * row..((r + 1) * row).min(total)).map(|idx| grid.point(dim, idx)));
                let mut out = vec![T::default(); points.len()];
                f(s, points, &mut out);
                bar.inc(1);
                out
            },
        )
        .collect();
    rows.into_iter().flatten().collect()
}

/// Algorithm 6.2 at a fixed orientation, with a progress bar (same verdicts as
/// `cdpr::workspace::constant_orientation_workspace`).
pub fn grid_workspace(
    eval: &PoseEvaluator,
    rotation: &Rotation3<f64>,
    grid: &Grid,
    bar: &ProgressBar,
) -> Result<GridWorkspace, CliError> {
    let dim = eval.robot().motion().space_dim();
    grid.validate(dim)?;
    eval.validate()?;
    let r = *rotation;
    let feasible = map_rows(eval, grid, dim, bar, |ev, u| {
        ev.is_feasible(&Pose::new(u, r))
    });
    bar.finish_and_clear();
    Ok(GridWorkspace::from_verdicts(*grid, dim, feasible))
}

/// A dextrous workspace on a grid (eq. 6.28) with the §6.5 check.
pub struct Dextrous {
    /// Points feasible at every sampled orientation.
    pub workspace: GridWorkspace,
    /// The check of the two-extremes shortcut.
    pub central_check: CentralCheck,
    /// Sampled angles.
    pub angles: Vec<f64>,
}

/// One evaluator per sampled orientation (each with the gravity moment of that orientation).
#[derive(Clone)]
struct Slices {
    evals: Vec<PoseEvaluator>,
    rotations: Vec<Rotation3<f64>>,
    /// Index of the central orientation among the slices, or its own evaluator.
    central: Result<usize, (Box<PoseEvaluator>, Rotation3<f64>)>,
}

/// Eq. (6.28) for rotations `base · R(axis, φ)`, φ over `range`, on `grid`: the points feasible at
/// every sampled orientation, tested as `cdpr::workspace::dextrous_workspace_about_axis` does
/// (extremes first, then the central orientation, then the others), but with one evaluator per
/// orientation so that the gravity moment of an offset centre of mass follows the platform.
#[allow(clippy::too_many_arguments)]
pub fn dextrous(
    setup: &CriteriaSetup,
    desc: &RobotDescription,
    robot: &Robot,
    base: &Rotation3<f64>,
    axis: &Unit<Vector3<f64>>,
    range: &OrientationRange,
    grid: &Grid,
    bar: &ProgressBar,
) -> Result<Dextrous, CliError> {
    range.validate()?;
    let motion = robot.motion();
    let dim = motion.space_dim();
    grid.validate(dim)?;
    let rot = |phi: f64| -> Rotation3<f64> {
        match motion {
            MotionPattern::Point2 | MotionPattern::Point3 => Rotation3::identity(),
            _ => base * Rotation3::from_axis_angle(axis, phi),
        }
    };
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
    // The lean planar r = 1 path of every orientation, if all have it (the same verdicts).
    let lean = evals
        .iter()
        .zip(&rotations)
        .map(|(e, r)| PlanarSlice::new(e, r))
        .collect::<Option<Vec<_>>>()
        .and_then(|l| match &central {
            Ok(_) => Some((l, None)),
            Err((e, r)) => PlanarSlice::new(e, r).map(|c| (l, Some(c))),
        });
    let slices = Slices {
        evals,
        rotations,
        central,
    };
    let n = angles.len();
    let verdicts = if let Some((lean, central_lean)) = &lean {
        // Row by row, four points at a time, orientation by orientation.
        let central = match &slices.central {
            Ok(k) => Ok(*k),
            Err(_) => Err(central_lean
                .as_ref()
                .expect("built with the central evaluator")),
        };
        let state = (slices, LeanScratch::default());
        map_row_blocks(&state, grid, dim, bar, |(s, scratch), points, out| {
            dextrous_verdicts_lean(lean, central, points, out, scratch, |k, u| match k {
                Some(k) => s.evals[k].is_feasible(&Pose::new(*u, s.rotations[k])),
                None => match &mut s.central {
                    Err((ev, r)) => ev.is_feasible(&Pose::new(*u, *r)),
                    Ok(k) => s.evals[*k].is_feasible(&Pose::new(*u, s.rotations[*k])),
                },
            })
        })
    } else {
        map_rows(&slices, grid, dim, bar, |s, u| {
            let ok =
                |s: &mut Slices, k: usize| s.evals[k].is_feasible(&Pose::new(u, s.rotations[k]));
            if !ok(s, 0) || (n > 1 && !ok(s, n - 1)) {
                return (false, false, false);
            }
            let (central_ok, central_index) = match &mut s.central {
                Ok(k) => {
                    let k = *k;
                    (ok(s, k), Some(k))
                }
                Err((ev, r)) => (ev.is_feasible(&Pose::new(u, *r)), None),
            };
            let others_ok = (1..n.saturating_sub(1))
                .filter(|&k| Some(k) != central_index)
                .all(|k| ok(s, k));
            let dextrous = (central_ok || central_index.is_none()) && others_ok;
            (dextrous, true, !central_ok)
        })
    };
    bar.finish_and_clear();
    let violations = verdicts.iter().filter(|v| v.2).count();
    Ok(Dextrous {
        workspace: GridWorkspace::from_verdicts(*grid, dim, verdicts.iter().map(|v| v.0).collect()),
        central_check: CentralCheck {
            holds: violations == 0,
            violations,
            extremes_points: verdicts.iter().filter(|v| v.1).count(),
        },
        angles,
    })
}

/// The pose at which the robot is drawn: `--draw-pose` or the box centre at `rotation`.
pub fn draw_pose(
    robot: &Robot,
    q: Option<&[f64]>,
    region: &Region,
    rotation: &Rotation3<f64>,
) -> Result<Pose, CliError> {
    match q {
        Some(q) => Ok(Pose::from_coordinates(robot.motion(), q)?),
        None => {
            let mut c = (region.min + region.max) * 0.5;
            if robot.motion().space_dim() == 2 {
                c.z = 0.0;
            }
            Ok(Pose::new(c, *rotation))
        }
    }
}

/// A figure's title (robot and what is drawn) and the line under it: orientation (rad), load
/// (N, N·m) and tension method, e.g. "orientation φ = 0.1 rad; load w_ext = [0, -10, 0] (N, N, N·m);
/// tensions l2".
pub fn plot_title(
    robot: &str,
    what: &str,
    motion: MotionPattern,
    orientation: &[f64],
    w_ext: &[f64],
    method: Method,
) -> (String, String) {
    let orientation = match motion {
        MotionPattern::Planar => format!(
            "orientation φ = {} rad; ",
            cdpr::plot::tick(orientation.first().copied().unwrap_or(0.0))
        ),
        MotionPattern::Spatial => format!("orientation [{}] rad; ", tick_list(orientation)),
        _ => String::new(),
    };
    (
        format!("{robot}: {what}"),
        format!("{orientation}{}", load_text(motion, w_ext, method)),
    )
}

/// "load w_ext = [0, -10, 0] (N, N, N·m); tensions l2".
pub fn load_text(motion: MotionPattern, w_ext: &[f64], method: Method) -> String {
    let units = match motion {
        MotionPattern::Planar => "N, N, N·m",
        MotionPattern::Spatial => "forces N, moments N·m",
        _ => "N",
    };
    format!(
        "load w_ext = [{}] ({units}); tensions {}",
        tick_list(w_ext),
        method.name()
    )
}

fn tick_list(v: &[f64]) -> String {
    v.iter()
        .map(|x| cdpr::plot::tick(*x))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Axis label of a length coordinate (robot files are in SI units, docs/robot-file.md).
pub fn length_axis(axis: &str) -> String {
    format!("{axis} (m)")
}

/// What an empty grid or chord result draws in the middle of the chart.
pub const EMPTY_WORKSPACE: &str = "no feasible pose in the box";

/// The planar workspace figure: anchors, cables at `pose`, feasible cells, outlined (and
/// filled) boundaries; a note in the middle when nothing is feasible.
pub fn workspace_plot(
    robot: &Robot,
    pose: &Pose,
    ws: Option<&GridWorkspace>,
    boundaries: Vec<Vec<(f64, f64)>>,
    title: String,
    notes: Vec<String>,
) -> WorkspacePlot {
    let mut feasible_points = Vec::new();
    let mut cell = (0.0, 0.0);
    if let Some(ws) = ws {
        cell = grid_cell(ws);
        feasible_points = layer_points(ws, 0);
    }
    let fill = ws.is_none() && !boundaries.is_empty();
    let empty = feasible_points.is_empty() && boundaries.is_empty();
    WorkspacePlot {
        title,
        feasible_points,
        cell,
        boundaries,
        fill_boundaries: fill,
        notes,
        axis_names: Some((length_axis("x"), length_axis("y"))),
        empty_message: empty.then(|| EMPTY_WORKSPACE.to_string()),
        ..WorkspacePlot::default()
    }
    .with_robot(robot, pose)
}

/// The 3-D figure (`.html` viewer, or isometric view and sections) of a spatial or point3
/// workspace on a grid: the surface of the grid cells, the robot at `pose`.
pub fn save_scene_plot(
    desc: &RobotDescription,
    pose: &Pose,
    ws: &GridWorkspace,
    title: String,
    legend: Vec<String>,
    path: &Path,
) -> Result<(), CliError> {
    let (vertices, triangles) = cdpr::plot::grid_surface(ws);
    let r = &ws.grid.region;
    let scene = cdpr::plot::Scene {
        title,
        vertices,
        triangles,
        region: ([r.min.x, r.min.y, r.min.z], [r.max.x, r.max.y, r.max.z]),
        legend,
        mesh_label: format!(
            "grid cells of the feasible points (m = {})",
            ws.grid.resolution
        ),
        ..cdpr::plot::Scene::default()
    }
    .with_robot(&desc.robot, pose, desc.platform_shape.as_ref());
    cdpr::plot::save_scene(&scene, path)?;
    Ok(())
}

/// The 3-D figure of a boundary mesh (`--boundary mesh`): the certified surface in place of the
/// grid cells.
pub fn save_mesh_scene_plot(
    desc: &RobotDescription,
    pose: &Pose,
    mesh: &cdpr::workspace::BoundaryMesh,
    title: String,
    legend: Vec<String>,
    path: &Path,
) -> Result<(), CliError> {
    let r = &mesh.grid.grid.region;
    let scene = cdpr::plot::Scene {
        title,
        vertices: mesh.vertices.clone(),
        triangles: mesh.triangles.clone(),
        region: ([r.min.x, r.min.y, r.min.z], [r.max.x, r.max.y, r.max.z]),
        legend,
        mesh_label: format!(
            "boundary mesh (vertices on the boundary to {:.1e} m)",
            mesh.tolerance
        ),
        ..cdpr::plot::Scene::default()
    }
    .with_robot(&desc.robot, pose, desc.platform_shape.as_ref());
    cdpr::plot::save_scene(&scene, path)?;
    Ok(())
}

/// Whether `path` names an HTML page (only 3-D workspaces have one).
pub fn is_html(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("html"))
}

/// The (Δx, Δy) spacing of a grid.
fn grid_cell(ws: &GridWorkspace) -> (f64, f64) {
    let m = ws.grid.resolution as f64;
    let ext = ws.grid.region.extent();
    (ext.x / m, ext.y / m)
}

/// The feasible (x, y) points of z-layer `k` of a grid (the only layer of a planar grid).
fn layer_points(ws: &GridWorkspace, k: usize) -> Vec<(f64, f64)> {
    let p = ws.grid.points_per_axis();
    let first = if ws.dim == 3 { k * p * p } else { 0 };
    (first..first + p * p)
        .filter(|&idx| ws.feasible[idx])
        .map(|idx| {
            let u = ws.point(idx);
            (u.x, u.y)
        })
        .collect()
}

/// Number of z-slices drawn for a 3-D workspace.
pub const SLICES: usize = 4;

/// The z-layers drawn for a 3-D grid of resolution m: the layers nearest the centres of
/// [`SLICES`] equal bands of the box height, without repeats.
pub fn slice_layers(m: usize) -> Vec<usize> {
    let mut layers: Vec<usize> = (0..SLICES)
        .map(|j| (((j as f64 + 0.5) / SLICES as f64) * m as f64).round() as usize)
        .collect();
    layers.dedup();
    layers
}

/// A 3-D grid workspace as [`SLICES`] z-slices side by side (2 × 2), each with the frame anchors
/// seen from above (coinciding anchors share a label) and the cables at `pose` moved to the
/// slice height; the title and notes above all slices.
pub fn workspace_slices(
    robot: &Robot,
    pose: &Pose,
    ws: &GridWorkspace,
    title: String,
    notes: Vec<String>,
) -> Panels<WorkspacePlot> {
    let p = ws.grid.points_per_axis();
    let panels = slice_layers(ws.grid.resolution)
        .into_iter()
        .map(|k| {
            let z = ws.point(k * p * p).z;
            let points = layer_points(ws, k);
            let count = points.len();
            let mut at = *pose;
            at.position.z = z;
            WorkspacePlot {
                title: format!("slice z = {}", cdpr::plot::tick(z)),
                notes: vec![format!("{count} of {} points feasible", p * p)],
                empty_message: (count == 0).then(|| EMPTY_WORKSPACE.to_string()),
                feasible_points: points,
                cell: grid_cell(ws),
                axis_names: Some((length_axis("x"), length_axis("y"))),
                ..WorkspacePlot::default()
            }
            .with_robot(robot, &at)
        })
        .collect();
    Panels {
        title,
        notes,
        columns: 2,
        panel_size: (640, 680),
        panels,
    }
}

/// Writes a plot (SVG or PNG by extension).
pub fn save_plot(fig: &impl Figure, path: &Path) -> Result<(), CliError> {
    cdpr::plot::save(fig, path)?;
    Ok(())
}

/// The grid's area (volume) fields: `area` in `convention`, both conventions, and its name.
pub fn measure_json(v: &mut Value, ws: &GridWorkspace, convention: VolumeConvention) {
    let a = ws.measure(convention);
    v["area"] = json!(a);
    v["area_cells"] = json!(ws.clipped_area);
    v["area_points"] = json!(ws.area);
    v["volume_convention"] = json!(convention.name());
    if ws.dim == 3 {
        v["volume"] = json!(a);
    }
}

/// The grid workspace figure: one chart for planar robots, z-slices for 3-D ones.
pub fn save_grid_plot(
    robot: &Robot,
    pose: &Pose,
    ws: &GridWorkspace,
    title: String,
    notes: Vec<String>,
    path: &Path,
) -> Result<(), CliError> {
    if ws.dim == 3 {
        save_plot(&workspace_slices(robot, pose, ws, title, notes), path)
    } else {
        save_plot(
            &workspace_plot(robot, pose, Some(ws), Vec::new(), title, notes),
            path,
        )
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

/// Box as JSON numbers.
pub fn box_json(r: &Region, dim: usize) -> Value {
    json!(box_numbers(r, dim))
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
    let desc = load_robot(&args.robot)?;
    let robot = &desc.robot;
    let motion = robot.motion();
    let dim = motion.space_dim();
    let method = args
        .criteria
        .method
        .unwrap_or_else(|| default_method(robot));
    let setup = CriteriaSetup::from_args(&args.criteria, &desc, method)?;
    let rot = rotation(motion, args.orientation.as_deref())?;
    let region = region(robot, args.area.as_deref(), "--box")?;
    let m = resolution(args.grid, dim, 50)?;
    super::workspace_mesh::check_options(&args_mesh_view(&args), motion)?;
    if let Some(set) = &args.orientations {
        if args.boundary == "chord" {
            return Err(
                "--orientations runs on the grid or the boundary mesh (--boundary grid|mesh)"
                    .into(),
            );
        }
        if args.section.is_some() || args.points.is_some() || args.mesh.is_some() {
            return Err(
                "--section, --points and --mesh apply to one orientation, not --orientations"
                    .into(),
            );
        }
        let kind = match args.kind.as_deref() {
            Some("maximal") => OrientationWorkspaceKind::Maximal,
            _ => OrientationWorkspaceKind::Total,
        };
        if args.boundary == "mesh" {
            return super::orientations::run_workspace_mesh(
                &desc,
                &setup,
                set,
                kind,
                &region,
                m,
                args.plot.as_deref(),
                args.draw_pose.as_deref(),
                args.json,
            );
        }
        return super::orientations::run_workspace(
            &desc,
            &setup,
            set,
            kind,
            &region,
            m,
            args.plot.as_deref(),
            args.draw_pose.as_deref(),
            args.json,
            args.volume_convention,
        );
    }
    let eval = setup.evaluator(&desc, robot.clone(), &rot)?;
    let w_ext = setup.external_wrench(&desc, &rot)?;
    let orientation = match (&args.orientation, motion) {
        (Some(o), _) => o.0.clone(),
        (None, MotionPattern::Planar) => vec![0.0],
        (None, MotionPattern::Spatial) => vec![0.0; 3],
        (None, _) => vec![],
    };
    if let Some(p) = &args.plot {
        if is_html(p) && (dim != 3 || args.boundary == "chord") {
            return Err(format!(
                "--plot {}: the HTML viewer shows 3-D workspaces (point3, spatial) on the grid; \
                 use .svg or .png",
                p.display()
            )
            .into());
        }
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
    if args.boundary == "chord" {
        if dim != 2 {
            return Err(format!(
                "--boundary chord maps boundary curves in the plane; this robot is `{}` \
                 (use --boundary grid)",
                motion.name()
            )
            .into());
        }
        let phi = if motion == MotionPattern::Planar {
            orientation.first().copied().unwrap_or(0.0)
        } else {
            0.0
        };
        // The bisection tolerance ε^u must stay below d/100: the default 1e-8 m, smaller for
        // chords under 1e-6 m (the user sets d only, so no tolerance of theirs is at fault).
        let defaults = ChordSettings::default();
        let settings = ChordSettings {
            chord: args.chord,
            seed_resolution: m,
            tolerance: defaults.tolerance.min(args.chord * 1e-3),
            ..defaults
        };
        let ws = chord_workspace(&eval, phi, &region, &settings)?;
        let polys: Vec<Vec<(f64, f64)>> = ws
            .boundaries
            .iter()
            .map(|b| b.vertices.iter().map(|v| (v[0], v[1])).collect())
            .collect();
        let regions = ws
            .boundaries
            .iter()
            .filter(|b| b.signed_area() > 0.0)
            .count();
        let holes = ws.boundaries.len() - regions;
        if let (Some(path), Some(pose)) = (&args.plot, &pose) {
            let (title, setting) = plot_title(
                &desc.name,
                "constant-orientation workspace (chord method)",
                motion,
                &orientation,
                w_ext.as_slice(),
                method,
            );
            let fig = workspace_plot(
                robot,
                pose,
                None,
                polys.clone(),
                title,
                vec![
                    setting,
                    format!(
                        "area {:.4}, {regions} region(s), {holes} hole(s), chord d = {}; {}",
                        ws.area,
                        args.chord,
                        setup.labels().join(", ")
                    ),
                ],
            );
            save_plot(&fig, path)?;
        }
        if args.json {
            return print_json(&super::workspace_mesh::with_chord_fields(
                json!({
                    "robot": desc.name,
                    "method": "chord",
                    "orientation": orientation,
                    "external_wrench": w_ext.as_slice(),
                    "criteria": setup.labels(),
                    "tension_method": method.name(),
                    "box": box_json(&region, dim),
                    "chord": args.chord,
                }),
                &ws,
            ));
        }
        println!(
            "robot {}: chord-method workspace at orientation {} rad, w_ext {}",
            desc.name,
            super::nums(&orientation),
            super::wrench_text(w_ext.as_slice(), motion.translation_dof())
        );
        println!(
            "criteria: {} (tensions: {})",
            setup.labels().join(", "),
            method.name()
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
    } else {
        let grid = Grid::new(m, region);
        let bar = progress(grid.point_count(dim).div_ceil(grid.points_per_axis()));
        let ws = grid_workspace(&eval, &rot, &grid, &bar)?;
        if let Some(path) = &args.points {
            super::workspace_mesh::write_points(&ws, path)?;
        }
        let (what, unit) = if dim == 2 {
            ("area", "m²")
        } else {
            ("volume", "m³")
        };
        if let (Some(path), Some(pose), 3) = (&args.plot, &pose, dim) {
            save_scene_plot(
                &desc,
                pose,
                &ws,
                format!(
                    "{}: constant-orientation workspace {:?}",
                    desc.name, orientation
                ),
                vec![
                    format!(
                        "volume {:.4} m³ ({} of {} points, m = {m}, {} convention)",
                        ws.measure(args.volume_convention),
                        ws.feasible_points,
                        ws.total_points,
                        args.volume_convention
                    ),
                    format!("criteria: {}", setup.labels().join(", ")),
                    format!(
                        "draw pose ({:.3}, {:.3}, {:.3}) m",
                        pose.position.x, pose.position.y, pose.position.z
                    ),
                ],
                path,
            )?;
        } else if let (Some(path), Some(pose)) = (&args.plot, &pose) {
            let (title, setting) = plot_title(
                &desc.name,
                "constant-orientation workspace (grid)",
                motion,
                &orientation,
                w_ext.as_slice(),
                method,
            );
            save_grid_plot(
                robot,
                pose,
                &ws,
                title,
                vec![
                    setting,
                    format!(
                        "{what} {:.4} {unit} ({} of {} points, m = {m}, {} convention); {}",
                        ws.measure(args.volume_convention),
                        ws.feasible_points,
                        ws.total_points,
                        args.volume_convention,
                        setup.labels().join(", ")
                    ),
                ],
                path,
            )?;
        }
        if args.json {
            let mut v = json!({
                "robot": desc.name,
                "method": "grid",
                "orientation": orientation,
                "external_wrench": w_ext.as_slice(),
                "criteria": setup.labels(),
                "tension_method": method.name(),
                "box": box_json(&region, dim),
                "resolution": m,
                "dimension": dim,
                "feasible_points": ws.feasible_points,
                "total_points": ws.total_points,
                "cell_area": ws.cell_area,
            });
            measure_json(&mut v, &ws, args.volume_convention);
            return print_json(&v);
        }
        println!(
            "robot {}: constant-orientation workspace at orientation {}, w_ext {}",
            desc.name,
            if orientation.is_empty() {
                "(none: a point robot)".to_string()
            } else {
                format!("{} rad", super::nums(&orientation))
            },
            super::wrench_text(w_ext.as_slice(), motion.translation_dof())
        );
        println!(
            "criteria: {} (tensions: {})",
            setup.labels().join(", "),
            method.name()
        );
        println!(
            "grid m = {m} over {} m: {} of {} points feasible, cell {what} {:.6e} {unit}",
            super::nums(&box_numbers(&region, dim)),
            ws.feasible_points,
            ws.total_points,
            ws.cell_area
        );
        println!(
            "{what} {:.6} {unit} ({})",
            ws.measure(args.volume_convention),
            args.volume_convention.describe()
        );
    }
    if let Some(p) = &args.plot {
        println!("plot written to {}", p.display());
    }
    Ok(())
}
