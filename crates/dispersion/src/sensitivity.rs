//! Sensitivity of a study's outputs to its varied inputs, from its samples: the linear
//! regression variance decomposition of RocketPy 1.13's `SensitivityModel`
//! (`rocketpy/sensitivity/sensitivity_model.py`; Sobol 2001 for the variance-based view it
//! takes to first order).
//!
//! For one output `y` and the inputs `x_1 … x_p` over the `n` completed samples:
//!
//! - each input is centred on its sample mean `x̄_j` and scaled by nothing; its spread is the
//!   population standard deviation `s_j = sqrt(Σ (x_ij − x̄_j)² / n)` (NumPy's `np.std`, as
//!   RocketPy estimates the "nominal sd" when none is given);
//! - ordinary least squares with an intercept, `y_i − ȳ = β_0 + Σ_j β_j (x_ij − x̄_j) + ε_i`,
//!   solved by Householder QR (Golub & Van Loan, *Matrix Computations*, 4th ed., §5.3.3);
//! - the residual variance `σ̂² = RSS / (n − r)`, `r` the rank of the design (p + 1 for
//!   independent inputs): statsmodels' `OLSResults.scale`, which RocketPy reads;
//! - the variance the model attributes to input `j` is `S_j = β_j² s_j²`, and the output's
//!   model variance `V = σ̂² + Σ_j S_j`;
//! - input `j`'s share is `S_j / V` and the unexplained part (RocketPy's "linear
//!   approximation error", LAE) is `σ̂² / V`, so the shares and the unexplained part sum to 1.
//!
//! An input that does not vary over the samples (`s_j = 0`) explains nothing: its share and
//! coefficient are 0 and it is left out of the design (statsmodels' pseudo-inverse gives it a
//! zero coefficient too, and the rank drops by one).

use crate::csv::Row;
use crate::error::DispersionError;
use crate::files::{self, SAMPLES_FILE, STUDY_FILE};
use crate::study::{Record, Study};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// One input's part in an output's variance.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct InputShare {
    /// The input's column in `samples.csv` (`rocket.mass`, `rocket.power_off_drag:factor`).
    pub input: String,
    /// Its sample mean over the samples used.
    pub mean: f64,
    /// Its population standard deviation over the samples used.
    pub std: f64,
    /// The regression coefficient `β_j` (output units per input unit).
    pub coefficient: f64,
    /// `β_j · s_j`: the change of the output for one standard deviation of the input.
    pub effect_per_std: f64,
    /// `β_j² s_j² / V`: the share of the output's variance this input explains.
    pub share: f64,
}

/// The variance decomposition of one output.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OutputSensitivity {
    /// The output's column.
    pub output: String,
    /// Samples used: completed, with this output present.
    pub samples: u64,
    /// The output's sample mean (RocketPy's estimated nominal value).
    pub mean: f64,
    /// `sqrt(V)`: the standard deviation the linear model gives the output.
    pub std: f64,
    /// One entry per input, in the study's order.
    pub inputs: Vec<InputShare>,
    /// `σ̂² / V`: the share of the variance no input explains linearly (RocketPy's LAE).
    pub unexplained: f64,
    /// `σ̂² = RSS / (n − r)`: the regression's residual variance.
    pub residual_variance: f64,
}

/// Outputs of a study that could not be decomposed, and why (when every output is asked
/// for, an output that never occurs or never varies is left out rather than an error).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Skipped {
    /// The output's column.
    pub output: String,
    /// Why.
    pub reason: String,
}

/// The sensitivity of a study's outputs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Sensitivity {
    /// The method, stated.
    pub method: String,
    /// One decomposition per output asked for.
    pub outputs: Vec<OutputSensitivity>,
    /// Outputs left out when every output was asked for.
    pub skipped: Vec<Skipped>,
}

