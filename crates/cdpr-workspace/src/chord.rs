//! # Chord method (§6.4.3, Algorithm 6.3)
//!
//! Maps the boundary of a constant-orientation workspace of a robot moving in a plane as closed
//! polygons whose vertices lie on the boundary (to the tolerance ε^u) at chord length d from one
//! another:
//!
//! 1. **Interior point u⁰.** From a coarse discretisation (Algorithm 6.2), or by minimising
//!    eq. (6.25), Σ (t_i − t^mean)², or given by the user.
//! 2. **First boundary point b¹**, eq. (6.26): the largest r with u⁰ + r s¹ feasible, found by
//!    stepping along the ray s¹ and bisecting the last step.
//! 3. **Next points**, eq. (6.27) by the bisection of Algorithm 6.3: on the circle of radius d
//!    about b^i, the angle where the circle leaves the workspace is bracketed between a feasible
//!    and an infeasible direction (scanning in steps of π/8 from the previous chord's
//!    direction: clockwise if that is feasible, counter-clockwise if not) and halved until the
//!    bracket is shorter than ε^u; the feasible end is b^{i+1}. (The thesis starts its bracket
//!    from s^{1i} of eq. (C.13), in an appendix not part of the thesis chapter.) The walk keeps the
//!    workspace on its left: counter-clockwise around a region, clockwise around a hole.
//! 4. **Bifurcation points** (corners of the boundary, where two constraints meet): when the
//!    chord turns by more than `max_turn`, the last chord (which may have cut the corner with a
//!    small turn) is redone with half its length, and so on down to d / 2^`refinement_levels`.
//!    Points crowd into the corner, and the vertex where a turn sharper than `max_turn`
//!    remains at the finest chord is reported as a bifurcation point (within two finest chords
//!    of the corner). This local chord refinement plays the role of the thesis' special
//!    procedure (Appendix C, not part of the thesis chapter).
//! 5. **Gaps.** A chord must not jump a gap narrower than itself to another region (the
//!    3-cable robot's two regions at φ = 0 are only ~0.016 apart): the point a tenth of a chord
//!    to the left of each chord's midpoint must be feasible, else the chord is halved.
//! 6. **Closure.** The walk closes when it comes back within one chord of an earlier vertex at
//!    least 3d of walk behind, heading the same way (normally b¹ itself).
//! 7. **Every region.** Workspaces of tendon-driven robots can split (the 3-cable robot's at
//!    φ = 0 splits at x = 0, a singularity) or have holes. Every edge of the coarse grid that
//!    joins a feasible to an infeasible point crosses some boundary curve; edges not yet crossed
//!    by a mapped polygon seed a new walk (a walk retracing a mapped curve is discarded). Points
//!    outside the search region count as infeasible, so a workspace cut by the region is closed
//!    along the region's edges.
//!
//! The area is the sum of the polygons' signed (shoelace) areas: positive around regions,
//! negative around holes.
//!
//! Features much narrower than the chord d (a spike, a sliver region) are approximated coarsely
//! or, if the coarse grid misses them, not at all: choose d and the seed resolution below the
//! smallest feature of interest, as the thesis does (d = 0.03 and 0.02 for some cases).
//!
//! **Plane sections.** The same walk maps the section of a 3-D workspace by a plane x, y or
//! z = c ([`chord_section`]): points of the plane are embedded in space, nothing else changes.
//!
//! ## References
//! - Thesis §6.4.3: eqs. (6.25)–(6.27), Algorithm 6.3; §6.4.2 Algorithm 6.2 (seeding).
//! - Du Plessis & Snyman (2001), the chord method for parallel manipulator workspaces
//!   (thesis §5.4, Appendix C).

use crate::discretisation::{checked_orientation, map_grid};
use crate::{Criterion, Grid, PoseEvaluator, Region, WorkspaceError};
use cdpr_kinematics::Pose;
use nalgebra::{DVector, Rotation3, Vector2, Vector3};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_8, PI};

/// How the interior point u⁰ of the first walk is chosen (§6.4.3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum InteriorPoint {
    /// Only the coarse grid seeds the walks (one per boundary curve).
    CoarseGrid,
    /// Minimise eq. (6.25), Σ_i (t_i − t_i^mean)², t^mean = (t_min + t_max)/2, over u
    /// (Nelder–Mead from the region's centre). For n > DOF the tensions are the solution of
    /// W t + w_ext = 0 closest to t^mean, so the objective is ‖W⁺(W t^mean + w_ext)‖². Uses the
    /// first [`Criterion::TensionFeasible`]'s wrench. The thesis prints
    /// t^mean = (t^max − t^min)/2, which we read as a typo for the mid-range value.
    TensionCentering,
    /// A given interior point (x, y).
    Given([f64; 2]),
}

