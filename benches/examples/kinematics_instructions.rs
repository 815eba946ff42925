//! A fixed number of calls of one kinematics hot path, for load-independent instruction counts:
//!
//! ```text
//! cargo build --release -p cdpr-benches --example kinematics_instructions
//! valgrind --tool=callgrind --callgrind-out-file=/tmp/x.out \
//!     target/release/examples/kinematics_instructions ik_w_8_spatial_pulley 100000
//! ```
//!
//! Instructions per call = (total with N calls − total with 0 calls) / N. The problems are those
//! of `benches/kinematics.rs` (same robots, poses and guesses).

use cdpr_benches::goals::forward_problems;
use cdpr_benches::{ipanema_like_8, ipanema_like_8_pulleys, spatial_poses};
use cdpr_kinematics::{ForwardKinematics, ForwardSettings, PoseKinematics};
use nalgebra::DMatrix;
use std::hint::black_box;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (case, calls) = match args.as_slice() {
        [_, case, calls] => (case.as_str(), calls.parse::<usize>().expect("a call count")),
        _ => {
            eprintln!(
                "usage: kinematics_instructions ik_and_wrench_matrix/spatial_8|ik_w_8_spatial_pulley|fk_8_spatial_standard|fk_8_spatial_pulley CALLS"
            );
            std::process::exit(2);
        }
    };
    let poses = spatial_poses(1000);
    let robot = match case {
        "ik_and_wrench_matrix/spatial_8" | "fk_8_spatial_standard" => ipanema_like_8(),
        "ik_w_8_spatial_pulley" | "fk_8_spatial_pulley" => ipanema_like_8_pulleys(),
        _ => panic!("unknown case {case}"),
    };
    let mut sum = 0.0;
    if case.starts_with("ik") {
        let mut kin = PoseKinematics::for_robot(&robot);
        let mut w = DMatrix::zeros(6, 8);
        for k in 0..calls {
            robot
                .update_kinematics(black_box(&poses[k % poses.len()]), &mut kin)
                .unwrap();
            kin.write_wrench_matrix(&mut w);
            sum += black_box(w[(5, 7)]);
        }
    } else {
        let problems = forward_problems(&robot, &poses);
        let mut fk = ForwardKinematics::new(&robot, ForwardSettings::default()).unwrap();
        let mut iterations = 0;
        for k in 0..calls {
            let (l, guess) = &problems[k % problems.len()];
            let solution = fk.solve(black_box(l), guess).unwrap();
            sum += solution.residual;
            iterations += solution.iterations;
        }
        println!(
            "{:.3} iterations per solve",
            iterations as f64 / calls.max(1) as f64
        );
    }
    println!("{case}: {calls} calls, checksum {sum:e}");
}
