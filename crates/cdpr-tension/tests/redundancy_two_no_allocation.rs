//! The redundancy-2 path of an 8-cable spatial robot (fixed-size 6 × 8 null space, feasible
//! polygon, dense linf, fixed-DOF improved closed form) does not allocate after its first call:
//! counted with a global allocator wrapper (issue 17).

use cdpr_kinematics::Pose;
use cdpr_kinematics::reference_robots::ipanema_like_8;
use cdpr_tension::{Method, TensionBounds, TensionProblem, TensionSolver};
use nalgebra::{DMatrix, DVector, Vector3};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;
thread_local! {
    /// Allocations made by this thread (the harness's threads must not count).
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

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

// One test function: the counter is global, tests in parallel would disturb each other.
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
