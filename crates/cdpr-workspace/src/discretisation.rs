//! # Discretisation method (Algorithm 6.2)
//!
//! The constant-orientation workspace on a regular grid: (m+1)² points
//! u^ij = [x_min + (i/m)(x_max − x_min), y_min + (j/m)(y_max − y_min)] (Algorithm 6.2 step 3),
//! each tested against the criteria (step 4). Robots moving in space (`point3`, `spatial`) use
//! the 3-D grid of (m+1)³ points. Two estimates of the area (volume) are given
//! ([`VolumeConvention`]):
//!
//! - **points** (the thesis' convention, [`GridWorkspace::area`]): the number of feasible points
//!   times the cell area (Δx/m)(Δy/m) (times Δz/m). The published areas of Tables 6.5–6.10 are
//!   multiples of the cell area, so this is the estimate that reproduces them; but (m+1)² points
//!   of (Δx/m)(Δy/m) cover (1 + 1/m)² times the box, so a fully feasible box reports more than
//!   its own area.
//! - **cells** ([`GridWorkspace::clipped_area`]): each point stands for the cell of side Δx/m
//!   centred on it, clipped to the box: a point on a face of the box counts ½ along that axis,
//!   on an edge ¼, at a corner of a square ¼ (of a cube ⅛). The weights sum to m² (m³), so the
//!   estimate never exceeds the box and equals it when every point is feasible (the trapezoid
//!   rule on the indicator function).
//!
//! Points are evaluated in parallel with rayon, in contiguous tasks, with one [`PoseEvaluator`]
//! clone per thread; each point's verdict depends on that point only, so the result is the same
//! whatever the number of threads. Constant-orientation grids pass each task's points to
//! [`PoseEvaluator::feasible_batch`] 64 at a time (the batch inverse kinematics when the
//! criteria need W only; the same verdicts as point by point).
//!
//! ## References
//! - Thesis §6.4.2, Algorithm 6.2.

use crate::evaluator::BATCH;
use crate::{PoseEvaluator, Region, WorkspaceError};
use cdpr_kinematics::{MotionPattern, Pose};
use nalgebra::{Rotation3, Vector3};
use std::sync::Mutex;

/// Smallest number of grid points a rayon task handles (amortises rayon's per-task cost).
const MIN_POINTS_PER_TASK: usize = 64;

/// A regular grid of resolution m over a box (Algorithm 6.2 steps 1–3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    /// m: the number of intervals per axis, giving (m+1)² points (or (m+1)³ in 3-D).
    pub resolution: usize,
    /// The box discretised.
    pub region: Region,
}

impl Grid {
    /// A grid of resolution `m` over `region`.
    pub fn new(resolution: usize, region: Region) -> Self {
        Self { resolution, region }
    }

    /// Algorithm 6.2 as stated: resolution `m` over the bounding box of the frame anchors.
    pub fn over_frame(robot: &cdpr_kinematics::Robot, resolution: usize) -> Self {
        Self::new(resolution, Region::frame_bounding_box(robot))
    }

    /// Checks m ≥ 1 and the box along the first `dim` axes.
    pub fn validate(&self, dim: usize) -> Result<(), WorkspaceError> {
        if self.resolution == 0 {
            return Err(WorkspaceError::InvalidSetting {
                what: "grid resolution m",
                value: 0.0,
                expected: "m ≥ 1",
            });
        }
        self.region.validate(dim)
    }

    /// Points per axis, m + 1.
    pub fn points_per_axis(&self) -> usize {
        self.resolution + 1
    }

    /// Number of points in `dim` dimensions, (m+1)^dim.
    pub fn point_count(&self, dim: usize) -> usize {
        self.points_per_axis().pow(dim as u32)
    }

    /// The point of flat index `idx` (x fastest, then y, then z), Algorithm 6.2 step 3.
    #[inline]
    pub fn point(&self, dim: usize, idx: usize) -> Vector3<f64> {
        let p = self.points_per_axis();
        // Axes beyond `dim` are 0 (a planar robot moves in z = 0 whatever the region's z).
        let mut q = Vector3::zeros();
        let mut rest = idx;
        for k in 0..dim {
            q[k] = self.coordinate(k, rest % p);
            rest /= p;
        }
        q
    }

