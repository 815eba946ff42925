//! Fixtures: the thesis robots (thesis Tables 6.1–6.4) and simple geometric workspaces.
#![allow(dead_code)]

use cdpr_kinematics::{Cable, MotionPattern, Robot};
use cdpr_tension::{Method, TensionBounds};
use cdpr_workspace::{Criterion, CustomCriterion, PoseEvaluator, Region};
use nalgebra::{DVector, Vector3};

/// Table 6.4.
pub const T_MIN: f64 = 5.0;
pub const T_MAX: f64 = 100.0;
pub const L_MIN: f64 = 0.1;
pub const D_MIN: f64 = 1e-3;

/// Table 6.3 load cases (f_x, f_y, τ).
pub const LOADS: [[f64; 3]; 3] = [[0.0, -10.0, 0.0], [5.0, -10.0, 0.0], [5.0, -10.0, 1.0]];

fn cable(c: [f64; 2], a: [f64; 2]) -> Cable {
    Cable {
        frame: Vector3::new(c[0], c[1], 0.0),
        platform: Vector3::new(a[0], a[1], 0.0),
        pulley: None,
    }
}

/// The 3-cable manipulator, Tables 6.1 and 6.2.
pub fn three_cable() -> Robot {
    let s = 0.1 / 2f64.sqrt();
    Robot::new(
        MotionPattern::Planar,
        vec![
            cable([1.0, 1.0], [s, s]),
            cable([-1.0, 1.0], [-s, s]),
            cable([0.0, -1.0], [0.0, -0.1]),
        ],
    )
    .unwrap()
}

/// The 4-cable manipulator, Tables 6.1 and 6.2.
pub fn four_cable() -> Robot {
    let s = 0.1 / 2f64.sqrt();
    Robot::new(
        MotionPattern::Planar,
        vec![
            cable([1.0, 0.5], [s, s]),
            cable([-1.0, 0.5], [-s, s]),
            cable([-1.0, -0.5], [-0.1, -0.1]),
            cable([1.0, -0.5], [0.1, -0.1]),
        ],
    )
    .unwrap()
}

pub fn load(k: usize) -> DVector<f64> {
    DVector::from_row_slice(&LOADS[k])
}

/// Eq. (6.23) with (6.24) for the 3-cable robot: unique tensions (6.12), limits of Table 6.4.
pub fn three_cable_eval(load_case: usize) -> PoseEvaluator {
    PoseEvaluator::new(
        three_cable(),
        TensionBounds::uniform(3, T_MIN, T_MAX).unwrap(),
        vec![
            Criterion::TensionFeasible {
                method: Method::Exact,
                wrench: load(load_case),
            },
            Criterion::MinCableLength(L_MIN),
            Criterion::MinJacobianDeterminant(D_MIN),
        ],
    )
    .unwrap()
}

/// Eq. (6.23) for the 4-cable robot with the given tension method.
pub fn four_cable_eval(load_case: usize, method: Method) -> PoseEvaluator {
    PoseEvaluator::new(
        four_cable(),
        TensionBounds::uniform(4, T_MIN, T_MAX).unwrap(),
        vec![
            Criterion::TensionFeasible {
                method,
                wrench: load(load_case),
            },
            Criterion::MinCableLength(L_MIN),
        ],
    )
    .unwrap()
}

/// A point robot whose workspace is given by `inside` (cables far away, never degenerate).
pub fn shape_eval(inside: impl Fn(f64, f64) -> bool + Send + Sync + 'static) -> PoseEvaluator {
    let c = |x: f64, y: f64| Cable {
        frame: Vector3::new(x, y, 0.0),
        platform: Vector3::zeros(),
        pulley: None,
    };
    let robot = Robot::new(
        MotionPattern::Point2,
        vec![c(5.0, 5.0), c(-5.0, 5.0), c(0.0, -5.0)],
    )
    .unwrap();
    PoseEvaluator::new(
        robot,
        TensionBounds::uniform(3, 0.0, 1.0).unwrap(),
        vec![Criterion::Custom(CustomCriterion::new(
            "shape",
            move |ctx| inside(ctx.pose.position.x, ctx.pose.position.y),
        ))],
    )
    .unwrap()
}

pub fn unit_box() -> Region {
    Region::planar(-1.0, 1.0, -1.0, 1.0)
}

/// An 8-cable spatial robot: frame anchors at the corners of the cube [−1, 1]³, platform
/// attachments at the corners of a 0.2 cube, crossed (upper cables swap x, lower cables swap y)
/// so that the centre of the frame is wrench-closure, as in IPAnema-type layouts.
pub fn eight_cable_spatial() -> Robot {
    let mut cables = Vec::new();
    for sx in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            for sz in [-1.0, 1.0] {
                let platform = if sz > 0.0 {
                    Vector3::new(-sx, sy, sz)
                } else {
                    Vector3::new(sx, -sy, sz)
                };
                cables.push(Cable {
                    frame: Vector3::new(sx, sy, sz),
                    platform: platform * 0.1,
                    pulley: None,
                });
            }
        }
    }
    Robot::new(MotionPattern::Spatial, cables).unwrap()
}
