//! # xtask: project automation for the `cdpr` workspace
//!
//! Run as `cargo xtask <subcommand>` (alias in `.cargo/config.toml`, release build):
//!
//! - `reproduce`: regenerate the published results from the code alone: Tables 6.5–6.10 of
//!   the thesis chapter (every published design re-evaluated, our optimiser re-run from every published
//!   start), written to `docs/reproduction.md` and `target/reproduce/tables.json`, with every
//!   convention the thesis leaves open settled by experiment;
//! - `gallery`: docs/robots.md, what cdpr computes for every published robot shipped in
//!   examples/robots/ (see `xtask/src/gallery.rs`); also run at the end of `reproduce`;
//! - `bench [--quick] [--no-run] [FILTER]`: run the criterion suite of `benches/` and print each
//!   benchmark's median against the performance target from the issues (pass/miss), also
//!   written to `target/bench/summary.md` (see `xtask/src/bench.rs`);
//! - `fuzz [--seconds N] [--target NAME]`: run the cargo-fuzz targets of `fuzz/` for N seconds
//!   each on stable Rust (`--sanitizer none`); exit code 1 if one crashed (see `xtask/src/fuzz.rs`);
//! - `soak [--problems N] [--json]`: every tension method on N random problems, every answer
//!   checked independently (compensated residual, an LP solved with Clarabel directly); exit
//!   code 1 on a false answer of a complete method (see `xtask/src/soak.rs`).

mod bench;
mod fuzz;
mod gallery;
mod reproduce;
mod soak;

use std::path::Path;
use std::process::ExitCode;

const USAGE: &str = "usage: cargo xtask <reproduce | gallery | bench | fuzz | soak> [options]   (`cargo xtask <command> --help`)";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives one level below the workspace root");
    match args.first().map(String::as_str) {
        Some("reproduce") => match reproduce::run(root).and_then(|()| gallery::run(root)) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::FAILURE
            }
        },
        Some("gallery") => match gallery::run(root) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::FAILURE
            }
        },
        Some("bench") => bench::run(root, &args[1..]),
        Some("fuzz") => fuzz::run(root, &args[1..]),
        Some("soak") => soak::run(&args[1..]),
        Some("-h" | "--help" | "help") => {
            println!("{USAGE}");
            ExitCode::SUCCESS
        }
        _ => {
            eprintln!("{USAGE}");
            ExitCode::from(2)
        }
    }
}
