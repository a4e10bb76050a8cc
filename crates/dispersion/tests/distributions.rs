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

/// Euler–Mascheroni constant (the mean of a standard Gumbel).
const EULER_GAMMA: f64 = 0.577_215_664_901_532_9;

#[test]
fn numpy_distributions_have_their_moments() {
    use std::f64::consts::PI;
    // Closed forms: NIST/SEMATECH e-Handbook §1.3.6.6 (exponential, gamma, Gumbel, double
    // exponential, logistic, Poisson, binomial, chi-square) and Chhikara & Folks (1989) for
    // the inverse Gaussian: mean μ, variance μ³/λ.
    let value = Variation::Value;
    check(
        "exponential",
        value(Distribution::Exponential { scale: 2.5 }),
        2.5,
        2.5,
    );
    let (k, theta) = (2.0, 1.5);
    check(
        "gamma",
        value(Distribution::Gamma {
            shape: k,
            scale: theta,
        }),
        k * theta,
        k.sqrt() * theta,
    );
    let (mu, beta) = (3.0, 0.8);
    check(
        "gumbel",
        value(Distribution::Gumbel {
            loc: mu,
            scale: beta,
        }),
        mu + EULER_GAMMA * beta,
        PI * beta / 6f64.sqrt(),
    );
    check(
        "laplace",
        value(Distribution::Laplace {
            loc: -1.0,
            scale: 0.5,
        }),
        -1.0,
        2f64.sqrt() * 0.5,
    );
    check(
        "logistic",
        value(Distribution::Logistic {
            loc: 4.0,
            scale: 0.3,
        }),
        4.0,
        PI * 0.3 / 3f64.sqrt(),
    );
    check(
        "poisson",
        value(Distribution::Poisson { lam: 4.0 }),
        4.0,
        2.0,
    );
    let (m, lambda) = (1.2, 3.0);
    check(
        "wald",
        value(Distribution::Wald {
            mean: m,
            scale: lambda,
        }),
        m,
        (m.powi(3) / lambda).sqrt(),
    );
    check(
        "binomial",
        value(Distribution::Binomial { n: 10, p: 0.3 }),
        3.0,
        (10.0f64 * 0.3 * 0.7).sqrt(),
    );
    check(
        "chisquare",
        value(Distribution::Chisquare { df: 3.0 }),
        3.0,
        6f64.sqrt(),
    );
}

fn truncated(distribution: Distribution, low: Option<f64>, high: Option<f64>) -> Distribution {
    Distribution::Truncated {
        distribution: Box::new(distribution),
        low,
        high,
    }
}

#[test]
fn truncation_keeps_draws_within_its_bounds_and_renormalises() {
    // A standard normal truncated at 0 is the half-normal: mean sqrt(2/π), variance 1 − 2/π
    // (Johnson, Kotz & Balakrishnan, Continuous Univariate Distributions 1, §13.10).
    let half = truncated(
        Distribution::Normal {
            mean: 0.0,
            std: 1.0,
        },
        Some(0.0),
        None,
    );
    let pi = std::f64::consts::PI;
    check(
        "half normal",
        Variation::Value(half.clone()),
        (2.0 / pi).sqrt(),
        (1.0 - 2.0 / pi).sqrt(),
    );
    // A uniform on [0, 10] truncated to [2, 5] is the uniform on [2, 5].
    check(
        "uniform cut",
        Variation::Value(truncated(
            Distribution::Uniform {
                low: 0.0,
                high: 10.0,
            },
            Some(2.0),
            Some(5.0),
        )),
        3.5,
        3.0 / 12f64.sqrt(),
    );
    // Every draw of a two-sided truncation lies within the bounds, on any distribution.
    let gumbel = truncated(
        Distribution::Gumbel {
            loc: 0.0,
            scale: 1.0,
        },
        Some(-0.5),
        Some(1.5),
    );
    let input = VariedInput::new("g", Target::Number(0.0), Variation::Value(gumbel));
    input.check().expect("valid");
    for i in 0..5_000 {
        let x = draw(3, i, std::slice::from_ref(&input))[0];
        assert!((-0.5..=1.5).contains(&x), "sample {i}: {x}");
    }
    let poisson = truncated(Distribution::Poisson { lam: 3.0 }, Some(1.0), Some(4.0));
    assert!(poisson.is_integral());
    let input = VariedInput::new("n", Target::Integer(2), Variation::Value(poisson));
    input.check().expect("a truncated Poisson fits an integer");
    for i in 0..2_000 {
        let x = draw(5, i, std::slice::from_ref(&input))[0];
        assert!(
            [1.0f64, 2.0, 3.0, 4.0]
                .iter()
                .any(|v| v.to_bits() == x.to_bits()),
            "{x}"
        );
    }
}

