//! Integration tests of karman-dispersion (one binary; a module per topic).

mod common;
mod convergence;
mod determinism;
mod distributions;
mod ellipses;
mod integrity;
mod lock;
mod never_panics;
mod resume;
mod sigkill;
mod sobol;
mod window;
