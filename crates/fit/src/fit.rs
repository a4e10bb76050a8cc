//! The least-squares fit of mission inputs to a flight log (the crate documentation states the
//! method).

use std::cell::{Cell, RefCell};

use karman_flightlog::{BACKOFF_MAX_S, FlightLog, SimulatedFlight, compare, first_motion_time};
use karman_mission::dispersion::Target;
use karman_mission::math::interpolate_clamped;
use karman_mission::montecarlo::{MonteCarlo, StudyOverrides};
use karman_mission::schema::{DispersionSpec, Distribution};
use karman_mission::{Mission, MissionError};
use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt, TerminationReason};
use nalgebra::storage::Owned;
use nalgebra::{DMatrix, DVector, Dyn};

use crate::bridge::simulated_flight;
use crate::error::FitError;

/// The smallest and largest factor a fit tries on a nominal value.
pub const FACTOR_RANGE: [f64; 2] = [0.2, 5.0];
/// Step of the forward differences of the Jacobian, in the logarithm of a factor (0.1 %).
const DIFFERENCE_STEP: f64 = 1e-3;
/// Largest offset of the log's clock the fit allows, s: the back-off window of the log
/// reader's liftoff rule (karman-flightlog [`BACKOFF_MAX_S`]), the most its liftoff can be
/// off by.
pub const MAX_CLOCK_OFFSET_S: f64 = BACKOFF_MAX_S;
/// A fitted clock offset beyond this, s (a few samples of a 20 Hz log), is reported: the
/// simulated ascent's timing then differs from the log's by more than the reader's liftoff
/// can explain, and the fitted values take part of that model error.
pub const NOTED_CLOCK_OFFSET_S: f64 = 0.25;
/// Step of the difference of the Jacobian in the clock offset, s.
const CLOCK_STEP_S: f64 = 1e-3;
/// Fewest log samples in a phase the fit uses.
pub const MIN_PHASE_SAMPLES: usize = 10;

/// What to fit and how long to try.
#[derive(Debug, Clone, PartialEq)]
pub struct FitOptions {
    /// The dotted input paths to fit (`rocket.power_off_drag`, `motor.total_impulse`,
    /// `rocket.parachutes.Main.cd_s`, `rocket.mass`): any input a Monte Carlo study can scale
    /// with `factor` (mission-format.md, `[dispersion]`).
    pub vary: Vec<String>,
    /// Most flights the fit may fly, the final Jacobian included.
    pub max_flights: usize,
    /// Seed of the parachute-trigger pressure noise of every flight (one seed: the fit's
    /// flights differ only in the fitted values).
    pub seed: u64,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions {
            vary: Vec::new(),
            max_flights: 100,
            seed: 0,
        }
    }
}

/// Where an input acts, and so which part of the log its residuals come from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Phase {
    /// Liftoff to apogee: the altitude at each of the log's times.
    Ascent,
    /// Under this parachute: the vertical velocity at each of the log's altitudes.
    Descent(String),
}

impl Phase {
    /// The phase of input `path`: a parachute's input acts on the descent under it, every
    /// other input on the ascent.
    #[must_use]
    pub fn of(path: &str) -> Phase {
        match path
            .strip_prefix("rocket.parachutes.")
            .and_then(|rest| rest.split('.').next())
        {
            Some(name) => Phase::Descent(name.to_owned()),
            None => Phase::Ascent,
        }
    }

    /// The unit of its residuals.
    #[must_use]
    pub fn unit(&self) -> &'static str {
        match self {
            Phase::Ascent => "m",
            Phase::Descent(_) => "m/s",
        }
    }
}

impl std::fmt::Display for Phase {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Phase::Ascent => write!(f, "ascent"),
            Phase::Descent(name) => write!(f, "descent under {name}"),
        }
    }
}

