//! Test support for dimensional analysis: random unit systems and scaled comparisons.
//!
//! The check is the one RocketPy runs with Python's `numericalunits` (Ceotto et al. 2021): build
//! and run a model once in SI and once in a unit system where every base unit is rescaled by
//! a random factor, with every input and every physical constant
//! ([`crate::PhysicalConstants::in_units`]) expressed in that system. A dimensionally correct
//! model returns each result multiplied by the factor of its dimension; a length added to an
//! area, or a literal with a hidden unit (a step of `1e-6` meaning seconds), breaks this.
//!
//! Nothing here runs in a simulation: it only builds [`Units`] values and compares numbers,
//! so the production hot path carries no unit checks.
//!
//! ```
//! use karman_math::dimensions::{Dimension, ScaledComparison};
//!
//! let mut check = ScaledComparison::new(7, 1e-12);
//! let u = *check.units();
//! // Kinetic energy ½ m v² in SI and in the scaled units.
//! let energy = |m: f64, v: f64| 0.5 * m * v * v;
//! let si = energy(2.0, 3.0);
//! let scaled = energy(u.scale(2.0, Dimension::MASS), u.scale(3.0, Dimension::VELOCITY));
//! check.compare("energy", si, scaled, Dimension::MASS * Dimension::VELOCITY.powi(2));
//! assert!(check.finish().is_ok());
//! ```

use std::fmt::Write as _;
use std::ops::{Div, Mul};

use crate::Units;

/// Exponents of a dimension `L^length M^mass T^time Θ^temperature`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dimension {
    /// Exponent of length.
    pub length: f64,
    /// Exponent of mass.
    pub mass: f64,
    /// Exponent of time.
    pub time: f64,
    /// Exponent of temperature.
    pub temperature: f64,
}

impl Dimension {
    /// `L^l M^m T^t Θ^k`.
    #[must_use]
    pub const fn new(l: f64, m: f64, t: f64, k: f64) -> Dimension {
        Dimension {
            length: l,
            mass: m,
            time: t,
            temperature: k,
        }
    }
    /// A pure number (Mach, margins, coefficients, angles).
    pub const NONE: Dimension = Dimension::new(0.0, 0.0, 0.0, 0.0);
    /// Length, m.
    pub const LENGTH: Dimension = Dimension::new(1.0, 0.0, 0.0, 0.0);
    /// Mass, kg.
    pub const MASS: Dimension = Dimension::new(0.0, 1.0, 0.0, 0.0);
    /// Time, s.
    pub const TIME: Dimension = Dimension::new(0.0, 0.0, 1.0, 0.0);
    /// Temperature, K.
    pub const TEMPERATURE: Dimension = Dimension::new(0.0, 0.0, 0.0, 1.0);
    /// Area, m².
    pub const AREA: Dimension = Dimension::new(2.0, 0.0, 0.0, 0.0);
    /// Volume, m³.
    pub const VOLUME: Dimension = Dimension::new(3.0, 0.0, 0.0, 0.0);
    /// Frequency or angular rate, 1/s.
    pub const FREQUENCY: Dimension = Dimension::new(0.0, 0.0, -1.0, 0.0);
    /// Velocity, m/s.
    pub const VELOCITY: Dimension = Dimension::new(1.0, 0.0, -1.0, 0.0);
    /// Acceleration, m/s².
    pub const ACCELERATION: Dimension = Dimension::new(1.0, 0.0, -2.0, 0.0);
    /// Force, N.
    pub const FORCE: Dimension = Dimension::new(1.0, 1.0, -2.0, 0.0);
    /// Impulse, N·s.
    pub const IMPULSE: Dimension = Dimension::new(1.0, 1.0, -1.0, 0.0);
    /// Pressure, Pa.
    pub const PRESSURE: Dimension = Dimension::new(-1.0, 1.0, -2.0, 0.0);
    /// Density, kg/m³.
    pub const DENSITY: Dimension = Dimension::new(-3.0, 1.0, 0.0, 0.0);
    /// Dynamic viscosity, Pa·s.
    pub const VISCOSITY: Dimension = Dimension::new(-1.0, 1.0, -1.0, 0.0);
    /// Mass flow rate, kg/s.
    pub const MASS_FLOW: Dimension = Dimension::new(0.0, 1.0, -1.0, 0.0);
    /// Moment of inertia, kg·m².
    pub const INERTIA: Dimension = Dimension::new(2.0, 1.0, 0.0, 0.0);
    /// Specific gas constant, J/(kg·K).
    pub const GAS_CONSTANT: Dimension = Dimension::new(2.0, 0.0, -2.0, -1.0);

    /// This dimension raised to the power `p`.
    #[must_use]
    pub fn powi(self, p: i32) -> Dimension {
        let p = f64::from(p);
        Dimension::new(
            self.length * p,
            self.mass * p,
            self.time * p,
            self.temperature * p,
        )
    }
}

impl Mul for Dimension {
    type Output = Dimension;
    fn mul(self, rhs: Dimension) -> Dimension {
        Dimension::new(
            self.length + rhs.length,
            self.mass + rhs.mass,
            self.time + rhs.time,
            self.temperature + rhs.temperature,
        )
    }
}

