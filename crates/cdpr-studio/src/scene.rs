//! # The 3-D scene at a pose
//!
//! What the page's renderer (the HTML viewer's `viewer.js`, shared) draws: frame anchors c_i,
//! each cable from its anchor to the platform attachment R ā_i + u, and the platform's faces
//! (the robot file's `[platform] shape`, else the hull of the attachment points). Planar robots
//! are drawn in the plane z = 0.

use crate::{Studio, StudioError};
use cdpr_kinematics::{ConvexPolyhedron, Pose};
use nalgebra::Vector3;
use serde::Serialize;

/// Anchors, cables and platform at one pose (base coordinates, m).
#[derive(Debug, Clone, Serialize)]
pub struct SceneData {
    /// Frame anchors c_i (m).
    pub anchors: Vec<[f64; 3]>,
    /// Cables: (frame anchor, platform attachment point) (m).
    pub cables: Vec<[[f64; 3]; 2]>,
    /// Platform faces (closed polygons, m); empty for a point platform.
    pub platform: Vec<Vec<[f64; 3]>>,
    /// The pose's position u (m).
    #[serde(rename = "platformPosition")]
    pub platform_position: [f64; 3],
}

fn arr(v: &Vector3<f64>) -> [f64; 3] {
    [v.x, v.y, v.z]
}

impl Studio {
    /// The scene at pose `q`.
    pub fn scene(&self, q: &[f64]) -> Result<SceneData, StudioError> {
        let d = &self.desc;
        let pose = Pose::from_coordinates(d.robot.motion(), q)?;
        let place = |p: &Vector3<f64>| arr(&(pose.position + pose.rotation * p));
        let hull = match &d.platform_shape {
            Some(s) => Some(s.clone()),
            None => {
                let pts: Vec<Vector3<f64>> = d.robot.cables().iter().map(|c| c.platform).collect();
                ConvexPolyhedron::from_points(&pts).ok()
            }
        };
        Ok(SceneData {
            anchors: d.robot.cables().iter().map(|c| arr(&c.frame)).collect(),
            cables: d
                .robot
                .cables()
                .iter()
                .map(|c| [arr(&c.frame), place(&c.platform)])
                .collect(),
            platform: hull
                .map(|h| {
                    h.faces()
                        .iter()
                        .map(|f| f.iter().map(|&v| place(&h.vertices()[v])).collect())
                        .collect()
                })
                .unwrap_or_default(),
            platform_position: arr(&pose.position),
        })
    }
}
