//! # Robot files
//!
//! A robot is described in TOML. These keys are a public contract (more may be added):
//!
//! ```toml
//! name = "tdpm-4"                       # free text
//! motion = "planar"                     # point2 | planar | point3 | spatial
//! home_pose = [0.0, 0.0, 0.0]           # optional: a reference pose (motion-pattern coordinates)
//! [tension]
//! min = 5.0                             # t_min, all cables (a cable may override with min/max keys)
//! max = 100.0
//! [limits]                              # optional
//! min_cable_length = 0.1                # l_min, eq. (6.22)
//! min_jacobian_det = 1e-3               # D_min, eq. (6.24): |det J| >= D_min, only when n = DOF
//! [platform]                            # optional: mass (kg), centre of mass (platform frame), gravity
//! mass = 0.0
//! centre_of_mass = [0.0, 0.0]
//! gravity = [0.0, -9.80665]             # default: -z in space, -y in the plane
//! shape = { box = [0.2, 0.2, 0.1] }     # spatial only, optional: the platform as a convex
//!                                       # polyhedron (platform coordinates, m), for the
//!                                       # interference criterion; one of
//!                                       #   { box = [lx, ly, lz], centre = [x, y, z] } (centre optional)
//!                                       #   { vertices = [[x, y, z], ...] }  (their convex hull)
//!                                       #   "attachments"  (hull of the cables' platform attachments)
//! inertia = [[0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.2]]  # optional: about the centre of mass, kg m²
//! [[cables]]
//! name = "cable 1"                      # optional free text (names may repeat)
//! frame = [1.0, 0.5]                    # anchor on the fixed frame, base coordinates (2 or 3 numbers)
//! platform = [0.0707106781, 0.0707106781]   # attachment, platform coordinates (absent for point2/point3)
//! axial_stiffness = 60000.0             # optional E*S in N, for stiffness (and elastic cables)
//! linear_density = 0.02                 # optional mass per unstrained metre in kg/m (sagging cables)
//! offset = 0.0                          # optional encoder calibration (`cdpr calibrate -o`): the
//! gain = 1.0                            # true length is gain · reading + offset (offset in m,
//!                                       # default 0; gain in m per reading unit, default 1)
//! # optional swivel pulley at the frame (Pott 2018): `frame` is then the point a on its axis,
//! # where the cable arrives travelling along +axis; radius in m
//! pulley = { radius = 0.05, axis = [0.0, 0.0, 1.0] }
//! # or, to fix the zero of the swivel angle too, the rows of the pulley frame Q (third column =
//! # axis, first column = zero of the swivel angle; orthonormal to 1e-6):
//! # pulley = { radius = 0.05, orientation = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] }
//! # optional drive train (every cable or none): drum radius r (m), gear ratio G (motor turns
//! # per drum turn), rotor inertia J_m at the motor shaft (kg m²), and optional limits: motor
//! # torque (N m) and motor speed (rad/s)
//! winch = { drum_radius = 0.05, gear_ratio = 10.0, motor_inertia = 1.5e-4, max_torque = 3.0, max_speed = 600.0 }
//! ```
//!
//! `axis` has 3 numbers (2 are accepted for 2-D motion patterns, whose pulley axes lie in the
//! plane); with `axis` alone, Q is [`Pulley::from_axis`]. A file without `pulley` keys describes
//! straight cables exactly as before pulleys existed.
//!
//! Errors name the file, the line and the key. Exact duplicate cables only give a warning.

use cdpr_dynamics::Winch;
use cdpr_kinematics::{
    Cable, ConvexPolyhedron, KinematicsError, MotionPattern, Pose, Pulley, Robot,
};
use cdpr_tension::TensionBounds;
use cdpr_wrench::{PassiveSprings, Platform};
use nalgebra::{DVector, Matrix3, Vector3};
use serde::Deserialize;
use std::ops::Range;
use std::path::{Path, PathBuf};
use thiserror::Error;
use toml::Spanned;

