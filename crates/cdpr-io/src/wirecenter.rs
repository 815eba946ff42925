//! # WireCenter robot files (`.wcrfx`)
//!
//! The XML robot files of WireCenter / WireLib (Pott 2018), versions 0.31 and 0.32:
//!
//! | `.wcrfx` | cdpr |
//! |---|---|
//! | `<robot motionpattern>` 3R3T / 1R2T / 2T / 3T | `spatial` / `planar` / `point2` / `point3` (others: an error) |
//! | `<chain id>` | one cable; `id` kept as its name (ids may repeat) |
//! | `<base x y z a11 … a33 radius>` | frame anchor **a**, pulley frame Q = (a_ij) as written, pulley radius ρ (none if 0) |
//! | `<platform x y z>` in a chain | platform attachment |
//! | `<robot><platform mass>`, `<centerofgravity>`, `<inertiatensor>` | platform mass, centre of mass, inertia |
//! | `<application min_cable_load max_cable_load>` | tension bounds of every cable |
//! | `<cable elasticity radius>` | axial stiffness E·S = E π r² (WireLib's `Kinematics.cpp`) |
//! | `<cable weight>` | linear density ρ (kg/m) of every cable (sagging cables) |
//! | `<winch>`: `<drum r_drum>`, `<motor gear_ratio inertia angular_velocity>`, `<cable max_velocity>` | every cable's `winch`: drum radius r (m), gear ratio G, motor inertia (kg·m²); max_speed (rad/s) = the smaller of the motor's `angular_velocity` (rpm) and the winch cable's `max_velocity` (m/s) × G/r, where given (> 0); no max_torque (the file has none) |
//!
//! WireLib's gravity is 9.81 m/s² along −z; the file has no gravity entry, so a converted robot
//! states it. Orientation matrices are used as written (some files store 0.707107; they are not
//! re-orthonormalised: lengths equal WireLib's, cable directions differ by the frame's deviation
//! from orthonormality, see docs/robot-file.md, "Pulley frames that are not orthonormal"). A `3R3T` file whose anchors all lie in
//! z = 0 (2DIPAnema2) is spatial, as declared. WireLib applies its pulley model to 3R3T robots
//! only: pulleys of planar files are not read (a warning says so).
//!
//! Tension bounds: `<application>` if present; otherwise the winch's `f_max` (with the cable's
//! `minimum_load`); otherwise WireLib's defaults 1–10 N. A warning names the source.
//!
//! ## References
//! - Pott, *Cable-Driven Parallel Robots: Theory and Application*, Springer 2018.
//! - WireX / WireLib (Pott, MIT licence): `RobotData.cpp` (file layout), `Kinematics.cpp`
//!   (`doInverseKinematicsPulleyEx`: pulley frame, E π r² stiffness).

use crate::xml::XmlFile;
use crate::{RobotDescription, RobotFileError};
use cdpr_kinematics::{Cable, MotionPattern, Pulley, Robot};
use cdpr_tension::TensionBounds;
use cdpr_wrench::Platform;
use nalgebra::{Matrix3, Vector3};
use roxmltree::Node;
use std::fmt::Write;
use std::path::Path;

/// WireLib's gravitational acceleration (m/s²), along −z.
pub const WIRELIB_GRAVITY: f64 = 9.81;

/// WireLib's default tension bounds (N) when a file gives none.
pub const WIRELIB_DEFAULT_BOUNDS: (f64, f64) = (1.0, 10.0);

/// WireLib's default pulley radius (m) when a `<base>` gives none.
pub const WIRELIB_DEFAULT_PULLEY_RADIUS: f64 = 0.1;

