//! The docs are tests: every `console` block of README.md and docs/*.md is run and its output
//! compared (trycmd).
//!
//! A `$ cdpr …` line runs this build's `cdpr`; the lines after it, up to the next `$ ` or the
//! block's end, are its expected stdout and stderr (`...` on a line of its own elides lines,
//! `[..]` elides the rest of a line; `? failed` or `? 2` before them sets the exit code). Blocks
//! marked `console,ignore` are not run. The commands run in a scratch directory that links
//! `examples/` and `crates/` of the repository, so they read the shipped robots by the paths the
//! docs show and the files they write (plots, meshes) land in the scratch directory, never in
//! the tree.
//!
//! After a change of output: `TRYCMD=overwrite cargo test -p cdpr --test readme` rewrites the
//! outputs in the Markdown files; review the diff (`git diff README.md docs/`) before committing.

use std::path::{Path, PathBuf};

fn repository_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .expect("the repository root exists")
}

/// A scratch directory holding links to the repository's `examples/` and `crates/`, and the
/// `bad.toml` of docs/getting-started.md: `examples/robots/tdpm-4.toml` with a third number in
/// the third cable's `frame` (line 21).
fn scratch_directory(root: &Path) -> tempfile::TempDir {
    let scratch = tempfile::tempdir().expect("a scratch directory");
    for entry in ["examples", "crates"] {
        std::os::unix::fs::symlink(root.join(entry), scratch.path().join(entry))
            .expect("a link into the repository");
    }
    let good = std::fs::read_to_string(root.join("examples/robots/tdpm-4.toml"))
        .expect("the tdpm-4 example");
    let third_frame = "frame = [-1.0, -0.5]";
    assert_eq!(
        good.lines().nth(20),
        Some(third_frame),
        "line 21 of tdpm-4.toml moved"
    );
    let bad = good.replace(third_frame, "frame = [-1.0, -0.5, 0.0]");
    std::fs::write(scratch.path().join("bad.toml"), bad).expect("write bad.toml");
    scratch
}

#[test]
fn docs_are_tests() {
    let root = repository_root();
    let scratch = scratch_directory(&root);
    // This binary holds this one test, so changing the process's directory races with nothing.
    std::env::set_current_dir(scratch.path()).expect("enter the scratch directory");
    let cases = trycmd::TestCases::new();
    cases
        .register_bin("cdpr", Path::new(env!("CARGO_BIN_EXE_cdpr")))
        .case(root.join("README.md"))
        .case(root.join("docs/*.md"));
    cases.run();
}
