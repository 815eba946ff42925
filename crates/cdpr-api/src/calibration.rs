//! # Kinematic calibration
//!
//! Calibrates a robot from samples of its cable-length readings (crate `cdpr-calibration`):
//! frame anchors, platform attachments, length offsets and encoder gains (true length =
//! gain_i · reading + offset_i). With known poses each cable is fitted by least squares on its
//! own; without, the poses are unknowns too (self-calibration, Borgstrom et al. 2009;
//! Miermeister & Pott 2012) with the gauge fixed. The samples come as the CSV text of
//! `cdpr calibrate --samples` ([`parse_samples_csv`], errors naming the file, line and column)
//! or as arrays (Python, a browser form).
//!
//! ## References
//! - Borgstrom, Jordan, Borgstrom, Stealey, Sukhatme, Batalin & Kaiser (2009), NIMS-PL:
//!   self-calibration of a cable-driven robot.
//! - Miermeister & Pott (2012), auto-calibration of cable-driven parallel robots.

use cdpr_calibration::{
    Calibration, ParameterSigma, Readings, Samples, Unknowns, calibrate_with_encoders,
};
use cdpr_io::Encoders;
use cdpr_kinematics::{MotionPattern, Pose};
use nalgebra::Vector3;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::{ApiError, Robot};

/// Where the samples come from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum SamplesSource {
    /// The CSV of `cdpr calibrate --samples` (a header line first, `#` comments and blank
    /// lines skipped): with `known_poses` the pose coordinates by name (point2 `x,y`; planar
    /// `x,y,phi`; point3 `x,y,z`; spatial `x,y,z,rx,ry,rz`, m and rad), and always the
    /// readings `l1,…,ln`.
    Csv {
        /// The file's text.
        text: String,
        /// The file name in error messages (default `samples.csv`).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        file: Option<String>,
        /// The CSV gives each sample's pose.
        #[serde(default)]
        known_poses: bool,
    },
    /// Arrays: k rows of n readings and, when measured, k rows of the pose's coordinates.
    Arrays {
        /// Readings ρ (one row of n per sample).
        readings: Vec<Vec<f64>>,
        /// Measured poses (one row of DOF coordinates per sample, m and rad).
        #[serde(default)]
        poses: Option<Vec<Vec<f64>>>,
    },
}

fn default_unknowns() -> String {
    "frame,offsets".into()
}

/// Kinematic calibration from cable-length readings (`cdpr calibrate`).
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
pub struct CalibrationRequest {
    /// The nominal robot (its cables' `offset` and `gain` keys give the starting encoders).
    pub robot: Robot,
    /// The samples.
    pub samples: SamplesSource,
    /// The parameter groups to calibrate, comma-separated: frame, platform, offsets, gains.
    #[serde(default = "default_unknowns")]
    pub unknowns: String,
    /// Readings relative to the reference pose (true length = gain · reading + offset + the
    /// length at the reference pose).
    #[serde(default)]
    pub relative: bool,
    /// The reference pose of relative readings (default: the robot file's `home_pose`, else the
    /// origin).
    #[serde(default)]
    pub reference: Option<Vec<f64>>,
}

/// Standard deviations of the calibrated parameters (σ̂²(JᵀJ)⁻¹), null for groups not
/// calibrated.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct SigmaReport {
    /// Of each anchor coordinate (m).
    pub frame: Option<Vec<Vec<f64>>>,
    /// Of each attachment coordinate (m).
    pub platform: Option<Vec<Vec<f64>>>,
    /// Of each offset (m).
    pub offsets: Option<Vec<f64>>,
    /// Of each gain.
    pub gains: Option<Vec<f64>>,
}

