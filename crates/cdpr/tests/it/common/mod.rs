//! Helpers shared by the CLI test files: the example robots and the `cdpr` binary.
#![allow(dead_code)] // each test file uses its own subset

use assert_cmd::Command;
use std::path::PathBuf;

/// Path of an example robot file in `examples/robots/`.
pub fn robot(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/robots")
        .join(name)
        .display()
        .to_string()
}

/// The `cdpr` binary under test.
pub fn cdpr() -> Command {
    Command::cargo_bin("cdpr").unwrap()
}

/// Runs a command that must succeed and returns its JSON output.
pub fn json(args: &[&str]) -> serde_json::Value {
    let out = cdpr().args(args).output().unwrap();
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}
