//! # Boundary mesh of a 3-D workspace (marching cubes refined by bisection)
//!
//! The constant-orientation workspace of a robot moving in space (`point3`, `spatial`), for any
//! list of criteria, as a closed, consistently oriented triangle mesh of its boundary inside the
//! search box, with every vertex on the boundary to a tolerance ε (10⁻⁸ of the box size by
//! default): the 3-D analogue of the chord method of §6.4.3, whose boundary points are also
//! found by bisection to ε^u (Algorithm 6.3).
//!
//! 1. **Grid verdicts.** The (M+1)³ points of Algorithm 6.2 are tested in parallel.
//! 2. **Crossings.** Every grid edge (between neighbours along x, y or z) whose two verdicts
//!    differ holds one mesh vertex, placed by bisection on the edge until the bracket is shorter
//!    than ε (the midpoint of the last bracket is kept: within ε/2 of a boundary point of the
//!    edge). Edges are bisected in parallel, one evaluator per rayon task.
//! 3. **Surface in each cell** (marching cubes, Lorensen & Cline 1987, with the face rule below
//!    in place of the case table). On each face of a cell, walked counter-clockwise seen from
//!    outside the cell, the crossings alternate between entering and leaving the feasible set; each
//!    entering crossing is joined to the next leaving one. On a face with four crossings (feasible
//!    corners on one diagonal, the ambiguous case of marching cubes) this always separates the
//!    feasible corners, and both cells sharing the face make the same choice: the segments of
//!    neighbouring cells coincide and the surface has no cracks (the consistency requirement of
//!    Nielson & Hamann 1991, here met by a fixed rule). The segments of a cell chain into closed
//!    loops, each triangulated by the minimum-length triangulation (dynamic programming over the
//!    polygon) that uses no chord between two vertices of a common cell face (such a chord could
//!    also be chosen by the neighbouring cell and be shared by four triangles).
//! 4. **Box caps.** Points outside the box count as infeasible: where the workspace reaches a box
//!    face, the face's feasible part (the square cells of the face, clipped by the same segments)
//!    closes the mesh. [`BoundaryMesh::box_faces_reached`] tells which faces do.
//!
//! Every edge of the result is shared by exactly two triangles, traversed in opposite directions
//! (each surface segment lies on one cell face, used by the two cells or the cell and the cap;
//! each chord lies inside one cell), and triangles are oriented with normals out of the workspace.
//! The volume follows from the divergence theorem, V = (1/6) Σ_T (v₀ − o)·((v₁ − o) × (v₂ − o)).
//! Along a flat piece of boundary the mesh is exact up to ε; across an edge or a curved piece of
//! boundary the chord of a cell deviates by O(h²) (h the cell size), so the volume error is
//! O(h²) where the grid count's is O(h).
//!
//! Features smaller than a cell (a thin sliver, a tunnel narrower than h) may be missed or
//! joined, as for any grid-seeded method: the topology is that of the grid verdicts.
//!
//! ## References
//! - Lorensen & Cline (1987), "Marching cubes: a high resolution 3D surface construction
//!   algorithm", SIGGRAPH 87.
//! - Nielson & Hamann (1991), "The asymptotic decider: resolving the ambiguity in marching
//!   cubes", IEEE Visualization 91 (face consistency).
//! - Ju, Losasso, Schaefer & Warren (2002), "Dual contouring of Hermite data", SIGGRAPH 02 (edge
//!   crossings found on the grid edges, then the surface built from them).
//! - Thesis §6.4.3 and Algorithm 6.3: the chord method, the planar analogue (boundary points by
//!   bisection to ε^u), and Algorithm 6.2 (the grid).

use crate::discretisation::{checked_orientation, map_grid};
use crate::{Grid, GridWorkspace, PoseEvaluator, WorkspaceError};
use cdpr_kinematics::Pose;
use nalgebra::{Rotation3, Vector3};

/// Settings of [`boundary_mesh`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshSettings {
    /// Bisection tolerance relative to the box size (its largest extent): the vertices lie within
    /// `tolerance × size / 2` of a boundary point on their grid edge. Default 10⁻⁸.
    pub tolerance: f64,
}

impl Default for MeshSettings {
    fn default() -> Self {
        Self { tolerance: 1e-8 }
    }
}