/// The nominal value of a fitted input.
#[derive(Debug, Clone, PartialEq)]
pub enum Nominal {
    /// A number.
    Number(f64),
    /// A curve (every ordinate scaled).
    Curve,
    /// An array of numbers (every component scaled).
    Array(Vec<f64>),
}

/// One fitted input.
#[derive(Debug, Clone, PartialEq)]
pub struct FittedInput {
    /// The dotted input path.
    pub path: String,
    /// Its nominal value.
    pub nominal: Nominal,
    /// The fitted factor on the nominal value.
    pub factor: f64,
    /// Its one-standard-deviation uncertainty.
    pub factor_std: f64,
}

impl FittedInput {
    /// The fitted value of a number input.
    #[must_use]
    pub fn value(&self) -> Option<f64> {
        match self.nominal {
            Nominal::Number(v) => Some(v * self.factor),
            _ => None,
        }
    }

    /// The uncertainty of [`FittedInput::value`].
    #[must_use]
    pub fn value_std(&self) -> Option<f64> {
        match self.nominal {
            Nominal::Number(v) => Some((v * self.factor_std).abs()),
            _ => None,
        }
    }
}

/// The residuals of one phase before and after the fit.
#[derive(Debug, Clone, PartialEq)]
pub struct PhaseResiduals {
    /// The phase.
    pub phase: Phase,
    /// The log samples it compares.
    pub samples: usize,
    /// RMS at the nominal values, in [`Phase::unit`].
    pub rms_before: f64,
    /// RMS at the fitted values.
    pub rms_after: f64,
}

/// The result of a fit.
#[derive(Debug, Clone, PartialEq)]
pub struct Fit {
    /// The fitted inputs, in the order asked.
    pub inputs: Vec<FittedInput>,
    /// The phases compared.
    pub phases: Vec<PhaseResiduals>,
    /// The offset of the log's clock fitted with the inputs and its uncertainty, s, when an
    /// ascent is compared: the log's time `t` from its liftoff is the simulation's `t +
    /// offset` from its own (the liftoff a reader finds in a log is uncertain by a sample or
    /// two, which would otherwise show as an altitude error of the speed times that).
    pub clock_offset_s: Option<[f64; 2]>,
    /// Flights flown.
    pub flights: usize,
    /// Whether the optimiser met its tolerances (not the flight budget or a flat objective).
    pub converged: bool,
    /// How the optimiser ended, in words.
    pub termination: String,
    /// The factor `(1 + ρ) / (1 − ρ)` by which the variances were widened for the residuals'
    /// lag-one autocorrelation `ρ` (1 for independent residuals).
    pub correlation_inflation: f64,
    /// What the user should know about the fit (a large clock offset, an input the log does
    /// not constrain).
    pub warnings: Vec<String>,
}

/// One phase's log samples: `(x, y)` with `x` the time from liftoff (ascent) or the
/// altitude (descent), `y` the altitude or the vertical velocity.
#[derive(Debug, Clone)]
struct Block {
    phase: Phase,
    points: Vec<(f64, f64)>,
    /// The weight of its residuals: one over their RMS at the nominal values.
    weight: f64,
}

/// The fit as the optimiser sees it: parameters `x = [ln f₁, …, ln fₙ]`, followed, when an
/// ascent is compared, by the offset of the log's clock (s).
struct Problem<'a> {
    study: &'a MonteCarlo,
    blocks: &'a [Block],
    /// Number of fitted inputs.
    inputs: usize,
    /// Whether the last parameter is the log's clock offset.
    shift: bool,
    x: DVector<f64>,
    /// The flight and weighted residuals at `x`.
    sim: Option<SimulatedFlight>,
    residuals: Option<DVector<f64>>,
    flights: Cell<usize>,
    budget: usize,
    failure: RefCell<Option<String>>,
    best: RefCell<Option<(f64, DVector<f64>)>>,
}