impl Div for Dimension {
    type Output = Dimension;
    fn div(self, rhs: Dimension) -> Dimension {
        self * rhs.powi(-1)
    }
}

impl std::fmt::Display for Dimension {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "L^{} M^{} T^{} Θ^{}",
            self.length, self.mass, self.time, self.temperature
        )
    }
}

/// SplitMix64 (Steele, Lea & Flood 2014): a small, seedable generator, enough to draw unit
/// factors without a dependency.
fn splitmix64(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Largest binary exponent of a random unit factor: factors lie in `[2^-E, 2^(E+1))`.
pub const MAX_EXPONENT: i32 = 6;

impl Units {
    /// A random unit system drawn from `seed`: each base factor is `2^k · μ` with `k` uniform
    /// in `−MAX_EXPONENT..=MAX_EXPONENT` and a mantissa `μ` uniform in `[1, 2)`, so the
    /// factors span about four decades and are not powers of two (whose scaling would be
    /// exact in binary floating point and hide rounding-order effects).
    #[must_use]
    pub fn random(seed: u64) -> Units {
        let mut state = seed;
        let mut draw = || {
            let bits = splitmix64(&mut state);
            let span = u64::try_from(2 * MAX_EXPONENT + 1).unwrap_or(1);
            let k = i32::try_from(bits % span).unwrap_or(0) - MAX_EXPONENT;
            // 53 random bits for the mantissa in [1, 2).
            let mantissa = 1.0 + (splitmix64(&mut state) >> 11) as f64 / (1u64 << 53) as f64;
            2f64.powi(k) * mantissa
        };
        Units {
            length: draw(),
            mass: draw(),
            time: draw(),
            temperature: draw(),
        }
    }

    /// The SI value `v` of dimension `d` expressed in this system.
    #[must_use]
    pub fn scale(&self, v: f64, d: Dimension) -> f64 {
        v * self.factor(d.length, d.mass, d.time, d.temperature)
    }
}

/// Seeds for a dimensional test: the one seed `KARMAN_UNITS_SEED` when it is set (to
/// reproduce a failure, or to explore other unit systems as `numericalunits.reset_units()`
/// does), otherwise `n` seeds derived from a fixed base, so that the suite is deterministic.
/// Failure messages name the seed.
#[must_use]
pub fn test_seeds(n: usize) -> Vec<u64> {
    if let Some(seed) = std::env::var("KARMAN_UNITS_SEED")
        .ok()
        .and_then(|s| s.trim().parse().ok())
    {
        return vec![seed];
    }
    let mut state = DEFAULT_UNITS_SEED;
    (0..n).map(|_| splitmix64(&mut state)).collect()
}

/// The base seed of [`test_seeds`] when `KARMAN_UNITS_SEED` is not set.
pub const DEFAULT_UNITS_SEED: u64 = 0x6B61_726D_616E;

/// Relative deviation `|b − a| / |a|` (0 when both are zero, `∞` when only `a` is).
#[must_use]
pub fn relative_deviation(a: f64, b: f64) -> f64 {
    let diff = (b - a).abs();
    if diff <= 0.0 { 0.0 } else { diff / a.abs() }
}

/// Collects comparisons between an SI run and a run in [`Units::random`] units and reports
/// every quantity whose scaled value is not its SI value times the factor of its dimension.
#[derive(Debug, Clone)]
pub struct ScaledComparison {
    seed: u64,
    units: Units,
    tolerance: f64,
    worst: f64,
    worst_name: String,
    failures: Vec<String>,
    count: usize,
}

impl ScaledComparison {
    /// A comparison in the unit system [`Units::random`]`(seed)`, failing on any relative
    /// deviation above `tolerance`.
    #[must_use]
    pub fn new(seed: u64, tolerance: f64) -> ScaledComparison {
        ScaledComparison {
            seed,
            units: Units::random(seed),
            tolerance,
            worst: 0.0,
            worst_name: String::new(),
            failures: Vec::new(),
            count: 0,
        }
    }

    /// The scaled unit system.
    #[must_use]
    pub fn units(&self) -> &Units {
        &self.units
    }

    /// The seed of the unit system.
    #[must_use]
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// Records that `scaled` should equal `si` (dimension `d`) converted to the scaled units,
    /// and returns the relative deviation. Non-finite values count as failures.
    pub fn compare(&mut self, what: &str, si: f64, scaled: f64, d: Dimension) -> f64 {
        self.check(what, si, scaled, d, 0.0, None)
    }

    /// As [`ScaledComparison::compare`] for a quantity that may vanish: the deviation is
    /// measured against `max(|si|, magnitude)`, with `magnitude` the SI size of the quantity
    /// in the problem (a value that should be 0 comes out as rounding noise of that size).
    pub fn compare_near(
        &mut self,
        what: &str,
        si: f64,
        scaled: f64,
        d: Dimension,
        magnitude: f64,
    ) -> f64 {
        self.check(what, si, scaled, d, magnitude, None)
    }

    /// As [`ScaledComparison::compare`] with a tolerance of its own (the caller documents
    /// why this quantity needs it).
    pub fn compare_with(
        &mut self,
        what: &str,
        si: f64,
        scaled: f64,
        d: Dimension,
        tolerance: f64,
    ) -> f64 {
        self.check(what, si, scaled, d, 0.0, Some(tolerance))
    }

    /// The general comparison: deviation against `max(|si|, magnitude)` (`magnitude` 0 for a
    /// plain relative deviation), failing above `tolerance` (the caller documents why this
    /// quantity needs it).
    pub fn record(
        &mut self,
        what: &str,
        si: f64,
        scaled: f64,
        d: Dimension,
        magnitude: f64,
        tolerance: f64,
    ) -> f64 {
        self.check(what, si, scaled, d, magnitude, Some(tolerance))
    }

    /// `tolerance` `None`: the comparison's own, and the deviation counts for
    /// [`ScaledComparison::worst`].
    fn check(
        &mut self,
        what: &str,
        si: f64,
        scaled: f64,
        d: Dimension,
        magnitude: f64,
        tolerance: Option<f64>,
    ) -> f64 {
        self.count += 1;
        let back = scaled / self.units.scale(1.0, d);
        let dev = if !(si.is_finite() && scaled.is_finite()) {
            f64::INFINITY
        } else if magnitude.abs() > si.abs() {
            (back - si).abs() / magnitude.abs()
        } else {
            relative_deviation(si, back)
        };
        if tolerance.is_none() && (dev > self.worst || self.worst_name.is_empty()) {
            self.worst = dev;
            self.worst_name = what.to_owned();
        }
        let tolerance = tolerance.unwrap_or(self.tolerance);
        if dev.is_nan() || dev > tolerance {
            self.failures.push(format!(
                "{what} [{d}]: SI {si:e}, scaled run {scaled:e} = {back:e} in SI, relative \
                 deviation {dev:e} > {tolerance:e}"
            ));
        }
        dev
    }

    /// Largest relative deviation recorded so far among the comparisons at the common
    /// tolerance (not those with a tolerance of their own) and the quantity it belongs to.
    #[must_use]
    pub fn worst(&self) -> (f64, &str) {
        (self.worst, &self.worst_name)
    }

    /// `Ok(largest deviation)` when every comparison passed, otherwise a message naming the
    /// seed (rerun with `KARMAN_UNITS_SEED=<seed>`), the unit factors and every failure.
    ///
    /// # Errors
    /// The message above when a quantity deviates beyond its tolerance or no comparison was
    /// made.
    pub fn finish(&self) -> Result<f64, String> {
        if self.failures.is_empty() && self.count > 0 {
            return Ok(self.worst);
        }
        let u = &self.units;
        let mut msg = format!(
            "dimensional check failed for unit seed {} (rerun with KARMAN_UNITS_SEED={}): \
             1 m = {:e}, 1 kg = {:e}, 1 s = {:e}, 1 K = {:e}; {} of {} comparisons failed",
            self.seed,
            self.seed,
            u.length,
            u.mass,
            u.time,
            u.temperature,
            self.failures.len(),
            self.count
        );
        for f in &self.failures {
            let _ = write!(msg, "\n  {f}");
        }
        Err(msg)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn random_units_are_reproducible_and_spread() {
        let a = Units::random(42);
        assert_eq!(a, Units::random(42));
        assert_ne!(a, Units::random(43));
        let lo = 2f64.powi(-MAX_EXPONENT);
        let hi = 2f64.powi(MAX_EXPONENT + 1);
        let mut exponents = std::collections::BTreeSet::new();
        for seed in 0..200 {
            let u = Units::random(seed);
            for f in [u.length, u.mass, u.time, u.temperature] {
                assert!(f >= lo && f < hi, "{f}");
                exponents.insert(f.log2().floor() as i32);
            }
        }
        assert_eq!(exponents.len(), 2 * MAX_EXPONENT as usize + 1);
    }

    #[test]
    fn dimension_algebra() {
        let d = Dimension::FORCE / Dimension::AREA;
        assert_eq!(d, Dimension::PRESSURE);
        assert_eq!(Dimension::LENGTH.powi(3), Dimension::VOLUME);
        let u = Units::random(1);
        let p = u.scale(1.0, Dimension::PRESSURE);
        assert!((p - u.mass / (u.length * u.time * u.time)).abs() <= 1e-15 * p);
    }

    #[test]
    fn comparison_reports_the_seed_and_the_culprit() {
        let mut c = ScaledComparison::new(9, 1e-12);
        let u = *c.units();
        c.compare("ok", 2.0, u.scale(2.0, Dimension::AREA), Dimension::AREA);
        c.compare(
            "wrong",
            2.0,
            u.scale(2.0, Dimension::LENGTH),
            Dimension::AREA,
        );
        let e = c.finish().expect_err("the length is not an area");
        assert!(
            e.contains("KARMAN_UNITS_SEED=9") && e.contains("wrong"),
            "{e}"
        );
        assert!(!e.contains("\n  ok"), "{e}");
        assert!(
            ScaledComparison::new(1, 1.0).finish().is_err(),
            "nothing compared"
        );
    }
}
