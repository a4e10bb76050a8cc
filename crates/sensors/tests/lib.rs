//! The integration tests of karman-sensors.

mod noise;
