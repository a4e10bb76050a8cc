//! Reproducible random streams: every sample, and every input within it, has its own stream
//! (docs/physics.md §27.1).
//!
//! Sample `i` of a study with seed `s` draws input `name` from ChaCha8 (Bernstein 2008, as
//! implemented by `rand_chacha`) keyed by the 256-bit key `(s, i, 0, 0)` (little-endian
//! `u64` words) on stream number `fnv1a64(name)`. ChaCha is a pseudo-random function of
//! (key, stream, position), so the draws of a sample depend on nothing but the seed, the
//! index and the input's name: not on the thread that flies it, the shard it is in, the
//! order the inputs are listed in, or which other inputs exist. Any sample replays alone.
//! The stream `u64::MAX` is reserved for the flight function's own randomness
//! ([`flight_seed`], e.g. parachute trigger noise).
//!
//! The mapping from random bits to numbers (`rand_distr` 0.5's ziggurat normal, `rand`'s
//! uniform floats) is part of the scheme: [`SCHEME`] names it and is recorded in
//! `study.json`, so a study is never resumed with a different one.

use crate::distribution::VariedInput;
use rand::{RngCore as _, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Name of the sampling scheme, recorded in `study.json`.
pub const SCHEME: &str = "chacha8 key=(seed,index) stream=fnv1a64(input name); rand_distr 0.5";

/// The stream reserved for the flight function's own random draws.
pub const FLIGHT_STREAM: u64 = u64::MAX;

/// FNV-1a, 64 bit (Fowler, Noll, Vo): a stable hash for stream numbers and fingerprints.
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    const OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    bytes.iter().fold(OFFSET, |hash, byte| {
        (hash ^ u64::from(*byte)).wrapping_mul(PRIME)
    })
}

/// The random stream `stream` of sample `index` of a study with seed `seed`.
pub fn sample_rng(seed: u64, index: u64, stream: u64) -> ChaCha8Rng {
    let mut key = [0u8; 32];
    key[..8].copy_from_slice(&seed.to_le_bytes());
    key[8..16].copy_from_slice(&index.to_le_bytes());
    let mut rng = ChaCha8Rng::from_seed(key);
    rng.set_stream(stream);
    rng
}

/// A seed for the flight function's own random draws in sample `index` (e.g. parachute
/// trigger noise): the first word of the sample's [`FLIGHT_STREAM`].
pub fn flight_seed(seed: u64, index: u64) -> u64 {
    sample_rng(seed, index, FLIGHT_STREAM).next_u64()
}

/// The sampled values of sample `index`, one per input in the given order.
pub fn draw(seed: u64, index: u64, inputs: &[VariedInput]) -> Vec<f64> {
    inputs
        .iter()
        .map(|input| {
            let mut rng = sample_rng(seed, index, fnv1a64(input.name.as_bytes()));
            input.sample(&mut rng)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::distribution::{Distribution, Target, Variation};
    use rand::Rng;

    #[test]
    fn fnv1a_matches_published_vectors() {
        // Test vectors of the FNV reference page (Noll, "FNV hash", isthe.com/chongo/tech/comp/fnv).
        assert_eq!(fnv1a64(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a64(b"foobar"), 0x8594_4171_f739_67e8);
    }

    #[test]
    fn streams_differ_and_replay() {
        let a: u64 = sample_rng(1, 2, 3).random();
        let again: u64 = sample_rng(1, 2, 3).random();
        assert_eq!(a, again);
        assert_ne!(flight_seed(1, 2), flight_seed(1, 3));
        for other in [
            sample_rng(1, 2, 4),
            sample_rng(1, 3, 3),
            sample_rng(2, 2, 3),
        ] {
            let mut other = other;
            let b: u64 = other.random();
            assert_ne!(a, b);
        }
    }

    #[test]
    fn a_draw_does_not_depend_on_the_other_inputs() {
        let x = VariedInput::new("x", Target::Number(1.0), Variation::Std(0.1));
        let y = VariedInput::new(
            "y",
            Target::Number(0.0),
            Variation::Value(Distribution::Uniform {
                low: 0.0,
                high: 1.0,
            }),
        );
        let both = draw(7, 11, &[x.clone(), y.clone()]);
        let reversed = draw(7, 11, &[y, x.clone()]);
        let alone = draw(7, 11, &[x]);
        assert_eq!(both[0].to_bits(), alone[0].to_bits());
        assert_eq!(both[0].to_bits(), reversed[1].to_bits());
    }
}
