//! Integration tests of karman-dynamics (one binary, one module per topic).

mod mock;
mod point_mass;
mod processes;
mod robustness;
mod seams;
mod toy_flights;
