//! The bad-input corpus (`tests/corpus/`): broken data files of every kind (garbage,
//! truncated, empty) and impossible values, each case applied to the corpus mission with
//! `--set`. `check` and `simulate` must agree on every case (both reject it, or both accept
//! it), reject it with the same message, and name the file and line (or the mission key) of
//! the problem; the flyable cases print their warnings, and `--json` carries them.

use crate::common::{karman, scratch, stderr};
use std::path::PathBuf;
use std::time::{Duration, Instant};

fn corpus_file(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/corpus")
        .join(name)
        .display()
        .to_string()
}

fn corpus_mission() -> String {
    corpus_file("mission.toml")
}

const SOUNDING: &str = "environment.atmosphere.model=\"sounding\"";
const WYOMING: &str = "environment.atmosphere.format=\"wyoming\"";
const GRID: &str = "environment.atmosphere.model=\"reanalysis\"";
const CUSTOM: &str = "environment.atmosphere.model=\"custom\"";

/// `(name, overrides, text every error message must contain)`: the rejected cases.
const REJECTED: &[(&str, &[&str], &str)] = &[
    (
        "thrust eng empty",
        &["motor.thrust=\"empty.eng\""],
        "empty.eng: 0 thrust point(s)",
    ),
    (
        "thrust eng comments only",
        &["motor.thrust=\"comments_only.eng\""],
        "comments_only.eng: 0",
    ),
    (
        "thrust eng header only",
        &["motor.thrust=\"header_only.eng\""],
        "header_only.eng: 0",
    ),
    (
        "thrust eng truncated",
        &["motor.thrust=\"truncated.eng\""],
        "truncated.eng:5:",
    ),
    (
        "thrust eng garbage",
        &["motor.thrust=\"garbage.eng\""],
        "garbage.eng:1:",
    ),
    (
        "thrust eng negative",
        &["motor.thrust=\"negative.eng\""],
        "negative.eng:3: negative",
    ),
    (
        "thrust eng decreasing",
        &["motor.thrust=\"decreasing.eng\""],
        "decreasing.eng:4: time",
    ),
    (
        "thrust csv empty",
        &["motor.thrust=\"empty.csv\""],
        "empty.csv: no data rows",
    ),
    (
        "thrust csv header only",
        &["motor.thrust=\"header_only.csv\""],
        "header_only.csv: no data",
    ),
    (
        "thrust csv garbage",
        &["motor.thrust=\"garbage.csv\""],
        "garbage.csv:3: column 2",
    ),
    (
        "thrust csv truncated",
        &["motor.thrust=\"truncated.csv\""],
        "truncated.csv:4: column 2",
    ),
    (
        "thrust csv 3 columns",
        &["motor.thrust=\"three_columns.csv\""],
        "three_columns.csv:1:",
    ),
    (
        "thrust rse empty",
        &["motor.thrust=\"empty.rse\""],
        "empty.rse:1:",
    ),
    (
        "thrust rse garbage",
        &["motor.thrust=\"garbage.rse\""],
        "garbage.rse:1:",
    ),
    (
        "thrust rse truncated",
        &["motor.thrust=\"truncated.rse\""],
        "truncated.rse:1:",
    ),
    (
        "thrust rse no engine",
        &["motor.thrust=\"no_engine.rse\""],
        "no_engine.rse:1:",
    ),
    (
        "drag empty",
        &["rocket.power_off_drag=\"drag_empty.csv\""],
        "drag_empty.csv: no data",
    ),
    (
        "drag garbage",
        &["rocket.power_off_drag=\"drag_garbage.csv\""],
        "drag_garbage.csv:3:",
    ),
    (
        "drag 1 column",
        &["rocket.power_on_drag=\"drag_one_column.csv\""],
        "drag_one_column.csv:1:",
    ),
    (
        "sounding empty",
        &[
            SOUNDING,
            WYOMING,
            "environment.atmosphere.file=\"sounding_empty.txt\"",
        ],
        "sounding_empty.txt: ",
    ),
    (
        "sounding garbage",
        &[
            SOUNDING,
            WYOMING,
            "environment.atmosphere.file=\"sounding_garbage.txt\"",
        ],
        "sounding_garbage.txt: ",
    ),
    (
        "sounding bad row",
        &[
            SOUNDING,
            WYOMING,
            "environment.atmosphere.file=\"sounding_bad_row.txt\"",
        ],
        "sounding_bad_row.txt, line 10:",
    ),
    (
        "sounding truncated",
        &[
            SOUNDING,
            WYOMING,
            "environment.atmosphere.file=\"sounding_truncated.txt\"",
        ],
        "sounding_truncated.txt: ",
    ),
    (
        "grid empty",
        &[GRID, "environment.atmosphere.file=\"grid_empty.nc\""],
        "grid_empty.nc: cannot read netCDF",
    ),
    (
        "grid garbage",
        &[GRID, "environment.atmosphere.file=\"grid_garbage.nc\""],
        "grid_garbage.nc: cannot read netCDF",
    ),
    (
        "grid truncated",
        &[GRID, "environment.atmosphere.file=\"grid_truncated.nc\""],
        "grid_truncated.nc: ",
    ),
    (
        "grid unknown dictionary",
        &[
            GRID,
            "environment.atmosphere.file=\"grid_truncated.nc\"",
            "environment.atmosphere.dictionary=\"NOPE\"",
        ],
        "unknown weather dictionary `NOPE`",
    ),
    (
        "profile garbage",
        &[
            CUSTOM,
            "environment.atmosphere.pressure=\"profile_garbage.csv\"",
        ],
        "profile_garbage.csv:3: column 2",
    ),
    (
        "airfoil garbage",
        &["rocket.surfaces.fins.airfoil={file=\"airfoil_garbage.csv\", unit=\"radians\"}"],
        "airfoil_garbage.csv:3: column 2",
    ),
    (
        "motor far away",
        &["rocket.motor_position=1e6"],
        "`rocket.motor_position`: ",
    ),
    (
        "rail too short",
        &["flight.rail_length=0.3"],
        "`flight.rail_length`: ",
    ),
    (
        "absurd wind",
        &[CUSTOM, "environment.atmosphere.wind_u=1000"],
        "`environment.atmosphere.wind_u`: ",
    ),
    (
        "motor too weak",
        &["motor.reshape_thrust_curve=[2.75, 40]"],
        "`motor.reshape_thrust_curve`: cannot build the model: the rocket is stuck on the rail: its thrust \
         never exceeds its weight",
    ),
    (
        "rocket creeps up the rail",
        &["motor.reshape_thrust_curve=[0.05, 15]"],
        "`motor.reshape_thrust_curve`: cannot build the model: the rocket is stuck on the rail: at burn-out",
    ),
    (
        "burn time outside the data",
        &["motor.burn_time=[10, 20]"],
        "`motor.burn_time`: ",
    ),
    (
        "rtol of one",
        &["flight.rtol=1"],
        "`flight.rtol`: 1 is out of range",
    ),
    (
        "sampling rate",
        &["rocket.parachutes.main.sampling_rate=1e9"],
        "sampling_rate`: ",
    ),
];

