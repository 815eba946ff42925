//! The checked-in JSON Schemas (docs/schema/) are the code's: `cargo xtask schema` rewrites them.

use std::path::Path;

#[test]
fn checked_in_schemas_match_the_code() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/schema");
    // `CDPR_WRITE_SCHEMAS=1 cargo test -p cdpr-api --test schema` writes them, as `cargo xtask
    // schema` does, without building the xtask.
    let write = std::env::var_os("CDPR_WRITE_SCHEMAS").is_some();
    let mut stale = Vec::new();
    for (name, text) in cdpr_api::schema::schema_files() {
        let path = dir.join(&name);
        if write {
            std::fs::create_dir_all(&dir).unwrap();
            std::fs::write(&path, &text).unwrap();
        }
        if std::fs::read_to_string(&path).ok().as_deref() != Some(text.as_str()) {
            stale.push(name);
        }
    }
    assert!(
        stale.is_empty(),
        "docs/schema is stale for {stale:?}: run `cargo xtask schema` and commit the files"
    );
}
