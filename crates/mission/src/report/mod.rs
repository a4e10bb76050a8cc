//! Reports of a mission's models and flights (summaries, reference comparisons).
pub mod environment;
pub mod flight;
pub mod motor;
pub mod openrocket;
pub mod rocket;
