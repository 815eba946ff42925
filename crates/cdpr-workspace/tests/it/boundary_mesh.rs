//! Boundary meshes of 3-D workspaces (`boundary_mesh.rs`): exact volumes of box-clipped
//! polyhedral workspaces, closure and orientation on every test robot, vertices on the boundary,
//! several components, cavities and tunnels.

use crate::common;

use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot, reference_robots::ipanema_like_8};
use cdpr_tension::{Method, TensionBounds};
use cdpr_workspace::ChordSettings;
use cdpr_workspace::{
    BoundaryMesh, BoxFace, Criterion, CustomCriterion, Grid, MeshSettings, MeshVertex,
    PoseEvaluator, Region, Section, WorkspaceError, boundary_mesh, chord_section,
    constant_orientation_workspace,
};
use nalgebra::{DVector, Rotation3, Vector3};
use proptest::prelude::*;

fn point(p: Vector3<f64>) -> Cable {
    Cable {
        frame: p,
        platform: Vector3::zeros(),
        pulley: None,
    }
}

/// A point robot with four cables: its wrench-closure workspace is the open tetrahedron of the
/// anchors (Gouttefarde & Gosselin 2006: W positively spans R³ iff u is inside the hull).
fn tetra_eval(anchors: [Vector3<f64>; 4]) -> PoseEvaluator {
    let robot = Robot::new(MotionPattern::Point3, anchors.map(point).to_vec()).unwrap();
    PoseEvaluator::new(
        robot,
        TensionBounds::uniform(4, 0.0, 1.0).unwrap(),
        vec![Criterion::WrenchClosure],
    )
    .unwrap()
}

/// A point robot (cables far away) whose workspace is `{u : inside(u)}`.
fn shape_eval(inside: impl Fn(Vector3<f64>) -> bool + Send + Sync + 'static) -> PoseEvaluator {
    let robot = Robot::new(
        MotionPattern::Point3,
        vec![
            point(Vector3::new(9.0, 9.0, 9.0)),
            point(Vector3::new(9.0, -9.0, -9.0)),
            point(Vector3::new(-9.0, 9.0, -9.0)),
            point(Vector3::new(-9.0, -9.0, 9.0)),
        ],
    )
    .unwrap();
    PoseEvaluator::new(
        robot,
        TensionBounds::uniform(4, 0.0, 1.0).unwrap(),
        vec![Criterion::Custom(CustomCriterion::new(
            "shape",
            move |ctx| inside(ctx.pose.position),
        ))],
    )
    .unwrap()
}

fn mesh(eval: &PoseEvaluator, m: usize, region: Region) -> BoundaryMesh {
    boundary_mesh(
        eval,
        &Rotation3::identity(),
        &Grid::new(m, region),
        &MeshSettings::default(),
    )
    .unwrap()
}

fn cube(h: f64) -> Region {
    Region::cuboid(Vector3::repeat(-h), Vector3::repeat(h))
}

/// Volume of the box [lo, hi] ∩ {n·x ≤ d}, by hand: in unit-cube coordinates u the half-space is
/// a·u ≤ c with a_i = n_i L_i, c = d − n·lo; flipping u_i → 1 − u_i makes every a_i > 0, and then
/// the inclusion–exclusion formula for a corner simplex clipped by the cube gives
/// vol = (1 / (6 a₁a₂a₃)) Σ_{ε ∈ {0,1}³} (−1)^{|ε|} max(0, c − a·ε)³ (times L₁L₂L₃).
fn clipped_box_volume(lo: Vector3<f64>, hi: Vector3<f64>, n: Vector3<f64>, d: f64) -> f64 {
    let l = hi - lo;
    let mut a = n.component_mul(&l);
    let mut c = d - n.dot(&lo);
    for i in 0..3 {
        if a[i] < 0.0 {
            c -= a[i];
            a[i] = -a[i];
        }
    }
    let mut s = 0.0;
    for e in 0..8 {
        let eps = Vector3::new((e & 1) as f64, (e >> 1 & 1) as f64, (e >> 2) as f64);
        let sign = if (e as u32).count_ones().is_multiple_of(2) {
            1.0
        } else {
            -1.0
        };
        s += sign * (c - a.dot(&eps)).max(0.0).powi(3);
    }
    s / (6.0 * a.x * a.y * a.z) * l.x * l.y * l.z
}

