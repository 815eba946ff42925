//! A 3-D scene of a spatial (or point3) robot and its workspace, shared by the HTML viewer
//! ([`super::viewer`]) and the isometric figure ([`super::iso`]): frame anchors, cables and
//! platform at the draw pose, the workspace as a triangle mesh, and the search box.

use cdpr_kinematics::{ConvexPolyhedron, Pose, Robot};
use cdpr_workspace::GridWorkspace;
use nalgebra::Vector3;
use std::collections::HashMap;

/// Everything a 3-D view shows (base coordinates, m).
#[derive(Debug, Clone, Default)]
pub struct Scene {
    /// Title.
    pub title: String,
    /// Frame anchors c^i.
    pub anchors: Vec<[f64; 3]>,
    /// Cables at the draw pose: (frame anchor, platform attachment point).
    pub cables: Vec<([f64; 3], [f64; 3])>,
    /// Sagging cables at the draw pose: per cable the polyline of its catenary from the frame
    /// anchor to the attachment (m); empty (or an empty entry) draws the straight chord.
    pub cable_curves: Vec<Vec<[f64; 3]>>,
    /// Platform faces at the draw pose (closed polygons); empty for a point platform.
    pub platform: Vec<Vec<[f64; 3]>>,
    /// The draw pose's position.
    pub platform_position: [f64; 3],
    /// Workspace mesh vertices.
    pub vertices: Vec<[f64; 3]>,
    /// Workspace mesh triangles (indices into `vertices`, counter-clockwise seen from outside).
    pub triangles: Vec<[u32; 3]>,
    /// The search box (min, max corners).
    pub region: ([f64; 3], [f64; 3]),
    /// Legend lines: volume, settings.
    pub legend: Vec<String>,
    /// What the mesh is, for the legend (e.g. "boundary mesh (vertices to 1e-8)").
    pub mesh_label: String,
    /// Unit of the three axes (empty: m). A force polytope's is N.
    pub units: String,
    /// A ball drawn inside the mesh: (centre, radius), e.g. the largest ball of the force
    /// polytope centred at −w_ext.
    pub ball: Option<([f64; 3], f64)>,
    /// What the ball is, for the legend.
    pub ball_label: String,
    /// Anchor labels: the cables' `name` keys (empty: `A1`, `A2`, …; see [`super::anchor_label`]).
    pub anchor_names: Vec<String>,
    /// Whether to leave out the dashed box (`region` then only frames the view).
    pub hide_box: bool,
}

fn arr(v: &Vector3<f64>) -> [f64; 3] {
    [v.x, v.y, v.z]
}

impl Scene {
    /// A scene with the robot drawn at `pose`: anchors, cables, and the platform (`shape` if
    /// given, else the hull of the attachments when they span a volume).
    pub fn with_robot(
        mut self,
        robot: &Robot,
        pose: &Pose,
        shape: Option<&ConvexPolyhedron>,
    ) -> Self {
        let place = |p: &Vector3<f64>| arr(&(pose.position + pose.rotation * p));
        self.anchors = robot.cables().iter().map(|c| arr(&c.frame)).collect();
        self.cables = robot
            .cables()
            .iter()
            .map(|c| (arr(&c.frame), place(&c.platform)))
            .collect();
        let hull = match shape {
            Some(s) => Some(s.clone()),
            None => {
                let pts: Vec<Vector3<f64>> = robot.cables().iter().map(|c| c.platform).collect();
                ConvexPolyhedron::from_points(&pts).ok()
            }
        };
        if let Some(h) = hull {
            self.platform = h
                .faces()
                .iter()
                .map(|f| f.iter().map(|&v| place(&h.vertices()[v])).collect())
                .collect();
        }
        self.platform_position = arr(&pose.position);
        self
    }

    /// The segments drawn for cable i: its catenary's polyline if [`Scene::cable_curves`] has
    /// one, else the chord.
    pub fn cable_segments(&self, i: usize) -> Vec<([f64; 3], [f64; 3])> {
        match self.cable_curves.get(i) {
            Some(c) if c.len() > 1 => c.windows(2).map(|w| (w[0], w[1])).collect(),
            _ => self.cables.get(i).copied().into_iter().collect(),
        }
    }