/// Runs `command` on the corpus mission with `overrides`.
fn run(command: &str, overrides: &[&str], extra: &[&str]) -> std::process::Output {
    run_on(&corpus_mission(), command, overrides, extra)
}

fn run_on(
    mission: &str,
    command: &str,
    overrides: &[&str],
    extra: &[&str],
) -> std::process::Output {
    let mut args = vec![command, mission];
    for o in overrides {
        args.extend(["--set", o]);
    }
    args.extend(extra);
    karman(&args)
}

#[test]
fn check_rejects_every_case_simulate_rejects_with_the_same_message() {
    for (name, overrides, expected) in REJECTED {
        let check = run("check", overrides, &[]);
        let simulate = run("simulate", overrides, &[]);
        let (check_err, simulate_err) = (stderr(&check), stderr(&simulate));
        for (command, output, text) in [
            ("check", &check, &check_err),
            ("simulate", &simulate, &simulate_err),
        ] {
            assert!(
                !text.contains("panicked at"),
                "{name}: {command} panicked: {text}"
            );
            assert_eq!(
                output.status.code(),
                Some(1),
                "{name}: {command} accepted it: {text}"
            );
            assert!(text.contains(expected), "{name}: {command} says: {text}");
        }
        assert_eq!(
            check_err, simulate_err,
            "{name}: check and simulate disagree"
        );
    }
}

#[test]
fn a_header_less_rasp_file_with_bom_and_crlf_flies_as_the_same_curve_with_header() {
    let with = run("simulate", &[], &["--json"]);
    let without = run(
        "simulate",
        &["motor.thrust=\"headerless_bom_crlf.eng\""],
        &["--json"],
    );
    assert!(
        with.status.success() && without.status.success(),
        "{}",
        stderr(&without)
    );
    let mut a: serde_json::Value = serde_json::from_slice(&with.stdout).expect("JSON");
    let mut b: serde_json::Value = serde_json::from_slice(&without.stdout).expect("JSON");
    let warnings = b["warnings"].take();
    assert_eq!(a["warnings"].take(), serde_json::json!([]));
    assert_eq!(a, b, "the same flight");
    assert_eq!(
        warnings,
        serde_json::json!([
            "`motor.thrust`: no RASP header line (name diameter length delays propellant-mass \
             total-mass maker): every line was read as a thrust point and the motor \
             description is unknown"
        ])
    );
    let check = run("check", &["motor.thrust=\"headerless_bom_crlf.eng\""], &[]);
    assert!(check.status.success());
    assert!(stderr(&check).contains("warning: `motor.thrust`: no RASP header line"));
}