/// The tetrahedral robot whose workspace, in a box about `centre`, is the half-space on the
/// fourth anchor's side of the plane through `centre` with normal `n` (three anchors in that
/// plane 50 box sizes away, the fourth 50 away along −n, so no other face meets the box).
fn half_space_robot(centre: Vector3<f64>, n: Vector3<f64>) -> PoseEvaluator {
    let n = n.normalize();
    let t1 = n.cross(&Vector3::new(0.3, 0.5, 0.7)).normalize();
    let t2 = n.cross(&t1);
    let r = 50.0;
    let a = |k: f64| {
        let ang = k * std::f64::consts::TAU / 3.0;
        centre + (t1 * ang.cos() + t2 * ang.sin()) * r
    };
    tetra_eval([a(0.0), a(1.0), a(2.0), centre - n * r])
}

/// The feasible side of that plane is n·x ≤ n·centre: exact volume, closed mesh, caps on the
/// faces the half-space reaches.
#[test]
fn half_space_clipped_by_the_box_has_its_exact_volume() {
    let centre = Vector3::new(0.1, -0.05, 0.2);
    let n = Vector3::new(0.3, -0.5, 0.8).normalize();
    let eval = half_space_robot(centre, n);
    let region = cube(1.0);
    let exact = clipped_box_volume(region.min, region.max, n, n.dot(&centre));
    for m in [4, 11, 30] {
        let mesh = mesh(&eval, m, region);
        assert_eq!(mesh.edge_defects(), 0, "m = {m}");
        assert_eq!(mesh.components, 1);
        assert_eq!(mesh.shells[0].genus, 0);
        assert!(
            (mesh.volume - exact).abs() <= 1e-6 * exact,
            "m = {m}: {} vs {exact}",
            mesh.volume
        );
        // The grid count is much further off.
        assert!((mesh.grid.area - exact).abs() > 100.0 * (mesh.volume - exact).abs());
    }
    // n = (0.3, −0.5, 0.8): the plane through the centre cuts the box; feasible below it.
    let mesh = mesh(&eval, 10, region);
    assert_eq!(mesh.box_faces_reached, [true; 6]);
}

/// The whole box feasible: the mesh is the box, six caps, volume and area exact.
#[test]
fn a_box_inside_the_workspace_is_closed_by_its_faces() {
    let eval = shape_eval(|_| true);
    let region = Region::cuboid(Vector3::new(-1.0, 0.0, 0.5), Vector3::new(2.0, 0.5, 1.5));
    let mesh = mesh(&eval, 5, region);
    assert_eq!(mesh.edge_defects(), 0);
    assert!((mesh.volume - 1.5).abs() < 1e-12);
    assert!((mesh.surface_area - 2.0 * (1.5 + 3.0 + 0.5)).abs() < 1e-12);
    assert_eq!(mesh.cap_area, mesh.surface_area);
    assert_eq!(mesh.box_faces_reached, [true; 6]);
    assert!(mesh.caps.iter().all(Option::is_some));
    // An empty workspace has an empty mesh.
    let none = shape_eval(|_| false);
    let empty = boundary_mesh(
        &none,
        &Rotation3::identity(),
        &Grid::new(4, region),
        &MeshSettings::default(),
    )
    .unwrap();
    assert!(empty.triangles.is_empty() && empty.volume == 0.0 && empty.components == 0);
}

/// The tetrahedron of the doc example, entirely inside the box: one closed shell, no face
/// reached; the volume converges to 8/3 and beats the grid count.
#[test]
fn tetrahedron_volume_converges_faster_than_the_grid_count() {
    let eval = tetra_eval([
        Vector3::new(1.0, 1.0, 1.0),
        Vector3::new(1.0, -1.0, -1.0),
        Vector3::new(-1.0, 1.0, -1.0),
        Vector3::new(-1.0, -1.0, 1.0),
    ]);
    let exact = 8.0 / 3.0;
    let mut errors = Vec::new();
    for m in [10, 20, 40] {
        let mesh = mesh(&eval, m, cube(1.1));
        assert_eq!(mesh.edge_defects(), 0);
        // The tetrahedron, plus grid points isolated in its thin spikes near the anchors.
        assert!(mesh.components >= 1 && mesh.regions() == mesh.components);
        assert_eq!(mesh.box_faces_reached, [false; 6]);
        errors.push((mesh.volume - exact).abs());
    }
    // Second order: halving h divides the error by about 4 (by 2 for the grid count).
    assert!(
        errors[1] < 0.35 * errors[0] && errors[2] < 0.35 * errors[1],
        "{errors:?}"
    );
    assert!(errors[2] < 6e-3 * exact, "{errors:?}");
}

