//! Criteria: wrench closure (fast null-space tests vs the linear programme), the Jacobian
//! determinant floor (6.24), the stiffness floor, composition.
use crate::common;

use cdpr_kinematics::strategies::{arb_pose, arb_robot};
use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
use cdpr_tension::{Method, TensionBounds};
use cdpr_workspace::wrench_closure::WrenchClosureTest;
use cdpr_workspace::{Criterion, PoseEvaluator, WorkspaceError};
use common::*;
use nalgebra::{DVector, Vector3};
use proptest::prelude::*;

fn point_robot(anchors: &[[f64; 2]]) -> Robot {
    Robot::new(
        MotionPattern::Point2,
        anchors
            .iter()
            .map(|a| Cable {
                frame: Vector3::new(a[0], a[1], 0.0),
                platform: Vector3::zeros(),
                pulley: None,
            })
            .collect(),
    )
    .unwrap()
}

/// A point with 3 cables is wrench-closure exactly inside the triangle of the anchors.
#[test]
fn point_wrench_closure_is_the_anchor_triangle() {
    let robot = point_robot(&[[1.0, 1.0], [-1.0, 1.0], [0.0, -1.0]]);
    let mut eval = PoseEvaluator::new(
        robot,
        TensionBounds::uniform(3, 0.0, 1.0).unwrap(),
        vec![Criterion::WrenchClosure],
    )
    .unwrap();
    // Triangle: y < 1, y > 2|x| − 1.
    for (x, y) in [(0.0, 0.0), (0.4, 0.5), (-0.45, 0.0), (0.0, 0.99)] {
        assert!(eval.is_feasible(&Pose::point(x, y, 0.0)), "({x}, {y})");
    }
    for (x, y) in [(0.6, 0.1), (0.0, 1.2), (-0.55, 0.0), (0.9, -0.9)] {
        assert!(!eval.is_feasible(&Pose::point(x, y, 0.0)), "({x}, {y})");
    }
}

#[test]
fn thesis_three_cable_is_never_wrench_closure_but_four_cable_is() {
    let ws = |robot: Robot| {
        let n = robot.cable_count();
        PoseEvaluator::new(
            robot,
            TensionBounds::uniform(n, 5.0, 100.0).unwrap(),
            vec![Criterion::WrenchClosure],
        )
        .unwrap()
    };
    let mut three = ws(three_cable());
    let mut four = ws(four_cable());
    assert!(!three.is_feasible(&Pose::planar(0.1, 0.0, 0.0)));
    assert!(four.is_feasible(&Pose::planar(0.1, 0.0, 0.0)));
}

/// Eq. (6.24): |det J| = |det W| ≥ D_min, checked against nalgebra's LU determinant; no-op when
/// n ≠ DOF.
#[test]
fn jacobian_floor_matches_lu_determinant() {
    let robot = three_cable();
    for (x, y, phi) in [
        (0.3, 0.1, 0.0),
        (0.0, 0.2, 0.0),
        (-0.2, -0.3, 0.05),
        (0.001, 0.0, 0.0),
    ] {
        let pose = Pose::planar(x, y, phi);
        let det = robot
            .inverse_kinematics(&pose)
            .unwrap()
            .jacobian_determinant()
            .unwrap();
        for d_min in [1e-3, 1e-2, 0.1] {
            let mut eval = PoseEvaluator::new(
                robot.clone(),
                TensionBounds::uniform(3, 5.0, 100.0).unwrap(),
                vec![Criterion::MinJacobianDeterminant(d_min)],
            )
            .unwrap();
            assert_eq!(
                eval.is_feasible(&pose),
                det.abs() >= d_min,
                "({x}, {y}, {phi}) det {det}"
            );
        }
    }
    // At x = 0, φ = 0 the three cable lines meet on the y axis: det J = 0 (the split of Fig. 6.4).
    let det = robot
        .inverse_kinematics(&Pose::planar(0.0, 0.1, 0.0))
        .unwrap()
        .jacobian_determinant()
        .unwrap();
    assert!(det.abs() < 1e-15);
    let mut four = PoseEvaluator::new(
        four_cable(),
        TensionBounds::uniform(4, 5.0, 100.0).unwrap(),
        vec![Criterion::MinJacobianDeterminant(1e6)],
    )
    .unwrap();
    assert!(four.is_feasible(&Pose::planar(0.0, 0.0, 0.0)));
}

