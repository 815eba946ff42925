//! The chord method (thesis §6.4.3, Algorithm 6.3).
use crate::common;

use cdpr_kinematics::Pose;
use cdpr_tension::Method;
use cdpr_workspace::{
    ChordSettings, ChordWorkspace, Grid, InteriorPoint, PoseEvaluator, Region, chord_workspace,
    planar_workspace,
};
use common::*;
use proptest::prelude::*;
use std::f64::consts::PI;

fn settings(chord: f64) -> ChordSettings {
    ChordSettings {
        chord,
        ..Default::default()
    }
}

/// Every vertex is feasible; a point 10⁻⁶ outside along the outward normal is not (vertices
/// next to a bifurcation point are skipped: the normal is undefined at a corner).
fn assert_on_boundary(eval: &PoseEvaluator, phi: f64, ws: &ChordWorkspace) {
    let region = Region::frame_bounding_box(eval.robot());
    assert_on_boundary_in(eval, phi, ws, &region);
}

/// As [`assert_on_boundary`], where points outside `region` count as outside the workspace.
fn assert_on_boundary_in(eval: &PoseEvaluator, phi: f64, ws: &ChordWorkspace, region: &Region) {
    let mut ev = eval.clone();
    let mut tested = 0;
    for poly in &ws.boundaries {
        let n = poly.vertices.len();
        let near_corner = |k: usize| {
            poly.bifurcations
                .iter()
                .any(|&b| (k + n - b) % n <= 2 || (b + n - k) % n <= 2)
        };
        for (k, v) in poly.vertices.iter().enumerate() {
            assert!(
                ev.is_feasible(&Pose::planar(v[0], v[1], phi)),
                "vertex {v:?}"
            );
            if near_corner(k) {
                continue;
            }
            // Right of the walking direction: out of the workspace, around regions and holes.
            let nrm = poly.outward_normal(k);
            let out = [v[0] + 1e-6 * nrm[0], v[1] + 1e-6 * nrm[1]];
            let out_pose = Pose::planar(out[0], out[1], phi);
            assert!(
                !region.contains(&out_pose.position, 2) || !ev.is_feasible(&out_pose),
                "outside {out:?} of {v:?}"
            );
            tested += 1;
        }
    }
    assert!(tested > 0);
}

#[test]
fn disc_vertices_lie_on_the_circle_and_area_converges() {
    let r = 0.6;
    let eval = shape_eval(move |x, y| (x - 0.1).powi(2) + y * y <= r * r);
    let mut prev_err = f64::INFINITY;
    for d in [0.1, 0.05, 0.025] {
        let ws = chord_workspace(&eval, 0.0, &unit_box(), &settings(d)).unwrap();
        assert_eq!(ws.boundaries.len(), 1);
        let poly = &ws.boundaries[0];
        for v in &poly.vertices {
            let rho = ((v[0] - 0.1).powi(2) + v[1] * v[1]).sqrt();
            assert!(rho <= r && r - rho < 1e-8, "{rho}");
            // Chord length d between successive points (the closing chord is shorter).
        }
        assert!(poly.signed_area() > 0.0, "walked counter-clockwise");
        assert!(poly.bifurcations.is_empty());
        // An inscribed polygon with chords d misses 2πr/d circular segments of area d³/(12 r):
        // π d²/6 in all.
        let err = PI * r * r - ws.area;
        assert!(err > 0.0 && err < PI * d * d / 6.0 * 1.1, "{err}");
        assert!(err < prev_err);
        prev_err = err;
        assert_on_boundary_in(&eval, 0.0, &ws, &unit_box());
    }
}

#[test]
fn annulus_has_a_hole_with_negative_area() {
    let eval = shape_eval(|x, y| {
        let r2 = x * x + y * y;
        (0.09..=0.49).contains(&r2)
    });
    let ws = chord_workspace(&eval, 0.0, &unit_box(), &settings(0.02)).unwrap();
    assert_eq!(ws.boundaries.len(), 2);
    let mut areas: Vec<f64> = ws.boundaries.iter().map(|b| b.signed_area()).collect();
    areas.sort_by(f64::total_cmp);
    assert!((areas[0] + PI * 0.09).abs() < 2e-3, "{areas:?}");
    assert!((areas[1] - PI * 0.49).abs() < 2e-3, "{areas:?}");
    assert!((ws.area - PI * 0.4).abs() < 4e-3);
    assert!(ws.contains([0.5, 0.0]) && !ws.contains([0.0, 0.0]) && !ws.contains([0.9, 0.0]));
    assert_on_boundary_in(&eval, 0.0, &ws, &unit_box());
}