/// Settings of the chord method.
#[derive(Debug, Clone, PartialEq)]
pub struct ChordSettings {
    /// Chord length d (the thesis uses 0.05, and 0.03 or 0.02 near fine features).
    pub chord: f64,
    /// Bisection termination ε^u of Algorithm 6.3 (10⁻⁸).
    pub tolerance: f64,
    /// Resolution m of the coarse grid seeding the walks.
    pub seed_resolution: usize,
    /// Interior point of the first walk.
    pub interior: InteriorPoint,
    /// With a `Given` or `TensionCentering` interior point, also map every other boundary curve
    /// the coarse grid reveals.
    pub all_regions: bool,
    /// Turn (rad) between successive chords above which the chord is halved (bifurcation
    /// refinement).
    pub max_turn: f64,
    /// Halvings allowed near a bifurcation point: finest chord d / 2^levels.
    pub refinement_levels: u32,
    /// Give up a walk (with [`WorkspaceError::ChordDidNotClose`]) after this many points, or
    /// 64 times as many steps tried.
    pub max_points: usize,
}

impl Default for ChordSettings {
    fn default() -> Self {
        Self {
            chord: 0.05,
            tolerance: 1e-8,
            seed_resolution: 40,
            interior: InteriorPoint::CoarseGrid,
            all_regions: true,
            max_turn: 0.3,
            refinement_levels: 6,
            max_points: 200_000,
        }
    }
}

impl ChordSettings {
    /// Checks the ranges: d > 0, 0 < ε^u < d, m ≥ 1, 0 < max_turn < π/2.
    pub fn validate(&self) -> Result<(), WorkspaceError> {
        let bad = |what, value: f64, expected| {
            Err(WorkspaceError::InvalidSetting {
                what,
                value,
                expected,
            })
        };
        if !(self.chord.is_finite() && self.chord > 0.0) {
            return bad("chord length d", self.chord, "finite and > 0");
        }
        if !(self.tolerance > 0.0 && self.tolerance < self.chord * 1e-2) {
            return bad("tolerance ε^u", self.tolerance, "0 < ε^u < d/100");
        }
        if self.seed_resolution == 0 {
            return bad("seed resolution", 0.0, "≥ 1");
        }
        if !(self.max_turn > 0.0 && self.max_turn < FRAC_PI_2) {
            return bad("max turn", self.max_turn, "0 < max_turn < π/2");
        }
        if self.refinement_levels > 30 {
            return bad("refinement levels", self.refinement_levels as f64, "≤ 30");
        }
        if self.max_points < 3 {
            return bad("max points", self.max_points as f64, "≥ 3");
        }
        if let InteriorPoint::Given(p) = self.interior
            && let Some(&v) = p.iter().find(|v| !v.is_finite())
        {
            return Err(WorkspaceError::NotFinite {
                what: "interior point",
                value: v,
            });
        }
        Ok(())
    }
}

/// A closed polygon (the last vertex joins the first).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Polygon {
    /// Vertices b¹, b², … on the workspace boundary.
    pub vertices: Vec<[f64; 2]>,
    /// Indices of the vertices found to be bifurcation points (boundary corners).
    pub bifurcations: Vec<usize>,
}

impl Polygon {
    /// Shoelace signed area: positive counter-clockwise (a region), negative clockwise (a hole).
    pub fn signed_area(&self) -> f64 {
        let v = &self.vertices;
        let n = v.len();
        if n < 3 {
            return 0.0;
        }
        // Shifted to the first vertex to limit cancellation.
        let o = v[0];
        let mut s = 0.0;
        for k in 1..n - 1 {
            let (a, b) = (v[k], v[k + 1]);
            s += (a[0] - o[0]) * (b[1] - o[1]) - (b[0] - o[0]) * (a[1] - o[1]);
        }
        0.5 * s
    }

    /// Enclosed area (absolute shoelace area).
    pub fn area(&self) -> f64 {
        self.signed_area().abs()
    }

    /// Perimeter, closing edge included.
    pub fn perimeter(&self) -> f64 {
        self.edges().map(|(a, b)| (b - a).norm()).sum()
    }

    /// Whether `p` is inside (even–odd rule).
    pub fn contains(&self, p: [f64; 2]) -> bool {
        let mut inside = false;
        for (a, b) in self.edges() {
            if (a.y > p[1]) != (b.y > p[1]) {
                let x = a.x + (p[1] - a.y) / (b.y - a.y) * (b.x - a.x);
                if p[0] < x {
                    inside = !inside;
                }
            }
        }
        inside
    }