/// Stiffness floor: a point at the origin held by four unit-length cables along ±x, ±y, E·S =
/// 1000 and (minimum-norm) t = 10 each. Each cable adds k = E·S/l = 1000 along itself and
/// t/l = 10 across it (Picard, Caro, Plestan & Claveau 2020, eqs. (3)–(4)): K = diag(2020, 2020), λ_min = 2020.
#[test]
fn stiffness_floor_by_hand() {
    let robot = point_robot(&[[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]]);
    let make = |floor: f64| {
        PoseEvaluator::new(
            robot.clone(),
            TensionBounds::uniform(4, 10.0, 100.0).unwrap(),
            vec![
                Criterion::Stiffness {
                    min_eigenvalue: floor,
                },
                Criterion::TensionFeasible {
                    method: Method::L2,
                    wrench: DVector::zeros(2),
                },
            ],
        )
        .unwrap()
    };
    let origin = Pose::point(0.0, 0.0, 0.0);
    // Without E·S the criterion cannot be evaluated.
    assert!(matches!(
        make(0.0).check(&origin),
        Err(WorkspaceError::MissingAxialStiffness { .. })
    ));
    let mut lo = make(2019.999)
        .with_axial_stiffness(vec![1000.0; 4])
        .unwrap();
    let mut hi = make(2020.001)
        .with_axial_stiffness(vec![1000.0; 4])
        .unwrap();
    assert_eq!(lo.check(&origin), Ok(true));
    assert_eq!(hi.check(&origin), Ok(false));
    assert!(make(0.0).with_axial_stiffness(vec![1000.0; 3]).is_err());
    assert!(
        make(0.0)
            .with_axial_stiffness(vec![1000.0, 1.0, 1.0, -1.0])
            .is_err()
    );
    // The stiffness criterion needs a tension criterion.
    assert!(matches!(
        PoseEvaluator::new(
            robot.clone(),
            TensionBounds::uniform(4, 1.0, 10.0).unwrap(),
            vec![Criterion::Stiffness {
                min_eigenvalue: 0.0
            }]
        ),
        Err(WorkspaceError::StiffnessNeedsTensions)
    ));
}

/// Issue 13 §1: a stiffness floor in its own units. The point robot of `stiffness_floor_by_hand`
/// (K = diag(2020, 2020) N/m) passes k_t = 2019.999 N/m and fails 2020.001 N/m, whatever k_r
/// (no rotation). On the thesis' 4-cable planar robot the verdict is that of a direct test:
/// sym(K) − diag(k_t, k_t, k_r) positive semidefinite, with K from `cdpr_wrench`.
#[test]
fn stiffness_floor_keeps_translational_and_rotational_units_apart() {
    let floor = |robot: &Robot, kt: f64, kr: f64, method: Method| {
        let n = robot.cable_count();
        PoseEvaluator::new(
            robot.clone(),
            TensionBounds::uniform(n, 10.0, 100.0).unwrap(),
            vec![
                Criterion::StiffnessFloor {
                    translational: kt,
                    rotational: kr,
                },
                Criterion::TensionFeasible {
                    method,
                    wrench: DVector::zeros(robot.dof()),
                },
            ],
        )
        .unwrap()
        .with_axial_stiffness(vec![1000.0; n])
        .unwrap()
    };
    let point = point_robot(&[[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]]);
    let origin = Pose::point(0.0, 0.0, 0.0);
    assert_eq!(
        floor(&point, 2019.999, 1e9, Method::L2).check(&origin),
        Ok(true)
    );
    assert_eq!(
        floor(&point, 2020.001, 0.0, Method::L2).check(&origin),
        Ok(false)
    );
    assert!(matches!(
        PoseEvaluator::new(
            point.clone(),
            TensionBounds::uniform(4, 1.0, 10.0).unwrap(),
            vec![Criterion::StiffnessFloor {
                translational: f64::NAN,
                rotational: 0.0
            }]
        ),
        Err(WorkspaceError::NotFinite { .. })
    ));
    // Planar: the direct test, over floors on both sides of the boundary.
    let robot = four_cable();
    let pose = Pose::planar(0.1, -0.05, 0.05);
    let mut with_tensions = floor(&robot, 0.0, 0.0, Method::L2);
    let t = with_tensions
        .tensions(&pose)
        .unwrap()
        .expect("feasible pose");
    let kin = robot.inverse_kinematics(&pose).unwrap();
    let k = cdpr_wrench::stiffness_matrix(&kin, t.as_slice(), &[1000.0; 4]).unwrap();
    let sym = (&k + k.transpose()) * 0.5;
    let (kt_max, kr_max) = (sym[(0, 0)].min(sym[(1, 1)]), sym[(2, 2)]);
    let mut seen = [false; 2];
    for i in 0..=10 {
        for j in 0..=10 {
            let (kt, kr) = (kt_max * i as f64 / 10.0, kr_max * j as f64 / 10.0);
            let d = nalgebra::DMatrix::from_diagonal(&DVector::from_vec(vec![kt, kt, kr]));
            let lambda = (&sym - d).symmetric_eigenvalues().min();
            if lambda.abs() < 1e-9 * kt_max {
                continue; // on the boundary: either verdict is right
            }
            let verdict = floor(&robot, kt, kr, Method::L2).check(&pose).unwrap();
            assert_eq!(verdict, lambda >= 0.0, "k_t = {kt} N/m, k_r = {kr} N·m/rad");
            seen[usize::from(verdict)] = true;
        }
    }
    assert_eq!(seen, [true, true], "both verdicts met");
}

