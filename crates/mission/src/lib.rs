//! # karman-mission
//!
//! The TOML mission format: parsing with located errors, validation, and building the
//! physical model from a mission.
