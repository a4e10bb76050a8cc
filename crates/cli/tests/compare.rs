//! `karman compare`: the validation missions set against their raw logs, with the errors
//! checked against the same quantities computed here from `simulate --out`'s trajectory and
//! `log show --json`; two boards of one flight in one report; the overlay plots; and located
//! errors (exit 1, never a panic) for bad input.

use crate::common::{failure, karman, scratch, stderr};
use std::path::{Path, PathBuf};

fn fixture(path: &str) -> String {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures")
        .join(path);
    path.to_str().expect("UTF-8 path").to_owned()
}

fn json(args: &[&str]) -> serde_json::Value {
    let output = karman(args);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    serde_json::from_slice(&output.stdout).expect("JSON on stdout")
}

/// The simulated apogee above the pad and its time from first motion, read from
/// `trajectory.csv` (its `time_s` and `altitude_agl_m` columns) independently of
/// karman-flightlog: the altitude counted from its first value, first motion the last row
/// before the altitude rises 1 cm above it.
fn simulated_apogee(mission: &str, dir: &Path) -> (f64, f64) {
    let out = dir.to_str().expect("UTF-8");
    let output = karman(&["simulate", mission, "--out", out]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let text = std::fs::read_to_string(dir.join("trajectory.csv")).expect("trajectory.csv");
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().expect("header").split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).expect(name);
    let (t_col, h_col) = (column("time_s"), column("altitude_agl_m"));
    let rows: Vec<(f64, f64)> = lines
        .map(|l| {
            let cells: Vec<&str> = l.split(',').collect();
            (cells[t_col].parse().unwrap(), cells[h_col].parse().unwrap())
        })
        .collect();
    let pad = rows[0].1;
    let moving = rows.iter().position(|r| r.1 > pad + 0.01).expect("motion");
    let liftoff = rows[moving - 1].0;
    let top = rows.iter().copied().fold(
        (0.0, f64::NEG_INFINITY),
        |a, r| if r.1 > a.1 { r } else { a },
    );
    (top.1 - pad, top.0 - liftoff)
}

/// `karman compare MISSION LOG --json` against the independent figures.
fn check_validation_flight(name: &str, log: &str) {
    let mission = fixture(&format!("validation/{name}/mission.toml"));
    let log = fixture(&format!("validation/{name}/{log}"));
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("karman-cli/compare-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    let (sim_apogee, sim_apogee_time) = simulated_apogee(&mission, &dir.join("simulate"));
    let shown = json(&["log", "show", &log, "--json"]);
    let log_apogee = shown["apogee_agl_m"].as_f64().expect("apogee");
    let log_apogee_time = shown["apogee_time_s"].as_f64().expect("apogee time");

    let out = dir.join("compare");
    let report = json(&[
        "compare",
        &mission,
        &log,
        "--json",
        "--out",
        out.to_str().unwrap(),
    ]);
    let entry = &report["logs"][0];
    for key in [
        "apogee_error_m",
        "apogee_error_pct",
        "apogee_time_error_s",
        "max_velocity_error_pct",
        "ascent_rms_altitude_m",
        "descent_rate_error_pct",
    ] {
        assert!(entry.get(key).is_some(), "{name}: {key} missing: {entry}");
    }
    let error = entry["apogee_error_m"].as_f64().unwrap();
    let expected = sim_apogee - log_apogee;
    assert!(
        (error - expected).abs() < 0.1,
        "{name}: apogee error {error} m, independently {expected} m"
    );
    let pct = entry["apogee_error_pct"].as_f64().unwrap();
    assert!(
        (pct - 100.0 * expected / log_apogee).abs() < 0.01,
        "{name}: {pct} %"
    );
    let time_error = entry["apogee_time_error_s"].as_f64().unwrap();
    let expected_time = sim_apogee_time - log_apogee_time;
    assert!(
        (time_error - expected_time).abs() < 1e-6,
        "{name}: {time_error} s, independently {expected_time} s"
    );
    let rms = entry["ascent_rms_altitude_m"].as_f64().unwrap();
    assert!(rms.is_finite() && rms >= 0.0, "{name}: {rms}");
    assert!(
        entry["ascent_samples"].as_u64().unwrap() > 100,
        "{name}: {entry}"
    );

    // The report on disk is the one printed, and every plot shows both curves.
    let written: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("comparison.json")).unwrap()).unwrap();
    assert_eq!(written, report);
    let log_name = Path::new(&log).file_name().unwrap().to_str().unwrap();
    for plot in ["altitude.svg", "velocity.svg"] {
        let svg = std::fs::read_to_string(out.join(plot)).expect(plot);
        assert!(
            svg.contains("simulation") && svg.contains(log_name),
            "{name}: {plot} legend"
        );
        assert!(
            svg.matches("<polyline").count() >= 2,
            "{name}: {plot} has fewer than two curves"
        );
    }
}

