//! A fixed number of runs of the 8-cable workspace grids of `benches/workspace.rs`
//! (`spatial_grid/eight_cable_*_15625`), for load-independent instruction counts:
//!
//! ```text
//! cargo build --release -p cdpr-benches --example grid_instructions
//! RAYON_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file=/tmp/x.out \
//!     target/release/examples/grid_instructions wrench_closure 10
//! ```
//!
//! Instructions per pose = (total with N runs − total with 0 runs) / (N · 15 625).

use cdpr_benches::ipanema_like_8;
use cdpr_tension::{Method, TensionBounds};
use cdpr_workspace::{Criterion, Grid, PoseEvaluator, constant_orientation_workspace};
use nalgebra::{DVector, Rotation3};
use std::hint::black_box;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (case, runs) = match args.as_slice() {
        [_, case, runs] => (case.as_str(), runs.parse::<usize>().expect("a run count")),
        _ => {
            eprintln!("usage: grid_instructions wrench_closure|l2 RUNS");
            std::process::exit(2);
        }
    };
    let robot = ipanema_like_8();
    let bounds = TensionBounds::uniform(8, 1.0, 1000.0).unwrap();
    let grid = Grid::over_frame(&robot, 24); // 25³ = 15 625 poses
    let criteria = match case {
        "wrench_closure" => vec![Criterion::WrenchClosure],
        "l2" => vec![Criterion::TensionFeasible {
            method: Method::L2,
            wrench: DVector::from_vec(vec![0.0, 0.0, -9.80665 * 10.0, 0.0, 0.0, 0.0]),
        }],
        _ => panic!("unknown case {case}"),
    };
    let eval = PoseEvaluator::new(robot, bounds, criteria).unwrap();
    let mut count = 0;
    for _ in 0..runs {
        let ws = constant_orientation_workspace(black_box(&eval), &Rotation3::identity(), &grid)
            .unwrap();
        count += ws.feasible.iter().filter(|&&f| f).count();
    }
    println!("{case}: {runs} runs, {count} feasible poses");
}