/// The factors of parameters `x` (its first `inputs` entries), clamped to [`FACTOR_RANGE`].
fn factors(x: &DVector<f64>, inputs: usize) -> Vec<f64> {
    x.iter()
        .take(inputs)
        .map(|v| v.exp().clamp(FACTOR_RANGE[0], FACTOR_RANGE[1]))
        .collect()
}

/// The log's clock offset of parameters `x`, clamped to ±[`MAX_CLOCK_OFFSET_S`].
fn clock_offset(x: &DVector<f64>, inputs: usize, shift: bool) -> f64 {
    if shift {
        x[inputs].clamp(-MAX_CLOCK_OFFSET_S, MAX_CLOCK_OFFSET_S)
    } else {
        0.0
    }
}

/// The simulated altitude above the pad at time `t` from liftoff.
fn altitude_at(sim: &SimulatedFlight, liftoff: f64, t: f64) -> f64 {
    interpolate_clamped(&sim.time_s, &sim.altitude_m, t + liftoff) - sim.altitude_m[0]
}

/// The simulated vertical velocity when the descent after apogee (the point `top`,
/// [`SimulatedFlight::apogee_index`]) first comes down to altitude `h` above the pad (the
/// last point's when it never does).
fn descent_velocity_at(sim: &SimulatedFlight, top: usize, h: f64) -> f64 {
    let pad = sim.altitude_m[0];
    for i in top + 1..sim.time_s.len() {
        let (h0, h1) = (sim.altitude_m[i - 1] - pad, sim.altitude_m[i] - pad);
        if h1 <= h && h0 >= h {
            let share = if h0 > h1 { (h0 - h) / (h0 - h1) } else { 0.0 };
            let (v0, v1) = (
                sim.vertical_velocity_mps[i - 1],
                sim.vertical_velocity_mps[i],
            );
            return v0 + share * (v1 - v0);
        }
    }
    sim.vertical_velocity_mps[sim.vertical_velocity_mps.len() - 1]
}

/// The raw (unweighted) residuals of each block for the simulated flight `sim`, the log's
/// time `t` read as `t + offset` from the simulation's liftoff: simulated minus measured.
fn block_residuals(
    sim: &SimulatedFlight,
    blocks: &[Block],
    offset: f64,
) -> Result<Vec<Vec<f64>>, FitError> {
    let liftoff = first_motion_time(&sim.time_s, &sim.altitude_m)
        .ok_or(FitError::Compare(karman_flightlog::CompareError::NoMotion))?;
    let top = sim.apogee_index();
    Ok(blocks
        .iter()
        .map(|block| {
            block
                .points
                .iter()
                .map(|&(x, y)| match block.phase {
                    Phase::Ascent => altitude_at(sim, liftoff, x + offset) - y,
                    Phase::Descent(_) => descent_velocity_at(sim, top, x) - y,
                })
                .collect()
        })
        .collect())
}

/// The residuals of `blocks`, each divided by its weight's inverse, end to end.
fn weighted(raw: &[Vec<f64>], blocks: &[Block]) -> DVector<f64> {
    DVector::from_vec(
        raw.iter()
            .zip(blocks)
            .flat_map(|(r, b)| r.iter().map(move |v| v * b.weight))
            .collect(),
    )
}

/// Flies the study's mission with `factors` and returns the flight as series.
fn fly(study: &MonteCarlo, factors: &[f64]) -> Result<SimulatedFlight, FitError> {
    let track = study.track(0, factors).map_err(FitError::Flight)?;
    let sim = simulated_flight(&track.samples, &track.summary);
    if sim.time_s.len() < 2 {
        return Err(FitError::Flight(
            "the flight stored fewer than two points".into(),
        ));
    }
    Ok(sim)
}