#[test]
fn prometheus_against_its_telemetrum_log() {
    check_validation_flight(
        "prometheus_2022",
        "2022-06-24-serial-5115-flight-0001-TeleMetrum.csv",
    );
}

#[test]
fn juno3_against_its_rrc3_log() {
    check_validation_flight("juno3", "cots_altimeter.csv");
}

#[test]
fn hedy_against_its_cats_log() {
    check_validation_flight("hedy", "filteredDataInfo.csv");
}

#[test]
fn two_boards_of_one_flight_in_one_report() {
    let mission = fixture("validation/prometheus_2022/mission.toml");
    let telemetrum =
        fixture("validation/prometheus_2022/2022-06-24-serial-5115-flight-0001-TeleMetrum.csv");
    let telemega = fixture(
        "flightlogs/altusmetrum-csv/rocketpy-prometheus-2022/2022-06-24-serial-6583-flight-0003-TeleMega.csv",
    );
    let report = json(&["compare", &mission, &telemetrum, &telemega, "--json"]);
    let logs = report["logs"].as_array().expect("logs");
    assert_eq!(logs.len(), 2);
    let simulated = report["simulation"]["apogee_m"].as_f64().unwrap();
    // The boards' own maxima (SOURCE.md): 3903.77 m and 3898.37 m.
    for (entry, board) in logs.iter().zip([3903.77, 3898.37]) {
        let measured = entry["apogee_m"].as_f64().unwrap();
        assert!((measured - board).abs() < 1.0, "{measured} vs {board}");
        let error = entry["apogee_error_m"].as_f64().unwrap();
        assert!((error - (simulated - measured)).abs() < 1e-9);
        // Both boards flew a drogue and a main: each phase has a measured rate.
        let descent = entry["descent"].as_array().unwrap();
        assert_eq!(descent.len(), 2, "{entry}");
        for phase in descent {
            let rate = phase["measured_rate_mps"].as_f64().expect("measured rate");
            assert!(rate > 3.0 && rate < 60.0, "{phase}");
        }
        // Both carry GNSS: a landing point a plausible distance from the pad.
        let drift = entry["landing"]["measured_drift_m"]
            .as_f64()
            .expect("GNSS landing");
        assert!(drift > 10.0 && drift < 20_000.0, "{drift}");
    }
    let a = logs[0]["apogee_m"].as_f64().unwrap();
    let b = logs[1]["apogee_m"].as_f64().unwrap();
    assert!((a - b).abs() < 0.01 * a, "the boards disagree: {a} {b}");

    // The text report names both logs.
    let output = karman(&["compare", &mission, &telemetrum, &telemega]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(
        text.contains("TeleMetrum") && text.contains("TeleMega"),
        "{text}"
    );
    assert!(text.contains("descent"), "{text}");
}

#[test]
fn bad_logs_fail_before_the_flight_naming_the_file() {
    let mission = fixture("validation/juno3/mission.toml");
    let empty = scratch("compare/empty.csv", b"");
    let text = failure(&["compare", &mission, empty.to_str().unwrap()]);
    assert!(text.contains("empty.csv"), "{text}");
    // A log that never lifts off.
    let mut flat = String::from("t,h\n");
    for i in 0..200 {
        flat.push_str(&format!("{i},1.0\n"));
    }
    let flat = scratch("compare/flat.csv", flat.as_bytes());
    let text = failure(&[
        "compare",
        &mission,
        flat.to_str().unwrap(),
        "--mapping",
        "time=t:s,altitude=h:m",
    ]);
    assert!(
        text.contains("flat.csv") && text.contains("no liftoff"),
        "{text}"
    );
    // A mapping naming a column the file does not have: the file and line.
    let text = failure(&[
        "compare",
        &mission,
        flat.to_str().unwrap(),
        "--mapping",
        "time=ts:s,altitude=h:m",
    ]);
    assert!(
        text.contains("flat.csv:1") && text.contains("'ts'"),
        "{text}"
    );
    let text = failure(&["compare", &mission, "/nonexistent/log.csv"]);
    assert!(text.contains("/nonexistent/log.csv"), "{text}");
    // A bad mission is reported as the mission's problem.
    let log = fixture("validation/juno3/cots_altimeter.csv");
    let text = failure(&["compare", &mission, &log, "--set", "flight.rtol=5"]);
    assert!(text.contains("flight.rtol"), "{text}");
    // No log at all is a usage error.
    let output = karman(&["compare", &mission]);
    assert_eq!(output.status.code(), Some(2));
}
