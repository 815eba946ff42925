//! The dense active-set path (redundancy ≥ 3, with the l2-max vertex search) and the redundancy-2 path of an 8-cable spatial
//! robot do not allocate after their first call for a problem size: counted with a global
//! allocator wrapper (per thread, so the test functions may run in parallel).

use cdpr_kinematics::reference_robots::ipanema_like_8;
use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
use cdpr_tension::{Method, TensionBounds, TensionProblem, TensionSolver};
use nalgebra::{DMatrix, DVector, Vector3};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;
thread_local! {
    /// Allocations made by this thread: other threads (the test harness, tests running in
    /// parallel) must not count.
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

/// This thread's allocation count so far.
fn allocations_so_far() -> usize {
    ALLOCATIONS.with(Cell::get)
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// An 8-cable planar robot (r = 5): two cables from each frame corner, crossed.
fn robot() -> Robot {
    let mut cables = Vec::new();
    for (x, y) in [(2.0f64, 1.0f64), (-2.0, 1.0), (-2.0, -1.0), (2.0, -1.0)] {
        for (px, py) in [
            (0.1f64.copysign(x), 0.05f64.copysign(-y)),
            (0.1f64.copysign(-x), 0.05f64.copysign(y)),
        ] {
            cables.push(Cable {
                frame: Vector3::new(x, y, 0.0),
                platform: Vector3::new(px, py, 0.0),
                pulley: None,
            });
        }
    }
    Robot::new(MotionPattern::Planar, cables).unwrap()
}

#[test]
fn dense_path_does_not_allocate() {
    let robot = robot();
    let ws: Vec<DMatrix<f64>> = (0..50)
        .map(|k| {
            let pose = Pose::planar(-1.0 + 0.04 * k as f64, 0.3 - 0.012 * k as f64, 0.05);
            robot.inverse_kinematics(&pose).unwrap().wrench_matrix()
        })
        .collect();
    // A feasible load, and one no tensions can hold (an infeasible verdict must not allocate).
    let loads = [
        DVector::from_vec(vec![0.0, -50.0, 0.5]),
        DVector::from_vec(vec![0.0, -5000.0, 0.0]),
    ];
    let b = TensionBounds::uniform(8, 5.0, 200.0).unwrap();
    for method in [
        Method::L1,
        Method::L1Max,
        Method::L2,
        Method::Linf,
        Method::L2Max,
    ] {
        let mut solver = TensionSolver::new(method);
        let mut t = DVector::zeros(8);
        let mut run = |solver: &mut TensionSolver| {
            let mut feasible = 0;
            for we in &loads {
                for w in &ws {
                    let p = TensionProblem::new(w, we, &b);
                    feasible += solver.solve_into(&p, &mut t).unwrap().is_ok() as usize;
                    feasible += solver.is_feasible(&p).unwrap() as usize;
                }
            }
            feasible
        };
        run(&mut solver);
        let before = allocations_so_far();
        let feasible = run(&mut solver);
        let allocations = allocations_so_far() - before;
        assert_eq!(allocations, 0, "{method}");
        assert_eq!(
            feasible,
            2 * ws.len(),
            "{method}: the first load is feasible, the second not"
        );
        assert_eq!(solver.clarabel_fallbacks(), 0, "{method}");
    }
}

/// The redundancy-2 path of an 8-cable spatial robot (fixed-size 6 × 8 null space, feasible
/// polygon clipped in fixed arrays, planar active set of l2, dense linf, fixed-DOF improved
/// closed form; issue 17).
#[test]
fn redundancy_two_path_does_not_allocate() {
    let robot = ipanema_like_8();
    let ws: Vec<DMatrix<f64>> = (0..40)
        .map(|k| {
            let s = k as f64 / 40.0;
            let pose = Pose::spatial(
                Vector3::new(-0.8 + 1.6 * s, 0.5 - s, 0.6 + 0.8 * s),
                0.05 * (s - 0.5),
                -0.04 * s,
                0.08 * (0.5 - s),
            );
            robot.inverse_kinematics(&pose).unwrap().wrench_matrix()
        })
        .collect();
    // A 10 kg platform under gravity (feasible), and a load no tensions can hold.
    let loads = [
        DVector::from_vec(vec![0.0, 0.0, -98.0665, 0.0, 0.0, 0.0]),
        DVector::from_vec(vec![0.0, 0.0, 1e6, 0.0, 0.0, 0.0]),
    ];
    let b = TensionBounds::uniform(8, 1.0, 1000.0).unwrap();
    for method in [
        Method::ImprovedClosedForm,
        Method::Barycenter,
        Method::L2,
        Method::L1,
        Method::L1Max,
        Method::L2Max,
        Method::Linf,
        Method::Pinv,
    ] {
        let mut solver = TensionSolver::new(method);
        let mut t = DVector::zeros(8);
        let mut run = |solver: &mut TensionSolver| {
            let mut feasible = [0; 2];
            for (f, we) in feasible.iter_mut().zip(&loads) {
                for w in &ws {
                    let p = TensionProblem::new(w, we, &b);
                    *f += solver.solve_into(&p, &mut t).unwrap().is_ok() as usize;
                    *f += solver.is_feasible(&p).unwrap() as usize;
                }
            }
            feasible
        };
        let first = run(&mut solver);
        let before = allocations_so_far();
        let feasible = run(&mut solver);
        let allocations = allocations_so_far() - before;
        assert_eq!(allocations, 0, "{method}");
        assert_eq!(feasible, first, "{method}");
        assert_eq!(feasible[1], 0, "{method}: the second load is infeasible");
        if method != Method::Pinv {
            assert!(
                feasible[0] > 0,
                "{method}: the first load is feasible somewhere"
            );
        }
        assert_eq!(solver.clarabel_fallbacks(), 0, "{method}");
    }
}
