//! Helpers shared by the test modules: where the validation missions and the test fixtures
//! are.

use std::path::{Path, PathBuf};

/// The validation folder (`KARMAN_VALIDATION_DATA`, else `<workspace>/../shared/validation`),
/// or `None` when it is absent (the caller prints that it skipped).
pub fn validation_dir() -> Option<PathBuf> {
    let dir = match std::env::var_os("KARMAN_VALIDATION_DATA") {
        Some(dir) => PathBuf::from(dir),
        None => PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/validation"),
    };
    dir.is_dir().then_some(dir)
}

/// Every `*/mission.toml` of the validation folder, sorted.
pub fn validation_missions() -> Option<Vec<PathBuf>> {
    let dir = validation_dir()?;
    let mut missions: Vec<PathBuf> = std::fs::read_dir(&dir)
        .ok()?
        .filter_map(Result::ok)
        .map(|entry| entry.path().join("mission.toml"))
        .filter(|path| path.is_file())
        .collect();
    missions.sort();
    Some(missions)
}

/// A file of `tests/fixtures`.
pub fn fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name)
}

/// The flight name of a validation mission: its folder's name.
pub fn flight_name(mission: &Path) -> String {
    mission.parent().and_then(Path::file_name).map_or_else(
        || mission.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

/// The RocketPy 1.13 `reference.json` beside a validation mission.
pub fn load_reference(mission: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(mission.with_file_name("reference.json"))
        .unwrap_or_else(|e| panic!("{}: reference.json: {e}", mission.display()));
    serde_json::from_str(&text)
        .unwrap_or_else(|e| panic!("{}: reference.json: {e}", mission.display()))
}
