//! Parachute pressure-signal noise (docs/physics.md §9.4).
//!
//! RocketPy draws `n_0 ~ N(μ, σ)` when the parachute is built and then, at every sampling
//! instant, `n_j = ρ n_{j−1} + s · N(μ, σ)` with `s = √(1 − ρ²)`. Here each parachute owns a
//! xoshiro256++ generator (Blackman & Vigna 2021, *Scrambled linear pseudorandom number
//! generators*, ACM Trans. Math. Softw. 47(4), as `rand_xoshiro` implements it; seeded through
//! SplitMix64) keyed by the flight's recorded `u64` seed and the parachute's index, so a noisy
//! flight replays exactly from its seed, on any platform and with any `rand` release (the
//! generator is named, unlike `rand`'s `StdRng`). Noise `(0, 0, 0)` is identically 0 and draws
//! nothing.
//!
//! Most sampling instants cannot fire a trigger (the rocket is climbing, or far above the
//! trigger height), yet the stream must still advance through them. [`NoiseStream::skip`]
//! jumps `m` instants at once with the exact `m`-step law of the recursion (one draw instead
//! of `m`): with the stationary mean `n̄ = μ s/(1 − ρ)`,
//!
//! `n_{j+m} = n̄ + ρ^m (n_j − n̄) + σ √(1 − ρ^{2m}) · Z`,  `Z ~ N(0, 1)`
//!
//! (the innovations' sum is normal with variance `s²σ² Σ_{k<m} ρ^{2k} = σ²(1 − ρ^{2m})`). The
//! values at the skipped instants are never drawn; the flight engine excludes a trigger from
//! a step only when [`NoiseStream::upper_bound`] — every coming value's conditional mean plus
//! [`EXCLUSION_SIGMAS`] conditional standard deviations — cannot reach it.

use rand::{Rng, SeedableRng};
use rand_distr::{Distribution, Normal, StandardNormal};
use rand_xoshiro::Xoshiro256PlusPlus;

/// Standard deviations above its conditional mean at which a skipped noise value is taken as
/// unreachable. A normal value exceeds it with probability `Q(12) ≈ 1.8e-33`, so even 10¹²
/// flights of 10⁵ skipped instants each would differ from drawing every instant with
/// probability below 2e-16.
pub const EXCLUSION_SIGMAS: f64 = 12.0;

