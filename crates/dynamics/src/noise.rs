//! Parachute pressure-signal noise (physics.md §9.4).
//!
//! RocketPy draws `n_0 ~ N(μ, σ)` when the parachute is built and then, at every sampling
//! instant, `n_j = ρ_c n_{j−1} + sqrt(1 − ρ_c²) · N(μ, σ)`. Here each parachute owns a
//! xoshiro256++ generator (Blackman & Vigna 2021, *Scrambled linear pseudorandom number
//! generators*, ACM Trans. Math. Softw. 47(4), as `rand_xoshiro` implements it; seeded through
//! SplitMix64) keyed by the flight's recorded `u64` seed and the parachute's index, so a noisy
//! flight replays exactly from its seed, on any platform and with any `rand` release (the
//! generator is named, unlike `rand`'s `StdRng`), and a draw costs a few nanoseconds (the
//! Calisto main parachute draws ~16,600 times per flight). Noise `(0, 0, 0)` is identically 0
//! and draws nothing.
//!
//! The flight engine may look ahead ([`NoiseStream::peek_max`]): values drawn before their
//! sampling instant are kept and handed out, in order, by [`NoiseStream::next_value`] and
//! [`NoiseStream::skip`], so the `k`-th value a stream delivers is the same whether or not it
//! was looked at early (the sequence, not the time of the draw, fixes the noise).

use rand::{Rng, SeedableRng};
use rand_distr::{Distribution, Normal, StandardNormal};
use rand_xoshiro::Xoshiro256PlusPlus;

/// An AR(1) noise stream with normal innovations.
#[derive(Debug, Clone)]
pub struct NoiseStream {
    rng: Xoshiro256PlusPlus,
    normal: Option<Normal<f64>>,
    correlation: f64,
    innovation_scale: f64,
    last: f64,
    /// Values drawn ahead of their instants; `ahead[head..]` are still to be delivered.
    ahead: Vec<f64>,
    head: usize,
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
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(mixed);
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
            ahead: Vec::new(),
            head: 0,
        }
    }

    /// True when the stream is identically zero (noise `(0, 0, ·)`).
    #[must_use]
    pub fn is_silent(&self) -> bool {
        self.normal.is_none()
    }

    /// Advances the stream one sampling instant and returns the new noise value, Pa.
    pub fn next_value(&mut self) -> f64 {
        if let Some(&value) = self.ahead.get(self.head) {
            self.head += 1;
            return value;
        }
        self.draw()
    }

    /// The largest of the next `count` values (−∞ for `count = 0`), Pa, without advancing the
    /// stream: the values are drawn now and delivered later. Allocation-free once the
    /// look-ahead buffer has grown to the largest `count` asked for.
    pub fn peek_max(&mut self, count: usize) -> f64 {
        let Some(normal) = self.normal else {
            return if count == 0 { f64::NEG_INFINITY } else { 0.0 };
        };
        if self.head > 0 {
            self.ahead.drain(..self.head);
            self.head = 0;
        }
        let mut max = self.ahead[..count.min(self.ahead.len())]
            .iter()
            .fold(f64::NEG_INFINITY, |max, &v| max.max(v));
        let mut last = self.last;
        for _ in self.ahead.len()..count {
            last = self.step(normal, last);
            self.ahead.push(last);
            max = max.max(last);
        }
        self.last = last;
        max
    }

    /// Advances the stream `count` sampling instants, discarding the values.
    pub fn skip(&mut self, count: usize) {
        let Some(normal) = self.normal else {
            return;
        };
        let buffered = (self.ahead.len() - self.head).min(count);
        self.head += buffered;
        if self.head == self.ahead.len() {
            self.ahead.clear();
            self.head = 0;
        }
        let mut last = self.last;
        for _ in buffered..count {
            last = self.step(normal, last);
        }
        self.last = last;
    }

    /// Draws the next value of the AR(1) recursion.
    fn draw(&mut self) -> f64 {
        let Some(normal) = self.normal else {
            return 0.0;
        };
        self.last = self.step(normal, self.last);
        self.last
    }

    /// One step of the AR(1) recursion from `last`: `ρ · last + √(1 − ρ²) · N(μ, σ)`.
    #[inline]
    fn step(&mut self, normal: Normal<f64>, last: f64) -> f64 {
        self.correlation * last
            + self.innovation_scale * normal.from_zscore(self.rng.sample(StandardNormal))
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

    #[test]
    fn look_ahead_keeps_the_sequence() {
        let mut plain = NoiseStream::new([0.5, 8.3, 0.5], 9, 3);
        let reference: Vec<f64> = (0..40).map(|_| plain.next_value()).collect();
        let mut s = NoiseStream::new([0.5, 8.3, 0.5], 9, 3);
        let mut got = Vec::new();
        let max5 = s.peek_max(5);
        assert_eq!(
            max5.to_bits(),
            reference[..5]
                .iter()
                .copied()
                .fold(f64::NEG_INFINITY, f64::max)
                .to_bits()
        );
        got.push(s.next_value());
        got.push(s.next_value());
        // A longer look-ahead over partly consumed values, then a skip across the buffer end.
        let max10 = s.peek_max(10);
        assert_eq!(
            max10.to_bits(),
            reference[2..12]
                .iter()
                .copied()
                .fold(f64::NEG_INFINITY, f64::max)
                .to_bits()
        );
        s.skip(3);
        got.extend(reference[2..5].iter());
        got.push(s.next_value());
        s.skip(20);
        got.extend(reference[6..26].iter());
        assert!(s.peek_max(0).is_infinite());
        got.extend((26..40).map(|_| s.next_value()));
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&got), bits(&reference));
        let mut silent = NoiseStream::new([0.0; 3], 9, 3);
        assert!(silent.peek_max(4).abs() < f64::MIN_POSITIVE);
        silent.skip(4);
        assert!(silent.next_value().abs() < f64::MIN_POSITIVE);
    }
}
