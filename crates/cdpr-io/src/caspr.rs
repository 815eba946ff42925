//! # CASPR XML models (single-body)
//!
//! A CASPR model is two files with a shared prefix: `NAME_bodies.xml` (the links: joint type,
//! initial pose, mass, centre of mass, inertia) and `NAME_cables.xml` (cable sets: per cable its
//! type, force limits and attachments). The cables file is the robot; its bodies file is found
//! beside it. Only single-body models (one `<link_rigid>` on the ground) are read.
//!
//! | CASPR | cdpr |
//! |---|---|
//! | joint `SPATIAL_EULER_XYZ` (x y z α β γ, R = R_x(α) R_y(β) R_z(γ)) | `spatial` (same Euler convention) |
//! | joint `PLANAR_XY` (x y θ) | `planar` |
//! | joint `PLANAR_YZ` (y z θ, θ about x) | `planar` with (x, y, z) → (y, z, x): file y, z are cdpr's x, y (a rotation, so θ is φ) |
//! | joint `T_XYZ` / `P_XY` (translations) | `point3` / `point2` |
//! | `q_initial` | `home_pose` |
//! | `<mass>`, `<com_location>`, `<inertia ref="com"/"joint">` | platform mass, centre of mass, inertia about the centre of mass |
//! | gravity 9.81 m/s² along −z | `platform.gravity` = (0, 0, −9.81); zero for `PLANAR_XY` and `P_XY` models (−z is normal to their plane); (0, −9.81) for `PLANAR_YZ` (a vertical plane) |
//! | `cable_ideal`, `cable_linear_spring` | a cable; `force_min`/`force_max` → its tension bounds |
//! | `cable_passive_linear_spring` (`K` N/m, `l0` m) | a passive spring ([`cdpr_wrench::PassiveSprings`]): not a cable; its force K (l − l₀) at each pose adds to the external wrench ([`RobotDescription::load_wrench`]) |
//! | `cable_linear_spring` `K` (N/m) | axial stiffness E·S = K · l(q_initial) (the same k = E·S/l at the initial pose) |
//! | `attachment_reference="joint"` | platform attachment = `location` (joint frame = platform frame) |
//! | `attachment_reference="com"` | platform attachment = `com_location` + `location` |
//! | `base_rotating_pulley` | a swivel pulley: `fixed_location` (where the cable enters, on the swivel axis) → frame anchor **a**, `pulley_radius` → ρ, `cable_entry_vector` → third column of Q |
//!
//! `base_rotating_pulley` (CASPR's `BaseRotatingPulleyAttachment`): the cable arrives at the
//! fixed point F travelling along the entry vector v, the pulley centre C lies at distance ρ
//! from F perpendicular to v in the plane of v and the platform attachment B, and the cable
//! leaves tangentially towards B. That is the swivel-pulley model of Pott 2018 with the swivel
//! axis through F along v: Q = [e₁ e₂ e₃] with e₃ = v/‖v‖, e₁ the base x axis (or y, when x is
//! nearly parallel to v) made orthogonal to e₃, e₂ = e₃ × e₁. CASPR defines no swivel-angle
//! zero, so e₁ is a convention; lengths and W do not depend on it.
//!
//! Not modelled (a clear error naming the element and its line): multi-body models, joints
//! other than the five above, VSD cables, cables with more than two attachments.
//!
//! ## References
//! - Lau, Eden, Tan & Oetomo, *CASPR: a comprehensive cable-robot analysis and simulation
//!   platform for the research of cable-driven parallel robots*, IROS 2016.
//! - Pott, *Cable-Driven Parallel Robots: Theory and Application*, Springer 2018 (pulley model).

use crate::xml::XmlFile;
use crate::{RobotDescription, RobotFileError};
use cdpr_kinematics::{Cable, MotionPattern, Pose, Pulley, Robot};
use cdpr_tension::TensionBounds;
use cdpr_wrench::{PassiveSprings, Platform};
use nalgebra::{Matrix3, Vector3};
use roxmltree::Node;
use std::path::{Path, PathBuf};

/// CASPR's gravitational acceleration (m/s²), along −z.
pub const CASPR_GRAVITY: f64 = 9.81;