/// Runs `simulate --json` and `check` on a flyable case; returns the warnings of the summary
/// and what `check` printed on stderr.
fn warnings_of(mission: &str, overrides: &[&str]) -> (Vec<String>, String) {
    let simulate = run_on(mission, "simulate", overrides, &["--json"]);
    let text = stderr(&simulate);
    assert!(!text.contains("panicked at"), "{text}");
    let summary: serde_json::Value = serde_json::from_slice(&simulate.stdout).expect("JSON");
    let warnings = summary["warnings"]
        .as_array()
        .expect("warnings array")
        .iter()
        .map(|w| w.as_str().expect("text").to_owned())
        .collect();
    let check = run_on(mission, "check", overrides, &[]);
    assert_eq!(check.status.success(), simulate.status.success(), "{text}");
    (warnings, stderr(&check))
}

#[test]
fn an_unstable_rocket_is_warned_about() {
    let (warnings, check) = warnings_of(&corpus_mission(), &["rocket.surfaces.fins.position=0.3"]);
    let expected = "`rocket`: negative static margin -14.988 calibres at t = 0.000 s of the \
                    powered flight: the centre of pressure lies ahead of the centre of mass and \
                    the rocket is unstable";
    assert_eq!(warnings, [expected]);
    assert!(check.contains(&format!("warning: {expected}")), "{check}");
}

#[test]
fn a_rocket_without_fins_is_warned_about() {
    let (warnings, check) = warnings_of(&corpus_file("no_fins.toml"), &[]);
    let expected = "`rocket.surfaces`: the rocket has no fins; nothing keeps it pointing into the \
                    wind";
    assert_eq!(
        warnings.first().map(String::as_str),
        Some(expected),
        "{warnings:?}"
    );
    assert!(
        warnings[1].starts_with("`rocket`: negative static margin"),
        "{warnings:?}"
    );
    assert!(check.contains(&format!("warning: {expected}")), "{check}");
}

#[test]
fn pressure_rising_with_height_is_warned_about() {
    let (warnings, _) = warnings_of(
        &corpus_mission(),
        &[
            CUSTOM,
            "environment.atmosphere.pressure=\"profile_rising.csv\"",
        ],
    );
    assert!(
        warnings
            .iter()
            .any(|w| w.starts_with("`environment.atmosphere`: pressure rises with height")),
        "{warnings:?}"
    );
}

/// How long a run may take before it counts as blocked: a hang guard, far above any run of
/// the corpus mission on a loaded machine (the test proves that nothing waits for a writer,
/// not how fast the refusal is).
const HANG_GUARD: Duration = Duration::from_secs(120);

/// Runs the binary like `common::failure`, but kills it and fails the test if it has not ended
/// after [`HANG_GUARD`].
fn failure_unblocked(args: &[&str]) -> String {
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_karman"))
        .args(args)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("the karman binary runs");
    let start = Instant::now();
    while child.try_wait().expect("child status").is_none() {
        if start.elapsed() > HANG_GUARD {
            let _ = child.kill();
            let _ = child.wait();
            panic!("`karman {}` blocked for {HANG_GUARD:?}", args.join(" "));
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let output = child.wait_with_output().expect("child output");
    let text = stderr(&output);
    assert!(!text.contains("panicked at"), "panic: {text}");
    assert_eq!(output.status.code(), Some(1), "stderr: {text}");
    text
}

#[test]
fn a_fifo_as_data_file_is_an_error_never_a_wait() {
    let dir = scratch("fifo/placeholder", b"")
        .parent()
        .expect("folder")
        .to_owned();
    let fifo = dir.join("thrust.eng");
    let _ = std::fs::remove_file(&fifo);
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|s| s.success()) {
        println!("skipped: mkfifo is not available");
        return;
    }
    let set = format!("motor.thrust=\"{}\"", fifo.display());
    for command in ["check", "simulate"] {
        let text = failure_unblocked(&[command, &corpus_mission(), "--set", &set]);
        assert!(text.contains("not a regular file"), "{text}");
    }
}

#[test]
fn a_rocket_that_coasts_off_the_rail_after_burn_out_is_warned_about() {
    let (warnings, check) =
        warnings_of(&corpus_mission(), &["motor.reshape_thrust_curve=[0.1, 60]"]);
    let expected = "`motor.thrust`: the motor burns out (0.100 s) before rail exit; the rocket \
                    coasts the last 1.649 m of the rail at 13.869 m/s";
    assert!(warnings.iter().any(|w| w == expected), "{warnings:?}");
    assert!(check.contains(&format!("warning: {expected}")), "{check}");
}
