//! Fuzz target: arbitrary bytes as a mission file, then as a `--set` override of a fixed
//! small mission; neither may panic. Run with `cargo fuzz run mission_toml` in
//! crates/mission.
#![no_main]

use karman_mission::{Override, parse};
use libfuzzer_sys::fuzz_target;
use std::path::Path;

const MISSION: &str = include_str!("../../tests/fixtures/minimal.toml");

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let _ = parse(text, Path::new("fuzz.toml"), &[]);
    if let Ok(item) = text.parse::<Override>() {
        let _ = parse(MISSION, Path::new("fuzz.toml"), &[item]);
    }
});