/// Every cable's winch from the file's `<winch>` (one winch type for all cables), if it has
/// a `<drum>` with a positive `r_drum` and a `<motor>` with a positive `gear_ratio`.
fn winches(
    x: &XmlFile,
    root: Node,
    n: usize,
) -> Result<Option<Vec<cdpr_dynamics::Winch>>, RobotFileError> {
    let Some(winch) = XmlFile::elements(root).find(|e| e.has_tag_name("winch")) else {
        return Ok(None);
    };
    let child = |tag: &str| XmlFile::elements(winch).find(|e| e.has_tag_name(tag));
    let (Some(drum), Some(motor)) = (child("drum"), child("motor")) else {
        return Ok(None);
    };
    let (Some(r), Some(gear)) = (
        x.attr_number(drum, "r_drum")?,
        x.attr_number(motor, "gear_ratio")?,
    ) else {
        return Ok(None);
    };
    if r <= 0.0 || gear <= 0.0 {
        return Ok(None);
    }
    let inertia = x.attr_number(motor, "inertia")?.unwrap_or(0.0);
    let motor_speed = x
        .attr_number(motor, "angular_velocity")?
        .filter(|&v| v > 0.0)
        .map(|rpm| rpm * std::f64::consts::TAU / 60.0);
    let cable_speed = match child("cable") {
        Some(c) => x
            .attr_number(c, "max_velocity")?
            .filter(|&v| v > 0.0)
            .map(|v| v * gear / r),
        None => None,
    };
    let max_speed = match (motor_speed, cable_speed) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    };
    let w = cdpr_dynamics::Winch::new(r, gear, inertia, None, max_speed)
        .map_err(|e| x.error(motor, None, e.to_string()))?;
    Ok(Some(vec![w; n]))
}

const MATRIX_KEYS: [[&str; 3]; 3] = [
    ["a11", "a12", "a13"],
    ["a21", "a22", "a23"],
    ["a31", "a32", "a33"],
];