    /// Coordinate i along axis k: x_min + (i/m)(x_max − x_min) (Algorithm 6.2 step 3), written
    /// so that i = m lands exactly on x_max.
    #[inline]
    fn coordinate(&self, k: usize, i: usize) -> f64 {
        if i == self.resolution {
            self.region.max[k]
        } else {
            let m = self.resolution as f64;
            self.region.min[k] + (i as f64 / m) * (self.region.max[k] - self.region.min[k])
        }
    }

    /// Area (2-D) or volume (3-D) of one cell, Π_k (max_k − min_k)/m.
    pub fn cell_measure(&self, dim: usize) -> f64 {
        let m = self.resolution as f64;
        (0..dim)
            .map(|k| (self.region.max[k] - self.region.min[k]) / m)
            .product()
    }
}

/// A workspace sampled on a [`Grid`].
#[derive(Debug, Clone, PartialEq)]
pub struct GridWorkspace {
    /// The grid.
    pub grid: Grid,
    /// 2 for robots moving in a plane, 3 in space.
    pub dim: usize,
    /// Verdict per grid point, row-major with x fastest (then y, then z).
    pub feasible: Vec<bool>,
    /// Number of feasible points.
    pub feasible_points: usize,
    /// Number of grid points, (m+1)^dim.
    pub total_points: usize,
    /// Area (volume in 3-D) represented by one point: Π_k (max_k − min_k)/m.
    pub cell_area: f64,
    /// Estimated workspace area (volume in 3-D) in the thesis' convention (points):
    /// `feasible_points × cell_area`. Can exceed the box by up to a factor (1 + 1/m)^dim.
    pub area: f64,
    /// Estimated workspace area (volume in 3-D) in the cells convention: each feasible point
    /// counts for its cell clipped to the box (module docs); at most the box's measure.
    pub clipped_area: f64,
}

/// How a grid turns feasible points into an area (volume): see the module documentation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum VolumeConvention {
    /// Each point stands for its cell clipped to the box ([`GridWorkspace::clipped_area`]):
    /// never more than the box. The default for grids a user chooses.
    #[default]
    Cells,
    /// Feasible points × cell area ([`GridWorkspace::area`]): the thesis' convention, which its
    /// published areas (Tables 6.5–6.10) follow.
    Points,
}

impl VolumeConvention {
    /// The name used on the command line and in JSON (`cells`, `points`).
    pub fn name(self) -> &'static str {
        match self {
            Self::Cells => "cells",
            Self::Points => "points",
        }
    }

    /// One line for reports.
    pub fn describe(self) -> &'static str {
        match self {
            Self::Cells => {
                "cells: each feasible point counts for its grid cell clipped to the box \
                 (never more than the box)"
            }
            Self::Points => {
                "points: feasible points × cell area (the thesis' convention, Algorithm 6.2; \
                 can exceed the box by up to (1 + 1/m)^dim)"
            }
        }
    }
}

impl std::str::FromStr for VolumeConvention {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "cells" => Ok(Self::Cells),
            "points" => Ok(Self::Points),
            _ => Err(format!(
                "unknown volume convention `{s}` (expected `cells` or `points`)"
            )),
        }
    }
}

impl std::fmt::Display for VolumeConvention {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl GridWorkspace {
    /// A workspace from per-point verdicts (counts and area derived).
    pub fn from_verdicts(grid: Grid, dim: usize, feasible: Vec<bool>) -> Self {
        let cell_area = grid.cell_measure(dim);
        // Clipped cells: weight 2^−(number of grid indices at 0 or m), summed in integers
        // scaled by 2^dim (exact for any grid size a machine can hold). This pass runs on one
        // thread after the parallel evaluation, so it goes line by line along x: the feasible
        // points of a line counted at once, its two ends (x index 0 or m) apart, and the
        // other indices stepped like an odometer.
        let p = grid.points_per_axis();
        let m = grid.resolution;
        let mut index = [0usize; 3];
        let mut scaled: u128 = 0;
        let mut feasible_points = 0;
        for line in feasible.chunks(p) {
            let halves = index[1..dim].iter().filter(|&&i| i == 0 || i == m).count();
            let count = line.iter().filter(|&&f| f).count();
            let ends = usize::from(line[0]) + usize::from(line.len() == p && p > 1 && line[p - 1]);
            feasible_points += count;
            scaled += ((count - ends) as u128) << (dim - halves);
            scaled += (ends as u128) << (dim - halves - 1);
            for i in &mut index[1..dim] {
                *i += 1;
                if *i < p {
                    break;
                }
                *i = 0;
            }
        }
        let clipped_area = scaled as f64 / (1u128 << dim) as f64 * cell_area;
        Self {
            grid,
            dim,
            total_points: feasible.len(),
            feasible,
            feasible_points,
            cell_area,
            area: feasible_points as f64 * cell_area,
            clipped_area,
        }
    }

