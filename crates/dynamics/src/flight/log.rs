//! The log of a flight: its stored points, the events found (rail exit, apogee, impact,
//! parachutes, separation, tumble), the values the processes record, the counters, and the
//! [`Flight`] they make at its end.

use karman_model::Configuration;

use super::schedule::PhaseKind;
use crate::integrator::{Pair, RungeKutta};
use crate::settings::EquationsForm;
use crate::state::State;

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
    /// A sampled process returned [`Action::Terminate`](crate::Action::Terminate).
    Terminated,
    /// A sampled process returned [`Action::SeparateStage`](crate::Action::SeparateStage): the flight of each part goes on
    /// with [`simulate_from`](crate::simulate_from).
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
    pub(super) fn add<F>(&mut self, integ: &RungeKutta<13, F>) {
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
    /// Values recorded by sampled processes ([`Action::Record`](crate::Action::Record)), in time order.
    pub records: Vec<Record>,
    /// Stage separation `(t, stage)` ([`Action::SeparateStage`](crate::Action::SeparateStage)).
    pub separation: Option<(f64, usize)>,
    /// Time the body started tumbling ([`Action::Tumble`](crate::Action::Tumble)), s.
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
    /// derivatives the integrator evaluates anyway (its FSAL stage at each stored point), so
    /// it costs nothing extra.
    pub max_acceleration: f64,
    /// Integration counters.
    pub stats: IntegrationStats,
}

/// `|v̇|` of a state derivative.
pub(super) fn acceleration(u_dot: &State) -> f64 {
    (u_dot[3] * u_dot[3] + u_dot[4] * u_dot[4] + u_dot[5] * u_dot[5]).sqrt()
}

/// A value recorded by a sampled process ([`Action::Record`](crate::Action::Record)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Record {
    /// Sample instant, s.
    pub t: f64,
    /// Index of the process (the vehicle's parachute triggers first, then the processes
    /// given to the flight in their order).
    pub process: usize,
    /// The process's channel.
    pub channel: usize,
    /// The value.
    pub value: f64,
}

/// What a flight in progress has stored so far.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Log {
    pub points: Vec<SolutionPoint>,
    pub rail_exit: Option<(f64, State)>,
    pub apogee: Option<(f64, State)>,
    pub impact: Option<(f64, State)>,
    pub parachute_events: Vec<ParachuteEvent>,
    pub records: Vec<Record>,
    pub separation: Option<(f64, usize)>,
    pub tumble: Option<f64>,
    pub termination: Termination,
    pub stats: IntegrationStats,
    /// Largest `|v̇|` so far ([`Flight::max_acceleration`]).
    pub max_acceleration: f64,
}

impl Log {
    /// The log of a flight that starts at `first`.
    pub fn new(first: SolutionPoint) -> Self {
        Self {
            points: vec![first],
            rail_exit: None,
            apogee: None,
            impact: None,
            parachute_events: Vec::new(),
            records: Vec::new(),
            separation: None,
            tumble: None,
            termination: Termination::MaxTime,
            stats: IntegrationStats::default(),
            max_acceleration: 0.0,
        }
    }

    /// The times of the last two stored points: the window of the last step.
    pub fn last_step(&self) -> (f64, f64) {
        let n = self.points.len();
        (self.points[n - 2].t, self.points[n - 1].t)
    }

    /// Takes `|v̇|` of a state derivative into [`Log::max_acceleration`].
    pub fn acceleration(&mut self, u_dot: &State) {
        self.max_acceleration = self.max_acceleration.max(acceleration(u_dot));
    }

    /// Stores a recorded value.
    pub fn record(&mut self, process: usize, channel: usize, value: f64, t: f64) {
        self.records.push(Record {
            t,
            process,
            channel,
            value,
        });
    }

    /// Replaces the last stored point by the dense state at `t` (an event or an action inside
    /// the step) and returns it.
    pub fn cut_step<F: FnMut(f64, &State) -> State>(
        &mut self,
        integ: &mut RungeKutta<13, F>,
        configuration: Configuration,
        kind: PhaseKind,
        t: f64,
    ) -> (f64, State) {
        let y = integ.dense(t);
        let n = self.points.len();
        self.points[n - 1] = SolutionPoint {
            t,
            state: y,
            phase: kind,
            configuration,
        };
        (t, y)
    }
}
