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
    /// Exponential, density `exp(−x/β)/β` on `x ≥ 0` (NumPy's `exponential(scale)`, `β >= 0`).
    Exponential {
        /// The scale `β` (the mean).
        scale: f64,
    },
    /// Gamma, density `x^(k−1) exp(−x/θ) / (Γ(k) θ^k)` (NumPy's `gamma(shape, scale)`,
    /// `k > 0`, `θ > 0`).
    Gamma {
        /// The shape `k`.
        shape: f64,
        /// The scale `θ`.
        scale: f64,
    },
    /// Gumbel (largest extreme value), CDF `exp(−exp(−(x−μ)/β))` (NumPy's
    /// `gumbel(loc, scale)`, `β >= 0`).
    Gumbel {
        /// The mode `μ`.
        loc: f64,
        /// The scale `β`.
        scale: f64,
    },
    /// Laplace (double exponential), density `exp(−|x−μ|/λ) / (2λ)` (NumPy's
    /// `laplace(loc, scale)`, `λ >= 0`).
    Laplace {
        /// The centre `μ`.
        loc: f64,
        /// The scale `λ`.
        scale: f64,
    },
    /// Logistic, CDF `1 / (1 + exp(−(x−μ)/s))` (NumPy's `logistic(loc, scale)`, `s >= 0`).
    Logistic {
        /// The centre `μ`.
        loc: f64,
        /// The scale `s`.
        scale: f64,
    },
    /// Poisson, `P(k) = λ^k e^(−λ) / k!` on the integers `k ≥ 0` (NumPy's `poisson(lam)`,
    /// `0 <= λ <= 1e18`).
    Poisson {
        /// The rate `λ` (the mean).
        lam: f64,
    },
    /// Wald (inverse Gaussian), density `sqrt(λ / (2π x³)) exp(−λ (x−μ)² / (2 μ² x))` on
    /// `x > 0` (NumPy's `wald(mean, scale)`, `μ > 0`, `λ > 0`).
    Wald {
        /// The mean `μ`.
        mean: f64,
        /// The scale (shape) `λ`.
        scale: f64,
    },
    /// Binomial, the number of successes in `n` trials of probability `p` (NumPy's
    /// `binomial(n, p)`, `0 <= p <= 1`).
    Binomial {
        /// The number of trials.
        n: u64,
        /// The probability of success of each trial.
        p: f64,
    },
    /// Chi-square with `k` degrees of freedom, the gamma of shape `k/2` and scale 2 (NumPy's
    /// `chisquare(df)`, `k > 0`).
    Chisquare {
        /// The degrees of freedom `k`.
        df: f64,
    },
    /// `distribution` restricted to `[low, high]` (either bound may be absent): the density
    /// of the inner distribution renormalised on the bounds, drawn by rejection (a draw out
    /// of the bounds is drawn again from the same stream, so the draws stay a function of the
    /// stream alone). The bounds must keep at least [`TRUNCATION_MIN_SHARE`] of the inner
    /// distribution.
    Truncated {
        /// The distribution that is truncated.
        distribution: Box<Distribution>,
        /// The lower bound (inclusive).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        low: Option<f64>,
        /// The upper bound (inclusive).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        high: Option<f64>,
    },
}

/// The least share of its inner distribution a truncation must keep: below it the rejection
/// sampling would cost more than a flight, and the bounds are almost surely a mistake.
pub const TRUNCATION_MIN_SHARE: f64 = 1e-3;

/// Draws of the untruncated distribution that [`Distribution::validate`] counts inside a
/// truncation's bounds to check [`TRUNCATION_MIN_SHARE`] (a fixed stream, so the check is
/// the same on every machine).
const TRUNCATION_CHECK_DRAWS: u32 = 20_000;

/// The seed of the fixed stream [`Distribution::validate`] checks a truncation's share on
/// (the bytes of "truncate").
const TRUNCATION_CHECK_SEED: u64 = 0x7472_756e_6361_7465;

