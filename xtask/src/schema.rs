//! # `cargo xtask schema`: the JSON Schemas of the requests and reports
//!
//! Writes every schema of `cdpr-api` (one per request and per report, see
//! `cdpr_api::schema`) to `docs/schema/NAME.request.json` and `docs/schema/NAME.report.json`.
//! The test `checked_in_schemas_match_the_code` of `cdpr-api` fails when a checked-in file
//! differs from the code.
//!
//! ## References
//! - JSON Schema 2020-12, <https://json-schema.org/draft/2020-12>.

use std::path::Path;

/// Writes the schemas under `root/docs/schema/`.
pub fn run(root: &Path) -> Result<(), String> {
    let dir = root.join("docs/schema");
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let files = cdpr::api::schema::schema_files();
    for (name, text) in &files {
        let path = dir.join(name);
        std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    println!("wrote {} schemas to {}", files.len(), dir.display());
    Ok(())
}