impl MeshSettings {
    /// Checks 0 < tolerance < 10⁻².
    pub fn validate(&self) -> Result<(), WorkspaceError> {
        if !(self.tolerance > 0.0 && self.tolerance < 1e-2) {
            return Err(WorkspaceError::InvalidSetting {
                what: "mesh tolerance (relative to the box size)",
                value: self.tolerance,
                expected: "0 < tolerance < 1e-2",
            });
        }
        Ok(())
    }
}

/// A face of the search box.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BoxFace {
    /// x = x_min.
    XMin,
    /// x = x_max.
    XMax,
    /// y = y_min.
    YMin,
    /// y = y_max.
    YMax,
    /// z = z_min.
    ZMin,
    /// z = z_max.
    ZMax,
}

impl BoxFace {
    /// The six faces, in the order of [`BoundaryMesh::box_faces_reached`].
    pub const ALL: [BoxFace; 6] = [
        BoxFace::XMin,
        BoxFace::XMax,
        BoxFace::YMin,
        BoxFace::YMax,
        BoxFace::ZMin,
        BoxFace::ZMax,
    ];

    /// Short name (`x_min`, …, `z_max`).
    pub fn name(self) -> &'static str {
        ["x_min", "x_max", "y_min", "y_max", "z_min", "z_max"][self as usize]
    }

    /// The axis normal to the face (0 = x, 1 = y, 2 = z).
    pub fn axis(self) -> usize {
        self as usize / 2
    }

    /// Whether the face is at the upper end of its axis.
    pub fn is_max(self) -> bool {
        self as usize % 2 == 1
    }
}

/// Where a mesh vertex comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MeshVertex {
    /// A boundary point found by bisection on the grid edge from the feasible grid point
    /// `feasible_end` to the infeasible `infeasible_end` (parallel to `axis`).
    Crossing {
        /// Axis of the grid edge (0 = x, 1 = y, 2 = z).
        axis: usize,
        /// The edge's feasible grid point.
        feasible_end: [f64; 3],
        /// The edge's infeasible grid point.
        infeasible_end: [f64; 3],
    },
    /// A feasible grid point on a box face: a corner of a box cap, not a workspace boundary point.
    GridPoint,
}

/// One closed, connected piece of the mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shell {
    /// Signed enclosed volume: > 0 around a region, < 0 around a cavity (a hole inside a region).
    pub volume: f64,
    /// Area of the shell (box caps included).
    pub area: f64,
    /// Number of triangles.
    pub triangles: usize,
    /// Number of vertices.
    pub vertices: usize,
    /// Genus from the Euler characteristic, g = (2 − (V − E + F)) / 2: the number of tunnels
    /// through the region (0 for a ball).
    pub genus: i64,
}

