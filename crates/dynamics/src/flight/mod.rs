//! Flight phases, events, sampled processes and actions (docs/physics.md §9), RocketPy's
//! `Flight.__simulate`.
//!
//! The module's files follow the design:
//! - `run` — the step loop: a flight is an ordered list of phases, each integrated by
//!   a fresh [`RungeKutta`] from its start to the next phase's
//!   start (a hard time node); after every accepted step the events and then the sampled
//!   processes are checked, and whatever ends the step early rolls its last point back to
//!   that instant.
//! - `phases` — the phases and the [`Configuration`] each phase flies (equations, deployed
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
//! - `events` — a value whose sign change inside a step is an event, located by one root
//!   routine, and what firing does: in RocketPy's order, (a) rail exit (§9.2, Hermite root of
//!   `|Δr|² − L₁²`), (b) apogee (§9.3, linear root of `v_z`), (c) impact (§9.5, Hermite root
//!   of `z − elevation`); burn-out and `max_time` are time nodes (a step stop and the last
//!   phase bound).
//! - `sampled` — [`SampledProcess`]: processes sampled at a rate during the flight (RocketPy's
//!   overshootable time nodes, evaluated on the dense output), with bounds that pass whole
//!   steps over, whose `sample` may return an [`Action`]. The parachute triggers
//!   (`parachute`: apogee and noisy-barometer height triggers, §9.4) are the first
//!   instances; controllers and sensors are more.
//! - `actions` — [`Action`]: deploy a device, set a control input, tumble, separate a stage,
//!   record a value, terminate.
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

mod actions;
mod events;
mod parachute;
mod phases;
mod policy;
mod run;
mod sampled;
#[cfg(test)]
mod tests;

use karman_model::{AtmosphereModel, Configuration, VehicleModel};

pub use actions::{Action, Record};
pub use sampled::{DenseOutput, Probe, SampledProcess, StepBounds};

use crate::DynamicsError;
use crate::equations::{CanopyState, Cursors, Derivative, Equations};
use crate::integrator::{Pair, RungeKutta};
use crate::settings::{EquationsForm, FlightSettings, SimulationMode};
use crate::state::State;

/// Which equations of motion a phase integrates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PhaseKind {
    /// 1-DOF slide along the rail (docs/physics.md §8.1).
    Rail,
    /// 6-DOF variable-mass flight (§8.2).
    SixDof,
    /// 3-DOF point-mass flight (§8.5, [`SimulationMode::ThreeDof`]) with this weathercock
    /// coefficient, 1/s.
    PointMass {
        /// [`FlightSettings::weathercock_coefficient`].
        weathercock: f64,
    },
    /// 3-DOF descent under the given canopy (§8.4), or a tumbling body ([`Action::Tumble`]:
    /// its drag area, no added mass).
    Parachute(CanopyState),
}

impl PhaseKind {
    /// The free flight (from rail exit until a canopy opens) the settings ask for.
    #[must_use]
    pub fn free_flight(settings: &FlightSettings) -> Self {
        match settings.simulation_mode {
            SimulationMode::SixDof => Self::SixDof,
            SimulationMode::ThreeDof => Self::PointMass {
                weathercock: settings.weathercock_coefficient,
            },
        }
    }

    /// Whether the phase's equations read the configuration's control inputs (the air
    /// brakes' level, docs/physics.md §16.1): the free flight, 6-DOF or point mass. The rail's
    /// equations drop them and a canopy's descent has none.
    #[must_use]
    pub fn reads_controls(&self) -> bool {
        matches!(self, Self::SixDof | Self::PointMass { .. })
    }
}

/// One stored solution point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolutionPoint {
    /// Time, s.
    pub t: f64,
    /// State (docs/physics.md §3).
    pub state: State,
    /// Equations in force for this point (RocketPy assigns a point to the phase with
    /// `t_start < t ≤ t_end`).
    pub phase: PhaseKind,
    /// Configuration in force for this point.
    pub configuration: Configuration,
}

/// How the flight ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Termination {
    /// Ground impact.
    Impact,
    /// Stopped at apogee (`terminate_on_apogee`).
    Apogee,
    /// Reached `max_time` in the air.
    MaxTime,
    /// Still on the rail at burn-out, too slow to coast off it against gravity.
    StuckOnRail,
    /// A sampled process returned [`Action::Terminate`].
    Terminated,
    /// A sampled process returned [`Action::SeparateStage`]: the flight of each part goes on
    /// with [`simulate_from`].
    Separation,
}

/// A parachute trigger.
#[derive(Debug, Clone, PartialEq)]
pub struct ParachuteEvent {
    /// Parachute name.
    pub name: String,
    /// Trigger (ejection) time, s, before the lag.
    pub trigger_time: f64,
    /// Full-inflation time `trigger_time + lag`, s.
    pub inflation_time: f64,
}