/// A robot file that could not be read or is not valid.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum RobotFileError {
    /// The file could not be read.
    #[error("{file}: cannot read: {source}")]
    Io {
        /// The file.
        file: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The file is not valid TOML, or a key has the wrong type.
    #[error("{file}:{line}: {message}")]
    Syntax {
        /// The file.
        file: PathBuf,
        /// 1-based line (0 if unknown).
        line: usize,
        /// What the TOML reader said.
        message: String,
    },
    /// A key has an invalid value.
    #[error("{file}:{line}: `{key}`: {message}")]
    Invalid {
        /// The file.
        file: PathBuf,
        /// 1-based line.
        line: usize,
        /// The key, e.g. `cables[2].frame`.
        key: String,
        /// What is wrong.
        message: String,
    },
    /// An XML element or attribute (CASPR, WireCenter) is missing, malformed or invalid.
    #[error("{}:{line}: <{element}>{}: {message}", file.display(), attribute.as_ref().map(|a| format!(" attribute `{a}`")).unwrap_or_default())]
    Element {
        /// The file.
        file: PathBuf,
        /// 1-based line of the element (or attribute).
        line: usize,
        /// The element's tag name.
        element: String,
        /// The attribute, if the problem is one attribute.
        attribute: Option<String>,
        /// What is wrong.
        message: String,
    },
    /// The file describes something cdpr does not model (multi-body robots, VSD cables, ...).
    #[error("{}:{line}: <{element}>: not modelled by cdpr: {message}", file.display())]
    Unsupported {
        /// The file.
        file: PathBuf,
        /// 1-based line of the element.
        line: usize,
        /// The element's tag name.
        element: String,
        /// What it is and why it is not read.
        message: String,
    },
    /// The file name does not say which format it is in.
    #[error("{}: {message}", file.display())]
    Format {
        /// The file.
        file: PathBuf,
        /// What is wrong (expected extensions, missing companion file, ...).
        message: String,
    },
    /// The robot cannot be written in the requested format without losing a modelled number.
    #[error("{}: cannot write as {format}: {message}", file.display())]
    Unrepresentable {
        /// The file to be written.
        file: PathBuf,
        /// The format.
        format: &'static str,
        /// What the format cannot hold.
        message: String,
    },
}

/// Optional limits of the workspace definition (Table 6.4).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Limits {
    /// l_min of eq. (6.22).
    pub min_cable_length: Option<f64>,
    /// D_min of eq. (6.24) (applies when n = DOF).
    pub min_jacobian_det: Option<f64>,
}

/// The calibration of the cable-length encoders (per cable): the true length of cable i is
/// l_i = `gains[i]` · ρ_i + `offsets[i]` for the reading ρ_i (the measurement model of
/// `cdpr-calibration`). Robot-file keys `offset` and `gain` of each `[[cables]]` entry.
#[derive(Debug, Clone, PartialEq)]
pub struct Encoders {
    /// Length offsets o_i (m).
    pub offsets: Vec<f64>,
    /// Gains g_i (m per reading unit).
    pub gains: Vec<f64>,
}

impl Encoders {
    /// The identity (offset 0, gain 1) for `n` cables.
    pub fn identity(n: usize) -> Self {
        Self {
            offsets: vec![0.0; n],
            gains: vec![1.0; n],
        }
    }

    /// The true lengths g_i ρ_i + o_i of readings ρ.
    ///
    /// ```
    /// let e = cdpr_io::Encoders { offsets: vec![0.1, 0.0], gains: vec![1.0, 2.0] };
    /// assert_eq!(e.lengths(&[1.0, 1.5]), vec![1.1, 3.0]);
    /// ```
    pub fn lengths(&self, readings: &[f64]) -> Vec<f64> {
        readings
            .iter()
            .zip(self.offsets.iter().zip(&self.gains))
            .map(|(r, (o, g))| g * r + o)
            .collect()
    }
}

/// Everything a robot file describes.
#[derive(Debug, Clone, PartialEq)]
pub struct RobotDescription {
    /// Free-text name.
    pub name: String,
    /// Geometry.
    pub robot: Robot,
    /// Per-cable tension bounds.
    pub bounds: TensionBounds,
    /// Workspace limits.
    pub limits: Limits,
    /// Platform mass properties (gravity wrench).
    pub platform: Platform,
    /// Per-cable E·S (N), if every cable gives `axial_stiffness`.
    pub axial_stiffness: Option<Vec<f64>>,
    /// Per-cable mass per unstrained length ρ (kg/m), if every cable gives `linear_density`:
    /// the weight of a sagging cable (elastic catenary, Irvine 1981).
    pub linear_density: Option<Vec<f64>>,
    /// The platform as a convex polyhedron in platform coordinates (`[platform] shape`), for
    /// the cable–platform interference test.
    pub platform_shape: Option<ConvexPolyhedron>,
    /// Per-cable names as the file gives them (for display only: names may repeat, so cables are
    /// never looked up by name).
    pub cable_names: Vec<Option<String>>,
    /// Platform inertia tensor about the centre of mass in platform axes (kg·m²), if the file
    /// gives one.
    pub inertia: Option<Matrix3<f64>>,
    /// A reference pose in the motion pattern's coordinates, if the file gives one (CASPR's
    /// `q_initial`, TOML `home_pose`).
    pub home_pose: Option<Vec<f64>>,
    /// Per-cable winches (drum, gear, motor), if every cable gives `winch`: motor speeds and
    /// torques along timed trajectories ([`cdpr_dynamics::drive_train()`]).
    pub winches: Option<Vec<Winch>>,
    /// Passive springs (CASPR's `cable_passive_linear_spring`, TOML `[[passive_springs]]`):
    /// not actuated, their force K (l − l₀) at each pose adds to the external wrench (see
    /// [`RobotDescription::load_wrench`]).
    pub passive_springs: Option<PassiveSprings>,
    /// Per-spring names as the file gives them (display only).
    pub passive_spring_names: Vec<Option<String>>,
    /// The encoders' offsets and gains, if any cable gives `offset` or `gain` (the others then
    /// have offset 0 and gain 1): written by `cdpr calibrate -o`.
    pub encoders: Option<Encoders>,
    /// Non-fatal remarks (e.g. duplicate cables).
    pub warnings: Vec<String>,
}

