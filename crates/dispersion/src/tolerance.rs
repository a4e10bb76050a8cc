//! Wilks' distribution-free tolerance bounds: "a fraction `p` of the flights stays below `X`
//! with confidence `γ`" from the order statistics of a study's samples, whatever the output's
//! distribution (Wilks 1941, *Ann. Math. Statist.* 12, 91–96; the form of Hahn & Meeker,
//! *Statistical Intervals*, 1991, §5.3).
//!
//! With the `n` values sorted, `X_(1) ≤ … ≤ X_(n)`, the coverage `F(X_(n−r+1))` of the r-th
//! largest is a beta variable, and `P(F(X_(n−r+1)) ≥ p) = P(B ≤ n − r)` with `B` binomial of
//! `n` trials and probability `p`. The upper bound is the r-th largest value for the largest
//! `r` with `P(B ≤ n − r) ≥ γ` (the tightest bound that still holds with confidence `γ`); the
//! lower bound is the r-th smallest by symmetry. With `r = 1` (the maximum) the condition is
//! `1 − p^n ≥ γ`, so at least `n = ⌈ln(1 − γ) / ln p⌉` values are needed (59 for 95 %/95 %,
//! 299 for 99 %/95 %).

use crate::csv::Row;
use crate::error::DispersionError;
use crate::study::Study;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The one-sided tolerance bounds of one output.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ToleranceBounds {
    /// The output's column.
    pub output: String,
    /// The fraction of flights the bound covers.
    pub coverage: f64,
    /// The confidence.
    pub confidence: f64,
    /// The completed samples with the output.
    pub samples: u64,
    /// The least number of samples the bounds need (`⌈ln(1 − γ) / ln p⌉`).
    pub samples_needed: u64,
    /// A fraction `coverage` of flights stays below this, with `confidence` (none with too
    /// few samples).
    pub upper: Option<f64>,
    /// A fraction `coverage` of flights stays above this, with `confidence`.
    pub lower: Option<f64>,
    /// The rank from the top (1: the maximum) of `upper`, from the bottom of `lower`.
    pub rank: Option<u64>,
    /// The confidence the rank achieves, `P(B ≤ n − r)` (at least `confidence`).
    pub achieved_confidence: Option<f64>,
}

/// The samples a one-sided bound of coverage `p` with confidence `γ` needs.
pub fn samples_needed(coverage: f64, confidence: f64) -> u64 {
    ((1.0 - confidence).ln() / coverage.ln()).ceil() as u64
}

/// The largest rank `r` (from the top) whose order statistic bounds a fraction `coverage` of
/// the population with confidence `confidence` among `n` values, and the confidence it
/// achieves; `None` when even the extreme value does not (`n` below [`samples_needed`]).
pub fn wilks_rank(n: u64, coverage: f64, confidence: f64) -> Option<(u64, f64)> {
    if n == 0 {
        return None;
    }
    let (p, nf) = (coverage, n as f64);
    // log P(B = k), from k = n down: log pmf(n) = n ln p, and
    // pmf(k − 1) = pmf(k) · k / (n − k + 1) · (1 − p) / p.
    let ratio = ((1.0 - p) / p).ln();
    let mut log_pmf = nf * p.ln();
    // tail = P(B ≥ n − r + 1), built up one term per rank.
    let mut tail = 0.0;
    let mut best = None;
    for r in 1..=n {
        let k = n - r + 1;
        tail += log_pmf.exp();
        let achieved = 1.0 - tail;
        if achieved >= confidence {
            best = Some((r, achieved));
        } else {
            break;
        }
        log_pmf += (k as f64 / (nf - k as f64 + 1.0)).ln() + ratio;
    }
    best
}

/// The bounds of one output over `values` (finite values only).
pub fn bounds_of(
    output: &str,
    values: &mut Vec<f64>,
    coverage: f64,
    confidence: f64,
) -> ToleranceBounds {
    values.retain(|v| v.is_finite());
    values.sort_by(f64::total_cmp);
    let n = values.len() as u64;
    let found = wilks_rank(n, coverage, confidence);
    let at = |i: u64| {
        values
            .get(usize::try_from(i).unwrap_or(usize::MAX))
            .copied()
    };
    ToleranceBounds {
        output: output.to_owned(),
        coverage,
        confidence,
        samples: n,
        samples_needed: samples_needed(coverage, confidence),
        upper: found.and_then(|(r, _)| at(n - r)),
        lower: found.and_then(|(r, _)| at(r - 1)),
        rank: found.map(|(r, _)| r),
        achieved_confidence: found.map(|(_, c)| c),
    }
}