/// Every crossing vertex is on the boundary: the criterion holds a little way towards the
/// feasible end of its grid edge and fails a little way towards the other end.
fn assert_vertices_on_boundary(
    eval: &PoseEvaluator,
    mesh: &BoundaryMesh,
    rotation: Rotation3<f64>,
) {
    let mut ev = eval.clone();
    let size = mesh.grid.grid.region.extent().max();
    let delta = 10.0 * mesh.tolerance;
    assert!(mesh.tolerance <= 1e-8 * size * (1.0 + 1e-12));
    let mut checked = 0;
    let step = (mesh.vertices.len() / 300).max(1);
    for (v, o) in mesh.vertices.iter().zip(&mesh.origins).step_by(step) {
        let MeshVertex::Crossing {
            feasible_end,
            infeasible_end,
            ..
        } = *o
        else {
            continue;
        };
        let v = Vector3::from(*v);
        let dir = (Vector3::from(infeasible_end) - Vector3::from(feasible_end)).normalize();
        assert!(
            ev.is_feasible(&Pose::new(v - dir * delta, rotation)),
            "feasible side of {v:?}"
        );
        assert!(
            !ev.is_feasible(&Pose::new(v + dir * delta, rotation)),
            "infeasible side of {v:?}"
        );
        checked += 1;
    }
    assert!(checked >= 1, "no crossing vertex checked");
}

/// The 8-cable IPAnema-like robot with gravity (l2 tensions in [10, 1000] N, 5 kg), box = its
/// frame, at the identity and at a tilted orientation.
#[test]
fn ipanema_like_wrench_feasible_mesh_is_closed_with_vertices_on_the_boundary() {
    let robot = ipanema_like_8();
    let (lo, hi) = robot.frame_bounding_box();
    let eval = PoseEvaluator::new(
        robot,
        TensionBounds::uniform(8, 10.0, 1000.0).unwrap(),
        vec![
            Criterion::TensionFeasible {
                method: Method::L2,
                wrench: DVector::from_vec(vec![0.0, 0.0, -5.0 * 9.80665, 0.0, 0.0, 0.0]),
            },
            Criterion::MinCableLength(0.05),
        ],
    )
    .unwrap();
    for rotation in [
        Rotation3::identity(),
        Rotation3::from_euler_angles(0.05, -0.03, 0.04),
    ] {
        let grid = Grid::new(14, Region::cuboid(lo, hi));
        let mesh = boundary_mesh(&eval, &rotation, &grid, &MeshSettings::default()).unwrap();
        assert_eq!(mesh.edge_defects(), 0);
        assert!(mesh.volume > 0.0 && mesh.volume < 24.0);
        let grid_ws = constant_orientation_workspace(&eval, &rotation, &grid).unwrap();
        assert_eq!(mesh.grid.feasible, grid_ws.feasible);
        assert!(mesh.volume > 0.5 * 24.0, "{}", mesh.volume);
        assert!((mesh.volume - grid_ws.area).abs() < 0.2 * mesh.volume);
        assert_vertices_on_boundary(&eval, &mesh, rotation);
    }
}