/// The two files of a CASPR model and its name, from either file's path.
pub(crate) fn companion_paths(path: &Path) -> Result<(PathBuf, PathBuf, String), RobotFileError> {
    let file_name = path
        .file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let prefix = file_name
        .strip_suffix("_cables.xml")
        .or_else(|| file_name.strip_suffix("_bodies.xml"))
        .ok_or_else(|| RobotFileError::Format {
            file: path.to_path_buf(),
            message:
                "a CASPR model is read from its NAME_cables.xml, with NAME_bodies.xml beside it"
                    .into(),
        })?;
    let dir = path.parent().unwrap_or(Path::new(""));
    Ok((
        dir.join(format!("{prefix}_cables.xml")),
        dir.join(format!("{prefix}_bodies.xml")),
        prefix.to_string(),
    ))
}

/// The plane of a planar joint, and how file coordinates map to cdpr's plane z = 0.
#[derive(Clone, Copy, PartialEq)]
enum Plane {
    /// `PLANAR_XY` (and every non-planar joint): coordinates as written.
    Xy,
    /// `PLANAR_YZ` (q = y, z, θ about x): (x, y, z) → (y, z, x), a cyclic permutation (a
    /// rotation), so CASPR's θ about +x is cdpr's φ about +z.
    Yz,
}

impl Plane {
    fn map(self, v: Vector3<f64>) -> Vector3<f64> {
        match self {
            Self::Xy => v,
            Self::Yz => Vector3::new(v.y, v.z, v.x),
        }
    }

    /// The file's axis normal to the plane, and the joint's name for messages.
    fn normal(self) -> (&'static str, &'static str) {
        match self {
            Self::Xy => ("z", "planar"),
            Self::Yz => ("x", "PLANAR_YZ"),
        }
    }
}

/// The single rigid body of a model (in cdpr's coordinates: see [`Plane`]).
struct Body {
    motion: MotionPattern,
    plane: Plane,
    /// CASPR's gravity (9.81 m/s² along −z of the file) in cdpr's coordinates, restricted to
    /// the plane of a planar model.
    gravity: Vector3<f64>,
    mass: f64,
    centre_of_mass: Vector3<f64>,
    inertia: Option<Matrix3<f64>>,
    home: Option<Vec<f64>>,
}

/// One cable as the file gives it (3-D, before the motion pattern's checks).
struct RawCable<'a, 'i> {
    node: Node<'a, 'i>,
    name: Option<String>,
    frame: Vector3<f64>,
    frame_node: Node<'a, 'i>,
    platform: Vector3<f64>,
    platform_node: Node<'a, 'i>,
    pulley: Option<Pulley>,
    min: f64,
    max: f64,
    spring: Option<f64>,
    /// A passive spring (`cable_passive_linear_spring`): its K and l₀.
    passive: Option<PassiveSpring>,
    /// `attachment_reference="com"`: the platform location is relative to the centre of mass.
    from_com: bool,
}

/// K (N/m) and l₀ (m) of a `cable_passive_linear_spring`.
#[derive(Clone, Copy)]
struct PassiveSpring {
    stiffness: f64,
    free_length: f64,
}

