//! Fuzz target: the Wyoming and NOAA RUC sounding parsers (and the profiles built from what
//! they accept) never panic on arbitrary text.
#![no_main]

use karman_atmos::Sounding;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    if let Ok(s) = Sounding::parse_wyoming(&text, "fuzz") {
        let _ = s.profiles(6.371e6);
    }
    if let Ok(s) = Sounding::parse_noaa_ruc(&text, "fuzz") {
        let _ = s.profiles(6.371e6);
    }
});
