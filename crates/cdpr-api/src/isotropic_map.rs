//! # Maximum isotropic force over a grid
//!
//! The index of Krut, Company & Pierrot 2004 (eq. 19; the force at zero moment for planar and
//! spatial robots) at every point of an (M+1) × (M+1) grid of positions at one orientation (and
//! one height for 3-D robots), under the load w_ext = w_e + the robot file's load at the slice's
//! orientation (Krut, Company & Pierrot 2004, Figs. 9–10). Rows run in parallel with the
//! `parallel` feature; a pose where the index is undefined (a zero-length cable, a singular W)
//! is null.
//!
//! ## References
//! - Krut, Company & Pierrot 2004 (eq. 19, Figs. 9–10).

use cdpr_kinematics::{MotionPattern, Pose};
use cdpr_polytope::IsotropicForce;
use nalgebra::Vector3;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::inputs::external_wrench;
use crate::{ApiError, Robot, definition};

/// The isotropic force over a grid (`cdpr isotropic --grid M`).
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
pub struct IsotropicMapRequest {
    /// The robot.
    pub robot: Robot,
    /// M: intervals per side, in [1, 2000].
    pub grid: usize,
    /// XMIN, XMAX, YMIN, YMAX (m); default: the frame anchors' bounding box.
    #[serde(default, rename = "box")]
    pub area: Option<Vec<f64>>,
    /// Platform orientation φ (rad, about z) for planar and spatial robots.
    #[serde(default)]
    pub orientation: f64,
    /// External wrench w_e (N, N·m; default zero), added to the robot file's load.
    #[serde(default)]
    pub wrench: Option<Vec<f64>>,
    /// Height of the slice for 3-D robots (m; default: the middle height of the robot's default
    /// region, `Robot::default_region`: the frame anchors' box, which for a suspended robot
    /// reaches half the frame's width below the anchors).
    #[serde(default)]
    pub z: Option<f64>,
}

/// Where the grid lies.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct SliceReport {
    /// Platform orientation φ (rad).
    pub orientation: f64,
    /// 3-D robots: the height of the slice (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub z: Option<f64>,
}

/// The grid and its values.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct MapGridReport {
    /// x of the columns (m).
    pub x: Vec<f64>,
    /// y of the rows (m).
    pub y: Vec<f64>,
    /// [rows, columns].
    pub shape: [usize; 2],
    /// The index (N), rows along y; null where undefined.
    pub values: Vec<Vec<Option<f64>>>,
}

/// A summary of the map.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct MapStatsReport {
    /// Smallest defined value (N).
    pub min: Option<f64>,
    /// Largest defined value (N).
    pub max: Option<f64>,
    /// Where the largest is (m).
    pub argmax: Option<[f64; 2]>,
    /// Fraction of the grid where the index is positive.
    pub positive_fraction: f64,
    /// Number of points where it is undefined.
    pub undefined: usize,
    /// The index at the centre of the box (N).
    pub centre: Option<f64>,
}

/// The JSON of `cdpr isotropic --grid --json`.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct IsotropicMapReport {
    /// Robot name.
    pub robot: String,
    /// What the index means for this motion pattern.
    pub definition: String,
    /// w_ext (N, N·m).
    pub external_wrench: Vec<f64>,
    /// Orientation and height of the grid.
    pub slice: SliceReport,
    /// The grid.
    pub grid: MapGridReport,
    /// Its summary.
    pub stats: MapStatsReport,
}

/// The pose at grid point (x, y).
fn grid_pose(motion: MotionPattern, x: f64, y: f64, z: f64, phi: f64) -> Pose {
    match motion {
        MotionPattern::Point2 => Pose::point(x, y, 0.0),
        MotionPattern::Planar => Pose::planar(x, y, phi),
        MotionPattern::Point3 => Pose::point(x, y, z),
        MotionPattern::Spatial => Pose::spatial(Vector3::new(x, y, z), 0.0, 0.0, phi),
    }
}

impl IsotropicMapRequest {
    /// The box (x0, x1, y0, y1) and the height z, checked.
    fn region(&self) -> Result<([f64; 4], f64), ApiError> {
        if !(1..=2000).contains(&self.grid) {
            return Err(ApiError::invalid("--grid M must lie in [1, 2000]"));
        }
        cdpr_wrench::require_enough_cables(
            &self.robot.robot,
            "the isotropic force (wrench closure)",
        )?;
        let (lo, hi) = self.robot.robot.default_region();
        let [x0, x1, y0, y1] = match &self.area {
            Some(b) if b.len() == 4 => [b[0], b[1], b[2], b[3]],
            Some(b) => {
                return Err(ApiError::invalid(format!(
                    "--box needs 4 numbers, got {}",
                    b.len()
                )));
            }
            None => [lo.x, hi.x, lo.y, hi.y],
        };
        if !(x0 < x1 && y0 < y1 && [x0, x1, y0, y1].iter().all(|v| v.is_finite())) {
            return Err(ApiError::invalid(format!(
                "the grid box [{x0}, {x1}] × [{y0}, {y1}] is empty or not finite"
            )));
        }
        let z = self.z.unwrap_or(0.5 * (lo.z + hi.z));
        if !z.is_finite() || !self.orientation.is_finite() {
            return Err(ApiError::invalid("--z and --orientation must be finite"));
        }
        Ok(([x0, x1, y0, y1], z))
    }