/// The JSON of `cdpr calibrate --json`.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct CalibrationReport {
    /// Robot name.
    pub robot: String,
    /// Motion pattern.
    pub motion: String,
    /// k, the number of samples.
    pub samples: usize,
    /// n, the number of cables.
    pub cables: usize,
    /// The samples gave their poses.
    pub known_poses: bool,
    /// The readings are relative to the reference pose.
    pub relative: bool,
    /// The parameter groups as requested.
    pub unknowns: Vec<String>,
    /// Calibrated frame anchors (m).
    pub frame: Vec<Vec<f64>>,
    /// Calibrated platform attachments (m; null for point robots).
    pub platform: Option<Vec<Vec<f64>>>,
    /// Length offsets (m).
    pub offsets: Vec<f64>,
    /// Encoder gains.
    pub gains: Vec<f64>,
    /// Self-calibration: the estimated poses (motion-pattern coordinates, m and rad); null with
    /// known poses.
    pub poses: Option<Vec<Vec<f64>>>,
    /// √(Σr²/N) (m; null when undefined).
    pub residual_rms: Option<f64>,
    /// Largest residual (m; null when undefined).
    pub residual_max: Option<f64>,
    /// σ̂ = √(Σr²/(N − P)) (m).
    pub length_sigma: Option<f64>,
    /// Per parameter group; null when not identifiable.
    pub sigma: Option<SigmaReport>,
    /// The samples identify the unknowns.
    pub identifiable: bool,
    /// Rank deficiency of the Jacobian.
    pub rank_deficiency: usize,
    /// Of the column-scaled Jacobian (null when singular).
    pub condition_number: Option<f64>,
    /// p, the parameters.
    pub parameters: usize,
    /// g, the gauge freedoms held.
    pub gauge_count: usize,
    /// What the gauge holds.
    pub gauge: Vec<String>,
    /// Samples needed to identify the unknowns (when too few).
    pub samples_needed: Option<usize>,
    /// Why the unknowns are not identifiable.
    pub reason: Option<String>,
    /// Solver iterations.
    pub iterations: usize,
    /// The solver converged.
    pub converged: bool,
    /// Warnings (an ill-conditioned Jacobian, …).
    pub warnings: Vec<String>,
    /// The calibration itself (for the table and the calibrated robot file; not in JSON).
    #[serde(skip)]
    pub calibration: Calibration,
}

/// The pose columns of a motion pattern.
pub fn pose_columns(motion: MotionPattern) -> &'static [&'static str] {
    match motion {
        MotionPattern::Point2 => &["x", "y"],
        MotionPattern::Planar => &["x", "y", "phi"],
        MotionPattern::Point3 => &["x", "y", "z"],
        MotionPattern::Spatial => &["x", "y", "z", "rx", "ry", "rz"],
    }
}

/// The wanted columns, in order, and their positions in the header of a samples CSV.
struct Header {
    names: Vec<String>,
    wanted: Vec<String>,
    index: Vec<usize>,
}

/// Reads and checks the header line against the columns a robot needs.
fn read_header(
    file: &str,
    (line, header): (usize, &str),
    motion: MotionPattern,
    n: usize,
    known_poses: bool,
) -> Result<Header, ApiError> {
    let names: Vec<String> = header.split(',').map(|s| s.trim().to_lowercase()).collect();
    let mut wanted: Vec<String> = (1..=n).map(|i| format!("l{i}")).collect();
    if known_poses {
        wanted.splice(0..0, pose_columns(motion).iter().map(|s| s.to_string()));
    }
    let mut index = Vec::with_capacity(wanted.len());
    for w in &wanted {
        match names.iter().position(|c| c == w) {
            Some(c) => index.push(c),
            None => {
                let needs = if known_poses {
                    format!(
                        ": the pose of a {} robot and one reading per cable",
                        motion.name()
                    )
                } else {
                    ": one reading per cable".to_string()
                };
                return Err(ApiError::invalid(format!(
                    "{file}:{line}: missing column `{w}` (the header needs {}{needs})",
                    wanted.join(",")
                )));
            }
        }
    }
    if let Some((c, extra)) = names.iter().enumerate().find(|(_, c)| !wanted.contains(c)) {
        let hint = if !known_poses && pose_columns(motion).contains(&extra.as_str()) {
            "; pose columns need --known-poses"
        } else {
            ""
        };
        return Err(ApiError::invalid(format!(
            "{file}:{line}, column {}: unexpected column `{extra}` (expected {}{hint})",
            c + 1,
            wanted.join(",")
        )));
    }
    Ok(Header {
        names,
        wanted,
        index,
    })
}

