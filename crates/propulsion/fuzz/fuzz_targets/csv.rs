//! Fuzz target: the csv thrust-file reader must never panic on arbitrary bytes.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let _ = karman_propulsion::csv::parse(&text, "fuzz.csv");
});
