//! The step loop: phases integrated in turn, events and sampled processes checked after
//! every accepted step.

use karman_model::{AtmosphereModel, Configuration, ParachuteSpec, VehicleModel};

use super::parachute::ParachuteTrigger;
use super::phases::Phase;
use super::policy::Policy;
use super::sampled::{Instants, SampledProcess};
use super::{
    Flight, IntegrationStats, ParachuteEvent, PhaseKind, Record, SolutionPoint, Termination,
    acceleration, evaluate,
};
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
    /// In free flight at `t0` from `state` in `configuration` ([`super::simulate_from`]).
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
    /// ([`Run::sample_processes`]).
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

/// Mutable bookkeeping of a flight in progress.
pub(super) struct Run<'a> {
    pub points: Vec<SolutionPoint>,
    pub phases: Vec<Phase>,
    pub rail_exit: Option<(f64, State)>,
    pub apogee: Option<(f64, State)>,
    pub impact: Option<(f64, State)>,
    pub parachute_events: Vec<ParachuteEvent>,
    pub records: Vec<Record>,
    pub separation: Option<(f64, usize)>,
    pub tumble: Option<f64>,
    pub termination: Termination,
    /// The vehicle's parachutes (what [`super::Action::DeployDevice`] deploys).
    pub parachutes: Vec<ParachuteSpec>,
    /// The sampled processes: the parachute triggers, then the flight's own.
    pub processes: Vec<Box<dyn SampledProcess + 'a>>,
    /// Indices of the processes still sampled, in order.
    pub active: Vec<usize>,
    /// The sampling instants of the last step, one range per process that samples it.
    pub instants: Vec<Instants>,
    /// The rocket has left the rail (sampling and the apogee and impact checks start).
    pub off_rail: bool,
    /// The equations of the free flight after rail exit ([`PhaseKind::free_flight`]).
    pub free_flight: PhaseKind,
    /// Rail travel to the upper button, m.
    pub rail_travel: f64,
    /// Gravity along the rail at the pad, `g sin i`, m/s² (the coast that decides whether a
    /// rocket still on the rail at burn-out leaves it).
    pub rail_gravity: f64,
    pub elevation: f64,
    pub burn_out: f64,
    pub terminate_on_apogee: bool,
    pub stats: IntegrationStats,
    pub sampling: Sampling,
}

