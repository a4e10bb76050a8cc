//! Integration tests of karman-airframe (one binary; one module per topic).

mod calisto;
mod common;
mod dimensions;
mod drag_openrocket;
mod robustness;
mod rocketpy_surfaces;
