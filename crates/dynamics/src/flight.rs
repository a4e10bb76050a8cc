//! Flight phases, time nodes and events (physics.md §9), RocketPy's `Flight.__simulate`.
//!
//! A flight is an ordered list of phases, each integrated by a fresh
//! [`RungeKutta`] integrator from its start to the next phase's start (a hard time node): DOPRI5
//! on the rail, through the burn and under parachutes, DOP853 for the unpowered 6-DOF flight
//! from burn-out (restarted there) unless its steps keep being rejected, a sign of kinks in the
//! right-hand side such as linearly interpolated atmosphere profiles, where DOPRI5 takes over;
//! under a parachute, once DOPRI5's steps are held back by stability (three steps in a row
//! with `h|λ| ≥ 3`), the Runge–Kutta–Chebyshev method takes over for the rest of the phase
//! (see [`crate::integrator`] for the measurements). After every
//! accepted step the engine stores the point and checks, in RocketPy's order, (a) rail exit
//! (§9.2, Hermite root of `|Δr|² − L₁²`), (b) apogee (§9.3, linear root of `v_z`), (c) impact
//! (§9.5, Hermite root of `z − elevation`), then (d) the parachute sampling instants that fell
//! inside the step (overshootable nodes evaluated on the dense output, §9.4). Events that
//! create phases insert them after the current one and roll the last point back to the event.
//!
//! Within a phase, steps also end on every thrust-curve knot of the burn and at burn-out
//! ([`FlightSettings::stop_at_thrust_knots`]): without those stops a DOPRI5 step at
//! the default tolerances straddles the kinks of a jagged thrust curve and the apogee drifts by
//! up to ~0.1 % (Valetudo), with them every validation apogee is within 0.02 % of RocketPy's.
//!
//! Parachute sampling (§9.4, RocketPy's `__process_overshootable_nodes`): the instants `j / f`
//! of every pending parachute inside a step are merged in time order on the fly (no node list,
//! no sort), instants within 1e-7 s of each other forming one group evaluated at its first
//! instant, exactly as a sorted, merged node list would be. Most steps cannot fire any trigger,
//! and bounds over the step prove it without evaluating the instants (see `sample_parachutes`):
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
//! - a rocket still at rest on the rail after burn-out can never leave it (the rail
//!   acceleration is clipped at zero), so the flight ends there with
//!   [`Termination::StuckOnRail`] instead of integrating a motionless state to `max_time`;
//! - parachute sampling and the impact check start at rail exit: on the rail `v_z ≥ 0` and
//!   `z ≥ elevation` hold up to round-off, which must not fire an apogee trigger or an impact;
//! - the impact check also runs on the step that detects apogee (see `after_step`).

use crate::DynamicsError;
use crate::equations::{CanopyState, Derivative, Equations};
use crate::integrator::{Pair, RungeKutta, StepStatus, Tolerances};
use crate::model::{AtmosphereModel, ParachuteSpec, TriggerKind, VehicleModel};
use crate::noise::NoiseStream;
use crate::settings::FlightSettings;
use crate::state::{State, euler313_to_quaternion};

/// DOP853 gives way to DOPRI5 for the rest of a phase once more than one in this many of
/// its attempted steps were rejected (a right-hand side with kinks).
const KINK_WINDOW: usize = 8;

/// Under a parachute DOPRI5 gives way to the Runge–Kutta–Chebyshev method once this many
/// accepted steps in a row had `h |λ|` ([`RungeKutta::stiffness`]) of at least
/// [`STIFF_BOUND`]…
const STIFF_STEPS: usize = 3;
/// …90 % of the reach of DOPRI5's stability region along the negative real axis (≈ 3.3): the
/// steps are then held back by stability, not accuracy.
const STIFF_BOUND: f64 = 3.0;

/// Which equations of motion a phase integrates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PhaseKind {
    /// 1-DOF slide along the rail (physics.md §8.1).
    Rail,
    /// 6-DOF variable-mass flight (§8.2).
    SixDof,
    /// 3-DOF descent under the given canopy (§8.4).
    Parachute(CanopyState),
}

/// A flight phase: start time, equations, and whether sampling instants at its start are
/// skipped (RocketPy's `clear`).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Phase {
    t: f64,
    kind: Option<PhaseKind>,
    clear: bool,
}

/// One stored solution point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolutionPoint {
    /// Time, s.
    pub t: f64,
    /// State (physics.md §3).
    pub state: State,
    /// Equations in force for this point (RocketPy assigns a point to the phase with
    /// `t_start < t ≤ t_end`).
    pub phase: PhaseKind,
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
    /// Still at rest on the rail after burn-out: the motor cannot lift the rocket.
    StuckOnRail,
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
fn acceleration(u_dot: &State) -> f64 {
    (u_dot[3] * u_dot[3] + u_dot[4] * u_dot[4] + u_dot[5] * u_dot[5]).sqrt()
}

/// Evaluates the equations of a phase.
#[inline]
pub(crate) fn evaluate<A: AtmosphereModel, V: VehicleModel>(
    eq: &Equations<'_, A, V>,
    kind: &PhaseKind,
    t: f64,
    u: &State,
) -> Derivative {
    match kind {
        PhaseKind::Rail => eq.rail(t, u),
        PhaseKind::SixDof => eq.six_dof(t, u),
        PhaseKind::Parachute(canopy) => eq.parachute(t, u, canopy),
    }
}

/// Real root in `(0, h)` of the cubic Hermite interpolant with values `y0, y1` and slopes
/// `yp0, yp1` at `0, h` (physics.md §9.2, §9.5), by bisection on the cubic (the end values
/// bracket a sign change by construction of the events).
fn hermite_root(h: f64, y0: f64, yp0: f64, y1: f64, yp1: f64) -> Option<f64> {
    let bracketed = h > 0.0 && y0 * y1 <= 0.0; // false for NaN too
    if !bracketed {
        return None;
    }
    // p(τ) = a τ³ + b τ² + c τ + d.
    let d = y0;
    let c = yp0;
    let b = (3.0 * (y1 - y0) / h - 2.0 * yp0 - yp1) / h;
    let a = (yp0 + yp1 - 2.0 * (y1 - y0) / h) / (h * h);
    let p = |x: f64| ((a * x + b) * x + c) * x + d;
    let (mut lo, mut hi) = (0.0, h);
    let mut plo = p(lo);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        let pm = p(mid);
        if (pm <= 0.0) == (plo <= 0.0) && pm != 0.0 {
            lo = mid;
            plo = pm;
        } else {
            hi = mid;
        }
    }
    Some(0.5 * (lo + hi))
}