impl Problem<'_> {
    /// The weighted residuals of `sim` with the clock offset of `x`.
    fn residuals_of(
        &self,
        sim: &SimulatedFlight,
        x: &DVector<f64>,
    ) -> Result<DVector<f64>, String> {
        let offset = clock_offset(x, self.inputs, self.shift);
        let raw = block_residuals(sim, self.blocks, offset).map_err(|e| e.to_string())?;
        Ok(weighted(&raw, self.blocks))
    }

    /// The flight and weighted residuals at `x` (one flight), or why they could not be had.
    fn evaluate(&self, x: &DVector<f64>) -> Result<(SimulatedFlight, DVector<f64>), String> {
        if self.flights.get() >= self.budget {
            return Err(format!(
                "the flight budget ({} flights) ran out",
                self.budget
            ));
        }
        self.flights.set(self.flights.get() + 1);
        let sim = fly(self.study, &factors(x, self.inputs)).map_err(|e| e.to_string())?;
        let r = self.residuals_of(&sim, x)?;
        self.remember(x, &r);
        Ok((sim, r))
    }

    /// Keeps `x` when its residuals are the smallest yet.
    fn remember(&self, x: &DVector<f64>, r: &DVector<f64>) {
        let sse = r.norm_squared();
        let mut best = self.best.borrow_mut();
        if best.as_ref().is_none_or(|(s, _)| sse < *s) {
            *best = Some((sse, x.clone()));
        }
    }

    fn fail(&self, message: String) {
        self.failure.borrow_mut().get_or_insert(message);
    }
}

impl LeastSquaresProblem<f64, Dyn, Dyn> for Problem<'_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, x: &DVector<f64>) {
        // A step in the clock offset alone needs no flight.
        let same_flight =
            self.sim.is_some() && (0..self.inputs).all(|i| x[i].to_bits() == self.x[i].to_bits());
        let evaluated = if same_flight {
            let sim = self.sim.take().expect("checked above");
            let r = self.residuals_of(&sim, x);
            if let Ok(r) = &r {
                self.remember(x, r);
            }
            r.map(|r| (sim, r))
        } else {
            self.evaluate(x)
        };
        self.x.copy_from(x);
        match evaluated {
            Ok((sim, r)) => {
                self.sim = Some(sim);
                self.residuals = Some(r);
            }
            Err(message) => {
                self.fail(message);
                self.sim = None;
                self.residuals = None;
            }
        }
    }

    fn params(&self) -> DVector<f64> {
        self.x.clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        self.residuals.clone()
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        let base = self.residuals.as_ref()?;
        let mut jacobian = DMatrix::zeros(base.len(), self.x.len());
        for j in 0..self.x.len() {
            let mut x = self.x.clone();
            let step = if j < self.inputs {
                DIFFERENCE_STEP
            } else {
                CLOCK_STEP_S
            };
            x[j] += step;
            let column = if j < self.inputs {
                self.evaluate(&x).map(|(_, r)| r)
            } else {
                self.residuals_of(self.sim.as_ref()?, &x)
            };
            match column {
                Ok(r) => jacobian.set_column(j, &((r - base) / step)),
                Err(message) => {
                    self.fail(message);
                    return None;
                }
            }
        }
        Some(jacobian)
    }
}

/// The lag-one autocorrelation of each block's residuals, pooled, clamped to `[0, 0.99]`.
fn lag_one_correlation(blocks: &[Vec<f64>]) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for r in blocks {
        if r.len() < 3 {
            continue;
        }
        let mean = r.iter().sum::<f64>() / r.len() as f64;
        num += r
            .windows(2)
            .map(|w| (w[0] - mean) * (w[1] - mean))
            .sum::<f64>();
        den += r.iter().map(|v| (v - mean).powi(2)).sum::<f64>();
    }
    if den > 0.0 {
        (num / den).clamp(0.0, 0.99)
    } else {
        0.0
    }
}

fn rms(values: &[f64]) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    (values.iter().map(|v| v * v).sum::<f64>() / values.len() as f64).sqrt()
}