/// The method as `Sensitivity::method` states it.
pub const METHOD: &str = "linear regression variance decomposition (RocketPy 1.13 \
    SensitivityModel): OLS with intercept on the inputs centred on their means; share_j = \
    beta_j^2 std_j^2 / V, unexplained = sigma^2 / V, V = sigma^2 + sum_j beta_j^2 std_j^2, \
    sigma^2 = RSS / (n - rank); std is the population standard deviation";

/// The sensitivity of the study in `dir` (its `study.json` and `samples.csv`, every row
/// checked as a resume checks it), for the named outputs (every output when `outputs` is
/// empty).
///
/// # Errors
/// The study's files cannot be read or are not a study's; an output name is not one of the
/// study's; a named output has too few completed samples, does not vary, or its inputs are
/// collinear ([`DispersionError::InvalidStudy`] saying which).
pub fn sensitivity(dir: &Path, outputs: &[String]) -> Result<Sensitivity, DispersionError> {
    let (study, rows) = read_rows(dir)?;
    sensitivity_of_rows(&study, &rows, outputs)
}

/// The study in `dir` and its complete rows, every row checked as a resume checks it.
pub(crate) fn read_rows(dir: &Path) -> Result<(Study, Vec<Row>), DispersionError> {
    let record =
        Record::read(&dir.join(STUDY_FILE))?.ok_or_else(|| DispersionError::MissingStudy {
            dir: dir.to_owned(),
        })?;
    let path = dir.join(SAMPLES_FILE);
    let scan = files::scan(&path, &record)?;
    let study = record.study();
    let mut rows = Vec::with_capacity(usize::try_from(scan.rows).unwrap_or(0));
    files::for_each_row(&path, study.inputs.len(), study.outputs.len(), |row| {
        rows.push(row);
    })?;
    // A trailing partial row (an interrupted run) is not part of the scan.
    rows.truncate(usize::try_from(scan.rows).unwrap_or(usize::MAX));
    Ok((study, rows))
}

/// [`sensitivity`] of rows in memory (as [`crate::run_in_memory`] keeps them).
///
/// # Errors
/// As [`sensitivity`], but for reading files.
pub fn sensitivity_of_rows(
    study: &Study,
    rows: &[Row],
    outputs: &[String],
) -> Result<Sensitivity, DispersionError> {
    let invalid = |reason: String| DispersionError::InvalidStudy { reason };
    let names: Vec<String> = study.inputs.iter().map(|i| i.column()).collect();
    if names.is_empty() {
        return Err(invalid("the study varies no input".to_owned()));
    }
    let wanted = study.output_columns(outputs)?;
    let mut result = Sensitivity {
        method: METHOD.to_owned(),
        outputs: Vec::new(),
        skipped: Vec::new(),
    };
    for k in wanted {
        let output = &study.outputs[k];
        let used: Vec<&Row> = rows
            .iter()
            .filter(|r| r.status.is_completed())
            .filter(|r| {
                r.outputs
                    .get(k)
                    .copied()
                    .flatten()
                    .is_some_and(f64::is_finite)
            })
            .filter(|r| r.inputs.iter().all(|v| v.is_finite()))
            .collect();
        let columns: Vec<Vec<f64>> = (0..names.len())
            .map(|j| used.iter().map(|r| r.inputs[j]).collect())
            .collect();
        let y: Vec<f64> = used
            .iter()
            .map(|r| r.outputs[k].unwrap_or(f64::NAN))
            .collect();
        match decompose(&names, &columns, &y) {
            Ok(mut decomposition) => {
                decomposition.output = output.clone();
                result.outputs.push(decomposition);
            }
            Err(reason) if outputs.is_empty() => result.skipped.push(Skipped {
                output: output.clone(),
                reason,
            }),
            Err(reason) => return Err(invalid(format!("output `{output}`: {reason}"))),
        }
    }
    Ok(result)
}

