//! What the benches share: where the Calisto validation mission is.

use std::path::PathBuf;

/// The `mission.toml` of the Calisto validation flight (`fixtures/validation/calisto`, or
/// `$KARMAN_VALIDATION_DATA/calisto`); `None` when it is absent.
pub fn calisto() -> Option<PathBuf> {
    Some(karman_validation::folder()?.flight("calisto")?.mission())
}
