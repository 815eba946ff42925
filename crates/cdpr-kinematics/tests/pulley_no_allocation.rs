//! The pulley hot paths do not allocate once their buffers exist: `update_kinematics` +
//! `write_wrench_matrix` of a pulley robot (blocks of cables, AVX2 build where the CPU has it)
//! and `ForwardKinematics::solve` (issue 14). Counted with a global allocator wrapper.

use cdpr_kinematics::reference_robots::ipanema_like_8_pulleys;
use cdpr_kinematics::{ForwardKinematics, ForwardSettings, Pose, PoseKinematics};
use nalgebra::{DMatrix, Rotation3, Vector3};
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
fn pulley_ik_and_forward_kinematics_do_not_allocate() {
    let robot = ipanema_like_8_pulleys();
    let poses: Vec<Pose> = (0..32)
        .map(|k| {
            let s = k as f64 / 32.0;
            Pose::spatial(
                Vector3::new(-0.5 + s, 0.2 - 0.4 * s, 0.7 + 0.5 * s),
                0.1 * s,
                0.0,
                -0.1,
            )
        })
        .collect();
    let lengths: Vec<Vec<f64>> = poses
        .iter()
        .map(|p| robot.inverse_kinematics(p).unwrap().lengths().collect())
        .collect();
    let mut kin = PoseKinematics::for_robot(&robot);
    let mut w = DMatrix::zeros(6, 8);
    let mut fk = ForwardKinematics::new(&robot, ForwardSettings::default()).unwrap();
    let nudge = Rotation3::new(Vector3::new(0.0, 0.02, -0.01));
    let before = allocations_so_far();
    let mut solved = 0;
    for (pose, l) in poses.iter().zip(&lengths) {
        robot.update_kinematics(pose, &mut kin).unwrap();
        kin.write_wrench_matrix(&mut w);
        let guess = Pose::new(
            pose.position + Vector3::new(0.02, 0.0, -0.01),
            nudge * pose.rotation,
        );
        solved += usize::from(fk.solve(l, &guess).unwrap().converged);
    }
    assert_eq!(allocations_so_far() - before, 0);
    assert_eq!(solved, poses.len());
}
