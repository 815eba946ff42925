//! # Plane sections of the workspace
//!
//! The exact boundary of the constant-orientation workspace in a plane `axis = value` by the
//! chord method (thesis §6.4.3, Algorithm 6.3: closed polygons with vertices bisected onto the
//! boundary, a chord length d apart, seeded by a coarse grid), with the criteria, box and load of
//! cdpr-api's section request, the one `cdpr workspace --section AXIS=VALUE --json` runs.
//! Robots moving in space only.
//!
//! ## References
//! - The thesis chapter on planar tendon-driven manipulators, §6.4.3 and Algorithm 6.3.

use crate::{Studio, StudioError};
use cdpr_api::{Axis, SectionPlane, SectionRequest};
use cdpr_workspace::{Section, WorkspaceError};
use nalgebra::Vector2;
use serde::Serialize;

/// A plane section for the page.
#[derive(Debug, Clone, Serialize)]
pub struct SectionReport {
    /// Axis normal to the plane (0 = x, 1 = y, 2 = z).
    pub axis: usize,
    /// Coordinate of the plane along that axis (m).
    pub value: f64,
    /// Enclosed area (m²): regions minus holes.
    pub area: f64,
    /// Chord length d (m).
    pub chord: f64,
    /// Closed boundary polygons in space (m): counter-clockwise around regions, clockwise
    /// around holes, seen in the plane's axes (a, b).
    pub loops: Vec<Vec<[f64; 3]>>,
    /// Signed area of each polygon (m²; negative: a hole).
    pub signed_areas: Vec<f64>,
    /// Pose evaluations.
    pub evaluations: usize,
}

/// The settings of one section request.
#[derive(Debug, Clone, Copy)]
pub struct SectionSettings {
    /// Axis normal to the plane (0 = x, 1 = y, 2 = z).
    pub axis: usize,
    /// Coordinate of the plane (m).
    pub value: f64,
    /// Seed grid resolution (intervals per side of the plane).
    pub grid: usize,
    /// Chord length d (m).
    pub chord: f64,
}

impl Studio {
    /// The section `s` of the workspace at the orientation of pose `q` for the tension `method`
    /// and the external wrench `wrench` (the robot file's load added).
    pub fn workspace_section(
        &self,
        q: &[f64],
        s: SectionSettings,
        method: &str,
        wrench: Option<&[f64]>,
    ) -> Result<SectionReport, StudioError> {
        let axis = *[Axis::X, Axis::Y, Axis::Z]
            .get(s.axis)
            .ok_or(StudioError::Workspace(WorkspaceError::InvalidSetting {
                what: "section axis",
                value: s.axis as f64,
                expected: "0 (x), 1 (y) or 2 (z)",
            }))?;
        let w = self.workspace_request(q, s.grid, method, wrench)?;
        let plane = SectionPlane {
            axis,
            value: s.value,
        };
        let mut request = SectionRequest::new(w.robot, plane);
        request.criteria = w.criteria;
        request.orientation = w.orientation;
        request.grid = w.grid;
        request.chord = s.chord;
        let r = request.run()?;
        let section = Section {
            axis: s.axis,
            value: s.value,
        };
        let loops = r
            .curves
            .boundaries
            .iter()
            .map(|b| {
                b.iter()
                    .map(|v| section.embed(Vector2::new(v[0], v[1])).into())
                    .collect()
            })
            .collect();
        Ok(SectionReport {
            axis: s.axis,
            value: s.value,
            area: r.curves.area,
            chord: s.chord,
            loops,
            signed_areas: r.curves.signed_areas,
            evaluations: r.curves.evaluations,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::SectionSettings;
    use crate::{RobotFileText, Studio};

    /// A massless point held by four cables at the corners of a regular tetrahedron, tensions in
    /// [1, 10⁶] N and no load: it is in equilibrium exactly where the cables can pull against
    /// each other (wrench closure), inside the tetrahedron. Its section z = 0 is the square
    /// |x| + |y| < 1, area 2 m² (by hand); the section x = 0 is the square |y| + |z| < 1.
    #[test]
    fn sections_of_the_tetrahedron_are_its_squares() {
        let text = "name = \"tetra\"\nmotion = \"point3\"\n[tension]\nmin = 1.0\nmax = 1e6\n\
            [[cables]]\nframe = [1.0, 1.0, 1.0]\n[[cables]]\nframe = [1.0, -1.0, -1.0]\n\
            [[cables]]\nframe = [-1.0, 1.0, -1.0]\n[[cables]]\nframe = [-1.0, -1.0, 1.0]\n";
        let s = Studio::open(&[RobotFileText {
            name: "tetra.toml".into(),
            text: text.into(),
        }])
        .unwrap();
        for axis in [2, 0] {
            let settings = SectionSettings {
                axis,
                value: 0.0,
                grid: 20,
                chord: 0.02,
            };
            let r = s
                .workspace_section(&[0.0, 0.0, 0.0], settings, "l2", None)
                .unwrap();
            assert!((r.area - 2.0).abs() < 2e-3, "axis {axis}: {}", r.area);
            assert_eq!(r.loops.len(), 1);
            for p in &r.loops[0] {
                assert_eq!(p[axis], 0.0);
                let [a, b] = [(axis + 1) % 3, (axis + 2) % 3];
                // Vertices on the boundary |a| + |b| = 1: the ratio t_max / t_min = 10⁶ moves
                // it inwards by ~1e-6 m (a cable's tension → 0 relative to the others there).
                assert!((p[a].abs() + p[b].abs() - 1.0).abs() < 1e-5, "{p:?}");
            }
        }
        let bad = SectionSettings {
            axis: 2,
            value: 5.0,
            grid: 20,
            chord: 0.02,
        };
        let e = s.workspace_section(&[0.0; 3], bad, "l2", None).unwrap_err();
        assert!(e.to_string().contains("section"), "{e}");
    }
}
