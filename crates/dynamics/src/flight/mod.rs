//! Flight phases, events, sampled processes and actions (docs/physics.md §9), RocketPy's
//! `Flight.__simulate`.
//!
//! The module's files follow the design, each using only those listed after it (no circle:
//! `cargo xtask tidy` checks it):
//! - `run` — the engine: `Run::new` sets a flight up (its start, the schedule, the
//!   processes connected to each other's signals and the vehicle's control channels, the
//!   events), then `fly` integrates the phases in turn, each by a fresh [`RungeKutta`] from
//!   its start to the next phase's start (a hard time node); after every accepted step the
//!   events, the user events and then the sampled processes are checked, and whatever ends
//!   the step early rolls its last point back to that instant.
//! - `instants` — the processes of a flight and their instants in each step (below).
//! - `parachute` — the parachute triggers (apogee and noisy-barometer height triggers, §9.4),
//!   the first sampled processes; controllers and sensors are more.
//! - `events` — a value whose sign change inside a step is an event, located by one root
//!   routine, and what firing does: in RocketPy's order, (a) rail exit (§9.2, Hermite root of
//!   `|Δr|² − L₁²`), (b) apogee (§9.3, linear root of `v_z`), (c) impact (§9.5, Hermite root
//!   of `z − elevation`); then the user's [`Event`]s (a value whose downward zero crossing
//!   fires an [`Action`], root by bisection on the dense output). Burn-out and `max_time`
//!   are time nodes (a step stop and the last phase bound).
//! - `process` — the interface of a [`SampledProcess`]: processes sampled at a rate during
//!   the flight (RocketPy's overshootable time nodes, evaluated on the dense output), with
//!   bounds that pass whole steps over, whose `sample` may return an [`Action`]; the
//!   [`Probe`] they read (state, its time derivative, the step's end) and the [`Signals`]
//!   they publish to and read from.
//! - `actions` — [`Action`]: deploy a device, set a control input, tumble, separate a stage,
//!   record a value, terminate; and what each does to the schedule and the log.
//! - `log` — the stored points, events, records and counters, and the [`Flight`] they make.
//! - `schedule` — the phases and the [`Configuration`] each phase flies (equations, deployed
//!   devices, control inputs); an action that changes the configuration inserts a phase.
//! - `policy` — the integrator policy: DOPRI5 on the rail, through the burn and under
//!   parachutes, DOP853 for the unpowered free flight (6 DOF or the 3-DOF point mass) from
//!   burn-out (restarted there) unless
//!   its steps keep being rejected, a sign of kinks in the right-hand side such as linearly
//!   interpolated atmosphere profiles, where DOPRI5 takes over; under a parachute, once
//!   DOPRI5's steps are held back by stability (three steps in a row with `h|λ| ≥ 3`), the
//!   Runge–Kutta–Chebyshev method takes over for the rest of the phase (see
//!   [`crate::integrator`] for the measurements). Within a phase, steps also end on every
//!   thrust-curve knot of the burn and at burn-out
//!   ([`FlightSettings::stop_at_thrust_knots`]): without those stops a DOPRI5 step at the
//!   default tolerances straddles the kinks of a jagged thrust curve and the apogee drifts by
//!   up to ~0.1 % (Valetudo), with them every validation apogee is within 0.02 % of
//!   RocketPy's.
//!
//! Sampling (§9.4, RocketPy's `__process_overshootable_nodes`): the instants `j / f` of every
//! active process inside a step are merged in time order on the fly (no node list, no sort),
//! instants within 1e-7 s of each other forming one group evaluated at its first instant,
//! exactly as a sorted, merged node list would be. Most steps cannot make any process act,
//! and bounds over the step prove it without evaluating the instants (see `sampled`); for the
//! parachutes:
//! - noise-free parachutes skip steps with `v_z > 0`, or well above a height trigger's threshold
//!   height, as if they had no instants there;
//! - a noisy height trigger still advances its noise stream through every instant, but its
//!   instants are only evaluated when the step's highest possible noisy pressure could reach
//!   the trigger pressure; otherwise the stream jumps over them with the exact law of the
//!   skipped AR(1) steps, one draw per step ([`NoiseStream::skip`]; "possible" meaning within
//!   [`crate::noise::EXCLUSION_SIGMAS`] standard deviations of the noise);
//! - an apogee trigger never reads the noise, so its stream is never drawn (its draws would
//!   change nothing: every parachute has its own stream).
//!
//! Deviations from RocketPy (none changes a validation flight):
//! - a rocket still on the rail at burn-out whose speed cannot carry it the rest of the rail
//!   against gravity ([`crate::equations::coasts_off_rail`]) ends there with
//!   [`Termination::StuckOnRail`]: RocketPy's rail acceleration, clipped at zero, would keep
//!   its speed and let it creep off the rail long after (or integrate a rocket at rest to
//!   `max_time`);
//! - sampling and the impact check start at rail exit: on the rail `v_z ≥ 0` and
//!   `z ≥ elevation` hold up to round-off, which must not fire an apogee trigger or an impact;
//! - the impact check also runs on the step that detects apogee (see `events`).
//!
//! [`NoiseStream::skip`]: crate::noise::NoiseStream::skip
//! [`RungeKutta`]: crate::integrator::RungeKutta
//! [`Configuration`]: karman_model::Configuration

