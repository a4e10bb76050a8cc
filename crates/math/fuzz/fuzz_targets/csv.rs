//! Fuzz target: the CSV reader must return `Ok` or `Err` on any input, never panic, and what
//! it accepts must be finite and rectangular.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    if let Ok(columns) = karman_math::csv::parse_columns(&text, Path::new("fuzz.csv")) {
        let rows = columns.first().map_or(0, Vec::len);
        assert!(columns.iter().all(|c| c.len() == rows && c.iter().all(|v| v.is_finite())));
    }
    let _ = karman_math::csv::parse_curve(&text, Path::new("fuzz.csv"));
});
