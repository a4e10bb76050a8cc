//! `karman log show`: the summary of a real (vendored) log as text and JSON, a generic CSV
//! through `--mapping`, and located errors (exit 1, never a panic) for bad input.

use crate::common::{failure, karman, scratch, stderr};
use std::path::PathBuf;

fn fixture(path: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures")
        .join(path)
}

fn json(args: &[&str]) -> serde_json::Value {
    let output = karman(args);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    serde_json::from_slice(&output.stdout).expect("JSON on stdout")
}

#[test]
fn show_json_of_an_rrc3_log() {
    let path = fixture("validation/juno3/cots_altimeter.csv");
    let v = json(&["log", "show", path.to_str().expect("UTF-8"), "--json"]);
    for key in [
        "format",
        "device",
        "samples",
        "liftoff_time_s",
        "apogee_agl_m",
        "apogee_time_s",
        "max_vertical_velocity_mps",
        "events",
        "warnings",
    ] {
        assert!(v.get(key).is_some(), "{key} missing: {v}");
    }
    assert_eq!(v["format"], "rrc3");
    assert_eq!(v["samples"], 609);
    // Juno III's flight card: 3213 m.
    let apogee = v["apogee_agl_m"].as_f64().expect("apogee");
    assert!((apogee - 3213.0).abs() < 0.005 * 3213.0, "{apogee}");
    let events = v["events"].as_array().expect("events");
    assert!(
        events
            .iter()
            .any(|e| e["kind"] == "drogue" && e["source"] == "device")
    );
    let warnings = v["warnings"].as_array().expect("warnings");
    assert!(
        warnings
            .iter()
            .any(|w| w.as_str().is_some_and(|w| w.contains("glitch")))
    );
}

#[test]
fn show_text_of_an_eggtimer_log() {
    let path = fixture("flightlogs/eggtimer/rocketpy-erebus11-2022/flight_data.csv");
    let output = karman(&["log", "show", path.to_str().expect("UTF-8")]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let text = String::from_utf8_lossy(&output.stdout);
    for needle in [
        "format:    eggtimer",
        "apogee:    3180.28 m AGL",
        "the device reports 3180.28 m",
        "drogue",
        "main",
    ] {
        assert!(text.contains(needle), "{needle} not in:\n{text}");
    }
}

#[test]
fn show_a_generic_csv_with_a_mapping() {
    let mut csv = String::from("ms,alt_ft\n");
    for i in 0..=300 {
        let t = f64::from(i) * 0.1;
        let h = if t < 1.0 {
            0.0
        } else {
            (1000.0 - 10.0 * (t - 11.0).powi(2)).max(0.0)
        };
        csv.push_str(&format!("{},{h}\n", t * 1000.0));
    }
    let path = scratch("log/generic.csv", csv.as_bytes());
    let path = path.to_str().expect("UTF-8");
    let text = failure(&["log", "show", path]);
    assert!(
        text.contains("unknown log format") && text.contains(":1:"),
        "{text}"
    );
    let v = json(&[
        "log",
        "show",
        path,
        "--mapping",
        "time=ms:ms,altitude=alt_ft:ft",
        "--json",
    ]);
    assert_eq!(v["format"], "generic");
    assert!((v["apogee_agl_m"].as_f64().expect("apogee") - 304.8).abs() < 1e-6);
    assert!(
        (v["apogee_time_s"].as_f64().expect("t") - 10.0).abs() < 0.2,
        "{v}"
    );
}

#[test]
fn bad_logs_are_located_errors() {
    let empty = scratch("log/empty.csv", b"");
    let text = failure(&["log", "show", empty.to_str().expect("UTF-8")]);
    assert!(text.contains("empty"), "{text}");
    let binary = scratch("log/binary.csv", b"\x00\x01\x02garbage\xff");
    let text = failure(&["log", "show", binary.to_str().expect("UTF-8")]);
    assert!(text.contains("binary"), "{text}");
    let missing = scratch("log/missing.csv", b"t,h\n0,0\n1,5\n");
    let text = failure(&[
        "log",
        "show",
        missing.to_str().expect("UTF-8"),
        "--mapping",
        "time=t,altitude=alt",
    ]);
    assert!(
        text.contains("missing.csv:1:") && text.contains("'alt'"),
        "{text}"
    );
    let text = failure(&[
        "log",
        "show",
        missing.to_str().expect("UTF-8"),
        "--format",
        "nope",
    ]);
    assert!(text.contains("unknown format name 'nope'"), "{text}");
    let text = failure(&["log", "show", "/nonexistent/flight.csv"]);
    assert!(text.contains("cannot read"), "{text}");
}

#[test]
fn show_plot_draws_each_channel_of_the_log() {
    let path =
        fixture("validation/prometheus_2022/2022-06-24-serial-5115-flight-0001-TeleMetrum.csv");
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("karman-cli/log-plot");
    let _ = std::fs::remove_dir_all(&dir);
    let output = karman(&[
        "log",
        "show",
        path.to_str().expect("UTF-8"),
        "--plot",
        dir.to_str().expect("UTF-8"),
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    for name in ["altitude.svg", "velocity.svg", "acceleration.svg"] {
        let svg = std::fs::read_to_string(dir.join(name)).expect(name);
        assert!(svg.contains("<polyline"), "{name} has no curve");
        assert!(svg.contains("TeleMetrum"), "{name} does not name the log");
    }
    // A log without an acceleration channel has no acceleration chart.
    let rrc3 = fixture("validation/juno3/cots_altimeter.csv");
    let dir = dir.join("rrc3");
    let output = karman(&[
        "log",
        "show",
        rrc3.to_str().unwrap(),
        "--plot",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert!(dir.join("altitude.svg").is_file());
    assert!(!dir.join("acceleration.svg").exists());
}
