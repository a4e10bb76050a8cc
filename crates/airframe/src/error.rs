//! The error type of karman-airframe.

use karman_math::MathError;
use thiserror::Error;

/// Errors raised while building a [`crate::Rocket`] from its inputs.
///
/// Every variant names the component (`"rocket"`, a surface or parachute name, `"motor"`,
/// `"rail_buttons"`), the offending quantity and its value, so that the mission layer can
/// point at the right table of the user's file.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum AirframeError {
    /// A quantity is NaN or infinite.
    #[error("{component}: {quantity} = {value} is not a finite number")]
    NotFinite {
        /// Component holding the quantity.
        component: String,
        /// Name of the quantity.
        quantity: &'static str,
        /// The offending value.
        value: f64,
    },
    /// A quantity that must be strictly positive is zero or negative.
    #[error("{component}: {quantity} = {value} must be greater than zero")]
    NotPositive {
        /// Component holding the quantity.
        component: String,
        /// Name of the quantity.
        quantity: &'static str,
        /// The offending value.
        value: f64,
    },
    /// A quantity that must not be negative is negative.
    #[error("{component}: {quantity} = {value} must not be negative")]
    Negative {
        /// Component holding the quantity.
        component: String,
        /// Name of the quantity.
        quantity: &'static str,
        /// The offending value.
        value: f64,
    },
    /// A quantity lies outside its admissible range.
    #[error("{component}: {quantity} = {value} is outside [{min}, {max}]")]
    OutOfRange {
        /// Component holding the quantity.
        component: String,
        /// Name of the quantity.
        quantity: &'static str,
        /// The offending value.
        value: f64,
        /// Smallest admissible value.
        min: f64,
        /// Largest admissible value.
        max: f64,
    },
    /// The geometry of a component cannot be built (explained in `reason`).
    #[error("{component}: impossible geometry: {reason}")]
    Geometry {
        /// Component with the impossible geometry.
        component: String,
        /// What is wrong.
        reason: String,
    },
    /// The inertia tensor does not have 3 or 6 components.
    #[error("{component}: inertia must have 3 or 6 components, got {got}")]
    InertiaComponents {
        /// Component holding the inertia.
        component: String,
        /// Number of components given.
        got: usize,
    },
    /// A table derived from the inputs could not be built.
    #[error("{component}: cannot tabulate {quantity}: {error}")]
    Table {
        /// Component the table belongs to.
        component: String,
        /// The tabulated quantity.
        quantity: &'static str,
        /// The underlying table error (in the message, not a source of its own: a chain
        /// printed whole would say it twice).
        error: MathError,
    },
}

/// Checks that `value` is finite.
pub(crate) fn finite(
    component: &str,
    quantity: &'static str,
    value: f64,
) -> Result<f64, AirframeError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(AirframeError::NotFinite {
            component: component.to_owned(),
            quantity,
            value,
        })
    }
}

/// Checks that `value` is finite and strictly positive.
pub(crate) fn positive(
    component: &str,
    quantity: &'static str,
    value: f64,
) -> Result<f64, AirframeError> {
    finite(component, quantity, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(AirframeError::NotPositive {
            component: component.to_owned(),
            quantity,
            value,
        })
    }
}

/// Checks that `value` is finite and not negative.
pub(crate) fn non_negative(
    component: &str,
    quantity: &'static str,
    value: f64,
) -> Result<f64, AirframeError> {
    finite(component, quantity, value)?;
    if value >= 0.0 {
        Ok(value)
    } else {
        Err(AirframeError::Negative {
            component: component.to_owned(),
            quantity,
            value,
        })
    }
}
