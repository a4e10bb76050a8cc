//! RocketPy 1.13's sensor noise model (`rocketpy/sensors/sensor.py`, classes `Sensor`,
//! `InertialSensor`, `ScalarSensor`; docs/physics.md §29.1), applied per component to a true
//! value `x` sampled at rate `f`:
//!
//! ```text
//! w_k  = N(0, √V_w) · D_w · √f                       white noise (density D_w, variance V_w)
//! d_k  = d_{k−1} + N(0, √V_r) · D_r / √f             random walk (density D_r, variance V_r)
//! y    = x + w_k + d_k + b                           constant bias b
//! y    = (y + (T − T_ref) b_T) · (1 + (T − T_ref)/100 · s_T)   temperature bias and scale
//! y    = clamp(y, lo, hi), then round(y / q) · q      range and resolution q (q = 0: none)
//! ```
//!
//! with `T_ref` = [`PhysicalConstants::sensor_reference_temperature`]. Each sensor draws from
//! its own xoshiro256++ stream (Blackman & Vigna 2021, as `rand_xoshiro` implements it)
//! keyed by the flight's seed and the sensor's index: six normal draws per inertial
//! measurement (white x, y, z, then walk x, y, z) and two per scalar one, whatever the
//! parameters, so that a reading depends on the seed, the sensor's index and its instants
//! only. RocketPy draws from NumPy's generator: noisy readings compare in distribution, not
//! value by value.

use karman_math::PhysicalConstants;
use rand::SeedableRng;
use rand_distr::{Distribution, StandardNormal};
use rand_xoshiro::Xoshiro256PlusPlus;

use crate::error::SensorError;

/// The noise parameters of a sensor, one value per axis (a scalar sensor reads axis 0).
/// [`Default`] is RocketPy 1.13's: no noise, bias, drift, range or resolution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NoiseParameters {
    /// `[low, high]` of a reading (saturation), sensor units.
    pub measurement_range: [f64; 2],
    /// Quantisation step of a reading, sensor units (0: none).
    pub resolution: f64,
    /// White-noise density `D_w`, sensor units/√Hz.
    pub noise_density: [f64; 3],
    /// Variance `V_w` of the unit normal the white noise scales (RocketPy's
    /// `noise_variance`, default 1).
    pub noise_variance: [f64; 3],
    /// Random-walk density `D_r`, sensor units·√Hz: the drift's increment per sample is
    /// `N(0, √V_r)·D_r/√f`, so its standard deviation after a time `t` is `D_r √(V_r t)`.
    pub random_walk_density: [f64; 3],
    /// Variance `V_r` of the unit normal the random walk scales (default 1).
    pub random_walk_variance: [f64; 3],
    /// Constant bias, sensor units.
    pub constant_bias: [f64; 3],
    /// Operating temperature `T`, K (default the reference temperature: no drift).
    pub operating_temperature: f64,
    /// Temperature bias `b_T`, sensor units/K.
    pub temperature_bias: [f64; 3],
    /// Temperature scale factor `s_T`, %/K.
    pub temperature_scale_factor: [f64; 3],
}

impl Default for NoiseParameters {
    fn default() -> Self {
        Self {
            measurement_range: [f64::NEG_INFINITY, f64::INFINITY],
            resolution: 0.0,
            noise_density: [0.0; 3],
            noise_variance: [1.0; 3],
            random_walk_density: [0.0; 3],
            random_walk_variance: [1.0; 3],
            constant_bias: [0.0; 3],
            operating_temperature: PhysicalConstants::SI.sensor_reference_temperature,
            temperature_bias: [0.0; 3],
            temperature_scale_factor: [0.0; 3],
        }
    }
}