#[test]
fn the_same_seed_gives_the_same_bits() {
    let inputs: Vec<VariedInput> = [
        Distribution::Exponential { scale: 2.0 },
        Distribution::Gamma {
            shape: 0.5,
            scale: 2.0,
        },
        Distribution::Wald {
            mean: 1.0,
            scale: 2.0,
        },
        Distribution::Binomial { n: 40, p: 0.25 },
        Distribution::Chisquare { df: 1.0 },
        truncated(
            Distribution::Laplace {
                loc: 0.0,
                scale: 1.0,
            },
            Some(0.5),
            None,
        ),
    ]
    .into_iter()
    .enumerate()
    .map(|(i, d)| VariedInput::new(format!("x{i}"), Target::Number(1.0), Variation::Value(d)))
    .collect();
    for index in 0..50 {
        let a = draw(17, index, &inputs);
        let b = draw(17, index, &inputs);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&a), bits(&b));
        assert!(a.iter().all(|x| x.is_finite()), "{a:?}");
    }
    // Another seed gives other draws.
    assert_ne!(
        draw(17, 0, &inputs)[0].to_bits(),
        draw(18, 0, &inputs)[0].to_bits()
    );
}

#[test]
fn bad_parameters_are_refused_naming_the_value() {
    let cases = [
        (Distribution::Exponential { scale: -1.0 }, "scale = -1"),
        (
            Distribution::Gamma {
                shape: 0.0,
                scale: 1.0,
            },
            "shape = 0",
        ),
        (
            Distribution::Gumbel {
                loc: 0.0,
                scale: -2.0,
            },
            "scale = -2",
        ),
        (
            Distribution::Laplace {
                loc: 0.0,
                scale: -0.5,
            },
            "scale = -0.5",
        ),
        (
            Distribution::Logistic {
                loc: f64::NAN,
                scale: 1.0,
            },
            "finite",
        ),
        (Distribution::Poisson { lam: -3.0 }, "lam = -3"),
        (
            Distribution::Poisson { lam: 1e30 },
            "lam = 1000000000000000000000000000000",
        ),
        (
            Distribution::Wald {
                mean: 0.0,
                scale: 1.0,
            },
            "mean = 0",
        ),
        (Distribution::Binomial { n: 3, p: 1.5 }, "p = 1.5"),
        (Distribution::Chisquare { df: 0.0 }, "df = 0"),
        (Distribution::Chisquare { df: f64::INFINITY }, "finite"),
        (
            truncated(
                Distribution::Exponential { scale: 1.0 },
                Some(2.0),
                Some(1.0),
            ),
            "low = 2, high = 1",
        ),
        (
            truncated(Distribution::Exponential { scale: 1.0 }, None, None),
            "a `low` or a `high`",
        ),
        (
            truncated(Distribution::Exponential { scale: -1.0 }, Some(0.0), None),
            "truncated exponential: exponential needs scale >= 0",
        ),
        (
            truncated(
                Distribution::Exponential { scale: 1.0 },
                Some(f64::NAN),
                None,
            ),
            "low = NaN",
        ),
        // A normal's tail beyond 10 σ holds about 1e-23 of it: no rejection sampler gets there.
        (
            truncated(
                Distribution::Normal {
                    mean: 0.0,
                    std: 1.0,
                },
                Some(10.0),
                None,
            ),
            "keep 0 of 20000 draws",
        ),
    ];
    for (distribution, expected) in cases {
        let input = VariedInput::new(
            "rocket.mass",
            Target::Number(1.0),
            Variation::Value(distribution.clone()),
        );
        let error = input.check().expect_err("refused").to_string();
        assert!(
            error.contains("rocket.mass") && error.contains(expected),
            "{distribution:?}: {error}"
        );
    }
    // A continuous distribution does not fit an integer input.
    let input = VariedInput::new(
        "n",
        Target::Integer(1),
        Variation::Value(Distribution::Exponential { scale: 1.0 }),
    );
    assert!(input.check().is_err());
}
