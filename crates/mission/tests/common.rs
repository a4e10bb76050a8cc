//! Helpers shared by the test modules: where the validation missions and the test fixtures
//! are.

use std::path::{Path, PathBuf};

/// The validation folder ([`karman_validation::folder`]: `fixtures/validation` unless
/// `KARMAN_VALIDATION_DATA` names another), or `None` when it is unavailable outside CI.
pub fn validation_dir() -> Option<PathBuf> {
    karman_validation::folder().map(|f| f.dir)
}

/// The `mission.toml` of every validation flight flown (the pending ones skipped by name),
/// sorted.
pub fn validation_missions() -> Option<Vec<PathBuf>> {
    karman_validation::folder().map(|f| f.missions())
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

/// The Calisto validation mission's file, or `None` when the validation folder is absent.
pub fn calisto_path() -> Option<PathBuf> {
    Some(validation_dir()?.join("calisto/mission.toml"))
}

/// The Calisto validation mission with `--set` overrides, or `None` when the validation folder
/// is absent.
pub fn calisto_with(overrides: &[(&str, &str)]) -> Option<karman_mission::Mission> {
    let items: Vec<karman_mission::Override> = overrides
        .iter()
        .map(|(p, v)| karman_mission::Override::new(p, v).expect("override parses"))
        .collect();
    Some(karman_mission::load(&calisto_path()?, &items).expect("Calisto loads with overrides"))
}

/// An error and its sources, `: `-separated, as every consumer prints it.
pub fn chain(error: &dyn std::error::Error) -> String {
    let mut text = error.to_string();
    let mut source = error.source();
    while let Some(cause) = source {
        text.push_str(": ");
        text.push_str(&cause.to_string());
        source = cause.source();
    }
    text
}

/// Every stored point of a flight, its time and state, as bits (equal flights, equal bits).
pub fn point_bits(run: &karman_mission::assemble::flight::FlightRun) -> Vec<u64> {
    run.flight
        .points
        .iter()
        .flat_map(|p| std::iter::once(p.t).chain(p.state))
        .map(f64::to_bits)
        .collect()
}
