//! `Robot::wrench_matrices` (batch IK + W) and the single-pose `update_kinematics` +
//! `write_wrench_matrix` do not allocate for straight cables: counted with a global allocator
//! wrapper (issue 17); nor do the pulley IK + W and the forward kinematics (issue 14).

use cdpr_kinematics::reference_robots::{ipanema_like_8, ipanema_like_8_pulleys};
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

/// 64 poses along a line through the workspace, slowly turning.
fn path_poses() -> Vec<Pose> {
    (0..64)
        .map(|k| {
            let s = k as f64 / 64.0;
            Pose::spatial(
                Vector3::new(-0.5 + s, 0.2 - 0.4 * s, 0.7 + 0.5 * s),
                0.1 * s,
                0.0,
                -0.1,
            )
        })
        .collect()
}

// The counter is per thread: tests in parallel do not disturb each other.
#[test]
fn batch_and_single_pose_ik_do_not_allocate() {
    let robot = ipanema_like_8();
    let mut poses = path_poses();
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

/// The pulley hot paths (issue 14): `update_kinematics` + `write_wrench_matrix` of a pulley robot
/// (blocks of cables, AVX2 build where the CPU has it) and `ForwardKinematics::solve`. The
/// counter is per thread, so this test may run beside the other one.
#[test]
fn pulley_ik_and_forward_kinematics_do_not_allocate() {
    let robot = ipanema_like_8_pulleys();
    let poses = path_poses();
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