/// Refuses a request with no input, an input named twice or too small a budget.
fn check_request(options: &FitOptions) -> Result<(), FitError> {
    if options.vary.is_empty() {
        return Err(FitError::Usage(
            "name at least one input to fit (--vary PATH)".into(),
        ));
    }
    for (i, path) in options.vary.iter().enumerate() {
        if options.vary[..i].contains(path) {
            return Err(FitError::Usage(format!("`{path}` is named twice")));
        }
    }
    let n = options.vary.len();
    if options.max_flights < 2 * (n + 1) {
        return Err(FitError::Usage(format!(
            "a fit of {n} input(s) needs a budget of at least {} flights",
            2 * (n + 1)
        )));
    }
    Ok(())
}

/// The study that flies `mission` with a factor on each input of `options.vary` (the
/// machinery applies them exactly as a Monte Carlo draw would), and the inputs' nominal
/// values.
fn prepare(
    mission: &Mission,
    options: &FitOptions,
) -> Result<(MonteCarlo, Vec<Nominal>), FitError> {
    let mut scaled = mission.clone();
    scaled.spec.dispersion = Some(DispersionSpec {
        samples: 1,
        seed: options.seed,
        vary: options
            .vary
            .iter()
            .map(|p| {
                let unit = Distribution::Normal([1.0, 0.0]);
                (p.clone(), Distribution::Factor(Box::new(unit)))
            })
            .collect(),
    });
    // The machinery's errors about the study it was handed are about the inputs asked for,
    // not about a `[dispersion]` table of the file.
    let study = MonteCarlo::new(&scaled, StudyOverrides::default()).map_err(|e| match e {
        MissionError::Model {
            section, source, ..
        } if section == "dispersion" => FitError::Usage(source.to_string()),
        other => FitError::Mission(other),
    })?;
    let mut nominals = Vec::with_capacity(options.vary.len());
    for (path, input) in options.vary.iter().zip(&study.study().inputs) {
        nominals.push(match &input.target {
            Target::Number(v) if v.is_finite() && *v != 0.0 => Nominal::Number(*v),
            Target::Number(v) => {
                return Err(FitError::Input {
                    input: path.clone(),
                    reason: format!("its nominal value {v} cannot be scaled"),
                });
            }
            Target::Curve => Nominal::Curve,
            Target::Array(values) => Nominal::Array(values.clone()),
            Target::Integer(_) => {
                return Err(FitError::Input {
                    input: path.clone(),
                    reason: "an integer input cannot be fitted".into(),
                });
            }
        });
    }
    Ok((study, nominals))
}

/// The log's samples of each phase the inputs `vary` act on, their weights left at 1: the
/// ascent from liftoff to the log's apogee, and each parachute's altitude band after apogee
/// (from the `nominal` flight's comparison with the log).
fn phase_blocks(
    nominal: &SimulatedFlight,
    log: &FlightLog,
    vary: &[String],
) -> Result<Vec<Block>, FitError> {
    let comparison = compare(nominal, log)?;
    let mut phases: Vec<Phase> = Vec::new();
    for path in vary {
        let phase = Phase::of(path);
        if !phases.contains(&phase) {
            phases.push(phase);
        }
    }
    let apogee_time = comparison.measured.apogee_time_s;
    let mut blocks = Vec::with_capacity(phases.len());
    for phase in phases {
        let points: Vec<(f64, f64)> = match &phase {
            Phase::Ascent => log
                .samples
                .iter()
                .filter(|s| (0.0..=apogee_time).contains(&s.time_s))
                .map(|s| (s.time_s, s.altitude_agl_m))
                .collect(),
            Phase::Descent(name) => {
                let band = comparison
                    .descent
                    .iter()
                    .find(|d| &d.parachute == name)
                    .map(|d| d.band_m)
                    .ok_or_else(|| FitError::Input {
                        input: format!("rocket.parachutes.{name}"),
                        reason: "the parachute does not open in the simulated flight, so \
                                 nothing in the log shows its effect"
                            .into(),
                    })?;
                log.samples
                    .iter()
                    .filter(|s| s.time_s > apogee_time)
                    .filter(|s| (band[0]..=band[1]).contains(&s.altitude_agl_m))
                    .map(|s| (s.altitude_agl_m, s.vertical_velocity_mps))
                    .collect()
            }
        };
        if points.len() < MIN_PHASE_SAMPLES {
            return Err(FitError::TooFewSamples {
                phase: phase.to_string(),
                samples: points.len(),
                needed: MIN_PHASE_SAMPLES,
            });
        }
        blocks.push(Block {
            phase,
            points,
            weight: 1.0,
        });
    }
    Ok(blocks)
}

