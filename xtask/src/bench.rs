//! # `cargo xtask bench`
//!
//! Runs the criterion suite (`cargo bench -p cdpr-benches --bench '*'`), reads every benchmark's
//! median from `target/criterion/**/new/{benchmark,estimates}.json` and prints a table:
//! benchmark, median per iteration, median per operation, the performance target from the
//! issues, pass/miss. The same table goes to `target/bench/summary.md`.
//!
//! Benchmarks that time a batch declare `Throughput::Elements(k)`: their per-operation median is
//! the iteration median / k. Each target says whether it is per operation (one pose, one
//! tension solve) or per iteration (a whole workspace grid, a whole trajectory), see
//! [`TARGETS`]. Benchmarks without a target print "—".

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};
use std::time::SystemTime;

/// What a target's time refers to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Per {
    /// One criterion iteration (e.g. a whole 50 × 50 grid).
    Iteration,
    /// One element of the iteration's `Throughput::Elements` (e.g. one pose).
    Element,
}

/// A performance target from the issues: benchmark id (criterion `full_id`), limit in seconds,
/// what the limit applies to, and how the issue states it.
pub struct Target {
    /// Criterion `group/function` id.
    pub id: &'static str,
    /// Upper limit in seconds.
    pub limit: f64,
    /// Per operation or per iteration.
    pub per: Per,
    /// The issue's wording.
    pub what: &'static str,
}

const NS: f64 = 1e-9;
const US: f64 = 1e-6;
const MS: f64 = 1e-3;

/// Benchmark ids → targets (issues 1–6, 27–29). Ids not listed have no target.
pub const TARGETS: &[Target] = &[
    Target {
        id: "kinematics/ik_and_wrench_matrix/spatial_8",
        limit: 100.0 * NS,
        per: Per::Iteration,
        what: "IK + W, 8 cables",
    },
    Target {
        id: "tension_8_cable/l2",
        limit: 2.0 * US,
        per: Per::Element,
        what: "8-cable l2",
    },
    Target {
        id: "tension_8_cable/l1",
        limit: 3.0 * US,
        per: Per::Element,
        what: "8-cable l1",
    },
    Target {
        id: "tension_8_cable/barycenter",
        limit: 5.0 * US,
        per: Per::Element,
        what: "8-cable barycenter",
    },
    Target {
        id: "tension_8_cable/sotda_corners",
        limit: 20.0 * US,
        per: Per::Element,
        what: "8-cable sotda corners",
    },
    Target {
        id: "tension_8_cable/improved_closed_form",
        limit: 2.0 * US,
        per: Per::Element,
        what: "8-cable improved closed form",
    },
    Target {
        id: "tension_planar_4_cable/closed_form",
        limit: 100.0 * NS,
        per: Per::Element,
        what: "planar 4-cable closed form",
    },
    Target {
        id: "capacity_margin/hyperplane_shifting_8_spatial",
        limit: 10.0 * US,
        per: Per::Iteration,
        what: "capacity margin, 8 cables",
    },
    Target {
        id: "isotropic_force/seed001_point2",
        limit: 200.0 * NS,
        per: Per::Iteration,
        what: "isotropic force, 3 motors",
    },
    Target {
        id: "discretisation/three_cable_m50",
        limit: 0.3 * MS,
        per: Per::Iteration,
        what: "3-cable workspace, m = 50",
    },
    Target {
        id: "discretisation/four_cable_m50_l2",
        limit: 3.0 * MS,
        per: Per::Iteration,
        what: "4-cable workspace, m = 50, l2",
    },
    Target {
        id: "chord/four_cable_l2_d0.05",
        limit: 5.0 * MS,
        per: Per::Iteration,
        what: "chord, 4 cables, l2",
    },
    Target {
        id: "spatial_grid/eight_cable_wrench_closure_15625",
        limit: 30.0 * MS,
        per: Per::Iteration,
        what: "8-cable grid, wrench closure (issue: 14 823 poses; here 15 625)",
    },
    Target {
        id: "spatial_grid/eight_cable_l2_15625",
        limit: 30.0 * MS,
        per: Per::Iteration,
        what: "8-cable grid, l2 (issue: 14 823 poses; here 15 625)",
    },
    Target {
        id: "trajectory_8_cable_1000_samples/sotda",
        limit: 20.0 * MS,
        per: Per::Iteration,
        what: "1000-sample sotda trajectory",
    },
    Target {
        id: "calibration/self_calibration_8_spatial_40_samples",
        limit: 50.0 * MS,
        per: Per::Iteration,
        what: "self-calibration, 8 cables, 40 samples",
    },
    Target {
        id: "kinematics/fk_8_spatial_noisy",
        limit: 5.0 * US,
        per: Per::Iteration,
        what: "FK on noisy lengths, 8 cables",
    },
    Target {
        id: "inverse_dynamics/l2_10000_samples",
        limit: 10.0 * MS,
        per: Per::Iteration,
        what: "inverse dynamics, l2, 10 000 samples",
    },
    Target {
        id: "forward_dynamics/rk4_tension_driven",
        limit: 2.0 * US,
        per: Per::Element,
        what: "RK4 step, tension-driven (≥ 500 000 steps/s)",
    },
    Target {
        id: "dynamic_grid/eight_cable_15625",
        limit: 50.0 * MS,
        per: Per::Iteration,
        what: "dynamic-feasible grid, 15 625 poses, 2 cores",
    },
    Target {
        id: "elastic_catenary/solve_for_tension",
        limit: 1.0 * US,
        per: Per::Element,
        what: "one catenary solve (span, tension → L0)",
    },
    Target {
        id: "sagging_statics/l2_spatial_8",
        limit: 20.0 * US,
        per: Per::Element,
        what: "l2 statics with sagging cables, 8 cables",
    },
    Target {
        id: "elasto_geometric_forward/elastic_spatial_8",
        limit: 10.0 * US,
        per: Per::Element,
        what: "elastic forward kinematics, 8 cables",
    },
];

