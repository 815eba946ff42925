//! # CASPR trajectories (`NAME_trajectories.xml`)
//!
//! CASPR keeps a model's joint-space trajectories in `NAME_trajectories.xml` beside its bodies
//! and cables (`templates/trajectories.dtd`):
//!
//! ```xml
//! <trajectories>
//!   <joint_trajectories>
//!     <quintic_spline_trajectory id="traj_1" time_definition="relative" time_step="0.01">
//!       <points>
//!         <point>           <q>-1 -0.5 1.5 0.2 -0.4 0.1</q> <q_dot>0 0 0 0 0 0</q_dot> <q_ddot>0 0 0 0 0 0</q_ddot> </point>
//!         <point time="1.0"> <q>1 0.5 0.5 0.3 0 -0.2</q>     <q_dot>0 0 0 0 0 0</q_dot> <q_ddot>0 0 0 0 0 0</q_ddot> </point>
//!       </points>
//!     </quintic_spline_trajectory>
//!   </joint_trajectories>
//! </trajectories>
//! ```
//!
//! | CASPR | cdpr |
//! |---|---|
//! | `linear_spline_trajectory`, `cubic_spline_trajectory`, `quintic_spline_trajectory`, `cubic_spline_average_velocity_trajectory`, `parabolic_blend_trajectory` | [`SplineKind`] (the splines: `cdpr_dynamics::joint_spline`) |
//! | `id` | `--trajectory-id` |
//! | `time_definition="relative"` / `"absolute"` | each point's `time` after the previous point / since the start; the first point is at t = 0 |
//! | `time_step` (s) | the sampling period |
//! | `<q>` | the pose in motion-pattern coordinates (m, rad; Euler angles α β γ for `SPATIAL_EULER_XYZ`) |
//! | `<q_dot>`, `<q_ddot>` | q̇, q̈ (Euler rates for the angles): every point (cubic: q̇; quintic: both), the first and last (cubic average velocity: q̇) |
//! | `blend_time_default`, a point's `blend_time` (s) | the parabolic blend time of the segment ending at that point |
//!
//! Not read (an error naming the element): `file_trajectory` (a `.traj` table), operational-space
//! trajectories. Every error names the file, the line and the element (and attribute).
//!
//! ## References
//! - Lau, Eden, Tan & Oetomo, CASPR, IROS 2016 (`JointTrajectory.LoadXmlObj`).

use crate::RobotFileError;
use crate::xml::XmlFile;
use cdpr_dynamics::DynamicsError;
use cdpr_dynamics::joint_spline::{JointSpline, SplineKind, SplinePoint, point_of_key};
use cdpr_kinematics::MotionPattern;
use roxmltree::Node;
use std::path::Path;

/// One CASPR trajectory, read and ready to sample.
#[derive(Debug, Clone, PartialEq)]
pub struct CasprTrajectory {
    /// Its `id`.
    pub id: String,
    /// Its points as read (absolute times, s).
    pub points: Vec<SplinePoint>,
    /// The spline through them.
    pub spline: JointSpline,
}

/// The file's joint trajectories: `(id, element name)` in file order.
pub fn caspr_trajectory_ids(
    text: &str,
    file: &Path,
) -> Result<Vec<(String, String)>, RobotFileError> {
    let xml = XmlFile::parse(text, file)?;
    let list = joint_trajectories(&xml)?;
    Ok(XmlFile::elements(list)
        .map(|n| {
            (
                n.attribute("id").unwrap_or("").to_string(),
                n.tag_name().name().to_string(),
            )
        })
        .collect())
}

fn joint_trajectories<'a, 'i>(xml: &'a XmlFile<'i>) -> Result<Node<'a, 'i>, RobotFileError> {
    let root = xml.doc.root_element();
    if !root.has_tag_name("trajectories") {
        return Err(xml.error(
            root,
            None,
            "a CASPR trajectories file has the root element <trajectories>",
        ));
    }
    xml.child(root, "joint_trajectories")
}