/// The optimiser's result: the best parameters, flights flown, whether it converged and
/// how it ended, in words.
struct Optimised {
    x: DVector<f64>,
    flights: usize,
    converged: bool,
    termination: String,
}

/// Levenberg–Marquardt from the nominal values (and the comparison's clock), starting from
/// the `nominal` flight and its weighted residuals `start`, within `budget` flights; `shift`:
/// the log's clock offset is a parameter after the inputs.
fn optimise(
    study: &MonteCarlo,
    blocks: &[Block],
    inputs: usize,
    nominal: SimulatedFlight,
    start: DVector<f64>,
    budget: usize,
    shift: bool,
) -> Result<Optimised, FitError> {
    let parameters = inputs + usize::from(shift);
    let problem = Problem {
        study,
        blocks,
        inputs,
        shift,
        x: DVector::zeros(parameters),
        best: RefCell::new(Some((start.norm_squared(), DVector::zeros(parameters)))),
        sim: Some(nominal),
        residuals: Some(start),
        flights: Cell::new(1),
        budget,
        failure: RefCell::new(None),
    };
    let optimiser = LevenbergMarquardt::new()
        .with_ftol(1e-8)
        .with_xtol(1e-6)
        .with_gtol(1e-10)
        .with_stepbound(0.5)
        .with_patience(budget.div_ceil(inputs + 1).max(1));
    let (problem, report) = optimiser.minimize(problem);
    let flights = problem.flights.get();
    let failure = problem.failure.borrow().clone();
    let best = problem.best.borrow().as_ref().map(|(_, x)| x.clone());
    let Some(x) = best else {
        return Err(FitError::Flight(
            failure.unwrap_or_else(|| "the optimiser flew no flight".into()),
        ));
    };
    let (converged, termination) = match &report.termination {
        TerminationReason::User(_) => (
            false,
            failure.unwrap_or_else(|| "the optimiser stopped".into()),
        ),
        TerminationReason::LostPatience => (false, "the flight budget ran out".into()),
        TerminationReason::Converged { ftol, xtol } => (
            true,
            format!(
                "converged ({})",
                match (ftol, xtol) {
                    (true, true) => "objective and values",
                    (true, false) => "objective",
                    _ => "values",
                }
            ),
        ),
        TerminationReason::Orthogonal => (true, "converged (gradient)".into()),
        TerminationReason::ResidualsZero => (true, "converged (no residual)".into()),
        other => (false, format!("{other:?}")),
    };
    Ok(Optimised {
        x,
        flights,
        converged,
        termination,
    })
}

/// What [`uncertainty`] finds at the best values.
struct Spread {
    /// The standard deviation of each parameter.
    sigma: Vec<f64>,
    /// The raw residuals of each block.
    after: Vec<Vec<f64>>,
    /// The variance inflation for correlated residuals.
    inflation: f64,
    /// Flights flown.
    flights: usize,
}

