//! Distributions of uncertain inputs (mission-format.md "[dispersion]"; docs/physics.md §12.1) and
//! the check that a distribution fits what it varies.
//!
//! Parameters follow NumPy's `Generator` conventions, as RocketPy's stochastic objects do:
//! `normal(mean, std)`, `uniform(low, high)`, `triangular(low, mode, high)`,
//! `lognormal(mu, sigma)` of the underlying normal, and a uniform `choice` among values.

use crate::error::DispersionError;
use rand::Rng;
use rand_distr::Distribution as _;
use serde::{Deserialize, Serialize};

/// A validated probability distribution of one number.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Distribution {
    /// Normal with this mean and standard deviation (`std >= 0`).
    Normal {
        /// Mean.
        mean: f64,
        /// Standard deviation.
        std: f64,
    },
    /// Uniform on `[low, high]` (`low <= high`).
    Uniform {
        /// Lower bound.
        low: f64,
        /// Upper bound.
        high: f64,
    },
    /// Triangular on `[low, high]` with its peak at `mode` (`low <= mode <= high`,
    /// `low < high`).
    Triangular {
        /// Lower bound.
        low: f64,
        /// Peak.
        mode: f64,
        /// Upper bound.
        high: f64,
    },
    /// `exp(N(mu, sigma))` (`sigma >= 0`).
    Lognormal {
        /// Mean of the underlying normal.
        mu: f64,
        /// Standard deviation of the underlying normal.
        sigma: f64,
    },
    /// Each value with equal probability (at least one value).
    Choice(Vec<f64>),
}

impl Distribution {
    /// Checks the parameters; `input` names the varied input in the error.
    pub fn validate(&self, input: &str) -> Result<(), DispersionError> {
        let invalid = |reason: &str| {
            Err(DispersionError::InvalidDistribution {
                input: input.to_owned(),
                reason: reason.to_owned(),
            })
        };
        let finite = match self {
            Distribution::Normal { mean, std } => [*mean, *std].iter().all(|v| v.is_finite()),
            Distribution::Uniform { low, high } => low.is_finite() && high.is_finite(),
            Distribution::Triangular { low, mode, high } => {
                [*low, *mode, *high].iter().all(|v| v.is_finite())
            }
            Distribution::Lognormal { mu, sigma } => mu.is_finite() && sigma.is_finite(),
            Distribution::Choice(values) => values.iter().all(|v| v.is_finite()),
        };
        if !finite {
            return invalid("distribution parameters must be finite numbers");
        }
        match self {
            Distribution::Normal { std, .. } if *std < 0.0 => invalid(&format!(
                "normal needs a standard deviation >= 0, got {std}"
            )),
            Distribution::Uniform { low, high } if low > high => {
                invalid(&format!("uniform needs low <= high, got [{low}, {high}]"))
            }
            Distribution::Triangular { low, mode, high }
                if !(low <= mode && mode <= high && low < high) =>
            {
                invalid(&format!(
                    "triangular needs low <= mode <= high and low < high, got [{low}, {mode}, {high}]"
                ))
            }
            Distribution::Lognormal { sigma, .. } if *sigma < 0.0 => {
                invalid(&format!("lognormal needs sigma >= 0, got {sigma}"))
            }
            Distribution::Choice(values) if values.is_empty() => {
                invalid("choice needs at least one value")
            }
            _ => Ok(()),
        }
    }

    /// One draw. The distribution must have passed [`Distribution::validate`]; a degenerate
    /// case (`std = 0`, `low = high`) returns its single value.
    pub fn sample<R: Rng + ?Sized>(&self, rng: &mut R) -> f64 {
        match self {
            Distribution::Normal { mean, std } => {
                let z: f64 = rand_distr::StandardNormal.sample(rng);
                mean + std * z
            }
            Distribution::Uniform { low, high } => {
                let u: f64 = rng.random();
                low + (high - low) * u
            }
            Distribution::Triangular { low, mode, high } => {
                rand_distr::Triangular::new(*low, *high, *mode)
                    .map_or(*mode, |triangular| triangular.sample(rng))
            }
            Distribution::Lognormal { mu, sigma } => {
                let z: f64 = rand_distr::StandardNormal.sample(rng);
                (mu + sigma * z).exp()
            }
            Distribution::Choice(values) => {
                let pick = rng.random_range(0..values.len().max(1));
                values.get(pick).copied().unwrap_or(f64::NAN)
            }
        }
    }
}