/// Two balls, a spherical shell (a cavity) and a solid torus: components, signs and genus.
#[test]
fn components_cavities_and_tunnels() {
    let two = shape_eval(|u| {
        (u - Vector3::new(-0.5, 0.0, 0.0)).norm() < 0.35
            || (u - Vector3::new(0.5, 0.13, 0.02)).norm() < 0.3
    });
    let mesh2 = mesh(&two, 40, cube(1.0));
    assert_eq!(mesh2.edge_defects(), 0);
    assert_eq!(
        (mesh2.components, mesh2.regions(), mesh2.cavities()),
        (2, 2, 0)
    );
    let balls = 4.0 / 3.0 * std::f64::consts::PI * (0.35f64.powi(3) + 0.3f64.powi(3));
    assert!((mesh2.volume - balls).abs() < 0.03 * balls);
    assert_vertices_on_boundary(&two, &mesh2, Rotation3::identity());

    let shell = shape_eval(|u| (0.3..0.8).contains(&u.norm()));
    let mesh_s = mesh(&shell, 40, cube(1.0));
    assert_eq!(mesh_s.edge_defects(), 0);
    assert_eq!((mesh_s.regions(), mesh_s.cavities()), (1, 1));
    let exact = 4.0 / 3.0 * std::f64::consts::PI * (0.8f64.powi(3) - 0.3f64.powi(3));
    assert!((mesh_s.volume - exact).abs() < 0.03 * exact);

    let torus = shape_eval(|u| {
        let r = (u.x * u.x + u.y * u.y).sqrt() - 0.6;
        r * r + u.z * u.z < 0.25 * 0.25
    });
    let mesh_t = mesh(&torus, 40, cube(1.0));
    assert_eq!(mesh_t.edge_defects(), 0);
    assert_eq!((mesh_t.components, mesh_t.shells[0].genus), (1, 1));
    let exact = 2.0 * std::f64::consts::PI.powi(2) * 0.6 * 0.25 * 0.25;
    assert!((mesh_t.volume - exact).abs() < 0.03 * exact);
}

/// A ball cut by the box: only the faces it crosses are reached and capped.
#[test]
fn caps_only_where_the_workspace_reaches_the_box() {
    let ball = shape_eval(|u| (u - Vector3::new(0.0, 0.0, 1.0)).norm() < 0.6);
    let mesh = mesh(&ball, 20, cube(1.0));
    assert_eq!(mesh.edge_defects(), 0);
    let reached: Vec<_> = BoxFace::ALL
        .iter()
        .filter(|f| mesh.box_faces_reached[**f as usize])
        .collect();
    assert_eq!(reached, [&BoxFace::ZMax]);
    assert!(mesh.caps.iter().flatten().all(|&f| f == BoxFace::ZMax));
    // Half a ball: its cap is a disc of radius 0.6 at z = 1.
    let disc = std::f64::consts::PI * 0.36;
    assert!((mesh.cap_area - disc).abs() < 0.03 * disc);
    let half = 2.0 / 3.0 * std::f64::consts::PI * 0.216;
    assert!((mesh.volume - half).abs() < 0.03 * half);
}

#[test]
fn planar_robots_and_bad_settings_are_usage_errors() {
    let eval = common::four_cable_eval(0, Method::L2);
    let err = boundary_mesh(
        &eval,
        &Rotation3::identity(),
        &Grid::new(10, cube(1.0)),
        &MeshSettings::default(),
    )
    .unwrap_err();
    assert!(matches!(err, WorkspaceError::NotSpatial { .. }), "{err}");
    let ball = shape_eval(|u| u.norm() < 0.5);
    for tolerance in [0.0, -1.0, f64::NAN, 0.5] {
        assert!(
            boundary_mesh(
                &ball,
                &Rotation3::identity(),
                &Grid::new(4, cube(1.0)),
                &MeshSettings { tolerance },
            )
            .is_err()
        );
    }
    assert!(
        boundary_mesh(
            &ball,
            &Rotation3::identity(),
            &Grid::new(0, cube(1.0)),
            &MeshSettings::default()
        )
        .is_err()
    );
}

