//! Fuzz target: a row of `samples.csv` (read back on resume, merge and summary) must parse to
//! `Ok` or `Err` on any input, never panic, and an accepted row has the columns asked for.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let (counts, line) = data.split_at(data.len().min(2));
    let inputs = usize::from(counts.first().copied().unwrap_or(0) % 16);
    let outputs = usize::from(counts.get(1).copied().unwrap_or(0) % 16);
    let line = String::from_utf8_lossy(line);
    if let Ok(row) = karman_dispersion::parse_row(&line, inputs, outputs) {
        assert_eq!(row.inputs.len(), inputs);
        assert_eq!(row.outputs.len(), outputs);
        let failed = matches!(row.status, karman_dispersion::Status::Failed(_));
        assert!(!failed || row.outputs.iter().all(Option::is_none));
    }
});