/// Draws a truncated distribution tries before giving up with NaN. With a share of at least
/// [`TRUNCATION_MIN_SHARE`] kept, giving up has a probability below `(1 − 1e-3)^1e6 ≈ e^−1000`.
const TRUNCATION_MAX_ATTEMPTS: u32 = 1_000_000;

/// The largest binomial trial count accepted: 2^53, every count up to it exact in a float.
const MAX_TRIALS: u64 = 1 << 53;

/// The largest Poisson rate accepted: NumPy's `poisson` refuses rates above about
/// `9.2e18` (its 64-bit integer range); 1e18 stays within every sampler's range.
const POISSON_MAX_LAM: f64 = 1e18;

/// A uniform number in the open interval (0, 1), for the inverse-CDF draws whose logarithm
/// must stay finite.
fn open01<R: Rng + ?Sized>(rng: &mut R) -> f64 {
    rand_distr::Open01.sample(rng)
}

impl Distribution {
    /// Its name as the mission file writes it (`normal`, `gamma`, ...).
    pub fn name(&self) -> &'static str {
        match self {
            Distribution::Normal { .. } => "normal",
            Distribution::Uniform { .. } => "uniform",
            Distribution::Triangular { .. } => "triangular",
            Distribution::Lognormal { .. } => "lognormal",
            Distribution::Choice(_) => "choice",
            Distribution::Exponential { .. } => "exponential",
            Distribution::Gamma { .. } => "gamma",
            Distribution::Gumbel { .. } => "gumbel",
            Distribution::Laplace { .. } => "laplace",
            Distribution::Logistic { .. } => "logistic",
            Distribution::Poisson { .. } => "poisson",
            Distribution::Wald { .. } => "wald",
            Distribution::Binomial { .. } => "binomial",
            Distribution::Chisquare { .. } => "chisquare",
            Distribution::Truncated { .. } => "truncated",
        }
    }

    /// Whether every draw is an integer (a Poisson, a binomial, a `choice` of integers, or a
    /// truncation of one): such a distribution fits an integer input.
    pub fn is_integral(&self) -> bool {
        match self {
            Distribution::Poisson { .. } | Distribution::Binomial { .. } => true,
            Distribution::Choice(values) => values.iter().all(|v| v.fract().abs() <= 0.0),
            Distribution::Truncated { distribution, .. } => distribution.is_integral(),
            _ => false,
        }
    }

    /// Checks the parameters; `input` names the varied input in the error.
    pub fn validate(&self, input: &str) -> Result<(), DispersionError> {
        self.problem().map_or(Ok(()), |reason| {
            Err(DispersionError::InvalidDistribution {
                input: input.to_owned(),
                reason,
            })
        })
    }

    /// What is wrong with the parameters, if anything (the text names each bad value).
    fn problem(&self) -> Option<String> {
        let finite = match self {
            Distribution::Normal { mean, std } => [*mean, *std].iter().all(|v| v.is_finite()),
            Distribution::Uniform { low, high } => low.is_finite() && high.is_finite(),
            Distribution::Triangular { low, mode, high } => {
                [*low, *mode, *high].iter().all(|v| v.is_finite())
            }
            Distribution::Lognormal { mu, sigma } => mu.is_finite() && sigma.is_finite(),
            Distribution::Choice(values) => values.iter().all(|v| v.is_finite()),
            Distribution::Exponential { scale } => scale.is_finite(),
            Distribution::Poisson { lam } => lam.is_finite(),
            Distribution::Chisquare { df } => df.is_finite(),
            Distribution::Binomial { p, .. } => p.is_finite(),
            Distribution::Gamma { shape: a, scale: b }
            | Distribution::Gumbel { loc: a, scale: b }
            | Distribution::Laplace { loc: a, scale: b }
            | Distribution::Logistic { loc: a, scale: b }
            | Distribution::Wald { mean: a, scale: b } => a.is_finite() && b.is_finite(),
            Distribution::Truncated { low, high, .. } => {
                low.is_none_or(f64::is_finite) && high.is_none_or(f64::is_finite)
            }
        };
        if !finite {
            return Some(match self {
                Distribution::Truncated { low, high, .. } => format!(
                    "truncated needs finite bounds (leave a bound out for none), got low = {}, high = {}",
                    bound_text(*low),
                    bound_text(*high)
                ),
                _ => "distribution parameters must be finite numbers".to_owned(),
            });
        }
        match self {
            Distribution::Normal { std, .. } if *std < 0.0 => {
                Some(format!("normal needs a standard deviation >= 0, got {std}"))
            }
            Distribution::Uniform { low, high } if low > high => {
                Some(format!("uniform needs low <= high, got [{low}, {high}]"))
            }
            Distribution::Triangular { low, mode, high }
                if !(low <= mode && mode <= high && low < high) =>
            {
                Some(format!(
                    "triangular needs low <= mode <= high and low < high, got [{low}, {mode}, {high}]"
                ))
            }
            Distribution::Lognormal { sigma, .. } if *sigma < 0.0 => {
                Some(format!("lognormal needs sigma >= 0, got {sigma}"))
            }
            Distribution::Choice(values) if values.is_empty() => {
                Some("choice needs at least one value".to_owned())
            }
            Distribution::Exponential { scale } if *scale < 0.0 => {
                Some(format!("exponential needs scale >= 0, got scale = {scale}"))
            }
            Distribution::Gamma { shape, scale } if !(*shape > 0.0 && *scale > 0.0) => {
                Some(format!(
                    "gamma needs shape > 0 and scale > 0, got shape = {shape}, scale = {scale}"
                ))
            }
            Distribution::Gumbel { scale, .. }
            | Distribution::Laplace { scale, .. }
            | Distribution::Logistic { scale, .. }
                if *scale < 0.0 =>
            {
                Some(format!(
                    "{} needs scale >= 0, got scale = {scale}",
                    self.name()
                ))
            }
            Distribution::Poisson { lam } if !(0.0..=POISSON_MAX_LAM).contains(lam) => Some(
                format!("poisson needs 0 <= lam <= {POISSON_MAX_LAM:e}, got lam = {lam}"),
            ),
            Distribution::Wald { mean, scale } if !(*mean > 0.0 && *scale > 0.0) => Some(format!(
                "wald needs mean > 0 and scale > 0, got mean = {mean}, scale = {scale}"
            )),
            Distribution::Binomial { p, .. } if !(0.0..=1.0).contains(p) => {
                Some(format!("binomial needs 0 <= p <= 1, got p = {p}"))
            }
            // rand_distr's sampler needs n·p within the 64-bit integers (it asserts so): every
            // count up to 2^53 is exact in a float and far within.
            Distribution::Binomial { n, .. } if *n > MAX_TRIALS => Some(format!(
                "binomial needs n <= 2^53 ({MAX_TRIALS}), got n = {n}"
            )),
            Distribution::Chisquare { df } if *df <= 0.0 => {
                Some(format!("chisquare needs df > 0, got df = {df}"))
            }
            Distribution::Truncated {
                distribution,
                low,
                high,
            } => truncation_problem(distribution, *low, *high),
            _ => None,
        }
    }

    /// One draw. The distribution must have passed [`Distribution::validate`]; a degenerate
    /// case (`std = 0`, `low = high`, a zero scale) returns its single value.
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
            // β·E with E a standard exponential (rand_distr's ziggurat `Exp1`).
            Distribution::Exponential { scale } => {
                let e: f64 = rand_distr::Exp1.sample(rng);
                scale * e
            }
            // Marsaglia & Tsang (2000), as rand_distr implements it.
            Distribution::Gamma { shape, scale } => {
                rand_distr::Gamma::new(*shape, *scale).map_or(f64::NAN, |gamma| gamma.sample(rng))
            }
            // Inverse CDF: x = μ − β ln(−ln U), U uniform on (0, 1).
            Distribution::Gumbel { loc, scale } => loc - scale * (-open01(rng).ln()).ln(),
            // Inverse CDF with V = U − ½ on (−½, ½): x = μ − λ sgn(V) ln(1 − 2|V|).
            Distribution::Laplace { loc, scale } => {
                let v = open01(rng) - 0.5;
                loc - scale * v.signum() * (1.0 - 2.0 * v.abs()).ln()
            }
            // Inverse CDF: x = μ + s ln(U / (1 − U)).
            Distribution::Logistic { loc, scale } => {
                let u = open01(rng);
                loc + scale * (u / (1.0 - u)).ln()
            }
            Distribution::Poisson { lam } => {
                if *lam <= 0.0 {
                    0.0
                } else {
                    rand_distr::Poisson::new(*lam).map_or(f64::NAN, |poisson| poisson.sample(rng))
                }
            }
            // Michael, Schucany & Haas (1976), as rand_distr's `InverseGaussian`.
            Distribution::Wald { mean, scale } => rand_distr::InverseGaussian::new(*mean, *scale)
                .map_or(f64::NAN, |wald| wald.sample(rng)),
            Distribution::Binomial { n, p } => rand_distr::Binomial::new(*n, *p)
                .map_or(f64::NAN, |binomial| binomial.sample(rng) as f64),
            Distribution::Chisquare { df } => rand_distr::ChiSquared::new(*df)
                .map_or(f64::NAN, |chi_square| chi_square.sample(rng)),
            Distribution::Truncated {
                distribution,
                low,
                high,
            } => {
                for _ in 0..TRUNCATION_MAX_ATTEMPTS {
                    let x = distribution.sample(rng);
                    if within(x, *low, *high) {
                        return x;
                    }
                }
                f64::NAN
            }
        }
    }
}