/// The wanted values of one data row, checked finite.
fn read_row(file: &str, h: &Header, line: usize, row: &str) -> Result<Vec<f64>, ApiError> {
    let fields: Vec<&str> = row.split(',').map(str::trim).collect();
    if fields.len() != h.names.len() {
        return Err(ApiError::invalid(format!(
            "{file}:{line}: {} fields, the header has {} columns",
            fields.len(),
            h.names.len()
        )));
    }
    let mut values = Vec::with_capacity(h.wanted.len());
    for (w, &c) in h.wanted.iter().zip(&h.index) {
        let v: f64 = fields[c].parse().map_err(|_| {
            ApiError::invalid(format!(
                "{file}:{line}, column {} (`{w}`): `{}` is not a number",
                c + 1,
                fields[c]
            ))
        })?;
        if !v.is_finite() {
            return Err(ApiError::invalid(format!(
                "{file}:{line}, column {} (`{w}`): not a finite number ({v})",
                c + 1
            )));
        }
        values.push(v);
    }
    Ok(values)
}

/// Parses the samples CSV of a robot with `n` cables (see [`SamplesSource::Csv`]); errors name
/// `file`, the line and the column.
pub fn parse_samples_csv(
    text: &str,
    file: &str,
    motion: MotionPattern,
    n: usize,
    known_poses: bool,
) -> Result<Samples, ApiError> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let Some(first) = lines.next() else {
        return Err(ApiError::invalid(format!(
            "{file}: no header line (expected l1,…,l{n})"
        )));
    };
    let header = read_header(file, first, motion, n, known_poses)?;
    let dof = motion.dof();
    let (mut readings, mut poses) = (Vec::new(), Vec::new());
    for (line, row) in lines {
        let values = read_row(file, &header, line, row)?;
        if known_poses {
            poses.push(Pose::from_coordinates(motion, &values[..dof])?);
            readings.extend_from_slice(&values[dof..]);
        } else {
            readings.extend_from_slice(&values);
        }
    }
    if readings.is_empty() {
        return Err(ApiError::invalid(format!(
            "{file}: no samples after the header"
        )));
    }
    Ok(Samples {
        readings,
        poses: known_poses.then_some(poses),
    })
}

/// Samples given as arrays: rows of n readings and rows of DOF pose coordinates.
fn samples_from_arrays(
    readings: &[Vec<f64>],
    poses: Option<&[Vec<f64>]>,
    motion: MotionPattern,
    n: usize,
) -> Result<Samples, ApiError> {
    if let Some((k, r)) = readings.iter().enumerate().find(|(_, r)| r.len() != n) {
        return Err(ApiError::invalid(format!(
            "samples: row {} has {} readings, expected {n} (one per cable)",
            k + 1,
            r.len()
        )));
    }
    let poses = match poses {
        None => None,
        Some(p) if p.len() != readings.len() => {
            return Err(ApiError::invalid(format!(
                "known poses: {} rows for {} samples (one pose per sample)",
                p.len(),
                readings.len()
            )));
        }
        Some(p) => Some(
            p.iter()
                .map(|q| Pose::from_coordinates(motion, q))
                .collect::<Result<Vec<_>, _>>()?,
        ),
    };
    Ok(Samples {
        readings: readings.concat(),
        poses,
    })
}

/// The checked parts of a request.
struct Prepared {
    unknowns: Unknowns,
    samples: Samples,
    readings: Readings,
}

impl CalibrationRequest {
    /// A request with the default unknowns (`frame,offsets`) and absolute readings.
    pub fn new(robot: Robot, samples: SamplesSource) -> Self {
        Self {
            robot,
            samples,
            unknowns: default_unknowns(),
            relative: false,
            reference: None,
        }
    }

    /// The samples gave their poses.
    pub fn known_poses(&self) -> bool {
        match &self.samples {
            SamplesSource::Csv { known_poses, .. } => *known_poses,
            SamplesSource::Arrays { poses, .. } => poses.is_some(),
        }
    }

