//! Building the physics models (environment, motor, rocket) from a validated mission.
pub mod drag;
pub mod environment;
pub mod flight;
pub mod motor;
pub mod motors;
pub mod preflight;
pub mod rocket;
pub mod scripts;
pub mod sensors;
pub mod stage_view;
pub mod stages;
