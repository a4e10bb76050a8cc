//! What the benches share: where the validation missions are.

use std::path::PathBuf;

/// The `mission.toml` of the validation flight `flight` (`fixtures/validation/<flight>`, or
/// `$KARMAN_VALIDATION_DATA/<flight>`); `None` when it is absent.
pub fn validation_mission(flight: &str) -> Option<PathBuf> {
    Some(karman_validation::folder()?.flight(flight)?.mission())
}

/// The Calisto validation mission ([`validation_mission`]).
pub fn calisto() -> Option<PathBuf> {
    validation_mission("calisto")
}
