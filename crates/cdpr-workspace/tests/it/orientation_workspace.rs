//! Orientation workspaces of spatial robots: a one-orientation set gives the
//! constant-orientation workspace; total ⊆ constant ⊆ maximal; a hand case whose total and
//! maximal workspaces, limiting orientation and boundary are known in closed form.

use cdpr_kinematics::{Cable, MotionPattern, Robot};
use cdpr_tension::{Method, TensionBounds};
use cdpr_workspace::{
    Criterion, CustomCriterion, Grid, OrientationSet, OrientationTest, OrientationWorkspaceKind,
    PoseEvaluator, Region, constant_orientation_workspace, orientation_workspace,
};
use nalgebra::{DVector, Vector3};

/// The 8-cable IPAnema-like example robot (examples/robots/ipanema-like-8.toml): a 4 × 3 × 2 m
/// frame, a 0.2 × 0.2 × 0.1 m platform, upper cables to the lower platform corners.
fn cube_robot() -> Robot {
    let mut cables = Vec::new();
    for (z, pz) in [(2.0, -0.05), (0.0, 0.05)] {
        for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)] {
            cables.push(Cable {
                frame: Vector3::new(2.0 * sx, 1.5 * sy, z),
                platform: Vector3::new(0.1 * sx, 0.1 * sy, pz),
                pulley: None,
            });
        }
    }
    Robot::new(MotionPattern::Spatial, cables).unwrap()
}

fn wrench_feasible() -> PoseEvaluator {
    PoseEvaluator::new(
        cube_robot(),
        TensionBounds::uniform(8, 10.0, 1000.0).unwrap(),
        vec![Criterion::TensionFeasible {
            method: Method::L2,
            wrench: DVector::from_vec(vec![0.0, 0.0, -50.0, 0.0, 0.0, 0.0]),
        }],
    )
    .unwrap()
}

fn grid(m: usize) -> Grid {
    Grid::new(
        m,
        Region::cuboid(Vector3::new(-2.0, -1.5, 0.0), Vector3::new(2.0, 1.5, 2.0)),
    )
}

#[test]
fn a_single_orientation_gives_the_constant_orientation_workspace() {
    let eval = wrench_feasible();
    let set: OrientationSet = "euler:rx=3,ry=-2,rz=4".parse().unwrap();
    let o = set.orientations().unwrap();
    assert_eq!(o.len(), 1);
    let constant = constant_orientation_workspace(&eval, &o[0].rotation, &grid(8)).unwrap();
    assert!(
        constant.feasible_points > 0 && constant.feasible_points < constant.total_points,
        "{} of {}",
        constant.feasible_points,
        constant.total_points
    );
    for kind in [
        OrientationWorkspaceKind::Total,
        OrientationWorkspaceKind::Maximal,
    ] {
        let test = OrientationTest::uniform(kind, &eval, &o).unwrap();
        let ws = orientation_workspace(&test, &grid(8)).unwrap();
        assert_eq!(ws.workspace.feasible, constant.feasible, "{kind:?}");
    }
}

#[test]
fn total_within_every_constant_within_maximal() {
    let eval = wrench_feasible();
    for spec in ["euler:rx=-5..5,rz=-5..5,n=3", "tilt:5,torsion=-4..4,n=3"] {
        let set: OrientationSet = spec.parse().unwrap();
        let o = set.orientations().unwrap();
        let g = grid(6);
        let total = orientation_workspace(
            &OrientationTest::uniform(OrientationWorkspaceKind::Total, &eval, &o).unwrap(),
            &g,
        )
        .unwrap();
        let maximal = orientation_workspace(
            &OrientationTest::uniform(OrientationWorkspaceKind::Maximal, &eval, &o).unwrap(),
            &g,
        )
        .unwrap();
        assert!(
            total.workspace.feasible_points < maximal.workspace.feasible_points,
            "{spec}"
        );
        for s in &o {
            let c = constant_orientation_workspace(&eval, &s.rotation, &g).unwrap();
            assert!(total.workspace.is_subset_of(&c), "{spec}");
            assert!(c.is_subset_of(&maximal.workspace), "{spec}");
        }
        // Every limiting orientation fails just outside its boundary point and every
        // orientation holds at the boundary grid point.
        assert!(!total.limiting.is_empty());
        let mut test =
            OrientationTest::uniform(OrientationWorkspaceKind::Total, &eval, &o).unwrap();
        for l in &total.limiting {
            assert!(test.is_feasible(total.workspace.point(l.point)));
        }
    }
}

/// The evaluator of the criterion x ≤ 0.5 sin(r_z) and the five rotations r_z = −20°, −10°, …,
/// 20° about z.
fn half_spaces() -> (PoseEvaluator, Vec<cdpr_workspace::SampledOrientation>) {
    let criterion = Criterion::Custom(CustomCriterion::new("x below 0.5 sin rz", |ctx| {
        let r = ctx.pose.rotation * Vector3::x();
        ctx.pose.position.x <= 0.5 * r.y
    }));
    let eval = PoseEvaluator::new(
        cube_robot(),
        TensionBounds::uniform(8, 1.0, 2.0).unwrap(),
        vec![criterion],
    )
    .unwrap();
    let set: OrientationSet = "euler:rz=-20..20,n=5".parse().unwrap();
    (eval, set.orientations().unwrap())
}

