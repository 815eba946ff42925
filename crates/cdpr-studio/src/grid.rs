//! # The workspace grid on demand
//!
//! The constant-orientation workspace on a regular grid (thesis Algorithm 6.2, eq. 6.23) at the
//! orientation of the pose shown: cdpr-api's [`WorkspaceRequest`], the request `cdpr workspace
//! --grid M --json` runs, with its default criteria (tension feasibility by the chosen method,
//! plus l_i ≥ l_min and |det J| ≥ D_min when the robot file gives them) and its default box (the
//! frame anchors' box). The page draws the feasible points in the scene; the measure (m² or m³)
//! is the report's, in the `cells` convention.
//!
//! ## References
//! - The thesis chapter on planar tendon-driven manipulators, Algorithm 6.2 and eq. (6.23).

use crate::{Studio, StudioError};
use cdpr_api::WorkspaceReport;
use serde::Serialize;

/// The workspace grid for the page: `cdpr workspace --json`'s report and the feasible points.
#[derive(Debug, Clone, Serialize)]
pub struct GridReport {
    /// The report (the JSON of `cdpr workspace --grid M --json`).
    #[serde(flatten)]
    pub report: WorkspaceReport,
    /// The feasible grid points (m; z = 0 for robots moving in a plane).
    pub points: Vec<[f64; 3]>,
}

/// The orientation part of a pose in motion-pattern coordinates (φ; α, β, γ; none for points).
pub(crate) fn orientation_of(q: &[f64], space_dim: usize) -> Vec<f64> {
    q.get(space_dim..).map(<[f64]>::to_vec).unwrap_or_default()
}

impl Studio {
    /// The workspace on a grid of `grid` intervals per side at the orientation of pose `q`, for
    /// the tension `method` and the external wrench `wrench` (the robot file's load added).
    pub fn workspace_grid(
        &self,
        q: &[f64],
        grid: usize,
        method: &str,
        wrench: Option<&[f64]>,
    ) -> Result<GridReport, StudioError> {
        let report = self.workspace_request(q, grid, method, wrench)?.run()?;
        let points = report
            .workspace
            .feasible_positions()
            .map(|p| [p.x, p.y, p.z])
            .collect();
        Ok(GridReport { report, points })
    }
}

#[cfg(test)]
mod tests {
    use crate::test_support::open;

    /// The points drawn are the grid points whose state is feasible with every cable at least
    /// `min_cable_length` = 0.1 m long (tdpm-4's limit): all 81 verdicts are checked against
    /// the page's own state request (tension by the same method, same load, same orientation).
    #[test]
    fn grid_points_are_the_feasible_states() {
        let s = open("tdpm-4.toml");
        let g = s.workspace_grid(&[0.0, 0.0, 0.1], 8, "l2", None).unwrap();
        let r = &g.report;
        assert_eq!(r.total_points, 81);
        assert_eq!(g.points.len(), r.feasible_points);
        assert!(r.feasible_points > 0 && r.feasible_points < r.total_points);
        // Cell area of the 8 × 8 grid over the anchors' box, by hand.
        let b = &r.area_box;
        assert!((r.cell_area - (b[1] - b[0]) * (b[3] - b[2]) / 64.0).abs() < 1e-12);
        let ws = &r.workspace;
        for idx in 0..r.total_points {
            let p = ws.point(idx);
            let st = s.state(&[p.x, p.y, 0.1], "l2", None).unwrap();
            let ok = st.feasible && st.lengths.iter().all(|&l| l >= 0.1);
            assert_eq!(ws.feasible[idx], ok, "{p:?}: {:?}", st.reason);
        }
        assert!(g.points.iter().all(|p| p[2] == 0.0));
    }

    #[test]
    fn bad_grid_requests_say_why() {
        let s = open("tdpm-4.toml");
        let e = s
            .workspace_grid(&[0.0, 0.0, 0.0], 0, "l2", None)
            .unwrap_err();
        assert!(e.to_string().contains("grid"), "{e}");
        let e = s
            .workspace_grid(&[0.0, 0.0, 0.0], 8, "no-such", None)
            .unwrap_err();
        assert!(e.to_string().contains("unknown tension method"), "{e}");
        let e = s
            .workspace_grid(&[0.0, 0.0, 0.0], 8, "l2", Some(&[1.0]))
            .unwrap_err();
        assert!(e.to_string().contains('3'), "{e}");
    }
}
