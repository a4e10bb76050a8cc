//! Draws follow their distributions: sample mean and standard deviation of 40 000 draws
//! against the closed forms (NIST/SEMATECH e-Handbook of Statistical Methods, §1.3.6.6).

use karman_dispersion::sampling::draw;
use karman_dispersion::{Distribution, Target, Variation, VariedInput};

const DRAWS: u64 = 40_000;

/// Mean and population standard deviation of the draws of `input` over samples 0..DRAWS.
fn moments(input: &VariedInput) -> (f64, f64) {
    let values: Vec<f64> = (0..DRAWS)
        .map(|i| draw(99, i, std::slice::from_ref(input))[0])
        .collect();
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n;
    (mean, var.sqrt())
}

/// Checks the draws' mean within 5 standard errors and the standard deviation within 3 %
/// (the relative standard error of a standard deviation is about 1/sqrt(2n) = 0.35 % for a
/// normal, larger for the skewed log-normal).
fn check(name: &str, variation: Variation, mean: f64, std: f64) {
    let input = VariedInput::new(name, Target::Number(10.0), variation);
    input.check().expect("valid input");
    let (m, s) = moments(&input);
    let tolerance = 5.0 * std / (DRAWS as f64).sqrt();
    assert!(
        (m - mean).abs() < tolerance,
        "{name}: mean {m} vs {mean} ± {tolerance}"
    );
    assert!((s / std - 1.0).abs() < 0.03, "{name}: std {s} vs {std}");
}

#[test]
fn distributions_have_their_moments() {
    check("std", Variation::Std(0.5), 10.0, 0.5);
    check(
        "normal",
        Variation::Value(Distribution::Normal {
            mean: -3.0,
            std: 2.0,
        }),
        -3.0,
        2.0,
    );
    check(
        "uniform",
        Variation::Value(Distribution::Uniform {
            low: 40.0,
            high: 50.0,
        }),
        45.0,
        10.0 / 12f64.sqrt(),
    );
    let (a, c, b) = (1.0, 2.0, 6.0);
    check(
        "triangular",
        Variation::Value(Distribution::Triangular {
            low: a,
            mode: c,
            high: b,
        }),
        (a + b + c) / 3.0,
        ((a * a + b * b + c * c - a * b - a * c - b * c) / 18.0).sqrt(),
    );
    let (mu, sigma) = (0.1, 0.25);
    check(
        "lognormal",
        Variation::Value(Distribution::Lognormal { mu, sigma }),
        (mu + sigma * sigma / 2.0).exp(),
        (((sigma * sigma).exp() - 1.0) * (2.0 * mu + sigma * sigma).exp()).sqrt(),
    );
    check(
        "factor",
        Variation::Factor(Distribution::Normal {
            mean: 1.0,
            std: 0.05,
        }),
        1.0,
        0.05,
    );
}

#[test]
fn choice_is_uniform_over_its_values() {
    let input = VariedInput::new(
        "member",
        Target::Integer(0),
        Variation::Value(Distribution::Choice(vec![0.0, 1.0, 2.0, 3.0])),
    );
    let mut counts = [0u64; 4];
    for i in 0..DRAWS {
        let v = draw(5, i, std::slice::from_ref(&input))[0];
        counts[v as usize] += 1;
    }
    // Binomial(n, 1/4): standard deviation sqrt(n · 3/16) ≈ 87; allow 5 of them.
    for count in counts {
        assert!(
            (count as f64 - DRAWS as f64 / 4.0).abs() < 5.0 * 87.0,
            "{counts:?}"
        );
    }
}
