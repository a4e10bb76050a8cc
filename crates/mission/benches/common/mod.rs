//! What the benches share: where the Calisto validation mission is.

use std::path::PathBuf;

/// `../shared/validation/calisto/mission.toml` beside the workspace, or
/// `$KARMAN_VALIDATION_DATA/calisto/mission.toml`; `None` when it is absent.
pub fn calisto() -> Option<PathBuf> {
    let dir = std::env::var_os("KARMAN_VALIDATION_DATA").map_or_else(
        || PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/validation"),
        PathBuf::from,
    );
    let path = dir.join("calisto/mission.toml");
    path.is_file().then_some(path)
}
