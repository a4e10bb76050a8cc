//! The engine: a flight is set up ([`Run::new`]: the start, the schedule, the processes
//! and the events), then its phases are integrated in turn ([`fly`]), the events and then
//! the sampled processes checked after every accepted step; whatever ends a step early
//! rolls its last point back to that instant.

use karman_model::{AtmosphereModel, Configuration, ParachuteSpec, VehicleModel, VehicleSetup};

use super::actions::{Acted, Action, Target};
use super::events::{Event, Events};
use super::instants::Processes;
use super::log::{Flight, Log, SolutionPoint};
use super::parachute::ParachuteTrigger;
use super::policy::Policy;
use super::process::{Connections, SampledProcess, Signals};
use super::schedule::{Phase, PhaseKind, Schedule, evaluate};
use crate::DynamicsError;
use crate::equations::{CanopyState, Cursors, Equations};
use crate::integrator::{RungeKutta, StepStatus, Tolerances};
use crate::noise::NoiseStream;
use crate::settings::FlightSettings;
use crate::state::{State, euler313_to_quaternion};

/// Where a flight starts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Start {
    /// At rest on the rail at `t = 0` (docs/physics.md §2.4).
    Rail,
    /// In free flight at `t0` from `state` in `configuration` ([`crate::simulate_from`]).
    From {
        t0: f64,
        state: State,
        configuration: Configuration,
    },
}

/// How the sampling instants of a step are evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Sampling {
    /// Steps in which no process can act are passed over with bounds
    /// ([`Processes::sample`]).
    Bounded,
    /// [`Sampling::Bounded`] with the noise streams drawn at every skipped instant instead of
    /// jumping over them (the tests compare it with [`Sampling::Direct`] bit for bit).
    #[cfg(test)]
    BoundedStepwise,
    /// Every instant of every active process evaluated directly, as a sorted node list
    /// (the tests' reference).
    #[cfg(test)]
    Direct,
}

/// What a flight flies besides the vehicle's parachute triggers: more sampled processes
/// (sampled after the triggers at the instants they share) and user-defined events.
#[derive(Default)]
pub(super) struct Extras<'a> {
    pub processes: Vec<Box<dyn SampledProcess + 'a>>,
    pub events: Vec<Box<dyn Event + 'a>>,
}

/// A flight in progress: the schedule of its phases, its log, its processes and their
/// instants, its events.
pub(super) struct Run<'a> {
    schedule: Schedule,
    log: Log,
    processes: Processes<'a>,
    events: Events<'a>,
    /// The vehicle's parachutes (what [`crate::Action::DeployDevice`] deploys).
    parachutes: Vec<ParachuteSpec>,
    sampling: Sampling,
}

/// The initial attitude on the rail (docs/physics.md §2.4) and the rail travel to the upper
/// button (§8.1, RocketPy's `effective_1rl`).
fn rail_start(
    settings: &FlightSettings,
    setup: &VehicleSetup,
    elevation: f64,
) -> Result<(State, f64), DynamicsError> {
    let csys = setup.csys;
    let buttons = setup.rail_buttons;
    let phi = buttons.map_or(0.0, |b| {
        if csys > 0.0 {
            b.angular_position_rad
        } else {
            2.0 * std::f64::consts::PI - b.angular_position_rad
        }
    });
    let theta = (settings.inclination_deg - 90.0).to_radians();
    let psi = (-settings.heading_deg).to_radians();
    let e = euler313_to_quaternion(phi, theta, psi);
    let u0: State = [
        0.0, 0.0, elevation, 0.0, 0.0, 0.0, e[0], e[1], e[2], e[3], 0.0, 0.0, 0.0,
    ];
    let nozzle = setup.nozzle_position;
    let upper = buttons.map_or(nozzle, |b| {
        b.lower_position + csys * (b.upper_position - b.lower_position).abs()
    });
    let rail_travel = settings.rail_length - (nozzle - upper).abs();
    let positive_travel = rail_travel > 0.0; // false for NaN too
    if !positive_travel {
        return Err(DynamicsError::InvalidSetting {
            name: "rail_length",
            value: settings.rail_length,
            reason: "must exceed the nozzle-to-upper-rail-button distance",
        });
    }
    Ok((u0, rail_travel))
}