    /// The area (volume) in the given convention.
    pub fn measure(&self, convention: VolumeConvention) -> f64 {
        match convention {
            VolumeConvention::Cells => self.clipped_area,
            VolumeConvention::Points => self.area,
        }
    }

    /// Position of the point of flat index `idx`.
    pub fn point(&self, idx: usize) -> Vector3<f64> {
        self.grid.point(self.dim, idx)
    }

    /// Positions of the feasible points.
    pub fn feasible_positions(&self) -> impl Iterator<Item = Vector3<f64>> + '_ {
        self.feasible
            .iter()
            .enumerate()
            .filter(|&(_, &f)| f)
            .map(|(i, _)| self.point(i))
    }

    /// Whether every feasible point of `self` is feasible in `other` (same grid).
    pub fn is_subset_of(&self, other: &GridWorkspace) -> bool {
        self.feasible.len() == other.feasible.len()
            && self
                .feasible
                .iter()
                .zip(&other.feasible)
                .all(|(&a, &b)| !a || b)
    }

    /// A text picture of a 2-D workspace (`#` feasible, `.` not), top row = y_max.
    pub fn to_ascii(&self) -> String {
        let p = self.grid.points_per_axis();
        let rows = if self.dim == 2 { p } else { p * p };
        let mut s = String::with_capacity(rows * (p + 1));
        for row in (0..rows).rev() {
            for i in 0..p {
                s.push(if self.feasible[row * p + i] { '#' } else { '.' });
            }
            s.push('\n');
        }
        s
    }
}

/// The orientation used for a grid: planar robots only rotate about z; point robots ignore it.
pub(crate) fn checked_orientation(
    motion: MotionPattern,
    rotation: &Rotation3<f64>,
) -> Result<Rotation3<f64>, WorkspaceError> {
    let r = rotation.matrix();
    if let Some(&v) = r.iter().find(|v| !v.is_finite()) {
        return Err(WorkspaceError::NotFinite {
            what: "orientation",
            value: v,
        });
    }
    match motion {
        MotionPattern::Point2 | MotionPattern::Point3 => Ok(Rotation3::identity()),
        MotionPattern::Planar => {
            let off = r[(0, 2)].abs() + r[(1, 2)].abs() + r[(2, 0)].abs() + r[(2, 1)].abs();
            if off > 1e-12 {
                return Err(WorkspaceError::NotPlanarRotation);
            }
            Ok(*rotation)
        }
        MotionPattern::Spatial => Ok(*rotation),
    }
}

/// The coordinates of a grid along each axis, computed once per grid (the values of
/// [`Grid::point`], without its per-point divisions).
pub(crate) struct Axes {
    /// Points per axis, m + 1.
    p: usize,
    dim: usize,
    /// Axis k's coordinates at `coords[k * p..(k + 1) * p]`.
    coords: Vec<f64>,
}

impl Axes {
    fn new(grid: &Grid, dim: usize) -> Self {
        let p = grid.points_per_axis();
        let coords = (0..dim)
            .flat_map(|k| (0..p).map(move |i| grid.coordinate(k, i)))
            .collect();
        Self { p, dim, coords }
    }