impl RobotDescription {
    /// Parses a WireCenter `.wcrfx` robot file; `file` names it in errors.
    pub fn parse_wcrfx(text: &str, file: impl AsRef<Path>) -> Result<Self, RobotFileError> {
        let x = XmlFile::parse(text, file.as_ref())?;
        let mut warnings = Vec::new();
        let root = x.doc.root_element();
        if !root.has_tag_name("models") {
            return Err(x.error(root, None, "expected a WireCenter <models> file"));
        }
        match root.attribute("version") {
            Some("0.31") | Some("0.32") => {}
            Some(v) => warnings.push(format!(
                "version {v}: read as 0.31 (the versions cdpr knows are 0.31 and 0.32)"
            )),
            None => warnings.push("no version: read as 0.31".into()),
        }
        let robots: Vec<Node> = XmlFile::elements(root)
            .filter(|n| n.has_tag_name("robot"))
            .collect();
        let robot = match robots.as_slice() {
            [] => return Err(x.error(root, None, "no <robot>")),
            [r] => *r,
            [_, second, ..] => {
                return Err(x.unsupported(*second, "a second <robot> in one file"));
            }
        };
        let motion = match robot.attribute("motionpattern") {
            None => {
                warnings.push("no motionpattern: 3R3T (WireLib's default)".into());
                MotionPattern::Spatial
            }
            Some("3R3T") => MotionPattern::Spatial,
            Some("1R2T") => MotionPattern::Planar,
            Some("2T") => MotionPattern::Point2,
            Some("3T") => MotionPattern::Point3,
            Some(other) => {
                return Err(x.unsupported(
                    robot,
                    format!("motionpattern {other} (cdpr reads 3R3T, 1R2T, 2T and 3T)"),
                ));
            }
        };
        let dim = motion.space_dim();
        let geometry = x.child(robot, "geometry")?;
        let chains: Vec<Node> = XmlFile::elements(geometry)
            .filter(|n| n.has_tag_name("chain"))
            .collect();
        let mut cables = Vec::new();
        let mut names = Vec::new();
        let (mut dropped_pulleys, mut shifted) = (false, false);
        for chain in &chains {
            let base = x.child(*chain, "base")?;
            let plat = x.child(*chain, "platform")?;
            let mut frame = position(&x, base)?;
            let mut platform = position(&x, plat)?;
            for (node, v) in [(base, frame), (plat, platform)] {
                if dim == 2 && v.z != 0.0 {
                    return Err(x.error(
                        node,
                        Some("z"),
                        format!(
                            "z = {} in a planar ({motion}) robot, whose plane is z = 0",
                            v.z
                        ),
                    ));
                }
            }
            if !motion.has_orientation() && platform != Vector3::zeros() {
                frame -= platform;
                platform = Vector3::zeros();
                shifted = true;
            }
            let radius = match x.attr_number(base, "radius")? {
                Some(r) if r < 0.0 => {
                    return Err(x.error(base, Some("radius"), format!("{r} is negative")));
                }
                Some(r) => r,
                None => {
                    warnings.push(format!(
                        "chain {}: no pulley radius, WireLib's default {WIRELIB_DEFAULT_PULLEY_RADIUS} m",
                        names.len() + 1
                    ));
                    WIRELIB_DEFAULT_PULLEY_RADIUS
                }
            };
            let orientation = orientation(&x, base)?;
            let pulley = if radius > 0.0 {
                if motion == MotionPattern::Spatial {
                    Some(Pulley {
                        radius,
                        orientation,
                    })
                } else {
                    dropped_pulleys = true;
                    None
                }
            } else {
                None
            };
            cables.push(Cable {
                frame,
                platform,
                pulley,
            });
            names.push(chain.attribute("id").map(str::to_string));
        }
        if dropped_pulleys {
            warnings.push(format!(
                "pulley radii not read: WireLib's pulley model applies to 3R3T robots, this one is {motion}"
            ));
        }
        if shifted {
            warnings.push(
                "platform anchors of a translating platform moved to the frame anchors (frame − offset): lengths and W are unchanged"
                    .into(),
            );
        }
        let n = cables.len();
        let robot_geometry =
            Robot::new(motion, cables).map_err(|e| x.error(geometry, None, e.to_string()))?;
        for (i, j) in robot_geometry.duplicate_cables() {
            warnings.push(format!(
                "cables {} and {} are exact duplicates (same anchor and attachment)",
                i + 1,
                j + 1
            ));
        }
        // Platform mass properties.
        let mut platform = Platform {
            mass: 0.0,
            centre_of_mass: Vector3::zeros(),
            gravity: if dim == 3 {
                Vector3::new(0.0, 0.0, -WIRELIB_GRAVITY)
            } else {
                Vector3::zeros()
            },
        };
        if dim == 2 {
            warnings.push(
                "a planar WireLib robot: gravity along −z is normal to its plane (no gravity wrench)"
                    .into(),
            );
        }
        let mut inertia = None;
        if let Some(p) = x.optional_child(robot, "platform")? {
            if let Some(m) = x.attr_number(p, "mass")? {
                if m < 0.0 {
                    return Err(x.error(p, Some("mass"), format!("{m} is negative")));
                }
                platform.mass = m;
            }
            if let Some(c) = x.optional_child(p, "centerofgravity")? {
                let mut v = position(&x, c)?;
                if dim == 2 {
                    v.z = 0.0;
                }
                platform.centre_of_mass = v;
            }
            if let Some(t) = x.optional_child(p, "inertiatensor")? {
                inertia = Some(inertia_tensor(&x, t)?);
            }
        }
        // Tension bounds.
        let application = x.optional_child(robot, "application")?;
        let cable_type = XmlFile::elements(root).find(|n| n.has_tag_name("cable"));
        let winch_cable = XmlFile::elements(root)
            .find(|n| n.has_tag_name("winch"))
            .and_then(|w| XmlFile::elements(w).find(|n| n.has_tag_name("cable")));
        let (t_min, t_max) = match application {
            Some(a) => (
                x.required_number(a, "min_cable_load")?,
                x.required_number(a, "max_cable_load")?,
            ),
            None => {
                let f_max = match winch_cable {
                    Some(w) => x.attr_number(w, "f_max")?.filter(|&f| f > 0.0),
                    None => None,
                };
                let f_min = match cable_type {
                    Some(c) => x.attr_number(c, "minimum_load")?.unwrap_or(0.0),
                    None => 0.0,
                };
                match f_max {
                    Some(f) => {
                        warnings.push(format!(
                            "no <application>: tension bounds {f_min}–{f} N from the winch's f_max and the cable's minimum_load"
                        ));
                        (f_min, f)
                    }
                    None => {
                        let (lo, hi) = WIRELIB_DEFAULT_BOUNDS;
                        warnings.push(format!(
                            "no <application> or winch f_max: WireLib's default tension bounds {lo}–{hi} N"
                        ));
                        (lo, hi)
                    }
                }
            }
        };
        if t_min < 0.0 {
            return Err(x.error(
                application.unwrap_or(robot),
                Some("min_cable_load"),
                format!("{t_min} N is negative: a cable can only pull (t_min ≥ 0)"),
            ));
        }
        if t_min > t_max {
            let node = application.unwrap_or(robot);
            return Err(x.error(
                node,
                Some("min_cable_load"),
                format!("{t_min} exceeds max_cable_load = {t_max}"),
            ));
        }
        let bounds = TensionBounds::new(vec![t_min; n], vec![t_max; n])
            .map_err(|e| x.error(robot, None, e.to_string()))?;
        // Axial stiffness E·S = E π r².
        let axial_stiffness = match cable_type {
            Some(c) => match (x.attr_number(c, "elasticity")?, x.attr_number(c, "radius")?) {
                (Some(e), Some(r)) if e > 0.0 && r > 0.0 => {
                    Some(vec![e * std::f64::consts::PI * r * r; n])
                }
                (Some(e), Some(r)) => {
                    return Err(x.error(
                        c,
                        None,
                        format!("elasticity {e} and radius {r} must be positive"),
                    ));
                }
                _ => None,
            },
            None => None,
        };
        // WireLib's `CCable::weight`: mass per length (kg/m).
        let linear_density = match cable_type {
            Some(c) => match x.attr_number(c, "weight")? {
                Some(rho) if rho >= 0.0 => Some(vec![rho; n]),
                Some(rho) => {
                    return Err(x.error(
                        c,
                        Some("weight"),
                        format!("{rho} kg/m must not be negative"),
                    ));
                }
                None => None,
            },
            None => None,
        };
        let winches = winches(&x, root, n)?;
        let name = robot
            .attribute("name")
            .filter(|s| !s.trim().is_empty())
            .map(str::to_string)
            .unwrap_or_else(|| {
                x.file
                    .file_stem()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_default()
            });
        Ok(Self {
            name,
            robot: robot_geometry,
            bounds,
            limits: Default::default(),
            platform,
            axial_stiffness,
            linear_density,
            cable_names: names,
            inertia,
            home_pose: None,
            winches,
            platform_shape: None,
            passive_springs: None,
            passive_spring_names: Vec::new(),
            encoders: None,
            warnings,
        })
    }

