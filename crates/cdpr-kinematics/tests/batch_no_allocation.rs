//! `Robot::wrench_matrices` (batch IK + W) and the single-pose `update_kinematics` +
//! `write_wrench_matrix` do not allocate for straight cables: counted with a global allocator
//! wrapper (issue 17).

use cdpr_kinematics::reference_robots::ipanema_like_8;
use cdpr_kinematics::{Pose, PoseKinematics};
use nalgebra::{DMatrix, Vector3};
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
fn batch_and_single_pose_ik_do_not_allocate() {
    let robot = ipanema_like_8();
    let mut poses: Vec<Pose> = (0..64)
        .map(|k| {
            let s = k as f64 / 64.0;
            Pose::spatial(
                Vector3::new(-0.5 + s, 0.2 - 0.4 * s, 0.7 + 0.5 * s),
                0.1 * s,
                0.0,
                -0.1,
            )
        })
        .collect();
    // One pose the batch rejects (cable 1 of zero length): rejection must not allocate either.
    poses[10] = Pose::spatial(
        robot.cables()[0].frame - robot.cables()[0].platform,
        0.0,
        0.0,
        0.0,
    );
    let mut out = vec![0.0; poses.len() * 48];
    let mut valid = vec![false; poses.len()];
    let mut kin = PoseKinematics::for_robot(&robot);
    let mut w = DMatrix::zeros(6, 8);
    let before = allocations_so_far();
    let count = robot.wrench_matrices(&poses, &mut out, &mut valid).unwrap();
    // The portable build of the structure-of-arrays kernel (the AVX2 one runs above).
    let portable = robot
        .wrench_matrices_portable(&poses, &mut out, &mut valid)
        .unwrap();
    for (k, pose) in poses.iter().enumerate() {
        if k != 10 {
            robot.update_kinematics(pose, &mut kin).unwrap();
            kin.write_wrench_matrix(&mut w);
        }
    }
    assert_eq!(allocations_so_far() - before, 0);
    assert_eq!(count, poses.len() - 1);
    assert_eq!(portable, count);
    assert!(!valid[10]);
}