    /// Checks the request.
    pub fn validate(&self) -> Result<(), ApiError> {
        self.prepare().map(|_| ())
    }

    /// Checks the unknowns, the samples and the reference pose, in this order.
    fn prepare(&self) -> Result<Prepared, ApiError> {
        let robot = &self.robot.robot;
        let (motion, n) = (robot.motion(), robot.cable_count());
        let unknowns = Unknowns::parse(&self.unknowns)?;
        let samples = match &self.samples {
            SamplesSource::Csv {
                text,
                file,
                known_poses,
            } => {
                let file = file.as_deref().unwrap_or("samples.csv");
                parse_samples_csv(text, file, motion, n, *known_poses)?
            }
            SamplesSource::Arrays { readings, poses } => {
                samples_from_arrays(readings, poses.as_deref(), motion, n)?
            }
        };
        let readings = if self.relative {
            let q = match (&self.reference, &self.robot.home_pose) {
                (Some(q), _) | (None, Some(q)) => q.clone(),
                (None, None) => vec![0.0; motion.dof()],
            };
            Readings::Relative {
                reference: Pose::from_coordinates(motion, &q)?,
            }
        } else {
            Readings::Absolute
        };
        Ok(Prepared {
            unknowns,
            samples,
            readings,
        })
    }

    /// Calibrates.
    pub fn run(&self) -> Result<CalibrationReport, ApiError> {
        let p = self.prepare()?;
        let desc = self.robot.description();
        // A robot file written by `calibrate -o` holds calibrated encoders: start from them.
        let encoders = desc
            .encoders
            .clone()
            .unwrap_or_else(|| Encoders::identity(desc.robot.cable_count()));
        let cal = calibrate_with_encoders(
            &desc.robot,
            &encoders.offsets,
            &encoders.gains,
            &p.samples,
            p.unknowns,
            &p.readings,
        )?;
        Ok(self.report(cal))
    }

    fn report(&self, cal: Calibration) -> CalibrationReport {
        let desc = self.robot.description();
        let motion = desc.robot.motion();
        let dim = motion.space_dim();
        let points = |v: &[Vector3<f64>]| -> Vec<Vec<f64>> {
            v.iter()
                .map(|p| p.iter().take(dim).copied().collect())
                .collect()
        };
        let finite = |v: f64| v.is_finite().then_some(v);
        let sigma = |s: &ParameterSigma| SigmaReport {
            frame: s.frame.as_deref().map(points),
            platform: s.platform.as_deref().map(points),
            offsets: s.offsets.clone(),
            gains: s.gains.clone(),
        };
        let p = &cal.parameters;
        let n = desc.robot.cable_count();
        CalibrationReport {
            robot: desc.name.clone(),
            motion: motion.name().into(),
            samples: cal.counting.equations / n,
            cables: n,
            known_poses: self.known_poses(),
            relative: self.relative,
            unknowns: self.unknowns.split(',').map(|s| s.trim().into()).collect(),
            frame: points(&p.frame),
            platform: motion.has_orientation().then(|| points(&p.platform)),
            offsets: p.offsets.clone(),
            gains: p.gains.clone(),
            poses: cal
                .poses_estimated
                .then(|| cal.poses.iter().map(|x| x.coordinates(motion)).collect()),
            residual_rms: finite(cal.residual_rms),
            residual_max: finite(cal.residual_max),
            length_sigma: cal.length_sigma,
            sigma: cal.sigma.as_ref().map(sigma),
            identifiable: cal.identifiable,
            rank_deficiency: cal.rank_deficiency,
            condition_number: finite(cal.condition_number),
            parameters: cal.counting.parameters,
            gauge_count: cal.counting.gauge,
            gauge: cal.gauge.clone(),
            samples_needed: cal.counting.samples_needed,
            reason: cal.counting.reason.clone(),
            iterations: cal.iterations,
            converged: cal.converged,
            warnings: cal.warnings.clone(),
            calibration: cal,
        }
    }
}
