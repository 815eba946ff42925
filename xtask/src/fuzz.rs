//! # `cargo xtask fuzz`
//!
//! Runs the cargo-fuzz targets of `fuzz/` one after the other, each for `--seconds N`
//! (`cargo fuzz run --sanitizer none <target> fuzz/corpus/<target> fuzz/seeds/<target> --
//! -max_total_time=N -timeout=T`), on stable Rust (no sanitizer, so no nightly). The committed
//! seeds in `fuzz/seeds/<target>` are read; new inputs go to the git-ignored
//! `fuzz/corpus/<target>`; a crashing input is written to `fuzz/artifacts/<target>/`.
//!
//! Prints per target the executions, the time and the verdict, keeps the full libFuzzer log in
//! `target/fuzz/<target>.log`, and exits non-zero if any target crashed (panic, timeout).
//!
//! Needs `cargo install cargo-fuzz`.

use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode, Stdio};
use std::time::Instant;

/// The targets, in the order they run.
pub const TARGETS: [&str; 4] = [
    "robot_file",
    "tension_methods",
    "polytope_index",
    "forward_kinematics",
];

const USAGE: &str = "usage: cargo xtask fuzz [--seconds N] [--target NAME] [--timeout S]

Runs every fuzz target of fuzz/ (robot_file, tension_methods, polytope_index,
forward_kinematics) for N seconds
each (default 60) with `cargo fuzz run --sanitizer none` (stable Rust). A single input taking
longer than S seconds (default 10) counts as a hang. Exit code 1 if any target crashed; the
crashing input is in fuzz/artifacts/<target>/ (replay: cargo fuzz run --sanitizer none
<target> <file>). Needs `cargo install cargo-fuzz`.";

struct Options {
    seconds: u64,
    timeout: u64,
    targets: Vec<String>,
}

fn parse(args: &[String]) -> Result<Option<Options>, String> {
    let mut o = Options {
        seconds: 60,
        timeout: 10,
        targets: Vec::new(),
    };
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut value = |name: &str| {
            it.next()
                .ok_or_else(|| format!("{name} needs a value"))
                .cloned()
        };
        match a.as_str() {
            "-h" | "--help" => return Ok(None),
            "--seconds" => {
                o.seconds = value("--seconds")?
                    .parse()
                    .map_err(|e| format!("--seconds: {e}"))?
            }
            "--timeout" => {
                o.timeout = value("--timeout")?
                    .parse()
                    .map_err(|e| format!("--timeout: {e}"))?
            }
            "--target" => {
                let t = value("--target")?;
                if !TARGETS.contains(&t.as_str()) {
                    return Err(format!(
                        "unknown target `{t}` (targets: {})",
                        TARGETS.join(", ")
                    ));
                }
                o.targets.push(t);
            }
            other => return Err(format!("unknown argument `{other}`")),
        }
    }
    if o.targets.is_empty() {
        o.targets = TARGETS.iter().map(|s| s.to_string()).collect();
    }
    Ok(Some(o))
}

/// What one libFuzzer run reported.
#[derive(Debug, Default)]
struct Report {
    runs: Option<u64>,
    seconds: f64,
    corpus: Option<String>,
    crashed: bool,
    artifact: Option<String>,
    first_panic: Option<String>,
}

/// Reads the lines libFuzzer prints (`Done N runs in S second(s)`,
/// `stat::number_of_executed_units: N`, `#N DONE cov: .. corp: ..`, `Test unit written to ..`).
fn scan(line: &str, r: &mut Report) {
    if let Some(rest) = line.strip_prefix("stat::number_of_executed_units:") {
        r.runs = rest.trim().parse().ok().or(r.runs);
    } else if let Some(rest) = line.strip_prefix("Done ") {
        if let Some(n) = rest.split_whitespace().next().and_then(|n| n.parse().ok()) {
            r.runs = Some(n);
        }
    } else if line.starts_with('#') && line.contains(" corp: ") {
        if let Some(c) = line
            .split(" corp: ")
            .nth(1)
            .and_then(|s| s.split(' ').next())
        {
            r.corpus = Some(c.to_string());
        }
        if let Some(n) = line[1..]
            .split(|c: char| !c.is_ascii_digit())
            .next()
            .and_then(|n| n.parse().ok())
        {
            r.runs = Some(n);
        }
    }
    if line.contains("Test unit written to ") {
        r.artifact = line
            .split("Test unit written to ")
            .nth(1)
            .map(|s| s.trim().to_string());
    }
    if r.first_panic.is_none() && line.contains("panicked at") {
        r.first_panic = Some(line.trim().to_string());
    }
    if line.contains("ERROR: libFuzzer") || line.contains("SUMMARY: libFuzzer") {
        r.crashed = true;
    }
}