impl RobotDescription {
    /// Parses a CASPR single-body model from the texts of its cables and bodies files; the
    /// file names appear in errors. `cable_set` selects a `<cable_set id>` (default: the file's
    /// `default_cable_set`).
    pub fn parse_caspr(
        cables_text: &str,
        cables_file: impl AsRef<Path>,
        bodies_text: &str,
        bodies_file: impl AsRef<Path>,
        cable_set: Option<&str>,
    ) -> Result<Self, RobotFileError> {
        let cables_file = cables_file.as_ref();
        let bodies_xml = XmlFile::parse(bodies_text, bodies_file.as_ref())?;
        let body = read_body(&bodies_xml)?;
        let cables_xml = XmlFile::parse(cables_text, cables_file)?;
        let mut warnings = Vec::new();
        let (set_node, raw) = read_cables(&cables_xml, cable_set)?;
        let motion = body.motion;
        let (mut cables, mut springs) = (Vec::with_capacity(raw.len()), Vec::new());
        let mut shifted = false;
        let (axis, joint) = body.plane.normal();
        for c in &raw {
            let mut frame = body.plane.map(c.frame);
            let mut platform = if c.from_com {
                body.centre_of_mass + body.plane.map(c.platform)
            } else {
                body.plane.map(c.platform)
            };
            if motion.space_dim() == 2 {
                if frame.z != 0.0 {
                    return Err(cables_xml.error(
                        c.frame_node,
                        None,
                        format!(
                            "{axis} = {} off the plane of a {joint} ({axis} = 0) model",
                            frame.z
                        ),
                    ));
                }
                if platform.z != 0.0 {
                    return Err(cables_xml.error(
                        c.platform_node,
                        None,
                        format!(
                            "platform attachment {axis} = {} off the plane of a {joint} ({axis} = 0) model",
                            platform.z
                        ),
                    ));
                }
            }
            if !motion.has_orientation() && platform != Vector3::zeros() {
                // A translating platform: the attachment offset moves with it, so the cable is
                // the one from frame − offset to the platform origin (lengths and W identical).
                frame -= platform;
                platform = Vector3::zeros();
                shifted = true;
            }
            if c.pulley.is_some() && motion != MotionPattern::Spatial {
                return Err(cables_xml.unsupported(
                    c.frame_node,
                    format!("a rotating pulley on a `{motion}` model (pulleys are modelled for spatial robots)"),
                ));
            }
            let cable = Cable {
                frame,
                platform,
                pulley: c.pulley,
            };
            match c.passive {
                None => cables.push((cable, c)),
                Some(spring) => springs.push((cable, spring, c)),
            }
        }
        if cables.is_empty() {
            return Err(cables_xml.error(
                set_node,
                None,
                "no actuated cable (only passive springs)",
            ));
        }
        let passive_spring_names = springs.iter().map(|(_, _, c)| c.name.clone()).collect();
        let passive_springs = if springs.is_empty() {
            None
        } else {
            let geometry = Robot::new(motion, springs.iter().map(|(s, _, _)| *s).collect())
                .map_err(|e| cables_xml.error(set_node, None, e.to_string()))?;
            let (k, l0) = springs
                .iter()
                .map(|(_, p, _)| (p.stiffness, p.free_length))
                .unzip();
            warnings.push(format!(
                "{} passive spring(s) (cable_passive_linear_spring): not actuated; their force K (l − l0) at each pose is added to the external wrench",
                springs.len()
            ));
            Some(
                PassiveSprings::new(geometry, k, l0)
                    .map_err(|e| cables_xml.error(set_node, None, e.to_string()))?,
            )
        };
        let (cables, raw): (Vec<Cable>, Vec<&RawCable>) = cables.into_iter().unzip();
        if shifted {
            warnings.push(
                "platform attachments of a translating platform moved to the frame anchors (frame − offset): lengths and W are unchanged"
                    .into(),
            );
        }
        let robot = Robot::new(motion, cables)
            .map_err(|e| cables_xml.error(set_node, None, e.to_string()))?;
        for (i, j) in robot.duplicate_cables() {
            warnings.push(format!(
                "cables {} and {} are exact duplicates (same anchor and attachment)",
                i + 1,
                j + 1
            ));
        }
        let bounds = TensionBounds::new(
            raw.iter().map(|c| c.min).collect(),
            raw.iter().map(|c| c.max).collect(),
        )
        .map_err(|e| cables_xml.error(set_node, None, e.to_string()))?;
        let home_q = body.home.clone().unwrap_or_else(|| vec![0.0; motion.dof()]);
        let axial_stiffness = match raw.iter().filter(|c| c.spring.is_some()).count() {
            0 => None,
            n if n == raw.len() => {
                let pose = Pose::from_coordinates(motion, &home_q).map_err(|e| {
                    bodies_xml.error(bodies_xml.doc.root_element(), None, e.to_string())
                })?;
                let kin = robot
                    .inverse_kinematics(&pose)
                    .map_err(|e| cables_xml.error(set_node, None, e.to_string()))?;
                let es: Vec<f64> = raw
                    .iter()
                    .zip(kin.lengths())
                    .map(|(c, l)| c.spring.unwrap_or(0.0) * l)
                    .collect();
                if let Some(i) = es.iter().position(|&k| !(k > 0.0 && k.is_finite())) {
                    return Err(cables_xml.error(
                        raw[i].node,
                        None,
                        "spring cable of zero length at q_initial: no axial stiffness E·S = K·l",
                    ));
                }
                warnings.push(format!(
                    "cable_linear_spring K (N/m) read as axial stiffness E·S = K·l at q_initial = {home_q:?} (the cable stiffness k = E·S/l equals K there)"
                ));
                Some(es)
            }
            _ => {
                warnings.push(
                    "only some cables of the set are springs (K): no axial stiffness is read"
                        .into(),
                );
                None
            }
        };
        let mut centre_of_mass = body.centre_of_mass;
        if motion.space_dim() == 2 && centre_of_mass.z != 0.0 {
            warnings.push(format!(
                "centre of mass z = {} dropped (planar model)",
                centre_of_mass.z
            ));
            centre_of_mass.z = 0.0;
        }
        let gravity = body.gravity;
        let name = cables_file
            .file_name()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let name = name
            .strip_suffix("_cables.xml")
            .unwrap_or(&name)
            .to_string();
        Ok(Self {
            name,
            robot,
            bounds,
            limits: Default::default(),
            platform: Platform {
                mass: body.mass,
                centre_of_mass,
                gravity,
            },
            axial_stiffness,
            // CASPR's cable models (ideal, linear springs) have no mass per length.
            linear_density: None,
            cable_names: raw.iter().map(|c| c.name.clone()).collect(),
            inertia: body.inertia,
            home_pose: body.home,
            winches: None,
            platform_shape: None,
            passive_springs,
            passive_spring_names,
            encoders: None,
            warnings,
        })
    }
}