/// The phase a flight resumed in `configuration` starts with: the descent under the deployed
/// parachute of highest index, or the free flight `free`.
fn resumed_kind(
    parachutes: &[ParachuteSpec],
    configuration: &Configuration,
    free: PhaseKind,
) -> PhaseKind {
    parachutes
        .iter()
        .enumerate()
        .rev()
        .find(|(i, _)| configuration.is_deployed(*i))
        .map_or(free, |(_, spec)| {
            PhaseKind::Parachute(CanopyState {
                cd_s: spec.cd_s,
                radius: spec.radius,
                height: spec.height,
                added_mass_coefficient: spec.added_mass_coefficient,
            })
        })
}

/// The start time, state, configuration, first phase and rail travel of a flight.
fn starting_point(
    settings: &FlightSettings,
    setup: &VehicleSetup,
    elevation: f64,
    start: Start,
) -> Result<(f64, State, Configuration, PhaseKind, f64), DynamicsError> {
    match start {
        Start::Rail => {
            let (u0, travel) = rail_start(settings, setup, elevation)?;
            let configuration = Configuration {
                controls: setup.initial_controls,
                ..Configuration::default()
            };
            Ok((0.0, u0, configuration, PhaseKind::Rail, travel))
        }
        Start::From {
            t0,
            state,
            configuration,
        } => {
            let before_end = t0 < settings.max_time; // false for NaN too
            if !before_end || !t0.is_finite() {
                return Err(DynamicsError::InvalidSetting {
                    name: "t0",
                    value: t0,
                    reason: "must be a finite time before max_time",
                });
            }
            let kind = resumed_kind(
                &setup.parachutes,
                &configuration,
                PhaseKind::free_flight(settings),
            );
            Ok((t0, state, configuration, kind, f64::NAN))
        }
    }
}

/// The steps stop on the knots of the thrust curve inside the burn and at burn-out (when
/// [`FlightSettings::stop_at_thrust_knots`]): the right-hand side has a kink at every knot
/// (linear interpolation) and a jump at burn-out (thrust and power-on drag stop). An
/// embedded Runge–Kutta error estimate resolves those poorly (RocketPy's LSODA, with its
/// max-norm and many short steps, absorbs them); with the steps stopped there the default
/// tolerances give converged apogees.
fn step_stops(settings: &FlightSettings, setup: &VehicleSetup) -> Vec<f64> {
    if !settings.stop_at_thrust_knots {
        return Vec::new();
    }
    let (b0, b1) = (setup.burn_start, setup.burn_out);
    let mut k: Vec<f64> = setup
        .thrust_knots
        .iter()
        .copied()
        .filter(|&x| b0 < x && x < b1)
        .collect();
    k.push(b1);
    k
}

/// The largest step of a phase of `kind`.
fn max_step(settings: &FlightSettings, kind: PhaseKind) -> f64 {
    if kind == PhaseKind::Rail {
        settings
            .max_time_step
            .min(settings.rail_max_time_step)
            .min(settings.control_max_time_step)
    } else if kind.reads_controls() {
        settings.max_time_step.min(settings.control_max_time_step)
    } else {
        settings.max_time_step
    }
}

impl<'a> Run<'a> {
    /// Sets a flight up from `start`: the vehicle's parachute triggers then `extra`'s
    /// processes, connected to each other's signals and the vehicle's control channels.
    fn new<A: AtmosphereModel, V: VehicleModel>(
        atmosphere: &'a A,
        vehicle: &'a V,
        settings: &FlightSettings,
        start: Start,
        extra: Extras<'a>,
        sampling: Sampling,
    ) -> Result<Self, DynamicsError> {
        let setup = vehicle.setup();
        let elevation = atmosphere.elevation();
        let (t0, u0, configuration, kind0, rail_travel) =
            starting_point(settings, &setup, elevation, start)?;
        let mut list: Vec<Box<dyn SampledProcess + 'a>> = Vec::new();
        for (i, spec) in setup.parachutes.iter().enumerate() {
            let stream = NoiseStream::new(spec.noise, settings.noise_seed, i as u64);
            #[cfg(test)]
            let stream = if sampling == Sampling::BoundedStepwise {
                stream.stepwise()
            } else {
                stream
            };
            list.push(Box::new(ParachuteTrigger::new(
                atmosphere,
                i,
                spec,
                stream,
                settings.trigger_band,
            )));
        }
        let parachutes = setup.parachutes.len();
        list.extend(extra.processes);
        let signals = Signals::new(list.iter().map(|p| p.outputs()))?;
        let connections = Connections {
            signals: &signals,
            controls: vehicle.control_channels(),
        };
        for process in &mut list {
            process.connect(&connections)?;
        }
        let active = (0..list.len())
            .filter(|&i| list[i].rate() > 0.0 && !(i < parachutes && configuration.is_deployed(i)))
            .collect();
        let first = Phase {
            t: t0,
            kind: Some(kind0),
            configuration,
            clear: false,
        };
        let events = Events {
            off_rail: kind0 != PhaseKind::Rail,
            free_flight: PhaseKind::free_flight(settings),
            rail_travel,
            rail_gravity: atmosphere.gravity(elevation)
                * settings.inclination_deg.to_radians().sin(),
            elevation,
            burn_out: setup.burn_out,
            terminate_on_apogee: settings.terminate_on_apogee,
            first_record: list.len(),
            custom: extra.events.into_iter().map(|e| (e, false)).collect(),
        };
        Ok(Self {
            schedule: Schedule::new(first, settings.max_time),
            log: Log::new(SolutionPoint {
                t: t0,
                state: u0,
                phase: kind0,
                configuration,
            }),
            processes: Processes {
                list,
                active,
                instants: Vec::new(),
                signals,
            },
            events,
            parachutes: setup.parachutes,
            sampling,
        })
    }

