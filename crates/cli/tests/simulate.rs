//! `karman simulate`: the contract's summary as JSON, the `--out` files, and clear non-zero
//! exits (never a panic, always within bounded time) for flights that cannot end normally.

use crate::common::{example, failure, karman, stderr};
use std::path::Path;

/// The summary keys of the mission contract (mission-format.md, "The summary").
const SUMMARY_KEYS: [&str; 20] = [
    "apogee_agl_m",
    "apogee_asl_m",
    "apogee_time_s",
    "apogee_x_m",
    "apogee_y_m",
    "out_of_rail_time_s",
    "out_of_rail_velocity_mps",
    "out_of_rail_stability_margin",
    "initial_static_margin",
    "burnout_static_margin",
    "max_speed_mps",
    "max_mach",
    "max_dynamic_pressure_pa",
    "max_acceleration_mps2",
    "impact_time_s",
    "impact_x_m",
    "impact_y_m",
    "impact_velocity_mps",
    "events",
    "warnings",
];

fn example_arg() -> String {
    example().display().to_string()
}

#[test]
fn json_is_exactly_the_contract_summary_with_warnings() {
    let output = karman(&["simulate", &example_arg(), "--json"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let summary: serde_json::Value =
        serde_json::from_slice(&output.stdout).expect("stdout is one JSON object");
    let mut keys: Vec<&str> = summary
        .as_object()
        .expect("an object")
        .keys()
        .map(String::as_str)
        .collect();
    keys.sort_unstable();
    let mut expected = SUMMARY_KEYS.to_vec();
    expected.sort_unstable();
    assert_eq!(keys, expected);
    let events: Vec<&str> = summary["events"]
        .as_array()
        .expect("events array")
        .iter()
        .map(|e| e["name"].as_str().expect("event name"))
        .collect();
    assert_eq!(events.first(), Some(&"rail_exit"));
    assert_eq!(events.last(), Some(&"impact"));
    assert!(events.contains(&"apogee") && events.contains(&"burnout"));
    assert!(summary["apogee_agl_m"].as_f64().expect("apogee") > 100.0);
    assert_eq!(summary["warnings"], serde_json::json!([]));
}

#[test]
fn out_writes_summary_trajectory_kml_and_plots() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("karman-cli/simulate-out");
    let _ = std::fs::remove_dir_all(&dir);
    let output = karman(&[
        "simulate",
        &example_arg(),
        "--out",
        dir.to_str().expect("UTF-8"),
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(text.contains("apogee AGL") && !text.contains("right-hand-side evaluations"));
    let summary: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join("summary.json")).expect("summary.json"),
    )
    .expect("JSON");
    assert_eq!(summary["termination"], "impact");
    assert_eq!(summary["seed"], 0);
    let csv = std::fs::read_to_string(dir.join("trajectory.csv")).expect("trajectory.csv");
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().expect("header").split(',').collect();
    for column in [
        "time_s",
        "altitude_agl_m",
        "mach",
        "angle_of_attack_deg",
        "mass_kg",
    ] {
        assert!(header.contains(&column), "no column {column}");
    }
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().expect("number")).collect())
        .collect();
    assert!(rows.len() > 100);
    assert!(
        rows.iter()
            .all(|r| r.len() == header.len() && r.iter().all(|v| v.is_finite()))
    );
    assert!(
        rows.windows(2).all(|w| w[1][0] >= w[0][0]),
        "time not increasing"
    );
    let kml = std::fs::read_to_string(dir.join("flight.kml")).expect("flight.kml");
    assert!(kml.contains("<LineString>") && kml.contains("<coordinates>"));
    for plot in [
        "altitude",
        "ground_track",
        "speed_mach",
        "attitude",
        "stability",
    ] {
        let svg = std::fs::read_to_string(dir.join(format!("{plot}.svg"))).expect("plot");
        assert!(svg.contains("<svg"), "{plot}.svg is not SVG");
    }
}

