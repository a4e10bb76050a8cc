//! First-order and total Sobol indices by Saltelli's sampling design, for nonlinear effects
//! the regression of [`crate::sensitivity`] cannot see (Sobol 2001; Saltelli et al. 2010,
//! "Variance based sensitivity analysis of model output", *Comput. Phys. Commun.* 181,
//! 259–270).
//!
//! Two independent matrices of `n` draws of the `k` inputs, `A` (samples `0..n` of the
//! study's streams) and `B` (samples `n..2n`), and for each input `i` the matrix `A_B^(i)`:
//! `A` with its column `i` taken from `B`. The model is evaluated on the `(k + 2) n` rows;
//! with `V` the variance of `f(A)` and `f(B)` together (divisor `2n`):
//!
//! - first order (Saltelli 2010, table 2, (b)):
//!   `S_i = (1/n) Σ_j (f(B)_j − f̄) (f(A_B^(i))_j − f(A)_j) / V`, `f̄` the mean over `A` and
//!   `B` (the centring leaves the expectation, `E[f(A_B^(i)) − f(A)] = 0`, and lowers the
//!   variance of the estimate);
//! - total (Jansen 1999; Saltelli 2010, table 2, (f)):
//!   `S_Ti = (1/(2n)) Σ_j (f(A)_j − f(A_B^(i))_j)² / V`.
//!
//! The draws are the study's ([`crate::sampling::draw`]): reproducible from the seed, row `j`
//! of `A` is sample `j` and of `B` sample `n + j`.

use crate::distribution::VariedInput;
use crate::error::DispersionError;
use crate::sampling::draw;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// The indices of one output.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SobolIndices {
    /// The inputs, in the order of the indices.
    pub inputs: Vec<String>,
    /// First-order indices `S_i`.
    pub first: Vec<f64>,
    /// Total indices `S_Ti`.
    pub total: Vec<f64>,
    /// `n`, the rows of each matrix.
    pub samples: u64,
    /// Model evaluations, `(k + 2) n`.
    pub evaluations: u64,
    /// `V`, the output's variance over `A` and `B`.
    pub variance: f64,
}

/// The rows of Saltelli's design for `inputs` with `seed`: `A`, `B`, then each `A_B^(i)`.
pub fn saltelli_design(seed: u64, n: u64, inputs: &[VariedInput]) -> Vec<Vec<f64>> {
    let a: Vec<Vec<f64>> = (0..n).map(|j| draw(seed, j, inputs)).collect();
    let b: Vec<Vec<f64>> = (0..n).map(|j| draw(seed, n + j, inputs)).collect();
    let mut rows = Vec::with_capacity((inputs.len() + 2) * a.len());
    rows.extend(a.iter().cloned());
    rows.extend(b.iter().cloned());
    for i in 0..inputs.len() {
        for (row_a, row_b) in a.iter().zip(&b) {
            let mut row = row_a.clone();
            row[i] = row_b[i];
            rows.push(row);
        }
    }
    rows
}