    /// The target of the actions: the schedule, the log and the parachutes.
    fn target(&mut self) -> Target<'_> {
        Target {
            schedule: &mut self.schedule,
            log: &mut self.log,
            parachutes: &self.parachutes,
        }
    }

    /// After an accepted step of phase `index`: the events, then the user events, then the
    /// sampled processes, and what acted; the state the next phase starts from when the
    /// step was cut (or the phase ends there).
    fn after_step<F: FnMut(f64, &State) -> State>(
        &mut self,
        integ: &mut RungeKutta<13, F>,
        index: usize,
        phase: &Phase,
        kind: PhaseKind,
    ) -> Result<Option<(f64, State)>, DynamicsError> {
        let mut target = Target {
            schedule: &mut self.schedule,
            log: &mut self.log,
            parachutes: &self.parachutes,
        };
        if let Some(event) = self.events.check(&mut target, integ, index, phase, kind)? {
            return Ok(Some(event));
        }
        if let Some(acted) = self.events.check_custom(integ) {
            if let Action::Record { channel, value } = acted.action {
                self.log.record(acted.process, channel, value, acted.t);
            } else {
                return Ok(Some(self.act(integ, acted, index, phase, kind)));
            }
        }
        // A rocket on the rail has not flown: its vertical speed is ≥ 0 up to round-off
        // (which could otherwise fire an apogee trigger), so only the processes that ask for
        // it (controllers) are sampled on the rail.
        let rail = kind == PhaseKind::Rail;
        let log = &mut self.log;
        let acted = match self.sampling {
            Sampling::Bounded => self.processes.sample(integ, phase, rail, log),
            #[cfg(test)]
            Sampling::BoundedStepwise => self.processes.sample(integ, phase, rail, log),
            #[cfg(test)]
            Sampling::Direct if rail => None,
            #[cfg(test)]
            Sampling::Direct => self.processes.sample_every_instant(integ, phase, log),
        };
        Ok(acted.map(|acted| self.act(integ, acted, index, phase, kind)))
    }

    /// Carries out a sampled process's (or an event's) action.
    fn act<F: FnMut(f64, &State) -> State>(
        &mut self,
        integ: &mut RungeKutta<13, F>,
        acted: Acted,
        index: usize,
        phase: &Phase,
        kind: PhaseKind,
    ) -> (f64, State) {
        let cut = self.target().act(integ, acted, index, phase, kind);
        if acted.process < self.processes.list.len() {
            self.processes.retire_if_done(acted.process);
        }
        cut
    }
}

