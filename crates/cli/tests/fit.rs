//! `karman fit`: a drag fit of a validation flight to its raw log (text and JSON), the
//! fitted copy of the mission flown again, and located errors for bad requests.

use crate::common::{failure, karman, stderr};
use std::path::{Path, PathBuf};

fn fixture(path: &str) -> String {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures")
        .join(path);
    path.to_str().expect("UTF-8 path").to_owned()
}

fn prometheus() -> (String, String) {
    (
        fixture("validation/prometheus_2022/mission.toml"),
        fixture("validation/prometheus_2022/2022-06-24-serial-5115-flight-0001-TeleMetrum.csv"),
    )
}

#[test]
fn a_drag_and_parachute_fit_in_json_and_its_fitted_copy() {
    let (mission, log) = prometheus();
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("karman-cli/fit");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("fitted.toml");
    let output = karman(&[
        "fit",
        &mission,
        &log,
        "--vary",
        "rocket.power_off_drag",
        "--vary",
        "rocket.parachutes.Main.cd_s",
        "--json",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let v: serde_json::Value = serde_json::from_slice(&output.stdout).expect("JSON");
    for key in [
        "flights",
        "converged",
        "termination",
        "clock_offset_s",
        "inputs",
        "phases",
        "warnings",
    ] {
        assert!(v.get(key).is_some(), "{key} missing: {v}");
    }
    assert!(v["flights"].as_u64().unwrap() <= 100);
    let phases = v["phases"].as_array().unwrap();
    assert_eq!(phases.len(), 2, "{v}");
    for phase in phases {
        let (before, after) = (
            phase["rms_before"].as_f64().unwrap(),
            phase["rms_after"].as_f64().unwrap(),
        );
        assert!(after < before, "{phase}");
    }
    let cd_s = &v["inputs"][1];
    assert_eq!(cd_s["path"], "rocket.parachutes.Main.cd_s");
    let value = cd_s["value"].as_f64().unwrap();
    // The fitted copy holds the fitted value, loads and flies.
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.starts_with("# Fitted by `karman fit`"), "{text}");
    let flown = karman(&["simulate", out.to_str().unwrap(), "--json"]);
    assert_eq!(flown.status.code(), Some(0), "{}", stderr(&flown));
    let check = karman(&["inspect", out.to_str().unwrap(), "--json"]);
    assert_eq!(check.status.code(), Some(0), "{}", stderr(&check));
    let written = karman_mission_value(&text, "cd_s", "[rocket.parachutes.Main]");
    assert!(
        (written - value).abs() < 1e-9 * value,
        "{written} vs {value}"
    );
}

/// The number after `key = ` in the table headed `table` of a TOML text.
fn karman_mission_value(text: &str, key: &str, table: &str) -> f64 {
    let start = text.find(table).expect("table");
    let line = text[start..]
        .lines()
        .find(|l| {
            l.trim_start().starts_with(&format!("{key} "))
                || l.trim_start().starts_with(&format!("{key}="))
        })
        .expect("key");
    let value = line
        .split('=')
        .nth(1)
        .unwrap()
        .split('#')
        .next()
        .unwrap()
        .trim();
    value.parse().expect("a number")
}

#[test]
fn the_text_report_names_each_input_and_phase() {
    let (mission, log) = prometheus();
    let output = karman(&["fit", &mission, &log, "--vary", "rocket.mass"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(
        text.contains("rocket.mass") && text.contains("nominal"),
        "{text}"
    );
    assert!(text.contains("RMS ascent"), "{text}");
}

#[test]
fn bad_requests_fail_naming_what_is_wrong() {
    let (mission, log) = prometheus();
    let text = failure(&["fit", &mission, &log, "--vary", "rocket.mas"]);
    assert!(text.contains("rocket.mas"), "{text}");
    let text = failure(&[
        "fit",
        &mission,
        &log,
        "--vary",
        "rocket.parachutes.Reserve.cd_s",
    ]);
    assert!(text.contains("Reserve"), "{text}");
    let text = failure(&[
        "fit",
        &mission,
        &log,
        "--vary",
        "rocket.mass",
        "--max-flights",
        "2",
    ]);
    assert!(text.contains("budget"), "{text}");
    let text = failure(&["fit", &mission, "/nonexistent.csv", "--vary", "rocket.mass"]);
    assert!(text.contains("/nonexistent.csv"), "{text}");
    let text = failure(&[
        "fit",
        &mission,
        &log,
        "--vary",
        "rocket.mass",
        "-o",
        &mission,
    ]);
    assert!(text.contains("replace the mission"), "{text}");
    // No --vary is a usage error.
    assert_eq!(karman(&["fit", &mission, &log]).status.code(), Some(2));
}
