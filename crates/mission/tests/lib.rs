//! Integration tests of karman-mission (one binary; one module per topic).

mod allocation;
mod broken;
mod common;
mod dimensions_flight;
mod distributions;
mod drag_estimate;
mod examples;
mod extra_motors;
mod fingerprint;
mod fuzz;
mod load;
mod openrocket;
mod ork;
mod overrides;
mod paths;
mod scripts;
mod sensor_readers;
mod sensors;
mod stages;
mod tanks;
mod validate_environment;
mod validate_flight;
mod validate_motor;
mod validate_rocket;
mod validate_three_dof;