    /// Distance from `p` to the polygon's edges, and the length of the nearest edge.
    pub fn distance(&self, p: [f64; 2]) -> (f64, f64) {
        let p = Vector2::from(p);
        let mut best = (f64::INFINITY, 0.0);
        for (a, b) in self.edges() {
            let ab = b - a;
            let len2 = ab.norm_squared();
            let s = if len2 > 0.0 {
                ((p - a).dot(&ab) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let d = (a + ab * s - p).norm();
            if d < best.0 {
                best = (d, len2.sqrt());
            }
        }
        best
    }

    /// Unit normal at vertex `k` to the right of the walking direction, from its two
    /// neighbours: out of the workspace for every curve the chord method walks (counter-clockwise
    /// regions and clockwise holes alike).
    pub fn outward_normal(&self, k: usize) -> [f64; 2] {
        let n = self.vertices.len();
        let a = Vector2::from(self.vertices[(k + n - 1) % n]);
        let b = Vector2::from(self.vertices[(k + 1) % n]);
        let t = (b - a).normalize();
        [t.y, -t.x]
    }

    fn edges(&self) -> impl Iterator<Item = (Vector2<f64>, Vector2<f64>)> + '_ {
        let n = self.vertices.len();
        (0..n).map(move |k| {
            (
                Vector2::from(self.vertices[k]),
                Vector2::from(self.vertices[(k + 1) % n]),
            )
        })
    }
}

/// The result of the chord method.
#[derive(Debug, Clone, PartialEq)]
pub struct ChordWorkspace {
    /// Orientation φ of the platform (rad).
    pub phi: f64,
    /// Closed boundary curves: counter-clockwise around regions, clockwise around holes.
    pub boundaries: Vec<Polygon>,
    /// Workspace area: the sum of the boundaries' signed areas.
    pub area: f64,
    /// Walks abandoned (the boundary could not be followed even at the finest chord); their
    /// curves are missing from `boundaries`.
    pub abandoned: usize,
    /// Number of pose evaluations, coarse grid included.
    pub evaluations: usize,
}

impl ChordWorkspace {
    /// Whether `p` lies in the mapped workspace (even–odd over all boundaries).
    pub fn contains(&self, p: [f64; 2]) -> bool {
        self.boundaries.iter().filter(|b| b.contains(p)).count() % 2 == 1
    }
}

/// The chord method, §6.4.3: boundary polygons of the constant-orientation workspace at
/// orientation `phi` (ignored for `point2` robots) within `region`.
///
/// ```
/// use cdpr_kinematics::{Cable, MotionPattern, Robot};
/// use cdpr_workspace::{chord_workspace, ChordSettings, Criterion, PoseEvaluator, Region};
/// use cdpr_tension::TensionBounds;
/// use nalgebra::Vector3;
/// let c = |x: f64, y: f64| Cable { frame: Vector3::new(x, y, 0.0), platform: Vector3::zeros(), pulley: None };
/// let robot = Robot::new(MotionPattern::Point2, vec![c(1.0, 1.0), c(-1.0, 1.0), c(0.0, -1.0)]).unwrap();
/// let eval = PoseEvaluator::new(robot, TensionBounds::uniform(3, 0.0, 1.0).unwrap(),
///                               vec![Criterion::WrenchClosure]).unwrap();
/// let ws = chord_workspace(&eval, 0.0, &Region::planar(-1.0, 1.0, -1.0, 1.0),
///                          &ChordSettings::default()).unwrap();
/// // The anchors' triangle, area 2, with its three corners as bifurcation points.
/// assert_eq!(ws.boundaries.len(), 1);
/// assert!((ws.area - 2.0).abs() < 1e-3);
/// ```
pub fn chord_workspace(
    eval: &PoseEvaluator,
    phi: f64,
    region: &Region,
    settings: &ChordSettings,
) -> Result<ChordWorkspace, WorkspaceError> {
    let motion = eval.robot().motion();
    if motion.space_dim() != 2 {
        return Err(WorkspaceError::NotPlanar {
            method: "the chord method",
            motion: motion.name(),
        });
    }
    if !phi.is_finite() {
        return Err(WorkspaceError::NotFinite {
            what: "orientation φ",
            value: phi,
        });
    }
    region.validate(2)?;
    settings.validate()?;
    eval.validate()?;
    let rotation =
        checked_orientation(motion, &Rotation3::from_axis_angle(&Vector3::z_axis(), phi))?;
    chord_in_plane(eval, rotation, Section::PLANE_Z0, region, settings, phi)
}

/// The plane section `section` of the constant-orientation workspace of a robot moving in space
/// (`point3`, `spatial`) at `orientation`, by the chord method within the box `region`: closed
/// polygons in the plane's coordinates ([`Section::in_plane_axes`]), every vertex on the
/// boundary of the section to ε^u. The 2-D analogue of [`crate::boundary_mesh()`], and an exact
/// check of its slices. `phi` of the result is 0.
///
/// ```
/// use cdpr_kinematics::{Cable, MotionPattern, Robot};
/// use cdpr_tension::TensionBounds;
/// use cdpr_workspace::{chord_section, ChordSettings, Criterion, PoseEvaluator, Region, Section};
/// use nalgebra::{Rotation3, Vector3};
/// let c = |x: f64, y: f64, z: f64| Cable { frame: Vector3::new(x, y, z), platform: Vector3::zeros(), pulley: None };
/// // Wrench closure of a point with four cables: the tetrahedron of the anchors.
/// let robot = Robot::new(MotionPattern::Point3, vec![
///     c(1.0, 1.0, 1.0), c(1.0, -1.0, -1.0), c(-1.0, 1.0, -1.0), c(-1.0, -1.0, 1.0),
/// ]).unwrap();
/// let eval = PoseEvaluator::new(robot, TensionBounds::uniform(4, 0.0, 1.0).unwrap(),
///                               vec![Criterion::WrenchClosure]).unwrap();
/// let region = Region::cuboid(Vector3::repeat(-1.0), Vector3::repeat(1.0));
/// let ws = chord_section(&eval, &Rotation3::identity(), Section { axis: 2, value: 0.0 },
///                        &region, &ChordSettings::default()).unwrap();
/// // At z = 0 the tetrahedron's section is the square |x| + |y| < 1 rotated by 45°: area 2.
/// assert!((ws.area - 2.0).abs() < 1e-3);
/// ```
pub fn chord_section(
    eval: &PoseEvaluator,
    orientation: &Rotation3<f64>,
    section: Section,
    region: &Region,
    settings: &ChordSettings,
) -> Result<ChordWorkspace, WorkspaceError> {
    let motion = eval.robot().motion();
    if motion.space_dim() != 3 {
        return Err(WorkspaceError::NotSpatial {
            method: "a plane section",
            motion: motion.name(),
        });
    }
    region.validate(3)?;
    section.validate(region)?;
    settings.validate()?;
    eval.validate()?;
    let rotation = checked_orientation(motion, orientation)?;
    let plane_region = section.plane_region(region);
    chord_in_plane(eval, rotation, section, &plane_region, settings, 0.0)
}

/// A plane section `axis = value` of a 3-D box; in-plane coordinates (a, b) are the other two
/// axes in order: (y, z) for x = c, (x, z) for y = c, (x, y) for z = c.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    /// Axis normal to the plane (0 = x, 1 = y, 2 = z).
    pub axis: usize,
    /// Coordinate of the plane along that axis (m).
    pub value: f64,
}

