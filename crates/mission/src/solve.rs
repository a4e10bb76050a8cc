//! `karman solve`: the value of one input of a mission that makes one summary output reach a
//! target (`--target apogee_agl_m=3048 --vary rocket.mass`), by Brent's bracketing root
//! finder on `g(x) = output(x) − target` (docs/montecarlo.md, "Solving for a target").
//!
//! Brent's method (R. P. Brent, *Algorithms for Minimization without Derivatives*, 1973,
//! ch. 4; the form of Press et al., *Numerical Recipes*, 3rd ed., §9.3), written here: the
//! root stays bracketed by `[b, c]` with `g(b) g(c) ≤ 0`, `b` the best estimate; each step
//! tries inverse quadratic interpolation through the last three points (the secant through
//! two when they coincide) and takes it only when it falls within the bracket's inner three
//! quarters and shrinks faster than half the step before last; otherwise it bisects. So it
//! converges superlinearly on a smooth output and never slower than bisection (to a factor
//! of about two), whatever the flight's noise. One evaluation is one flight; the two bounds
//! are the first two.
//!
//! A trial flies the mission with the input set through the Monte Carlo machinery (a study
//! of one input drawn with zero spread, [`MonteCarlo::fly`]), so every input a study can vary
//! can be solved for, with the sample's parachute-noise seed.

use crate::Mission;
use crate::montecarlo::{MonteCarlo, StudyOverrides};
use crate::schema::{DispersionSpec, Distribution};
use karman_dispersion::{Status, Target};
use thiserror::Error;

/// Errors of a solve.
#[derive(Debug, Error)]
pub enum SolveError {
    /// The mission's models cannot be built, or the input cannot be varied.
    #[error(transparent)]
    Mission(#[from] crate::MissionError),
    /// The request is not valid (bounds reversed, an unknown output, a bad tolerance).
    #[error("{0}")]
    Invalid(String),
    /// A trial flight failed or ended early.
    #[error("the flight with {input} = {value} {reason}")]
    Flight {
        /// The varied input.
        input: String,
        /// Its trial value.
        value: f64,
        /// What happened.
        reason: String,
    },
    /// The target lies outside the outputs at the bounds: no value within them reaches it.
    #[error(
        "no value of {input} within [{low}, {high}] reaches {output} = {target}: it is {at_low} \
         at {input} = {low} and {at_high} at {input} = {high} (both on one side of the target); \
         widen --bounds or change the target"
    )]
    NotBracketed {
        /// The varied input.
        input: String,
        /// The output.
        output: String,
        /// The target.
        target: f64,
        /// The bounds.
        low: f64,
        /// The bounds.
        high: f64,
        /// The output at the lower bound.
        at_low: f64,
        /// The output at the upper bound.
        at_high: f64,
    },
    /// The flight budget ran out before the tolerance was met.
    #[error(
        "{output} is {achieved} at {input} = {value} after {flights} flights, {miss} from the \
         target {target}: not within the tolerance {tolerance}; raise --max-flights or the \
         tolerance"
    )]
    NotConverged {
        /// The varied input.
        input: String,
        /// The output.
        output: String,
        /// The target.
        target: f64,
        /// The best value found.
        value: f64,
        /// The output there.
        achieved: f64,
        /// Its distance to the target.
        miss: f64,
        /// The tolerance asked for.
        tolerance: f64,
        /// Flights flown.
        flights: usize,
    },
}

/// What to solve.
#[derive(Debug, Clone, PartialEq)]
pub struct SolveOptions {
    /// The input, by dotted path (`rocket.mass`, `motor.total_impulse`).
    pub vary: String,
    /// The summary output (`apogee_agl_m`).
    pub output: String,
    /// The output's target value.
    pub target: f64,
    /// The bracket `[low, high]` searched; default the nominal value ∓ 50 % (∓ 1 for a zero
    /// nominal).
    pub bounds: Option<[f64; 2]>,
    /// How close to the target the output must come, in the output's units.
    pub tolerance: f64,
    /// Most flights.
    pub max_flights: usize,
    /// The seed of the flights' parachute noise (sample 0 of a study with this seed).
    pub seed: u64,
}

impl SolveOptions {
    /// The defaults for `vary` and `output = target`: tolerance 0.01, at most 30 flights,
    /// seed 0.
    pub fn new(vary: impl Into<String>, output: impl Into<String>, target: f64) -> Self {
        SolveOptions {
            vary: vary.into(),
            output: output.into(),
            target,
            bounds: None,
            tolerance: 0.01,
            max_flights: 30,
            seed: 0,
        }
    }
}

