//! `cargo xtask reproduce`: regenerate the published results from the code alone.
//!
//! - [`conventions`]: settle what the thesis leaves open, by experiment;
//! - [`tables`]: Tables 6.5–6.10 (published designs re-evaluated, our optimiser re-run);
//! - [`report`]: docs/reproduction.md and target/reproduce/tables.json.
//!
//! - `figures`: the papers' figures into docs/figures/ (one module per area).

pub mod conventions;
mod figures;
pub mod published;
pub mod report;
pub mod tables;

use std::path::Path;
use std::time::Instant;

/// Runs every reproduction step and writes the outputs under `root` (the workspace root).
pub fn run(root: &Path) -> Result<(), String> {
    let clock = Instant::now();
    eprintln!("settling conventions on the published designs …");
    let conventions = conventions::Conventions::settle();
    let settle_time = clock.elapsed().as_secs_f64();
    eprintln!("  {settle_time:.1} s");
    eprintln!("Tables 6.5–6.10 …");
    let rows = tables::reproduce(&conventions);
    let tables_time = clock.elapsed().as_secs_f64();
    eprintln!("figures …");
    let figures = figures::run(root)?;
    // The reported time covers everything: conventions, tables and figures.
    let total = clock.elapsed().as_secs_f64();
    eprintln!("  figures took {:.1} s", total - tables_time);
    let out = root.join("target/reproduce");
    std::fs::create_dir_all(&out).map_err(|e| format!("creating {}: {e}", out.display()))?;
    let json = out.join("tables.json");
    std::fs::write(&json, report::json(&rows, &conventions, total, settle_time))
        .map_err(|e| format!("writing {}: {e}", json.display()))?;
    let md = root.join("docs/reproduction.md");
    let mut doc = report::markdown(&rows, &conventions);
    doc.push_str(&figures::markdown(&figures));
    std::fs::write(&md, doc).map_err(|e| format!("writing {}: {e}", md.display()))?;
    eprintln!("{}", report::summary(&rows));
    eprintln!(
        "wrote {} and {} in {total:.1} s (of which {settle_time:.1} s settling conventions)",
        md.display(),
        json.display()
    );
    Ok(())
}
