//! Convergence stopping (`karman montecarlo --until "apogee_agl_m.ci95 < 5"`): fly a study
//! in steps of [`Until::every`] samples and stop at the first step at which every condition
//! holds, or at the study's sample count (the cap). The study written is the study of that
//! many samples, byte for byte: the samples already flown are kept in memory and handed to
//! [`crate::run`] of the study of `n` samples, which writes its files as a fresh run of `n`
//! samples does (a sample's draws and flight depend on the seed and its index only).
//!
//! Conditions, each `QUANTITY.ci95 < VALUE`, over the completed samples of the first `n`:
//!
//! - `OUTPUT.ci95`: the half-width of the 95 % confidence interval of the output's mean by
//!   the normal approximation (central limit theorem), `1.959964 · s / √m`, `s` the sample
//!   standard deviation (divisor `m − 1`) of the `m` values;
//! - `landing.semi_major.ci95`, `landing.semi_minor.ci95`: the half-width of the 95 %
//!   confidence interval of a semi-axis `a = k√λ` of the landing ellipse (any `k`, so the
//!   1σ axes of the summary and the 95.45 % region's alike, relatively), by the delta method
//!   on the large-sample variance of an eigenvalue of a normal sample covariance,
//!   `Var(λ̂) ≈ 2λ² / (m − 1)` (Anderson 1963, *Ann. Math. Statist.* 34, 122–148): `Var(â) ≈
//!   a² / (2(m − 1))`, so the half-width is `1.959964 · a / √(2(m − 1))`, stated for the
//!   95.45 % probability contour's semi-axis (`k = 2.486`, the summary's `probability`
//!   region).

use crate::csv::Row;
use crate::error::DispersionError;
use crate::stats::{Ellipse, probability_scale};
use crate::study::Study;

/// The standard normal's 97.5 % quantile: a 95 % two-sided interval.
pub const Z95: f64 = 1.959_963_984_540_054;

/// The probability of the landing ellipse whose semi-axes `landing.semi_major` and
/// `landing.semi_minor` name (the summary's 95.45 % region).
pub const LANDING_PROBABILITY: f64 = 0.9545;

/// What a condition measures.
#[derive(Debug, Clone, PartialEq)]
pub enum Quantity {
    /// The confidence half-width of the mean of the output at this column index.
    Output(usize),
    /// The confidence half-width of the landing ellipse's semi-major axis.
    LandingMajor,
    /// The confidence half-width of the landing ellipse's semi-minor axis.
    LandingMinor,
}

/// One stopping condition: `QUANTITY.ci95 < threshold`.
#[derive(Debug, Clone, PartialEq)]
pub struct Condition {
    /// The condition as written.
    pub text: String,
    /// What it measures.
    pub quantity: Quantity,
    /// The bound the half-width must fall below.
    pub threshold: f64,
}

/// The stopping rule: every condition must hold at a check.
#[derive(Debug, Clone, PartialEq)]
pub struct Until {
    /// The conditions.
    pub conditions: Vec<Condition>,
    /// Samples between checks (the first check at this many samples).
    pub every: u64,
}

/// The samples between checks unless told otherwise.
pub const DEFAULT_EVERY: u64 = 100;

impl Condition {
    /// Parses `NAME.ci95 < VALUE` for `study` (NAME an output or `landing.semi_major` /
    /// `landing.semi_minor`).
    ///
    /// # Errors
    /// [`DispersionError::InvalidStudy`] naming the text and what is wrong: not of that form,
    /// an unknown output (the study's are listed), a study without landing points, a bound
    /// that is not a positive number.
    pub fn parse(text: &str, study: &Study) -> Result<Self, DispersionError> {
        let invalid = |reason: String| DispersionError::InvalidStudy {
            reason: format!("--until {text:?}: {reason}"),
        };
        let Some((left, right)) = text.split_once('<') else {
            return Err(invalid(
                "expected QUANTITY.ci95 < VALUE (e.g. \"apogee_agl_m.ci95 < 5\")".to_owned(),
            ));
        };
        let threshold: f64 = right
            .trim()
            .parse()
            .map_err(|_| invalid(format!("{:?} is not a number", right.trim())))?;
        if !(threshold.is_finite() && threshold > 0.0) {
            return Err(invalid(format!(
                "the bound must be a positive number, got {threshold}"
            )));
        }
        let left = left.trim();
        let Some(name) = left.strip_suffix(".ci95") else {
            return Err(invalid(format!(
                "{left:?} names no statistic; the statistic is `ci95` (the 95 % confidence \
                 half-width): `{left}.ci95`"
            )));
        };
        let quantity = match name {
            "landing.semi_major" | "landing.semi_minor" => {
                if study.points.landing.is_none() {
                    return Err(invalid("the study has no landing points".to_owned()));
                }
                if name.ends_with("major") {
                    Quantity::LandingMajor
                } else {
                    Quantity::LandingMinor
                }
            }
            _ => Quantity::Output(study.outputs.iter().position(|o| o == name).ok_or_else(
                || {
                    invalid(format!(
                        "`{name}` is not an output of the study (its outputs: {}; and \
                         landing.semi_major, landing.semi_minor)",
                        study.outputs.join(", ")
                    ))
                },
            )?),
        };
        Ok(Condition {
            text: text.trim().to_owned(),
            quantity,
            threshold,
        })
    }