impl Section {
    /// The plane z = 0 of robots moving in a plane.
    pub const PLANE_Z0: Section = Section {
        axis: 2,
        value: 0.0,
    };

    /// The two in-plane axes, in order.
    pub fn in_plane_axes(&self) -> [usize; 2] {
        match self.axis {
            0 => [1, 2],
            1 => [0, 2],
            _ => [0, 1],
        }
    }

    /// The point of in-plane coordinates `u` in space.
    #[inline]
    pub fn embed(&self, u: Vector2<f64>) -> Vector3<f64> {
        let [a, b] = self.in_plane_axes();
        let mut p = Vector3::zeros();
        p[a] = u.x;
        p[b] = u.y;
        p[self.axis.min(2)] = self.value;
        p
    }

    /// The box's face in the plane, in in-plane coordinates (a planar [`Region`]).
    pub fn plane_region(&self, region: &Region) -> Region {
        let [a, b] = self.in_plane_axes();
        Region::planar(region.min[a], region.max[a], region.min[b], region.max[b])
    }

    /// Checks axis < 3 and a finite value within the box along the axis.
    pub fn validate(&self, region: &Region) -> Result<(), WorkspaceError> {
        if self.axis > 2 {
            return Err(WorkspaceError::InvalidSetting {
                what: "section axis",
                value: self.axis as f64,
                expected: "0 (x), 1 (y) or 2 (z)",
            });
        }
        if !self.value.is_finite() {
            return Err(WorkspaceError::NotFinite {
                what: "section coordinate",
                value: self.value,
            });
        }
        let (lo, hi) = (region.min[self.axis], region.max[self.axis]);
        if !(lo..=hi).contains(&self.value) {
            return Err(WorkspaceError::InvalidSetting {
                what: "section coordinate",
                value: self.value,
                expected: "within the search box along the section's axis",
            });
        }
        Ok(())
    }
}

