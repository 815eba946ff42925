//! # The workspace on demand
//!
//! The boundary mesh of the constant-orientation workspace (thesis eq. (6.23), Algorithm 6.2
//! grid verdicts, marching cubes with vertices bisected onto the boundary) at the orientation of
//! the pose shown, over the default search box (the anchors' box), with the default criteria of
//! `cdpr workspace`: tensions in bounds for the load (6.21) by the chosen method, plus l_i ≥ l_min
//! (6.22) and |det J| ≥ D_min (6.24) when the robot file gives these limits. It is the
//! `MeshRequest` of `cdpr-api` (the request behind `cdpr workspace --boundary mesh`), run
//! single-threaded in the browser (without the `parallel` feature): same verdicts, same mesh.
//!
//! ## References
//! - The thesis chapter on planar tendon-driven manipulators, eqs. (6.21)–(6.24), Algorithm 6.2.
//! - Lorensen & Cline 1987 (marching cubes).

use crate::grid::orientation_of;
use crate::state::parse_method;
use crate::{Studio, StudioError};
use cdpr_api::{MeshRequest, Robot, WorkspaceCriteria, WorkspaceRequest};
use cdpr_kinematics::{MotionPattern, Pose};
use serde::Serialize;

/// The workspace mesh for the page (and its downloads).
#[derive(Debug, Clone, Serialize)]
pub struct MeshReport {
    /// Grid resolution m (m + 1 points per axis).
    pub grid: usize,
    /// Tension method of the tension criterion.
    pub method: String,
    /// Criteria (as `cdpr workspace --criteria` writes them).
    pub criteria: Vec<String>,
    /// Enclosed volume (m³), by the divergence theorem.
    pub volume: f64,
    /// Grid estimate of the volume: each feasible point's cell clipped to the box (m³).
    pub grid_volume: f64,
    /// Vertices (m).
    pub vertices: Vec<[f64; 3]>,
    /// Triangles (indices into `vertices`, counter-clockwise seen from outside).
    pub triangles: Vec<[u32; 3]>,
    /// The search box (min, max corners; m).
    #[serde(rename = "box")]
    pub search_box: [[f64; 3]; 2],
    /// Pose evaluations (grid and bisections).
    pub evaluations: usize,
    /// The mesh as a binary STL file (m; cdpr-workspace's writer).
    #[serde(skip)]
    pub stl: Vec<u8>,
}

impl Studio {
    /// cdpr-api's workspace request for this robot at the orientation of pose `q` (the default
    /// criteria and box of `cdpr workspace`), for the tension `method` and the external wrench
    /// `wrench` (the robot file's load added), on `grid` intervals per side.
    pub(crate) fn workspace_request(
        &self,
        q: &[f64],
        grid: usize,
        method: &str,
        wrench: Option<&[f64]>,
    ) -> Result<WorkspaceRequest, StudioError> {
        let method = parse_method(method)?;
        let dim = self.desc.robot.motion().space_dim();
        let mut request = WorkspaceRequest::new(Robot::from_description(self.desc.clone()));
        request.criteria = WorkspaceCriteria {
            method: Some(method),
            wrench: wrench.map(<[f64]>::to_vec),
            ..WorkspaceCriteria::default()
        };
        request.orientation = Some(orientation_of(q, dim));
        request.grid = Some(grid);
        Ok(request)
    }

    /// The boundary mesh at grid resolution `grid` for the orientation of pose `q`, the tension
    /// `method` and the external wrench `wrench` (gravity added). Robots moving in space only.
    pub fn workspace_mesh(
        &self,
        q: &[f64],
        grid: usize,
        method: &str,
        wrench: Option<&[f64]>,
    ) -> Result<MeshReport, StudioError> {
        let motion = self.desc.robot.motion();
        if motion.space_dim() != 3 {
            return Err(StudioError::NotApplicable {
                what: "the boundary mesh",
                needs: "a robot moving in space (point3 or spatial)",
                motion: motion.name(),
            });
        }
        let method = parse_method(method)?;
        Pose::from_coordinates(motion, q)?;
        let mut request = MeshRequest::new(Robot::from_description(self.desc.clone()));
        request.criteria.method = Some(method);
        request.criteria.wrench = wrench.map(<[f64]>::to_vec);
        request.orientation = (motion == MotionPattern::Spatial).then(|| q[3..6].to_vec());
        request.grid = Some(grid);
        let r = request.run()?;
        let mut stl = Vec::new();
        r.mesh
            .write_stl(&mut stl)
            .expect("writing into a Vec cannot fail");
        let b = &r.area_box;
        Ok(MeshReport {
            grid: r.resolution,
            method: r.tension_method,
            criteria: r.criteria,
            volume: r.volume,
            grid_volume: r.area_cells,
            search_box: [[b[0], b[2], b[4]], [b[1], b[3], b[5]]],
            evaluations: r.evaluations,
            stl,
            vertices: r.vertices,
            triangles: r.triangles,
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::test_support::open;

    #[test]
    fn mesh_of_the_8_cable_robot_is_closed_and_planar_robots_are_refused() {
        let s = open("ipanema-like-8.toml");
        let q = s.table().start_pose;
        let m = s.workspace_mesh(&q, 6, "l2", None).unwrap();
        assert!(m.volume > 0.0 && !m.triangles.is_empty());
        // Closed mesh: every edge is shared by exactly two triangles.
        let mut edges = std::collections::HashMap::new();
        for t in &m.triangles {
            for k in 0..3 {
                let (a, b) = (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3]));
                *edges.entry((a, b)).or_insert(0) += 1;
            }
        }
        assert!(edges.values().all(|&c| c == 2));
        // Same volume order as the grid count (O(h) apart at this coarse grid).
        assert!((m.volume - m.grid_volume).abs() < 0.5 * m.grid_volume);
        // Binary STL: 80-byte header, triangle count, 50 bytes per triangle.
        assert_eq!(m.stl.len(), 84 + 50 * m.triangles.len());
        let e = open("tdpm-4.toml")
            .workspace_mesh(&[0.0, 0.0, 0.0], 6, "l2", None)
            .unwrap_err();
        assert!(e.to_string().contains("planar"), "{e}");
    }
}
