//! The error type of karman-dynamics.

use thiserror::Error;

/// Errors raised while setting up or flying a trajectory.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum DynamicsError {
    /// The state or its derivative became NaN or infinite (a bad input curve, or a
    /// physically impossible configuration such as a zero mass).
    #[error("the state or its derivative is not finite at t = {t} s")]
    NonFinite {
        /// Time of the failure, s.
        t: f64,
    },
    /// The adaptive step fell below the minimum step (a stiff or unstable configuration).
    #[error("step size {step:e} s fell below the minimum at t = {t} s")]
    StepTooSmall {
        /// Time of the failure, s.
        t: f64,
        /// The step the controller asked for, s.
        step: f64,
    },
    /// The integrator exceeded its step budget in one flight phase.
    #[error("more than {steps} integration steps in one flight phase (at t = {t} s)")]
    TooManySteps {
        /// Time when the budget ran out, s.
        t: f64,
        /// Steps taken (accepted and rejected).
        steps: usize,
    },
    /// A flight setting is outside its valid range.
    #[error("invalid flight setting `{name}` = {value}: {reason}")]
    InvalidSetting {
        /// The setting's name (as in the mission's `[flight]` table).
        name: &'static str,
        /// The offending value.
        value: f64,
        /// What is expected.
        reason: &'static str,
    },
    /// An event root (rail exit, impact) could not be located inside its step.
    #[error("could not locate the {event} event inside the step [{t0}, {t1}] s")]
    EventRoot {
        /// The event's name.
        event: &'static str,
        /// Start of the step, s.
        t0: f64,
        /// End of the step, s.
        t1: f64,
    },
    /// Two outputs of the flight's sampled processes share a name.
    #[error("two sampled processes publish a signal named `{name}`")]
    DuplicateSignal {
        /// The name.
        name: String,
    },
    /// A sampled process asked for a signal or a control channel nobody provides.
    #[error("no {kind} named `{name}` in this flight")]
    Unconnected {
        /// What was asked for: "signal", "control channel".
        kind: &'static str,
        /// Its name.
        name: String,
    },
}
