//! Issue 17's table operations in a plain loop, for load-independent instruction counts:
//! `valgrind --tool=callgrind <binary> OPERATION REPS` runs OPERATION (`ik_w`,
//! `ik_w_batch`, `ik_w_batch_portable`, `improved_closed_form`, `barycenter`, `l2`, `l1`, `linf`) REPS times over the 20 000 poses of
//! the fixture; instructions per call = (count at REPS − count at 0) / (20 000 · REPS). It prints
//! the feasible count and a digest of the tensions' bits (to compare two builds' answers). With
//! `TENSIONS_OUT=FILE` it also writes the first pass's tensions in N (8 little-endian f64 per pose,
//! NaN for no answer), to measure how far two builds' answers are apart.

use cdpr_benches::issue_17::fixture;
use cdpr_kinematics::{KinematicsError, Pose, PoseKinematics, Robot};
use cdpr_tension::{Method, TensionProblem, TensionSolver};
use nalgebra::{DMatrix, DVector};
use std::hint::black_box;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let op = args.get(1).map_or("l2", String::as_str);
    let reps: usize = args.get(2).map_or(1, |s| s.parse().expect("REPS"));
    let f = fixture();
    let mut kin = PoseKinematics::for_robot(&f.robot);
    let mut w = DMatrix::zeros(6, 8);
    if op == "ik_w" {
        let mut s = 0.0;
        for _ in 0..reps {
            for pose in &f.poses {
                f.robot
                    .update_kinematics(black_box(pose), &mut kin)
                    .unwrap();
                kin.write_wrench_matrix(&mut w);
                s += w[(5, 7)];
            }
        }
        println!("{s}");
        return;
    }
    // The batch API (the structure-of-arrays kernel the CPU selects, or its portable build).
    type Batch = fn(&Robot, &[Pose], &mut [f64], &mut [bool]) -> Result<usize, KinematicsError>;
    let batch: Option<Batch> = match op {
        "ik_w_batch" => Some(Robot::wrench_matrices),
        "ik_w_batch_portable" => Some(Robot::wrench_matrices_portable),
        _ => None,
    };
    if let Some(batch) = batch {
        let mut out = vec![0.0; f.poses.len() * 48];
        let mut valid = vec![false; f.poses.len()];
        let mut count = 0;
        for _ in 0..reps {
            count += batch(&f.robot, black_box(&f.poses), &mut out, &mut valid).unwrap();
        }
        println!("{count} {}", out[out.len() - 1]);
        return;
    }
    let method: Method = op.replace('_', "-").parse().expect("a method name");
    let ws: Vec<DMatrix<f64>> = f
        .poses
        .iter()
        .map(|p| f.robot.inverse_kinematics(p).unwrap().wrench_matrix())
        .collect();
    let mut solver = TensionSolver::new(method);
    let mut t = DVector::zeros(8);
    let mut ok = 0usize;
    // FNV-1a over the bits of every feasible answer: equal digests, bit-identical tensions.
    let mut digest = 0xcbf2_9ce4_8422_2325u64;
    let out_path = std::env::var_os("TENSIONS_OUT");
    let mut dump = Vec::new();
    for pass in 0..reps {
        for w in &ws {
            let p = TensionProblem::new(w, &f.load, &f.bounds);
            let feasible = solver.solve_into(black_box(&p), &mut t).unwrap().is_ok();
            if feasible {
                ok += 1;
                for x in t.iter() {
                    digest = (digest ^ x.to_bits()).wrapping_mul(0x100_0000_01b3);
                }
            }
            if pass == 0 && out_path.is_some() {
                for x in t.iter() {
                    let v = if feasible { *x } else { f64::NAN };
                    dump.extend_from_slice(&v.to_le_bytes());
                }
            }
        }
    }
    if let Some(path) = out_path {
        std::fs::write(path, dump).expect("TENSIONS_OUT is writable");
    }
    println!("{op}: {ok} feasible answers in {reps} passes, tension digest {digest:016x}");
}