/// Criteria compose by AND: the workspace with two criteria is the intersection.
#[test]
fn composition_is_intersection() {
    let g = cdpr_workspace::Grid::over_frame(&four_cable(), 30);
    let bounds = TensionBounds::uniform(4, T_MIN, T_MAX).unwrap();
    let tension = Criterion::TensionFeasible {
        method: Method::L1,
        wrench: load(1),
    };
    let length = Criterion::MinCableLength(0.5);
    let ws = |c: Vec<Criterion>| {
        cdpr_workspace::planar_workspace(
            &PoseEvaluator::new(four_cable(), bounds.clone(), c).unwrap(),
            0.05,
            &g,
        )
        .unwrap()
    };
    let a = ws(vec![tension.clone()]);
    let b = ws(vec![length.clone()]);
    let both = ws(vec![length, tension]);
    for i in 0..a.total_points {
        assert_eq!(both.feasible[i], a.feasible[i] && b.feasible[i]);
    }
    assert!(both.feasible_points > 0 && both.feasible_points < a.feasible_points);
}

fn closure_agrees(robot: &Robot, pose: &Pose) -> Result<(), TestCaseError> {
    let Ok(kin) = robot.inverse_kinematics(pose) else {
        return Ok(());
    };
    let w = kin.wrench_matrix();
    let mut test = WrenchClosureTest::new(robot.dof(), robot.cable_count());
    let fast = test.is_wrench_closure(&w);
    let lp = test.is_wrench_closure_by_lp(&w);
    prop_assert_eq!(fast, lp);
    if robot.motion() == MotionPattern::Point2 {
        // Independent: unit vectors in the plane positively span R² iff the largest angular gap
        // between consecutive directions is below π.
        let mut ang: Vec<f64> = kin
            .cables()
            .iter()
            .map(|c| c.unit.y.atan2(c.unit.x))
            .collect();
        ang.sort_by(f64::total_cmp);
        let mut gap = ang[0] + std::f64::consts::TAU - ang[ang.len() - 1];
        for k in 1..ang.len() {
            gap = gap.max(ang[k] - ang[k - 1]);
        }
        if (gap - std::f64::consts::PI).abs() > 1e-9 {
            prop_assert_eq!(fast, gap < std::f64::consts::PI);
        }
    }
    Ok(())
}

proptest! {
    /// r = 1 and r = 2 null-space tests agree with the linear programme (independent method).
    #[test]
    fn fast_wrench_closure_agrees_with_lp_planar(robot in arb_robot(MotionPattern::Planar, 4..=5),
                                                  pose in arb_pose(MotionPattern::Planar)) {
        closure_agrees(&robot, &pose)?;
    }

    #[test]
    fn fast_wrench_closure_agrees_with_lp_point(robot in arb_robot(MotionPattern::Point2, 3..=6),
                                                 pose in arb_pose(MotionPattern::Point2)) {
        closure_agrees(&robot, &pose)?;
    }

    #[test]
    fn fast_wrench_closure_agrees_with_lp_spatial(robot in arb_robot(MotionPattern::Spatial, 7..=8),
                                                   pose in arb_pose(MotionPattern::Spatial)) {
        closure_agrees(&robot, &pose)?;
    }

    /// Wrench closure is invariant under cable reordering.
    #[test]
    fn wrench_closure_ignores_cable_order(robot in arb_robot(MotionPattern::Point3, 4..=6),
                                          pose in arb_pose(MotionPattern::Point3)) {
        let n = robot.cable_count();
        let order: Vec<usize> = (0..n).rev().collect();
        let ev = |r: Robot| PoseEvaluator::new(r, TensionBounds::uniform(n, 0.0, 1.0).unwrap(),
                                               vec![Criterion::WrenchClosure]).unwrap();
        prop_assert_eq!(ev(robot.clone()).is_feasible(&pose), ev(robot.permuted(&order).unwrap()).is_feasible(&pose));
    }
}

