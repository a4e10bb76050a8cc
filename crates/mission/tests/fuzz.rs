//! Arbitrary input never panics the mission parser (the normal-suite counterpart of the
//! cargo-fuzz target `fuzz/fuzz_targets/mission_toml.rs`).

use crate::common::fixture;
use karman_mission::{Override, parse};
use proptest::prelude::*;

fn minimal() -> String {
    std::fs::read_to_string(fixture("minimal.toml")).expect("fixture readable")
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn arbitrary_text_never_panics(text in "\\PC{0,400}") {
        let _ = parse(&text, &fixture("arbitrary.toml"), &[]);
    }

    #[test]
    fn arbitrary_override_never_panics(item in "[a-z._=\\[\\]\"0-9, ]{0,40}") {
        if let Ok(item) = item.parse::<Override>() {
            let _ = parse(&minimal(), &fixture("arbitrary.toml"), &[item]);
        }
    }

    /// Valid lines in a random order, some dropped, some duplicated: mostly well-formed
    /// TOML with missing, repeated and misplaced keys.
    #[test]
    fn shuffled_mission_never_panics(picks in proptest::collection::vec(0usize..60, 0..80)) {
        let text = minimal();
        let lines: Vec<&str> = text.lines().collect();
        let shuffled: Vec<&str> = picks.iter().filter_map(|&i| lines.get(i).copied()).collect();
        let _ = parse(&shuffled.join("\n"), &fixture("arbitrary.toml"), &[]);
    }

    /// One line of the valid mission replaced by arbitrary text.
    #[test]
    fn one_bad_line_never_panics(index in 0usize..60, line in "\\PC{0,40}") {
        let text = minimal();
        let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
        if let Some(slot) = lines.get_mut(index) {
            *slot = line;
        }
        let _ = parse(&lines.join("\n"), &fixture("arbitrary.toml"), &[]);
    }
}
