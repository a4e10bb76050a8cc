//! Test helpers: where the project's shared weather data is; the netCDF classic writer of
//! small synthetic weather grids is `karman_validation::netcdf` (shared with the CLI tests).

pub use karman_validation::netcdf::{Var, classic_nc, classic_nc_numeric};

use std::path::PathBuf;

/// `<workspace>/../shared`, the project's shared data beside the repository (its
/// `data/weather` soundings are not part of the repository), or `None` when absent.
pub fn shared_dir() -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared");
    dir.join("data/weather").is_dir().then_some(dir)
}