/// How an input varies: the distribution and how a draw combines with the nominal value.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Variation {
    /// `std = σ`: normal around the nominal number, `N(nominal, σ)`.
    Std(f64),
    /// The draw replaces the nominal value.
    Value(Distribution),
    /// The draw multiplies the nominal value (a number or every ordinate of a curve).
    Factor(Distribution),
    /// The draw is added to the nominal value (a number or every ordinate of a curve).
    Offset(Distribution),
}

/// What a draw means to the caller who applies it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Meaning {
    /// The sampled value of the input itself.
    Value,
    /// A factor on the nominal value.
    Factor,
    /// An offset added to the nominal value.
    Offset,
}

/// What a varied input is, as far as the fit of a distribution goes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Target {
    /// A real number with this nominal value (which may be infinite: an input the mission
    /// leaves at an unbounded default, such as `flight.max_time_step`).
    Number(#[serde(with = "extended_real")] f64),
    /// An integer (a count, an index) with this nominal value: only integral `choice` fits.
    Integer(i64),
    /// A curve (a table of points or a file): only `factor` and `offset` fit.
    Curve,
    /// An array of numbers (an inertia tensor) with these nominal components: only `factor`
    /// and `offset` fit, and scale or shift every component.
    Array(#[serde(with = "extended_reals")] Vec<f64>),
}

/// Serde for a nominal value that may be infinite or NaN: JSON has no such numbers
/// (`serde_json` would write `null`, which then fails to read back and makes the study's
/// `study.json` unreadable), so a finite value is a JSON number and any other the string
/// `"inf"`, `"-inf"` or `"NaN"`. Finite values serialise exactly as before, so the
/// fingerprint of a study without such values is unchanged.
mod extended_real {
    use serde::{Deserialize, Deserializer, Serializer};

    /// The text of a non-finite value.
    fn text(value: f64) -> &'static str {
        if value.is_nan() {
            "NaN"
        } else if value > 0.0 {
            "inf"
        } else {
            "-inf"
        }
    }

    pub(super) fn serialize<S: Serializer>(value: &f64, serializer: S) -> Result<S::Ok, S::Error> {
        if value.is_finite() {
            serializer.serialize_f64(*value)
        } else {
            serializer.serialize_str(text(*value))
        }
    }

    /// A number or one of the three texts.
    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Repr {
        Number(f64),
        Text(String),
    }

    impl Repr {
        fn value<E: serde::de::Error>(self) -> Result<f64, E> {
            match self {
                Repr::Number(value) => Ok(value),
                Repr::Text(text) => match text.as_str() {
                    "inf" => Ok(f64::INFINITY),
                    "-inf" => Ok(f64::NEG_INFINITY),
                    "NaN" => Ok(f64::NAN),
                    _ => Err(E::custom(format!(
                        "expected a number, \"inf\", \"-inf\" or \"NaN\", found {text:?}"
                    ))),
                },
            }
        }
    }

    pub(super) fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<f64, D::Error> {
        Repr::deserialize(deserializer)?.value()
    }
}

/// [`extended_real`] for each component of an array.
mod extended_reals {
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    /// One component, in [`super::extended_real`]'s form.
    #[derive(Serialize, Deserialize)]
    struct Component(#[serde(with = "super::extended_real")] f64);

    pub(super) fn serialize<S: Serializer>(
        values: &[f64],
        serializer: S,
    ) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(values.iter().map(|&v| Component(v)))
    }

    pub(super) fn deserialize<'de, D: Deserializer<'de>>(
        deserializer: D,
    ) -> Result<Vec<f64>, D::Error> {
        Ok(Vec::<Component>::deserialize(deserializer)?
            .into_iter()
            .map(|c| c.0)
            .collect())
    }
}

/// One uncertain input of a study.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct VariedInput {
    /// Its name, for a mission the dotted path (`rocket.mass`).
    pub name: String,
    /// What it is and its nominal value.
    pub target: Target,
    /// How it varies.
    pub variation: Variation,
}

impl VariedInput {
    /// A varied input; see [`VariedInput::check`] for validation.
    pub fn new(name: impl Into<String>, target: Target, variation: Variation) -> Self {
        VariedInput {
            name: name.into(),
            target,
            variation,
        }
    }