/// The uncertainty at the best values `x`: the Jacobian of the weighted residuals by forward
/// differences (`inputs` flights and one for the residuals), `s² = Σr²/(m − p)`, `cov = s²
/// (JᵀJ)⁻¹` widened for correlated residuals.
fn uncertainty(
    study: &MonteCarlo,
    blocks: &[Block],
    inputs: usize,
    x: &DVector<f64>,
    shift: bool,
) -> Result<Spread, FitError> {
    let parameters = x.len();
    let mut last = Problem {
        study,
        blocks,
        inputs,
        shift,
        x: x.clone(),
        sim: None,
        residuals: None,
        flights: Cell::new(0),
        budget: inputs + 1,
        failure: RefCell::new(None),
        best: RefCell::new(None),
    };
    let (sim, base) = last.evaluate(x).map_err(FitError::Flight)?;
    last.sim = Some(sim);
    last.residuals = Some(base.clone());
    let jacobian = last
        .jacobian()
        .ok_or_else(|| FitError::Flight(last.failure.borrow().clone().unwrap_or_default()))?;
    let m = base.len();
    let s2 = base.norm_squared() / (m.saturating_sub(parameters).max(1)) as f64;
    let mut weighted_after: Vec<Vec<f64>> = Vec::with_capacity(blocks.len());
    let mut from = 0;
    for block in blocks {
        let to = from + block.points.len();
        weighted_after.push(base.as_slice()[from..to].to_vec());
        from = to;
    }
    let after: Vec<Vec<f64>> = weighted_after
        .iter()
        .zip(blocks)
        .map(|(r, b)| r.iter().map(|v| v / b.weight).collect())
        .collect();
    let rho = lag_one_correlation(&weighted_after);
    let inflation = (1.0 + rho) / (1.0 - rho);
    let normal = jacobian.transpose() * &jacobian;
    let covariance = normal.try_inverse().map(|inv| inv * (s2 * inflation));
    let sigma = (0..parameters)
        .map(|i| {
            covariance
                .as_ref()
                .map_or(f64::INFINITY, |c| c[(i, i)].max(0.0).sqrt())
        })
        .collect();
    Ok(Spread {
        sigma,
        after,
        inflation,
        flights: last.flights.get(),
    })
}