    /// The robot as a WireCenter `.wcrfx` file (version 0.31). `file` names the destination in
    /// errors. Fails when the format cannot hold a modelled number: per-cable tension bounds
    /// or axial stiffnesses that differ, passive springs. [`RobotDescription::wcrfx_losses`] lists what the
    /// format drops (limits, home pose, non-WireLib gravity).
    pub fn to_wcrfx(&self, file: impl AsRef<Path>) -> Result<String, RobotFileError> {
        let unrepresentable = |message: String| RobotFileError::Unrepresentable {
            file: file.as_ref().to_path_buf(),
            format: "WireCenter .wcrfx",
            message,
        };
        let (lo, hi) = (self.bounds.min(), self.bounds.max());
        if lo.iter().any(|&v| v != lo[0]) || hi.iter().any(|&v| v != hi[0]) {
            return Err(unrepresentable(
                "per-cable tension bounds differ; .wcrfx has one range for all cables".into(),
            ));
        }
        if let Some(es) = &self.axial_stiffness
            && es.iter().any(|&v| v != es[0])
        {
            return Err(unrepresentable(
                "per-cable axial stiffnesses differ; .wcrfx has one cable type".into(),
            ));
        }
        if let Some(rho) = &self.linear_density
            && rho.iter().any(|&v| v != rho[0])
        {
            return Err(unrepresentable(
                "per-cable linear densities differ; .wcrfx has one cable type".into(),
            ));
        }
        if let Some(springs) = &self.passive_springs {
            return Err(unrepresentable(format!(
                "{} passive spring(s): .wcrfx has no passive elements",
                springs.count()
            )));
        }
        let motion = self.robot.motion();
        let pattern = match motion {
            MotionPattern::Spatial => "3R3T",
            MotionPattern::Planar => "1R2T",
            MotionPattern::Point2 => "2T",
            MotionPattern::Point3 => "3T",
        };
        if motion != MotionPattern::Spatial
            && self.robot.cables().iter().any(|c| c.pulley.is_some())
        {
            return Err(unrepresentable(format!(
                "pulleys on a {motion} robot (WireLib models pulleys of 3R3T robots only)"
            )));
        }
        let mut s = String::new();
        let esc = xml_escape;
        let _ = writeln!(s, "<models version=\"0.31\">");
        let _ = writeln!(
            s,
            "    <robot name=\"{}\" generator=\"cdpr {}\" motionpattern=\"{pattern}\">",
            esc(&self.name),
            env!("CARGO_PKG_VERSION")
        );
        let _ = writeln!(s, "        <geometry>");
        for (i, c) in self.robot.cables().iter().enumerate() {
            let id = self
                .cable_names
                .get(i)
                .cloned()
                .flatten()
                .unwrap_or_else(|| (i + 1).to_string());
            let (q, radius) = match &c.pulley {
                Some(p) => (p.orientation, p.radius),
                None => (Matrix3::identity(), 0.0),
            };
            let _ = writeln!(s, "            <chain id=\"{}\">", esc(&id));
            let _ = writeln!(
                s,
                "                <base {}{} radius=\"{}\" />",
                position_attributes(&c.frame),
                matrix_attributes(&q),
                num(radius)
            );
            let _ = writeln!(
                s,
                "                <platform {} />",
                position_attributes(&c.platform)
            );
            let _ = writeln!(s, "            </chain>");
        }
        let _ = writeln!(s, "        </geometry>");
        let _ = writeln!(s, "        <platform mass=\"{}\">", num(self.platform.mass));
        if let Some(i) = &self.inertia {
            let _ = writeln!(
                s,
                "            <inertiatensor Ixx=\"{}\" Ixy=\"{}\" Ixz=\"{}\" Iyx=\"{}\" Iyy=\"{}\" Iyz=\"{}\" Izx=\"{}\" Izy=\"{}\" Izz=\"{}\" />",
                num(i[(0, 0)]),
                num(i[(0, 1)]),
                num(i[(0, 2)]),
                num(i[(1, 0)]),
                num(i[(1, 1)]),
                num(i[(1, 2)]),
                num(i[(2, 0)]),
                num(i[(2, 1)]),
                num(i[(2, 2)])
            );
        }
        let _ = writeln!(
            s,
            "            <centerofgravity {} />",
            position_attributes(&self.platform.centre_of_mass)
        );
        let _ = writeln!(s, "        </platform>");
        let _ = writeln!(
            s,
            "        <application min_cable_load=\"{}\" max_cable_load=\"{}\" />",
            num(lo[0]),
            num(hi[0])
        );
        let _ = writeln!(s, "    </robot>");
        if self.axial_stiffness.is_some() || self.linear_density.is_some() {
            let mut attributes = String::new();
            if let Some(es) = &self.axial_stiffness {
                // E·S = E π r² with r = 1/√π: E = E·S.
                let _ = write!(
                    attributes,
                    " elasticity=\"{}\" radius=\"{}\"",
                    num(es[0]),
                    num(1.0 / std::f64::consts::PI.sqrt())
                );
            }
            if let Some(rho) = &self.linear_density {
                let _ = write!(attributes, " weight=\"{}\"", num(rho[0]));
            }
            let _ = writeln!(s, "    <cable name=\"cdpr\"{attributes} />");
        }
        let _ = writeln!(s, "</models>");
        Ok(s)
    }

