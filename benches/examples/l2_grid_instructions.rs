//! The 8-cable l2 grid of `benches/workspace.rs` (`spatial_grid/eight_cable_l2_15625`) a fixed
//! number of times, for load-independent instruction counts:
//!
//! ```text
//! cargo build --release -p cdpr-benches --example l2_grid_instructions
//! RAYON_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file=/tmp/x.out \
//!     target/release/examples/l2_grid_instructions 4
//! ```
//!
//! Instructions per pose = (total with N grids − total with 0 grids) / (15 625 N). Prints the
//! feasible count of the grid (the verdicts must not change).

use cdpr_benches::ipanema_like_8;
use cdpr_tension::{Method, TensionBounds};
use cdpr_workspace::{Criterion as Cr, Grid, PoseEvaluator, constant_orientation_workspace};
use nalgebra::{DVector, Rotation3};
use std::hint::black_box;

fn main() {
    let grids = match std::env::args().nth(1) {
        Some(s) => s.parse::<usize>().expect("a grid count"),
        None => {
            eprintln!("usage: l2_grid_instructions GRIDS");
            std::process::exit(2);
        }
    };
    let robot = ipanema_like_8();
    let bounds = TensionBounds::uniform(8, 1.0, 1000.0).unwrap();
    let grid = Grid::over_frame(&robot, 24);
    let gravity = DVector::from_vec(vec![0.0, 0.0, -9.80665 * 10.0, 0.0, 0.0, 0.0]);
    let l2 = PoseEvaluator::new(
        robot,
        bounds,
        vec![Cr::TensionFeasible {
            method: Method::L2,
            wrench: gravity,
        }],
    )
    .unwrap();
    let id = Rotation3::identity();
    let mut feasible = 0;
    for _ in 0..grids {
        feasible = constant_orientation_workspace(black_box(&l2), &id, &grid)
            .unwrap()
            .feasible_points;
    }
    println!("{grids} grids, {feasible} feasible of 15625 poses");
}
