//! Reports of a mission's models and flights (summaries, reference comparisons, the
//! trajectory's series, CSV and KML).
pub mod environment;
pub mod flight;
pub mod motor;
pub mod openrocket;
pub mod rocket;
pub mod trajectory;