/// The boundary of a 3-D workspace inside the search box as a closed triangle mesh (see the
/// module documentation).
///
/// ```
/// use cdpr_kinematics::{Cable, MotionPattern, Robot};
/// use cdpr_tension::TensionBounds;
/// use cdpr_workspace::{boundary_mesh, Criterion, Grid, MeshSettings, PoseEvaluator, Region};
/// use nalgebra::{Rotation3, Vector3};
/// // A point robot with four cables to the corners of a tetrahedron: its wrench-closure
/// // workspace is the open tetrahedron of the anchors (volume 8/3 here).
/// let c = |x: f64, y: f64, z: f64| Cable { frame: Vector3::new(x, y, z), platform: Vector3::zeros(), pulley: None };
/// let robot = Robot::new(MotionPattern::Point3, vec![
///     c(1.0, 1.0, 1.0), c(1.0, -1.0, -1.0), c(-1.0, 1.0, -1.0), c(-1.0, -1.0, 1.0),
/// ]).unwrap();
/// let eval = PoseEvaluator::new(robot, TensionBounds::uniform(4, 0.0, 1.0).unwrap(),
///                               vec![Criterion::WrenchClosure]).unwrap();
/// let grid = Grid::new(20, Region::cuboid(Vector3::repeat(-1.2), Vector3::repeat(1.2)));
/// let mesh = boundary_mesh(&eval, &Rotation3::identity(), &grid, &MeshSettings::default()).unwrap();
/// assert_eq!(mesh.edge_defects(), 0); // closed, consistently oriented
/// assert_eq!(mesh.cavities(), 0);
/// // O(h²) error (h = 0.12 here); the grid count's is O(h).
/// assert!((mesh.volume - 8.0 / 3.0).abs() < 0.03 * 8.0 / 3.0);
/// assert!(mesh.box_faces_reached.iter().all(|&r| !r));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct BoundaryMesh {
    /// Vertex positions (m).
    pub vertices: Vec<[f64; 3]>,
    /// Origin of each vertex (boundary crossing or box-cap corner).
    pub origins: Vec<MeshVertex>,
    /// Triangles (vertex indices), counter-clockwise seen from outside the workspace.
    pub triangles: Vec<[u32; 3]>,
    /// For each triangle, the box face it lies on (a cap closing the workspace where it reaches
    /// the box), or `None` for a workspace boundary triangle.
    pub caps: Vec<Option<BoxFace>>,
    /// Enclosed volume (m³), by the divergence theorem.
    pub volume: f64,
    /// Area of the closed mesh (m²), box caps included.
    pub surface_area: f64,
    /// Area of the box caps (m²): `surface_area − cap_area` is the workspace boundary proper.
    pub cap_area: f64,
    /// Number of connected pieces of the mesh ([`BoundaryMesh::shells`]).
    pub components: usize,
    /// The connected pieces, in order of their first triangle.
    pub shells: Vec<Shell>,
    /// Whether the workspace reaches each box face, in the order of [`BoxFace::ALL`].
    pub box_faces_reached: [bool; 6],
    /// Absolute bisection tolerance ε (m).
    pub tolerance: f64,
    /// Pose evaluations: the grid's plus the bisections'.
    pub evaluations: usize,
    /// The grid verdicts the mesh was seeded from (Algorithm 6.2).
    pub grid: GridWorkspace,
}

impl BoundaryMesh {
    /// Number of regions: shells of positive volume.
    pub fn regions(&self) -> usize {
        self.shells.iter().filter(|s| s.volume > 0.0).count()
    }

    /// Number of cavities (holes inside a region): shells of negative volume.
    pub fn cavities(&self) -> usize {
        self.shells.iter().filter(|s| s.volume < 0.0).count()
    }

    /// Number of directed edges that break closure: 0 when every edge is shared by exactly two
    /// triangles traversed in opposite directions (watertight, consistently oriented).
    pub fn edge_defects(&self) -> usize {
        let mut directed: Vec<(u32, u32)> = self
            .triangles
            .iter()
            .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
            .collect();
        directed.sort_unstable();
        let mut defects = 0;
        for (k, &(a, b)) in directed.iter().enumerate() {
            let repeated = k > 0 && directed[k - 1] == (a, b)
                || k + 1 < directed.len() && directed[k + 1] == (a, b);
            let paired = directed.binary_search(&(b, a)).is_ok();
            if repeated || !paired || a == b {
                defects += 1;
            }
        }
        defects
    }

    /// Area-weighted unit normal at each vertex (out of the workspace).
    pub fn vertex_normals(&self) -> Vec<[f64; 3]> {
        let mut n = vec![Vector3::zeros(); self.vertices.len()];
        for t in &self.triangles {
            let [a, b, c] = t.map(|i| Vector3::from(self.vertices[i as usize]));
            let w = (b - a).cross(&(c - a));
            for &i in t {
                n[i as usize] += w;
            }
        }
        n.into_iter()
            .map(|v| {
                let l = v.norm();
                if l > 0.0 { (v / l).into() } else { [0.0; 3] }
            })
            .collect()
    }

    /// Unit normal of each triangle (out of the workspace).
    pub fn triangle_normals(&self) -> Vec<[f64; 3]> {
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| Vector3::from(self.vertices[i as usize]));
                let w = (b - a).cross(&(c - a));
                let l = w.norm();
                if l > 0.0 { (w / l).into() } else { [0.0; 3] }
            })
            .collect()
    }
}

/// Corners of a cell: corner c is at grid offset (c & 1, (c >> 1) & 1, c >> 2).
const FACES: [[usize; 4]; 6] = [
    // Counter-clockwise seen from outside the cell, in the order of `BoxFace::ALL`.
    [0, 4, 6, 2],
    [1, 3, 7, 5],
    [0, 1, 5, 4],
    [2, 6, 7, 3],
    [0, 2, 3, 1],
    [4, 5, 7, 6],
];