    /// Calls `visit(slot, u)` for the points of flat indices `start..start + out.len()`, in order.
    #[inline]
    pub(crate) fn for_each_point<T>(
        &self,
        start: usize,
        out: &mut [T],
        mut visit: impl FnMut(&mut T, Vector3<f64>),
    ) {
        let p = self.p;
        // Grid indices (i, j, l) of `start`; the loop then steps them like an odometer.
        let mut ijl = [start % p, (start / p) % p, start / (p * p)];
        let axis = |k: usize, i: usize| {
            if k < self.dim {
                self.coords[k * p + i]
            } else {
                0.0
            }
        };
        let mut u = Vector3::new(axis(0, ijl[0]), axis(1, ijl[1]), axis(2, ijl[2]));
        for slot in out {
            visit(slot, u);
            ijl[0] += 1;
            if ijl[0] < p {
                u.x = self.coords[ijl[0]];
                continue;
            }
            ijl[0] = 0;
            u.x = self.coords[0];
            ijl[1] += 1;
            if ijl[1] < p {
                u.y = axis(1, ijl[1]);
                continue;
            }
            ijl[1] = 0;
            u.y = axis(1, 0);
            ijl[2] += 1;
            // ijl[2] = p only after the last point of a 3-D grid: nothing is visited after it.
            if ijl[2] < p {
                u.z = axis(2, ijl[2]);
            }
        }
    }
}

/// Rayon tasks per thread at most. Work-stealing splits the grid only as threads run out of work,
/// so tasks this small cost little when the threads keep pace, while a thread that finishes
/// early (verdicts cost from a few ns, a cable too short, to µs, a tension solve) or a thread
/// that the OS pauses leaves at most one small task unfinished for the others.
const TASKS_PER_THREAD: usize = 16;

/// Points per rayon task for `points` points on `threads` threads.
fn task_len(points: usize, threads: usize) -> usize {
    points
        .div_ceil(threads.max(1) * TASKS_PER_THREAD)
        .max(MIN_POINTS_PER_TASK)
}

/// Evaluates `f` at every grid point in parallel, in grid order (`eval`: a [`PoseEvaluator`] or
/// any per-thread state, e.g. an orientation test).
///
/// The points are cut into contiguous tasks ([`task_len`]); each rayon thread clones the
/// evaluator once, on its first task, and reuses it (warm buffers) for its later tasks, however
/// many tasks work-stealing gives it. Each verdict depends on its point only, so the result does
/// not depend on the number of threads nor on which thread evaluates which point.
pub(crate) fn map_grid<S, T, F>(eval: &S, grid: &Grid, dim: usize, f: F) -> Vec<T>
where
    S: Clone + Send + Sync,
    T: Send + Copy + Default,
    F: Fn(&mut S, Vector3<f64>) -> T + Sync,
{
    map_grid_tasks(eval, grid, dim, |ev, axes, start, slots| {
        axes.for_each_point(start, slots, |slot, u| *slot = f(ev, u))
    })
}

/// [`map_grid`] with the task as the unit: `task(state, axes, start, slots)` fills the verdicts
/// of the points of flat indices `start..start + slots.len()`.
pub(crate) fn map_grid_tasks<S, T, F>(eval: &S, grid: &Grid, dim: usize, task_fn: F) -> Vec<T>
where
    S: Clone + Send + Sync,
    T: Send + Copy + Default,
    F: Fn(&mut S, &Axes, usize, &mut [T]) + Sync,
{
    let axes = Axes::new(grid, dim);
    let mut out = vec![T::default(); grid.point_count(dim)];
    let threads = crate::parallel::current_num_threads();
    let len = task_len(out.len(), threads);
    // One slot per thread of the pool running the tasks; a thread only ever locks its own slot,
    // so the lock is uncontended. `try_lock` fails only if a criterion re-enters rayon and this
    // thread picks up another task meanwhile: that task then uses a clone of its own.
    let evaluators: Vec<Mutex<Option<S>>> = (0..threads).map(|_| Mutex::new(None)).collect();
    crate::parallel::for_each_chunk_mut(&mut out, len, |task, slots| {
        let mut run = |ev: &mut S| task_fn(ev, &axes, task * len, slots);
        let own = crate::parallel::current_thread_index().unwrap_or(0) % threads;
        match evaluators[own].try_lock() {
            Ok(mut slot) => run(slot.get_or_insert_with(|| eval.clone())),
            Err(_) => run(&mut eval.clone()),
        }
    });
    out
}