/// The value found.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Solution {
    /// The input.
    pub input: String,
    /// Its value that reaches the target.
    pub value: f64,
    /// The input's nominal value in the mission.
    pub nominal: f64,
    /// The output.
    pub output: String,
    /// The target.
    pub target: f64,
    /// The output at `value`.
    pub achieved: f64,
    /// The bracket searched.
    pub bounds: [f64; 2],
    /// Flights flown.
    pub flights: usize,
    /// Every trial: `[input value, output]`, in the order flown.
    pub trials: Vec<[f64; 2]>,
    /// The method, stated.
    pub method: String,
}

/// The method as [`Solution::method`] states it.
pub const METHOD: &str = "Brent's bracketing root finder (Brent 1973, ch. 4): inverse quadratic \
    interpolation or secant steps inside the bracket, bisection otherwise; one flight per step";

/// The request's own checks: a finite target, a positive tolerance, room for the two
/// bounds, and `--vary` naming one real number of the mission.
fn check_request(mission: &Mission, options: &SolveOptions) -> Result<(), SolveError> {
    let invalid = |reason: String| SolveError::Invalid(reason);
    if !(options.target.is_finite()) {
        return Err(invalid(format!(
            "the target {} = {} is not a finite number",
            options.output, options.target
        )));
    }
    if !(options.tolerance.is_finite() && options.tolerance > 0.0) {
        return Err(invalid(format!(
            "the tolerance must be a positive number, got {}",
            options.tolerance
        )));
    }
    if options.max_flights < 2 {
        return Err(invalid(format!(
            "a bracketing search needs at least 2 flights (the bounds), got --max-flights {}",
            options.max_flights
        )));
    }
    // What the path names, said in the solve's own terms before the study machinery sees it.
    match crate::paths::resolve(&mission.spec, &options.vary) {
        Err(error) => return Err(invalid(format!("--vary {}: {error}", options.vary))),
        Ok(crate::paths::Input::Number { integer: true, .. }) => {
            return Err(invalid(format!(
                "--vary {}: an integer (a count or an index); solve varies one real number",
                options.vary
            )));
        }
        Ok(crate::paths::Input::Curve(_) | crate::paths::Input::Table(_)) => {
            return Err(invalid(format!(
                "--vary {}: a curve; solve varies one real number",
                options.vary
            )));
        }
        Ok(crate::paths::Input::Array(_)) => {
            return Err(invalid(format!(
                "--vary {}: an array; solve one component by its index, `{}.0`",
                options.vary, options.vary
            )));
        }
        Ok(crate::paths::Input::Number { .. } | crate::paths::Input::Knob(_)) => {}
    }
    Ok(())
}

/// The one-sample study that flies each trial value of `--vary`: the study, the input's
/// nominal value and the column of `--target`'s output.
fn trial_study(
    mission: &Mission,
    options: &SolveOptions,
) -> Result<(MonteCarlo, f64, usize), SolveError> {
    let invalid = |reason: String| SolveError::Invalid(reason);
    let mut trial = mission.clone();
    trial.spec.dispersion = Some(DispersionSpec {
        samples: 1,
        seed: options.seed,
        vary: [(options.vary.clone(), Distribution::Std(0.0))].into(),
    });
    let study = MonteCarlo::new(&trial, StudyOverrides::default())?;
    let definition = study.study();
    let nominal = match definition.inputs.first().map(|i| &i.target) {
        Some(Target::Number(value)) if value.is_finite() => *value,
        _ => {
            return Err(invalid(format!(
                "{} is not a number with a finite value: solve varies one real number",
                options.vary
            )));
        }
    };
    let column = definition
        .outputs
        .iter()
        .position(|o| *o == options.output)
        .ok_or_else(|| {
            invalid(format!(
                "`{}` is not a summary output (the outputs: {})",
                options.output,
                definition.outputs.join(", ")
            ))
        })?;
    Ok((study, nominal, column))
}

/// The bracket searched: `--bounds`, else half the nominal value either side of it (±1 about
/// a nominal of zero).
fn search_bounds(options: &SolveOptions, nominal: f64) -> Result<[f64; 2], SolveError> {
    let invalid = |reason: String| SolveError::Invalid(reason);
    let [low, high] = options.bounds.unwrap_or(if nominal.abs() > 0.0 {
        let spread = 0.5 * nominal.abs();
        [nominal - spread, nominal + spread]
    } else {
        [-1.0, 1.0]
    });
    if !(low.is_finite() && high.is_finite() && low < high) {
        return Err(invalid(format!(
            "--bounds must be two finite numbers LO,HI with LO < HI, got {low},{high}"
        )));
    }
    Ok([low, high])
}