/// Local index (0..12) of the cell edge between corners `a` and `b` (differing in one bit):
/// axis × 4 + the two other bits of the lower corner.
const fn local_edge(a: usize, b: usize) -> usize {
    let lo = if a < b { a } else { b };
    let axis = (a ^ b).trailing_zeros() as usize;
    let rest = match axis {
        0 => lo >> 1,
        1 => (lo & 1) | ((lo >> 2) << 1),
        _ => lo & 3,
    };
    axis * 4 + rest
}

/// Lower corner and axis of local edge `e`.
const fn edge_corner(e: usize) -> (usize, usize) {
    let (axis, rest) = (e / 4, e % 4);
    let lo = match axis {
        0 => rest << 1,
        1 => (rest & 1) | ((rest >> 1) << 2),
        _ => rest,
    };
    (lo, axis)
}

/// Whether local edges `a` and `b` lie on a common cell face.
fn share_face(a: usize, b: usize) -> bool {
    FACES.iter().any(|f| {
        let on = |e: usize| (0..4).any(|t| local_edge(f[t], f[(t + 1) % 4]) == e);
        on(a) && on(b)
    })
}

/// Precomputed tables of the cell.
struct CellTables {
    share_face: [[bool; 12]; 12],
}

impl CellTables {
    fn new() -> Self {
        let mut share = [[false; 12]; 12];
        for (a, row) in share.iter_mut().enumerate() {
            for (b, s) in row.iter_mut().enumerate() {
                *s = a != b && share_face(a, b);
            }
        }
        Self { share_face: share }
    }
}

const NONE: u32 = u32::MAX;

/// The boundary mesh of the constant-orientation workspace at `orientation` on `grid` (see the
/// module documentation). Robots moving in space only.
pub fn boundary_mesh(
    eval: &PoseEvaluator,
    orientation: &Rotation3<f64>,
    grid: &Grid,
    settings: &MeshSettings,
) -> Result<BoundaryMesh, WorkspaceError> {
    let motion = eval.robot().motion();
    if motion.space_dim() != 3 {
        return Err(WorkspaceError::NotSpatial {
            method: "the boundary mesh",
            motion: motion.name(),
        });
    }
    grid.validate(3)?;
    settings.validate()?;
    eval.validate()?;
    let rotation = checked_orientation(motion, orientation)?;
    let verdicts = map_grid(eval, grid, 3, |ev, u| {
        ev.is_feasible_finite_rotation(&Pose::new(u, rotation))
    });
    let ws = GridWorkspace::from_verdicts(*grid, 3, verdicts);
    Ok(mesh_from_verdicts(
        eval,
        |ev: &mut PoseEvaluator, u| ev.is_feasible_finite_rotation(&Pose::new(u, rotation)),
        ws,
        settings,
    ))
}

/// The boundary mesh of any set of positions given by a per-point predicate `feasible(state,
/// u)` (e.g. an [`crate::OrientationTest`] for total-orientation and maximal workspaces): the
/// same steps as [`boundary_mesh`], `state` cloned once per rayon task.
pub fn boundary_mesh_of<S, F>(
    state: &S,
    feasible: F,
    grid: &Grid,
    settings: &MeshSettings,
) -> Result<BoundaryMesh, WorkspaceError>
where
    S: Clone + Send + Sync,
    F: Fn(&mut S, Vector3<f64>) -> bool + Sync,
{
    grid.validate(3)?;
    settings.validate()?;
    let verdicts = map_grid(state, grid, 3, &feasible);
    let ws = GridWorkspace::from_verdicts(*grid, 3, verdicts);
    Ok(mesh_from_verdicts(state, feasible, ws, settings))
}