/// The chord method in the plane `plane`, within `region` (in-plane coordinates).
fn chord_in_plane(
    eval: &PoseEvaluator,
    rotation: Rotation3<f64>,
    plane: Section,
    region: &Region,
    settings: &ChordSettings,
    phi: f64,
) -> Result<ChordWorkspace, WorkspaceError> {
    let mut walker = Walker {
        eval: eval.clone(),
        region: *region,
        plane,
        rotation,
        settings,
        evaluations: 0,
    };
    let mut boundaries: Vec<Polygon> = Vec::new();
    let mut abandoned = 0;

    let interior = match settings.interior {
        InteriorPoint::CoarseGrid => None,
        InteriorPoint::Given(p) => Some(Vector2::from(p)),
        InteriorPoint::TensionCentering => tension_centering(eval, region, plane, rotation)?,
    };
    if let Some(u0) = interior.filter(|&u| walker.inside(u)) {
        // Eq. (6.26) along s¹ = +x.
        let s1 = Vector2::x();
        let h = 0.5 * settings.chord;
        let mut r = 0.0;
        let limit = (region.max.x - region.min.x) / h + 2.0;
        let mut k = 0.0;
        while walker.inside(u0 + s1 * (r + h)) && k < limit {
            r += h;
            k += 1.0;
        }
        let b1 = walker.bisect_segment(u0 + s1 * r, u0 + s1 * (r + h));
        match walker.walk(b1, s1)? {
            Some(p) => boundaries.push(p),
            None => abandoned += 1,
        }
    }

    if interior.is_none() || settings.all_regions {
        let m = settings.seed_resolution;
        let grid = Grid::new(m, *region);
        let coarse = map_grid(eval, &grid, 2, |ev, u| {
            ev.is_feasible_finite_rotation(&Pose::new(plane.embed(u.xy()), rotation))
        });
        walker.evaluations += coarse.len();
        let p = m + 1;
        let at = |i: usize, j: usize| grid.point(2, j * p + i).xy();
        let h = Vector2::new(
            (region.max.x - region.min.x) / m as f64,
            (region.max.y - region.min.y) / m as f64,
        );
        for j in 0..p {
            for i in 0..p {
                if !coarse[j * p + i] {
                    continue;
                }
                let a = at(i, j);
                // Right, up, left, down: neighbours off the grid are outside the region.
                let neighbours = [
                    (i + 1 < p).then(|| (coarse[j * p + i + 1], at(i + 1, j))),
                    (j + 1 < p).then(|| (coarse[(j + 1) * p + i], at(i, j + 1))),
                    (i > 0).then(|| (coarse[j * p + i - 1], at(i - 1, j))),
                    (j > 0).then(|| (coarse[(j - 1) * p + i], at(i, j - 1))),
                ];
                let off = [
                    Vector2::new(h.x, 0.0),
                    Vector2::new(0.0, h.y),
                    Vector2::new(-h.x, 0.0),
                    Vector2::new(0.0, -h.y),
                ];
                for (nb, o) in neighbours.into_iter().zip(off) {
                    let q = match nb {
                        Some((true, _)) => continue,
                        Some((false, q)) => q,
                        None => a + o,
                    };
                    let (pa, pq) = ([a.x, a.y], [q.x, q.y]);
                    if boundaries.iter().any(|b| b.contains(pa) != b.contains(pq)) {
                        continue; // this crossing is on a mapped curve
                    }
                    let b1 = walker.bisect_segment(a, q);
                    let near = boundaries.iter().any(|b| {
                        let (dist, edge) = b.distance([b1.x, b1.y]);
                        dist <= 0.1 * edge + 10.0 * settings.tolerance
                    });
                    if near {
                        continue;
                    }
                    match walker.walk(b1, (q - a).normalize())? {
                        Some(p) if !duplicates(&p, &boundaries, settings.chord) => {
                            boundaries.push(p)
                        }
                        Some(_) => {}
                        None => abandoned += 1,
                    }
                }
            }
        }
    }
    let area = boundaries.iter().map(Polygon::signed_area).sum();
    Ok(ChordWorkspace {
        phi,
        boundaries,
        area,
        abandoned,
        evaluations: walker.evaluations,
    })
}

/// Whether `new` retraces a curve already in `mapped`: at least half of its vertices lie within
/// d/10 of one mapped polygon. (A seed near a mapped curve can escape the quick tests above where
/// the polygon cuts a tight bend; distinct curves share so much length only if they are closer
/// than d/10 over it, below the chord's resolution.)
fn duplicates(new: &Polygon, mapped: &[Polygon], chord: f64) -> bool {
    mapped.iter().any(|old| {
        let close = new
            .vertices
            .iter()
            .filter(|&&v| old.distance(v).0 <= 0.1 * chord)
            .count();
        2 * close >= new.vertices.len()
    })
}

/// Outcome of one chord step.
enum Step {
    /// The next boundary point and the chord's direction angle.
    Found(Vector2<f64>, f64),
    /// The chord would turn by more than `max_turn` (not bisected).
    Sharp,
    /// The circle does not leave (or enter) the workspace as expected.
    Lost,
}

/// Walks boundaries with one evaluator.
struct Walker<'s> {
    eval: PoseEvaluator,
    /// The search box in the plane's coordinates.
    region: Region,
    /// The plane walked (z = 0 for robots moving in a plane).
    plane: Section,
    rotation: Rotation3<f64>,
    settings: &'s ChordSettings,
    evaluations: usize,
}

