//! Integration tests of karman-math, one binary with a module per topic.

mod allocation;
mod csv_reader;
mod dimensions;
mod functions;
mod grids;
mod interpolation;
mod quadrature;
mod validate;