/// Steps 2–4 of the module documentation, from the grid verdicts.
fn mesh_from_verdicts<S, F>(
    state: &S,
    feasible_at: F,
    ws: GridWorkspace,
    settings: &MeshSettings,
) -> BoundaryMesh
where
    S: Clone + Send + Sync,
    F: Fn(&mut S, Vector3<f64>) -> bool + Sync,
{
    let grid = ws.grid;
    let m = grid.resolution;
    let p = m + 1;
    let stride = [1, p, p * p];
    let at = |idx: usize| grid.point(3, idx);
    let size = grid.region.extent().max();
    let tolerance = settings.tolerance * size;
    let feasible = &ws.feasible;

    // Step 2: one vertex per grid edge with differing verdicts, edge id = 3 · point + axis.
    let mut edge_vertex = vec![NONE; 3 * feasible.len()];
    let mut crossings: Vec<(usize, usize)> = Vec::new();
    for idx in 0..feasible.len() {
        let ijk = [idx % p, (idx / p) % p, idx / (p * p)];
        for axis in 0..3 {
            if ijk[axis] < m && feasible[idx] != feasible[idx + stride[axis]] {
                edge_vertex[3 * idx + axis] = crossings.len() as u32;
                crossings.push((idx, axis));
            }
        }
    }
    const CHUNK: usize = 64;
    let bisected: Vec<([f64; 3], MeshVertex, usize)> = crate::parallel::map_init(
        crossings.len().div_ceil(CHUNK),
        || state.clone(),
        |ev, c| {
            crossings[c * CHUNK..crossings.len().min((c + 1) * CHUNK)]
                .iter()
                .map(|&(idx, axis)| {
                    let (a, b) = if feasible[idx] {
                        (idx, idx + stride[axis])
                    } else {
                        (idx + stride[axis], idx)
                    };
                    let (pa, pb) = (at(a), at(b));
                    let mut u = pa;
                    let (mut lo, mut hi) = (pa[axis], pb[axis]);
                    let mut evaluations = 0;
                    while (hi - lo).abs() > tolerance {
                        let mid = 0.5 * (lo + hi);
                        u[axis] = mid;
                        evaluations += 1;
                        if feasible_at(ev, u) {
                            lo = mid;
                        } else {
                            hi = mid;
                        }
                    }
                    u[axis] = 0.5 * (lo + hi);
                    let origin = MeshVertex::Crossing {
                        axis,
                        feasible_end: pa.into(),
                        infeasible_end: pb.into(),
                    };
                    (u.into(), origin, evaluations)
                })
                .collect::<Vec<_>>()
        },
    )
    .into_iter()
    .flatten()
    .collect();
    let evaluations = ws.total_points + bisected.iter().map(|b| b.2).sum::<usize>();
    let mut vertices: Vec<[f64; 3]> = bisected.iter().map(|b| b.0).collect();
    let mut origins: Vec<MeshVertex> = bisected.iter().map(|b| b.1).collect();
    drop(bisected);

    // Steps 3–4, cell by cell.
    let tables = CellTables::new();
    let mut point_vertex: Vec<u32> = Vec::new(); // grid point → cap corner vertex, lazily
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    let mut caps: Vec<Option<BoxFace>> = Vec::new();
    let mut box_faces_reached = [false; 6];
    for k in 0..m {
        for j in 0..m {
            for i in 0..m {
                let base = i + j * p + k * p * p;
                let corner_idx = |c: usize| base + (c & 1) + ((c >> 1) & 1) * p + (c >> 2) * p * p;
                let mut mask = 0u8;
                for c in 0..8 {
                    if feasible[corner_idx(c)] {
                        mask |= 1 << c;
                    }
                }
                let on_box = [i == 0, i + 1 == m, j == 0, j + 1 == m, k == 0, k + 1 == m];
                if mask == 0 || (mask == 255 && !on_box.iter().any(|&b| b)) {
                    continue;
                }
                let inside = |c: usize| mask >> c & 1 == 1;
                let vertex_of = |e: usize| {
                    let (lo, axis) = edge_corner(e);
                    edge_vertex[3 * corner_idx(lo) + axis]
                };
                // Step 3: face segments, entering → next leaving crossing.
                let mut next = [usize::MAX; 12];
                for face in &FACES {
                    let mut cross = [(0usize, false); 4];
                    let mut n = 0;
                    for t in 0..4 {
                        let (a, b) = (face[t], face[(t + 1) % 4]);
                        if inside(a) != inside(b) {
                            cross[n] = (local_edge(a, b), inside(b));
                            n += 1;
                        }
                    }
                    for q in 0..n {
                        if cross[q].1 {
                            next[cross[q].0] = cross[(q + 1) % n].0;
                        }
                    }
                }
                let mut seen = [false; 12];
                for start in 0..12 {
                    if next[start] == usize::MAX || seen[start] {
                        continue;
                    }
                    let mut lp = [0usize; 12];
                    let mut len = 0;
                    let mut e = start;
                    while !seen[e] {
                        seen[e] = true;
                        lp[len] = e;
                        len += 1;
                        e = next[e];
                    }
                    triangulate_loop(&lp[..len], &tables, &vertex_of, &vertices, |t| {
                        triangles.push(t);
                        caps.push(None);
                    });
                }
                // Step 4: caps on the cell faces that lie on the box.
                for (f, face) in FACES.iter().enumerate() {
                    if !on_box[f] || !face.iter().any(|&c| inside(c)) {
                        continue;
                    }
                    box_faces_reached[f] = true;
                    let mut corner_vertex = |c: usize| {
                        let idx = corner_idx(c);
                        if point_vertex.is_empty() {
                            point_vertex = vec![NONE; feasible.len()];
                        }
                        if point_vertex[idx] == NONE {
                            point_vertex[idx] = vertices.len() as u32;
                            vertices.push(at(idx).into());
                            origins.push(MeshVertex::GridPoint);
                        }
                        point_vertex[idx]
                    };
                    let mut poly = [0u32; 6];
                    let mut emit = |poly: &[u32]| {
                        for q in 1..poly.len() - 1 {
                            triangles.push([poly[0], poly[q], poly[q + 1]]);
                            caps.push(Some(BoxFace::ALL[f]));
                        }
                    };
                    if face.iter().all(|&c| inside(c)) {
                        for (t, &c) in face.iter().enumerate() {
                            poly[t] = corner_vertex(c);
                        }
                        emit(&poly[..4]);
                        continue;
                    }
                    // From each entering crossing, along the feasible corners, to the leaving one.
                    for t in 0..4 {
                        let (a, b) = (face[t], face[(t + 1) % 4]);
                        if inside(a) || !inside(b) {
                            continue;
                        }
                        poly[0] = vertex_of(local_edge(a, b));
                        let mut n = 1;
                        let mut s = (t + 1) % 4;
                        while inside(face[s]) {
                            poly[n] = corner_vertex(face[s]);
                            n += 1;
                            s = (s + 1) % 4;
                        }
                        let last = (s + 3) % 4;
                        poly[n] = vertex_of(local_edge(face[last], face[s]));
                        emit(&poly[..n + 1]);
                    }
                }
            }
        }
    }
    finish(
        vertices,
        origins,
        triangles,
        caps,
        box_faces_reached,
        tolerance,
        evaluations,
        ws,
    )
}

