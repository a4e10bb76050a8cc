//! Integration tests of karman-dynamics (one binary, one module per topic).

mod dimensions;
mod mock;
mod robustness;
mod toy_flights;