fn read_body(x: &XmlFile) -> Result<Body, RobotFileError> {
    let root = x.doc.root_element();
    if !root.has_tag_name("bodies_system") {
        return Err(x.error(root, None, "expected a CASPR <bodies_system> file"));
    }
    let links = x.child(root, "links")?;
    let mut rigid = Vec::new();
    for n in XmlFile::elements(links) {
        if n.has_tag_name("link_rigid") {
            rigid.push(n);
        } else {
            return Err(x.unsupported(n, "a link type other than <link_rigid>"));
        }
    }
    let link = match rigid.as_slice() {
        [] => return Err(x.error(links, None, "no <link_rigid>")),
        [one] => *one,
        [_, second, ..] => {
            return Err(x.unsupported(
                *second,
                format!(
                    "a second rigid link (num=\"{}\"): multi-body models are not modelled; cdpr reads single-body robots",
                    second.attribute("num").unwrap_or("?")
                ),
            ));
        }
    };
    let joint = x.child(link, "joint")?;
    let kind = joint
        .attribute("type")
        .ok_or_else(|| x.error(joint, Some("type"), "missing"))?;
    let (motion, plane) = match kind {
        "SPATIAL_EULER_XYZ" => (MotionPattern::Spatial, Plane::Xy),
        "PLANAR_XY" => (MotionPattern::Planar, Plane::Xy),
        "PLANAR_YZ" => (MotionPattern::Planar, Plane::Yz),
        "T_XYZ" => (MotionPattern::Point3, Plane::Xy),
        "P_XY" => (MotionPattern::Point2, Plane::Xy),
        other => {
            return Err(x.unsupported(
                joint,
                format!(
                    "joint type {other} (cdpr reads SPATIAL_EULER_XYZ, PLANAR_XY, PLANAR_YZ, T_XYZ and P_XY)"
                ),
            ));
        }
    };
    let file_gravity = Vector3::new(0.0, 0.0, -CASPR_GRAVITY);
    let gravity = match plane.map(file_gravity) {
        // In space, or in a plane: its in-plane part (zero for PLANAR_XY and P_XY, where −z is
        // normal to the plane; (0, −9.81) for PLANAR_YZ, a vertical plane).
        g if motion.space_dim() == 3 => g,
        g => Vector3::new(g.x, g.y, 0.0),
    };
    let home = match joint.attribute("q_initial") {
        None => None,
        Some(text) => {
            let q: Result<Vec<f64>, _> = text.split_whitespace().map(str::parse::<f64>).collect();
            match q {
                Ok(q) if q.len() == motion.dof() && q.iter().all(|v| v.is_finite()) => Some(q),
                _ => {
                    return Err(x.error(
                        joint,
                        Some("q_initial"),
                        format!("expected {} finite numbers for {kind}", motion.dof()),
                    ));
                }
            }
        }
    };
    let physical = x.child(link, "physical")?;
    let mass_node = x.child(physical, "mass")?;
    let mass = x.number(mass_node)?;
    if mass < 0.0 {
        return Err(x.error(mass_node, None, format!("mass {mass} is negative")));
    }
    let centre_of_mass = plane.map(x.vector3(x.child(physical, "com_location")?)?);
    let inertia = match x.optional_child(physical, "inertia")? {
        None => None,
        Some(node) => {
            let get = |k: &str| -> Result<f64, RobotFileError> { x.number(x.child(node, k)?) };
            let (ixx, iyy, izz) = (get("Ixx")?, get("Iyy")?, get("Izz")?);
            let (ixy, ixz, iyz) = (get("Ixy")?, get("Ixz")?, get("Iyz")?);
            let i = Matrix3::new(ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz);
            // In cdpr's axes: I' = P I Pᵀ with P the plane's permutation.
            let p = Matrix3::from_columns(&[
                plane.map(Vector3::x()),
                plane.map(Vector3::y()),
                plane.map(Vector3::z()),
            ]);
            let i = p * i * p.transpose();
            match node.attribute("ref").unwrap_or("com") {
                "com" => Some(i),
                // Parallel-axis theorem: I_joint = I_com + m (‖c‖² E − c cᵀ).
                "joint" => {
                    let c = centre_of_mass;
                    Some(i - mass * (Matrix3::identity() * c.norm_squared() - c * c.transpose()))
                }
                other => {
                    return Err(x.error(
                        node,
                        Some("ref"),
                        format!("`{other}` (expected com or joint)"),
                    ));
                }
            }
        }
    };
    let parent = x.child(link, "parent")?;
    let num_node = x.child(parent, "num")?;
    if x.number(num_node)? != 0.0 {
        return Err(x.unsupported(
            num_node,
            "a link whose parent is not the ground (link 0): multi-body models are not modelled",
        ));
    }
    if let Some(loc) = x.optional_child(parent, "location")?
        && x.vector3(loc)? != Vector3::zeros()
    {
        return Err(x.unsupported(
            loc,
            "a joint located away from the base origin (cdpr's pose is the joint's)",
        ));
    }
    Ok(Body {
        motion,
        plane,
        gravity,
        mass,
        centre_of_mass,
        inertia,
        home,
    })
}