fn fuzz_one(root: &Path, target: &str, o: &Options) -> Result<Report, String> {
    let fuzz_dir = root.join("fuzz");
    let corpus = fuzz_dir.join("corpus").join(target);
    let seeds = fuzz_dir.join("seeds").join(target);
    std::fs::create_dir_all(&corpus).map_err(|e| format!("{}: {e}", corpus.display()))?;
    let log_dir = root.join("target").join("fuzz");
    std::fs::create_dir_all(&log_dir).map_err(|e| format!("{}: {e}", log_dir.display()))?;
    let log_path = log_dir.join(format!("{target}.log"));
    let mut log =
        std::fs::File::create(&log_path).map_err(|e| format!("{}: {e}", log_path.display()))?;

    let mut cmd = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()));
    cmd.current_dir(root)
        .args(["fuzz", "run", "--sanitizer", "none", "--fuzz-dir"])
        .arg(&fuzz_dir)
        .arg(target)
        .arg(&corpus);
    if seeds.is_dir() {
        cmd.arg(&seeds);
    }
    cmd.arg("--")
        .arg(format!("-max_total_time={}", o.seconds))
        .arg(format!("-timeout={}", o.timeout))
        .arg("-print_final_stats=1")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    eprintln!("== fuzz {target}: {} s ==", o.seconds);
    let start = Instant::now();
    let mut child = cmd.spawn().map_err(|e| {
        format!("cannot run `cargo fuzz` ({e}); install it with `cargo install cargo-fuzz`")
    })?;
    // libFuzzer writes to stderr; cargo's build output too. Merge stdout in a thread.
    let stdout = child.stdout.take().expect("piped");
    let out_thread = std::thread::spawn(move || {
        BufReader::new(stdout)
            .lines()
            .map_while(Result::ok)
            .collect::<Vec<_>>()
    });
    let mut report = Report::default();
    let stderr = child.stderr.take().expect("piped");
    for line in BufReader::new(stderr).lines().map_while(Result::ok) {
        let _ = writeln!(log, "{line}");
        scan(&line, &mut report);
        // Echo the progress lines, not every new corpus entry.
        let noisy = line.starts_with('#')
            && (line.contains("\tNEW ")
                || line.contains("\tREDUCE ")
                || line.contains("\tRELOAD "));
        if !noisy {
            eprintln!("  {line}");
        }
    }
    for line in out_thread.join().unwrap_or_default() {
        let _ = writeln!(log, "{line}");
        scan(&line, &mut report);
        eprintln!("  {line}");
    }
    let status = child.wait().map_err(|e| e.to_string())?;
    report.seconds = start.elapsed().as_secs_f64();
    if !status.success() {
        report.crashed = true;
    }
    Ok(report)
}

/// `cargo xtask fuzz ...`: exit code 0 if no target crashed, 1 if one did, 2 on usage errors.
pub fn run(root: &Path, args: &[String]) -> ExitCode {
    let o = match parse(args) {
        Ok(Some(o)) => o,
        Ok(None) => {
            println!("{USAGE}");
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            eprintln!("error: {e}\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    let mut rows = Vec::new();
    for t in &o.targets {
        match fuzz_one(root, t, &o) {
            Ok(r) => rows.push((t.clone(), r)),
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::from(2);
            }
        }
    }
    println!();
    println!("| target | time (s) | runs | runs/s | corpus | result |");
    println!("|---|---:|---:|---:|---|---|");
    let mut crashed = false;
    for (t, r) in &rows {
        crashed |= r.crashed;
        let runs = r.runs.map_or("?".into(), |n| n.to_string());
        let rate = r.runs.map_or("?".into(), |n| {
            format!("{:.0}", n as f64 / r.seconds.max(1e-9))
        });
        let result = if r.crashed {
            format!(
                "CRASH {}{}",
                r.artifact
                    .as_deref()
                    .unwrap_or("(no artifact: see the log)"),
                r.first_panic
                    .as_deref()
                    .map(|p| format!(" — {p}"))
                    .unwrap_or_default()
            )
        } else {
            "ok".to_string()
        };
        println!(
            "| {t} | {:.0} | {runs} | {rate} | {} | {result} |",
            r.seconds,
            r.corpus.as_deref().unwrap_or("?")
        );
    }
    println!(
        "\nlogs: {}",
        PathBuf::from("target/fuzz/<target>.log").display()
    );
    if crashed {
        eprintln!("fuzzing found a crash: add the input as a regression test (see fuzz/README.md)");
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_libfuzzer_output() {
        let mut r = Report::default();
        for l in [
            "#4096\tpulse  cov: 10 ft: 20 corp: 12/340b lim: 4096 exec/s: 2048 rss: 50Mb",
            "#8000\tDONE   cov: 11 ft: 21 corp: 13/350b lim: 4096 exec/s: 4000 rss: 50Mb",
            "Done 8000 runs in 2 second(s)",
            "stat::number_of_executed_units: 8001",
        ] {
            scan(l, &mut r);
        }
        assert_eq!(r.runs, Some(8001));
        assert_eq!(r.corpus.as_deref(), Some("13/350b"));
        assert!(!r.crashed);
        scan(
            "thread '<unnamed>' panicked at fuzz_targets/x.rs:3:5:",
            &mut r,
        );
        scan("==1== ERROR: libFuzzer: deadly signal", &mut r);
        scan(
            "artifact_prefix='a/'; Test unit written to fuzz/artifacts/x/crash-abc",
            &mut r,
        );
        assert!(r.crashed);
        assert_eq!(r.artifact.as_deref(), Some("fuzz/artifacts/x/crash-abc"));
        assert!(r.first_panic.unwrap().contains("x.rs:3:5"));
    }

    #[test]
    fn parses_arguments() {
        let a = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        let o = parse(&a(&["--seconds", "5", "--target", "robot_file"]))
            .unwrap()
            .unwrap();
        assert_eq!((o.seconds, o.targets.len()), (5, 1));
        assert_eq!(
            parse(&a(&[])).unwrap().unwrap().targets.len(),
            TARGETS.len()
        );
        assert!(parse(&a(&["--target", "nope"])).is_err());
        assert!(parse(&a(&["--seconds"])).is_err());
        assert!(parse(&a(&["--help"])).unwrap().is_none());
    }
}