impl Walker<'_> {
    /// In the region and feasible.
    fn inside(&mut self, u: Vector2<f64>) -> bool {
        if !self.region.contains(&Vector3::new(u.x, u.y, 0.0), 2) {
            return false;
        }
        self.evaluations += 1;
        self.eval
            .is_feasible_finite_rotation(&Pose::new(self.plane.embed(u), self.rotation))
    }

    /// Bisection on the segment from feasible `a` to infeasible `b`: the feasible end once
    /// ‖a − b‖ ≤ ε^u (problem (6.26) along a ray, solved by bisection with the stopping rule of
    /// Algorithm 6.3).
    fn bisect_segment(&mut self, mut a: Vector2<f64>, mut b: Vector2<f64>) -> Vector2<f64> {
        while (b - a).norm() > self.settings.tolerance {
            let m = (a + b) * 0.5;
            if self.inside(m) {
                a = m;
            } else {
                b = m;
            }
        }
        a
    }

    /// Eq. (6.27) by Algorithm 6.3: the next boundary point on the circle of radius `c` about
    /// `b`, walking with the workspace on the left, starting the search from the direction
    /// `forward` (angle). `None` if the circle does not cross the boundary as expected.
    fn step(&mut self, b: Vector2<f64>, forward: f64, c: f64, sharp_from: Option<f64>) -> Step {
        let at = |theta: f64| b + Vector2::new(theta.cos(), theta.sin()) * c;
        // Exponential scan from `forward` (steps π/64, π/32, … capped at π/8, at most π in all):
        // a good prediction brackets the crossing in one or two evaluations, in a narrow
        // bracket. β: feasible angle, α: infeasible angle.
        let start_inside = self.inside(at(forward));
        // Clockwise (towards the outside) from a feasible start, else counter-clockwise.
        let sense = if start_inside { -1.0 } else { 1.0 };
        let (mut prev, mut turned, mut delta) = (forward, 0.0, FRAC_PI_8 / 8.0);
        let (mut beta, mut alpha) = loop {
            if turned >= PI {
                return Step::Lost;
            }
            let theta = prev + sense * delta;
            if self.inside(at(theta)) != start_inside {
                break if start_inside {
                    (prev, theta)
                } else {
                    (theta, prev)
                };
            }
            prev = theta;
            turned += delta;
            delta = (2.0 * delta).min(FRAC_PI_8);
        };
        // A turn sharper than max_turn over the whole bracket (measured from the heading
        // `sharp_from`) will be refined by the caller: skip the bisection.
        if let Some(h) = sharp_from {
            let (t1, t2) = (wrap(alpha - h), wrap(beta - h));
            let limit = self.settings.max_turn;
            if t1.abs() > limit && t2.abs() > limit && t1.signum() == t2.signum() {
                return Step::Sharp;
            }
        }
        // Algorithm 6.3 steps 2–5: γ halves the angle between α and β.
        while c * (alpha - beta).abs() > self.settings.tolerance {
            let gamma = 0.5 * (alpha + beta);
            if self.inside(at(gamma)) {
                beta = gamma;
            } else {
                alpha = gamma;
            }
        }
        Step::Found(at(beta), beta)
    }

    /// Maps one boundary curve from its point `b1`, where `outward` points out of the workspace.
    fn walk(
        &mut self,
        b1: Vector2<f64>,
        outward: Vector2<f64>,
    ) -> Result<Option<Polygon>, WorkspaceError> {
        let s = self.settings;
        let d = s.chord;
        let c_min = d / f64::powi(2.0, s.refinement_levels as i32);
        let sharp = |turn: f64| turn.abs() > s.max_turn;
        // Workspace on the left: forward = outward turned by +90°. A first step of the finest
        // chord gives the tangent at b¹, so that the first real step is refined like the others.
        let guess = outward.y.atan2(outward.x) + FRAC_PI_2;
        let Step::Found(_, mut heading) = self.step(b1, guess, c_min, None) else {
            return Ok(None);
        };
        let mut pts = vec![b1];
        let mut arc = vec![0.0];
        let mut headings = vec![heading];
        let (mut last_turn, mut last_chord) = (0.0, d);
        // Every loop pass either adds a point or refines the chord; bound them all the same.
        let mut attempts = 0usize;
        let mut bifurcations = Vec::new();
        let mut c = d;
        loop {
            let b = *pts.last().expect("the walk starts with b¹");
            let here = *arc.last().expect("one arc length per point");
            attempts += 1;
            if pts.len() > s.max_points || attempts > 64 * s.max_points {
                return Err(WorkspaceError::ChordDidNotClose { points: pts.len() });
            }
            // Closure: back within one chord of an earlier point, at least 3d of walk ago,
            // heading the same way (not the far side of a thin strip).
            let close_to = (0..pts.len().saturating_sub(2)).find(|&k| {
                here - arc[k] > 3.0 * d
                    && (pts[k] - b).norm() <= c
                    && (pts[k + 1] - pts[k]).dot(&Vector2::new(heading.cos(), heading.sin())) > 0.0
            });
            if let Some(k) = close_to {
                let to = pts[k] - b;
                let turn = wrap(to.y.atan2(to.x) - heading);
                let n = pts.len();
                let prev_chord = if n > 1 { arc[n - 1] - arc[n - 2] } else { 0.0 };
                if sharp(turn) && prev_chord > c_min * (1.0 + 1e-9) && n - 1 > k + 1 {
                    // As for a step: the corner may lie on the last chord.
                    pts.pop();
                    arc.pop();
                    headings.pop();
                    bifurcations.retain(|&i| i < n - 1);
                    heading = *headings.last().expect("b¹ is never removed");
                    c = 0.5 * prev_chord;
                    last_turn = 0.0;
                } else if sharp(turn) && c > c_min * (1.0 + 1e-9) && to.norm() > c_min {
                    c *= 0.5; // a corner before the closing point: walk on with finer chords
                } else {
                    if sharp(turn) {
                        bifurcations.push(pts.len() - 1);
                    }
                    let next = pts[k + 1] - pts[k];
                    if sharp(wrap(next.y.atan2(next.x) - to.y.atan2(to.x))) {
                        bifurcations.push(k);
                    }
                    // Drop a lead-in not on the closed curve (k > 0 only after a jump).
                    let vertices: Vec<[f64; 2]> = pts[k..].iter().map(|p| [p.x, p.y]).collect();
                    let mut bif: Vec<usize> = bifurcations
                        .into_iter()
                        .filter(|&i| i >= k)
                        .map(|i| i - k)
                        .collect();
                    bif.sort_unstable();
                    bif.dedup();
                    let bif = merge_close(&vertices, bif, 2.5 * c_min);
                    return Ok(Some(Polygon {
                        vertices,
                        bifurcations: bif,
                    }));
                }
            }
            let refinable = c > c_min * (1.0 + 1e-9);
            // Predict the next direction from the last turn (same curvature), for a quick bracket.
            let predicted = heading + (last_turn * c / last_chord).clamp(-s.max_turn, s.max_turn);
            // When the chord can still be refined, a sharp step need not be bisected.
            let can_refine = refinable
                || (pts.len() > 1 && {
                    let n = pts.len();
                    arc[n - 1] - arc[n - 2] > c_min * (1.0 + 1e-9)
                });
            let (next, theta) = match self.step(b, predicted, c, can_refine.then_some(heading)) {
                Step::Found(next, theta) => (next, theta),
                Step::Sharp => {
                    // Same handling as a sharp found step below, with the bracket's angle.
                    (b, heading + PI)
                }
                Step::Lost => {
                    if refinable {
                        c *= 0.5;
                        continue;
                    }
                    return Ok(None);
                }
            };
            let turn = wrap(theta - heading);
            if sharp(turn) && pts.len() > 1 {
                let n = pts.len();
                let prev_chord = arc[n - 1] - arc[n - 2];
                if prev_chord > c_min * (1.0 + 1e-9) {
                    // The corner may lie on the last chord (cut with a small turn): redo it
                    // with half that chord.
                    pts.pop();
                    arc.pop();
                    headings.pop();
                    bifurcations.retain(|&i| i < n - 1);
                    heading = *headings.last().expect("b¹ is never removed");
                    c = 0.5 * prev_chord;
                    last_turn = 0.0;
                    continue;
                }
            }
            if refinable && (sharp(turn) || !self.bridges(b, next)) {
                c *= 0.5;
                continue;
            }
            if sharp(turn) {
                bifurcations.push(pts.len() - 1);
            }
            pts.push(next);
            arc.push(here + c);
            headings.push(theta);
            heading = theta;
            (last_turn, last_chord) = (if sharp(turn) { 0.0 } else { turn }, c);
            if turn.abs() <= 0.5 * s.max_turn {
                c = (2.0 * c).min(d);
            }
        }
    }

    /// Whether the chord from `b` to `next` stays in one piece of the workspace: the point a
    /// tenth of a chord to the left of its midpoint (the inside) is feasible. A chord that jumps
    /// a gap narrower than itself to another region fails this (the midpoint is in the gap).
    fn bridges(&mut self, b: Vector2<f64>, next: Vector2<f64>) -> bool {
        let t = next - b;
        let left = Vector2::new(-t.y, t.x);
        self.inside((b + next) * 0.5 + left * 0.1)
    }
}