/// The target of a benchmark id, if the issues set one.
pub fn target_of(id: &str) -> Option<&'static Target> {
    TARGETS.iter().find(|t| t.id == id)
}

const USAGE: &str = "usage: cargo xtask bench [--quick] [--no-run] [FILTER]

Runs the criterion benchmarks of `benches/` (cargo bench -p cdpr-benches --bench '*') and prints
benchmark, median, the target from the issues and pass/miss; also written to
target/bench/summary.md.
  --quick   shorter runs: --warm-up-time 1 --measurement-time 2
  --no-run  do not run criterion; summarise the results already in target/criterion
  FILTER    only benchmarks whose id contains FILTER (criterion's filter)";

/// One benchmark's result.
#[derive(Debug, Clone, PartialEq)]
pub struct Measurement {
    /// Criterion `full_id`.
    pub id: String,
    /// Median time of one iteration (s).
    pub median: f64,
    /// Elements per iteration (`Throughput::Elements`), if declared.
    pub elements: Option<u64>,
    /// When the estimate was written.
    pub modified: Option<SystemTime>,
}

impl Measurement {
    /// The median per element (per iteration if no throughput is declared).
    pub fn per_element(&self) -> f64 {
        self.median / self.elements.unwrap_or(1).max(1) as f64
    }
}

/// Formats seconds with a unit (ns, µs, ms, s), three significant digits.
pub fn human(s: f64) -> String {
    let (v, unit) = if s < 1e-6 {
        (s * 1e9, "ns")
    } else if s < 1e-3 {
        (s * 1e6, "µs")
    } else if s < 1.0 {
        (s * 1e3, "ms")
    } else {
        (s, "s")
    };
    if v >= 100.0 {
        format!("{v:.0} {unit}")
    } else if v >= 10.0 {
        format!("{v:.1} {unit}")
    } else {
        format!("{v:.2} {unit}")
    }
}

/// Parses one criterion result directory (`…/new/` with benchmark.json and estimates.json).
fn read_measurement(new_dir: &Path) -> Option<Measurement> {
    let bench: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(new_dir.join("benchmark.json")).ok()?)
            .ok()?;
    let est_path = new_dir.join("estimates.json");
    let est: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&est_path).ok()?).ok()?;
    let id = bench.get("full_id")?.as_str()?.to_string();
    let median_ns = est.get("median")?.get("point_estimate")?.as_f64()?;
    let elements = bench
        .get("throughput")
        .and_then(|t| t.get("Elements"))
        .and_then(|e| e.as_u64());
    let modified = std::fs::metadata(&est_path).and_then(|m| m.modified()).ok();
    Some(Measurement {
        id,
        median: median_ns * 1e-9,
        elements,
        modified,
    })
}

