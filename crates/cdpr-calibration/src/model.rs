//! # Measurement model of cable-length calibration
//!
//! The true length of cable i at the pose x_k is the straight-cable length (thesis eqs.
//! (6.2)–(6.4)), and the encoder reads ρ_ki with
//!
//! ```text
//!   l_i(x_k; c_i, ā_i) = g_i ρ_ki + o_i                        (absolute readings)
//!   l_i(x_k; c_i, ā_i) = g_i ρ_ki + o_i + l_i(x_ref; c_i, ā_i)  (readings relative to x_ref)
//! ```
//!
//! with l_i(x; c, ā) = ‖c − p − R ā‖, the frame anchor c_i, the platform attachment ā_i, the
//! gain g_i (nominal 1) and the offset o_i (nominal 0). Relative readings are the Hangprinter
//! workflow: the encoders count from a reference pose (the homed pose), whose lengths follow
//! from the anchors. The residual of a reading is r_ki = l_i(x_k) − (model of the reading), and
//! its derivatives are
//!
//! ```text
//!   ∂r/∂c_i = u,   ∂r/∂ā_i = −Rᵀ u,   ∂r/∂o_i = −1,   ∂r/∂g_i = −ρ,   ∂r/∂x = −(u; b × u)
//! ```
//!
//! (u the unit vector from the attachment to the anchor, b = R ā, the pose twist as in the
//! forward kinematics: l̇ = −Wᵀ q̇), minus the same anchor/attachment derivatives at x_ref for
//! relative readings.
//!
//! Cables over swivel pulleys (Pott 2018) have the pulley model's length L = ρβ + l_f from the
//! point on the swivel axis (the cable's `frame`), with the pulleys held at their nominal radius
//! and orientation; the derivatives keep their form with u the free-segment direction (the arc
//! and swivel cancel from L̇, module `cdpr_kinematics::pulley`; moving the axis point moves the
//! whole pulley). The adjustment evaluates them with the kinematics of `cdpr-kinematics`.
//!
//! ## References
//! - Pott, *Cable-Driven Parallel Robots*, Springer 2018, ch. 4–5 (kinematic model and its
//!   calibration).
//! - Gouttefarde et al.'s thesis chapter on planar tendon-driven manipulators, eqs. (6.2)–(6.4).
//! - Pott, *Cable-Driven Parallel Robots: Theory and Application*, Springer 2018 (pulley
//!   kinematics).

use crate::CalibrationError;
use cdpr_kinematics::nalgebra::{Rotation3, Vector3};
use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};

/// Which parameter groups are unknown.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Unknowns {
    /// The frame anchors c_i.
    pub frame: bool,
    /// The platform attachments ā_i (planar and spatial robots).
    pub platform: bool,
    /// The length offsets o_i.
    pub offsets: bool,
    /// The encoder gains g_i.
    pub gains: bool,
}

impl Unknowns {
    /// Parses a comma-separated list of `frame`, `platform`, `offsets`, `gains`.
    ///
    /// ```
    /// let u = cdpr_calibration::Unknowns::parse("frame,offsets").unwrap();
    /// assert!(u.frame && u.offsets && !u.gains && !u.platform);
    /// assert!(cdpr_calibration::Unknowns::parse("anchors").is_err());
    /// ```
    pub fn parse(list: &str) -> Result<Self, CalibrationError> {
        let mut u = Self::default();
        for name in list.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            match name {
                "frame" => u.frame = true,
                "platform" => u.platform = true,
                "offsets" => u.offsets = true,
                "gains" => u.gains = true,
                other => return Err(CalibrationError::UnknownGroup(other.to_string())),
            }
        }
        if !(u.frame || u.platform || u.offsets || u.gains) {
            return Err(CalibrationError::NoUnknowns);
        }
        Ok(u)
    }

    /// Checks the groups against the motion pattern (no `platform` for point robots).
    pub fn check(&self, motion: MotionPattern) -> Result<(), CalibrationError> {
        if !(self.frame || self.platform || self.offsets || self.gains) {
            return Err(CalibrationError::NoUnknowns);
        }
        if self.platform && !motion.has_orientation() {
            return Err(CalibrationError::NoPlatform(motion.name()));
        }
        Ok(())
    }

    /// Unknown parameters of one cable for a robot moving in `dim` dimensions.
    pub fn per_cable(&self, dim: usize) -> usize {
        dim * (self.frame as usize + self.platform as usize)
            + self.offsets as usize
            + self.gains as usize
    }
}