/// Inserts a phase before index `index` keeping start times strictly increasing; ties are
/// shifted by 1e-7 s as RocketPy's `FlightPhases.add` does. A phase at or after the final
/// bound is dropped (the flight ends first).
fn insert_phase(phases: &mut Vec<Phase>, mut index: usize, mut phase: Phase) {
    let Some(end) = phases.last().map(|p| p.t) else {
        return;
    };
    loop {
        if phase.t >= end {
            return;
        }
        if index == 0 {
            index = 1;
        }
        if index >= phases.len() {
            index = phases.len() - 1;
        }
        let prev = phases[index - 1].t;
        let next = phases[index].t;
        if prev < phase.t && phase.t < next {
            phases.insert(index, phase);
            return;
        }
        let tie = (phase.t - prev).abs() < f64::MIN_POSITIVE
            || (phase.t - next).abs() < f64::MIN_POSITIVE;
        let new_index = if phase.t < prev {
            index - 1
        } else if phase.t > next {
            index + 1
        } else {
            index
        };
        if tie {
            phase.t += 1e-7;
        }
        index = new_index;
    }
}

/// Key of a sampling instant rounded to 1e-7 s (RocketPy's `TimeNodes.merge`): `(t·1e7)`
/// rounded half away from zero, as `f64::round` does, without its libm call (x86-64 has no
/// rounding instruction before SSE4.1, and the noisy triggers key every sampling instant).
#[inline]
fn node_key(t: f64) -> i64 {
    let x = t * 1e7;
    if x.abs() >= 4_503_599_627_370_496.0 {
        // Already an integer (or infinite: the cast saturates, as after `round`).
        return x as i64;
    }
    // Below 2^52 the truncation and the fraction it leaves are exact. Branch-free: the
    // fraction's side of ±0.5 is as unpredictable as a coin (a NaN's key stays 0).
    let whole = x as i64;
    let fraction = x - whole as f64;
    whole + i64::from(fraction >= 0.5) - i64::from(fraction <= -0.5)
}

/// Mutable bookkeeping of a flight in progress.
struct Run {
    points: Vec<SolutionPoint>,
    phases: Vec<Phase>,
    rail_exit: Option<(f64, State)>,
    apogee: Option<(f64, State)>,
    impact: Option<(f64, State)>,
    parachute_events: Vec<ParachuteEvent>,
    termination: Termination,
    pending: Vec<usize>,
    streams: Vec<NoiseStream>,
    /// The sampling instants of the last step, one range per parachute that samples it.
    instants: Vec<Instants>,
    /// Per parachute: the ASL height below which a noise-free height trigger fires.
    thresholds: Vec<Option<f64>>,
    /// [`FlightSettings::trigger_band`], m.
    band: f64,
    stats: IntegrationStats,
    sampling: Sampling,
}

/// How the parachute sampling instants of a step are evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Sampling {
    /// Steps in which no trigger can fire are passed over with bounds ([`Run::sample_parachutes`]).
    Bounded,
    /// [`Sampling::Bounded`] with the noise streams drawn at every skipped instant instead of
    /// jumping over them (the tests compare it with [`Sampling::Direct`] bit for bit).
    #[cfg(test)]
    BoundedStepwise,
    /// Every instant of every pending parachute evaluated directly, as a sorted node list
    /// (the tests' reference).
    #[cfg(test)]
    Direct,
}

/// The sampling instants `j · interval`, `j = next..=last`, of one parachute in the last step.
#[derive(Debug, Clone, Copy)]
struct Instants {
    /// Parachute index.
    p: usize,
    /// Sampling interval `1 / f`, s.
    interval: f64,
    /// Next instant to evaluate.
    next: i64,
    /// Last instant to evaluate.
    last: i64,
    /// The noise stream is advanced at every instant (a noisy height trigger).
    draws: bool,
    /// First instant at which the trigger may fire: the bounds exclude the instants before
    /// it (`last + 1` when they exclude the whole step).
    first_candidate: i64,
    /// Instants passed over whose noise has not been drawn yet ([`NoiseStream::skip`] jumps
    /// over them in one draw when the stream is next read, or when the step ends).
    undrawn: usize,
}

impl Instants {
    /// Time of instant `j`, s (computed as RocketPy's node list does, `j · Δ`).
    #[inline]
    fn time(&self, j: i64) -> f64 {
        j as f64 * self.interval
    }

    /// Number of instants left.
    #[inline]
    fn count(&self) -> usize {
        usize::try_from(self.last - self.next + 1).unwrap_or(0)
    }

    /// Whether the trigger may fire at one of the instants left.
    #[inline]
    fn may_fire(&self) -> bool {
        self.first_candidate <= self.last
    }
}

/// The ASL height `z` where a noise-free height trigger switches, `h_baro(P(z)) − elevation =
/// height_agl`, by bisection (both functions are monotone); `None` if not bracketed.
fn trigger_height<A: AtmosphereModel>(atm: &A, elevation: f64, height_agl: f64) -> Option<f64> {
    let g = |z: f64| atm.barometric_height(atm.pressure(z)) - elevation - height_agl;
    let guess = elevation + height_agl;
    let (mut lo, mut hi) = (guess - 1000.0, guess + 1000.0);
    let (g_lo, g_hi) = (g(lo), g(hi));
    let bracketed = g_lo < 0.0 && g_hi > 0.0;
    if !bracketed {
        return None;
    }
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if g(mid) < 0.0 { lo = mid } else { hi = mid }
    }
    Some(0.5 * (lo + hi))
}

/// Resolution of the height above which a noisy height trigger is out of reach within a step,
/// as a fraction of [`FlightSettings::trigger_band`].
const REACH_RESOLUTION: f64 = 0.01;

/// The lowest height in `(low, high]`, to `resolution`, at which the monotone predicate
/// `out_of_reach` (false at `low`, and once true, true at every greater height) holds; `None`
/// if it does not hold at `high`. Bisection: the answer is a height where the predicate was
/// evaluated true, so every height at or above it is out of reach.
fn reach_height(
    low: f64,
    high: f64,
    resolution: f64,
    out_of_reach: impl Fn(f64) -> bool,
) -> Option<f64> {
    if !out_of_reach(high) {
        return None;
    }
    let (mut lo, mut hi) = (low, high);
    while hi - lo > resolution {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if out_of_reach(mid) {
            hi = mid
        } else {
            lo = mid
        }
    }
    Some(hi)
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
    fly(atmosphere, vehicle, settings, Sampling::Bounded)
}