/// Integration work of one flight.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub struct IntegrationStats {
    /// Accepted steps.
    pub steps: usize,
    /// Rejected steps.
    pub rejected_steps: usize,
    /// Right-hand-side evaluations (integration only, not post-processing).
    pub evaluations: usize,
    /// Flight phases integrated.
    pub phases: usize,
    /// Accepted steps of the Runge–Kutta–Chebyshev method (stiff parachute descents), among
    /// `steps`.
    pub chebyshev_steps: usize,
}

impl IntegrationStats {
    /// Adds the counters of one finished integrator.
    fn add<F>(&mut self, integ: &RungeKutta<13, F>) {
        self.steps += integ.steps();
        self.rejected_steps += integ.rejected_steps();
        self.evaluations += integ.evaluations();
        if integ.pair() == Pair::Rkc2 {
            self.chebyshev_steps += integ.steps();
        }
    }
}

/// The raw result of a flight: stored points, events and counters. Derived outputs come from
/// [`crate::output`].
#[derive(Debug, Clone, PartialEq)]
pub struct Flight {
    /// Stored solution points in time order.
    pub points: Vec<SolutionPoint>,
    /// Rail exit `(t, state)`.
    pub rail_exit: Option<(f64, State)>,
    /// Apogee `(t, state)`.
    pub apogee: Option<(f64, State)>,
    /// Impact `(t, state)`.
    pub impact: Option<(f64, State)>,
    /// Parachute triggers in time order.
    pub parachute_events: Vec<ParachuteEvent>,
    /// Values recorded by sampled processes ([`Action::Record`]), in time order.
    pub records: Vec<Record>,
    /// Stage separation `(t, stage)` ([`Action::SeparateStage`]).
    pub separation: Option<(f64, usize)>,
    /// Time the body started tumbling ([`Action::Tumble`]), s.
    pub tumble: Option<f64>,
    /// How the flight ended.
    pub termination: Termination,
    /// Final time, s.
    pub t_final: f64,
    /// Motor burn-out time, s.
    pub burn_out: f64,
    /// Launch elevation, m ASL.
    pub elevation: f64,
    /// Seed of the parachute noise streams.
    pub noise_seed: u64,
    /// The form of the 6-DOF equations flown (post-processing re-evaluates the same).
    pub equations: EquationsForm,
    /// Largest acceleration magnitude `|v̇|` at the stored points, m/s², including the
    /// equations of the next phase at each phase start (a canopy inflates instantly, so the
    /// deceleration peaks there; RocketPy's LSODA stores its first point a fraction of a
    /// millisecond later, a Runge–Kutta step tens of milliseconds later). Taken from the
    /// derivatives the integrator evaluates anyway (its FSAL stage at each stored point).
    pub max_acceleration: f64,
    /// Integration counters.
    pub stats: IntegrationStats,
}

/// `|v̇|` of a state derivative.
fn acceleration(u_dot: &State) -> f64 {
    (u_dot[3] * u_dot[3] + u_dot[4] * u_dot[4] + u_dot[5] * u_dot[5]).sqrt()
}

/// Evaluates the equations of a phase in a configuration.
#[inline(always)]
pub(crate) fn evaluate<A: AtmosphereModel, V: VehicleModel>(
    eq: &Equations<'_, A, V>,
    kind: &PhaseKind,
    configuration: &Configuration,
    t: f64,
    u: &State,
    cursors: &mut Cursors,
) -> Derivative {
    match kind {
        PhaseKind::Rail => eq.rail(t, u, configuration, cursors),
        PhaseKind::SixDof => eq.six_dof(t, u, configuration, cursors),
        PhaseKind::PointMass { weathercock } => {
            eq.point_mass(t, u, *weathercock, configuration, cursors)
        }
        PhaseKind::Parachute(canopy) => eq.parachute(t, u, canopy, cursors),
    }
}

/// Flies a rocket from the rail to the ground (or apogee / `max_time`).
///
/// # Errors
/// [`DynamicsError::InvalidSetting`] for bad settings or a rail shorter than the
/// nozzle-to-upper-button distance; integrator failures ([`DynamicsError::NonFinite`],
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
        Vec::new(),
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
        processes,
        run::Sampling::Bounded,
    )
}

/// A flight that starts at time `t0` from a given free-flight `state` (off the rail) in a
/// given configuration, as RocketPy's `initial_solution`: a stage after separation, or a
/// flight resumed from one of its own points. Its phase is the free flight of the settings'
/// [`SimulationMode`], or the descent
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
        processes,
        run::Sampling::Bounded,
    )
}
