//! A fixed number of l2-max solves on the poses of the bench `tension_12_cable/l2_max`, for
//! load-independent instruction counts:
//!
//! ```text
//! cargo build --release -p cdpr-benches --example l2_max_instructions
//! valgrind --tool=callgrind --callgrind-out-file=/tmp/x.out \
//!     target/release/examples/l2_max_instructions 1000
//! ```
//!
//! Instructions per solve = (total with N solves − total with 0 solves) / N. The problems are
//! those of `benches/tension.rs` (`twelve_cable_spatial`, t ∈ [1, 1000] N, 10 kg platform under
//! gravity, the first 100 l2-feasible poses of `spatial_poses`).

use cdpr_benches::{spatial_poses, twelve_cable_spatial};
use cdpr_tension::{Method, TensionBounds, TensionProblem, TensionSolver};
use nalgebra::{DMatrix, DVector};
use std::hint::black_box;

fn main() {
    let solves: usize = match std::env::args().nth(1).map(|v| v.parse()) {
        Some(Ok(n)) => n,
        _ => {
            eprintln!("usage: l2_max_instructions SOLVES");
            std::process::exit(2);
        }
    };
    let robot = twelve_cable_spatial();
    let we = DVector::from_vec(vec![0.0, 0.0, -9.80665 * 10.0, 0.0, 0.0, 0.0]);
    let b = TensionBounds::uniform(robot.cable_count(), 1.0, 1000.0).unwrap();
    let mut l2 = TensionSolver::new(Method::L2);
    let mut ws: Vec<DMatrix<f64>> = Vec::new();
    for pose in spatial_poses(2000) {
        let Ok(kin) = robot.inverse_kinematics(&pose) else {
            continue;
        };
        let w = kin.wrench_matrix();
        if l2.is_feasible(&TensionProblem::new(&w, &we, &b)).unwrap() {
            ws.push(w);
            if ws.len() == 100 {
                break;
            }
        }
    }
    assert_eq!(ws.len(), 100, "not enough feasible poses");
    let mut solver = TensionSolver::new(Method::L2Max);
    let mut t = DVector::zeros(12);
    // A fingerprint of every bit of the answers, to compare builds.
    let (mut ok, mut sum, mut bits) = (0, 0.0, 0u64);
    for k in 0..solves {
        let p = TensionProblem::new(black_box(&ws[k % ws.len()]), &we, &b);
        if solver.solve_into(&p, &mut t).unwrap().is_ok() {
            ok += 1;
            sum += t.norm_squared();
            for v in t.iter() {
                bits = (bits.rotate_left(7) ^ v.to_bits()).wrapping_mul(0x9e37_79b9_7f4a_7c15);
            }
        }
    }
    println!(
        "{ok} of {solves} solved, mean ‖t‖² {:e} N², answer bits {bits:016x}",
        sum / ok.max(1) as f64
    );
}