/// Flies a vehicle from `start` with the vehicle's parachute triggers and `extra`'s
/// processes and events: the setup ([`Run::new`]), then the phases in turn.
pub(super) fn fly<'a, A: AtmosphereModel, V: VehicleModel>(
    atmosphere: &'a A,
    vehicle: &'a V,
    settings: &FlightSettings,
    start: Start,
    extra: Extras<'a>,
    sampling: Sampling,
) -> Result<Flight, DynamicsError> {
    settings.validate()?;
    let eq = Equations::new(atmosphere, vehicle, settings.equations);
    let mut run = Run::new(atmosphere, vehicle, settings, start, extra, sampling)?;
    let stops = step_stops(settings, &vehicle.setup());
    let first = run.log.points[0];
    let (mut t, mut y) = (first.t, first.state);
    let mut index = 0;
    while index + 1 < run.schedule.len() {
        let phase = *run.schedule.get(index).expect("index is in the schedule");
        let Some(kind) = phase.kind else { break };
        (t, y) = run.fly_phase(&eq, settings, &stops, index, &phase, kind, (t, y))?;
        index += 1;
    }
    let log = run.log;
    Ok(Flight {
        points: log.points,
        rail_exit: log.rail_exit,
        apogee: log.apogee,
        impact: log.impact,
        parachute_events: log.parachute_events,
        records: log.records,
        separation: log.separation,
        tumble: log.tumble,
        termination: log.termination,
        t_final: t,
        burn_out: run.events.burn_out,
        elevation: run.events.elevation,
        noise_seed: settings.noise_seed,
        equations: settings.equations,
        max_acceleration: log.max_acceleration,
        stats: log.stats,
    })
}

impl Run<'_> {
    /// Integrates phase `index` from `(t, y)` to the next phase's start (or to the event or
    /// action that ends it) and returns where it ended.
    #[allow(clippy::too_many_arguments)]
    fn fly_phase<A: AtmosphereModel, V: VehicleModel>(
        &mut self,
        eq: &Equations<'_, A, V>,
        settings: &FlightSettings,
        stops: &[f64],
        index: usize,
        phase: &Phase,
        kind: PhaseKind,
        (mut t, mut y): (f64, State),
    ) -> Result<(f64, State), DynamicsError> {
        let t_bound = self.schedule.get(index + 1).map_or(f64::INFINITY, |p| p.t);
        let max_step = max_step(settings, kind);
        // Whether the steps are bounded by `control_max_time_step` (in a descent, from the
        // step that reaches the ground on).
        let mut bounded = max_step <= settings.control_max_time_step;
        let mut tol = Tolerances {
            rtol: settings.rtol,
            atol: settings.atol,
            max_step,
            min_step: settings.min_time_step,
            max_steps: settings.max_steps_per_phase,
        };
        let configuration = phase.configuration;
        let mut rhs_cursors = Cursors::default();
        let rhs = move |tt: f64, uu: &State| {
            evaluate(eq, &kind, &configuration, tt, uu, &mut rhs_cursors).u_dot
        };
        let (mut policy, pair) = Policy::new(kind, t, self.events.burn_out);
        let mut integ = RungeKutta::new(pair, rhs, t, y, t_bound, tol)?;
        self.log.stats.phases += 1;
        // The phase's equations at its first point (the last point of the previous phase).
        self.log.acceleration(integ.f());
        loop {
            if let Some(pair) = policy.switch(&integ, t, t_bound) {
                self.log.stats.add(&integ);
                integ = RungeKutta::new(pair, integ.into_rhs(), t, y, t_bound, tol)?;
            }
            integ.set_stop(
                stops
                    .iter()
                    .copied()
                    .find(|&k| k > t)
                    .unwrap_or(f64::INFINITY),
            );
            let status = integ.step()?;
            // The step that finds the impact is not sampled (docs/physics.md §16.4): in a phase
            // whose steps are not bounded, a step longer than the bound that reaches the
            // ground is integrated again with bounded steps, so that the instants the last
            // step of the flight leaves unsampled are as few as in the bounded phases.
            if !bounded
                && self.events.off_rail
                && integ.y()[2] < self.events.elevation
                && integ.last_step() > settings.control_max_time_step
            {
                self.log.stats.add(&integ);
                tol.max_step = max_step.min(settings.control_max_time_step);
                let pair = integ.pair();
                integ = RungeKutta::new(pair, integ.into_rhs(), t, y, t_bound, tol)?;
                bounded = true;
                continue;
            }
            policy.accepted(&integ);
            t = integ.t();
            y = *integ.y();
            self.log.points.push(SolutionPoint {
                t,
                state: y,
                phase: kind,
                configuration,
            });
            if let Some((t_event, y_event)) = self.after_step(&mut integ, index, phase, kind)? {
                // The step's end point was replaced by the event's.
                let mut cursors = Cursors::default();
                let u_dot = evaluate(eq, &kind, &configuration, t_event, &y_event, &mut cursors);
                self.log.acceleration(&u_dot.u_dot);
                t = t_event;
                y = y_event;
                break;
            }
            // The FSAL stage is the derivative at the stored end point.
            self.log.acceleration(integ.f());
            if status == StepStatus::Finished {
                break;
            }
        }
        self.log.stats.add(&integ);
        Ok((t, y))
    }
}