#[test]
fn square_workspace_finds_its_four_corners() {
    // |x|, |y| ≤ 0.4, axis-aligned: corners are bifurcation points.
    let eval = shape_eval(|x, y| x.abs() <= 0.4 && y.abs() <= 0.4);
    let ws = chord_workspace(&eval, 0.0, &unit_box(), &settings(0.05)).unwrap();
    assert_eq!(ws.boundaries.len(), 1);
    let p = &ws.boundaries[0];
    assert!((ws.area - 0.64).abs() < 1e-4, "{}", ws.area);
    assert_eq!(p.bifurcations.len(), 4, "{:?}", p.bifurcations);
    for &k in &p.bifurcations {
        let v = p.vertices[k];
        // Located to within two of the finest chords d/64.
        let tol = 2.0 * 0.05 / 64.0 + 1e-8;
        assert!(
            (v[0].abs() - 0.4).abs() < tol && (v[1].abs() - 0.4).abs() < tol,
            "{v:?}"
        );
    }
}

#[test]
fn region_cuts_the_workspace() {
    // Everything feasible: the boundary is the region itself.
    let eval = shape_eval(|_, _| true);
    let ws = chord_workspace(
        &eval,
        0.0,
        &Region::planar(-0.3, 0.5, -0.2, 0.1),
        &settings(0.05),
    )
    .unwrap();
    assert_eq!(ws.boundaries.len(), 1);
    // Only the corners are cut, by less than the finest chord d/64.
    assert!(
        (ws.area - 0.8 * 0.3).abs() < 4.0 * (0.05f64 / 64.0).powi(2),
        "{}",
        ws.area
    );
    assert_eq!(ws.boundaries[0].bifurcations.len(), 4);
}

#[test]
fn separate_regions_are_all_found() {
    let eval = shape_eval(|x, y| {
        (x + 0.5).powi(2) + y * y <= 0.09
            || (x - 0.5).powi(2) + y * y <= 0.04
            || (x.abs() < 0.1 && (y - 0.7).abs() < 0.1)
    });
    let ws = chord_workspace(&eval, 0.0, &unit_box(), &settings(0.02)).unwrap();
    assert_eq!(ws.boundaries.len(), 3);
    assert!((ws.area - (PI * 0.13 + 0.04)).abs() < 2e-3);
}

/// Thesis Fig. 6.4 (left column): the 3-cable workspace at φ = 0 is split at x = 0 by the
/// singularity det J = 0; the chord method maps both parts (under L1 and L2; under L3 the torque
/// leaves only the part x > 0, see `thesis.rs`).
#[test]
fn three_cable_phi_zero_has_two_regions_split_at_x_zero() {
    for load_case in 0..2 {
        let eval = three_cable_eval(load_case);
        let region = Region::frame_bounding_box(eval.robot());
        let ws = chord_workspace(&eval, 0.0, &region, &settings(0.03)).unwrap();
        let sides: Vec<(bool, bool)> = ws
            .boundaries
            .iter()
            .map(|b| {
                (
                    b.vertices.iter().all(|v| v[0] < 0.0),
                    b.vertices.iter().all(|v| v[0] > 0.0),
                )
            })
            .collect();
        assert!(
            sides.iter().any(|s| s.0),
            "L{}: no region left of x = 0",
            load_case + 1
        );
        assert!(
            sides.iter().any(|s| s.1),
            "L{}: no region right of x = 0",
            load_case + 1
        );
        assert!(
            sides.iter().all(|s| s.0 || s.1),
            "L{}: a region crosses x = 0",
            load_case + 1
        );
        assert_eq!(ws.abandoned, 0);
        assert_on_boundary(&eval, 0.0, &ws);
    }
}

