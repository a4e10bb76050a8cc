//! The error type of karman-math.

use thiserror::Error;

/// Errors raised when building or evaluating functions from data.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum MathError {
    /// A table needs at least `needed` points.
    #[error("a table needs at least {needed} point(s), got {got}")]
    TooFewPoints {
        /// Minimum number of points for the requested interpolation.
        needed: usize,
        /// Number of points given.
        got: usize,
    },
    /// The x and y columns have different lengths.
    #[error("x has {x} values but y has {y}")]
    LengthMismatch {
        /// Length of the x column.
        x: usize,
        /// Length of the y column.
        y: usize,
    },
    /// A value is NaN or infinite.
    #[error("point {index}: value {value} is not finite")]
    NotFinite {
        /// Zero-based index of the point.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// The abscissae are not strictly increasing.
    #[error("point {index}: x = {x} does not increase (previous x = {previous})")]
    NotIncreasing {
        /// Zero-based index of the point.
        index: usize,
        /// The offending abscissa.
        x: f64,
        /// The abscissa before it.
        previous: f64,
    },
}
