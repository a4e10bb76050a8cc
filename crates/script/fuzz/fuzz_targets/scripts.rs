//! Fuzz target: arbitrary bytes as a trigger expression (parsed, then evaluated) and as a
//! controller script (compiled); neither may panic. Run with `cargo fuzz run scripts` in
//! crates/script.
#![no_main]

use karman_script::{ControllerScript, Expression, TriggerInputs};
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(expression) = Expression::parse(text) {
        let _ = expression.evaluate(&TriggerInputs {
            pressure: 90_000.0,
            height: 1_000.0,
            state: [0.5; 13],
        });
    }
    let _ = ControllerScript::compile(Path::new("fuzz.rhai"), text);
});