/// An AR(1) noise stream with normal innovations.
#[derive(Debug, Clone)]
pub struct NoiseStream {
    rng: Xoshiro256PlusPlus,
    normal: Option<Normal<f64>>,
    correlation: f64,
    innovation_scale: f64,
    /// Stationary mean `n̄ = μ s/(1 − ρ)` (0 when `s = 0`: the stream is then constant or
    /// alternates, `n_{j+1} = ρ n_j` with `ρ = ±1`).
    stationary_mean: f64,
    last: f64,
    /// Test-only: [`NoiseStream::skip`] draws every skipped instant, as
    /// [`NoiseStream::next_value`] would (the oracle of the flight engine's bounds).
    #[cfg(test)]
    stepwise: bool,
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
        let innovation_scale = (1.0 - correlation * correlation).sqrt();
        let stationary_mean = if innovation_scale > 0.0 {
            mean * innovation_scale / (1.0 - correlation)
        } else {
            0.0
        };
        Self {
            rng,
            normal,
            correlation,
            innovation_scale,
            stationary_mean,
            last,
            #[cfg(test)]
            stepwise: false,
        }
    }

    /// Test-only: the same stream with [`NoiseStream::skip`] drawing every instant.
    #[cfg(test)]
    #[must_use]
    pub(crate) fn stepwise(self) -> Self {
        Self {
            stepwise: true,
            ..self
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
        self.last = self.correlation * self.last
            + self.innovation_scale * normal.from_zscore(self.rng.sample(StandardNormal));
        self.last
    }

    /// An upper bound of every coming value, Pa: the largest conditional mean,
    /// `n̄ + |n_j − n̄|`, plus [`EXCLUSION_SIGMAS`] times the largest conditional standard
    /// deviation, `σ` (the `k`-step law from the current value `n_j` has mean
    /// `n̄ + ρ^k (n_j − n̄)` and standard deviation `σ √(1 − ρ^{2k})`). 0 for a silent stream.
    #[must_use]
    pub fn upper_bound(&self) -> f64 {
        self.normal.map_or(0.0, |normal| {
            self.stationary_mean
                + (self.last - self.stationary_mean).abs()
                + EXCLUSION_SIGMAS * normal.std_dev()
        })
    }

    /// Advances the stream `count` sampling instants at once, with the exact `count`-step law
    /// (module documentation); a single instant is one [`NoiseStream::next_value`].
    pub fn skip(&mut self, count: usize) {
        let Some(normal) = self.normal else {
            return;
        };
        #[cfg(test)]
        if self.stepwise {
            for _ in 0..count {
                self.next_value();
            }
            return;
        }
        match count {
            0 => {}
            1 => {
                self.next_value();
            }
            _ => {
                // ρ^m underflows to 0 long before m reaches i32::MAX.
                let decay = self
                    .correlation
                    .powi(i32::try_from(count).unwrap_or(i32::MAX));
                let z: f64 = self.rng.sample(StandardNormal);
                self.last = self.stationary_mean
                    + decay * (self.last - self.stationary_mean)
                    + normal.std_dev() * (1.0 - decay * decay).sqrt() * z;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_noise_is_identically_zero() {
        let mut s = NoiseStream::new([0.0, 0.0, 0.0], 7, 0);
        assert!((0..100).all(|_| s.next_value().abs() < f64::MIN_POSITIVE));
        s.skip(1000);
        assert!(s.next_value().abs() < f64::MIN_POSITIVE);
        assert!(s.upper_bound().abs() < f64::MIN_POSITIVE);
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
        assert!((a.stationary_mean - expected_mean).abs() < 1e-15);
        // Tolerances: ~5 standard errors of the estimators for 20 000 correlated samples.
        assert!((mean - expected_mean).abs() < 0.3, "mean {mean}");
        assert!((var.sqrt() - 8.3).abs() < 0.4, "std {}", var.sqrt());
        let mut c = NoiseStream::new([1.0, 8.3, 0.5], 42, 2);
        assert!(
            (c.next_value() - xs[0]).abs() > 1e-12,
            "different parachutes differ"
        );
    }

    /// Sample mean and standard deviation.
    fn moments(xs: &[f64]) -> (f64, f64) {
        let n = xs.len() as f64;
        let mean = xs.iter().sum::<f64>() / n;
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
        (mean, var.sqrt())
    }

    #[test]
    fn a_skip_follows_the_law_of_the_skipped_steps() {
        // From a fixed value far from the stationary mean, the value after m instants is
        // drawn (a) step by step, as the recursion defines it, and (b) by one skip. Both
        // samples must match the m-step law's mean n̄ + ρ^m (n_0 − n̄) and standard deviation
        // σ √(1 − ρ^{2m}) within 5 standard errors (of the mean: sd/√N; of the standard
        // deviation: sd/√(2N)).
        const N: u64 = 20_000;
        for noise in [
            [1.0, 8.3, 0.5],
            [0.5, 3.0, -0.7],
            [2.0, 5.0, 0.0],
            [0.0, 8.3, 0.95],
        ] {
            for m in [2, 5, 40] {
                let start = 50.0;
                let draw = |seed: u64, stepwise: bool| {
                    let mut s = NoiseStream::new(noise, seed, 0);
                    if stepwise {
                        s = s.stepwise();
                    }
                    s.last = start;
                    s.skip(m);
                    s.last
                };
                let [mu, sigma, rho] = noise;
                let stationary = mu * (1.0 - rho * rho).sqrt() / (1.0 - rho);
                let decay = rho.powi(m as i32);
                let mean = stationary + decay * (start - stationary);
                let sd = sigma * (1.0 - decay * decay).sqrt();
                let n = N as f64;
                for stepwise in [true, false] {
                    let xs: Vec<f64> = (0..N).map(|seed| draw(seed, stepwise)).collect();
                    let (got_mean, got_sd) = moments(&xs);
                    let what = format!("noise {noise:?}, m {m}, stepwise {stepwise}");
                    assert!(
                        (got_mean - mean).abs() < 5.0 * sd / n.sqrt(),
                        "{what}: mean {got_mean} vs {mean}"
                    );
                    assert!(
                        (got_sd - sd).abs() < 5.0 * sd / (2.0 * n).sqrt(),
                        "{what}: sd {got_sd} vs {sd}"
                    );
                }
            }
        }
    }

    #[test]
    fn skips_keep_the_stream_deterministic_and_continuing() {
        let run = |seed| {
            let mut s = NoiseStream::new([0.5, 8.3, 0.5], seed, 3);
            let mut out = vec![s.next_value()];
            s.skip(17);
            out.push(s.next_value());
            s.skip(1);
            s.skip(0);
            out.push(s.next_value());
            out
        };
        let bits = |v: Vec<f64>| v.into_iter().map(f64::to_bits).collect::<Vec<_>>();
        assert_eq!(bits(run(9)), bits(run(9)));
        assert_ne!(bits(run(9)), bits(run(10)));
        // A one-instant skip is one step of the recursion.
        let mut a = NoiseStream::new([0.5, 8.3, 0.5], 9, 3);
        let mut b = a.clone();
        a.skip(1);
        b.next_value();
        assert_eq!(a.last.to_bits(), b.last.to_bits());
    }

    #[test]
    fn the_upper_bound_holds_for_a_noise_free_innovation() {
        // σ = 0: the recursion is deterministic, n_{j+1} = ρ n_j + s μ, and must stay below
        // the bound (its conditional mean part) from any start, for either sign of ρ.
        for (rho, start) in [
            (0.5, -30.0),
            (0.5, 30.0),
            (-0.8, 30.0),
            (-0.8, -30.0),
            (1.0, 4.0),
        ] {
            let mut s = NoiseStream::new([2.0, 0.0, rho], 1, 0);
            s.last = start;
            let bound = s.upper_bound();
            let mut reference = s.clone();
            for m in 1..60 {
                let v = reference.next_value();
                assert!(
                    v <= bound + 1e-12,
                    "ρ {rho}, start {start}, step {m}: {v} > {bound}"
                );
                let mut jumped = s.clone();
                jumped.skip(m);
                assert!(
                    (jumped.last - v).abs() <= 1e-12 * (1.0 + v.abs()),
                    "ρ {rho}, m {m}"
                );
            }
        }
        // With σ > 0 the bound adds EXCLUSION_SIGMAS standard deviations.
        let mut s = NoiseStream::new([0.0, 8.3, 0.5], 1, 0);
        s.last = -3.0;
        assert!((s.upper_bound() - (3.0 + EXCLUSION_SIGMAS * 8.3)).abs() < 1e-12);
    }
}
