//! Parachute pressure-signal noise (physics.md §9.4).
//!
//! RocketPy draws `n_0 ~ N(μ, σ)` when the parachute is built and then, at every sampling
//! instant, `n_j = ρ_c n_{j−1} + sqrt(1 − ρ_c²) · N(μ, σ)`. Here each parachute owns a
//! [`rand::rngs::StdRng`] seeded from the flight's recorded `u64` seed and the parachute's
//! index, so a noisy flight replays exactly from its seed. Noise `(0, 0, 0)` is identically 0
//! and draws nothing.

use rand::SeedableRng;
use rand::rngs::StdRng;
use rand_distr::{Distribution, Normal};

/// An AR(1) noise stream with normal innovations.
#[derive(Debug, Clone)]
pub struct NoiseStream {
    rng: StdRng,
    normal: Option<Normal<f64>>,
    correlation: f64,
    innovation_scale: f64,
    last: f64,
}

impl NoiseStream {
    /// A stream for noise `(mean, std, correlation)`; `seed` and `index` select the
    /// random sequence. A negative or non-finite standard deviation is treated as 0.
    #[must_use]
    pub fn new(noise: [f64; 3], seed: u64, index: u64) -> Self {
        let [mean, std, correlation] = noise;
        let std = if std.is_finite() && std > 0.0 {
            std
        } else {
            0.0
        };
        let mean = if mean.is_finite() { mean } else { 0.0 };
        // SplitMix64-style mixing of (seed, index) so streams of different parachutes differ.
        let mixed = seed ^ index.wrapping_add(1).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        let mut rng = StdRng::seed_from_u64(mixed);
        let normal = if std > 0.0 || mean != 0.0 {
            Normal::new(mean, std).ok()
        } else {
            None
        };
        let last = normal.map_or(0.0, |n| n.sample(&mut rng));
        let correlation = if correlation.is_finite() {
            correlation.clamp(-1.0, 1.0)
        } else {
            0.0
        };
        Self {
            rng,
            normal,
            correlation,
            innovation_scale: (1.0 - correlation * correlation).sqrt(),
            last,
        }
    }

    /// True when the stream is identically zero (noise `(0, 0, ·)`).
    #[must_use]
    pub fn is_silent(&self) -> bool {
        self.normal.is_none()
    }

    /// Advances the stream one sampling instant and returns the new noise value, Pa.
    pub fn next_value(&mut self) -> f64 {
        let Some(normal) = self.normal else {
            return 0.0;
        };
        self.last =
            self.correlation * self.last + self.innovation_scale * normal.sample(&mut self.rng);
        self.last
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_noise_is_identically_zero() {
        let mut s = NoiseStream::new([0.0, 0.0, 0.0], 7, 0);
        assert!((0..100).all(|_| s.next_value().abs() < f64::MIN_POSITIVE));
    }

    #[test]
    fn same_seed_replays_and_statistics_match() {
        let mut a = NoiseStream::new([1.0, 8.3, 0.5], 42, 1);
        let mut b = NoiseStream::new([1.0, 8.3, 0.5], 42, 1);
        let xs: Vec<f64> = (0..20_000).map(|_| a.next_value()).collect();
        let ys: Vec<f64> = (0..20_000).map(|_| b.next_value()).collect();
        assert!(
            xs.iter()
                .zip(&ys)
                .all(|(x, y)| (x - y).abs() < f64::MIN_POSITIVE)
        );
        // Stationary AR(1) with N(μ, σ) innovations: E[n] = μ sqrt(1 − ρ²)/(1 − ρ)
        // (1.0 · 0.866/0.5 = 1.732) and var = σ² (the innovation scale keeps it).
        let n = xs.len() as f64;
        let mean = xs.iter().sum::<f64>() / n;
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n;
        let expected_mean = 0.75f64.sqrt() / 0.5;
        // Tolerances: ~5 standard errors of the estimators for 20 000 correlated samples.
        assert!((mean - expected_mean).abs() < 0.3, "mean {mean}");
        assert!((var.sqrt() - 8.3).abs() < 0.4, "std {}", var.sqrt());
        let mut c = NoiseStream::new([1.0, 8.3, 0.5], 42, 2);
        assert!(
            (c.next_value() - xs[0]).abs() > 1e-12,
            "different parachutes differ"
        );
    }
}
