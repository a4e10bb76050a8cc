//! Integration tests of karman-script, one module per topic.

mod controllers;
mod expressions;
