//! Fuzz target: arbitrary bytes as an OpenRocket `.ork` file (zip archive or XML) must give
//! a design or an error, never a panic. Run with `cargo fuzz run ork` in crates/openrocket.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let path = Path::new("fuzz.ork");
    if let Ok(text) = karman_openrocket::document_text(path, data) {
        let _ = karman_openrocket::Design::parse(path, &text);
    }
});
