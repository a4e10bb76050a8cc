//! Integration tests of karman-script, one module per topic.

mod compiled;
mod controllers;
mod expressions;
mod hostile;
