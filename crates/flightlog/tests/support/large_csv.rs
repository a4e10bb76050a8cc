//! A large synthetic log, shared by the `large_log` benchmark and the memory test: a generic
//! CSV of `time, altitude, acceleration` rows at 1 kHz (the rate of a high-rate flight
//! computer) until the text reaches the size asked for.

use std::fmt::Write as _;

/// The column mapping that reads [`csv`]'s text.
pub const MAPPING: &str = "time=time_ms:ms,altitude=altitude_ft:ft,acceleration=accel_g:g";

/// A flight sampled at 1 kHz until the text reaches `bytes`: 2 s on the pad, a 3 s boost at
/// 60 m/s², a coast to apogee, then a 20 m/s descent (repeated every 200 s if the text needs
/// more).
#[must_use]
pub fn csv(bytes: usize) -> String {
    let mut text = String::with_capacity(bytes + 64);
    text.push_str("time_ms,altitude_ft,accel_g\n");
    let mut k: u64 = 0;
    while text.len() < bytes {
        let t = k as f64 * 1e-3;
        let phase = t % 200.0 - 2.0;
        let (h, a) = if phase < 0.0 {
            (0.0, 0.0)
        } else if phase < 3.0 {
            (30.0 * phase * phase, 6.1)
        } else if phase < 21.3 {
            let c = phase - 3.0;
            (270.0 + 180.0 * c - 4.903 * c * c, -1.0)
        } else {
            ((1920.0 - 20.0 * (phase - 21.3)).max(0.0), 0.0)
        };
        let _ = writeln!(text, "{},{:.2},{a:.3}", k, h / 0.3048);
        k += 1;
    }
    text
}