/// [`simulate`] with a choice of parachute sampling.
fn fly<A: AtmosphereModel, V: VehicleModel>(
    atmosphere: &A,
    vehicle: &V,
    settings: &FlightSettings,
    sampling: Sampling,
) -> Result<Flight, DynamicsError> {
    settings.validate()?;
    let eq = Equations::new(atmosphere, vehicle);
    let elevation = atmosphere.elevation();
    let csys = vehicle.csys();
    let buttons = vehicle.rail_buttons();

    // Initial attitude (physics.md §2.4).
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

    // Effective rail length to the upper button (physics.md §8.1, RocketPy `effective_1rl`).
    let nozzle = vehicle.nozzle_position();
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

    let specs = vehicle.parachutes();
    let streams = specs
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let stream = NoiseStream::new(p.noise, settings.noise_seed, i as u64);
            #[cfg(test)]
            let stream = if sampling == Sampling::BoundedStepwise {
                stream.stepwise()
            } else {
                stream
            };
            stream
        })
        .collect();
    let mut run = Run {
        points: vec![SolutionPoint {
            t: 0.0,
            state: u0,
            phase: PhaseKind::Rail,
        }],
        phases: vec![
            Phase {
                t: 0.0,
                kind: Some(PhaseKind::Rail),
                clear: false,
            },
            Phase {
                t: settings.max_time,
                kind: None,
                clear: true,
            },
        ],
        rail_exit: None,
        apogee: None,
        impact: None,
        parachute_events: Vec::new(),
        termination: Termination::MaxTime,
        pending: (0..specs.len())
            .filter(|&i| specs[i].sampling_rate > 0.0)
            .collect(),
        streams,
        instants: Vec::new(),
        thresholds: specs
            .iter()
            .map(|p| match p.trigger {
                TriggerKind::Apogee => None,
                TriggerKind::HeightAboveGround(h) => trigger_height(atmosphere, elevation, h),
            })
            .collect(),
        band: settings.trigger_band,
        stats: IntegrationStats::default(),
        sampling,
    };

    // Steps end on the knots of the thrust curve during the burn and at burn-out: the
    // right-hand side has a kink at every knot (linear interpolation) and a jump at burn-out
    // (thrust and power-on drag stop). An embedded Runge–Kutta error estimate resolves those
    // poorly (RocketPy's LSODA, with its max-norm and many short steps, absorbs them); with
    // the steps stopped there the default tolerances give converged apogees.
    let knots: Vec<f64> = if settings.stop_at_thrust_knots {
        let (b0, b1) = (vehicle.burn_start(), vehicle.burn_out());
        let mut k: Vec<f64> = vehicle
            .thrust_knots()
            .into_iter()
            .filter(|&x| b0 < x && x < b1)
            .collect();
        k.push(b1);
        k
    } else {
        Vec::new()
    };
    let burn_out = vehicle.burn_out();
    let mut t = 0.0;
    let mut y = u0;
    let mut index = 0;
    let mut max_acceleration: f64 = 0.0;
    while index + 1 < run.phases.len() {
        let phase = run.phases[index];
        let Some(kind) = phase.kind else { break };
        let t_bound = run.phases[index + 1].t;
        let max_step = if kind == PhaseKind::Rail {
            settings.max_time_step.min(settings.rail_max_time_step)
        } else {
            settings.max_time_step
        };
        let tol = Tolerances {
            rtol: settings.rtol,
            atol: settings.atol,
            max_step,
            min_step: settings.min_time_step,
            max_steps: settings.max_steps_per_phase,
        };
        let rhs = |tt: f64, uu: &State| evaluate(&eq, &kind, tt, uu).u_dot;
        // DOPRI5 on the rail, through the burn and under parachutes until its steps are bound
        // by stability, then RKC; DOP853 for the unpowered 6-DOF flight (see the integrator's
        // overview for why).
        let mut burning = kind == PhaseKind::SixDof && t < burn_out;
        let pair = match kind {
            PhaseKind::SixDof if !burning => Pair::Dop853,
            _ => Pair::Dopri5,
        };
        let mut integ = RungeKutta::new(pair, rhs, t, y, t_bound, tol)?;
        let mut stiff_steps = 0;
        run.stats.phases += 1;
        // The phase's equations at its first point (the last point of the previous phase).
        max_acceleration = max_acceleration.max(acceleration(integ.f()));
        loop {
            if burning && t >= burn_out && t < t_bound {
                // The unpowered rest of the phase goes on with the eighth-order pair.
                burning = false;
                run.stats.add(&integ);
                integ = RungeKutta::new(Pair::Dop853, rhs, t, y, t_bound, tol)?;
            } else if integ.pair() == Pair::Dop853 && t < t_bound {
                let (rejected, tried) = (
                    integ.rejected_steps(),
                    integ.steps() + integ.rejected_steps(),
                );
                if tried >= KINK_WINDOW && rejected * KINK_WINDOW > tried {
                    run.stats.add(&integ);
                    integ = RungeKutta::new(Pair::Dopri5, rhs, t, y, t_bound, tol)?;
                }
            } else if stiff_steps >= STIFF_STEPS && t < t_bound {
                // The rest of the descent goes on with the stabilized pair.
                stiff_steps = 0;
                run.stats.add(&integ);
                integ = RungeKutta::new(Pair::Rkc2, rhs, t, y, t_bound, tol)?;
            }
            integ.set_stop(
                knots
                    .iter()
                    .copied()
                    .find(|&k| k > t)
                    .unwrap_or(f64::INFINITY),
            );
            let status = integ.step()?;
            if matches!(kind, PhaseKind::Parachute(_)) && integ.pair() == Pair::Dopri5 {
                stiff_steps = if integ.stiffness() >= STIFF_BOUND {
                    stiff_steps + 1
                } else {
                    0
                };
            }
            t = integ.t();
            y = *integ.y();
            run.points.push(SolutionPoint {
                t,
                state: y,
                phase: kind,
            });
            let outcome = run.after_step(
                &mut integ,
                &eq,
                &specs,
                index,
                phase,
                kind,
                settings,
                rail_travel,
                elevation,
            )?;
            if let Some((t_event, y_event)) = outcome {
                // The step's end point was replaced by the event's.
                let u_dot = evaluate(&eq, &kind, t_event, &y_event).u_dot;
                max_acceleration = max_acceleration.max(acceleration(&u_dot));
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
        termination: run.termination,
        t_final: t,
        burn_out: vehicle.burn_out(),
        elevation,
        noise_seed: settings.noise_seed,
        max_acceleration,
        stats: run.stats,
    })
}

