//! Why a fit cannot be made or written.

use karman_mission::MissionError;

/// An error of [`crate::fit`] or [`crate::write_fitted`].
#[derive(Debug, thiserror::Error)]
pub enum FitError {
    /// The mission could not be prepared for the fit (an unknown input path, a distribution
    /// that does not fit its input, a model that cannot be built).
    #[error(transparent)]
    Mission(#[from] MissionError),
    /// The inputs asked for cannot be fitted.
    #[error("cannot fit `{input}`: {reason}")]
    Input {
        /// The dotted input path.
        input: String,
        /// Why.
        reason: String,
    },
    /// No input to fit, or the same one twice.
    #[error("{0}")]
    Usage(String),
    /// A flight of the fit failed.
    #[error("a flight of the fit failed: {0}")]
    Flight(String),
    /// The log and the simulation cannot be compared.
    #[error(transparent)]
    Compare(#[from] karman_flightlog::CompareError),
    /// The log has too few samples in the phase an input acts on.
    #[error("the log has {samples} sample(s) in the {phase}; the fit needs at least {needed}")]
    TooFewSamples {
        /// The phase (`ascent`, `descent under Main`).
        phase: String,
        /// Its samples.
        samples: usize,
        /// The fewest it needs.
        needed: usize,
    },
    /// The fitted copy of the mission cannot be written.
    #[error("{file}: cannot write the fitted mission: {reason}")]
    Write {
        /// The mission file read or the file written.
        file: String,
        /// Why.
        reason: String,
    },
}