/// The calibrated quantities: one entry per cable each.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameters {
    /// Frame anchors c_i (m, base frame; z = 0 in the plane).
    pub frame: Vec<Vector3<f64>>,
    /// Platform attachments ā_i (m, platform frame; zero for point robots).
    pub platform: Vec<Vector3<f64>>,
    /// Offsets o_i (m).
    pub offsets: Vec<f64>,
    /// Gains g_i (m per reading unit).
    pub gains: Vec<f64>,
}

impl Parameters {
    /// The robot's geometry with offsets 0 and gains 1.
    pub fn nominal(robot: &Robot) -> Self {
        let n = robot.cable_count();
        Self {
            frame: robot.cables().iter().map(|c| c.frame).collect(),
            platform: robot.cables().iter().map(|c| c.platform).collect(),
            offsets: vec![0.0; n],
            gains: vec![1.0; n],
        }
    }

    /// The robot with these anchors and attachments (straight cables).
    pub fn robot(&self, motion: MotionPattern) -> Result<Robot, CalibrationError> {
        let cables = self
            .frame
            .iter()
            .zip(&self.platform)
            .map(|(c, a)| Cable {
                frame: *c,
                platform: *a,
                pulley: None,
            })
            .collect();
        Ok(Robot::new(motion, cables)?)
    }
}

/// How the readings relate to the lengths.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Readings {
    /// l = g ρ + o.
    Absolute,
    /// l = g ρ + o + l(x_ref): readings count from the reference pose.
    Relative {
        /// The reference pose (the homed pose).
        reference: Pose,
    },
}

/// Measured samples: k rows of n readings, with the k poses when they are known (a tracker).
#[derive(Debug, Clone, PartialEq)]
pub struct Samples {
    /// Readings ρ_ki, sample after sample (k × n values).
    pub readings: Vec<f64>,
    /// The poses of the samples, when measured.
    pub poses: Option<Vec<Pose>>,
}

impl Samples {
    /// Checks the shapes and values against a robot with `n` cables; returns k.
    pub fn check(&self, n: usize) -> Result<usize, CalibrationError> {
        if self.readings.is_empty() {
            return Err(CalibrationError::NoSamples);
        }
        if !self.readings.len().is_multiple_of(n) {
            return Err(CalibrationError::WrongCount {
                what: format!("readings (a multiple of the {n} cables)"),
                expected: n * self.readings.len().div_ceil(n),
                found: self.readings.len(),
            });
        }
        let k = self.readings.len() / n;
        if let Some((i, &v)) = self
            .readings
            .iter()
            .enumerate()
            .find(|(_, v)| !v.is_finite())
        {
            return Err(CalibrationError::NotFinite {
                sample: i / n,
                what: format!("reading of cable {}", i % n + 1),
                value: v,
            });
        }
        if let Some(p) = &self.poses {
            if p.len() != k {
                return Err(CalibrationError::WrongCount {
                    what: "known poses (one per sample)".into(),
                    expected: k,
                    found: p.len(),
                });
            }
            for (s, pose) in p.iter().enumerate() {
                if let Some(&v) = pose
                    .position
                    .iter()
                    .chain(pose.rotation.matrix().iter())
                    .find(|v| !v.is_finite())
                {
                    return Err(CalibrationError::NotFinite {
                        sample: s,
                        what: "pose".into(),
                        value: v,
                    });
                }
            }
        }
        Ok(k)
    }
}

/// The straight-cable length of one cable at a pose and the unit vector and rotated attachment
/// that its derivatives need: (l, u, b = R ā).
#[inline]
pub(crate) fn cable(
    c: &Vector3<f64>,
    a: &Vector3<f64>,
    pose: &Pose,
) -> (f64, Vector3<f64>, Vector3<f64>) {
    let b = pose.rotation * a;
    let v = c - pose.position - b;
    let l = v.norm();
    (l, v / l, b)
}