impl Run {
    /// Ends the flight at the current phase: every later phase is replaced by a final bound
    /// at `t`.
    fn end_flight(&mut self, index: usize, t: f64, termination: Termination) {
        self.phases.truncate(index + 1);
        self.phases.push(Phase {
            t,
            kind: None,
            clear: true,
        });
        self.termination = termination;
    }

    /// Event checks after an accepted step (physics.md §9.1 step 4). Returns the state the
    /// next phase starts from when the current phase ends here.
    #[allow(clippy::too_many_arguments)]
    fn after_step<A: AtmosphereModel, V: VehicleModel, F: FnMut(f64, &State) -> State>(
        &mut self,
        integ: &mut RungeKutta<13, F>,
        eq: &Equations<'_, A, V>,
        specs: &[ParachuteSpec],
        index: usize,
        phase: Phase,
        kind: PhaseKind,
        settings: &FlightSettings,
        rail_travel: f64,
        elevation: f64,
    ) -> Result<Option<(f64, State)>, DynamicsError> {
        let n = self.points.len();
        let prev = self.points[n - 2];
        let last = self.points[n - 1];
        let (t0, y0) = (prev.t, prev.state);
        let (t1, y1) = (last.t, last.state);

        // (a) Rail exit.
        if self.rail_exit.is_none() {
            let dr = |u: &State| [u[0], u[1], u[2] - elevation];
            let f = |u: &State| {
                let d = dr(u);
                d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - rail_travel * rail_travel
            };
            let fp = |u: &State| {
                let d = dr(u);
                2.0 * (d[0] * u[3] + d[1] * u[4] + d[2] * u[5])
            };
            if f(&y1) >= 0.0 {
                let h = t1 - t0;
                let tau = hermite_root(h, f(&y0), fp(&y0), f(&y1), fp(&y1)).ok_or(
                    DynamicsError::EventRoot {
                        event: "rail exit",
                        t0,
                        t1,
                    },
                )?;
                let t_exit = t0 + tau;
                let y_exit = integ.dense(t_exit);
                self.points[n - 1] = SolutionPoint {
                    t: t_exit,
                    state: y_exit,
                    phase: kind,
                };
                self.rail_exit = Some((t_exit, y_exit));
                insert_phase(
                    &mut self.phases,
                    index + 1,
                    Phase {
                        t: t_exit,
                        kind: Some(PhaseKind::SixDof),
                        clear: true,
                    },
                );
                return Ok(Some((t_exit, y_exit)));
            }
            // A rocket at rest on the rail after burn-out never leaves it.
            let burn_out = eq.vehicle().burn_out();
            if kind == PhaseKind::Rail && t1 > burn_out && y1[3..6].iter().all(|v| v.abs() == 0.0) {
                self.end_flight(index, t1, Termination::StuckOnRail);
                return Ok(Some((t1, y1)));
            }
        }
        // (b) Apogee.
        if self.apogee.is_none() && self.rail_exit.is_some() && y1[5] < 0.0 {
            let (vz0, vz1) = (y0[5], y1[5]);
            let t_apogee = t0 - vz0 * (t1 - t0) / (vz1 - vz0);
            let y_apogee = integ.dense(t_apogee);
            self.apogee = Some((t_apogee, y_apogee));
            if settings.terminate_on_apogee {
                self.points[n - 1] = SolutionPoint {
                    t: t_apogee,
                    state: y_apogee,
                    phase: kind,
                };
                self.end_flight(index, t_apogee, Termination::Apogee);
                return Ok(Some((t_apogee, y_apogee)));
            }
            if n > 2 {
                self.points.insert(
                    n - 1,
                    SolutionPoint {
                        t: t_apogee,
                        state: y_apogee,
                        phase: kind,
                    },
                );
            }
        }
        // RocketPy skips the impact check on the apogee step; a step that spans both (a
        // ballistic arc in vacuum) would then never find the ground, so it is checked here.
        // On the rail the height cannot fall below the pad; only round-off (the fifth-order
        // weights include a negative one) could make it, so the check starts at rail exit.
        if self.rail_exit.is_some() && y1[2] < elevation {
            // (c) Impact.
            let h = t1 - t0;
            let tau = hermite_root(h, y0[2] - elevation, y0[5], y1[2] - elevation, y1[5]).ok_or(
                DynamicsError::EventRoot {
                    event: "impact",
                    t0,
                    t1,
                },
            )?;
            let t_impact = t0 + tau;
            let y_impact = integ.dense(t_impact);
            let last_index = self.points.len() - 1;
            self.points[last_index] = SolutionPoint {
                t: t_impact,
                state: y_impact,
                phase: kind,
            };
            self.impact = Some((t_impact, y_impact));
            self.end_flight(index, t_impact, Termination::Impact);
            return Ok(Some((t_impact, y_impact)));
        }
        // (d) Parachute sampling instants inside the step.
        match self.sampling {
            Sampling::Bounded => {
                Ok(self.sample_parachutes(integ, eq, specs, index, phase, kind, elevation))
            }
            #[cfg(test)]
            Sampling::BoundedStepwise => {
                Ok(self.sample_parachutes(integ, eq, specs, index, phase, kind, elevation))
            }
            #[cfg(test)]
            Sampling::Direct => {
                Ok(self.sample_every_instant(integ, eq, specs, index, phase, kind, elevation))
            }
        }
    }

    /// Bounds `[low, high]` of `v_z` and of `z` over the last step: the end values widened by a
    /// generous allowance (`h · max|derivative|` at the ends) for the dense output between
    /// them.
    fn step_bounds<F>(integ: &RungeKutta<13, F>) -> ([f64; 2], [f64; 2]) {
        let (y0, y1) = (integ.y_old(), integ.y());
        let (f0, f1) = (integ.f_old(), integ.f());
        let h = integ.last_step();
        let bounds = |a: f64, b: f64, slope: f64| [a.min(b) - h * slope, a.max(b) + h * slope];
        (
            bounds(y0[5], y1[5], f0[5].abs().max(f1[5].abs())),
            bounds(y0[2], y1[2], y0[5].abs().max(y1[5].abs())),
        )
    }