impl NoiseParameters {
    /// Checks the parameters: finite values (the range may be infinite), non-negative
    /// densities, variances and resolution, a positive temperature, `low ≤ high`.
    ///
    /// # Errors
    /// [`SensorError::Parameter`] naming the first offending parameter.
    pub fn validate(&self) -> Result<(), SensorError> {
        let bad = |name: &'static str, value: f64, reason: &'static str| {
            Err(SensorError::Parameter {
                name,
                value,
                reason,
            })
        };
        let [lo, hi] = self.measurement_range;
        if lo.is_nan() || hi.is_nan() || lo > hi {
            return bad(
                "measurement_range",
                if lo.is_nan() { lo } else { hi },
                "must be [low, high] with low ≤ high",
            );
        }
        if !(self.resolution.is_finite() && self.resolution >= 0.0) {
            return bad(
                "resolution",
                self.resolution,
                "must be finite and non-negative",
            );
        }
        for (name, values) in [
            ("noise_density", self.noise_density),
            ("noise_variance", self.noise_variance),
            ("random_walk_density", self.random_walk_density),
            ("random_walk_variance", self.random_walk_variance),
        ] {
            for v in values {
                if !(v.is_finite() && v >= 0.0) {
                    return bad(name, v, "must be finite and non-negative");
                }
            }
        }
        for (name, values) in [
            ("constant_bias", self.constant_bias),
            ("temperature_bias", self.temperature_bias),
            ("temperature_scale_factor", self.temperature_scale_factor),
        ] {
            for v in values {
                if !v.is_finite() {
                    return bad(name, v, "must be finite");
                }
            }
        }
        let t = self.operating_temperature;
        if !(t.is_finite() && t > 0.0) {
            return bad(
                "operating_temperature",
                t,
                "must be a positive temperature in K",
            );
        }
        Ok(())
    }
}

/// The random state of one sensor: its generator and its random-walk drift.
#[derive(Debug, Clone)]
pub(crate) struct NoiseState {
    rng: Xoshiro256PlusPlus,
    drift: [f64; 3],
}

/// Key of the sensors' streams, apart from the parachutes' (which mix `index + 1` alone):
/// sensor `k` mixes `SENSOR_STREAMS + k + 1`.
const SENSOR_STREAMS: u64 = 1 << 32;

impl NoiseState {
    /// The stream of sensor `index` of a flight seeded with `seed`.
    pub(crate) fn new(seed: u64, index: u64) -> Self {
        let key = SENSOR_STREAMS.wrapping_add(index).wrapping_add(1);
        let mixed = seed ^ key.wrapping_mul(0x9E37_79B9_7F4A_7C15);
        Self {
            rng: Xoshiro256PlusPlus::seed_from_u64(mixed),
            drift: [0.0; 3],
        }
    }

    /// One standard normal draw.
    #[inline]
    pub(crate) fn normal(&mut self) -> f64 {
        StandardNormal.sample(&mut self.rng)
    }

    /// `value` with white noise, random walk and constant bias added on its first `n` axes
    /// (RocketPy's `apply_noise`), at sampling rate `rate`.
    pub(crate) fn apply(&mut self, p: &NoiseParameters, rate: f64, value: &mut [f64; 3], n: usize) {
        let root = rate.sqrt();
        let mut white = [0.0; 3];
        for (i, w) in white.iter_mut().enumerate().take(n) {
            *w = self.normal() * p.noise_variance[i].sqrt() * (p.noise_density[i] * root);
        }
        for i in 0..n {
            self.drift[i] += self.normal()
                * p.random_walk_variance[i].sqrt()
                * (p.random_walk_density[i] / root);
        }
        for i in 0..n {
            value[i] += white[i] + self.drift[i] + p.constant_bias[i];
        }
    }
}

/// `value` with the temperature bias and scale drift applied on its first `n` axes (RocketPy's
/// `apply_temperature_drift`).
pub(crate) fn temperature_drift(p: &NoiseParameters, value: &mut [f64; 3], n: usize) {
    let dt = p.operating_temperature - PhysicalConstants::SI.sensor_reference_temperature;
    let factors = p.temperature_bias.iter().zip(&p.temperature_scale_factor);
    for (v, (bias, scale)) in value.iter_mut().zip(factors).take(n) {
        *v += dt * bias;
        *v *= 1.0 + dt / 100.0 * scale;
    }
}

/// `value` saturated to the measurement range and quantised to the resolution on its first
/// `n` axes (RocketPy's `quantize`: Python's `round`, ties to even).
pub(crate) fn quantize(p: &NoiseParameters, value: &mut [f64; 3], n: usize) {
    let [lo, hi] = p.measurement_range;
    for v in value.iter_mut().take(n) {
        *v = v.max(lo).min(hi);
        if p.resolution != 0.0 {
            *v = (*v / p.resolution).round_ties_even() * p.resolution;
        }
    }
}