impl RobotDescription {
    /// The wrench the robot file itself puts on the platform at `pose` (N, N·m): the platform's
    /// weight ([`Platform::gravity_wrench`]) plus the passive springs' forces
    /// ([`PassiveSprings::wrench`]); the actuated cables balance W t + w_e + this = 0.
    pub fn load_wrench(&self, pose: &Pose) -> Result<DVector<f64>, KinematicsError> {
        let motion = self.robot.motion();
        let mut w = self.platform.gravity_wrench(motion, pose);
        if let Some(springs) = &self.passive_springs {
            w += springs.wrench(pose)?;
        }
        Ok(w)
    }

    /// A usage error naming `analysis` when the robot has passive springs: their wrench
    /// depends on the pose, so an analysis that keeps one external wrench over many poses
    /// would leave them out.
    pub fn require_no_passive_springs(&self, analysis: &str) -> Result<(), String> {
        match &self.passive_springs {
            Some(s) => Err(format!(
                "{analysis} keeps one external wrench over its poses, but this robot has {} passive spring(s) whose force K (l − l0) changes with the pose: not modelled there (tension, capacity, isotropic and trajectory include them pose by pose)",
                s.count()
            )),
            None => Ok(()),
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    name: Option<String>,
    motion: Spanned<String>,
    home_pose: Option<Spanned<Vec<f64>>>,
    tension: Spanned<RawTension>,
    limits: Option<RawLimits>,
    platform: Option<RawPlatform>,
    cables: Spanned<Vec<Spanned<RawCable>>>,
    passive_springs: Option<Spanned<Vec<Spanned<RawSpring>>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSpring {
    name: Option<String>,
    frame: Spanned<Vec<f64>>,
    platform: Option<Spanned<Vec<f64>>>,
    stiffness: Spanned<f64>,
    free_length: Spanned<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTension {
    min: Spanned<f64>,
    max: Spanned<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLimits {
    min_cable_length: Option<Spanned<f64>>,
    min_jacobian_det: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPlatform {
    mass: Option<Spanned<f64>>,
    #[serde(alias = "center_of_mass")]
    centre_of_mass: Option<Spanned<Vec<f64>>>,
    gravity: Option<Spanned<Vec<f64>>>,
    inertia: Option<Spanned<Vec<Vec<f64>>>>,
    shape: Option<Spanned<RawShape>>,
}

#[derive(Deserialize)]
#[serde(untagged)]
enum RawShape {
    Named(String),
    Table(RawShapeTable),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawShapeTable {
    #[serde(rename = "box")]
    cuboid: Option<Vec<f64>>,
    #[serde(alias = "center")]
    centre: Option<Vec<f64>>,
    vertices: Option<Vec<Vec<f64>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCable {
    name: Option<String>,
    frame: Spanned<Vec<f64>>,
    platform: Option<Spanned<Vec<f64>>>,
    axial_stiffness: Option<Spanned<f64>>,
    linear_density: Option<Spanned<f64>>,
    offset: Option<Spanned<f64>>,
    gain: Option<Spanned<f64>>,
    min: Option<Spanned<f64>>,
    max: Option<Spanned<f64>>,
    pulley: Option<Spanned<RawPulley>>,
    winch: Option<Spanned<RawWinch>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawWinch {
    drum_radius: f64,
    gear_ratio: f64,
    motor_inertia: f64,
    max_torque: Option<f64>,
    max_speed: Option<f64>,
    cable_diameter: Option<f64>,
    /// Read as any value so that a non-integer is named by its key.
    turns_per_layer: Option<toml::Value>,
    cable_length: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPulley {
    radius: Spanned<f64>,
    axis: Option<Spanned<Vec<f64>>>,
    orientation: Option<Spanned<Vec<Vec<f64>>>>,
}

struct Ctx<'a> {
    file: &'a Path,
    text: &'a str,
}

impl Ctx<'_> {
    fn line(&self, span: Range<usize>) -> usize {
        self.text[..span.start.min(self.text.len())]
            .matches('\n')
            .count()
            + 1
    }
    fn invalid(
        &self,
        span: Range<usize>,
        key: impl Into<String>,
        message: impl Into<String>,
    ) -> RobotFileError {
        RobotFileError::Invalid {
            file: self.file.to_path_buf(),
            line: self.line(span),
            key: key.into(),
            message: message.into(),
        }
    }
    /// The frame point and platform attachment of a cable or spring (`key("frame")`, …).
    fn attachments(
        &self,
        frame: &Spanned<Vec<f64>>,
        platform: Option<&Spanned<Vec<f64>>>,
        key: &dyn Fn(&str) -> String,
        motion: MotionPattern,
    ) -> Result<(Vector3<f64>, Vector3<f64>), RobotFileError> {
        let dim = motion.space_dim();
        let a = self.vector(frame, &key("frame"), dim, motion)?;
        let b = match (platform, motion.has_orientation()) {
            (Some(p), true) => self.vector(p, &key("platform"), dim, motion)?,
            (None, true) => {
                return Err(self.invalid(
                    frame.span(),
                    key("platform"),
                    format!("missing: a `{motion}` robot needs every platform attachment"),
                ));
            }
            (Some(p), false) => {
                let v = self.vector(p, &key("platform"), dim, motion)?;
                if v != Vector3::zeros() {
                    return Err(self.invalid(
                        p.span(),
                        key("platform"),
                        format!(
                            "a `{motion}` platform is a point: attachments must be absent or zero"
                        ),
                    ));
                }
                v
            }
            (None, false) => Vector3::zeros(),
        };
        Ok((a, b))
    }

    fn finite(&self, v: &Spanned<f64>, key: &str) -> Result<f64, RobotFileError> {
        let x = *v.get_ref();
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.invalid(v.span(), key, format!("{x} is not a finite number")))
        }
    }
    /// A t_max: finite, or `inf` (an unlimited cable; TOML spells it `inf`).
    fn upper_bound(&self, v: &Spanned<f64>, key: &str) -> Result<f64, RobotFileError> {
        let x = *v.get_ref();
        if x.is_finite() || x == f64::INFINITY {
            Ok(x)
        } else {
            Err(self.invalid(
                v.span(),
                key,
                format!("{x} is not a number of newtons (finite, or inf for no upper limit)"),
            ))
        }
    }
    fn non_negative(&self, v: &Spanned<f64>, key: &str) -> Result<f64, RobotFileError> {
        let x = self.finite(v, key)?;
        if x >= 0.0 {
            Ok(x)
        } else {
            Err(self.invalid(v.span(), key, format!("{x} is negative")))
        }
    }
    fn vector(
        &self,
        v: &Spanned<Vec<f64>>,
        key: &str,
        dim: usize,
        motion: MotionPattern,
    ) -> Result<Vector3<f64>, RobotFileError> {
        let x = v.get_ref();
        if x.len() != dim {
            return Err(self.invalid(
                v.span(),
                key,
                format!("has {} numbers, motion `{motion}` needs {dim}", x.len()),
            ));
        }
        if let Some(bad) = x.iter().find(|a| !a.is_finite()) {
            return Err(self.invalid(v.span(), key, format!("{bad} is not a finite number")));
        }
        Ok(Vector3::new(x[0], x[1], if dim == 3 { x[2] } else { 0.0 }))
    }
    fn matrix(
        &self,
        v: &Spanned<Vec<Vec<f64>>>,
        key: &str,
    ) -> Result<Matrix3<f64>, RobotFileError> {
        let rows = v.get_ref();
        if rows.len() != 3 || rows.iter().any(|r| r.len() != 3) {
            return Err(self.invalid(v.span(), key, "must be 3 rows of 3 numbers"));
        }
        if let Some(bad) = rows.iter().flatten().find(|a| !a.is_finite()) {
            return Err(self.invalid(v.span(), key, format!("{bad} is not a finite number")));
        }
        Ok(Matrix3::from_fn(|i, j| rows[i][j]))
    }
}

/// The dotted key of the `key = value` line holding byte `offset` of `text`, with its table:
/// `tension.max`, `cables[2].frame` (cables counted from 1); `None` off such a line.
fn key_at(text: &str, offset: usize) -> Option<String> {
    let offset = offset.min(text.len());
    let start = text[..offset].rfind('\n').map_or(0, |i| i + 1);
    let line = text[start..].lines().next()?;
    let (key, _) = line.split_once('=')?;
    let key = key.trim().trim_matches('"');
    if key.is_empty() || key.starts_with('[') || key.starts_with('#') {
        return None;
    }
    let mut table = None;
    let mut cables = 0;
    for l in text[..start].lines() {
        let l = l.trim();
        if let Some(name) = l.strip_prefix("[[").and_then(|r| r.split_once("]]")) {
            let name = name.0.trim().to_string();
            if name == "cables" {
                cables += 1;
                table = Some(format!("cables[{cables}]"));
            } else {
                table = Some(name);
            }
        } else if let Some(name) = l.strip_prefix('[').and_then(|r| r.split_once(']')) {
            table = Some(name.0.trim().to_string());
        }
    }
    Some(match table {
        Some(t) => format!("{t}.{key}"),
        None => key.to_string(),
    })
}

impl Ctx<'_> {
    /// The pulley of `cables[i]`, with errors naming its keys.
    fn pulley(
        &self,
        raw: &Spanned<RawPulley>,
        key: &str,
        motion: MotionPattern,
    ) -> Result<Pulley, RobotFileError> {
        let p = raw.get_ref();
        let radius = self.finite(&p.radius, &format!("{key}.radius"))?;
        if radius <= 0.0 {
            return Err(self.invalid(
                p.radius.span(),
                format!("{key}.radius"),
                format!("{radius} must be positive (m)"),
            ));
        }
        match (&p.axis, &p.orientation) {
            (Some(a), None) => {
                let k = format!("{key}.axis");
                let x = a.get_ref();
                let axis = if x.len() == 3 || x.len() == motion.space_dim() {
                    self.vector(a, &k, x.len(), motion)?
                } else {
                    return Err(self.invalid(
                        a.span(),
                        k,
                        format!("has {} numbers, an axis needs 3", x.len()),
                    ));
                };
                if axis.norm() == 0.0 {
                    return Err(self.invalid(a.span(), k, "is the zero vector"));
                }
                Ok(Pulley::from_axis(radius, axis))
            }
            (None, Some(o)) => {
                let k = format!("{key}.orientation");
                let rows = o.get_ref();
                if rows.len() != 3 || rows.iter().any(|r| r.len() != 3) {
                    return Err(self.invalid(
                        o.span(),
                        k,
                        "must be 3 rows of 3 numbers (the rows of Q)",
                    ));
                }
                if let Some(bad) = rows.iter().flatten().find(|v| !v.is_finite()) {
                    return Err(self.invalid(o.span(), k, format!("{bad} is not a finite number")));
                }
                Ok(Pulley {
                    radius,
                    orientation: Matrix3::from_fn(|i, j| rows[i][j]),
                })
            }
            (Some(_), Some(_)) => Err(self.invalid(
                raw.span(),
                key,
                "give either `axis` or `orientation`, not both",
            )),
            (None, None) => Err(self.invalid(
                raw.span(),
                key,
                "needs `axis = [x, y, z]` or `orientation = [[..], [..], [..]]` beside `radius`",
            )),
        }
    }
}

/// A pulley as the inline table of the robot-file key `pulley` (radius and the rows of Q, with
/// Rust's shortest round-trip formatting, so that reading it back gives the same numbers).
///
/// ```
/// use cdpr_io::pulley_toml;
/// use cdpr_kinematics::Pulley;
/// use nalgebra::Vector3;
/// let p = Pulley::from_axis(0.05, Vector3::z());
/// assert_eq!(
///     pulley_toml(&p),
///     "{ radius = 0.05, orientation = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] }"
/// );
/// ```
pub fn pulley_toml(pulley: &Pulley) -> String {
    let q = &pulley.orientation;
    let rows: Vec<String> = (0..3)
        .map(|i| format!("[{:?}, {:?}, {:?}]", q[(i, 0)], q[(i, 1)], q[(i, 2)]))
        .collect();
    format!(
        "{{ radius = {:?}, orientation = [{}] }}",
        pulley.radius,
        rows.join(", ")
    )
}

impl RobotDescription {
    /// Reads and validates a cdpr TOML robot file.
    pub(crate) fn load_toml(path: &Path) -> Result<Self, RobotFileError> {
        let text = std::fs::read_to_string(path).map_err(|source| RobotFileError::Io {
            file: path.to_path_buf(),
            source,
        })?;
        Self::parse(&text, path)
    }

    /// Parses and validates robot-file text; `file` names it in error messages.
    ///
    /// ```
    /// use cdpr_io::RobotDescription;
    /// let text = r#"
    /// motion = "point2"
    /// [tension]
    /// min = 50.0
    /// max = 500.0
    /// [[cables]]
    /// frame = [1.0, 0.0]
    /// [[cables]]
    /// frame = [-0.5, 0.866]
    /// [[cables]]
    /// frame = [-0.5, -0.866]
    /// "#;
    /// let robot = RobotDescription::parse(text, "inline.toml").unwrap();
    /// assert_eq!(robot.robot.cable_count(), 3);
    /// let err = RobotDescription::parse(&text.replace("500.0", "5.0"), "inline.toml").unwrap_err();
    /// assert!(err.to_string().starts_with("inline.toml:"));
    /// ```
    pub fn parse(text: &str, file: impl AsRef<Path>) -> Result<Self, RobotFileError> {
        let ctx = Ctx {
            file: file.as_ref(),
            text,
        };
        let raw: RawFile = toml::from_str(text).map_err(|e| {
            let message = e.message().trim().to_string();
            match e.span().and_then(|s| key_at(text, s.start).map(|k| (s, k))) {
                // A value of the wrong type: name its key.
                Some((span, key)) => ctx.invalid(span, key, message),
                None => RobotFileError::Syntax {
                    file: ctx.file.to_path_buf(),
                    line: e.span().map(|s| ctx.line(s)).unwrap_or(0),
                    message,
                },
            }
        })?;
        let motion: MotionPattern =
            raw.motion.get_ref().parse().map_err(|e: KinematicsError| {
                ctx.invalid(raw.motion.span(), "motion", e.to_string())
            })?;
        let dim = motion.space_dim();
        let t_min = ctx.finite(&raw.tension.get_ref().min, "tension.min")?;
        let t_max = ctx.upper_bound(&raw.tension.get_ref().max, "tension.max")?;
        if t_min < 0.0 {
            return Err(ctx.invalid(
                raw.tension.get_ref().min.span(),
                "tension.min",
                negative_t_min(t_min),
            ));
        }
        if t_min > t_max {
            return Err(ctx.invalid(
                raw.tension.get_ref().min.span(),
                "tension.min",
                format!("t_min = {t_min} exceeds t_max = {t_max}"),
            ));
        }
        let mut warnings = Vec::new();
        let cables_raw = raw.cables.get_ref();
        let (mut cables, mut mins, mut maxs, mut stiff, mut names) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let mut density = Vec::new();
        let mut winches = Vec::new();
        let mut encoders = Encoders::identity(cables_raw.len());
        let mut has_encoders = false;
        for (i, c) in cables_raw.iter().enumerate() {
            let key = |k: &str| format!("cables[{}].{k}", i + 1);
            let c = c.get_ref();
            let (frame, platform) = ctx.attachments(&c.frame, c.platform.as_ref(), &key, motion)?;
            let pulley = c
                .pulley
                .as_ref()
                .map(|p| ctx.pulley(p, &key("pulley"), motion))
                .transpose()?;
            cables.push(Cable {
                frame,
                platform,
                pulley,
            });
            names.push(c.name.clone());
            let lo = c
                .min
                .as_ref()
                .map(|v| ctx.finite(v, &key("min")))
                .transpose()?
                .unwrap_or(t_min);
            let hi = c
                .max
                .as_ref()
                .map(|v| ctx.upper_bound(v, &key("max")))
                .transpose()?
                .unwrap_or(t_max);
            if let (true, Some(min)) = (lo < 0.0, &c.min) {
                return Err(ctx.invalid(min.span(), key("min"), negative_t_min(lo)));
            }
            if lo > hi {
                let span = c
                    .min
                    .as_ref()
                    .or(c.max.as_ref())
                    .map(|s| s.span())
                    .unwrap_or(c.frame.span());
                return Err(ctx.invalid(
                    span,
                    key("min"),
                    format!("t_min = {lo} exceeds t_max = {hi}"),
                ));
            }
            mins.push(lo);
            maxs.push(hi);
            if let Some(es) = &c.axial_stiffness {
                let v = ctx.finite(es, &key("axial_stiffness"))?;
                if v <= 0.0 {
                    return Err(ctx.invalid(
                        es.span(),
                        key("axial_stiffness"),
                        format!("{v} must be positive"),
                    ));
                }
                stiff.push(v);
            }
            if let Some(rho) = &c.linear_density {
                let v = ctx.finite(rho, &key("linear_density"))?;
                if v < 0.0 {
                    return Err(ctx.invalid(
                        rho.span(),
                        key("linear_density"),
                        format!("{v} must not be negative (kg/m)"),
                    ));
                }
                density.push(v);
            }
            if let Some(w) = &c.winch {
                let r = w.get_ref();
                let winch = Winch::new(
                    r.drum_radius,
                    r.gear_ratio,
                    r.motor_inertia,
                    r.max_torque,
                    r.max_speed,
                )
                .and_then(|w| w.with_cable_diameter(r.cable_diameter))
                .and_then(|w| {
                    let turns = match &r.turns_per_layer {
                        None => None,
                        Some(v) => Some(
                            v.as_integer()
                                .and_then(|n| u32::try_from(n).ok())
                                .ok_or_else(|| cdpr_dynamics::DynamicsError::BadSetting {
                                    key: "winch.turns_per_layer".into(),
                                    value: v.as_integer().map_or_else(
                                        || v.as_float().unwrap_or(f64::NAN),
                                        |n| n as f64,
                                    ),
                                    why: "must be an integer from 1 to 4294967295 (turns)".into(),
                                })?,
                        ),
                    };
                    w.with_layers(turns, r.cable_length)
                })
                .map_err(|e| match e {
                    cdpr_dynamics::DynamicsError::BadSetting { key: k, value, why } => {
                        ctx.invalid(w.span(), key(&k), format!("{value} {why}"))
                    }
                    e => ctx.invalid(w.span(), key("winch"), e.to_string()),
                })?;
                winches.push(winch);
            }
            if let Some(o) = &c.offset {
                encoders.offsets[i] = ctx.finite(o, &key("offset"))?;
                has_encoders = true;
            }
            if let Some(g) = &c.gain {
                let v = ctx.finite(g, &key("gain"))?;
                if v == 0.0 {
                    return Err(ctx.invalid(
                        g.span(),
                        key("gain"),
                        "is zero: the length would not depend on the reading",
                    ));
                }
                encoders.gains[i] = v;
                has_encoders = true;
            }
        }
        let axial_stiffness = match stiff.len() {
            0 => None,
            n if n == cables.len() => Some(stiff),
            _ => {
                return Err(ctx.invalid(
                    raw.cables.span(),
                    "cables.axial_stiffness",
                    "given for some cables but not all",
                ));
            }
        };
        let linear_density = match density.len() {
            0 => None,
            n if n == cables.len() => Some(density),
            _ => {
                return Err(ctx.invalid(
                    raw.cables.span(),
                    "cables.linear_density",
                    "given for some cables but not all",
                ));
            }
        };
        let winches = match winches.len() {
            0 => None,
            n if n == cables.len() => Some(winches),
            _ => {
                return Err(ctx.invalid(
                    raw.cables.span(),
                    "cables.winch",
                    "given for some cables but not all",
                ));
            }
        };
        let robot = Robot::new(motion, cables).map_err(|e| match e {
            KinematicsError::InvalidPulley { cable, .. } => {
                let span = cables_raw[cable]
                    .get_ref()
                    .pulley
                    .as_ref()
                    .map_or(raw.cables.span(), |p| p.span());
                ctx.invalid(span, format!("cables[{}].pulley", cable + 1), e.to_string())
            }
            e => ctx.invalid(raw.cables.span(), "cables", e.to_string()),
        })?;
        for (i, j) in robot.duplicate_cables() {
            warnings.push(format!(
                "cables {} and {} are exact duplicates (same anchor and attachment)",
                i + 1,
                j + 1
            ));
        }
        let limits = match &raw.limits {
            None => Limits::default(),
            Some(l) => Limits {
                min_cable_length: l
                    .min_cable_length
                    .as_ref()
                    .map(|v| ctx.non_negative(v, "limits.min_cable_length"))
                    .transpose()?,
                min_jacobian_det: l
                    .min_jacobian_det
                    .as_ref()
                    .map(|v| ctx.non_negative(v, "limits.min_jacobian_det"))
                    .transpose()?,
            },
        };
        let mut platform = Platform::default();
        if dim == 2 {
            platform.gravity = Vector3::new(0.0, -cdpr_wrench::STANDARD_GRAVITY.z.abs(), 0.0);
        }
        if let Some(p) = &raw.platform {
            if let Some(m) = &p.mass {
                platform.mass = ctx.non_negative(m, "platform.mass")?;
            }
            if let Some(c) = &p.centre_of_mass {
                platform.centre_of_mass = ctx.vector(c, "platform.centre_of_mass", dim, motion)?;
            }
            if let Some(g) = &p.gravity {
                platform.gravity = ctx.vector(g, "platform.gravity", dim, motion)?;
            }
        }
        let platform_shape = match raw.platform.as_ref().and_then(|p| p.shape.as_ref()) {
            None => None,
            Some(shape) => Some(platform_shape(&ctx, shape, &robot, &mut warnings)?),
        };
        let inertia = match raw.platform.as_ref().and_then(|p| p.inertia.as_ref()) {
            None => None,
            Some(m) => {
                let i = ctx.matrix(m, "platform.inertia")?;
                if (i - i.transpose()).amax() > 1e-12 * i.amax().max(1.0) {
                    let rows: Vec<String> = i
                        .row_iter()
                        .map(|r| {
                            let v: Vec<String> = r.iter().map(|x| format!("{x:?}")).collect();
                            format!("[{}]", v.join(", "))
                        })
                        .collect();
                    let value = format!("[{}]", rows.join(", "));
                    return Err(ctx.invalid(
                        m.span(),
                        "platform.inertia",
                        format!("{value} (kg·m²) is not symmetric"),
                    ));
                }
                Some(i)
            }
        };
        let home_pose = match &raw.home_pose {
            None => None,
            Some(q) => {
                cdpr_kinematics::Pose::from_coordinates(motion, q.get_ref())
                    .map_err(|e| ctx.invalid(q.span(), "home_pose", e.to_string()))?;
                Some(q.get_ref().clone())
            }
        };
        let bounds = TensionBounds::new(mins, maxs)
            .map_err(|e| ctx.invalid(raw.tension.span(), "tension", e.to_string()))?;
        let (passive_springs, passive_spring_names) = match &raw.passive_springs {
            None => (None, Vec::new()),
            Some(list) => {
                let (mut attach, mut ks, mut l0s, mut names) =
                    (Vec::new(), Vec::new(), Vec::new(), Vec::new());
                for (j, sp) in list.get_ref().iter().enumerate() {
                    let key = |k: &str| format!("passive_springs[{}].{k}", j + 1);
                    let sp = sp.get_ref();
                    let (frame, platform) =
                        ctx.attachments(&sp.frame, sp.platform.as_ref(), &key, motion)?;
                    attach.push(Cable::new(frame, platform));
                    let k = ctx.finite(&sp.stiffness, &key("stiffness"))?;
                    if k <= 0.0 {
                        return Err(ctx.invalid(
                            sp.stiffness.span(),
                            key("stiffness"),
                            format!("{k} N/m must be positive"),
                        ));
                    }
                    ks.push(k);
                    l0s.push(ctx.non_negative(&sp.free_length, &key("free_length"))?);
                    names.push(sp.name.clone());
                }
                let invalid = |e: String| ctx.invalid(list.span(), "passive_springs", e);
                let geometry = Robot::new(motion, attach).map_err(|e| invalid(e.to_string()))?;
                let springs =
                    PassiveSprings::new(geometry, ks, l0s).map_err(|e| invalid(e.to_string()))?;
                (Some(springs), names)
            }
        };
        Ok(Self {
            name: raw.name.unwrap_or_else(|| {
                ctx.file
                    .file_stem()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_default()
            }),
            robot,
            bounds,
            limits,
            platform,
            axial_stiffness,
            linear_density,
            platform_shape,
            cable_names: names,
            inertia,
            home_pose,
            winches,
            passive_springs,
            passive_spring_names,
            encoders: has_encoders.then_some(encoders),
            warnings,
        })
    }
}

/// `[platform] shape`: a box, the hull of given vertices, or the hull of the attachments.
fn platform_shape(
    ctx: &Ctx<'_>,
    shape: &Spanned<RawShape>,
    robot: &Robot,
    warnings: &mut Vec<String>,
) -> Result<ConvexPolyhedron, RobotFileError> {
    let key = "platform.shape";
    let bad = |m: String| ctx.invalid(shape.span(), key, m);
    if robot.motion() != MotionPattern::Spatial {
        return Err(bad(format!(
            "a platform shape is a convex polyhedron in space: `spatial` robots only, this one is \
             `{}`",
            robot.motion()
        )));
    }
    let triple = |v: &[f64], what: &str| -> Result<nalgebra::Vector3<f64>, RobotFileError> {
        match v {
            [x, y, z] if v.iter().all(|a| a.is_finite()) => Ok(nalgebra::Vector3::new(*x, *y, *z)),
            [_, _, _] => Err(bad(format!("{what}: not finite numbers"))),
            _ => Err(bad(format!("{what} needs 3 numbers, got {}", v.len()))),
        }
    };
    let hull = match shape.get_ref() {
        RawShape::Named(n) if n == "attachments" => {
            let points: Vec<_> = robot.cables().iter().map(|c| c.platform).collect();
            ConvexPolyhedron::from_points(&points)
        }
        RawShape::Named(n) => {
            return Err(bad(format!(
                "unknown shape `{n}` (expected \"attachments\", {{ box = [lx, ly, lz] }} or \
                 {{ vertices = [[x, y, z], ...] }})"
            )));
        }
        RawShape::Table(t) => match (&t.cuboid, &t.vertices) {
            (Some(b), None) => {
                let centre = match &t.centre {
                    Some(c) => triple(c, "centre")?,
                    None => nalgebra::Vector3::zeros(),
                };
                ConvexPolyhedron::cuboid(triple(b, "box")?, centre)
            }
            (None, Some(vs)) => {
                if t.centre.is_some() {
                    return Err(bad("`centre` goes with `box`, not with `vertices`".into()));
                }
                let points = vs
                    .iter()
                    .enumerate()
                    .map(|(k, v)| triple(v, &format!("vertex {}", k + 1)))
                    .collect::<Result<Vec<_>, _>>()?;
                ConvexPolyhedron::from_points(&points)
            }
            _ => {
                return Err(bad(
                    "give exactly one of `box = [lx, ly, lz]` or `vertices = [[x, y, z], ...]`"
                        .into(),
                ));
            }
        },
    }
    .map_err(|e| bad(e.to_string()))?;
    let tol = 1e-9 * hull.size();
    for (i, c) in robot.cables().iter().enumerate() {
        if hull.depth(&c.platform) > tol {
            warnings.push(format!(
                "cable {}'s platform attachment lies inside the platform shape: the cable always \
                 passes through the platform (attachments belong on its surface)",
                i + 1
            ));
        }
    }
    Ok(hull)
}
/// The error of a negative lower tension bound: a cable only pulls.
fn negative_t_min(t_min: f64) -> String {
    format!("t_min = {t_min} N is negative: a cable can only pull (t_min ≥ 0)")
}
