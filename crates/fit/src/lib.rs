//! The values of a mission's inputs that make its simulation match a flight log best.
//!
//! [`fit`] takes a loaded mission, a flight log read by karman-flightlog and the dotted paths
//! of the inputs to fit (a drag curve, `motor.total_impulse`, a parachute's `cd_s`, the
//! mass: anything a Monte Carlo study can scale with `factor`, mission-format.md
//! `[dispersion]`), and finds the factors on their nominal values that minimise the weighted
//! sum of squared differences between the simulated flight and the log:
//!
//! - **Residuals.** An input acts on a phase of the flight and is fitted to that phase only.
//!   A parachute's inputs (`rocket.parachutes.NAME.*`) act on the descent under it: for each
//!   log sample after apogee inside the parachute's altitude band (karman-flightlog's
//!   comparison rule 5, from the nominal flight), the simulated vertical velocity when the
//!   simulated descent passes the same altitude minus the logged one. Every other input acts
//!   on the ascent: for each log sample from liftoff to the log's apogee, the simulated
//!   altitude above the pad at the same time from liftoff minus the logged one (the time
//!   axis of karman-flightlog's comparison rules 1–2).
//! - **Weights.** Each phase's residuals are divided by their RMS at the nominal values, so
//!   that metres and metres per second weigh alike and each phase counts once.
//! - **Optimiser.** Levenberg–Marquardt (the `levenberg-marquardt` crate, a Rust port of
//!   MINPACK's `lmder`: Moré 1978, "The Levenberg–Marquardt algorithm: implementation and
//!   theory", Lecture Notes in Mathematics 630) on `x = ln(factor)`, which keeps every factor
//!   positive; factors are held to [`FACTOR_RANGE`]. The Jacobian is a forward difference of
//!   0.1 % in each factor, one flight per input. Every flight flies the trial values through
//!   the Monte Carlo machinery (`MonteCarlo::track`), so they reach the models exactly as a
//!   study's draws do. The fit ends within [`FitOptions::max_flights`] flights.
//! - **Clock.** When an ascent is compared, the offset of the log's clock is fitted with the
//!   inputs (a nuisance parameter, within ±[`MAX_CLOCK_OFFSET_S`], the log reader's liftoff
//!   back-off): the log's liftoff is found from its own samples and may be off by a sample
//!   or more, which would otherwise show as an altitude error of the speed times that. An
//!   offset beyond [`NOTED_CLOCK_OFFSET_S`] is reported in [`Fit::warnings`]: the timing of
//!   the simulated ascent then differs from the log's.
//! - **Uncertainty.** At the best values, `cov = s² (JᵀJ)⁻¹` with `s² = Σr²/(m − n)` of the
//!   weighted residuals (the Gauss–Newton covariance; Press et al., *Numerical Recipes*, 3rd
//!   ed., §15.4–15.5), widened by `(1 + ρ)/(1 − ρ)` for the lag-one autocorrelation `ρ` of
//!   the residuals (the effective number of independent samples of an AR(1) series;
//!   Bretherton et al. 1999, J. Climate 12:1990). Residuals of a real flight are dominated
//!   by model error, not noise: read the uncertainty as how well the log pins the factor
//!   down, not as the model's accuracy.
//!
//! [`write_fitted`] writes the mission with the fitted values set in place (comments and
//! layout kept) and a header recording the fit. [`simulated_flight`] hands a flown
//! mission's points to karman-flightlog's comparison; `karman compare` and `karman fit` use
//! it. [`log_json`], [`comparison_json`], [`simulation_json`] and [`fit_json`] are the JSON
//! shapes of a log, a comparison and a fit, shared by the CLI's `--json` output and the
//! Python package.

mod bridge;
mod error;
mod fit;
mod report;
mod write;

pub use bridge::simulated_flight;
pub use error::FitError;
pub use fit::{
    FACTOR_RANGE, Fit, FitOptions, FittedInput, MAX_CLOCK_OFFSET_S, MIN_PHASE_SAMPLES,
    NOTED_CLOCK_OFFSET_S, Nominal, Phase, PhaseResiduals, fit,
};
pub use report::{comparison_json, fit_json, log_json, simulation_json};
pub use write::write_fitted;

/// The README's example, compiled and run by `cargo test --doc`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeExample;