    /// What the sampled value handed to the flight function means.
    pub fn meaning(&self) -> Meaning {
        match self.variation {
            Variation::Std(_) | Variation::Value(_) => Meaning::Value,
            Variation::Factor(_) => Meaning::Factor,
            Variation::Offset(_) => Meaning::Offset,
        }
    }

    /// Its column in `samples.csv`: the name, with `:factor` or `:offset` appended when the
    /// column holds a factor or an offset rather than the input's value.
    pub fn column(&self) -> String {
        match self.meaning() {
            Meaning::Value => self.name.clone(),
            Meaning::Factor => format!("{}:factor", self.name),
            Meaning::Offset => format!("{}:offset", self.name),
        }
    }

    /// Checks the distribution's parameters and that it fits the target: a curve takes only
    /// `factor`/`offset`; an integer only a `choice` of integers; `std` needs a finite
    /// nominal number.
    pub fn check(&self) -> Result<(), DispersionError> {
        let misfit = |reason: &str| {
            Err(DispersionError::DoesNotFit {
                input: self.name.clone(),
                reason: reason.to_owned(),
            })
        };
        match &self.variation {
            Variation::Std(std) => {
                Distribution::Normal {
                    mean: 0.0,
                    std: *std,
                }
                .validate(&self.name)?;
            }
            Variation::Value(d) | Variation::Factor(d) | Variation::Offset(d) => {
                d.validate(&self.name)?;
            }
        }
        match (&self.target, &self.variation) {
            (Target::Curve, Variation::Factor(_) | Variation::Offset(_)) => Ok(()),
            (Target::Curve, _) => misfit("a curve only takes `factor = ...` or `offset = ...`"),
            (Target::Array(_), Variation::Factor(_) | Variation::Offset(_)) => Ok(()),
            (Target::Array(_), _) => misfit(
                "an array only takes `factor = ...` or `offset = ...` (on every component); \
                 vary one component by its index, `PATH.0`",
            ),
            (Target::Integer(_), Variation::Value(Distribution::Choice(values))) => {
                if values.iter().all(|v| v.fract().abs() <= 0.0) {
                    Ok(())
                } else {
                    misfit("an integer input takes a `choice` of integers")
                }
            }
            (Target::Integer(_), _) => misfit("an integer input only takes `choice = [...]`"),
            (
                Target::Number(nominal),
                Variation::Std(_) | Variation::Factor(_) | Variation::Offset(_),
            ) if !nominal.is_finite() => misfit(
                "`std`, `factor` and `offset` need a finite nominal value (the mission leaves \
                     this input at an unbounded default); draw the value itself with a distribution, \
                     e.g. `{ uniform = [LOW, HIGH] }`, or give the input a value",
            ),
            (Target::Number(_), _) => Ok(()),
        }
    }

