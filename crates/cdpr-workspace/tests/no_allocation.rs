//! The evaluator does not allocate per pose (after its first use): counted with a global
//! allocator wrapper.
#[path = "it/common/mod.rs"]
mod common;

use cdpr_kinematics::Pose;
use cdpr_tension::{Method, TensionBounds};
use cdpr_workspace::{Criterion, PoseEvaluator};
use common::*;
use nalgebra::{DVector, Rotation3, Vector3};
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

/// Allocations made while evaluating `poses` (after one warm-up pass).
fn allocations(eval: &mut PoseEvaluator, poses: &[Pose]) -> (usize, usize) {
    let mut feasible = 0;
    for p in poses {
        eval.is_feasible(p);
    }
    let before = allocations_so_far();
    for p in poses {
        feasible += eval.is_feasible(p) as usize;
    }
    (allocations_so_far() - before, feasible)
}

fn planar_poses(phi: f64) -> Vec<Pose> {
    let mut v = Vec::new();
    for i in 0..=20 {
        for j in 0..=20 {
            v.push(Pose::planar(
                -1.0 + 0.1 * i as f64,
                -1.0 + 0.1 * j as f64,
                phi,
            ));
        }
    }
    v
}

// One test function: the counter is global, tests in parallel would disturb each other.
#[test]
fn evaluator_does_not_allocate_per_pose() {
    let mut cases: Vec<(&str, PoseEvaluator, Vec<Pose>)> = vec![
        ("3-cable exact", three_cable_eval(0), planar_poses(0.05)),
        (
            "4-cable l2",
            four_cable_eval(1, Method::L2),
            planar_poses(0.1),
        ),
        (
            "4-cable l1",
            four_cable_eval(2, Method::L1),
            planar_poses(0.0),
        ),
    ];
    let spatial = eight_cable_spatial();
    let mut poses = Vec::new();
    for i in 0..=8 {
        for j in 0..=8 {
            for k in 0..=8 {
                let p = Vector3::new(i as f64, j as f64, k as f64) * 0.15 - Vector3::repeat(0.6);
                poses.push(Pose::new(p, Rotation3::identity()));
            }
        }
    }
    let bounds = TensionBounds::uniform(8, 1.0, 100.0).unwrap();
    cases.push((
        "8-cable wrench closure",
        PoseEvaluator::new(
            spatial.clone(),
            bounds.clone(),
            vec![Criterion::WrenchClosure],
        )
        .unwrap(),
        poses.clone(),
    ));
    let gravity = DVector::from_vec(vec![0.0, 0.0, -10.0, 0.0, 0.0, 0.0]);
    cases.push((
        "8-cable l2",
        PoseEvaluator::new(
            spatial,
            bounds,
            vec![Criterion::TensionFeasible {
                method: Method::L2,
                wrench: gravity,
            }],
        )
        .unwrap(),
        poses,
    ));
    // The stiffness floor on top of l2 (tensions and K in reused buffers).
    cases.push((
        "4-cable l2 + stiffness",
        PoseEvaluator::new(
            four_cable(),
            TensionBounds::uniform(4, T_MIN, T_MAX).unwrap(),
            vec![
                Criterion::TensionFeasible {
                    method: Method::L2,
                    wrench: load(0),
                },
                Criterion::Stiffness {
                    min_eigenvalue: 50.0,
                },
            ],
        )
        .unwrap()
        .with_axial_stiffness(vec![1e4; 4])
        .unwrap(),
        planar_poses(0.0),
    ));
    for (name, mut eval, poses) in cases {
        let (allocs, feasible) = allocations(&mut eval, &poses);
        // The batch path (SIMD inverse kinematics for the W-only criteria, pose by pose for
        // the others), warmed up once, then counted.
        let mut verdicts = vec![false; poses.len()];
        eval.feasible_batch(&poses, &mut verdicts);
        let before = allocations_so_far();
        eval.feasible_batch(&poses, &mut verdicts);
        let batch_allocs = allocations_so_far() - before;
        assert_eq!(
            batch_allocs, 0,
            "{name}: {batch_allocs} allocations in the batch"
        );
        assert_eq!(verdicts.iter().filter(|&&f| f).count(), feasible, "{name}");
        assert!(
            feasible > 0 && feasible < poses.len(),
            "{name}: {feasible} feasible"
        );
        assert_eq!(
            allocs,
            0,
            "{name}: {allocs} allocations for {} poses",
            poses.len()
        );
    }
}