/// Every measurement under `criterion_dir` (recursively, the `new/` directories), sorted by id.
pub fn collect(criterion_dir: &Path) -> Vec<Measurement> {
    fn walk(dir: &Path, out: &mut Vec<Measurement>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for e in entries.flatten() {
            let p = e.path();
            if !p.is_dir() {
                continue;
            }
            if p.file_name().is_some_and(|n| n == "new") {
                if let Some(m) = read_measurement(&p) {
                    out.push(m);
                }
            } else if p.file_name().is_none_or(|n| n != "report") {
                walk(&p, out);
            }
        }
    }
    let mut out = Vec::new();
    walk(criterion_dir, &mut out);
    out.sort_by(|a, b| a.id.cmp(&b.id));
    out.dedup_by(|a, b| a.id == b.id);
    out
}

/// The markdown table of `measurements` against [`TARGETS`]; also returns the number of misses.
pub fn table(measurements: &[Measurement]) -> (String, usize) {
    let mut s = String::new();
    let mut misses = 0;
    s.push_str("| benchmark | median / iter | per op | target | result |\n");
    s.push_str("|---|---:|---:|---|---|\n");
    for m in measurements {
        let per_op = match m.elements {
            Some(k) => format!("{} (÷{k})", human(m.per_element())),
            None => "=".to_string(),
        };
        let (target, result) = match target_of(&m.id) {
            None => ("—".to_string(), "—".to_string()),
            Some(t) => {
                let value = match t.per {
                    Per::Element => m.per_element(),
                    Per::Iteration => m.median,
                };
                let per = match t.per {
                    Per::Element => "/op",
                    Per::Iteration => "",
                };
                let pass = value <= t.limit;
                misses += usize::from(!pass);
                (
                    format!("≤ {}{per} ({})", human(t.limit), t.what),
                    if pass { "pass" } else { "MISS" }.to_string(),
                )
            }
        };
        let _ = writeln!(
            s,
            "| {} | {} | {per_op} | {target} | {result} |",
            m.id,
            human(m.median)
        );
    }
    let missing: Vec<&str> = TARGETS
        .iter()
        .filter(|t| !measurements.iter().any(|m| m.id == t.id))
        .map(|t| t.id)
        .collect();
    if !missing.is_empty() {
        let _ = writeln!(
            s,
            "\nTargets without a measurement in this run: {}",
            missing.join(", ")
        );
    }
    (s, misses)
}