    /// One draw: the input's value (`std`, plain distributions), or the factor or offset.
    pub fn sample<R: Rng + ?Sized>(&self, rng: &mut R) -> f64 {
        match &self.variation {
            Variation::Std(std) => {
                let nominal = match self.target {
                    Target::Number(value) => value,
                    Target::Integer(value) => value as f64,
                    Target::Curve | Target::Array(_) => f64::NAN,
                };
                Distribution::Normal {
                    mean: nominal,
                    std: *std,
                }
                .sample(rng)
            }
            Variation::Value(d) | Variation::Factor(d) | Variation::Offset(d) => d.sample(rng),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn input(target: Target, variation: Variation) -> VariedInput {
        VariedInput::new("x", target, variation)
    }

    #[test]
    fn non_finite_nominal_values_round_trip_through_json() {
        for value in [f64::INFINITY, f64::NEG_INFINITY] {
            let target = Target::Number(value);
            let json = serde_json::to_string(&target).unwrap();
            assert!(!json.contains("null"), "{json}");
            assert_eq!(serde_json::from_str::<Target>(&json).unwrap(), target);
        }
        let json = serde_json::to_string(&Target::Number(f64::NAN)).unwrap();
        assert_eq!(json, r#"{"number":"NaN"}"#);
        match serde_json::from_str::<Target>(&json).unwrap() {
            Target::Number(value) => assert!(value.is_nan()),
            other => panic!("{other:?}"),
        }
        let array = Target::Array(vec![1.5, f64::INFINITY, -2.0]);
        let json = serde_json::to_string(&array).unwrap();
        assert_eq!(json, r#"{"array":[1.5,"inf",-2.0]}"#);
        assert_eq!(serde_json::from_str::<Target>(&json).unwrap(), array);
        // Finite values keep their plain JSON form, so old study files read unchanged.
        assert_eq!(
            serde_json::to_string(&Target::Number(0.25)).unwrap(),
            r#"{"number":0.25}"#
        );
        let error = serde_json::from_str::<Target>(r#"{"number":"infinity"}"#).unwrap_err();
        assert!(error.to_string().contains("\"infinity\""), "{error}");
    }

    #[test]
    fn relative_variations_of_an_infinite_nominal_are_refused() {
        for variation in [
            Variation::Std(0.1),
            Variation::Factor(Distribution::Normal {
                mean: 1.0,
                std: 0.1,
            }),
            Variation::Offset(Distribution::Normal {
                mean: 0.0,
                std: 0.1,
            }),
        ] {
            let error = input(Target::Number(f64::INFINITY), variation)
                .check()
                .unwrap_err();
            assert!(
                error.to_string().contains("finite nominal value"),
                "{error}"
            );
        }
        let drawn = Variation::Value(Distribution::Uniform {
            low: 0.05,
            high: 0.2,
        });
        input(Target::Number(f64::INFINITY), drawn).check().unwrap();
    }

    #[test]
    fn parameters_are_checked() {
        let bad = [
            Variation::Std(-1.0),
            Variation::Value(Distribution::Uniform {
                low: 2.0,
                high: 1.0,
            }),
            Variation::Value(Distribution::Triangular {
                low: 0.0,
                mode: 2.0,
                high: 1.0,
            }),
            Variation::Value(Distribution::Triangular {
                low: 1.0,
                mode: 1.0,
                high: 1.0,
            }),
            Variation::Value(Distribution::Lognormal {
                mu: 0.0,
                sigma: -0.1,
            }),
            Variation::Value(Distribution::Choice(vec![])),
            Variation::Factor(Distribution::Normal {
                mean: f64::NAN,
                std: 1.0,
            }),
        ];
        for variation in bad {
            let error = input(Target::Number(1.0), variation.clone()).check();
            assert!(
                matches!(error, Err(DispersionError::InvalidDistribution { .. })),
                "{variation:?} accepted"
            );
        }
    }

    #[test]
    fn fit_to_target() {
        let normal = Distribution::Normal {
            mean: 1.0,
            std: 0.1,
        };
        assert!(
            input(Target::Curve, Variation::Factor(normal.clone()))
                .check()
                .is_ok()
        );
        assert!(input(Target::Curve, Variation::Std(0.1)).check().is_err());
        let array = || Target::Array(vec![1.0, 2.0]);
        assert!(
            input(array(), Variation::Factor(normal.clone()))
                .check()
                .is_ok()
        );
        assert!(
            input(array(), Variation::Offset(normal.clone()))
                .check()
                .is_ok()
        );
        assert!(input(array(), Variation::Std(0.1)).check().is_err());
        assert!(
            input(array(), Variation::Value(normal.clone()))
                .check()
                .is_err()
        );
        assert!(
            input(Target::Curve, Variation::Value(normal.clone()))
                .check()
                .is_err()
        );
        let ints = Distribution::Choice(vec![0.0, 1.0, 2.0]);
        assert!(
            input(Target::Integer(0), Variation::Value(ints))
                .check()
                .is_ok()
        );
        let fractions = Distribution::Choice(vec![0.0, 0.5]);
        let error = input(Target::Integer(0), Variation::Value(fractions)).check();
        assert!(matches!(error, Err(DispersionError::DoesNotFit { .. })));
        assert!(
            input(Target::Integer(0), Variation::Std(1.0))
                .check()
                .is_err()
        );
        assert!(
            input(Target::Number(2.0), Variation::Offset(normal))
                .check()
                .is_ok()
        );
    }

    #[test]
    fn columns_say_what_they_hold() {
        let d = Distribution::Normal {
            mean: 1.0,
            std: 0.1,
        };
        assert_eq!(
            input(Target::Curve, Variation::Factor(d.clone())).column(),
            "x:factor"
        );
        assert_eq!(
            input(Target::Curve, Variation::Offset(d.clone())).column(),
            "x:offset"
        );
        assert_eq!(
            input(Target::Number(1.0), Variation::Value(d)).column(),
            "x"
        );
    }
}