/// Reads the trajectory `id` of a CASPR trajectories file's text for a robot of `motion`
/// (`file` names it in errors).
///
/// ```
/// use cdpr_io::parse_caspr_trajectory;
/// use cdpr_kinematics::MotionPattern;
/// let text = r#"<trajectories><joint_trajectories>
///   <linear_spline_trajectory id="go" time_definition="relative" time_step="0.5">
///     <points><point><q>0 0</q></point><point time="2"><q>1 0</q></point></points>
///   </linear_spline_trajectory></joint_trajectories></trajectories>"#;
/// let t = parse_caspr_trajectory(text, "x_trajectories.xml".as_ref(), "go", MotionPattern::Point2).unwrap();
/// assert_eq!(t.spline.samples().len(), 5);
/// let e = parse_caspr_trajectory(text, "x_trajectories.xml".as_ref(), "back", MotionPattern::Point2);
/// assert!(e.unwrap_err().to_string().contains("no joint trajectory with id `back` (the file has: go)"));
/// ```
pub fn parse_caspr_trajectory(
    text: &str,
    file: &Path,
    id: &str,
    motion: MotionPattern,
) -> Result<CasprTrajectory, RobotFileError> {
    let xml = XmlFile::parse(text, file)?;
    let list = joint_trajectories(&xml)?;
    let Some(node) = XmlFile::elements(list).find(|n| n.attribute("id") == Some(id)) else {
        let ids: Vec<&str> = XmlFile::elements(list)
            .filter_map(|n| n.attribute("id"))
            .collect();
        let has = match ids.is_empty() {
            true => "none".to_string(),
            false => ids.join(", "),
        };
        return Err(xml.error(
            list,
            None,
            format!("no joint trajectory with id `{id}` (the file has: {has})"),
        ));
    };
    let name = node.tag_name().name();
    let Some(kind) = SplineKind::from_element(name) else {
        if name == "file_trajectory" {
            return Err(xml.unsupported(
                node,
                "a trajectory read from a .traj table: give its points in a spline trajectory",
            ));
        }
        let known: Vec<&str> = SplineKind::ALL.iter().map(|k| k.element()).collect();
        return Err(xml.error(
            node,
            None,
            format!(
                "unknown trajectory type (expected one of: {})",
                known.join(", ")
            ),
        ));
    };
    let absolute = match node.attribute("time_definition") {
        Some("relative") => false,
        Some("absolute") => true,
        Some(v) => {
            return Err(xml.error(
                node,
                Some("time_definition"),
                format!("`{v}`: must be `relative` or `absolute`"),
            ));
        }
        None => return Err(xml.error(node, Some("time_definition"), "missing")),
    };
    let time_step = xml.required_number(node, "time_step")?;
    let blend_default = xml.attr_number(node, "blend_time_default")?;
    let points_node = xml.child(node, "points")?;
    let point_nodes: Vec<Node> = XmlFile::elements(points_node).collect();
    let mut points = Vec::with_capacity(point_nodes.len());
    for (k, &p) in point_nodes.iter().enumerate() {
        let previous = points.last().map(|q: &SplinePoint| q.time);
        points.push(read_point(&xml, p, k, previous, absolute, motion)?);
    }
    let spline = JointSpline::new(motion, kind, time_step, &points, blend_default)
        .map_err(|e| spline_error(&xml, node, &point_nodes, e))?;
    Ok(CasprTrajectory {
        id: id.to_string(),
        points,
        spline,
    })
}

/// Reads [`parse_caspr_trajectory`] from a file.
pub fn load_caspr_trajectory(
    path: impl AsRef<Path>,
    id: &str,
    motion: MotionPattern,
) -> Result<CasprTrajectory, RobotFileError> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|source| RobotFileError::Io {
        file: path.to_path_buf(),
        source,
    })?;
    parse_caspr_trajectory(&text, path, id, motion)
}

/// One `<point>` (k from 0) after a point at time `previous`.
fn read_point(
    xml: &XmlFile,
    node: Node,
    k: usize,
    previous: Option<f64>,
    absolute: bool,
    motion: MotionPattern,
) -> Result<SplinePoint, RobotFileError> {
    if !node.has_tag_name("point") {
        return Err(xml.error(node, None, "<points> holds <point> elements only"));
    }
    for child in XmlFile::elements(node) {
        if !["q", "q_dot", "q_ddot"].contains(&child.tag_name().name()) {
            return Err(xml.error(
                child,
                None,
                "unknown element in a <point> (expected <q>, <q_dot>, <q_ddot>)",
            ));
        }
    }
    let dof = motion.dof();
    let coordinates = match motion {
        MotionPattern::Point2 => "x y",
        MotionPattern::Planar => "x y θ",
        MotionPattern::Point3 => "x y z",
        MotionPattern::Spatial => "x y z α β γ",
    };
    let vector = |name: &str| -> Result<Option<Vec<f64>>, RobotFileError> {
        let Some(n) = xml.optional_child(node, name)? else {
            return Ok(None);
        };
        let v = xml.numbers(n)?;
        if v.len() != dof {
            return Err(xml.error(
                n,
                None,
                format!(
                    "expected {dof} numbers (the robot's {} coordinates {coordinates}), found {}",
                    motion.name(),
                    v.len()
                ),
            ));
        }
        Ok(Some(v))
    };
    let q = vector("q")?.ok_or_else(|| xml.error(node, None, "missing child element <q>"))?;
    let given = xml.attr_number(node, "time")?;
    let time = match (previous, given) {
        (None, None | Some(0.0)) => 0.0,
        (None, Some(t)) => {
            return Err(xml.error(
                node,
                Some("time"),
                format!("{t}: the first point is at t = 0 (CASPR ignores its time)"),
            ));
        }
        (Some(_), None) => return Err(xml.error(node, Some("time"), "missing")),
        (Some(prev), Some(t)) if !absolute => prev + t,
        (Some(_), Some(t)) => t,
    };
    let blend_time = xml.attr_number(node, "blend_time")?;
    if k == 0 && blend_time.is_some() {
        return Err(xml.error(
            node,
            Some("blend_time"),
            "the blend time of a segment is on its end point, not on the first point",
        ));
    }
    Ok(SplinePoint {
        time,
        q,
        q_dot: vector("q_dot")?,
        q_ddot: vector("q_ddot")?,
        blend_time,
    })
}

/// A spline error on the element (and attribute) it is about.
fn spline_error(xml: &XmlFile, node: Node, points: &[Node], e: DynamicsError) -> RobotFileError {
    let DynamicsError::BadSetting { key, value, why } = &e else {
        return xml.error(node, None, e.to_string());
    };
    match point_of_key(key) {
        Some((k, field)) if k < points.len() => match field {
            "q_dot" | "q_ddot" => xml.error(points[k], None, format!("missing <{field}>: {why}")),
            _ => xml.error(points[k], Some(field), format!("{value}: {why}")),
        },
        _ => xml.error(node, Some(key), format!("{value}: {why}")),
    }
}