    /// Checks the request.
    pub fn validate(&self) -> Result<(), ApiError> {
        self.region().map(|_| ())
    }

    /// Maps the index.
    pub fn run(&self) -> Result<IsotropicMapReport, ApiError> {
        self.run_with_progress(&|| {})
    }

    /// Maps the index, calling `row_done` after each row (a progress bar).
    pub fn run_with_progress(
        &self,
        row_done: &(dyn Fn() + Sync),
    ) -> Result<IsotropicMapReport, ApiError> {
        let ([x0, x1, y0, y1], z) = self.region()?;
        let robot = &self.robot;
        let motion = robot.robot.motion();
        let (m, phi) = (self.grid, self.orientation);
        let k = m + 1;
        let axis = |a: f64, b: f64| -> Vec<f64> {
            (0..k).map(|i| a + (b - a) * i as f64 / m as f64).collect()
        };
        let (xs, ys) = (axis(x0, x1), axis(y0, y1));
        let slice_pose = grid_pose(motion, x0, y0, z, phi);
        let w_ext = external_wrench(robot, &slice_pose, self.wrench.as_deref())?;
        let template =
            IsotropicForce::new(&robot.robot, &robot.bounds)?.with_load(w_ext.as_slice())?;
        let row = |index: &mut IsotropicForce, y: f64| -> Vec<f64> {
            let r = xs
                .iter()
                .map(|&x| {
                    index
                        .force_at_pose(&grid_pose(motion, x, y, z, phi))
                        .unwrap_or(f64::NAN)
                })
                .collect();
            row_done();
            r
        };
        #[cfg(feature = "parallel")]
        let rows: Vec<Vec<f64>> = {
            use rayon::prelude::*;
            ys.par_iter()
                .map_init(|| template.clone(), |index, &y| row(index, y))
                .collect()
        };
        #[cfg(not(feature = "parallel"))]
        let rows: Vec<Vec<f64>> = {
            let mut index = template.clone();
            ys.iter().map(|&y| row(&mut index, y)).collect()
        };
        let values = rows.concat();
        let centre_pose = grid_pose(motion, 0.5 * (x0 + x1), 0.5 * (y0 + y1), z, phi);
        let centre = template.clone().force_at_pose(&centre_pose).ok();
        let stats = stats(&values, &xs, &ys, centre);
        let finite = |v: f64| v.is_finite().then_some(v);
        Ok(IsotropicMapReport {
            robot: robot.name.clone(),
            definition: definition(motion).to_string(),
            external_wrench: w_ext.as_slice().to_vec(),
            slice: SliceReport {
                orientation: phi,
                z: (motion.space_dim() == 3).then_some(z),
            },
            grid: MapGridReport {
                shape: [k, k],
                values: values
                    .chunks(k)
                    .map(|r| r.iter().map(|&v| finite(v)).collect())
                    .collect(),
                x: xs,
                y: ys,
            },
            stats,
        })
    }
}

/// Minimum, maximum and where, positive fraction, undefined count of a row-major map.
fn stats(values: &[f64], xs: &[f64], ys: &[f64], centre: Option<f64>) -> MapStatsReport {
    let k = xs.len();
    let defined: Vec<(usize, f64)> = values
        .iter()
        .copied()
        .enumerate()
        .filter(|(_, v)| !v.is_nan())
        .collect();
    let (amax, vmax) = defined
        .iter()
        .copied()
        .fold((usize::MAX, f64::NEG_INFINITY), |a, b| {
            if b.1 > a.1 { b } else { a }
        });
    let vmin = defined.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
    let finite = |v: f64| v.is_finite().then_some(v);
    MapStatsReport {
        min: finite(vmin),
        max: finite(vmax),
        argmax: (amax != usize::MAX).then(|| [xs[amax % k], ys[amax / k]]),
        positive_fraction: defined.iter().filter(|p| p.1 > 0.0).count() as f64
            / values.len() as f64,
        undefined: values.len() - defined.len(),
        centre: centre.and_then(finite),
    }
}