/// The grid area converges to the chord area as m grows (m = 50, 100, 200): each grid
/// estimate is within the band of cells the boundary crosses (|ΔA| ≤ 2 P h, P the perimeter),
/// and the mean relative gap over several workspaces shrinks.
#[test]
fn grid_area_converges_to_chord_area() {
    let cases = [
        (three_cable_eval(0), 0.1),
        (three_cable_eval(2), 0.05),
        (four_cable_eval(0, Method::L2), 0.0),
        (four_cable_eval(1, Method::L2), 0.1),
        (four_cable_eval(2, Method::L1), -0.2),
    ];
    let mut mean = [0.0; 3];
    for (eval, phi) in &cases {
        let region = Region::frame_bounding_box(eval.robot());
        let chord = chord_workspace(eval, *phi, &region, &settings(0.02)).unwrap();
        let perimeter: f64 = chord.boundaries.iter().map(|b| b.perimeter()).sum();
        for (k, m) in [50, 100, 200].into_iter().enumerate() {
            let g = planar_workspace(eval, *phi, &Grid::new(m, region)).unwrap();
            let h = (region.max - region.min).max() / m as f64;
            assert!(
                (g.area - chord.area).abs() <= 2.0 * perimeter * h,
                "m = {m}: {} vs {}",
                g.area,
                chord.area
            );
            mean[k] += (g.area - chord.area).abs() / chord.area / cases.len() as f64;
        }
        assert_on_boundary(eval, *phi, &chord);
    }
    assert!(mean[2] < mean[1] && mean[1] < mean[0], "{mean:?}");
    assert!(mean[2] < 0.01, "{mean:?}");
}

/// The interior-point options (eq. (6.25), a given point, the coarse grid) map the same set.
#[test]
fn interior_point_options_agree() {
    let eval = four_cable_eval(1, Method::L2);
    let region = Region::frame_bounding_box(eval.robot());
    let base = chord_workspace(&eval, 0.05, &region, &settings(0.05)).unwrap();
    for interior in [
        InteriorPoint::TensionCentering,
        InteriorPoint::Given([0.0, 0.0]),
    ] {
        for all_regions in [false, true] {
            let s = ChordSettings {
                interior,
                all_regions,
                ..settings(0.05)
            };
            let ws = chord_workspace(&eval, 0.05, &region, &s).unwrap();
            assert_eq!(ws.boundaries.len(), base.boundaries.len());
            assert!(
                (ws.area - base.area).abs() < 1e-3 * base.area,
                "{} vs {}",
                ws.area,
                base.area
            );
        }
    }
}

#[test]
fn bad_input_is_an_error() {
    let spatial = PoseEvaluator::new(
        eight_cable_spatial(),
        cdpr_tension::TensionBounds::uniform(8, 1.0, 10.0).unwrap(),
        vec![],
    )
    .unwrap();
    assert!(matches!(
        chord_workspace(&spatial, 0.0, &unit_box(), &settings(0.05)),
        Err(cdpr_workspace::WorkspaceError::NotPlanar { .. })
    ));
    let eval = four_cable_eval(0, Method::L2);
    let region = Region::frame_bounding_box(eval.robot());
    assert!(chord_workspace(&eval, f64::NAN, &region, &settings(0.05)).is_err());
    assert!(chord_workspace(&eval, 0.0, &region, &settings(0.0)).is_err());
    assert!(
        chord_workspace(
            &eval,
            0.0,
            &Region::planar(0.0, -1.0, 0.0, 1.0),
            &settings(0.05)
        )
        .is_err()
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]
    /// Random discs: vertices on the circle, area within the inscribed-polygon bound.
    #[test]
    fn random_discs(cx in -0.4f64..0.4, cy in -0.4f64..0.4, r in 0.1f64..0.5) {
        let eval = shape_eval(move |x, y| (x - cx).powi(2) + (y - cy).powi(2) <= r * r);
        let ws = chord_workspace(&eval, 0.0, &unit_box(), &settings(0.05)).unwrap();
        let inside_box = (cx.abs() + r <= 1.0) && (cy.abs() + r <= 1.0);
        prop_assume!(inside_box);
        prop_assert_eq!(ws.boundaries.len(), 1);
        for v in &ws.boundaries[0].vertices {
            let rho = ((v[0] - cx).powi(2) + (v[1] - cy).powi(2)).sqrt();
            prop_assert!(rho <= r && r - rho < 1e-8);
        }
        let exact = PI * r * r;
        prop_assert!(ws.area <= exact && exact - ws.area < PI * 0.05 * 0.05 / 6.0 * 1.1);
    }
}