    /// Bounding box of everything shown (box, anchors, mesh).
    pub fn bounds(&self) -> ([f64; 3], [f64; 3]) {
        let (mut lo, mut hi) = self.region;
        for p in self.anchors.iter().chain(&self.vertices) {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        (lo, hi)
    }

    /// The segments where the plane x_axis = value cuts the mesh (a section of the workspace).
    pub fn section(&self, axis: usize, value: f64) -> Vec<([f64; 3], [f64; 3])> {
        let mut out = Vec::new();
        for t in &self.triangles {
            let p = t.map(|i| self.vertices[i as usize]);
            let mut cut = Vec::with_capacity(2);
            for k in 0..3 {
                let (a, b) = (p[k], p[(k + 1) % 3]);
                let (da, db) = (a[axis] - value, b[axis] - value);
                if (da < 0.0) != (db < 0.0) {
                    let s = da / (da - db);
                    cut.push([0, 1, 2].map(|j| a[j] + s * (b[j] - a[j])));
                }
            }
            if cut.len() == 2 {
                out.push((cut[0], cut[1]));
            }
        }
        out
    }
}

/// The surface of the grid verdicts' cells: each feasible grid point stands for the cell of
/// side Δ around it (clipped to the box), and every cell face between a feasible and an
/// infeasible (or outside) neighbour is drawn as two triangles, outward normals. A picture of
/// the grid verdicts — not a certified boundary (the boundary mesh is that).
pub fn grid_surface(ws: &GridWorkspace) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let g = &ws.grid;
    let p = g.points_per_axis();
    let m = g.resolution as f64;
    let (lo, ext) = (g.region.min, g.region.extent());
    // Lattice coordinates 2i ± 1 of the cell corners, clipped to [0, 2m].
    let coord = |k: usize, twice: i64| {
        let t = (twice.clamp(0, 2 * g.resolution as i64)) as f64 / 2.0;
        lo[k] + ext[k] * t / m
    };
    let mut index: HashMap<[i64; 3], u32> = HashMap::new();
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    let mut vertex = |c: [i64; 3], vertices: &mut Vec<[f64; 3]>| {
        *index.entry(c).or_insert_with(|| {
            vertices.push([coord(0, c[0]), coord(1, c[1]), coord(2, c[2])]);
            (vertices.len() - 1) as u32
        })
    };
    let feasible = |i: i64, j: i64, l: i64| {
        let r = 0..p as i64;
        r.contains(&i)
            && r.contains(&j)
            && r.contains(&l)
            && ws.feasible[(i + j * p as i64 + l * (p * p) as i64) as usize]
    };
    for idx in 0..ws.feasible.len() {
        if !ws.feasible[idx] {
            continue;
        }
        let ijk = [
            (idx % p) as i64,
            ((idx / p) % p) as i64,
            (idx / (p * p)) as i64,
        ];
        for axis in 0..3 {
            for dir in [-1i64, 1] {
                let mut n = ijk;
                n[axis] += dir;
                if feasible(n[0], n[1], n[2]) {
                    continue;
                }
                // The face's four corners, counter-clockwise seen from outside (along +dir).
                let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
                let corner = |a: i64, b: i64| {
                    let mut c = [2 * ijk[0], 2 * ijk[1], 2 * ijk[2]];
                    c[axis] += dir;
                    c[u] += a;
                    c[v] += b;
                    c
                };
                let mut q = [corner(-1, -1), corner(1, -1), corner(1, 1), corner(-1, 1)];
                if dir < 0 {
                    q.reverse();
                }
                let q = q.map(|c| vertex(c, &mut vertices));
                triangles.push([q[0], q[1], q[2]]);
                triangles.push([q[0], q[2], q[3]]);
            }
        }
    }
    (vertices, triangles)
}

/// A placed label: the point it names (pixels), the top-left corner of its text, the text.
pub type PlacedLabel = ((f64, f64), (f64, f64), String);

/// Label positions that do not overlap: each label (width `w`, height `h` pixels) goes to the
/// first of eight offsets around its point whose rectangle is free of the labels placed
/// before and that lies inside `area` (width, height in pixels) when one does; points that
/// project within 2 px of each other share one label (texts joined with "/"). Returns
/// (anchor pixel, top-left of the label, text).
pub fn place_labels(
    points: &[(f64, f64)],
    texts: &[String],
    char_width: f64,
    height: f64,
    area: (f64, f64),
) -> Vec<PlacedLabel> {
    let mut groups: Vec<((f64, f64), Vec<String>)> = Vec::new();
    for (p, t) in points.iter().zip(texts) {
        match groups
            .iter_mut()
            .find(|(q, _)| (q.0 - p.0).abs() <= 2.0 && (q.1 - p.1).abs() <= 2.0)
        {
            Some(g) => g.1.push(t.clone()),
            None => groups.push((*p, vec![t.clone()])),
        }
    }
    let mut placed: Vec<PlacedLabel> = Vec::new();
    let overlaps = |a: (f64, f64, f64, f64), b: (f64, f64, f64, f64)| {
        a.0 < b.0 + b.2 && b.0 < a.0 + a.2 && a.1 < b.1 + b.3 && b.1 < a.1 + a.3
    };
    for (p, ts) in groups {
        let text = ts.join("/");
        let w = char_width * text.chars().count() as f64;
        let gap = 6.0;
        let mut candidates = vec![
            (p.0 + gap, p.1 - height - gap),
            (p.0 + gap, p.1 + gap),
            (p.0 - w - gap, p.1 - height - gap),
            (p.0 - w - gap, p.1 + gap),
            (p.0 - w / 2.0, p.1 - height - 2.0 * gap),
            (p.0 - w / 2.0, p.1 + 2.0 * gap),
            (p.0 + 2.0 * gap, p.1 - height / 2.0),
            (p.0 - w - 2.0 * gap, p.1 - height / 2.0),
        ];
        // Farther rings if all eight are taken.
        for r in 1..6 {
            let d = r as f64 * (height + 2.0);
            candidates.push((p.0 + gap, p.1 - height - gap - d));
            candidates.push((p.0 + gap, p.1 + gap + d));
        }
        let free_of_others = |c: &(f64, f64)| {
            placed.iter().all(|(_, q, t)| {
                let wq = char_width * t.chars().count() as f64;
                !overlaps((c.0, c.1, w, height), (q.0, q.1, wq, height))
            })
        };
        let inside = |c: &(f64, f64)| {
            c.0 >= 0.0 && c.1 >= 0.0 && c.0 + w <= area.0 && c.1 + height <= area.1
        };
        let free = candidates
            .iter()
            .copied()
            .find(|c| free_of_others(c) && inside(c))
            .or_else(|| candidates.iter().copied().find(free_of_others))
            .unwrap_or(candidates[0]);
        placed.push((p, free, text));
    }
    placed
}