/// Krut, Company & Pierrot 2004, §IV-B: three motors at 1000 mm (30°, 150°, 270°), t ∈ [50, 500] N: at the centre
/// the maximum isotropic force is 225√3 ≈ 389.71 N.
#[test]
fn isotropic_force_floor_reproduces_seed_001() {
    let m = |deg: f64| {
        [
            1000.0 * deg.to_radians().cos(),
            1000.0 * deg.to_radians().sin(),
        ]
    };
    let robot = point_robot(&[m(30.0), m(150.0), m(270.0)]);
    let ev = |min: f64| {
        PoseEvaluator::new(
            robot.clone(),
            TensionBounds::uniform(3, 50.0, 500.0).unwrap(),
            vec![Criterion::IsotropicForce { min }],
        )
        .unwrap()
    };
    let centre = Pose::point(0.0, 0.0, 0.0);
    assert!(ev(389.7).is_feasible(&centre));
    assert!(!ev(389.8).is_feasible(&centre));
    assert!((225.0 * 3f64.sqrt() - 389.7).abs() < 0.02);
}

fn grid_of(criteria: Vec<Criterion>, phi: f64) -> cdpr_workspace::GridWorkspace {
    let eval = PoseEvaluator::new(
        four_cable(),
        TensionBounds::uniform(4, T_MIN, T_MAX).unwrap(),
        criteria,
    )
    .unwrap();
    cdpr_workspace::planar_workspace(
        &eval,
        phi,
        &cdpr_workspace::Grid::over_frame(eval.robot(), 40),
    )
    .unwrap()
}

/// Capacity margin of a single wrench ≥ 0 ⟺ that wrench can be balanced: the polytope test
/// (hyperplane shifting) and the tension LP agree up to the boundary.
#[test]
fn capacity_margin_of_a_point_is_tension_feasibility() {
    use cdpr_polytope::RequiredWrenchSet;
    for load_case in 0..3 {
        for phi in [-0.1, 0.0, 0.15] {
            let margin = |floor: f64| {
                grid_of(
                    vec![Criterion::CapacityMargin {
                        required: RequiredWrenchSet::point(load(load_case)).unwrap(),
                        min_margin: floor,
                    }],
                    phi,
                )
            };
            let lp = grid_of(
                vec![Criterion::TensionFeasible {
                    method: Method::L1,
                    wrench: load(load_case),
                }],
                phi,
            );
            let inner = margin(1e-7);
            let outer = margin(-1e-7);
            assert!(
                inner.is_subset_of(&lp) && lp.is_subset_of(&outer),
                "L{} φ = {phi}",
                load_case + 1
            );
            assert!(inner.feasible_points > 0);
            // A ball of disturbances of radius 2 shrinks the workspace.
            let ball = grid_of(
                vec![Criterion::CapacityMargin {
                    required: RequiredWrenchSet::ball(load(load_case), 2.0).unwrap(),
                    min_margin: 0.0,
                }],
                phi,
            );
            assert!(ball.is_subset_of(&outer) && ball.feasible_points < lp.feasible_points);
        }
    }
}

/// Isotropic force ≥ 0 ⟺ the zero wrench can be balanced (the origin is in the AWS).
#[test]
fn isotropic_force_sign_is_zero_wrench_feasibility() {
    let lp = grid_of(
        vec![Criterion::TensionFeasible {
            method: Method::L1,
            wrench: DVector::zeros(3),
        }],
        0.1,
    );
    let inner = grid_of(vec![Criterion::IsotropicForce { min: 1e-7 }], 0.1);
    let outer = grid_of(vec![Criterion::IsotropicForce { min: -1e-7 }], 0.1);
    assert!(inner.is_subset_of(&lp) && lp.is_subset_of(&outer));
    assert!(inner.feasible_points > 0);
    let strong = grid_of(vec![Criterion::IsotropicForce { min: 5.0 }], 0.1);
    assert!(strong.is_subset_of(&inner) && strong.feasible_points < inner.feasible_points);
}

#[test]
fn polytope_criteria_validate_their_input() {
    use cdpr_polytope::RequiredWrenchSet;
    let bounds = TensionBounds::uniform(4, T_MIN, T_MAX).unwrap();
    let wrong = Criterion::CapacityMargin {
        required: RequiredWrenchSet::point(DVector::zeros(2)).unwrap(),
        min_margin: 0.0,
    };
    assert!(matches!(
        PoseEvaluator::new(four_cable(), bounds.clone(), vec![wrong]),
        Err(WorkspaceError::DimensionMismatch { .. })
    ));
    let nan = Criterion::IsotropicForce { min: f64::NAN };
    assert!(PoseEvaluator::new(four_cable(), bounds, vec![nan]).is_err());
}
