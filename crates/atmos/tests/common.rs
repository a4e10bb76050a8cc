//! Test helpers: where the project's shared weather data is; the netCDF classic writer of
//! small synthetic weather grids is `karman_validation::netcdf` (shared with the CLI tests).

pub use karman_validation::netcdf::{Var, classic_nc, classic_nc_numeric};

use std::path::PathBuf;

/// `<workspace>/../shared`, the project's shared data beside the repository (its
/// `data/weather` soundings are not part of the repository), or `None` when absent, after a
/// line on stderr naming the test that did not run. With `CI` set an absent folder fails the
/// test instead: CI has the shared data, and a test that did not run must not pass there.
pub fn shared_dir(test: &str) -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared");
    if dir.join("data/weather").is_dir() {
        return Some(dir);
    }
    assert!(
        !karman_validation::in_ci(),
        "{test}: {} not found (CI is set: the shared data must be there)",
        dir.join("data/weather").display()
    );
    eprintln!("SKIPPED {test}: no {}", dir.join("data/weather").display());
    None
}