/// The decomposition of `y` on the input `columns` (one per name, each as long as `y`);
/// `output` of the result is left empty for the caller. The error says why it cannot be
/// computed.
pub fn decompose(
    names: &[String],
    columns: &[Vec<f64>],
    y: &[f64],
) -> Result<OutputSensitivity, String> {
    let n = y.len();
    if columns.len() != names.len() || columns.iter().any(|c| c.len() != n) {
        return Err("the input columns do not match the output's samples".to_owned());
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let std = |v: &[f64], m: f64| {
        (v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / v.len() as f64).sqrt()
    };
    let varied: Vec<usize> = (0..names.len())
        .filter(|&j| n > 0 && std(&columns[j], mean(&columns[j])) > 0.0)
        .collect();
    let rank = varied.len() + 1;
    if n <= rank {
        return Err(format!(
            "{n} completed samples with this output; the regression on {} varying inputs needs \
             at least {}",
            varied.len(),
            rank + 1
        ));
    }
    let y_mean = mean(y);
    let centred_y: Vec<f64> = y.iter().map(|v| v - y_mean).collect();
    // The design, column-major: the intercept, then each varying input centred on its mean.
    let mut design: Vec<Vec<f64>> = Vec::with_capacity(rank);
    design.push(vec![1.0; n]);
    let mut moments = vec![(0.0, 0.0); names.len()];
    for (j, column) in columns.iter().enumerate() {
        let m = mean(column);
        moments[j] = (m, std(column, m));
    }
    for &j in &varied {
        let m = moments[j].0;
        design.push(columns[j].iter().map(|x| x - m).collect());
    }
    let (beta, rss) = least_squares(design, centred_y).map_err(|column| {
        let name = column
            .checked_sub(1)
            .and_then(|c| varied.get(c))
            .map_or("the intercept", |&j| names[j].as_str());
        format!(
            "the inputs are collinear over these samples ({name} is a linear combination of \
             the inputs before it): the regression has no unique solution"
        )
    })?;
    let residual_variance = rss / (n - rank) as f64;
    let mut coefficients = vec![0.0; names.len()];
    for (c, &j) in varied.iter().enumerate() {
        coefficients[j] = beta[c + 1];
    }
    let explained: Vec<f64> = (0..names.len())
        .map(|j| (coefficients[j] * moments[j].1).powi(2))
        .collect();
    let variance = residual_variance + explained.iter().sum::<f64>();
    if variance <= 0.0 || !variance.is_finite() {
        return Err("the output does not vary over these samples".to_owned());
    }
    Ok(OutputSensitivity {
        output: String::new(),
        samples: n as u64,
        mean: y_mean,
        std: variance.sqrt(),
        inputs: names
            .iter()
            .enumerate()
            .map(|(j, name)| InputShare {
                input: name.clone(),
                mean: moments[j].0,
                std: moments[j].1,
                coefficient: coefficients[j],
                effect_per_std: coefficients[j] * moments[j].1,
                share: explained[j] / variance,
            })
            .collect(),
        unexplained: residual_variance / variance,
        residual_variance,
    })
}

/// Least squares `min ‖A β − b‖` by Householder QR (Golub & Van Loan §5.3.3): `A` given by
/// its columns (each as long as `b`, more rows than columns). Returns `β` and the residual
/// sum of squares `‖b − A β‖²` (the squared norm of the transformed `b` below row `m`). A
/// column whose diagonal of `R` vanishes relative to the column's own norm (a linear
/// combination of the columns before it) is the error.
fn least_squares(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Result<(Vec<f64>, f64), usize> {
    let m = a.len();
    let n = b.len();
    let mut diagonal = vec![0.0; m];
    for k in 0..m {
        let column_norm = a[k].iter().map(|v| v * v).sum::<f64>().sqrt();
        // The norm of the part of column k on rows k.. (what the reflection maps onto e_k).
        let norm = a[k][k..].iter().map(|v| v * v).sum::<f64>().sqrt();
        if norm.is_nan() || norm <= 1e-12 * column_norm || column_norm <= 0.0 {
            return Err(k);
        }
        // H = I − 2 v vᵀ / (vᵀ v), v = x − α e_k with α = −sign(x_k) ‖x‖ (no cancellation).
        let alpha = if a[k][k] > 0.0 { -norm } else { norm };
        let mut v: Vec<f64> = a[k][k..].to_vec();
        v[0] -= alpha;
        let vv: f64 = v.iter().map(|x| x * x).sum();
        diagonal[k] = alpha;
        for column in a.iter_mut().skip(k + 1) {
            let dot: f64 = v.iter().zip(&column[k..]).map(|(p, q)| p * q).sum();
            let f = 2.0 * dot / vv;
            for (x, p) in column[k..].iter_mut().zip(&v) {
                *x -= f * p;
            }
        }
        let dot: f64 = v.iter().zip(&b[k..]).map(|(p, q)| p * q).sum();
        let f = 2.0 * dot / vv;
        for (x, p) in b[k..].iter_mut().zip(&v) {
            *x -= f * p;
        }
    }
    // Back substitution R β = (Qᵀ b)[..m], R's diagonal the α's, above it the reflected columns.
    let mut beta = vec![0.0; m];
    for k in (0..m).rev() {
        let mut s = b[k];
        for j in k + 1..m {
            s -= a[j][k] * beta[j];
        }
        beta[k] = s / diagonal[k];
    }
    let rss = b[m..n].iter().map(|v| v * v).sum();
    Ok((beta, rss))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_exact_linear_output_has_no_unexplained_part() {
        // y = 3 x1 − 2 x2 + 5 on a grid: the coefficients are recovered exactly, and the
        // residual is zero.
        let mut x1 = Vec::new();
        let mut x2 = Vec::new();
        for i in 0..7 {
            for j in 0..5 {
                x1.push(f64::from(i));
                x2.push(f64::from(j) * 0.5);
            }
        }
        let y: Vec<f64> = x1
            .iter()
            .zip(&x2)
            .map(|(a, b)| 3.0 * a - 2.0 * b + 5.0)
            .collect();
        let names = ["a".to_owned(), "b".to_owned()];
        let s = decompose(&names, &[x1, x2], &y).unwrap();
        assert!((s.inputs[0].coefficient - 3.0).abs() < 1e-12);
        assert!((s.inputs[1].coefficient + 2.0).abs() < 1e-12);
        assert!(s.unexplained.abs() < 1e-20);
        // Independent grid columns: the shares are the variances' proportions,
        // 9·var(x1) : 4·var(x2) = 9·4 : 4·0.5 (population variances of 0..=6 and 0..=2 by 0.5).
        assert!((s.inputs[0].share - 36.0 / 38.0).abs() < 1e-12, "{s:?}");
        assert!((s.inputs[1].share - 2.0 / 38.0).abs() < 1e-12, "{s:?}");
    }

    #[test]
    fn collinear_and_short_samples_are_errors() {
        let x: Vec<f64> = (0..10).map(f64::from).collect();
        let twice: Vec<f64> = x.iter().map(|v| 2.0 * v).collect();
        let y = x.clone();
        let names = ["a".to_owned(), "b".to_owned()];
        let error = decompose(&names, &[x.clone(), twice], &y).unwrap_err();
        assert!(
            error.contains("collinear") && error.contains('b'),
            "{error}"
        );
        let error = decompose(&names[..1], &[x[..2].to_vec()], &y[..2]).unwrap_err();
        assert!(error.contains("needs at least 3"), "{error}");
        // A constant input explains nothing and is left out of the design.
        let constant = vec![4.0; 10];
        let noisy: Vec<f64> = (0..10)
            .map(|i| f64::from(i) + if i % 2 == 0 { 0.1 } else { -0.1 })
            .collect();
        let s = decompose(&names, &[x, constant], &noisy).unwrap();
        assert!(s.inputs[1].share.abs() <= 0.0 && s.inputs[1].coefficient.abs() <= 0.0);
        assert!((s.inputs[0].share + s.unexplained - 1.0).abs() < 1e-12);
    }
}