#[cfg(test)]
mod tests {
    use super::*;
    use cdpr_workspace::{Grid, Region};

    #[test]
    fn grid_surface_of_one_cell_is_a_closed_cube() {
        // 3 × 3 × 3 grid, only the centre feasible: a cube of side Δ = 1 around (1, 1, 1).
        let grid = Grid::new(2, Region::cuboid(Vector3::zeros(), Vector3::repeat(2.0)));
        let mut feasible = vec![false; 27];
        feasible[13] = true;
        let ws = GridWorkspace::from_verdicts(grid, 3, feasible);
        let (v, t) = grid_surface(&ws);
        assert_eq!((v.len(), t.len()), (8, 12));
        // Divergence theorem: volume 1, outward orientation.
        let vol: f64 = t
            .iter()
            .map(|f| {
                let [a, b, c] = f.map(|i| Vector3::from(v[i as usize]));
                a.dot(&b.cross(&c)) / 6.0
            })
            .sum();
        assert!((vol - 1.0).abs() < 1e-12, "{vol}");
        // Every directed edge appears once and its reverse once (watertight).
        let mut edges = std::collections::HashMap::new();
        for f in &t {
            for k in 0..3 {
                *edges.entry((f[k], f[(k + 1) % 3])).or_insert(0) += 1;
            }
        }
        for (&(a, b), &n) in &edges {
            assert_eq!(n, 1);
            assert_eq!(edges.get(&(b, a)), Some(&1));
        }
    }

    #[test]
    fn labels_never_overlap_and_coincident_points_share_one() {
        let pts = [
            (100.0, 100.0),
            (100.0, 100.0),
            (104.0, 101.0),
            (110.0, 98.0),
            (310.0, 5.0),
        ];
        let texts: Vec<String> = (1..=5).map(|k| format!("A{k}")).collect();
        let placed = place_labels(&pts, &texts, 8.0, 14.0, (320.0, 200.0));
        // The label of the point at the right edge is moved inside the area.
        let last = placed.last().unwrap();
        assert!(last.1.0 + 8.0 * 2.0 <= 320.0 && last.1.1 >= 0.0, "{last:?}");
        assert_eq!(placed.len(), 4);
        assert_eq!(placed[0].2, "A1/A2");
        for (i, a) in placed.iter().enumerate() {
            for b in &placed[i + 1..] {
                let (wa, wb) = (8.0 * a.2.len() as f64, 8.0 * b.2.len() as f64);
                let apart = a.1.0 + wa <= b.1.0
                    || b.1.0 + wb <= a.1.0
                    || a.1.1 + 14.0 <= b.1.1
                    || b.1.1 + 14.0 <= a.1.1;
                assert!(apart, "{a:?} {b:?}");
            }
        }
    }

    #[test]
    fn section_of_a_cube_surface_is_a_square() {
        let grid = Grid::new(2, Region::cuboid(Vector3::zeros(), Vector3::repeat(2.0)));
        let mut feasible = vec![false; 27];
        feasible[13] = true;
        let (vertices, triangles) = grid_surface(&GridWorkspace::from_verdicts(grid, 3, feasible));
        let scene = Scene {
            vertices,
            triangles,
            ..Scene::default()
        };
        let s = scene.section(2, 1.2);
        // Four sides, two triangles each: 8 segments of total length 4 (perimeter of the
        // unit square [0.5, 1.5]²).
        let len: f64 = s
            .iter()
            .map(|(a, b)| (Vector3::from(*a) - Vector3::from(*b)).norm())
            .sum();
        assert_eq!(s.len(), 8);
        assert!((len - 4.0).abs() < 1e-12);
    }
}
