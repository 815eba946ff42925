//! Krut, Company & Pierrot 2004: the 3-motor planar wire robot of §IV-B and the
//! regular n-motor robots of Fig. 10, with hand-derived isotropic forces.

use approx::assert_relative_eq;
use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
use cdpr_polytope::{
    AvailableWrenchSet, IsotropicForce, hyperplane_shifting, isotropic_force, isotropic_force_of,
    krut_vertex_projection, largest_inscribed_ellipse,
};
use cdpr_tension::TensionBounds;
use nalgebra::{DVector, Vector3, dmatrix};

/// Motors on a circle of radius 1000 mm at the given angles (degrees), eqs. (20)–(21).
fn robot(angles_deg: &[f64]) -> Robot {
    let cables = angles_deg
        .iter()
        .map(|a| Cable {
            frame: Vector3::new(
                1000.0 * a.to_radians().cos(),
                1000.0 * a.to_radians().sin(),
                0.0,
            ),
            platform: Vector3::zeros(),
            pulley: None,
        })
        .collect();
    Robot::new(MotionPattern::Point2, cables).unwrap()
}

fn seed_robot() -> Robot {
    robot(&[30.0, 150.0, 270.0])
}

fn bounds(n: usize) -> TensionBounds {
    TensionBounds::uniform(n, 50.0, 500.0).unwrap()
}

fn aws_at(robot: &Robot, x: f64, y: f64) -> (AvailableWrenchSet, AvailableWrenchSet) {
    let w = robot
        .inverse_kinematics(&Pose::point(x, y, 0.0))
        .unwrap()
        .wrench_matrix();
    let b = bounds(robot.cable_count());
    (
        krut_vertex_projection::available_wrench_set(&w, &b).unwrap(),
        hyperplane_shifting::available_wrench_set(&w, &b).unwrap(),
    )
}

/// At the centre the unit vectors u_i (30°, 150°, 270°) sum to zero, so with t_i = 275 + s_i,
/// s_i ∈ [−225, 225], the AWS is the centred zonotope Σ s_i u_i: a regular hexagon. Its facet
/// orthogonal to u_1 has normal c at 120°, and c·u_2 = cos 30° = √3/2, c·u_3 = cos 150° = −√3/2,
/// so its distance from the origin is h(c) = 225(√3/2 + √3/2) = 225√3 ≈ 389.71; by the 120°
/// symmetry all six facets are at that distance.
#[test]
fn isotropic_force_at_the_centre_is_225_sqrt3() {
    let expected = 225.0 * 3f64.sqrt();
    assert_relative_eq!(expected, 389.711, epsilon = 1e-3);
    let (krut, hs) = aws_at(&seed_robot(), 0.0, 0.0);
    for aws in [&krut, &hs] {
        assert_eq!(aws.facets().len(), 6);
        assert_relative_eq!(
            isotropic_force(aws, MotionPattern::Point2).unwrap(),
            expected,
            epsilon = 1e-9
        );
        for f in aws.facets() {
            assert_relative_eq!(f.offset, expected, epsilon = 1e-9);
        }
        // Hexagon vertices: Σ ±225 u_i with one sign pattern per vertex; |vertex| = 450.
        let v = aws.vertices().unwrap();
        assert_eq!(v.len(), 6);
        for p in v {
            assert_relative_eq!(p.norm(), 450.0, epsilon = 1e-9);
        }
    }
    let mut fast = IsotropicForce::new(&seed_robot(), &bounds(3)).unwrap();
    let f = fast.force_at_pose(&Pose::point(0.0, 0.0, 0.0)).unwrap();
    assert_relative_eq!(f, expected, epsilon = 1e-9);
    // Point robot: the wrench radius is the force radius.
    let (f2, r) = fast.indices_at_pose(&Pose::point(0.0, 0.0, 0.0)).unwrap();
    assert_eq!(f2, f);
    assert_relative_eq!(r, expected, epsilon = 1e-9);
    assert!(IsotropicForce::new(&seed_robot(), &bounds(4)).is_err());
}

/// Fig. 9: the index is positive inside the workspace and negative outside (drawn white in the
/// paper): near a motor, or beyond the triangle's edge, the cables cannot balance zero load with
/// t ≥ 50.
#[test]
fn index_is_signed_across_the_workspace() {
    let r = seed_robot();
    let b = bounds(3);
    let f = |x: f64, y: f64| {
        let w = r
            .inverse_kinematics(&Pose::point(x, y, 0.0))
            .unwrap()
            .wrench_matrix();
        isotropic_force_of(MotionPattern::Point2, &w, &b).unwrap()
    };
    assert!(f(0.0, 0.0) > 0.0);
    assert!(f(100.0, -100.0) > 0.0);
    // Outside the triangle of motors (its lower-right edge joins (866, 500) and (0, −1000)).
    assert!(f(800.0, -600.0) < 0.0);
    // The centre is the best point by symmetry: moving off-centre lowers the index.
    assert!(f(200.0, 0.0) < f(0.0, 0.0));
    // Krut and hyperplane shifting agree off-centre too, including negative values.
    for (x, y) in [(300.0, 200.0), (800.0, -600.0), (-400.0, 100.0)] {
        let (krut, hs) = aws_at(&r, x, y);
        assert_relative_eq!(
            isotropic_force(&krut, MotionPattern::Point2).unwrap(),
            isotropic_force(&hs, MotionPattern::Point2).unwrap(),
            epsilon = 1e-7
        );
    }
}

