//! A `[dispersion.vary]` distribution as the dispersion crate draws it
//! (`karman_dispersion::Distribution`), with the parameters of the named distributions
//! checked by NumPy's names (mission-format.md, `[dispersion]`; RocketPy 1.13's
//! `rocketpy.tools.get_distribution` maps the same names onto NumPy's `Generator`).
//!
//! | name | NumPy | parameters, in NumPy's order |
//! |---|---|---|
//! | `exponential` | `exponential(scale)` | `scale` |
//! | `gamma` | `gamma(shape, scale)` | `shape`, `scale` |
//! | `gumbel` | `gumbel(loc, scale)` | `loc`, `scale` |
//! | `laplace` | `laplace(loc, scale)` | `loc`, `scale` |
//! | `logistic` | `logistic(loc, scale)` | `loc`, `scale` |
//! | `poisson` | `poisson(lam)` | `lam` |
//! | `wald` | `wald(mean, scale)` | `mean`, `scale` |
//! | `binomial` | `binomial(n, p)` | `n`, `p` |
//! | `chisquare` | `chisquare(df)` | `df` |

use crate::schema::{Distribution, Parameters};
use karman_dispersion::Distribution as Draw;

/// The largest binomial trial count accepted: every integer up to 2^53 is exact in a float.
const MAX_TRIALS: f64 = 9_007_199_254_740_992.0;