/// The indices from the model's values on [`saltelli_design`]'s rows (in its order).
///
/// # Errors
/// [`DispersionError::InvalidStudy`]: the values do not match the design, a value is not
/// finite (a failed flight: the estimators need every row), or the output does not vary.
pub fn sobol_indices(
    names: &[String],
    n: u64,
    values: &[f64],
) -> Result<SobolIndices, DispersionError> {
    let invalid = |reason: String| DispersionError::InvalidStudy { reason };
    let k = names.len();
    let rows = usize::try_from(n).unwrap_or(usize::MAX);
    if n < 2 || values.len() != (k + 2) * rows {
        return Err(invalid(format!(
            "Saltelli's design of {k} inputs and n = {n} has {} rows, got {} values",
            (k + 2).saturating_mul(rows),
            values.len()
        )));
    }
    if let Some(bad) = values.iter().position(|v| !v.is_finite()) {
        return Err(invalid(format!(
            "row {bad} of the design has no value (a failed flight): Sobol's estimators need \
             every row"
        )));
    }
    let (fa, rest) = values.split_at(rows);
    let (fb, fab) = rest.split_at(rows);
    let all = || fa.iter().chain(fb);
    let mean = all().sum::<f64>() / (2 * rows) as f64;
    let variance = all().map(|v| (v - mean).powi(2)).sum::<f64>() / (2 * rows) as f64;
    if variance <= 0.0 {
        return Err(invalid(
            "the output does not vary over the design".to_owned(),
        ));
    }
    let nf = rows as f64;
    let mut first = Vec::with_capacity(k);
    let mut total = Vec::with_capacity(k);
    for i in 0..k {
        let fi = &fab[i * rows..(i + 1) * rows];
        // f(B) centred on the mean: the same expectation (E[f(A_B^(i)) − f(A)] = 0), less
        // variance when the output's mean is large against its spread.
        let s: f64 = fb
            .iter()
            .zip(fi)
            .zip(fa)
            .map(|((b, ab), a)| (b - mean) * (ab - a))
            .sum();
        let t: f64 = fa.iter().zip(fi).map(|(a, ab)| (a - ab).powi(2)).sum();
        first.push(s / nf / variance);
        total.push(t / (2.0 * nf) / variance);
    }
    Ok(SobolIndices {
        inputs: names.to_vec(),
        first,
        total,
        samples: n,
        evaluations: values.len() as u64,
        variance,
    })
}

/// Saltelli's design for `inputs` evaluated by `f` (in parallel), and the indices.
///
/// # Errors
/// As [`sobol_indices`].
pub fn sobol<F>(
    seed: u64,
    n: u64,
    inputs: &[VariedInput],
    f: F,
) -> Result<SobolIndices, DispersionError>
where
    F: Fn(&[f64]) -> f64 + Sync,
{
    for input in inputs {
        input.check()?;
    }
    let rows = saltelli_design(seed, n, inputs);
    let values: Vec<f64> = rows.par_iter().map(|row| f(row)).collect();
    let names: Vec<String> = inputs.iter().map(VariedInput::column).collect();
    sobol_indices(&names, n, &values)
}

/// An output's name and its indices, or why they cannot be computed.
pub type OutputIndices = (String, Result<SobolIndices, String>);

/// The Sobol indices of every output of `study` (its inputs and seed; `n` rows per matrix),
/// its flight function `fly` called on each row of Saltelli's design with the row's number as
/// the sample index, on `options.threads` workers. An output with a row that has no value (a
/// failed flight, an output that did not occur) gets the reason instead of its indices.
///
/// # Errors
/// The study's inputs are invalid, `n < 2`, or the thread pool cannot be built.
pub fn sobol_study<F>(
    study: &crate::Study,
    n: u64,
    options: &crate::RunOptions,
    fly: F,
) -> Result<Vec<OutputIndices>, DispersionError>
where
    F: Fn(u64, &[f64]) -> Result<crate::Outcome, String> + Sync,
{
    study.validate()?;
    if n < 2 {
        return Err(DispersionError::InvalidStudy {
            reason: format!("Saltelli's design needs at least 2 samples per matrix, got {n}"),
        });
    }
    let pool = crate::runner::thread_pool(options)?;
    let rows = saltelli_design(study.seed, n, &study.inputs);
    let outcomes: Vec<Result<crate::Outcome, String>> = pool.install(|| {
        rows.par_iter()
            .enumerate()
            .map(|(r, row)| {
                std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| fly(r as u64, row)))
                    .unwrap_or_else(|_| Err("the flight panicked".to_owned()))
            })
            .collect()
    });
    let names: Vec<String> = study.inputs.iter().map(VariedInput::column).collect();
    Ok(study
        .outputs
        .iter()
        .enumerate()
        .map(|(k, output)| {
            let values: Vec<f64> = outcomes
                .iter()
                .map(|o| match o {
                    Ok(outcome) if outcome.status().is_completed() => outcome
                        .values()
                        .get(k)
                        .copied()
                        .flatten()
                        .unwrap_or(f64::NAN),
                    _ => f64::NAN,
                })
                .collect();
            let indices = sobol_indices(&names, n, &values).map_err(|e| match e {
                DispersionError::InvalidStudy { reason } => reason,
                other => other.to_string(),
            });
            (output.clone(), indices)
        })
        .collect())
}