fn read_cables<'a, 'i>(
    x: &'a XmlFile<'i>,
    requested: Option<&str>,
) -> Result<(Node<'a, 'i>, Vec<RawCable<'a, 'i>>), RobotFileError> {
    let root = x.doc.root_element();
    if !root.has_tag_name("cables") {
        return Err(x.error(root, None, "expected a CASPR <cables> file"));
    }
    let sets: Vec<Node> = XmlFile::elements(root)
        .filter(|n| n.has_tag_name("cable_set"))
        .collect();
    let ids: Vec<&str> = sets.iter().filter_map(|s| s.attribute("id")).collect();
    let id = match requested {
        Some(id) => id,
        None => root.attribute("default_cable_set").ok_or_else(|| {
            x.error(
                root,
                Some("default_cable_set"),
                format!(
                    "missing: choose a cable set with --cable-set ({})",
                    ids.join(", ")
                ),
            )
        })?,
    };
    let set = sets
        .iter()
        .find(|s| s.attribute("id") == Some(id))
        .copied()
        .ok_or_else(|| {
            x.error(
                root,
                None,
                format!(
                    "no <cable_set id=\"{id}\"> (the file has: {})",
                    ids.join(", ")
                ),
            )
        })?;
    let mut cables = Vec::new();
    for node in XmlFile::elements(set) {
        cables.push(read_cable(x, node)?);
    }
    if cables.is_empty() {
        return Err(x.error(set, None, "no cables"));
    }
    Ok((set, cables))
}