/// Keeps one bifurcation per corner: drops indices whose vertex is within `radius` of the
/// previously kept one (cyclically).
fn merge_close(vertices: &[[f64; 2]], sorted: Vec<usize>, radius: f64) -> Vec<usize> {
    let dist = |a: usize, b: usize| {
        let (p, q) = (vertices[a], vertices[b]);
        (p[0] - q[0]).hypot(p[1] - q[1])
    };
    let mut kept: Vec<usize> = Vec::with_capacity(sorted.len());
    for i in sorted {
        if kept.last().is_none_or(|&k| dist(k, i) > radius) {
            kept.push(i);
        }
    }
    if kept.len() > 1 && dist(kept[0], kept[kept.len() - 1]) <= radius {
        kept.pop();
    }
    kept
}

/// Angle wrapped to (−π, π].
fn wrap(a: f64) -> f64 {
    let t = a.rem_euclid(2.0 * PI);
    if t > PI { t - 2.0 * PI } else { t }
}

/// Eq. (6.25), generalised to n ≥ DOF: min over u of ‖W⁺(W t^mean + w_ext)‖², the squared
/// distance from t^mean to the tensions balancing w_ext. Nelder–Mead from the region centre;
/// `None` if there is no tension criterion, an infinite t_max, or no feasible minimiser.
fn tension_centering(
    eval: &PoseEvaluator,
    region: &Region,
    plane: Section,
    rotation: Rotation3<f64>,
) -> Result<Option<Vector2<f64>>, WorkspaceError> {
    let Some(wrench) = eval.criteria().iter().find_map(|c| match c {
        Criterion::TensionFeasible { wrench, .. } => Some(wrench.clone()),
        _ => None,
    }) else {
        return Ok(None);
    };
    let b = eval.bounds();
    if b.max().iter().any(|v| !v.is_finite()) {
        return Ok(None);
    }
    let t_mean: DVector<f64> = (b.min() + b.max()) * 0.5;
    let robot = eval.robot().clone();
    let objective = |u: Vector2<f64>| -> f64 {
        if !region.contains(&Vector3::new(u.x, u.y, 0.0), 2) {
            return f64::INFINITY;
        }
        let Ok(kin) = robot.inverse_kinematics(&Pose::new(plane.embed(u), rotation)) else {
            return f64::INFINITY;
        };
        let w = kin.wrench_matrix();
        let rhs = &w * &t_mean + &wrench;
        match (&w * w.transpose()).cholesky() {
            Some(ch) => {
                let y = ch.solve(&rhs);
                (w.transpose() * y).norm_squared()
            }
            None => f64::INFINITY,
        }
    };
    let centre = Vector2::new(
        0.5 * (region.min.x + region.max.x),
        0.5 * (region.min.y + region.max.y),
    );
    let size = 0.1 * (region.max.x - region.min.x).min(region.max.y - region.min.y);
    let u = nelder_mead(objective, centre, size, 400);
    let mut ev = eval.clone();
    let pose = Pose::new(plane.embed(u), rotation);
    Ok((region.contains(&Vector3::new(u.x, u.y, 0.0), 2) && ev.check(&pose)?).then_some(u))
}