#[test]
fn two_simultaneous_runs_into_one_folder_leave_whole_files() {
    let root = Path::new(env!("CARGO_TARGET_TMPDIR")).join("karman-cli/simulate-twice");
    let _ = std::fs::remove_dir_all(&root);
    let (alone, shared) = (root.join("alone"), root.join("shared"));
    let run = |dir: &Path| {
        std::process::Command::new(env!("CARGO_BIN_EXE_karman"))
            .args([
                "simulate",
                &example_arg(),
                "--out",
                dir.to_str().expect("UTF-8"),
            ])
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .expect("the karman binary runs")
    };
    let output = run(&alone).wait_with_output().expect("a run");
    assert!(output.status.success(), "{}", stderr(&output));
    // Two runs writing the same files at once: each writes its own temporary files, so both
    // succeed and every file is one run's whole file (the same bytes as a run alone).
    let (first, second) = (run(&shared), run(&shared));
    for child in [first, second] {
        let output = child.wait_with_output().expect("a run");
        assert!(output.status.success(), "{}", stderr(&output));
    }
    let names = |dir: &Path| {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .expect("the output folder")
            .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    };
    assert_eq!(names(&shared), names(&alone), "no temporary file left");
    for name in names(&alone) {
        let same = std::fs::read(alone.join(&name)).expect("file")
            == std::fs::read(shared.join(&name)).expect("file");
        assert!(same, "{name} differs from a run alone");
    }
}

/// The names in `dir`, sorted.
fn names_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("a folder")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// `simulate --out` under a file size limit (`ulimit -f 16`, 16 blocks of 512 bytes, with
/// SIGXFSZ ignored): every write past the limit fails with EFBIG as it would with ENOSPC
/// (a full disk, simulated portably on Unix). summary.json fits, trajectory.csv (hundreds of
/// kB) does not: the run fails partway through its output set.
#[cfg(unix)]
fn simulate_on_a_full_disk(dir: &Path) -> std::process::Output {
    let script = format!(
        "trap '' XFSZ; ulimit -f 16 && exec '{}' simulate '{}' --out '{}'",
        env!("CARGO_BIN_EXE_karman"),
        example_arg(),
        dir.display()
    );
    std::process::Command::new("sh")
        .args(["-c", &script])
        .output()
        .expect("sh runs")
}

/// A full disk on a first `simulate --out`: the error names the file (under DIR, where it
/// goes); nothing is left, neither the folder nor its temporary sibling.
#[cfg(unix)]
#[test]
fn a_full_disk_on_out_names_the_file_and_leaves_no_partial_file() {
    let root = Path::new(env!("CARGO_TARGET_TMPDIR")).join("karman-cli/simulate-full-disk");
    let _ = std::fs::remove_dir_all(&root);
    std::fs::create_dir_all(&root).expect("a folder");
    let dir = root.join("out");
    let output = simulate_on_a_full_disk(&dir);
    let text = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{text}");
    assert!(!text.contains("panicked"), "{text}");
    let named = dir.join("trajectory.csv");
    assert!(
        text.contains(&named.display().to_string()),
        "the error names the file: {text}"
    );
    assert!(!dir.exists(), "no partial output set");
    assert!(names_in(&root).is_empty(), "no temporary folder left");
}