fn read_cable<'a, 'i>(
    x: &'a XmlFile<'i>,
    node: Node<'a, 'i>,
) -> Result<RawCable<'a, 'i>, RobotFileError> {
    let tag = node.tag_name().name();
    let (is_spring, is_passive) = match tag {
        "cable_ideal" => (false, false),
        "cable_linear_spring" => (true, false),
        "cable_passive_linear_spring" => (false, true),
        t if t.starts_with("cable_vsd") => {
            return Err(x.unsupported(node, "a cable with a variable-stiffness device (VSD)"));
        }
        _ => {
            return Err(x.unsupported(
                node,
                "an element other than cable_ideal / cable_linear_spring / cable_passive_linear_spring in a cable set",
            ));
        }
    };
    let reference = node
        .attribute("attachment_reference")
        .ok_or_else(|| x.error(node, Some("attachment_reference"), "missing (joint or com)"))?;
    let from_com = match reference {
        "joint" => false,
        "com" => true,
        other => {
            return Err(x.error(
                node,
                Some("attachment_reference"),
                format!("`{other}` (expected joint or com)"),
            ));
        }
    };
    let properties = x.child(node, "properties")?;
    let passive = if is_passive {
        let k_node = x.child(properties, "K")?;
        let stiffness = x.number(k_node)?;
        if stiffness <= 0.0 {
            return Err(x.error(k_node, None, format!("K = {stiffness} must be positive")));
        }
        let l0_node = x.child(properties, "l0")?;
        let free_length = x.number(l0_node)?;
        if free_length < 0.0 {
            return Err(x.error(l0_node, None, format!("l0 = {free_length} is negative")));
        }
        Some(PassiveSpring {
            stiffness,
            free_length,
        })
    } else {
        None
    };
    // A passive spring has no force limits (its force follows from its length).
    let (min, max) = if is_passive {
        (0.0, f64::INFINITY)
    } else {
        let min_node = x.child(properties, "force_min")?;
        let max_node = x.child(properties, "force_max")?;
        let (min, max) = (x.number(min_node)?, x.number(max_node)?);
        if min > max {
            return Err(x.error(
                min_node,
                None,
                format!("force_min = {min} exceeds force_max = {max}"),
            ));
        }
        (min, max)
    };
    let spring = if is_spring {
        let k_node = x.child(properties, "K")?;
        let k = x.number(k_node)?;
        if k <= 0.0 {
            return Err(x.error(k_node, None, format!("K = {k} must be positive")));
        }
        Some(k)
    } else {
        None
    };
    let attachments = x.child(node, "attachments")?;
    let mut frame = None;
    let mut platform = None;
    for a in XmlFile::elements(attachments) {
        let slot = match a.tag_name().name() {
            "attachment" => {
                let link_node = x.child(a, "link")?;
                let link = x.number(link_node)?;
                let loc_node = x.child(a, "location")?;
                let loc = x.vector3(loc_node)?;
                if link == 0.0 {
                    (&mut frame, (loc, None, loc_node))
                } else if link == 1.0 {
                    (&mut platform, (loc, None, loc_node))
                } else {
                    return Err(x.unsupported(
                        link_node,
                        format!("an attachment on link {link}: multi-body models are not modelled"),
                    ));
                }
            }
            "base_rotating_pulley" => {
                let loc_node = x.child(a, "fixed_location")?;
                let loc = x.vector3(loc_node)?;
                let r_node = x.child(a, "pulley_radius")?;
                let radius = x.number(r_node)?;
                if radius <= 0.0 {
                    return Err(x.error(r_node, None, format!("radius {radius} must be positive")));
                }
                let v_node = x.child(a, "cable_entry_vector")?;
                let v = x.vector3(v_node)?;
                if v.norm() == 0.0 {
                    return Err(x.error(v_node, None, "the cable entry vector is zero"));
                }
                let pulley = Pulley {
                    radius,
                    orientation: pulley_frame(&v),
                };
                (&mut frame, (loc, Some(pulley), loc_node))
            }
            _ => {
                return Err(x.unsupported(
                    a,
                    "an attachment type other than attachment / base_rotating_pulley",
                ));
            }
        };
        let (target, value) = slot;
        if target.is_some() {
            return Err(x.unsupported(
                a,
                "a cable with more than one attachment on the same link (routed cables) is not modelled",
            ));
        }
        *target = Some(value);
    }
    let (frame, pulley, frame_node) = frame.ok_or_else(|| {
        x.error(
            attachments,
            None,
            "no attachment on the frame (link 0 or base_rotating_pulley)",
        )
    })?;
    let (location, _, platform_node) = platform
        .ok_or_else(|| x.error(attachments, None, "no attachment on the platform (link 1)"))?;
    Ok(RawCable {
        node,
        name: node.attribute("name").map(str::to_string),
        frame,
        frame_node,
        platform: location,
        platform_node,
        pulley,
        min,
        max,
        spring,
        passive,
        from_com,
    })
}

/// The pulley frame Q of a CASPR rotating pulley from its cable entry vector v: third column
/// v/‖v‖ (the swivel axis), first column the base x axis (y if x is within ~6° of v) made
/// orthogonal to it, second column e₃ × e₁.
pub fn pulley_frame(v: &Vector3<f64>) -> Matrix3<f64> {
    let e3 = v.normalize();
    let x = if e3.x.abs() < 0.995 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let e1 = (x - e3 * e3.dot(&x)).normalize();
    let e2 = e3.cross(&e1);
    Matrix3::from_columns(&[e1, e2, e3])
}
