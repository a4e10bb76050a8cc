//! `karman check`: exit 0 and "ok" on valid missions; exit 1 and every problem with its
//! location on invalid ones; never a panic.

use crate::common::{example, failure, karman, scratch, stderr, validation_flights};
use std::path::Path;

fn redact(text: &str, path: &Path) -> String {
    text.replace(&path.display().to_string(), "[mission]")
}

#[test]
fn validate_check_accepts_every_validation_mission() {
    let Some(flights) = validation_flights() else {
        return;
    };
    let mut count = 0;
    for flight in flights {
        let mission = flight.mission();
        let output = karman(&["check", mission.to_str().expect("UTF-8 path")]);
        assert_eq!(
            output.status.code(),
            Some(0),
            "{}: {}",
            mission.display(),
            stderr(&output)
        );
        assert_eq!(String::from_utf8_lossy(&output.stdout), "ok\n");
        count += 1;
    }
    assert!(count >= 8, "found {count} missions");
}

#[test]
fn check_accepts_the_example_with_overrides() {
    let example = example();
    let output = karman(&[
        "check",
        example.to_str().expect("UTF-8 path"),
        "--set",
        "flight.inclination=84",
        "--set",
        "rocket.parachutes.main.noise=[0,0,0]",
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
}

#[test]
fn broken_toml_is_located() {
    let path = scratch("broken.toml", b"[rocket]\nradius = = 0.04\n");
    let text = failure(&["check", path.to_str().expect("UTF-8 path")]);
    insta::assert_snapshot!("broken_toml", redact(&text, &path));
}

#[test]
fn unknown_key_is_located() {
    let example = std::fs::read_to_string(example()).expect("example readable");
    let text = example.replacen("[flight]\n", "[flight]\nlaunch_angle = 85\n", 1);
    // The schema error is found before any data file is looked for, so the example's
    // relative data paths need not resolve from the scratch folder.
    let path = scratch("unknown_key.toml", text.as_bytes());
    let stderr = failure(&["check", path.to_str().expect("UTF-8 path")]);
    assert!(stderr.contains("`flight.launch_angle`"), "{stderr}");
    insta::assert_snapshot!("unknown_key", redact(&stderr, &path));
}

#[test]
fn missing_file_fails() {
    let text = failure(&["check", "/nonexistent/karman/mission.toml"]);
    insta::assert_snapshot!("missing_file", text);
}

#[test]
fn binary_file_fails() {
    // Deterministic pseudo-random bytes (xorshift64), most of them not UTF-8.
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let bytes: Vec<u8> = (0..4096)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state.to_le_bytes()[0]
        })
        .collect();
    let path = scratch("random.bin", &bytes);
    let text = failure(&["check", path.to_str().expect("UTF-8 path")]);
    assert!(text.contains("not a UTF-8 text file"), "{text}");
}

#[test]
fn bad_set_path_fails() {
    let example = example();
    let text = failure(&[
        "check",
        example.to_str().expect("UTF-8 path"),
        "--set",
        "flight.tilt=3",
    ]);
    insta::assert_snapshot!("bad_set_path", redact(&text, &example));
}

#[test]
fn malformed_set_is_a_usage_error() {
    let example = example();
    let output = karman(&[
        "check",
        example.to_str().expect("UTF-8 path"),
        "--set",
        "flight",
    ]);
    let text = stderr(&output);
    assert!(!text.contains("panicked at"), "{text}");
    assert_eq!(output.status.code(), Some(2), "{text}");
    assert!(text.contains("expected PATH=VALUE"), "{text}");
}

/// A radius typed in millimetres (28.5 m) and fins hanging 0.1 m past the tail: warnings
/// naming the key or the surface. The 28.5 m rocket cannot be flown (its nominal flight needs
/// more steps than a phase may take), so `check` fails as `simulate` does, after the warning.
#[test]
fn check_warns_on_implausible_sizes_and_overhanging_fins() {
    let example = example();
    let mission = example.to_str().expect("UTF-8 path");
    let output = karman(&["check", mission, "--set", "rocket.radius=28.5"]);
    let text = stderr(&output);
    assert!(
        text.contains("`rocket.radius`: 28.5 m is outside the range"),
        "{text}"
    );
    assert_eq!(output.status.code(), Some(1), "{text}");
    assert!(text.contains("`flight`: the flight fails"), "{text}");
    let output = karman(&["check", mission]);
    assert!(
        !stderr(&output).contains("past the tail"),
        "{}",
        stderr(&output)
    );
    // The example's fins (0.15 m root) moved from 1.42 m to 1.55 m from the nose tip end
    // 0.10 m behind its tail at 1.60 m.
    let output = karman(&[
        "check",
        mission,
        "--set",
        "rocket.surfaces.fins.position=1.55",
    ]);
    let text = stderr(&output);
    assert!(
        text.contains("fins: the fin root runs 0.1000 m past the tail"),
        "{text}"
    );
}

/// The air-brakes example with its controller replaced by one whose body is `body`.
fn air_brakes_with(name: &str, body: &str) -> (String, Vec<String>) {
    let script = scratch(
        &format!("check/{name}.rhai"),
        format!(
            "fn controller_function(time, sampling_rate, state, state_history, \
             observed_variables, air_brakes, sensors, environment) {{\n    {body}\n}}\n"
        )
        .as_bytes(),
    );
    let mission = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/airbrakes/calisto_docs.toml")
        .display()
        .to_string();
    let set = format!(
        "rocket.air_brakes.controller=\"{}\"",
        script.display().to_string().replace('\\', "\\\\")
    );
    (mission, vec!["--set".to_owned(), set])
}

/// `check` makes the controller's first call as the flight makes it: a run-time error of that
/// call (a method of a number, an air-brake property that does not exist, a string written
/// to the level, a sandbox limit) fails `check` with the flight's message, located at the
/// script's line; controllers the flight accepts still check.
#[test]
fn check_calls_the_controller_once() {
    for (name, body, line) in [
        ("method", "time.foo();", ":2:"),
        ("property", "let x = air_brakes.nonexistent;", ":2:"),
        (
            "string level",
            "air_brakes.deployment_level = \"open\";",
            ":2:",
        ),
        ("environment", "let x = environment.nothing(1.0);", ":2:"),
        ("endless", "loop { }", ":1:1:"),
        // A branch the first call does not take: found by the nominal flight check flies.
        ("late error", "if time > 2.0 { time.foo(); }", ":2:"),
    ] {
        let (mission, set) = air_brakes_with(name, body);
        let mut args = vec!["check", mission.as_str()];
        args.extend(set.iter().map(String::as_str));
        let text = failure(&args);
        assert!(
            text.contains(&format!("{name}.rhai{line}"))
                && text.contains("`rocket.air_brakes.controller`: the flight fails")
                && !text.contains("cannot build the model")
                && !text.contains("(line"),
            "{name}: {text}"
        );
        args[0] = "simulate";
        let flown = failure(&args);
        assert_eq!(
            flown.lines().last(),
            text.lines().last(),
            "{name}: check and the flight fail alike"
        );
    }
    for (name, body) in [
        ("returns a string", "\"hello\""),
        ("NaN level", "air_brakes.deployment_level = 0.0 / 0.0;"),
    ] {
        let (mission, set) = air_brakes_with(name, body);
        let mut args = vec!["check", mission.as_str()];
        args.extend(set.iter().map(String::as_str));
        let output = karman(&args);
        assert_eq!(output.status.code(), Some(0), "{name}: {}", stderr(&output));
    }
}