/// A rerun of `simulate --out` that fails partway (a full disk after summary.json) leaves the
/// previous run's output set whole: no new summary.json beside the old trajectory.csv.
#[cfg(unix)]
#[test]
fn a_failed_rerun_leaves_the_previous_output_set_intact() {
    let root = Path::new(env!("CARGO_TARGET_TMPDIR")).join("karman-cli/simulate-rerun-fails");
    let _ = std::fs::remove_dir_all(&root);
    let dir = root.join("out");
    let output = karman(&[
        "simulate",
        &example_arg(),
        "--out",
        dir.to_str().expect("UTF-8"),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    // The previous set, marked so that a rewritten file would show.
    std::fs::write(dir.join("summary.json"), "{\"previous\": true}\n").expect("write");
    let before: Vec<(String, Vec<u8>)> = names_in(&dir)
        .into_iter()
        .map(|n| {
            let bytes = std::fs::read(dir.join(&n)).expect("file");
            (n, bytes)
        })
        .collect();
    let output = simulate_on_a_full_disk(&dir);
    assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
    let after: Vec<(String, Vec<u8>)> = names_in(&dir)
        .into_iter()
        .map(|n| {
            let bytes = std::fs::read(dir.join(&n)).expect("file");
            (n, bytes)
        })
        .collect();
    assert!(after == before, "the previous output set is left as it was");
    assert_eq!(names_in(&root), ["out"], "no temporary folder left");
}

#[test]
fn max_time_reached_is_a_clear_failure() {
    let text = failure(&["simulate", &example_arg(), "--set", "flight.max_time=5"]);
    assert!(text.contains("max_time"), "{text}");
}

#[test]
fn a_motor_too_weak_to_leave_the_rail_is_a_clear_failure() {
    let text = failure(&["simulate", &example_arg(), "--set", "rocket.mass=500"]);
    assert!(text.contains("stuck on the rail"), "{text}");
}

#[test]
fn an_unstable_rocket_ends_within_bounded_work() {
    // Fins moved to the nose: a negative static margin. The flight must end (landing,
    // tumbling or an integration error), never hang or panic.
    let output = karman(&[
        "simulate",
        &example_arg(),
        "--json",
        "--set",
        "rocket.surfaces.fins.position=0.2",
    ]);
    let text = stderr(&output);
    assert!(!text.contains("panicked at"), "{text}");
    if output.status.success() {
        let summary: serde_json::Value =
            serde_json::from_slice(&output.stdout).expect("JSON summary");
        assert!(summary["initial_static_margin"].as_f64().expect("margin") < 0.0);
    } else {
        assert_eq!(output.status.code(), Some(1), "{text}");
    }
}

#[test]
fn bad_missions_fail_without_panicking() {
    let missing = failure(&["simulate", "no/such/mission.toml"]);
    assert!(missing.contains("no/such/mission.toml"), "{missing}");
    let bad_set = failure(&["simulate", &example_arg(), "--set", "rocket.nope=1"]);
    assert!(bad_set.contains("rocket.nope"), "{bad_set}");
}

fn two_stage_arg() -> String {
    example()
        .with_file_name("two_stage.toml")
        .display()
        .to_string()
}

/// The table a person reads: figures to 0.1 m, 0.01 s, 0.1 m/s, 0.01 calibre and 1 Pa, no
/// solver line; `--verbose` adds it.
#[test]
fn the_summary_table_rounds_to_meaningful_figures() {
    let output = karman(&["simulate", &example_arg()]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = String::from_utf8(output.stdout).expect("utf-8");
    assert!(!text.contains("Integration:"), "{text}");
    insta::assert_snapshot!("example_report", text);
    let output = karman(&["simulate", &example_arg(), "--verbose"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = String::from_utf8(output.stdout).expect("utf-8");
    assert!(
        text.contains("Integration: ") && text.contains("right-hand-side evaluations"),
        "{text}"
    );
}

#[test]
fn a_two_stage_flight_reports_both_bodies_and_one_timeline() {
    let output = karman(&["simulate", &two_stage_arg()]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = String::from_utf8(output.stdout).expect("utf-8");
    insta::assert_snapshot!("two_stage_report", text);
}

#[test]
fn a_two_stage_flight_writes_each_body_and_its_json() {
    let output = karman(&["simulate", &two_stage_arg(), "--json"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).expect("json");
    let bodies = json["bodies"].as_array().expect("bodies");
    assert_eq!(bodies.len(), 2);
    for (body, name) in bodies.iter().zip(["sustainer", "booster"]) {
        assert_eq!(body["name"], name);
        assert_eq!(body["summary"]["termination"], "impact");
        for key in &SUMMARY_KEYS[..SUMMARY_KEYS.len() - 1] {
            assert!(body["summary"].get(key).is_some(), "{name}: {key}");
        }
    }
    assert_eq!(json["separations"][0]["stage"], "booster");
    assert!(json["timeline"].as_array().is_some_and(|t| t.len() > 5));

    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("karman-cli/two_stage_out");
    let _ = std::fs::remove_dir_all(&dir);
    let output = karman(&["simulate", &two_stage_arg(), "--out", dir.to_str().unwrap()]);
    assert!(output.status.success(), "{}", stderr(&output));
    for file in ["summary.json", "altitude.svg", "ground_track.svg"] {
        assert!(dir.join(file).is_file(), "{file}");
    }
    for body in ["sustainer", "booster"] {
        let csv = std::fs::read_to_string(dir.join(body).join("trajectory.csv")).expect("csv");
        assert!(csv.starts_with("time_s,x_m,"), "{body}");
        assert!(csv.lines().count() > 100, "{body}");
        let kml = std::fs::read_to_string(dir.join(body).join("flight.kml")).expect("kml");
        assert!(kml.contains(body), "{body}");
    }
}
