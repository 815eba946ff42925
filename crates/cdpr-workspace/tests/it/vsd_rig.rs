//! Regression: the CASPR 2-DoF VSD test rig (Yeo, Yang & Lim 2013; `examples/robots/
//! caspr-2-dof-vsd-stiff.toml`, ideal cables "stiff"): a point mass with anchors at the corners
//! of a 1 m × 0.5 m frame, t ∈ [0, 50] N and no load, so t = 0 balances every pose. Every point
//! of the gallery's grid (`--grid 200`, 201 × 201 over the frame) except the 4 anchors is
//! wrench-feasible: 40 397 of 40 401. On the frame's edges the feasible polygon is a segment
//! through t = 0 between near-parallel half-planes, where a shortcut of `is_feasible` once
//! called 20 feasible points infeasible (session 7). Every r = 2 complete method must give the
//! verdict of its own solve at every point.

use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
use cdpr_tension::{Method, TensionBounds, TensionProblem, TensionSolver};
use cdpr_workspace::{Criterion, Grid, PoseEvaluator, constant_orientation_workspace};
use nalgebra::{DVector, Rotation3, Vector3};

fn vsd_rig() -> Robot {
    let c = |x: f64, y: f64| Cable {
        frame: Vector3::new(x, y, 0.0),
        platform: Vector3::zeros(),
        pulley: None,
    };
    let cables = vec![c(0.0, 0.0), c(1.0, 0.0), c(1.0, 0.5), c(0.0, 0.5)];
    Robot::new(MotionPattern::Point2, cables).unwrap()
}

#[test]
fn every_grid_point_but_the_anchors_is_feasible_and_is_feasible_agrees_with_solve() {
    let robot = vsd_rig();
    let bounds = TensionBounds::uniform(4, 0.0, 50.0).unwrap();
    let grid = Grid::over_frame(&robot, 200);
    let wrench = DVector::zeros(2);
    let eval = PoseEvaluator::new(
        robot.clone(),
        bounds.clone(),
        vec![Criterion::TensionFeasible {
            method: Method::L2,
            wrench: wrench.clone(),
        }],
    )
    .unwrap();
    let ws = constant_orientation_workspace(&eval, &Rotation3::identity(), &grid).unwrap();
    assert_eq!((ws.feasible_points, ws.total_points), (40_397, 40_401));

    let methods = [
        Method::L1,
        Method::L1Max,
        Method::L2,
        Method::L2Max,
        Method::Linf,
        Method::Barycenter,
    ];
    let mut verdict = methods.map(TensionSolver::new);
    let mut solve = methods.map(TensionSolver::new);
    let mut feasible = [0usize; 6];
    for idx in 0..grid.point_count(2) {
        let p = grid.point(2, idx);
        let Ok(kin) = robot.inverse_kinematics(&Pose::point(p.x, p.y, 0.0)) else {
            continue; // an anchor: a zero-length cable
        };
        let w = kin.wrench_matrix();
        let problem = TensionProblem::new(&w, &wrench, &bounds);
        for (k, m) in methods.iter().enumerate() {
            let v = verdict[k].is_feasible(&problem).unwrap();
            let s = solve[k].solve(&problem).unwrap().is_feasible();
            assert_eq!(v, s, "{m:?} at ({}, {}) m", p.x, p.y);
            feasible[k] += usize::from(v);
        }
    }
    assert_eq!(feasible, [40_397; 6]);
}