    /// Whether a silent (noise-free) parachute certainly cannot fire inside the last step, so
    /// that it has no sampling instants there: both triggers need `v_z < 0`, a height trigger
    /// also `z` below its threshold ([`Run::step_bounds`]).
    fn cannot_fire<F>(&self, p: usize, integ: &RungeKutta<13, F>) -> bool {
        if !self.streams[p].is_silent() {
            return false;
        }
        let ([vz_low, _], [z_low, _]) = Self::step_bounds(integ);
        if vz_low > 0.0 {
            return true;
        }
        match self.thresholds[p] {
            Some(z_threshold) => z_low > z_threshold + self.band,
            None => false,
        }
    }

    /// Overshootable parachute nodes of the last step (physics.md §9.4, RocketPy's
    /// `__process_overshootable_nodes`).
    ///
    /// The instants of each parachute are the `j · Δ` whose 1e-7 s keys lie in the step
    /// (`[t_start, t_end]`); the first group is cleared on the start of a `clear` phase and the
    /// group at the step end is left to the next step. They are merged in time order (ties in
    /// parachute order) and grouped by key, which is the order and grouping of RocketPy's
    /// sorted, merged node list. Before any instant is evaluated each parachute's trigger is
    /// bounded over the step: it cannot fire if `v_z > 0` throughout ([`Run::step_bounds`]), and a
    /// noisy height trigger cannot fire if even the highest possible pressure, `P(z_low)` plus
    /// the noise stream's bound on its coming values ([`NoiseStream::upper_bound`]), reads a
    /// barometric height at least the band ([`FlightSettings::trigger_band`]) above its
    /// threshold (`h_baro` and `P` decrease with their arguments; the band absorbs round-off and
    /// interpolation wiggles).
    /// When no parachute can fire the noisy streams jump past the step's instants
    /// ([`NoiseStream::skip`], one draw each) and nothing else is evaluated; otherwise the
    /// instants are evaluated in order, those of excluded parachutes only advancing their
    /// streams.
    #[allow(clippy::too_many_arguments)]
    fn sample_parachutes<A: AtmosphereModel, V: VehicleModel, F: FnMut(f64, &State) -> State>(
        &mut self,
        integ: &mut RungeKutta<13, F>,
        eq: &Equations<'_, A, V>,
        specs: &[ParachuteSpec],
        index: usize,
        phase: Phase,
        kind: PhaseKind,
        elevation: f64,
    ) -> Option<(f64, State)> {
        // A rocket on the rail has not flown: its vertical speed is ≥ 0 up to round-off
        // (which could otherwise fire an apogee trigger), so sampling starts at rail exit.
        if self.pending.is_empty() || kind == PhaseKind::Rail {
            return None;
        }
        let n = self.points.len();
        let t_start = self.points[n - 2].t;
        let t_end = self.points[n - 1].t;
        // The instants of this step by their keys, so that one at the step end is deferred to
        // the next step and found there whatever the rounding of t/Δ (a quotient a hair above
        // an integer lost it, and shifted the trigger noise).
        let (k_start, k_end) = (node_key(t_start), node_key(t_end));
        self.instants.clear();
        let mut first = f64::INFINITY;
        for i in 0..self.pending.len() {
            let p = self.pending[i];
            if self.cannot_fire(p, integ) {
                continue;
            }
            let mut range = Instants {
                p,
                interval: 1.0 / specs[p].sampling_rate,
                next: 0,
                last: 0,
                draws: matches!(specs[p].trigger, TriggerKind::HeightAboveGround(_))
                    && !self.streams[p].is_silent(),
                first_candidate: 0,
                undrawn: 0,
            };
            // The keys grow with j: the instants in the window form one run of j.
            range.next = (t_start / range.interval).floor() as i64 - 1;
            range.last = (t_end / range.interval).ceil() as i64 + 1;
            while range.next <= range.last && node_key(range.time(range.next)) < k_start {
                range.next += 1;
            }
            while range.last >= range.next && node_key(range.time(range.last)) > k_end {
                range.last -= 1;
            }
            if range.count() > 0 {
                first = first.min(range.time(range.next));
                self.instants.push(range);
            }
        }
        if self.instants.is_empty() {
            return None;
        }
        // The first group is cleared when it sits on the start of a `clear` phase; the group
        // at the step end is evaluated with the next step.
        let first_key = node_key(first);
        let skip_first = phase.clear && (first - phase.t).abs() < 1e-9;
        let ([vz_low, vz_high], [z_low, z_high]) = Self::step_bounds(integ);
        let descending = vz_low <= 0.0 || vz_low.is_nan();
        let atm = eq.atmosphere();
        // A noisy height trigger cannot fire where even the highest possible noisy pressure
        // (the clean pressure at `z` plus the stream's bound) reads a barometric height at
        // least the band above the trigger height.
        let band = self.band;
        let out_of_reach = |z: f64, bound: f64, h: f64| {
            atm.barometric_height(atm.pressure(z) + bound) - elevation >= h + band
        };
        let mut any_may_fire = false;
        for range in &mut self.instants {
            while skip_first
                && range.next <= range.last
                && node_key(range.time(range.next)) == first_key
            {
                range.next += 1;
            }
            while range.last >= range.next && node_key(range.time(range.last)) == k_end {
                range.last -= 1;
            }
            range.first_candidate = if !descending {
                range.last + 1
            } else {
                match specs[range.p].trigger {
                    TriggerKind::HeightAboveGround(h) if range.draws => {
                        let bound = self.streams[range.p].upper_bound();
                        if out_of_reach(z_low, bound, h) {
                            range.last + 1
                        } else {
                            // The step reaches down to the band: pass over the instants that
                            // are still out of reach at their own height, i.e. above the
                            // lowest height `z_reach` found out of reach (the predicate grows
                            // with `z`: `P` and `h_baro` both decrease).
                            let mut j = range.next;
                            let resolution = REACH_RESOLUTION * band;
                            if let Some(z_reach) = reach_height(z_low, z_high, resolution, |z| {
                                out_of_reach(z, bound, h)
                            }) {
                                if vz_high < 0.0 {
                                    // Falling throughout: the dense heights decrease with j,
                                    // so the first instant below `z_reach` is found by
                                    // bisection (a long step holds hundreds of instants).
                                    let mut end = range.last + 1;
                                    while j < end {
                                        let mid = j + (end - j) / 2;
                                        if integ.dense_component(range.time(mid), 2) >= z_reach {
                                            j = mid + 1;
                                        } else {
                                            end = mid;
                                        }
                                    }
                                } else {
                                    while j <= range.last
                                        && integ.dense_component(range.time(j), 2) >= z_reach
                                    {
                                        j += 1;
                                    }
                                }
                            }
                            j
                        }
                    }
                    // Apogee triggers, and noise-free height triggers that `cannot_fire` has
                    // already bounded.
                    _ => range.next,
                }
            };
            any_may_fire |= range.may_fire();
        }
        if !any_may_fire {
            for range in &self.instants {
                if range.draws {
                    self.streams[range.p].skip(range.count());
                }
            }
            return None;
        }
        if let [range] = self.instants.as_mut_slice() {
            // One parachute: the instants before its first candidate are passed over at once
            // (with several, they still take part in the grouping of the instants by key).
            let passed = range.first_candidate.min(range.last + 1) - range.next;
            if passed > 0 {
                range.next += passed;
                if range.draws {
                    range.undrawn += usize::try_from(passed).unwrap_or(0);
                }
            }
        }
        let mut group_key = None;
        let mut t_node = 0.0;
        let (mut z, mut vz, mut pressure) = (None, None, None);
        let fired = loop {
            // The earliest instant left; ties go to the earlier parachute.
            let mut earliest: Option<(usize, f64)> = None;
            for (k, range) in self.instants.iter().enumerate() {
                if range.next > range.last {
                    continue;
                }
                let t = range.time(range.next);
                if earliest.is_none_or(|(_, t_min)| t < t_min) {
                    earliest = Some((k, t));
                }
            }
            // None once every instant is evaluated: nothing fired.
            let Some((k, t)) = earliest else {
                break None;
            };
            let range = &mut self.instants[k];
            let j = range.next;
            range.next += 1;
            let key = node_key(t);
            if group_key != Some(key) {
                group_key = Some(key);
                t_node = t;
                (z, vz, pressure) = (None, None, None);
            }
            let p = range.p;
            if j < range.first_candidate {
                if range.draws {
                    range.undrawn += 1;
                }
                continue;
            }
            let noise = if range.draws {
                let stream = &mut self.streams[p];
                stream.skip(std::mem::take(&mut range.undrawn));
                stream.next_value()
            } else {
                0.0
            };
            let vz_node = *vz.get_or_insert_with(|| integ.dense_component(t_node, 5));
            let fires = vz_node < 0.0
                && match specs[p].trigger {
                    TriggerKind::Apogee => true,
                    TriggerKind::HeightAboveGround(h) => {
                        let z_node = *z.get_or_insert_with(|| integ.dense_component(t_node, 2));
                        match self.thresholds[p] {
                            // Noise-free: compare heights directly, away from the threshold.
                            Some(zt) if noise == 0.0 && (z_node - zt).abs() > band => z_node < zt,
                            _ => {
                                let p_clean = *pressure.get_or_insert_with(|| atm.pressure(z_node));
                                atm.barometric_height(p_clean + noise) - elevation < h
                            }
                        }
                    }
                };
            if fires {
                break Some(p);
            }
        };
        // The noise of the instants passed over is drawn (as one jump per stream) up to the
        // instant that fired, or to the step end.
        for range in &mut self.instants {
            self.streams[range.p].skip(std::mem::take(&mut range.undrawn));
        }
        fired.map(|p| self.fire(integ, specs, p, index, kind, t_node))
    }

