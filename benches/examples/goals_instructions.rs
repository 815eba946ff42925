//! A fixed number of runs of one speed goal of issues 27–29 ([`cdpr_benches::goals`], the code
//! the criterion benches time), for load-independent instruction counts:
//!
//! ```text
//! cargo build --release -p cdpr-benches --example goals_instructions
//! RAYON_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file=/tmp/x.out \
//!     target/release/examples/goals_instructions inverse_dynamics 3
//! ```
//!
//! Instructions per unit = (total with N runs − total with 0 runs) / (N · units per run); the
//! units per run are printed (solves, samples, steps or poses). `--describe` also prints what
//! the work took (iterations per solve; not to be combined with a count).

use cdpr_benches::goals::{
    CatenarySolve, DynamicGrid, ElasticForward, Goal, InverseDynamics, NoisyForward, Rk4,
    SaggingStatics, SelfCalibration,
};
use std::hint::black_box;

fn repeat<G: Goal>(mut goal: G, runs: usize, describe: bool) -> (u64, f64) {
    let mut sum = 0.0;
    for _ in 0..runs {
        sum += black_box(goal.run());
    }
    if describe {
        let note = goal.describe();
        if !note.is_empty() {
            println!("{note}");
        }
    }
    (G::UNITS, sum)
}

fn main() {
    const CASES: &str = "self_calibration|fk_noisy|inverse_dynamics|rk4|dynamic_grid|\
                         catenary|sagging_statics|elastic_fk|catenary_fk";
    let args: Vec<String> = std::env::args().collect();
    let (case, runs, describe) = match args.as_slice() {
        [_, case, runs, rest @ ..] if rest.iter().all(|a| a == "--describe") => (
            case.as_str(),
            runs.parse::<usize>().expect("a run count"),
            !rest.is_empty(),
        ),
        _ => {
            eprintln!("usage: goals_instructions {CASES} RUNS [--describe]");
            std::process::exit(2);
        }
    };
    let (units, sum) = match case {
        "self_calibration" => repeat(SelfCalibration::new(), runs, describe),
        "fk_noisy" => repeat(NoisyForward::new(), runs, describe),
        "inverse_dynamics" => repeat(InverseDynamics::new(), runs, describe),
        "rk4" => repeat(Rk4::new(), runs, describe),
        "dynamic_grid" => repeat(DynamicGrid::new(), runs, describe),
        "catenary" => repeat(CatenarySolve::new(), runs, describe),
        "sagging_statics" => repeat(SaggingStatics::new(), runs, describe),
        "elastic_fk" => repeat(ElasticForward::elastic(), runs, describe),
        "catenary_fk" => repeat(ElasticForward::catenary(), runs, describe),
        _ => {
            eprintln!("unknown case {case}; one of {CASES}");
            std::process::exit(2);
        }
    };
    println!("{case}: {runs} runs of {units} units, checksum {sum:.12e}");
}