/// `cargo xtask bench ...`: exit 0 when criterion ran (misses are reported, not fatal).
pub fn run(root: &Path, args: &[String]) -> ExitCode {
    let (mut quick, mut no_run, mut filter) = (false, false, None::<String>);
    for a in args {
        match a.as_str() {
            "--quick" => quick = true,
            "--no-run" => no_run = true,
            "-h" | "--help" => {
                println!("{USAGE}");
                return ExitCode::SUCCESS;
            }
            s if !s.starts_with('-') && filter.is_none() => filter = Some(s.to_string()),
            other => {
                eprintln!("error: unknown argument `{other}`\n{USAGE}");
                return ExitCode::from(2);
            }
        }
    }
    let criterion_dir = root.join("target").join("criterion");
    let started = SystemTime::now();
    if !no_run {
        let mut cmd = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()));
        cmd.current_dir(root)
            .args(["bench", "-p", "cdpr-benches", "--bench", "*", "--"]);
        if quick {
            cmd.args(["--warm-up-time", "1", "--measurement-time", "2"]);
        }
        if let Some(f) = &filter {
            cmd.arg(f);
        }
        eprintln!("running: {cmd:?}");
        match cmd.status() {
            Ok(s) if s.success() => {}
            Ok(s) => {
                eprintln!("error: cargo bench failed ({s})");
                return ExitCode::FAILURE;
            }
            Err(e) => {
                eprintln!("error: cannot run cargo bench: {e}");
                return ExitCode::FAILURE;
            }
        }
    }
    let mut ms = collect(&criterion_dir);
    if !no_run {
        // Only what this run measured (older results may linger in target/criterion).
        ms.retain(|m| m.modified.is_none_or(|t| t >= started));
    }
    if let Some(f) = &filter {
        ms.retain(|m| m.id.contains(f.as_str()));
    }
    if ms.is_empty() {
        eprintln!(
            "error: no criterion results found in {}",
            criterion_dir.display()
        );
        return ExitCode::FAILURE;
    }
    let (t, misses) = table(&ms);
    println!("{t}");
    let with_target = ms.iter().filter(|m| target_of(&m.id).is_some()).count();
    println!(
        "{} benchmarks, {with_target} with a target: {} pass, {misses} miss",
        ms.len(),
        with_target - misses
    );
    let out: PathBuf = root.join("target").join("bench");
    let summary = out.join("summary.md");
    let text = format!(
        "# Benchmark summary\n\n`cargo xtask bench{}`; medians from criterion.\n\n{t}\n{} benchmarks, {with_target} with a target: {} pass, {misses} miss\n",
        if quick { " --quick" } else { "" },
        ms.len(),
        with_target - misses
    );
    if let Err(e) = std::fs::create_dir_all(&out).and_then(|_| std::fs::write(&summary, text)) {
        eprintln!("error: cannot write {}: {e}", summary.display());
        return ExitCode::FAILURE;
    }
    println!("written: {}", summary.display());
    ExitCode::SUCCESS
}

#[cfg(test)]
mod tests {
    use super::*;

    fn m(id: &str, median: f64, elements: Option<u64>) -> Measurement {
        Measurement {
            id: id.into(),
            median,
            elements,
            modified: None,
        }
    }

    #[test]
    fn per_element_and_per_iteration_targets() {
        // 1000 l2 solves in 1.5 ms: 1.5 µs each ≤ 2 µs.
        let (t, misses) = table(&[
            m("tension_8_cable/l2", 1.5e-3, Some(1000)),
            // The whole 1000-sample trajectory against 20 ms: 25 ms misses.
            m("trajectory_8_cable_1000_samples/sotda", 25e-3, Some(1000)),
            m("something/else", 1.0, None),
        ]);
        assert_eq!(misses, 1, "{t}");
        assert!(t.contains("| tension_8_cable/l2 | 1.50 ms | 1.50 µs (÷1000) | ≤ 2.00 µs/op"));
        assert!(t.contains("| trajectory_8_cable_1000_samples/sotda | 25.0 ms |"));
        assert!(t.contains("| MISS |"));
        assert!(t.contains("| something/else | 1.00 s | = | — | — |"));
    }

    #[test]
    fn human_units() {
        assert_eq!(human(85e-9), "85.0 ns");
        assert_eq!(human(1.234e-6), "1.23 µs");
        assert_eq!(human(0.3e-3), "300 µs");
        assert_eq!(human(12.5e-3), "12.5 ms");
    }

    #[test]
    fn reads_criterion_files() {
        let dir = std::env::temp_dir().join(format!("xtask-bench-{}", std::process::id()));
        let new = dir.join("g").join("f").join("new");
        std::fs::create_dir_all(&new).unwrap();
        std::fs::write(
            new.join("benchmark.json"),
            r#"{"group_id":"g","function_id":"f","full_id":"g/f","throughput":{"Elements":10}}"#,
        )
        .unwrap();
        std::fs::write(
            new.join("estimates.json"),
            r#"{"median":{"point_estimate":2000.0,"standard_error":1.0}}"#,
        )
        .unwrap();
        let ms = collect(&dir);
        std::fs::remove_dir_all(&dir).unwrap();
        assert_eq!(ms.len(), 1);
        assert_eq!(ms[0].id, "g/f");
        assert!((ms[0].median - 2e-6).abs() < 1e-18);
        assert_eq!(ms[0].elements, Some(10));
        assert!((ms[0].per_element() - 2e-7).abs() < 1e-18);
    }
}