/// The initial attitude on the rail (docs/physics.md §2.4) and the rail travel to the upper
/// button (§8.1, RocketPy's `effective_1rl`).
fn rail_start(
    settings: &FlightSettings,
    setup: &karman_model::VehicleSetup,
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

/// Flies a vehicle from `start` with the vehicle's parachute triggers and `extra` processes.
pub(super) fn fly<'a, A: AtmosphereModel, V: VehicleModel>(
    atmosphere: &'a A,
    vehicle: &'a V,
    settings: &FlightSettings,
    start: Start,
    extra: Vec<Box<dyn SampledProcess + 'a>>,
    sampling: Sampling,
) -> Result<Flight, DynamicsError> {
    settings.validate()?;
    let eq = Equations::new(atmosphere, vehicle, settings.equations);
    let setup = vehicle.setup();
    let elevation = atmosphere.elevation();
    let (t0, u0, configuration, kind0, rail_travel) = match start {
        Start::Rail => {
            let (u0, travel) = rail_start(settings, &setup, elevation)?;
            let configuration = Configuration {
                controls: setup.initial_controls,
                ..Configuration::default()
            };
            (0.0, u0, configuration, PhaseKind::Rail, travel)
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
            (t0, state, configuration, kind, f64::NAN)
        }
    };

    let mut processes: Vec<Box<dyn SampledProcess + 'a>> = Vec::new();
    for (i, spec) in setup.parachutes.iter().enumerate() {
        let stream = NoiseStream::new(spec.noise, settings.noise_seed, i as u64);
        #[cfg(test)]
        let stream = if sampling == Sampling::BoundedStepwise {
            stream.stepwise()
        } else {
            stream
        };
        processes.push(Box::new(ParachuteTrigger::new(
            atmosphere,
            i,
            spec,
            stream,
            settings.trigger_band,
        )));
    }
    let parachutes = setup.parachutes.len();
    processes.extend(extra);
    let active = (0..processes.len())
        .filter(|&i| processes[i].rate() > 0.0 && !(i < parachutes && configuration.is_deployed(i)))
        .collect();
    let mut run = Run {
        points: vec![SolutionPoint {
            t: t0,
            state: u0,
            phase: kind0,
            configuration,
        }],
        phases: vec![
            Phase {
                t: t0,
                kind: Some(kind0),
                configuration,
                clear: false,
            },
            Phase::end(settings.max_time),
        ],
        rail_exit: None,
        apogee: None,
        impact: None,
        parachute_events: Vec::new(),
        records: Vec::new(),
        separation: None,
        tumble: None,
        termination: Termination::MaxTime,
        parachutes: setup.parachutes,
        processes,
        active,
        instants: Vec::new(),
        off_rail: kind0 != PhaseKind::Rail,
        free_flight: PhaseKind::free_flight(settings),
        rail_travel,
        rail_gravity: atmosphere.gravity(elevation) * settings.inclination_deg.to_radians().sin(),
        elevation,
        burn_out: setup.burn_out,
        terminate_on_apogee: settings.terminate_on_apogee,
        stats: IntegrationStats::default(),
        sampling,
    };

    // Steps end on the knots of the thrust curve during the burn and at burn-out: the
    // right-hand side has a kink at every knot (linear interpolation) and a jump at burn-out
    // (thrust and power-on drag stop). An embedded Runge–Kutta error estimate resolves those
    // poorly (RocketPy's LSODA, with its max-norm and many short steps, absorbs them); with
    // the steps stopped there the default tolerances give converged apogees.
    let knots: Vec<f64> = if settings.stop_at_thrust_knots {
        let (b0, b1) = (setup.burn_start, setup.burn_out);
        let mut k: Vec<f64> = setup
            .thrust_knots
            .iter()
            .copied()
            .filter(|&x| b0 < x && x < b1)
            .collect();
        k.push(b1);
        k
    } else {
        Vec::new()
    };
    let burn_out = setup.burn_out;
    let mut t = t0;
    let mut y = u0;
    let mut index = 0;
    let mut max_acceleration: f64 = 0.0;
    // Cursors of the evaluations made outside the integrators (values never depend on them).
    let mut cursors = Cursors::default();
    let eq = &eq;
    while index + 1 < run.phases.len() {
        let phase = run.phases[index];
        let Some(kind) = phase.kind else { break };
        let t_bound = run.phases[index + 1].t;
        let max_step = if kind == PhaseKind::Rail {
            settings
                .max_time_step
                .min(settings.rail_max_time_step)
                .min(settings.control_max_time_step)
        } else if kind.reads_controls() {
            settings.max_time_step.min(settings.control_max_time_step)
        } else {
            settings.max_time_step
        };
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
        let (mut policy, pair) = Policy::new(kind, t, burn_out);
        let mut integ = RungeKutta::new(pair, rhs, t, y, t_bound, tol)?;
        run.stats.phases += 1;
        // The phase's equations at its first point (the last point of the previous phase).
        max_acceleration = max_acceleration.max(acceleration(integ.f()));
        loop {
            if let Some(pair) = policy.switch(&integ, t, t_bound) {
                run.stats.add(&integ);
                integ = RungeKutta::new(pair, integ.into_rhs(), t, y, t_bound, tol)?;
            }
            integ.set_stop(
                knots
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
                && run.off_rail
                && integ.y()[2] < run.elevation
                && integ.last_step() > settings.control_max_time_step
            {
                run.stats.add(&integ);
                tol.max_step = max_step.min(settings.control_max_time_step);
                let pair = integ.pair();
                integ = RungeKutta::new(pair, integ.into_rhs(), t, y, t_bound, tol)?;
                bounded = true;
                continue;
            }
            policy.accepted(&integ);
            t = integ.t();
            y = *integ.y();
            run.points.push(SolutionPoint {
                t,
                state: y,
                phase: kind,
                configuration,
            });
            let outcome = match run.check_events(&mut integ, index, &phase, kind)? {
                Some(event) => Some(event),
                None => {
                    // A rocket on the rail has not flown: its vertical speed is ≥ 0 up to
                    // round-off (which could otherwise fire an apogee trigger), so only the
                    // processes that ask for it (controllers) are sampled on the rail.
                    let rail = kind == PhaseKind::Rail;
                    let acted = match run.sampling {
                        Sampling::Bounded => run.sample_processes(&mut integ, &phase, rail),
                        #[cfg(test)]
                        Sampling::BoundedStepwise => run.sample_processes(&mut integ, &phase, rail),
                        #[cfg(test)]
                        Sampling::Direct if rail => None,
                        #[cfg(test)]
                        Sampling::Direct => run.sample_every_instant(&mut integ, &phase),
                    };
                    acted.map(|acted| run.act(&mut integ, acted, index, &phase, kind))
                }
            };
            if let Some((t_event, y_event)) = outcome {
                // The step's end point was replaced by the event's.
                let u_dot = evaluate(eq, &kind, &configuration, t_event, &y_event, &mut cursors);
                max_acceleration = max_acceleration.max(acceleration(&u_dot.u_dot));
                t = t_event;
                y = y_event;
                break;
            }
            // The FSAL stage is the derivative at the stored end point.
            max_acceleration = max_acceleration.max(acceleration(integ.f()));
            if status == StepStatus::Finished {
                break;
            }
        }
        run.stats.add(&integ);
        index += 1;
    }

    Ok(Flight {
        points: run.points,
        rail_exit: run.rail_exit,
        apogee: run.apogee,
        impact: run.impact,
        parachute_events: run.parachute_events,
        records: run.records,
        separation: run.separation,
        tumble: run.tumble,
        termination: run.termination,
        t_final: t,
        burn_out,
        elevation,
        noise_seed: settings.noise_seed,
        equations: settings.equations,
        max_acceleration,
        stats: run.stats,
    })
}