/// Fits the inputs `options.vary` of `mission` to `log` (crate documentation: residuals,
/// weights, optimiser, uncertainty).
///
/// # Errors
/// [`FitError`]: no input or one twice, an input that is not a scalable number, curve or
/// array, a parachute that does not open in the simulation, too few log samples in a phase,
/// a flight that fails.
pub fn fit(mission: &Mission, log: &FlightLog, options: &FitOptions) -> Result<Fit, FitError> {
    check_request(options)?;
    let n = options.vary.len();
    let (study, nominals) = prepare(mission, options)?;
    let nominal = fly(&study, &vec![1.0; n])?;
    let mut blocks = phase_blocks(&nominal, log, &options.vary)?;
    let before = block_residuals(&nominal, &blocks, 0.0)?;
    for (block, r) in blocks.iter_mut().zip(&before) {
        block.weight = 1.0 / rms(r).max(1e-6);
    }
    // One flight is kept back per input for the final Jacobian and one for the final
    // residuals; the nominal flight counts as the first.
    let budget = options.max_flights - 1 - n - 1;
    let start = weighted(&before, &blocks);
    // The log's clock offset is fitted with the inputs when an ascent is compared.
    let shift = blocks.iter().any(|b| b.phase == Phase::Ascent);
    let optimised = optimise(&study, &blocks, n, nominal, start, budget, shift)?;
    let x = &optimised.x;
    let Spread {
        sigma,
        after,
        inflation,
        flights: final_flights,
    } = uncertainty(&study, &blocks, n, x, shift)?;
    let fitted = factors(x, n);
    let inputs: Vec<FittedInput> = options
        .vary
        .iter()
        .zip(nominals)
        .enumerate()
        .map(|(i, (path, nominal))| FittedInput {
            path: path.clone(),
            nominal,
            factor: fitted[i],
            factor_std: fitted[i] * sigma[i],
        })
        .collect();
    let phases = blocks
        .iter()
        .zip(before.iter().zip(&after))
        .map(|(b, (r0, r1))| PhaseResiduals {
            phase: b.phase.clone(),
            samples: b.points.len(),
            rms_before: rms(r0),
            rms_after: rms(r1),
        })
        .collect();
    let offset = clock_offset(x, n, shift);
    let mut warnings = Vec::new();
    if shift && offset.abs() > NOTED_CLOCK_OFFSET_S {
        warnings.push(format!(
            "the log's clock is {offset:+.2} s off the simulation's{}: more than the log's \
             liftoff can be off by, so the simulated ascent's timing differs from the log's \
             (thrust curve, ignition, rail) and the fitted values take part of that",
            if offset.abs() >= MAX_CLOCK_OFFSET_S * (1.0 - 1e-9) {
                " (at its bound)"
            } else {
                ""
            }
        ));
    }
    if sigma.iter().any(|s| !s.is_finite()) {
        warnings.push(
            "an uncertainty is infinite: the log does not constrain that input (or a factor \
             or the clock offset ended at its bound)"
                .to_owned(),
        );
    }
    Ok(Fit {
        inputs,
        phases,
        clock_offset_s: shift.then(|| [offset, sigma[n]]),
        flights: optimised.flights + final_flights,
        converged: optimised.converged,
        termination: optimised.termination,
        correlation_inflation: inflation,
        warnings,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inputs_act_on_their_phase() {
        assert_eq!(Phase::of("rocket.power_off_drag"), Phase::Ascent);
        assert_eq!(Phase::of("motor.total_impulse"), Phase::Ascent);
        assert_eq!(
            Phase::of("rocket.parachutes.Main.cd_s"),
            Phase::Descent("Main".into())
        );
        assert_eq!(
            Phase::Descent("Main".into()).to_string(),
            "descent under Main"
        );
    }

    #[test]
    fn factors_stay_in_their_range() {
        let x = DVector::from_vec(vec![0.0, 10.0, -10.0, 0.5f64.ln()]);
        let f = factors(&x, 4);
        assert!((f[0] - 1.0).abs() < 1e-15);
        assert!((f[1] - FACTOR_RANGE[1]).abs() < 1e-15);
        assert!((f[2] - FACTOR_RANGE[0]).abs() < 1e-15);
        assert!((f[3] - 0.5).abs() < 1e-15);
    }

    #[test]
    fn correlation_of_white_and_smooth_residuals() {
        // Alternating residuals: negative correlation, clamped to 0.
        let alternating: Vec<f64> = (0..100)
            .map(|i| if i % 2 == 0 { 1.0 } else { -1.0 })
            .collect();
        assert!(lag_one_correlation(&[alternating]).abs() < 1e-15);
        // A slow sine: correlation near 1.
        let smooth: Vec<f64> = (0..1000).map(|i| (f64::from(i) * 0.01).sin()).collect();
        assert!(lag_one_correlation(&[smooth]) > 0.9);
    }

    #[test]
    fn descent_velocity_is_read_at_the_altitude() {
        let sim = SimulatedFlight {
            time_s: vec![0.0, 10.0, 20.0, 30.0, 40.0],
            altitude_m: vec![5.0, 505.0, 1005.0, 505.0, 5.0],
            vertical_velocity_mps: vec![0.0, 50.0, 0.0, -50.0, -50.0],
            vertical_acceleration_mps2: vec![0.0; 5],
            deployments: Vec::new(),
            landing: None,
        };
        // 250 m above the pad on the way down: between 500 m (-50) and 0 m (-50).
        assert!((descent_velocity_at(&sim, sim.apogee_index(), 250.0) + 50.0).abs() < 1e-12);
        // 750 m: halfway from apogee (0) to 500 m (-50).
        assert!((descent_velocity_at(&sim, sim.apogee_index(), 750.0) + 25.0).abs() < 1e-12);
        // The pad-relative ascent altitude.
        assert!((altitude_at(&sim, 0.0, 5.0) - 250.0).abs() < 1e-12);
    }
}
