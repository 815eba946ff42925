//! `TensionSolver::is_feasible` of the complete methods at redundancy 2 decides the feasible
//! polygon without the method's optimum (module `planar_feasibility`): its verdicts must be
//! those of the method's own solve, `solve(..).is_feasible()`, on random problems that include
//! fixed cables (t_min = t_max), infinite t_max and problems on or within 10⁻⁶ of the boundary
//! of the feasible set.

use cdpr_kinematics::strategies::arb_robot_and_pose;
use cdpr_tension::{Method, TensionBounds, TensionProblem, TensionSolver};
use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;

const COMPLETE: [Method; 6] = [
    Method::L1,
    Method::L1Max,
    Method::L2,
    Method::L2Max,
    Method::Linf,
    Method::Barycenter,
];

#[derive(Debug, Clone)]
struct Case {
    w: DMatrix<f64>,
    we: DVector<f64>,
    b: TensionBounds,
}

/// Cable kinds: 0 free, 1 fixed (t_min = t_max), 2 infinite t_max; the reference tensions
/// t_r sit on a bound (frac 0 or 1) for many cables, so that w_ext = −W t_r + δ puts the problem
/// on the boundary of the feasible set (δ = 0) or close to it (|δ| ≤ 10⁻⁶). With every t_r at
/// t_min (a quarter of the cases) the polygon of a wrench-closure pose is the point t_r, and a
/// small δ leaves it empty or a polygon about |δ| wide: far thinner than the decision's margin.
fn arb_case() -> impl Strategy<Value = Case> {
    (
        arb_robot_and_pose(2..=2),
        prop::collection::vec(0.0f64..5.0, 12),
        prop::collection::vec(1.0f64..1000.0, 12),
        prop::collection::vec(prop_oneof![Just(0.0), Just(1.0), 0.0f64..1.0], 12),
        prop::collection::vec(
            prop_oneof![6 => Just(0u8), 1 => Just(1u8), 1 => Just(2u8)],
            12,
        ),
        prop::collection::vec(-1.0f64..1.0, 6),
        prop_oneof![Just(0.0), 0.0f64..1e-6, 0.0f64..1e-3, 0.0f64..100.0],
        prop_oneof![3 => Just(false), 1 => Just(true)],
    )
        .prop_map(
            |((robot, pose), lo, span, frac, kind, dir, mag, at_lower)| {
                let w = robot.inverse_kinematics(&pose).unwrap().wrench_matrix();
                let (m, n) = w.shape();
                let lo: Vec<f64> = lo[..n].to_vec();
                let hi: Vec<f64> = (0..n)
                    .map(|i| match kind[i] {
                        1 => lo[i],
                        2 => f64::INFINITY,
                        _ => lo[i] + span[i],
                    })
                    .collect();
                let tr = DVector::from_fn(n, |i, _| {
                    let top = if hi[i].is_finite() {
                        hi[i]
                    } else {
                        lo[i] + span[i]
                    };
                    if at_lower {
                        lo[i]
                    } else {
                        lo[i] + frac[i] * (top - lo[i])
                    }
                });
                let we = -(&w * tr) + DVector::from_fn(m, |k, _| mag * dir[k]);
                Case {
                    w,
                    we,
                    b: TensionBounds::new(lo, hi).unwrap(),
                }
            },
        )
}

proptest! {
    #[test]
    fn verdicts_are_those_of_the_methods(case in arb_case()) {
        let p = TensionProblem::new(&case.w, &case.we, &case.b);
        for method in COMPLETE {
            let mut fast = TensionSolver::new(method);
            let mut full = TensionSolver::new(method);
            let verdict = fast.is_feasible(&p).unwrap();
            let reference = full.solve(&p).unwrap().is_feasible();
            prop_assert_eq!(verdict, reference, "{}", method);
        }
    }
}

/// The decision itself answers on the IPAnema 1 grid problems (8 cables, 10 kg load): 200
/// poses across the frame, feasible and not, same verdicts as the l2 solve, and the many
/// verdicts that do not come from the polygon boundary agree too (a load no tensions hold).
#[test]
fn ipanema_grid_verdicts_match_l2() {
    let robot = cdpr_kinematics::reference_robots::ipanema_like_8();
    let b = TensionBounds::uniform(8, 1.0, 1000.0).unwrap();
    let loads = [
        DVector::from_vec(vec![0.0, 0.0, -98.0665, 0.0, 0.0, 0.0]),
        DVector::from_vec(vec![0.0, 0.0, 1e6, 0.0, 0.0, 0.0]),
    ];
    let mut fast = TensionSolver::new(Method::L2);
    let mut full = TensionSolver::new(Method::L2);
    let mut counts = [[0usize; 2]; 2];
    for (k, we) in loads.iter().enumerate() {
        for s in 0..200 {
            let u = s as f64 / 200.0;
            let pose = cdpr_kinematics::Pose::point(
                -1.9 + 3.8 * u,
                1.4 * (7.0 * u).sin(),
                -0.9 + 1.8 * (3.0 * u).cos().abs(),
            );
            let w = robot.inverse_kinematics(&pose).unwrap().wrench_matrix();
            let p = TensionProblem::new(&w, we, &b);
            let verdict = fast.is_feasible(&p).unwrap();
            assert_eq!(verdict, full.solve(&p).unwrap().is_feasible(), "pose {s}");
            counts[k][verdict as usize] += 1;
        }
    }
    assert!(counts[0][1] > 0 && counts[0][0] > 0, "{counts:?}");
    assert_eq!(counts[1][1], 0, "{counts:?}");
}
