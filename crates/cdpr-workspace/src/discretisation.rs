//! # Discretisation method (Algorithm 6.2)
//!
//! The constant-orientation workspace on a regular grid: (m+1)² points
//! u^ij = [x_min + (i/m)(x_max − x_min), y_min + (j/m)(y_max − y_min)] (Algorithm 6.2 step 3),
//! each tested against the criteria (step 4). Robots moving in space (`point3`, `spatial`) use
//! the 3-D grid of (m+1)³ points. The area (volume) estimate is the number of feasible points
//! times the cell area (Δx/m)(Δy/m) (times Δz/m).
//!
//! Points are evaluated in parallel with rayon, one [`PoseEvaluator`] clone per task
//! (`map_init`); each point's verdict depends on that point only, so the result is the same
//! whatever the number of threads.
//!
//! ## References
//! - Seed 000, §6.4.2, Algorithm 6.2.

use crate::{PoseEvaluator, Region, WorkspaceError};
use cdpr_kinematics::{MotionPattern, Pose};
use nalgebra::{Rotation3, Vector3};
use rayon::prelude::*;

/// Smallest number of grid points a rayon task handles (amortises the evaluator clone).
const MIN_POINTS_PER_TASK: usize = 128;

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
        let m = self.resolution as f64;
        // Axes beyond `dim` are 0 (a planar robot moves in z = 0 whatever the region's z).
        let mut q = Vector3::zeros();
        let mut rest = idx;
        for k in 0..dim {
            let i = rest % p;
            rest /= p;
            // Written as min + (i/m)(max − min) so that i = m lands exactly on max.
            q[k] = if i == self.resolution {
                self.region.max[k]
            } else {
                self.region.min[k] + (i as f64 / m) * (self.region.max[k] - self.region.min[k])
            };
        }
        q
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
    /// Estimated workspace area (volume in 3-D): `feasible_points × cell_area`.
    pub area: f64,
}

impl GridWorkspace {
    /// A workspace from per-point verdicts (counts and area derived).
    pub fn from_verdicts(grid: Grid, dim: usize, feasible: Vec<bool>) -> Self {
        let feasible_points = feasible.iter().filter(|&&f| f).count();
        let cell_area = grid.cell_measure(dim);
        Self {
            grid,
            dim,
            total_points: feasible.len(),
            feasible,
            feasible_points,
            cell_area,
            area: feasible_points as f64 * cell_area,
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

/// Evaluates `f` at every grid point in parallel (one evaluator clone per rayon task), in
/// grid order.
pub(crate) fn map_grid<T, F>(eval: &PoseEvaluator, grid: &Grid, dim: usize, f: F) -> Vec<T>
where
    T: Send,
    F: Fn(&mut PoseEvaluator, Vector3<f64>) -> T + Sync,
{
    (0..grid.point_count(dim))
        .into_par_iter()
        .with_min_len(MIN_POINTS_PER_TASK)
        .map_init(|| eval.clone(), |ev, idx| f(ev, grid.point(dim, idx)))
        .collect()
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
/// let c = |x: f64, y: f64| Cable { frame: Vector3::new(x, y, 0.0), platform: Vector3::zeros() };
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
    let feasible = map_grid(eval, grid, dim, |ev, u| {
        ev.is_feasible(&Pose::new(u, rotation))
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