/// The bounds of the named outputs (every output when empty) over the completed rows.
///
/// # Errors
/// [`DispersionError::InvalidStudy`]: a coverage or confidence outside (0, 1), an output the
/// study does not have.
pub fn tolerance_of_rows(
    study: &Study,
    rows: &[Row],
    outputs: &[String],
    coverage: f64,
    confidence: f64,
) -> Result<Vec<ToleranceBounds>, DispersionError> {
    let invalid = |reason: String| DispersionError::InvalidStudy { reason };
    for (name, value) in [("coverage", coverage), ("confidence", confidence)] {
        if !(value > 0.0 && value < 1.0) {
            return Err(invalid(format!(
                "the {name} must be a fraction strictly between 0 and 1 (0.99 for 99 %), got {value}"
            )));
        }
    }
    let wanted = study.output_columns(outputs)?;
    Ok(wanted
        .into_iter()
        .map(|k| {
            let mut values: Vec<f64> = rows
                .iter()
                .filter(|r| r.status.is_completed())
                .filter_map(|r| r.outputs.get(k).copied().flatten())
                .collect();
            bounds_of(&study.outputs[k], &mut values, coverage, confidence)
        })
        .collect())
}

/// [`tolerance_of_rows`] of the study in `dir`.
///
/// # Errors
/// As [`crate::sensitivity`] for reading the study, and as [`tolerance_of_rows`].
pub fn tolerance(
    dir: &Path,
    outputs: &[String],
    coverage: f64,
    confidence: f64,
) -> Result<Vec<ToleranceBounds>, DispersionError> {
    let (study, rows) = crate::sensitivity::read_rows(dir)?;
    tolerance_of_rows(&study, &rows, outputs, coverage, confidence)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_classic_sample_sizes() {
        // Wilks' first-order sample sizes (Hahn & Meeker Table A.18; Wilks 1941).
        assert_eq!(samples_needed(0.95, 0.95), 59);
        assert_eq!(samples_needed(0.99, 0.95), 299);
        assert_eq!(samples_needed(0.95, 0.99), 90);
        assert_eq!(wilks_rank(58, 0.95, 0.95), None);
        let (r, c) = wilks_rank(59, 0.95, 0.95).unwrap();
        assert_eq!(r, 1);
        assert!((c - (1.0 - 0.95f64.powi(59))).abs() < 1e-12);
        // The second largest needs 93 values (the second-order sample size for 95 %/95 %).
        assert_eq!(wilks_rank(92, 0.95, 0.95).map(|x| x.0), Some(1));
        assert_eq!(wilks_rank(93, 0.95, 0.95).map(|x| x.0), Some(2));
        // 99 %/95 % with 1000 samples: the 5th largest, P(B ≤ 995) = 0.9713136000009954
        // and P(B ≤ 994) = 0.9338604883927484 (SciPy 1.x `scipy.stats.binom.cdf(995, 1000,
        // 0.99)`, `(994, 1000, 0.99)`).
        let (r, c) = wilks_rank(1000, 0.99, 0.95).unwrap();
        assert_eq!(r, 5);
        assert!((c - 0.9713136000009954).abs() < 1e-12, "{c}");
    }

    #[test]
    fn bounds_are_order_statistics() {
        let mut values: Vec<f64> = (1..=100).map(f64::from).rev().collect();
        let b = bounds_of("x", &mut values, 0.95, 0.95);
        // n = 100 ≥ 93: the second largest and the second smallest.
        assert_eq!(b.rank, Some(2));
        assert_eq!(b.upper, Some(99.0));
        assert_eq!(b.lower, Some(2.0));
        let mut few = vec![1.0, 2.0, 3.0];
        let b = bounds_of("x", &mut few, 0.99, 0.95);
        assert_eq!((b.upper, b.samples_needed), (None, 299));
    }
}
