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
//!   code 1 on a false answer of a complete method (see `xtask/src/soak.rs`);
//! - `schema`: the JSON Schema of every request and report of `cdpr-api`, written to
//!   `docs/schema/` (see `xtask/src/schema.rs`; a test of `cdpr-api` checks the files);
//! - `studio [--check]`: the browser studio into `target/studio/` (cdpr-studio compiled to
//!   WebAssembly, wasm-bindgen, the page and the example robots); `--check` loads it in headless
//!   Chromium and compares its numbers with the CLI's (see `xtask/src/studio.rs`);
//! - `loops [--tests]`: the files of the tree that import each other in a loop; exit code 1 if there is one
//!   (see `xtask/src/loops.rs`; its test runs the check under `cargo test`);
//! - `fn-length [MAX] [DIR …]`: the front-end functions (CLI and plots, Python, studio) longer
//!   than MAX = 80 lines; exit code 1 if there is one (see `xtask/src/fn_length.rs`; its test
//!   runs the check under `cargo test`).

mod bench;
mod fn_length;
mod fuzz;
mod gallery;
mod loops;
mod reproduce;
mod schema;
mod soak;
mod studio;

use std::path::Path;
use std::process::ExitCode;

const USAGE: &str = "usage: cargo xtask <reproduce | gallery | bench | fuzz | soak | studio | loops | fn-length | schema> [options]   (`cargo xtask <command> --help`)";

const REPRODUCE_HELP: &str = "cargo xtask reproduce: regenerates the reproduction of the thesis chapter on \
planar tendon-driven manipulators (Tables 6.5-6.10), Krut, Company & Pierrot 2004 and Picard, Caro, \
Plestan & Claveau 2020 (docs/reproduction.md and docs/figures/), then the published-robot gallery \
(docs/robots.md). It takes no options.";

const GALLERY_HELP: &str = "cargo xtask gallery: regenerates the published-robot gallery (docs/robots.md \
and its pictures) from examples/robots/caspr-*.toml and wirecenter-*.toml. It takes no options.";

/// `reproduce` and `gallery` take no options: `Some(Ok(help))` for `--help`, `Some(Err(usage
/// error))` for any other argument (they used to be ignored, so `reproduce --help` started the
/// whole reproduction), `None` to run the command.
fn no_option_command(args: &[String]) -> Option<Result<&'static str, String>> {
    let help = match args.first().map(String::as_str) {
        Some("reproduce") => REPRODUCE_HELP,
        Some("gallery") => GALLERY_HELP,
        _ => return None,
    };
    let extra = args.get(1)?;
    Some(if matches!(extra.as_str(), "-h" | "--help") {
        Ok(help)
    } else {
        Err(format!(
            "error: `cargo xtask {}` takes no arguments, got `{extra}`\n\n{help}",
            args[0]
        ))
    })
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives one level below the workspace root");
    if let Some(answer) = no_option_command(&args) {
        return match answer {
            Ok(help) => {
                println!("{help}");
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("{e}");
                ExitCode::from(2)
            }
        };
    }
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
        Some("schema") => match schema::run(root) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::FAILURE
            }
        },
        Some("studio") => studio::run(root, &args[1..]),
        Some("fn-length") => match fn_length::run(root, &args[1..]) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::FAILURE
            }
        },
        Some("loops") => match loops::run(root, &args[1..]) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::FAILURE
            }
        },
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

#[cfg(test)]
mod tests {
    use super::*;

    fn args(a: &[&str]) -> Vec<String> {
        a.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn reproduce_and_gallery_teach_on_help_and_refuse_arguments() {
        assert!(no_option_command(&args(&["reproduce"])).is_none());
        assert!(no_option_command(&args(&["gallery"])).is_none());
        assert!(no_option_command(&args(&["soak", "--help"])).is_none());
        let help = no_option_command(&args(&["reproduce", "--help"]))
            .unwrap()
            .unwrap();
        assert!(help.contains("docs/reproduction.md"), "{help}");
        let help = no_option_command(&args(&["gallery", "-h"]))
            .unwrap()
            .unwrap();
        assert!(help.contains("docs/robots.md"), "{help}");
        let err = no_option_command(&args(&["reproduce", "--fast"]))
            .unwrap()
            .unwrap_err();
        assert!(
            err.contains("takes no arguments") && err.contains("--fast"),
            "{err}"
        );
    }
}
