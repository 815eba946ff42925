//! # The orientation workspace at a position
//!
//! Which orientations of a sampled set (an Euler box or a tilt cone with torsion, Bonev,
//! Zlatanov & Gosselin 2002) are feasible at one position of a `spatial` robot: every criterion
//! holds, the platform's gravity evaluated at each orientation. The verdicts at the samples are
//! exact; nothing is claimed between them. The map folds them onto two angles (tilt against
//! torsion, or the two ranged Euler angles) as the fraction of samples feasible over the third.
//!
//! ## References
//! - Bonev, Zlatanov & Gosselin 2002 (tilt-and-torsion angles).
//! - Merlet, "Parallel Robots" (2006), §6 (orientation workspace).

use cdpr_workspace::{OrientationSet, OrientationWorkspaceKind, SampledOrientation};
use nalgebra::Vector3;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::criteria::{CriteriaSetup, WorkspaceCriteria, default_method};
use crate::orientation_set::{degrees, orientation_test};
use crate::{ApiError, Robot};

/// The feasible orientations of a set at one position (`cdpr orientations`).
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
pub struct OrientationsRequest {
    /// The robot (`spatial`).
    pub robot: Robot,
    /// The criteria and their load.
    #[serde(flatten)]
    pub criteria: WorkspaceCriteria,
    /// Platform position x, y, z (m).
    pub position: Vec<f64>,
    /// The orientation set, e.g. `tilt:20,torsion=-30..30,n=5` (degrees).
    pub orientations: String,
}

/// One sampled orientation and its verdict.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct SampleReport {
    /// The angles (degrees, in `angle_names`).
    pub angles_deg: [f64; 3],
    /// Every criterion holds.
    pub feasible: bool,
}

/// The fraction of samples feasible over two of the angles.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct FractionMapReport {
    /// The angle along x.
    pub x: String,
    /// The angle along y.
    pub y: String,
    /// Sample values along x (degrees).
    pub x_deg: Vec<f64>,
    /// Sample values along y (degrees).
    pub y_deg: Vec<f64>,
    /// Rows by y: the fraction of the samples at (x, y) that are feasible, over the third angle
    /// (null where there is no sample).
    pub fraction: Vec<Vec<Option<f64>>>,
}

/// The JSON of `cdpr orientations --json`.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct OrientationsReport {
    /// Robot name.
    pub robot: String,
    /// The position (m).
    pub position: [f64; 3],
    /// The set, as parsed (degrees).
    pub orientation_set: String,
    /// The names of the three angles.
    pub angle_names: [String; 3],
    /// Criterion labels.
    pub criteria: Vec<String>,
    /// Sampled orientations.
    pub count: usize,
    /// Feasible ones.
    pub feasible_count: usize,
    /// Every sample, in sampling order.
    pub orientations: Vec<SampleReport>,
    /// The map.
    pub map: FractionMapReport,
    /// The angle indices along x and y of the map (not in JSON).
    #[serde(skip)]
    pub map_axes: (usize, usize),
}

/// Sorted distinct values.
fn distinct(mut v: Vec<f64>) -> Vec<f64> {
    v.sort_by(f64::total_cmp);
    v.dedup_by(|a, b| (*a - *b).abs() <= 1e-12 * b.abs().max(1.0));
    v
}

/// The angle indices (x, y) of a set's map: tilt against torsion, or the two ranged Euler
/// angles.
fn map_axes(set: &OrientationSet) -> (usize, usize) {
    match set {
        OrientationSet::TiltTorsion { .. } => (2, 0),
        OrientationSet::EulerBox { min, max, .. } => {
            let ranged: Vec<usize> = (0..3).filter(|&k| min[k] < max[k]).collect();
            match ranged.as_slice() {
                [] => (0, 1),
                [a] => (*a, if *a == 0 { 1 } else { 0 }),
                [a, b, ..] => (*a, *b),
            }
        }
    }
}

/// The map of a set's verdicts: sample values along the axes (degrees) and the fraction
/// feasible in each cell, rows by y.
fn fraction_map(
    axes: (usize, usize),
    samples: &[SampledOrientation],
    feasible: &[bool],
) -> (Vec<f64>, Vec<f64>, Vec<Vec<Option<f64>>>) {
    let deg = |o: &SampledOrientation, k: usize| o.angles[k].to_degrees();
    let xs = distinct(samples.iter().map(|o| deg(o, axes.0)).collect());
    let ys = distinct(samples.iter().map(|o| deg(o, axes.1)).collect());
    let find = |v: &[f64], x: f64| {
        v.iter()
            .position(|a| (a - x).abs() <= 1e-12 * x.abs().max(1.0))
            .unwrap_or(0)
    };
    let mut count = vec![(0usize, 0usize); xs.len() * ys.len()];
    for (o, &ok) in samples.iter().zip(feasible) {
        let cell = find(&ys, deg(o, axes.1)) * xs.len() + find(&xs, deg(o, axes.0));
        count[cell].1 += 1;
        count[cell].0 += ok as usize;
    }
    let fraction = count
        .chunks(xs.len().max(1))
        .map(|row| {
            row.iter()
                .map(|&(a, n)| (n > 0).then(|| a as f64 / n as f64))
                .collect()
        })
        .collect();
    (xs, ys, fraction)
}

impl OrientationsRequest {
    /// Checks the request.
    pub fn validate(&self) -> Result<(), ApiError> {
        self.prepare().map(|_| ())
    }

    fn prepare(&self) -> Result<(CriteriaSetup, OrientationSet, Vector3<f64>), ApiError> {
        let desc = self.robot.description();
        let method = self
            .criteria
            .method
            .unwrap_or_else(|| default_method(&desc.robot));
        let setup = CriteriaSetup::new(&self.criteria, desc, method)?;
        let u = match self.position.as_slice() {
            [x, y, z] if [x, y, z].iter().all(|v| v.is_finite()) => Vector3::new(*x, *y, *z),
            p => {
                return Err(ApiError::invalid(format!(
                    "--position needs 3 finite numbers x,y,z (m), got {p:?}"
                )));
            }
        };
        let set: OrientationSet = self
            .orientations
            .parse()
            .map_err(|e| ApiError::invalid(format!("--orientations {}: {e}", self.orientations)))?;
        Ok((setup, set, u))
    }

    /// The verdict of every sampled orientation at the position, and their map.
    pub fn run(&self) -> Result<OrientationsReport, ApiError> {
        let (setup, set, u) = self.prepare()?;
        let desc = self.robot.description();
        let (mut test, samples) =
            orientation_test(desc, &setup, &set, OrientationWorkspaceKind::Total)?;
        let feasible = test.feasible_orientations(u);
        let names = set.angle_names();
        let axes = map_axes(&set);
        let (x_deg, y_deg, fraction) = fraction_map(axes, &samples, &feasible);
        Ok(OrientationsReport {
            robot: desc.name.clone(),
            position: u.into(),
            orientation_set: set.to_string(),
            angle_names: names.map(String::from),
            criteria: setup.labels(),
            count: samples.len(),
            feasible_count: feasible.iter().filter(|&&f| f).count(),
            orientations: samples
                .iter()
                .zip(&feasible)
                .map(|(o, &feasible)| SampleReport {
                    angles_deg: degrees(o),
                    feasible,
                })
                .collect(),
            map: FractionMapReport {
                x: names[axes.0].into(),
                y: names[axes.1].into(),
                x_deg,
                y_deg,
                fraction,
            },
            map_axes: axes,
        })
    }
}