/// Algorithm 6.2: the constant-orientation workspace at `orientation` on `grid`.
///
/// For a planar robot the orientation must be a rotation about z (use
/// [`planar_workspace`] for an angle φ); point robots ignore it.
///
/// ```
/// use cdpr_kinematics::{Cable, MotionPattern, Robot};
/// use cdpr_workspace::{constant_orientation_workspace, Criterion, Grid, PoseEvaluator, Region};
/// use cdpr_tension::TensionBounds;
/// use nalgebra::{Rotation3, Vector3};
/// let c = |x: f64, y: f64| Cable { frame: Vector3::new(x, y, 0.0), platform: Vector3::zeros(), pulley: None };
/// let robot = Robot::new(MotionPattern::Point2, vec![c(1.0, 1.0), c(-1.0, 1.0), c(0.0, -1.0)]).unwrap();
/// let eval = PoseEvaluator::new(robot, TensionBounds::uniform(3, 0.0, 1.0).unwrap(),
///                               vec![Criterion::WrenchClosure]).unwrap();
/// let grid = Grid::new(40, Region::planar(-1.0, 1.0, -1.0, 1.0));
/// let ws = constant_orientation_workspace(&eval, &Rotation3::identity(), &grid).unwrap();
/// // Wrench closure of a point with 3 cables: the open triangle of the anchors, area 2.
/// assert!((ws.area - 2.0).abs() < 0.15);
/// ```
pub fn constant_orientation_workspace(
    eval: &PoseEvaluator,
    orientation: &Rotation3<f64>,
    grid: &Grid,
) -> Result<GridWorkspace, WorkspaceError> {
    let motion = eval.robot().motion();
    let dim = motion.space_dim();
    grid.validate(dim)?;
    eval.validate()?;
    let rotation = checked_orientation(motion, orientation)?;
    // Each task takes its points [`BATCH`] at a time through `PoseEvaluator::feasible_batch`
    // (the batch inverse kinematics when the criteria need W only; the same verdicts).
    let state = (
        eval.clone(),
        vec![Pose::new(Vector3::zeros(), rotation); BATCH],
    );
    let feasible = map_grid_tasks(&state, grid, dim, |(ev, poses), axes, start, slots| {
        for (c, verdicts) in slots.chunks_mut(BATCH).enumerate() {
            let poses = &mut poses[..verdicts.len()];
            axes.for_each_point(start + c * BATCH, poses, |p, u| p.position = u);
            ev.feasible_batch(poses, verdicts);
        }
    });
    Ok(GridWorkspace::from_verdicts(*grid, dim, feasible))
}

