//! Fuzz target: the Open-Meteo JSON reader (and the profiles of what it accepts, at every hour
//! and member) never panics on arbitrary bytes.
#![no_main]

use karman_atmos::OpenMeteo;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(forecast) = OpenMeteo::parse(data, "fuzz.json") {
        let (first, last) = forecast.time_span();
        for member in 0..forecast.members().min(4) {
            for t in [first - 1.0, first, 0.5 * (first + last), last, last + 1.0] {
                let _ = forecast.profile(t, Some(member), 6.371e6);
            }
        }
    }
});