    /// Deploys parachute `p` at `t_node` inside the last step and cuts the step there.
    fn fire<F: FnMut(f64, &State) -> State>(
        &mut self,
        integ: &mut RungeKutta<13, F>,
        specs: &[ParachuteSpec],
        p: usize,
        index: usize,
        kind: PhaseKind,
        t_node: f64,
    ) -> (f64, State) {
        let y_node = integ.dense(t_node);
        self.deploy(&specs[p], p, index, kind, t_node);
        let n = self.points.len();
        self.points[n - 1] = SolutionPoint {
            t: t_node,
            state: y_node,
            phase: kind,
        };
        (t_node, y_node)
    }

    /// Schedules a triggered parachute: an optional lag phase with the current equations,
    /// then the parachute phase (physics.md §9.4).
    fn deploy(
        &mut self,
        spec: &ParachuteSpec,
        p: usize,
        index: usize,
        kind: PhaseKind,
        t_node: f64,
    ) {
        self.pending.retain(|&q| q != p);
        let mut at = index + 1;
        if spec.lag != 0.0 {
            insert_phase(
                &mut self.phases,
                at,
                Phase {
                    t: t_node,
                    kind: Some(kind),
                    clear: true,
                },
            );
            at += 1;
        }
        let canopy = CanopyState {
            cd_s: spec.cd_s,
            radius: spec.radius,
            height: spec.height,
            added_mass_coefficient: spec.added_mass_coefficient,
        };
        insert_phase(
            &mut self.phases,
            at,
            Phase {
                t: t_node + spec.lag,
                kind: Some(PhaseKind::Parachute(canopy)),
                clear: false,
            },
        );
        // Without lag the parachute phase starts right at the node: it must follow the current
        // phase, which the insertion above guarantees.
        self.parachute_events.push(ParachuteEvent {
            name: spec.name.clone(),
            trigger_time: t_node,
            inflation_time: t_node + spec.lag,
        });
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn node_keys_round_as_f64_round() {
        let mut times = vec![
            0.0,
            -0.0,
            1e-8,
            5e-8,
            1.5e-7,
            2.5e-7,
            -2.5e-7,
            0.123_456_75,
            1e300,
        ];
        times.extend([
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            4.503_599_627_370_497e8,
        ]);
        // Halves and their neighbours at many scales, and a dense sweep.
        for k in 0..2000 {
            let half = (f64::from(k) + 0.5) * 1e-7 * 1.37f64.powi(k % 60);
            times.extend([half, f64::from_bits(half.to_bits() + 1), -half]);
            times.push(f64::from(k) * 0.012_345_678_9);
        }
        for t in times {
            assert_eq!(super::node_key(t), (t * 1e7).round() as i64, "{t}");
        }
    }

    use super::*;

    /// The reference the bounded sampling must agree with: every instant of every pending
    /// parachute collected into a node list, sorted, grouped by key and evaluated in order
    /// (every noisy stream drawn at each of its instants), with no bounds.
    impl Run {
        #[allow(clippy::too_many_arguments)]
        pub(super) fn sample_every_instant<
            A: AtmosphereModel,
            V: VehicleModel,
            F: FnMut(f64, &State) -> State,
        >(
            &mut self,
            integ: &mut RungeKutta<13, F>,
            eq: &Equations<'_, A, V>,
            specs: &[ParachuteSpec],
            index: usize,
            phase: Phase,
            kind: PhaseKind,
            elevation: f64,
        ) -> Option<(f64, State)> {
            if self.pending.is_empty() || kind == PhaseKind::Rail {
                return None;
            }
            let n = self.points.len();
            let (t_start, t_end) = (self.points[n - 2].t, self.points[n - 1].t);
            let (k_start, k_end) = (node_key(t_start), node_key(t_end));
            let mut nodes: Vec<(f64, usize)> = Vec::new();
            for &p in &self.pending {
                let interval = 1.0 / specs[p].sampling_rate;
                let j0 = (t_start / interval).floor() as i64 - 1;
                let j1 = (t_end / interval).ceil() as i64 + 1;
                for j in j0..=j1 {
                    let t = j as f64 * interval;
                    if (k_start..=k_end).contains(&node_key(t)) {
                        nodes.push((t, p));
                    }
                }
            }
            if nodes.is_empty() {
                return None;
            }
            nodes.sort_by(|a, b| a.0.total_cmp(&b.0));
            let first_key = node_key(nodes[0].0);
            let skip_first = phase.clear && (nodes[0].0 - phase.t).abs() < 1e-9;
            let atm = eq.atmosphere();
            for &(t, p) in &nodes {
                let key = node_key(t);
                if key == k_end {
                    break;
                }
                if skip_first && key == first_key {
                    continue;
                }
                // The group is evaluated at its first instant.
                let t_node = nodes
                    .iter()
                    .find(|m| node_key(m.0) == key)
                    .map_or(t, |m| m.0);
                let z = integ.dense_component(t_node, 2);
                let vz = integ.dense_component(t_node, 5);
                let noise = self.streams[p].next_value();
                let fired = vz < 0.0
                    && match specs[p].trigger {
                        TriggerKind::Apogee => true,
                        TriggerKind::HeightAboveGround(h) => {
                            atm.barometric_height(atm.pressure(z) + noise) - elevation < h
                        }
                    };
                if fired {
                    return Some(self.fire(integ, specs, p, index, kind, t_node));
                }
            }
            None
        }
    }

    use crate::mock::{MockAtmosphere, MockRocket};

    /// The test atmosphere: the mock's, with a constant wind (2, −1) m/s.
    fn air() -> MockAtmosphere {
        MockAtmosphere {
            wind: [2.0, -1.0],
            ..MockAtmosphere::default()
        }
    }

    /// The mock's stable rocket with `parachutes`.
    fn rocket(parachutes: Vec<ParachuteSpec>) -> MockRocket {
        MockRocket {
            parachutes,
            ..MockRocket::stable()
        }
    }

    /// A parachute with the given trigger, rate, lag and noise.
    fn chute(
        name: &str,
        trigger: TriggerKind,
        rate: f64,
        lag: f64,
        noise: [f64; 3],
    ) -> ParachuteSpec {
        ParachuteSpec {
            name: name.into(),
            cd_s: if trigger == TriggerKind::Apogee {
                0.5
            } else {
                2.0
            },
            trigger,
            sampling_rate: rate,
            lag,
            noise,
            radius: 0.5,
            height: 0.5,
            added_mass_coefficient: 1.0,
        }
    }

    fn fly_with(parachutes: Vec<ParachuteSpec>, seed: u64, sampling: Sampling) -> Flight {
        let mut settings = FlightSettings::new(3.0);
        settings.inclination_deg = 86.0;
        settings.noise_seed = seed;
        fly(&air(), &rocket(parachutes), &settings, sampling).expect("flies")
    }

    /// Calisto's trigger noise, Pa.
    const CALISTO_NOISE: [f64; 3] = [0.0, 8.3, 0.5];

    #[test]
    fn stiff_descent_is_finished_by_chebyshev_steps_at_terminal_speed() {
        // The 10 kg rocket under a 2 m² canopy from apogee: the drag relaxes the descent speed
        // at 2g/v ≈ 2/s, which holds DOPRI5 to ≈ 1.5 s steps; RKC takes over and lands at the
        // terminal speed √(2mg/(ρ C_dS)) (the wind is constant, so the canopy drifts with it),
        // up to the lag of the speed behind the density change (≈ 3e-4 of it here).
        let main = ParachuteSpec {
            cd_s: 2.0,
            ..chute("main", TriggerKind::Apogee, 100.0, 0.0, [0.0; 3])
        };
        let flight = fly_with(vec![main], 1, Sampling::BoundedStepwise);
        assert!(flight.stats.chebyshev_steps > 0, "{:?}", flight.stats);
        let (_, state) = flight.impact.expect("lands");
        let (atm, body) = (air(), MockRocket::stable());
        let terminal = (2.0 * body.dry_mass * atm.g / (atm.density(state[2]) * 2.0)).sqrt();
        assert!(
            (-state[5] / terminal - 1.0).abs() < 1e-3,
            "{} vs {terminal}",
            -state[5]
        );
        for (v, w) in state[3..5].iter().zip(atm.wind) {
            assert!((v - w).abs() < 1e-3 * terminal, "drift {v} vs wind {w}");
        }
    }

    #[test]
    fn max_acceleration_is_the_largest_at_the_stored_points() {
        // The definition the FSAL shortcut replaces: the equations evaluated at every stored
        // point, and the next phase's equations at each phase boundary (the canopy peak).
        // A main canopy so large that its opening shock is the largest acceleration of the
        // flight, at the first instant of its phase.
        let chutes = || {
            let mut main = chute(
                "main",
                TriggerKind::HeightAboveGround(300.0),
                100.0,
                0.0,
                [0.0; 3],
            );
            main.cd_s = 400.0;
            vec![
                chute("drogue", TriggerKind::Apogee, 100.0, 1.0, [0.0; 3]),
                main,
            ]
        };
        let flight = fly_with(chutes(), 0, Sampling::Bounded);
        assert_eq!(flight.parachute_events.len(), 2);
        let (air, rocket) = (air(), rocket(chutes()));
        let eq = Equations::new(&air, &rocket);
        let at =
            |kind: &PhaseKind, t: f64, u: &State| acceleration(&evaluate(&eq, kind, t, u).u_dot);
        let mut expected: f64 = 0.0;
        for p in &flight.points {
            expected = expected.max(at(&p.phase, p.t, &p.state));
        }
        for w in flight.points.windows(2) {
            if w[0].phase != w[1].phase {
                expected = expected.max(at(&w[1].phase, w[0].t, &w[0].state));
            }
        }
        // The same evaluations (the FSAL stage is taken at the stored point's time).
        assert!(
            (flight.max_acceleration - expected).abs() <= 1e-12 * expected,
            "{} vs {expected}",
            flight.max_acceleration
        );
    }

    #[test]
    fn noisy_flight_replays_bit_for_bit() {
        let chutes = || {
            vec![
                chute(
                    "main",
                    TriggerKind::HeightAboveGround(300.0),
                    105.0,
                    1.5,
                    CALISTO_NOISE,
                ),
                chute("drogue", TriggerKind::Apogee, 105.0, 1.5, CALISTO_NOISE),
            ]
        };
        let a = fly_with(chutes(), 11, Sampling::Bounded);
        let b = fly_with(chutes(), 11, Sampling::Bounded);
        assert_eq!(a.parachute_events.len(), 2);
        let bits = |f: &Flight| {
            f.points
                .iter()
                .flat_map(|p| std::iter::once(p.t).chain(p.state))
                .map(f64::to_bits)
                .collect::<Vec<_>>()
        };
        assert_eq!(bits(&a), bits(&b));
        assert_eq!(a, b);
    }

    #[test]
    fn bounded_sampling_decides_as_direct_evaluation() {
        // Apogee of this rocket with no parachute, m above the pad.
        let ballistic = fly_with(Vec::new(), 0, Sampling::Bounded);
        let apogee_agl = ballistic.apogee.expect("apogee").1[2] - 100.0;
        let height = TriggerKind::HeightAboveGround;
        let cases: Vec<(&str, Vec<ParachuteSpec>)> = vec![
            (
                "Calisto-like, equal rates",
                vec![
                    chute("main", height(300.0), 105.0, 1.5, CALISTO_NOISE),
                    chute("drogue", TriggerKind::Apogee, 105.0, 1.5, CALISTO_NOISE),
                ],
            ),
            (
                "unequal rates, no lag, silent drogue",
                vec![
                    chute("drogue", TriggerKind::Apogee, 100.0, 0.0, [0.0; 3]),
                    chute("main", height(250.0), 30.0, 0.0, [2.0, 40.0, 0.8]),
                ],
            ),
            (
                // 0.3 m below apogee, with 8.3 Pa (~0.7 m) of noise: fires at apogee or not.
                "height trigger at the apogee threshold",
                vec![
                    chute("high", height(apogee_agl - 0.3), 100.0, 0.0, CALISTO_NOISE),
                    chute("low", height(200.0), 105.0, 1.0, CALISTO_NOISE),
                    chute("quiet", height(120.0), 10.0, 0.0, [0.0; 3]),
                ],
            ),
            (
                "two noisy height triggers, one without lag",
                vec![
                    chute("upper", height(400.0), 20.0, 0.0, [0.0, 300.0, 0.5]),
                    chute("lower", height(150.0), 50.0, 0.7, [1.0, 300.0, 0.0]),
                ],
            ),
        ];
        let mut high_triggers = Vec::new();
        for (name, chutes) in &cases {
            for seed in 0..6 {
                let bounded = fly_with(chutes.clone(), seed, Sampling::BoundedStepwise);
                let direct = fly_with(chutes.clone(), seed, Sampling::Direct);
                assert!(
                    !bounded.parachute_events.is_empty(),
                    "{name}, seed {seed}: nothing fired"
                );
                assert_eq!(
                    bounded.parachute_events, direct.parachute_events,
                    "{name}, seed {seed}"
                );
                // The reference asks for dense values in more steps: DOP853 steps among them
                // make their three extra evaluations, which change no value.
                assert!(bounded.stats.evaluations <= direct.stats.evaluations);
                let direct = Flight {
                    stats: IntegrationStats {
                        evaluations: bounded.stats.evaluations,
                        ..direct.stats
                    },
                    ..direct
                };
                assert_eq!(bounded, direct, "{name}, seed {seed}");
                let apogee_t = bounded.apogee.expect("apogee").0;
                high_triggers.extend(
                    bounded
                        .parachute_events
                        .iter()
                        .filter(|e| e.name == "high")
                        .map(|e| e.trigger_time - apogee_t),
                );
            }
        }
        // The threshold case must depend on the draws to test anything.
        assert!(
            high_triggers
                .iter()
                .any(|&dt| (dt - high_triggers[0]).abs() > 1e-6),
            "high trigger instants after apogee {high_triggers:?}"
        );
    }

    #[test]
    fn hermite_root_of_a_cubic() {
        // p(τ) = τ³ − 0.5 on [0, 1]: root 0.5^(1/3).
        let r = hermite_root(1.0, -0.5, 0.0, 0.5, 3.0).unwrap();
        assert!((r - 0.5f64.cbrt()).abs() < 1e-12);
        assert!(hermite_root(1.0, 1.0, 0.0, 2.0, 0.0).is_none());
    }

    #[test]
    fn phases_stay_sorted_and_ties_shift() {
        let mut phases = vec![
            Phase {
                t: 0.0,
                kind: Some(PhaseKind::Rail),
                clear: false,
            },
            Phase {
                t: 600.0,
                kind: None,
                clear: true,
            },
        ];
        insert_phase(
            &mut phases,
            1,
            Phase {
                t: 0.4,
                kind: Some(PhaseKind::SixDof),
                clear: true,
            },
        );
        insert_phase(
            &mut phases,
            2,
            Phase {
                t: 0.4,
                kind: Some(PhaseKind::SixDof),
                clear: true,
            },
        );
        insert_phase(
            &mut phases,
            1,
            Phase {
                t: 700.0,
                kind: Some(PhaseKind::SixDof),
                clear: true,
            },
        );
        let ts: Vec<f64> = phases.iter().map(|p| p.t).collect();
        assert_eq!(ts.len(), 4);
        assert!(ts.windows(2).all(|w| w[0] < w[1]), "{ts:?}");
        assert!((ts[2] - 0.4 - 1e-7).abs() < 1e-12);
    }
}
