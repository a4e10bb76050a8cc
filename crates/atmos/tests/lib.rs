//! Integration tests of karman-atmos (one binary; one module per topic).

mod common;
mod dimensions;
#[cfg(feature = "fetch")]
mod fetch;
mod grids;
mod parsers_never_panic;
mod soundings;