/// The derivative of the length with respect to the pose twist, −(u; b × u) in the motion
/// pattern's twist order (position, then rotation).
pub(crate) fn pose_gradient(motion: MotionPattern, u: &Vector3<f64>, b: &Vector3<f64>) -> [f64; 6] {
    let m = b.cross(u);
    match motion {
        MotionPattern::Point2 => [-u.x, -u.y, 0.0, 0.0, 0.0, 0.0],
        MotionPattern::Planar => [-u.x, -u.y, -m.z, 0.0, 0.0, 0.0],
        MotionPattern::Point3 => [-u.x, -u.y, -u.z, 0.0, 0.0, 0.0],
        MotionPattern::Spatial => [-u.x, -u.y, -u.z, -m.x, -m.y, -m.z],
    }
}

/// x ⊕ δ: the pose moved by the twist δ (position, then base-frame rotation vector), as in the
/// forward kinematics.
pub(crate) fn displaced(motion: MotionPattern, pose: &Pose, delta: &[f64]) -> Pose {
    let (dp, w) = match motion {
        MotionPattern::Point2 => (Vector3::new(delta[0], delta[1], 0.0), None),
        MotionPattern::Planar => (
            Vector3::new(delta[0], delta[1], 0.0),
            Some(Vector3::new(0.0, 0.0, delta[2])),
        ),
        MotionPattern::Point3 => (Vector3::new(delta[0], delta[1], delta[2]), None),
        MotionPattern::Spatial => (
            Vector3::new(delta[0], delta[1], delta[2]),
            Some(Vector3::new(delta[3], delta[4], delta[5])),
        ),
    };
    let rotation = match w {
        Some(w) => Rotation3::new(w) * pose.rotation,
        None => pose.rotation,
    };
    Pose::new(pose.position + dp, rotation)
}

/// One reading's residual and what its derivatives need.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Reading {
    /// r = l(x) − model of the reading (m).
    pub residual: f64,
    /// The reading ρ.
    pub rho: f64,
    /// Unit vector from the attachment to the anchor at x.
    pub unit: Vector3<f64>,
    /// b = R ā at x.
    pub attachment: Vector3<f64>,
    /// The platform rotation at x.
    pub rotation: Rotation3<f64>,
    /// At the reference pose (relative readings): its unit vector and rotation.
    pub reference: Option<(Vector3<f64>, Rotation3<f64>)>,
}

/// The reading ρ of cable i at `pose` under `params`.
pub(crate) fn reading(
    params: &Parameters,
    readings: &Readings,
    i: usize,
    pose: &Pose,
    rho: f64,
) -> Reading {
    let (l, unit, attachment) = cable(&params.frame[i], &params.platform[i], pose);
    let mut model = params.gains[i] * rho + params.offsets[i];
    let reference = match readings {
        Readings::Absolute => None,
        Readings::Relative { reference } => {
            let (l_ref, u_ref, _) = cable(&params.frame[i], &params.platform[i], reference);
            model += l_ref;
            Some((u_ref, reference.rotation))
        }
    };
    Reading {
        residual: l - model,
        rho,
        unit,
        attachment,
        rotation: pose.rotation,
        reference,
    }
}

impl Reading {
    /// ∂r/∂θ for one free parameter of this reading's cable.
    pub(crate) fn derivative(&self, parameter: &crate::gauge::Parameter) -> f64 {
        use crate::gauge::Parameter;
        match *parameter {
            Parameter::Frame { direction, .. } => {
                let mut d = self.unit.dot(&direction);
                if let Some((u_ref, _)) = &self.reference {
                    d -= u_ref.dot(&direction);
                }
                d
            }
            Parameter::Platform { direction, .. } => {
                let mut d = -self.unit.dot(&(self.rotation * direction));
                if let Some((u_ref, r_ref)) = &self.reference {
                    d += u_ref.dot(&(r_ref * direction));
                }
                d
            }
            Parameter::Offset { .. } => -1.0,
            Parameter::Gain { .. } => -self.rho,
        }
    }
}