/// Whether `x` lies within the inclusive bounds (an absent bound is no bound).
fn within(x: f64, low: Option<f64>, high: Option<f64>) -> bool {
    low.is_none_or(|low| x >= low) && high.is_none_or(|high| x <= high)
}

fn bound_text(bound: Option<f64>) -> String {
    bound.map_or_else(|| "none".to_owned(), |b| b.to_string())
}

/// What is wrong with a truncation: its inner distribution, reversed or absent bounds, or
/// bounds that keep less than [`TRUNCATION_MIN_SHARE`] of it.
fn truncation_problem(inner: &Distribution, low: Option<f64>, high: Option<f64>) -> Option<String> {
    if let Some(reason) = inner.problem() {
        return Some(format!("truncated {}: {reason}", inner.name()));
    }
    if low.is_none() && high.is_none() {
        return Some("truncated needs a `low` or a `high` bound (or both)".to_owned());
    }
    if let (Some(low), Some(high)) = (low, high) {
        if low > high {
            return Some(format!(
                "truncated needs low <= high, got low = {low}, high = {high}"
            ));
        }
    }
    // The share kept, estimated from a fixed stream of the untruncated distribution.
    let mut rng =
        <rand_chacha::ChaCha8Rng as rand::SeedableRng>::seed_from_u64(TRUNCATION_CHECK_SEED);
    let kept = (0..TRUNCATION_CHECK_DRAWS)
        .filter(|_| within(inner.sample(&mut rng), low, high))
        .count();
    let share = kept as f64 / f64::from(TRUNCATION_CHECK_DRAWS);
    if share < TRUNCATION_MIN_SHARE {
        return Some(format!(
            "truncated {}: the bounds low = {}, high = {} keep {kept} of {TRUNCATION_CHECK_DRAWS} \
             draws of the distribution, less than the {} % required; widen them",
            inner.name(),
            bound_text(low),
            bound_text(high),
            TRUNCATION_MIN_SHARE * 100.0
        ));
    }
    None
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
            (Target::Integer(_), Variation::Value(d)) if d.is_integral() => Ok(()),
            (Target::Integer(_), _) => misfit(
                "an integer input only takes `choice = [...]` of integers, `poisson` or \
                 `binomial` (or a truncation of one)",
            ),
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
