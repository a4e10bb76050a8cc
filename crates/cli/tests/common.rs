//! Helpers shared by the CLI tests: running the binary, scratch files, data folders.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub fn karman(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_karman"))
        .args(args)
        .output()
        .expect("the karman binary runs")
}

pub fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// Asserts a failed run: exit code 1, no panic, and returns stderr.
pub fn failure(args: &[&str]) -> String {
    let output = karman(args);
    let text = stderr(&output);
    assert!(!text.contains("panicked at"), "panic: {text}");
    assert_eq!(output.status.code(), Some(1), "stderr: {text}");
    text
}

/// The validation flights flown ([`karman_validation::Folder::flown`]), or `None` when the
/// folder is unavailable outside CI.
pub fn validation_flights() -> Option<Vec<karman_validation::Flight>> {
    karman_validation::folder().map(|f| f.flown())
}

/// The repository's example mission (fixtures/example.toml).
pub fn example() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/example.toml")
}

/// Writes `bytes` to a file named `name` in this test binary's scratch folder.
pub fn scratch(name: &str, bytes: &[u8]) -> PathBuf {
    let path = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("karman-cli")
        .join(name);
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).expect("scratch folder");
    }
    std::fs::write(&path, bytes).expect("scratch file");
    path
}
