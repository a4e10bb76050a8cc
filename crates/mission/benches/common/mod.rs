//! What the benches share: where the validation missions are.

use std::path::PathBuf;

/// `../shared/validation/<flight>/mission.toml` beside the workspace, or
/// `$KARMAN_VALIDATION_DATA/<flight>/mission.toml`; `None` when it is absent.
pub fn validation_mission(flight: &str) -> Option<PathBuf> {
    let dir = std::env::var_os("KARMAN_VALIDATION_DATA").map_or_else(
        || PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/validation"),
        PathBuf::from,
    );
    let path = dir.join(flight).join("mission.toml");
    path.is_file().then_some(path)
}

/// The Calisto validation mission ([`validation_mission`]).
pub fn calisto() -> Option<PathBuf> {
    validation_mission("calisto")
}