/// Algorithm 6.2 for a planar robot at orientation φ (radians) about z.
pub fn planar_workspace(
    eval: &PoseEvaluator,
    phi: f64,
    grid: &Grid,
) -> Result<GridWorkspace, WorkspaceError> {
    if !phi.is_finite() {
        return Err(WorkspaceError::NotFinite {
            what: "orientation φ",
            value: phi,
        });
    }
    constant_orientation_workspace(
        eval,
        &Rotation3::from_axis_angle(&Vector3::z_axis(), phi),
        grid,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 13 §1: a 3-D grid with every point feasible reported 27.78 m³ in a 24 m³ box
    /// (21³ points × 24/20³). In the cells convention it is the box, exactly; a lone corner
    /// point is ⅛ cell, an edge point ¼, a face point ½, an interior point 1.
    #[test]
    fn clipped_cells_never_exceed_the_box() {
        let region = Region::cuboid(Vector3::new(-2.0, -1.5, 0.0), Vector3::new(2.0, 1.5, 2.0));
        let grid = Grid::new(20, region);
        let ws = GridWorkspace::from_verdicts(grid, 3, vec![true; 21 * 21 * 21]);
        assert!(
            (ws.area - 9261.0 * 24.0 / 8000.0).abs() < 1e-9,
            "{}",
            ws.area
        );
        assert!(ws.area > 27.7);
        assert_eq!(ws.clipped_area, 24.0);
        assert_eq!(ws.measure(VolumeConvention::Cells), 24.0);
        assert_eq!(ws.measure(VolumeConvention::Points), ws.area);
        let one = |idx: usize| {
            let mut f = vec![false; 21 * 21 * 21];
            f[idx] = true;
            GridWorkspace::from_verdicts(grid, 3, f).clipped_area / ws.cell_area
        };
        assert_eq!(one(0), 0.125);
        assert_eq!(one(5), 0.25); // on the edge y = z = min
        assert_eq!(one(5 + 21 * 5), 0.5); // on the face z = min
        assert_eq!(one(5 + 21 * 5 + 441 * 5), 1.0);
        assert_eq!(one(20 + 21 * 20 + 441 * 20), 0.125);
        // 2-D: the whole square is the square; the thesis' count is (1 + 1/m)² of it.
        let grid = Grid::new(50, Region::planar(-1.0, 1.0, -1.0, 1.0));
        let ws = GridWorkspace::from_verdicts(grid, 2, vec![true; 51 * 51]);
        assert!((ws.clipped_area - 4.0).abs() < 1e-12);
        assert!((ws.area - 51.0 * 51.0 * 0.0016).abs() < 1e-12);
        let none = GridWorkspace::from_verdicts(grid, 2, vec![false; 51 * 51]);
        assert_eq!(none.clipped_area, 0.0);
        assert_eq!(
            "points".parse::<VolumeConvention>(),
            Ok(VolumeConvention::Points)
        );
        assert!("volume".parse::<VolumeConvention>().is_err());
    }

    /// The odometer walk of `Axes` visits exactly the points of `Grid::point` (bit for bit), in
    /// order, from any start and over row and layer ends, in 2-D and 3-D.
    #[test]
    fn axes_walk_matches_grid_points() {
        let region = Region::cuboid(Vector3::new(-1.3, 0.2, -0.7), Vector3::new(0.9, 2.1, 0.4));
        for (m, dim) in [(1, 2), (4, 2), (7, 3), (50, 2), (6, 3)] {
            let grid = Grid::new(m, region);
            let axes = Axes::new(&grid, dim);
            let n = grid.point_count(dim);
            for (start, len) in [
                (0, n),
                (3, 1),
                (m, 2),
                (m + 1, m + 2),
                (n - 1, 1),
                (n / 3, n / 2),
            ] {
                let mut seen = vec![Vector3::repeat(f64::NAN); len];
                axes.for_each_point(start, &mut seen, |s, u| *s = u);
                for (k, u) in seen.iter().enumerate() {
                    assert_eq!(*u, grid.point(dim, start + k), "m = {m}, dim = {dim}");
                }
            }
        }
    }

    /// The clipped measure summed line by line equals the weights computed from the flat index
    /// by division (2^−(indices at 0 or m) per feasible point), on pseudo-random verdicts in
    /// 2-D and 3-D, and so does the feasible count.
    #[test]
    fn clipped_cells_from_the_odometer_equal_the_divided_indices() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        for (dim, m) in [(2, 1), (2, 7), (3, 1), (3, 4), (3, 9)] {
            let region = Region::cuboid(Vector3::new(0.0, 0.0, 0.0), Vector3::new(1.0, 2.0, 3.0));
            let grid = Grid::new(m, region);
            let p = m + 1;
            let feasible: Vec<bool> = (0..grid.point_count(dim))
                .map(|_| {
                    seed ^= seed << 13;
                    seed ^= seed >> 7;
                    seed ^= seed << 17;
                    !seed.is_multiple_of(3)
                })
                .collect();
            let weight = |idx: usize| {
                let halves = (0..dim)
                    .filter(|&a| {
                        let i = idx / p.pow(a as u32) % p;
                        i == 0 || i == m
                    })
                    .count();
                0.5f64.powi(halves as i32)
            };
            let expected: f64 = (0..feasible.len())
                .filter(|&idx| feasible[idx])
                .map(weight)
                .sum();
            let count = feasible.iter().filter(|&&f| f).count();
            let ws = GridWorkspace::from_verdicts(grid, dim, feasible);
            assert_eq!(ws.feasible_points, count);
            assert!(
                (ws.clipped_area / ws.cell_area - expected).abs() < 1e-9,
                "{dim}-D, m = {m}"
            );
        }
    }

    #[test]
    fn task_lengths_cover_the_grid_in_a_bounded_number_of_tasks() {
        assert_eq!(task_len(2601, 2), 2601usize.div_ceil(2 * TASKS_PER_THREAD));
        assert_eq!(task_len(10, 4), MIN_POINTS_PER_TASK);
        assert_eq!(task_len(2601, 0), task_len(2601, 1));
        for (points, threads) in [(2601, 1), (2601, 2), (15_625, 3), (100, 2)] {
            let len = task_len(points, threads);
            assert!(points.div_ceil(len) <= threads * TASKS_PER_THREAD);
        }
    }
}