    /// The half-width over `rows` (the completed ones); `None` with fewer than two values.
    pub fn half_width(&self, study: &Study, rows: &[Row]) -> Option<f64> {
        let completed = rows.iter().filter(|r| r.status.is_completed());
        match self.quantity {
            Quantity::Output(k) => {
                let values: Vec<f64> = completed
                    .filter_map(|r| r.outputs.get(k).copied().flatten())
                    .filter(|v| v.is_finite())
                    .collect();
                let m = values.len();
                if m < 2 {
                    return None;
                }
                let mean = values.iter().sum::<f64>() / m as f64;
                let variance =
                    values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (m - 1) as f64;
                Some(Z95 * variance.sqrt() / (m as f64).sqrt())
            }
            Quantity::LandingMajor | Quantity::LandingMinor => {
                let [x, y] = study.points.landing.as_ref()?;
                let ix = study.outputs.iter().position(|o| o == x)?;
                let iy = study.outputs.iter().position(|o| o == y)?;
                let points: Vec<[f64; 2]> = completed
                    .filter_map(|r| {
                        Some([r.outputs.get(ix).copied()??, r.outputs.get(iy).copied()??])
                    })
                    .filter(|p| p[0].is_finite() && p[1].is_finite())
                    .collect();
                let ellipse = Ellipse::fit(&points)?;
                let m = ellipse.count;
                if m < 2 {
                    return None;
                }
                let axes = ellipse.semi_axes(probability_scale(LANDING_PROBABILITY));
                let a = if self.quantity == Quantity::LandingMajor {
                    axes[0]
                } else {
                    axes[1]
                };
                Some(Z95 * a / (2.0 * (m - 1) as f64).sqrt())
            }
        }
    }
}

impl Until {
    /// Whether every condition holds over `rows` (the first `n` samples), with each
    /// condition's half-width (`None`: too few values, which does not hold).
    pub fn check(&self, study: &Study, rows: &[Row]) -> (bool, Vec<Option<f64>>) {
        let widths: Vec<Option<f64>> = self
            .conditions
            .iter()
            .map(|c| c.half_width(study, rows))
            .collect();
        let met = self
            .conditions
            .iter()
            .zip(&widths)
            .all(|(c, w)| w.is_some_and(|w| w < c.threshold));
        (met, widths)
    }
}

/// How a converging run ended.
#[derive(Debug, Clone, PartialEq)]
pub struct Converged {
    /// The samples of the study written (a multiple of [`Until::every`], or the cap).
    pub samples: u64,
    /// Whether every condition held (false: the cap was reached first).
    pub met: bool,
    /// Each condition's half-width at the last check (`None`: too few values).
    pub widths: Vec<Option<f64>>,
    /// The checks made.
    pub checks: u64,
}

/// Runs `study` (its sample count the cap) in steps of `until.every` samples, checking
/// `until` over the first `n` samples after each step, and writes into `dir` the study of the
/// `n` samples at which every condition first held (or of the cap): byte for byte the files
/// [`crate::run`] of a study of `n` samples writes.
///
/// # Errors
/// A shard (a converging study is one whole study), `every = 0`, the runner's errors (a
/// directory holding another study, among them one of another sample count).
pub fn run_converging<F>(
    study: &Study,
    dir: &std::path::Path,
    options: &crate::RunOptions,
    until: &Until,
    fly: F,
) -> Result<(crate::RunReport, Converged), DispersionError>
where
    F: Fn(u64, &[f64]) -> Result<crate::Outcome, String> + Sync,
{
    use std::collections::HashMap;
    use std::sync::{Mutex, PoisonError};
    let invalid = |reason: &str| DispersionError::InvalidStudy {
        reason: reason.to_owned(),
    };
    if options
        .shard
        .is_some_and(|shard| shard != crate::Shard::WHOLE)
    {
        return Err(invalid(
            "--until stops one whole study; it takes no --shard",
        ));
    }
    if until.every == 0 {
        return Err(invalid(
            "the samples between --until checks must be at least 1",
        ));
    }
    study.validate()?;
    let pool = crate::runner::thread_pool(options)?;
    // Every flight's result, by index: the study finally written flies none again.
    let flown: Mutex<HashMap<u64, Result<crate::Outcome, String>>> = Mutex::new(HashMap::new());
    let cached = |index: u64, values: &[f64]| {
        if let Some(result) = flown
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .get(&index)
        {
            return result.clone();
        }
        let result = fly(index, values);
        flown
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .insert(index, result.clone());
        result
    };
    let cap = study.samples;
    let mut rows: Vec<Row> = Vec::new();
    let mut checks = 0;
    let (samples, met, widths) = loop {
        let n = (rows.len() as u64 + until.every).min(cap);
        let step = Study {
            samples: n,
            ..study.clone()
        };
        rows.extend(crate::runner::fly_rows(
            &pool,
            &step,
            rows.len() as u64..n,
            &cached,
        ));
        checks += 1;
        let (met, widths) = until.check(&step, &rows);
        if met || n >= cap {
            break (n, met, widths);
        }
    };
    let written = Study {
        samples,
        ..study.clone()
    };
    let report = crate::run(&written, dir, options, cached)?;
    Ok((
        report,
        Converged {
            samples,
            met,
            widths,
            checks,
        },
    ))
}