    /// What a `.wcrfx` file of this robot would not hold (empty if nothing): workspace limits,
    /// the home pose, the platform shape, the encoders' offsets and gains, a gravity other than
    /// WireLib's.
    pub fn wcrfx_losses(&self) -> Vec<String> {
        let mut out = Vec::new();
        if self.limits != Default::default() {
            out.push(
                "workspace limits (min_cable_length, min_jacobian_det) are not written".into(),
            );
        }
        if self.home_pose.is_some() {
            out.push("the home pose is not written".into());
        }
        if self.platform_shape.is_some() {
            out.push("the platform shape is not written".into());
        }
        if self.winches.is_some() {
            out.push("the winches (drum, gear, motor) are not written".into());
        }
        if self.encoders.is_some() {
            out.push("the encoders' offsets and gains are not written".into());
        }
        let g = if self.robot.motion().space_dim() == 3 {
            Vector3::new(0.0, 0.0, -WIRELIB_GRAVITY)
        } else {
            Vector3::zeros()
        };
        if self.platform.mass > 0.0 && self.platform.gravity != g {
            out.push(format!(
                "gravity {:?} m/s² is not written (WireLib uses 9.81 m/s² along −z)",
                self.platform.gravity.as_slice()
            ));
        }
        out
    }
}

/// Shortest text that reads back as the same f64.
fn num(v: f64) -> String {
    format!("{v:?}")
}

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn position_attributes(v: &Vector3<f64>) -> String {
    format!("x=\"{}\" y=\"{}\" z=\"{}\"", num(v.x), num(v.y), num(v.z))
}