/// Custom criterion x ≤ 0.5 sin(r_z) (the platform x axis' y component, scaled), rotations
/// about z only: over r_z ∈ [−20°, 20°] the total workspace is x ≤ −0.5 sin 20°, the maximal
/// x ≤ 0.5 sin 20°, the limiting orientation is r_z = −20° (the first sample) and the
/// boundary points lie at x = −0.5 sin 20°.
#[test]
fn hand_case_half_spaces() {
    let (eval, o) = half_spaces();
    let g = Grid::new(
        10,
        Region::cuboid(Vector3::repeat(-0.5), Vector3::repeat(0.5)),
    );
    let s20 = 0.5 * 20f64.to_radians().sin(); // 0.171…
    let total = orientation_workspace(
        &OrientationTest::uniform(OrientationWorkspaceKind::Total, &eval, &o).unwrap(),
        &g,
    )
    .unwrap();
    let maximal = orientation_workspace(
        &OrientationTest::uniform(OrientationWorkspaceKind::Maximal, &eval, &o).unwrap(),
        &g,
    )
    .unwrap();
    for idx in 0..g.point_count(3) {
        let x = g.point(3, idx).x;
        assert_eq!(total.workspace.feasible[idx], x <= -s20, "x = {x}");
        assert_eq!(maximal.workspace.feasible[idx], x <= s20, "x = {x}");
    }
    assert!(maximal.limiting.is_empty());
    // Boundary grid points: x = −0.2 (next to −0.1), 11 × 11 of them.
    assert_eq!(total.limiting.len(), 121);
    for l in &total.limiting {
        assert_eq!(l.orientation, 0);
        assert!((o[0].angles[2] + 20f64.to_radians()).abs() < 1e-15);
        assert!(
            (l.boundary_point.x + s20).abs() < 1e-9,
            "{}",
            l.boundary_point
        );
    }
    // At x = 0 exactly the orientations with r_z ≥ 0 are feasible.
    let mut test = OrientationTest::uniform(OrientationWorkspaceKind::Total, &eval, &o).unwrap();
    let at = test.feasible_orientations(Vector3::zeros());
    assert_eq!(at, vec![false, false, true, true, true]);
}

#[test]
fn non_spatial_robots_and_bad_sets_are_errors() {
    let c = |x: f64, y: f64| Cable {
        frame: Vector3::new(x, y, 0.0),
        platform: Vector3::zeros(),
        pulley: None,
    };
    let planar = Robot::new(
        MotionPattern::Point2,
        vec![c(1.0, 0.0), c(-1.0, 1.0), c(-1.0, -1.0)],
    )
    .unwrap();
    let eval = PoseEvaluator::new(
        planar,
        TensionBounds::uniform(3, 1.0, 2.0).unwrap(),
        vec![Criterion::WrenchClosure],
    )
    .unwrap();
    let o = "euler:rz=0..10,n=2"
        .parse::<OrientationSet>()
        .unwrap()
        .orientations()
        .unwrap();
    assert!(OrientationTest::uniform(OrientationWorkspaceKind::Total, &eval, &o).is_err());
    assert!(OrientationTest::new(OrientationWorkspaceKind::Total, vec![], vec![]).is_err());
}

/// The hand case on the boundary mesh: the total-orientation workspace is the slab
/// x ≤ −0.5 sin 20° of the unit box (volume 0.5 − 0.5 sin 20°, exact since the boundary is
/// flat), the maximal one x ≤ 0.5 sin 20°; every boundary vertex of the total mesh is limited
/// by r_z = −20° and lies on the plane.
#[test]
fn hand_case_on_the_boundary_mesh() {
    use cdpr_workspace::{MeshSettings, MeshVertex, orientation_boundary_mesh};
    let (eval, o) = half_spaces();
    let g = Grid::new(
        7,
        Region::cuboid(Vector3::repeat(-0.5), Vector3::repeat(0.5)),
    );
    let s20 = 0.5 * 20f64.to_radians().sin();
    for (kind, volume) in [
        (OrientationWorkspaceKind::Total, 0.5 - s20),
        (OrientationWorkspaceKind::Maximal, 0.5 + s20),
    ] {
        let test = OrientationTest::uniform(kind, &eval, &o).unwrap();
        let m = orientation_boundary_mesh(&test, &g, &MeshSettings::default()).unwrap();
        assert!(
            (m.mesh.volume - volume).abs() < 1e-7,
            "{kind:?}: {}",
            m.mesh.volume
        );
        assert_eq!(m.mesh.edge_defects(), 0);
        for (v, (origin, limit)) in m
            .mesh
            .vertices
            .iter()
            .zip(m.mesh.origins.iter().zip(&m.limiting))
        {
            match (origin, kind) {
                (MeshVertex::Crossing { .. }, OrientationWorkspaceKind::Total) => {
                    assert_eq!(*limit, Some(0));
                    assert!((v[0] + s20).abs() < 1e-8, "{v:?}");
                }
                _ => assert_eq!(*limit, None),
            }
        }
    }
}