/// Fig. 10: n motors regularly spaced on the circle; at the centre the AWS is the centred
/// zonotope Σ s_i u_i (Σ u_i = 0), whose facet orthogonal to u_1 is at distance
/// 225 Σ_i |sin(θ_i − θ_1)| (all facets equivalent by symmetry). The index grows with n, as the
/// paper observes.
#[test]
fn regular_robots_of_fig_10() {
    let mut previous = 0.0;
    for n in 3..=6 {
        let angles: Vec<f64> = (0..n).map(|i| 90.0 + 360.0 * i as f64 / n as f64).collect();
        let expected: f64 = 225.0
            * angles
                .iter()
                .map(|a| (a - angles[0]).to_radians().sin().abs())
                .sum::<f64>();
        let (krut, hs) = aws_at(&robot(&angles), 0.0, 0.0);
        for aws in [&krut, &hs] {
            assert_relative_eq!(
                isotropic_force(aws, MotionPattern::Point2).unwrap(),
                expected,
                epsilon = 1e-8
            );
        }
        assert!(expected > previous);
        previous = expected;
    }
    // Hand values: n = 4: 225·2 = 450; n = 6: 225·2√3 ≈ 779.42.
    let (_, hs) = aws_at(&robot(&[0.0, 90.0, 180.0, 270.0]), 0.0, 0.0);
    assert_relative_eq!(
        isotropic_force(&hs, MotionPattern::Point2).unwrap(),
        450.0,
        epsilon = 1e-9
    );
}

/// §IV-C: general redundant mechanisms with t_min = −t_max. Columns e_x, e_y, (1, 1)/√2 and
/// t ∈ [−1, 1]: facets ⊥ e_x and ⊥ e_y are at 1 + 1/√2, the facet ⊥ (1, 1)/√2 at
/// 1/√2 + 1/√2 = √2, so the isotropic force is √2, and the AWS is centrally symmetric.
#[test]
fn symmetric_bounds_of_a_general_redundant_mechanism() {
    let s = 0.5f64.sqrt();
    let w = dmatrix![1.0, 0.0, s; 0.0, 1.0, s];
    let b = TensionBounds::uniform(3, -1.0, 1.0).unwrap();
    let krut = krut_vertex_projection::available_wrench_set(&w, &b).unwrap();
    let hs = hyperplane_shifting::available_wrench_set(&w, &b).unwrap();
    for aws in [&krut, &hs] {
        assert_eq!(aws.facets().len(), 6);
        assert_relative_eq!(
            isotropic_force(aws, MotionPattern::Point2).unwrap(),
            2f64.sqrt(),
            epsilon = 1e-12
        );
        for f in aws.facets() {
            let mirror = aws
                .facets()
                .iter()
                .find(|g| (&g.normal + &f.normal).amax() < 1e-9)
                .expect("mirror facet");
            assert_relative_eq!(mirror.offset, f.offset, epsilon = 1e-12);
        }
        assert!(aws.contains(&DVector::from_vec(vec![1.0 + s, 1.0 + s])));
    }
}

/// The second index of §IV-C at the centre of the paper's robot: the AWS is a regular hexagon
/// with apothem 225√3, so the largest centred ellipse is its inscribed circle.
#[test]
fn largest_ellipse_of_the_seed_robot_is_the_inscribed_circle() {
    let (_, hs) = aws_at(&seed_robot(), 0.0, 0.0);
    let e = largest_inscribed_ellipse(&hs).unwrap().unwrap();
    assert_relative_eq!(e.semi_axes[0], 225.0 * 3f64.sqrt(), max_relative = 1e-6);
    assert_relative_eq!(e.semi_axes[1], 225.0 * 3f64.sqrt(), max_relative = 1e-6);
    // Off-centre the hexagon is no longer regular: the ellipse is elongated but still inside.
    let (_, hs) = aws_at(&seed_robot(), 150.0, 50.0);
    let e = largest_inscribed_ellipse(&hs).unwrap().unwrap();
    assert!(e.semi_axes[0] > e.semi_axes[1] * 1.001);
    for f in hs.facets() {
        let n = nalgebra::Vector2::new(f.normal[0], f.normal[1]);
        assert!(e.support(&n) <= f.offset * (1.0 + 1e-9));
    }
}