/// Triangulates one loop of local edges (in order) by the minimum total chord length, avoiding
/// chords between two vertices of a common cell face (which a neighbouring cell could also use).
/// Triangles (i, k, j) with i < k < j keep the loop's orientation.
fn triangulate_loop(
    lp: &[usize],
    tables: &CellTables,
    vertex_of: &impl Fn(usize) -> u32,
    vertices: &[[f64; 3]],
    mut push: impl FnMut([u32; 3]),
) {
    let n = lp.len();
    let v: [u32; 12] = std::array::from_fn(|q| if q < n { vertex_of(lp[q]) } else { 0 });
    if n == 3 {
        push([v[0], v[1], v[2]]);
        return;
    }
    let pos = |q: usize| Vector3::from(vertices[v[q] as usize]);
    // Chord weight: its length, plus a penalty for a chord on a cell face.
    let weight = |a: usize, b: usize| {
        if b == a + 1 || (a == 0 && b == n - 1) {
            return 0.0;
        }
        let penalty = if tables.share_face[lp[a]][lp[b]] {
            1e30
        } else {
            0.0
        };
        (pos(a) - pos(b)).norm() + penalty
    };
    let mut cost = [[0.0f64; 12]; 12];
    let mut split = [[0usize; 12]; 12];
    for gap in 2..n {
        for a in 0..n - gap {
            let b = a + gap;
            let best = (a + 1..b)
                .map(|c| (cost[a][c] + cost[c][b] + weight(a, c) + weight(c, b), c))
                .fold((f64::INFINITY, a + 1), |x, y| if y.0 < x.0 { y } else { x });
            cost[a][b] = best.0;
            split[a][b] = best.1;
        }
    }
    let mut stack = [(0usize, 0usize); 12];
    let mut top = 1;
    stack[0] = (0, n - 1);
    while top > 0 {
        top -= 1;
        let (a, b) = stack[top];
        if b < a + 2 {
            continue;
        }
        let c = split[a][b];
        push([v[a], v[c], v[b]]);
        stack[top] = (a, c);
        stack[top + 1] = (c, b);
        top += 2;
    }
}