/// Nelder–Mead simplex minimisation in the plane (standard coefficients 1, 2, ½, ½).
fn nelder_mead(
    f: impl Fn(Vector2<f64>) -> f64,
    x0: Vector2<f64>,
    size: f64,
    iterations: usize,
) -> Vector2<f64> {
    let mut s = [
        x0,
        x0 + Vector2::new(size, 0.0),
        x0 + Vector2::new(0.0, size),
    ];
    let mut v = s.map(&f);
    for _ in 0..iterations {
        let mut idx = [0, 1, 2];
        idx.sort_by(|&a, &b| v[a].total_cmp(&v[b]));
        let (best, mid, worst) = (idx[0], idx[1], idx[2]);
        if (s[worst] - s[best]).norm() < 1e-10 {
            break;
        }
        let centroid = (s[best] + s[mid]) * 0.5;
        let xr = centroid + (centroid - s[worst]);
        let fr = f(xr);
        if fr < v[best] {
            let xe = centroid + (xr - centroid) * 2.0;
            let fe = f(xe);
            if fe < fr {
                (s[worst], v[worst]) = (xe, fe);
            } else {
                (s[worst], v[worst]) = (xr, fr);
            }
        } else if fr < v[mid] {
            (s[worst], v[worst]) = (xr, fr);
        } else {
            let xc = centroid + (s[worst] - centroid) * 0.5;
            let fc = f(xc);
            if fc < v[worst] {
                (s[worst], v[worst]) = (xc, fc);
            } else {
                for k in [mid, worst] {
                    s[k] = s[best] + (s[k] - s[best]) * 0.5;
                    v[k] = f(s[k]);
                }
            }
        }
    }
    let mut best = 0;
    for k in 1..3 {
        if v[k] < v[best] {
            best = k;
        }
    }
    s[best]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Polygon {
        Polygon {
            vertices: vec![[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]],
            bifurcations: vec![],
        }
    }

    #[test]
    fn shoelace_orientation_and_containment() {
        let mut p = square();
        assert!((p.signed_area() - 2.0).abs() < 1e-15);
        assert!((p.perimeter() - 6.0).abs() < 1e-15);
        assert!(p.contains([1.0, 0.5]));
        assert!(!p.contains([2.5, 0.5]));
        assert_eq!(p.distance([1.0, 2.0]).0, 1.0);
        // Neighbours of (2, 0) are (0, 0) and (2, 1): tangent (2, 1)/√5, right normal (1, −2)/√5.
        let n = p.outward_normal(1);
        let r5 = 5f64.sqrt();
        assert!((n[0] - 1.0 / r5).abs() < 1e-15 && (n[1] + 2.0 / r5).abs() < 1e-15);
        p.vertices.reverse();
        assert!((p.signed_area() + 2.0).abs() < 1e-15);
    }

    #[test]
    fn nelder_mead_finds_a_quadratic_minimum() {
        let f = |u: Vector2<f64>| (u.x - 0.3).powi(2) + 4.0 * (u.y + 0.2).powi(2);
        let u = nelder_mead(f, Vector2::zeros(), 0.1, 500);
        assert!((u - Vector2::new(0.3, -0.2)).norm() < 1e-6);
    }

    #[test]
    fn settings_are_validated() {
        assert!(ChordSettings::default().validate().is_ok());
        let bad = ChordSettings {
            chord: -1.0,
            ..Default::default()
        };
        assert!(bad.validate().is_err());
        let bad = ChordSettings {
            tolerance: 0.1,
            ..Default::default()
        };
        assert!(bad.validate().is_err());
        let bad = ChordSettings {
            interior: InteriorPoint::Given([f64::NAN, 0.0]),
            ..Default::default()
        };
        assert!(bad.validate().is_err());
    }

    #[test]
    fn wrap_is_into_minus_pi_pi() {
        assert!((wrap(3.0 * PI / 2.0) + PI / 2.0).abs() < 1e-15);
        assert!((wrap(-3.0 * PI / 2.0) - PI / 2.0).abs() < 1e-15);
        assert_eq!(wrap(0.25), 0.25);
    }
}