mod actions;
mod events;
mod instants;
mod log;
mod parachute;
mod policy;
mod process;
mod run;
mod schedule;
#[cfg(test)]
mod tests;

use karman_model::{AtmosphereModel, Configuration, VehicleModel};

pub use actions::Action;
pub use events::Event;
pub use log::{Flight, IntegrationStats, ParachuteEvent, Record, SolutionPoint, Termination};
pub use process::{
    Connections, DenseOutput, Probe, SampledProcess, Signal, SignalId, Signals, StepBounds,
};
pub use schedule::PhaseKind;
pub(crate) use schedule::evaluate;

use crate::DynamicsError;
use crate::settings::FlightSettings;
use crate::state::State;

/// Flies a rocket from the rail to the ground (or apogee / `max_time`).
///
/// # Errors
/// [`DynamicsError::InvalidSetting`] for bad settings or a rail shorter than the
/// nozzle-to-upper-button distance; [`DynamicsError::DuplicateSignal`] and
/// [`DynamicsError::Unconnected`] for processes that do not connect
/// ([`SampledProcess::connect`]); integrator failures ([`DynamicsError::NonFinite`],
/// [`DynamicsError::StepTooSmall`], [`DynamicsError::TooManySteps`]) for unflyable models.
pub fn simulate<A: AtmosphereModel, V: VehicleModel>(
    atmosphere: &A,
    vehicle: &V,
    settings: &FlightSettings,
) -> Result<Flight, DynamicsError> {
    run::fly(
        atmosphere,
        vehicle,
        settings,
        run::Start::Rail,
        run::Extras::default(),
        run::Sampling::Bounded,
    )
}

/// [`simulate`] with more sampled processes besides the vehicle's parachute triggers
/// (controllers, sensors), sampled after them at the instants they share.
///
/// # Errors
/// As [`simulate`].
pub fn simulate_with<'a, A: AtmosphereModel, V: VehicleModel>(
    atmosphere: &'a A,
    vehicle: &'a V,
    settings: &FlightSettings,
    processes: Vec<Box<dyn SampledProcess + 'a>>,
) -> Result<Flight, DynamicsError> {
    run::fly(
        atmosphere,
        vehicle,
        settings,
        run::Start::Rail,
        run::Extras {
            processes,
            events: Vec::new(),
        },
        run::Sampling::Bounded,
    )
}

/// [`simulate_with`] with user-defined events besides the built-in ones ([`Event`]: a value
/// whose crossing of zero fires an action), checked after them in the given order.
///
/// # Errors
/// As [`simulate`].
pub fn simulate_with_events<'a, A: AtmosphereModel, V: VehicleModel>(
    atmosphere: &'a A,
    vehicle: &'a V,
    settings: &FlightSettings,
    processes: Vec<Box<dyn SampledProcess + 'a>>,
    events: Vec<Box<dyn Event + 'a>>,
) -> Result<Flight, DynamicsError> {
    run::fly(
        atmosphere,
        vehicle,
        settings,
        run::Start::Rail,
        run::Extras { processes, events },
        run::Sampling::Bounded,
    )
}

/// A flight that starts at time `t0` from a given free-flight `state` (off the rail) in a
/// given configuration, as RocketPy's `initial_solution`: a stage after separation, or a
/// flight resumed from one of its own points. Its phase is the free flight of the settings'
/// [`SimulationMode`](crate::SimulationMode), or the descent
/// under the newest parachute deployed in `configuration`; parachutes already deployed there
/// are not sampled again. Rail exit is taken as passed at `t0`; apogee and impact are
/// detected as in [`simulate`].
///
/// # Errors
/// As [`simulate`], and [`DynamicsError::InvalidSetting`] (`t0`) when `t0` is not before
/// `max_time`.
pub fn simulate_from<'a, A: AtmosphereModel, V: VehicleModel>(
    atmosphere: &'a A,
    vehicle: &'a V,
    settings: &FlightSettings,
    t0: f64,
    state: State,
    configuration: Configuration,
    processes: Vec<Box<dyn SampledProcess + 'a>>,
) -> Result<Flight, DynamicsError> {
    run::fly(
        atmosphere,
        vehicle,
        settings,
        run::Start::From {
            t0,
            state,
            configuration,
        },
        run::Extras {
            processes,
            events: Vec::new(),
        },
        run::Sampling::Bounded,
    )
}