fn matrix_attributes(q: &Matrix3<f64>) -> String {
    let mut s = String::new();
    for (i, row) in MATRIX_KEYS.iter().enumerate() {
        for (j, key) in row.iter().enumerate() {
            let _ = write!(s, " {key}=\"{}\"", num(q[(i, j)]));
        }
    }
    s
}

fn position(x: &XmlFile, node: Node) -> Result<Vector3<f64>, RobotFileError> {
    Ok(Vector3::new(
        x.required_number(node, "x")?,
        x.required_number(node, "y")?,
        x.required_number(node, "z")?,
    ))
}

/// The orientation a11 … a33 (a_ij: row i, column j) as written; identity if none is given.
fn orientation(x: &XmlFile, node: Node) -> Result<Matrix3<f64>, RobotFileError> {
    let given = MATRIX_KEYS
        .iter()
        .flatten()
        .filter(|k| node.attribute(**k).is_some())
        .count();
    if given == 0 {
        return Ok(Matrix3::identity());
    }
    let mut q = Matrix3::zeros();
    for (i, row) in MATRIX_KEYS.iter().enumerate() {
        for (j, key) in row.iter().enumerate() {
            q[(i, j)] = x.attr_number(node, key)?.ok_or_else(|| {
                x.error(node, Some(key), "missing (give all of a11 … a33 or none)")
            })?;
        }
    }
    Ok(q)
}

/// `<inertiatensor>`: the components given (others zero; Iyx = Ixy etc. when only one is given).
fn inertia_tensor(x: &XmlFile, node: Node) -> Result<Matrix3<f64>, RobotFileError> {
    let axes = ['x', 'y', 'z'];
    let mut m = Matrix3::zeros();
    for i in 0..3 {
        for j in 0..3 {
            let key = format!("I{}{}", axes[i], axes[j]);
            let mirror = format!("I{}{}", axes[j], axes[i]);
            m[(i, j)] = match x.attr_number(node, &key)? {
                Some(v) => v,
                None => x.attr_number(node, &mirror)?.unwrap_or(0.0),
            };
        }
    }
    Ok(m)
}