/// Finds the value of `options.vary` within the bounds at which `options.output` equals
/// `options.target` within `options.tolerance`.
///
/// # Errors
/// [`SolveError`]: the request, the mission's models, a failed trial flight, a target outside
/// the outputs at the bounds, or no convergence within the flight budget.
pub fn solve(mission: &Mission, options: &SolveOptions) -> Result<Solution, SolveError> {
    check_request(mission, options)?;
    let (study, nominal, column) = trial_study(mission, options)?;
    let [low, high] = search_bounds(options, nominal)?;
    let mut trials: Vec<[f64; 2]> = Vec::new();
    let output_at = |x: f64, trials: &mut Vec<[f64; 2]>| -> Result<f64, SolveError> {
        let flight = |reason: String| SolveError::Flight {
            input: options.vary.clone(),
            value: x,
            reason,
        };
        let outcome = study
            .fly(0, &[x])
            .map_err(|e| flight(format!("failed: {e}")))?;
        // A flight that ended early (still in the air at max_time) counts when the output
        // occurred before it ended (its apogee); one without the output is the error.
        let ended = match outcome.status() {
            Status::Completed => None,
            Status::Ended { kind, message } => Some(format!("ended early ({kind}): {message}")),
            Status::Failed(message) => return Err(flight(format!("failed: {message}"))),
        };
        let y = outcome
            .values()
            .get(column)
            .copied()
            .flatten()
            .filter(|y| y.is_finite())
            .ok_or_else(|| flight(ended.unwrap_or_else(|| format!("has no {}", options.output))))?;
        trials.push([x, y]);
        Ok(y)
    };
    let target = options.target;
    let g = |y: f64| y - target;
    let (mut b, mut fb) = (high, g(output_at(high, &mut trials)?));
    let (mut a, mut fa) = (low, g(output_at(low, &mut trials)?));
    let done = |trials: &[[f64; 2]], x: f64, y: f64| Solution {
        input: options.vary.clone(),
        value: x,
        nominal,
        output: options.output.clone(),
        target,
        achieved: y,
        bounds: [low, high],
        flights: trials.len(),
        trials: trials.to_vec(),
        method: METHOD.to_owned(),
    };
    if fa.abs() <= options.tolerance {
        return Ok(done(&trials, a, fa + target));
    }
    if fb.abs() <= options.tolerance {
        return Ok(done(&trials, b, fb + target));
    }
    if fa.signum() == fb.signum() {
        return Err(SolveError::NotBracketed {
            input: options.vary.clone(),
            output: options.output.clone(),
            target,
            low,
            high,
            at_low: fa + target,
            at_high: fb + target,
        });
    }
    // Brent: b the best estimate, c the other end of the bracket, a the previous b.
    let (mut c, mut fc) = (a, fa);
    let mut d = b - a;
    let mut e = d;
    loop {
        if fb.signum() == fc.signum() {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        // The input's own resolution: a bracket narrower than this cannot be split further.
        let x_tolerance = 2.0 * f64::EPSILON * b.abs() + 1e-12 * (high - low);
        let m = 0.5 * (c - b);
        if fb.abs() <= options.tolerance {
            return Ok(done(&trials, b, fb + target));
        }
        if m.abs() <= x_tolerance || trials.len() >= options.max_flights {
            return Err(SolveError::NotConverged {
                input: options.vary.clone(),
                output: options.output.clone(),
                target,
                value: b,
                achieved: fb + target,
                miss: fb.abs(),
                tolerance: options.tolerance,
                flights: trials.len(),
            });
        }
        if e.abs() >= x_tolerance && fa.abs() > fb.abs() {
            // Interpolation: the step p/q from b.
            let s = fb / fa;
            let (mut p, mut q) = if a.to_bits() == c.to_bits() {
                // Secant through a and b.
                (2.0 * m * s, 1.0 - s)
            } else {
                // Inverse quadratic through a, b, c.
                let q = fa / fc;
                let r = fb / fc;
                (
                    s * (2.0 * m * q * (q - r) - (b - a) * (r - 1.0)),
                    (q - 1.0) * (r - 1.0) * (s - 1.0),
                )
            };
            if p > 0.0 {
                q = -q;
            }
            p = p.abs();
            // Accept within the bracket's inner three quarters and when it shrinks faster
            // than half the step before last; otherwise bisect.
            if 2.0 * p < (3.0 * m * q - (x_tolerance * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = m;
                e = m;
            }
        } else {
            d = m;
            e = m;
        }
        a = b;
        fa = fb;
        b += if d.abs() > x_tolerance {
            d
        } else {
            x_tolerance.copysign(m)
        };
        fb = g(output_at(b, &mut trials)?);
    }
}
