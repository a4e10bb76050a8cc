//! Integration tests of karman-propulsion (one binary, one module per topic).

mod dimensions;
mod motors;
mod parsers;
mod tanks;
mod thrust_files;
mod validate_calisto;