/// NumPy's parameter names of a named distribution, in its positional order.
fn parameter_names(distribution: &Distribution) -> Option<(&'static str, &'static [&'static str])> {
    Some(match distribution {
        Distribution::Exponential(_) => ("exponential", &["scale"]),
        Distribution::Gamma(_) => ("gamma", &["shape", "scale"]),
        Distribution::Gumbel(_) => ("gumbel", &["loc", "scale"]),
        Distribution::Laplace(_) => ("laplace", &["loc", "scale"]),
        Distribution::Logistic(_) => ("logistic", &["loc", "scale"]),
        Distribution::Poisson(_) => ("poisson", &["lam"]),
        Distribution::Wald(_) => ("wald", &["mean", "scale"]),
        Distribution::Binomial(_) => ("binomial", &["n", "p"]),
        Distribution::Chisquare(_) => ("chisquare", &["df"]),
        _ => return None,
    })
}

/// The values of `parameters` in the order of `names`; the error names the distribution, the
/// parameter and the value that is wrong.
fn values(kind: &str, names: &[&str], parameters: &Parameters) -> Result<Vec<f64>, String> {
    let list = names.join(", ");
    match parameters {
        Parameters::Positional(values) => {
            if values.len() == names.len() {
                Ok(values.clone())
            } else {
                Err(format!(
                    "{kind} takes {} parameter{} [{list}], got {} ({values:?})",
                    names.len(),
                    if names.len() == 1 { "" } else { "s" },
                    values.len()
                ))
            }
        }
        Parameters::Named(map) => {
            if let Some(unknown) = map.keys().find(|k| !names.contains(&k.as_str())) {
                return Err(format!(
                    "{kind} has no parameter `{unknown}` (= {}); its parameters are {list} \
                     (NumPy's names)",
                    map[unknown]
                ));
            }
            names
                .iter()
                .map(|name| {
                    map.get(*name)
                        .copied()
                        .ok_or_else(|| format!("{kind} needs `{name}` (its parameters are {list})"))
                })
                .collect()
        }
    }
}

/// The draw of a plain (not `factor` / `offset`) distribution; `std` is a normal around
/// `centre`. The error says what is wrong with a named distribution's parameters (their
/// ranges are [`Draw::validate`]'s).
pub fn plain(distribution: &Distribution, centre: f64) -> Result<Draw, String> {
    if let Some((kind, names)) = parameter_names(distribution) {
        let parameters = match distribution {
            Distribution::Exponential(p)
            | Distribution::Gamma(p)
            | Distribution::Gumbel(p)
            | Distribution::Laplace(p)
            | Distribution::Logistic(p)
            | Distribution::Poisson(p)
            | Distribution::Wald(p)
            | Distribution::Binomial(p)
            | Distribution::Chisquare(p) => p,
            _ => return Err(format!("{kind}: not a named distribution")),
        };
        let v = values(kind, names, parameters)?;
        return Ok(match distribution {
            Distribution::Exponential(_) => Draw::Exponential { scale: v[0] },
            Distribution::Gamma(_) => Draw::Gamma {
                shape: v[0],
                scale: v[1],
            },
            Distribution::Gumbel(_) => Draw::Gumbel {
                loc: v[0],
                scale: v[1],
            },
            Distribution::Laplace(_) => Draw::Laplace {
                loc: v[0],
                scale: v[1],
            },
            Distribution::Logistic(_) => Draw::Logistic {
                loc: v[0],
                scale: v[1],
            },
            Distribution::Poisson(_) => Draw::Poisson { lam: v[0] },
            Distribution::Wald(_) => Draw::Wald {
                mean: v[0],
                scale: v[1],
            },
            Distribution::Binomial(_) => {
                let n = v[0];
                if !(n.is_finite() && n >= 0.0 && n.fract().abs() <= 0.0 && n <= MAX_TRIALS) {
                    return Err(format!(
                        "binomial needs a whole number of trials 0 <= n <= 2^53, got n = {n}"
                    ));
                }
                Draw::Binomial {
                    n: n as u64,
                    p: v[1],
                }
            }
            _ => Draw::Chisquare { df: v[0] },
        });
    }
    Ok(match distribution {
        Distribution::Std(std) => Draw::Normal {
            mean: centre,
            std: *std,
        },
        Distribution::Normal([mean, std]) => Draw::Normal {
            mean: *mean,
            std: *std,
        },
        Distribution::Uniform([low, high]) => Draw::Uniform {
            low: *low,
            high: *high,
        },
        Distribution::Triangular([low, mode, high]) => Draw::Triangular {
            low: *low,
            mode: *mode,
            high: *high,
        },
        Distribution::Lognormal([mu, sigma]) => Draw::Lognormal {
            mu: *mu,
            sigma: *sigma,
        },
        Distribution::Choice(values) => Draw::Choice(values.clone()),
        Distribution::Truncated(truncated) => {
            let inner = match &truncated.distribution {
                Distribution::Std(_) => {
                    return Err("truncated takes a distribution with its own centre \
                                (`normal = [mean, std]`), not `std`"
                        .to_owned());
                }
                Distribution::Factor(_) | Distribution::Offset(_) => {
                    return Err("truncated takes a plain distribution, not `factor` or \
                                `offset` (truncate inside them: `factor = { truncated = ... }`)"
                        .to_owned());
                }
                other => plain(other, centre)?,
            };
            Draw::Truncated {
                distribution: Box::new(inner),
                low: truncated.low,
                high: truncated.high,
            }
        }
        Distribution::Factor(_) | Distribution::Offset(_) => {
            return Err("`factor` and `offset` take a plain distribution".to_owned());
        }
        _ => return Err("not a plain distribution".to_owned()),
    })
}

/// The text of what is wrong with a distribution's parameters, for the located problems of
/// `validate` (`None` when they are valid).
pub fn problem(distribution: &Distribution) -> Option<String> {
    match plain(distribution, 0.0) {
        Err(reason) => Some(reason),
        Ok(draw) => match draw.validate("") {
            Ok(()) => None,
            Err(karman_dispersion::DispersionError::InvalidDistribution { reason, .. }) => {
                Some(reason)
            }
            Err(other) => Some(other.to_string()),
        },
    }
}

/// Whether every draw of `distribution` is an integer (`choice` of integers, `poisson`,
/// `binomial`, a truncation of one): such a distribution fits an integer input.
pub fn is_integral(distribution: &Distribution) -> bool {
    plain(distribution, 0.0).is_ok_and(|draw| draw.is_integral())
}
