//! A fixed number of runs of one operation of issue 26's throughput table over the 20 000 poses
//! of its fixture (`cdpr_benches::issue_26`, the code `benches/benches/throughput.rs` times),
//! for load-independent instruction counts and `perf stat` CPU times:
//!
//! ```text
//! cargo build --release -p cdpr-benches --example issue_26_instructions
//! valgrind --tool=callgrind --callgrind-out-file=/tmp/x.out \
//!     target/release/examples/issue_26_instructions dykstra 1
//! perf stat -e task-clock,instructions target/release/examples/issue_26_instructions dykstra 5
//! ```
//!
//! Per call = (total with RUNS runs − total with 0 runs) / (RUNS · 20 000): the set-up (the
//! poses and, for the tension methods, their 20 000 wrench matrices) is in both totals. The
//! checksum (feasible poses, Σ of the tensions' first entries) changes when an answer does.

use cdpr_benches::issue_26::{POSES, fixture};
use cdpr_kinematics::PoseKinematics;
use cdpr_tension::{Method, MethodOptions, PunctureInterior, TensionProblem, TensionSolver};
use nalgebra::{DMatrix, DVector};
use std::hint::black_box;

const CASES: &str = "ik_w|ik_w_batch|improved_closed_form|barycenter|l2|l1|linf|\
                     pott_closed_form|pott_closed_form_ee|puncture|puncture_cf|dykstra|\
                     dykstra_alternating|l2_mid|vertex_centroid|p_norm|optimally_safe";

/// The method and options of a tension case, `None` for the kinematic cases and unknown names.
fn tension_case(case: &str) -> Option<(Method, MethodOptions)> {
    let d = MethodOptions::default();
    Some(match case {
        "improved_closed_form" => (Method::ImprovedClosedForm, d),
        "barycenter" => (Method::Barycenter, d),
        "l2" => (Method::L2, d),
        "l1" => (Method::L1, d),
        "linf" => (Method::Linf, d),
        "pott_closed_form" => (Method::PottClosedForm, d),
        "pott_closed_form_ee" => (Method::PottClosedFormEe, d),
        "puncture" => (Method::Puncture, d),
        "puncture_cf" => (
            Method::Puncture,
            MethodOptions {
                interior: PunctureInterior::ClosedForm,
                ..d
            },
        ),
        "dykstra" => (Method::Dykstra, d),
        "dykstra_alternating" => (
            Method::Dykstra,
            MethodOptions {
                alternating: true,
                ..d
            },
        ),
        "l2_mid" => (Method::L2Mid, d),
        "vertex_centroid" => (Method::VertexCentroid, d),
        "p_norm" => (Method::PNorm, d),
        "optimally_safe" => (Method::OptimallySafe, d),
        _ => return None,
    })
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let [_, case, runs] = args.as_slice() else {
        eprintln!("usage: issue_26_instructions {CASES} RUNS");
        std::process::exit(2);
    };
    let runs: usize = runs.parse().expect("a run count");
    let f = fixture();
    let (mut feasible, mut sum) = (0usize, 0.0f64);
    match case.as_str() {
        "ik_w" => {
            let mut kin = PoseKinematics::for_robot(&f.robot);
            let mut w = DMatrix::zeros(6, 8);
            for _ in 0..runs {
                for pose in &f.poses {
                    f.robot
                        .update_kinematics(black_box(pose), &mut kin)
                        .unwrap();
                    kin.write_wrench_matrix(&mut w);
                    sum += w[(5, 7)];
                }
            }
        }
        "ik_w_batch" => {
            let mut out = vec![0.0; POSES * 48];
            let mut valid = vec![false; POSES];
            // Touch the 7.7 MB output once in the set-up, so that the first run's page faults
            // (about 1 900) count in the 0-run total too: the runs measure the steady state.
            f.robot
                .wrench_matrices(&f.poses, &mut out, &mut valid)
                .unwrap();
            for _ in 0..runs {
                feasible += f
                    .robot
                    .wrench_matrices(black_box(&f.poses), &mut out, &mut valid)
                    .unwrap();
                sum += out[POSES * 48 - 1];
            }
        }
        name => {
            let Some((method, options)) = tension_case(name) else {
                eprintln!("unknown case {name}; one of {CASES}");
                std::process::exit(2);
            };
            let ws: Vec<DMatrix<f64>> = f
                .poses
                .iter()
                .map(|p| f.robot.inverse_kinematics(p).unwrap().wrench_matrix())
                .collect();
            let mut solver = TensionSolver::new(method).with_options(options).unwrap();
            let mut t = DVector::zeros(8);
            for _ in 0..runs {
                for w in &ws {
                    let p = TensionProblem::new(black_box(w), &f.load, &f.bounds);
                    if solver.solve_into(&p, &mut t).unwrap().is_ok() {
                        feasible += 1;
                        sum += t[0];
                    }
                }
            }
        }
    }
    println!("{case}: {runs} runs of {POSES} poses, {feasible} feasible, checksum {sum:.12e}");
}
