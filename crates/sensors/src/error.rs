//! The errors of building a sensor.

/// A sensor parameter out of its domain.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SensorError {
    /// Parameter `name` has value `value`, which `reason` excludes.
    #[error("{name} = {value}: {reason}")]
    Parameter {
        /// The parameter (its mission-format key).
        name: &'static str,
        /// The value given.
        value: f64,
        /// What it must be.
        reason: &'static str,
    },
}
