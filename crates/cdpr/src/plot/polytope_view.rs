//! # The 3-D force polytope view
//!
//! The available force polytope {W t : t_min ≤ t ≤ t_max} of a point3 robot (Krut, Company &
//! Pierrot 2004, §III) as a [`Scene`] for the HTML viewer: its faces
//! ([`AvailableWrenchSet::faces`]) split into triangles, in N, and the largest ball centred at
//! −w_ext inside it, whose radius is the maximum isotropic force (eq. 19).
//!
//! ## References
//! - S. Krut, O. Company, F. Pierrot, *Force performance indexes for parallel mechanisms with
//!   actuation redundancy, especially for parallel wire-driven manipulators*, IROS 2004
//!   (Krut, Company & Pierrot 2004), eqs. (3), (19).

use super::Scene;
use cdpr_polytope::AvailableWrenchSet;

/// The scene of a bounded 3-D available wrench set with the ball (centre, radius) in it (no
/// ball when the radius is not positive); `None` when the set has no faces (not DOF 3, or
/// unbounded). Triangles fan out from each face's first vertex, counter-clockwise seen from
/// outside like the faces.
pub fn force_polytope_scene(
    aws: &AvailableWrenchSet,
    centre: [f64; 3],
    radius: f64,
) -> Option<Scene> {
    if aws.dof() != 3 {
        return None;
    }
    let (vs, faces) = (aws.vertices()?, aws.faces()?);
    let vertices: Vec<[f64; 3]> = vs.iter().map(|v| [v[0], v[1], v[2]]).collect();
    let triangles = faces
        .iter()
        .flat_map(|f| {
            let v = &f.vertices;
            (1..v.len().saturating_sub(1)).map(move |k| [v[0], v[k], v[k + 1]].map(|i| i as u32))
        })
        .collect();
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in &vertices {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    Some(Scene {
        vertices,
        triangles,
        region: (lo, hi),
        units: "N".into(),
        hide_box: true,
        mesh_label: format!(
            "available force polytope {{W t}} ({} faces, {} vertices)",
            faces.len(),
            vs.len()
        ),
        ball: (radius > 0.0).then_some((centre, radius)),
        ball_label: "largest ball centred at −w_ext (its radius: the maximum isotropic force)"
            .into(),
        ..Scene::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use cdpr_polytope::hyperplane_shifting::available_wrench_set;
    use cdpr_tension::TensionBounds;
    use nalgebra::{DMatrix, Vector3};

    /// Three orthogonal unit cables with tensions in [0, 1]: the unit cube, 6 faces, 12
    /// outward triangles enclosing volume 1 (divergence theorem).
    #[test]
    fn cube_polytope_is_a_closed_outward_mesh() {
        let aws = available_wrench_set(
            &DMatrix::identity(3, 3),
            &TensionBounds::uniform(3, 0.0, 1.0).unwrap(),
        )
        .unwrap();
        let s = force_polytope_scene(&aws, [0.5; 3], 0.5).unwrap();
        assert_eq!((s.vertices.len(), s.triangles.len()), (8, 12));
        let vol: f64 = s
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| Vector3::from(s.vertices[i as usize]));
                a.dot(&b.cross(&c)) / 6.0
            })
            .sum();
        assert!((vol - 1.0).abs() < 1e-12, "{vol}");
        assert_eq!(s.region, ([0.0; 3], [1.0; 3]));
        assert_eq!(s.ball, Some(([0.5; 3], 0.5)));
        assert!(
            force_polytope_scene(&aws, [0.0; 3], -1.0)
                .unwrap()
                .ball
                .is_none()
        );
    }
}