/// Plane sections by the chord method: a ball's section z = c is the disc of radius
/// √(r² − c²); the half-space's section is a triangle of known area; planar robots are refused.
#[test]
fn plane_sections_by_the_chord_method() {
    let ball = shape_eval(|u| (u - Vector3::new(0.1, 0.0, 0.0)).norm() < 0.7);
    let settings = ChordSettings {
        chord: 0.02,
        ..ChordSettings::default()
    };
    for (axis, value) in [(2, 0.3), (1, -0.2), (0, 0.5)] {
        let ws = chord_section(
            &ball,
            &Rotation3::identity(),
            Section { axis, value },
            &cube(1.0),
            &settings,
        )
        .unwrap();
        let offset = if axis == 0 { value - 0.1 } else { value };
        let exact = std::f64::consts::PI * (0.49 - offset * offset);
        assert_eq!(ws.boundaries.len(), 1);
        assert!(
            (ws.area - exact).abs() < 2e-3 * exact,
            "{axis}: {} vs {exact}",
            ws.area
        );
        // Every vertex on the sphere to ε.
        for v in &ws.boundaries[0].vertices {
            let p = Section { axis, value }.embed(nalgebra::Vector2::from(*v));
            assert!(((p - Vector3::new(0.1, 0.0, 0.0)).norm() - 0.7).abs() < 1e-7);
        }
    }
    // The half-space x + y + z ≤ 0.2 in [−1, 1]³ at y = 0.4: x + z ≤ c = −0.2 in [−1, 1]², the
    // corner triangle below the line, legs c + 2 = 1.8: area 1.8²/2 = 1.62.
    let n = Vector3::new(1.0, 1.0, 1.0);
    let eval = half_space_robot(Vector3::new(0.2 / 3.0, 0.2 / 3.0, 0.2 / 3.0), n);
    let ws = chord_section(
        &eval,
        &Rotation3::identity(),
        Section {
            axis: 1,
            value: 0.4,
        },
        &cube(1.0),
        &ChordSettings::default(),
    )
    .unwrap();
    assert!((ws.area - 1.62).abs() < 1e-6, "{}", ws.area);
    let planar = common::four_cable_eval(0, Method::L2);
    assert!(matches!(
        chord_section(
            &planar,
            &Rotation3::identity(),
            Section {
                axis: 2,
                value: 0.0
            },
            &cube(1.0),
            &ChordSettings::default()
        ),
        Err(WorkspaceError::NotSpatial { .. })
    ));
    assert!(
        chord_section(
            &ball,
            &Rotation3::identity(),
            Section {
                axis: 2,
                value: 1.5
            },
            &cube(1.0),
            &settings
        )
        .is_err()
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// A robot family with a known volume: random half-space workspaces (random plane through a
    /// random point of a random box) match the hand formula to 1e-6, closed, every vertex on
    /// the boundary.
    #[test]
    fn random_half_spaces_have_exact_volumes(
        c in prop::array::uniform3(-0.4..0.4f64),
        n in prop::array::uniform3(0.2..1.0f64),
        signs in prop::array::uniform3(any::<bool>()),
        ext in prop::array::uniform3(0.5..2.0f64),
        m in 3usize..16,
    ) {
        let n = Vector3::from(n).zip_map(&Vector3::from(signs.map(|s| if s { 1.0 } else { -1.0 })), |a, s| a * s);
        let ext = Vector3::from(ext);
        let region = Region::cuboid(-ext * 0.5, ext * 0.5);
        let centre = Vector3::from(c).component_mul(&ext);
        let eval = half_space_robot(centre, n);
        let mesh = mesh(&eval, m, region);
        let nn = n.normalize();
        let exact = clipped_box_volume(region.min, region.max, nn, nn.dot(&centre));
        prop_assert_eq!(mesh.edge_defects(), 0);
        prop_assert!((mesh.volume - exact).abs() <= 1e-6 * exact, "{} vs {}", mesh.volume, exact);
        prop_assert_eq!(mesh.components, 1);
        assert_vertices_on_boundary(&eval, &mesh, Rotation3::identity());
    }

    /// Random unions of balls: always closed and consistently oriented, volume within the
    /// grid's resolution, regions ≥ 1.
    #[test]
    fn random_ball_unions_are_watertight(
        balls in prop::collection::vec((prop::array::uniform3(-0.8..0.8f64), 0.1..0.5f64), 1..5),
        m in 4usize..14,
    ) {
        let b = balls.clone();
        let eval = shape_eval(move |u| b.iter().any(|(c, r)| (u - Vector3::from(*c)).norm() < *r));
        let mesh = mesh(&eval, m, cube(1.0));
        prop_assert_eq!(mesh.edge_defects(), 0);
        if mesh.grid.feasible_points > 0 {
            prop_assert!(mesh.regions() >= 1);
            prop_assert!(mesh.volume > 0.0);
        }
    }
}