/// Volume, areas and shells of the assembled mesh.
#[allow(clippy::too_many_arguments)]
fn finish(
    vertices: Vec<[f64; 3]>,
    origins: Vec<MeshVertex>,
    triangles: Vec<[u32; 3]>,
    caps: Vec<Option<BoxFace>>,
    box_faces_reached: [bool; 6],
    tolerance: f64,
    evaluations: usize,
    grid: GridWorkspace,
) -> BoundaryMesh {
    let o = (grid.grid.region.min + grid.grid.region.max) * 0.5;
    // Union–find over vertices joined by triangles.
    let mut parent: Vec<u32> = (0..vertices.len() as u32).collect();
    fn root(parent: &mut [u32], mut a: u32) -> u32 {
        while parent[a as usize] != a {
            let g = parent[parent[a as usize] as usize];
            parent[a as usize] = g;
            a = g;
        }
        a
    }
    for t in &triangles {
        for q in 1..3 {
            let (ra, rb) = (root(&mut parent, t[0]), root(&mut parent, t[q]));
            if ra != rb {
                parent[ra.max(rb) as usize] = ra.min(rb);
            }
        }
    }
    let mut shell_of_root = vec![NONE; vertices.len()];
    let mut shells: Vec<Shell> = Vec::new();
    let (mut volume, mut surface_area, mut cap_area) = (0.0, 0.0, 0.0);
    for (t, cap) in triangles.iter().zip(&caps) {
        let [a, b, c] = t.map(|i| Vector3::from(vertices[i as usize]) - o);
        let w = (b - a).cross(&(c - a));
        let (vol, area) = (a.dot(&b.cross(&c)) / 6.0, 0.5 * w.norm());
        let r = root(&mut parent, t[0]) as usize;
        if shell_of_root[r] == NONE {
            shell_of_root[r] = shells.len() as u32;
            shells.push(Shell {
                volume: 0.0,
                area: 0.0,
                triangles: 0,
                vertices: 0,
                genus: 0,
            });
        }
        let s = &mut shells[shell_of_root[r] as usize];
        s.volume += vol;
        s.area += area;
        s.triangles += 1;
        volume += vol;
        surface_area += area;
        if cap.is_some() {
            cap_area += area;
        }
    }
    for v in 0..vertices.len() as u32 {
        let r = root(&mut parent, v) as usize;
        if shell_of_root[r] != NONE {
            shells[shell_of_root[r] as usize].vertices += 1;
        }
    }
    for s in &mut shells {
        // Closed surface: E = 3F/2, χ = V − E + F = V − F/2.
        let chi = s.vertices as i64 - (s.triangles as i64) / 2;
        s.genus = (2 - chi) / 2;
    }
    BoundaryMesh {
        vertices,
        origins,
        triangles,
        caps,
        volume,
        surface_area,
        cap_area,
        components: shells.len(),
        shells,
        box_faces_reached,
        tolerance,
        evaluations,
        grid,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn local_edges_round_trip_and_faces_are_outward() {
        for e in 0..12 {
            let (lo, axis) = edge_corner(e);
            assert_eq!(lo >> axis & 1, 0);
            assert_eq!(local_edge(lo, lo | 1 << axis), e);
        }
        let corner = |c: usize| Vector3::new((c & 1) as f64, (c >> 1 & 1) as f64, (c >> 2) as f64);
        for (f, face) in FACES.iter().enumerate() {
            let [a, b, c, _] = face.map(corner);
            let n = (b - a).cross(&(c - b));
            let mut outward = Vector3::zeros();
            outward[f / 2] = if f % 2 == 1 { 1.0 } else { -1.0 };
            assert_eq!(n, outward, "face {f}");
        }
        // Each edge lies on exactly two faces.
        for e in 0..12 {
            let faces = FACES
                .iter()
                .filter(|f| (0..4).any(|t| local_edge(f[t], f[(t + 1) % 4]) == e))
                .count();
            assert_eq!(faces, 2);
        }
    }
}
