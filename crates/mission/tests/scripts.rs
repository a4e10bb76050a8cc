//! Air brakes, controller scripts and scripted parachute triggers in mission files: what the
//! schema accepts, what validation reports (with the script's file, line and column), and
//! the dotted paths that reach them.

use crate::common::fixture;
use karman_mission::schema::{AirBrakesCurve, Trigger};
use karman_mission::{MissionError, Override, ProblemKind, parse, paths};

/// The minimal fixture with `extra` appended to its `[rocket.parachutes.main]` table and
/// `brakes` (an `[rocket.air_brakes]` table, or nothing) before `[flight]`.
fn mission(trigger: &str, brakes: &str) -> String {
    let text = std::fs::read_to_string(fixture("minimal.toml")).expect("fixture readable");
    text.replacen("trigger = 200\n", &format!("trigger = {trigger}\n"), 1)
        .replacen("[flight]\n", &format!("{brakes}\n[flight]\n"), 1)
}

const BRAKES: &str = r#"
[rocket.air_brakes]
drag_coefficient_curve = [[0.0, 0.1, 0.0], [1.0, 0.1, 0.8], [0.0, 0.9, 0.0], [1.0, 0.9, 1.1]]
controller = "brakes.rhai"
sampling_rate = 20
override_rocket_drag = false
initial_observed_variables = [0, 0]

[rocket.air_brakes.constants]
TARGET = 900.0
"#;

fn load(text: &str, sets: &[(&str, &str)]) -> Result<karman_mission::Mission, MissionError> {
    let overrides: Vec<Override> = sets
        .iter()
        .map(|(path, value)| Override::new(path, value).expect("override"))
        .collect();
    parse(text, &fixture("scripted.toml"), &overrides)
}

fn problems(text: &str) -> Vec<karman_mission::Problem> {
    match load(text, &[]) {
        Err(MissionError::Invalid { problems, .. }) => problems,
        other => panic!("expected an invalid mission, got {other:?}"),
    }
}

#[test]
fn air_brakes_and_triggers_load() {
    for (trigger, expected) in [
        ("\"launch + 5\"", Trigger::Launch(5.0)),
        ("\"burnout + 1.5\"", Trigger::Burnout(1.5)),
        (
            "{ expression = \"vz < 5.0 && z > 1700.0\" }",
            Trigger::Expression("vz < 5.0 && z > 1700.0".into()),
        ),
    ] {
        let m = load(&mission(trigger, BRAKES), &[]).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(m.spec.rocket.parachutes["main"].trigger, expected);
        let ab = m.spec.rocket.air_brakes.as_ref().expect("air brakes");
        assert!(ab.clamp, "clamp defaults to true");
        assert!(matches!(ab.drag_coefficient_curve, AirBrakesCurve::Rows(ref r) if r.len() == 4));
        assert_eq!(ab.constants["TARGET"].to_bits(), 900.0f64.to_bits());
        assert!(m.spec.flight.time_overshoot);
    }
}

#[test]
fn dotted_paths_reach_air_brake_inputs_and_constants() {
    let text = mission("200", BRAKES);
    let m = load(
        &text,
        &[
            ("rocket.air_brakes.constants.TARGET", "750.0"),
            ("rocket.air_brakes.sampling_rate", "50"),
            ("rocket.air_brakes.deployment_level", "0.25"),
            ("flight.time_overshoot", "false"),
        ],
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let ab = m.spec.rocket.air_brakes.as_ref().expect("air brakes");
    assert_eq!(ab.constants["TARGET"].to_bits(), 750.0f64.to_bits());
    assert_eq!(ab.sampling_rate.to_bits(), 50.0f64.to_bits());
    assert!(!m.spec.flight.time_overshoot);
    let mut spec = m.spec.clone();
    paths::set_number(&mut spec, "rocket.air_brakes.constants.TARGET", 640.0).expect("slot");
    paths::set_number(&mut spec, "rocket.air_brakes.deployment_level", 0.5).expect("slot");
    let ab = spec.rocket.air_brakes.as_ref().expect("air brakes");
    assert_eq!(ab.constants["TARGET"].to_bits(), 640.0f64.to_bits());
    assert_eq!(ab.deployment_level.to_bits(), 0.5f64.to_bits());
    assert!(paths::set_number(&mut spec, "rocket.air_brakes.constants.GAIN", 1.0).is_err());
}

#[test]
fn a_bad_expression_is_located_in_it() {
    let found = problems(&mission("{ expression = \"vz < 5 && z > 300.0\" }", ""));
    assert_eq!(found.len(), 1);
    assert_eq!(found[0].key, "rocket.parachutes.main.trigger.expression");
    assert!(matches!(found[0].kind, ProblemKind::Expression { .. }));
    let text = found[0].display(std::path::Path::new("m.toml")).to_string();
    assert!(text.contains("character 6 of the expression"), "{text}");
    assert!(text.contains("write 5.0"), "{text}");
}

#[test]
fn a_script_error_names_the_script_line_and_column() {
    let brakes = BRAKES
        .replace("brakes.rhai", "broken_brakes.rhai")
        .replace("[rocket.air_brakes.constants]\nTARGET = 900.0\n", "");
    let found = problems(&mission("200", &brakes));
    assert_eq!(found.len(), 1);
    assert_eq!(found[0].key, "rocket.air_brakes.controller");
    let text = found[0].display(std::path::Path::new("m.toml")).to_string();
    assert!(text.contains("broken_brakes.rhai:4:17: "), "{text}");
}

#[test]
fn constants_must_be_declared_by_the_script() {
    let brakes = BRAKES.replace("TARGET = 900.0", "TARGET = 900.0\nGAIN = 2.0");
    let found = problems(&mission("200", &brakes));
    assert_eq!(found.len(), 1);
    assert_eq!(found[0].key, "rocket.air_brakes.constants.GAIN");
}

#[test]
fn air_brake_inputs_are_checked() {
    let brakes = BRAKES
        .replace(
            "sampling_rate = 20",
            "sampling_rate = 0\nreference_area = -1",
        )
        .replace(
            "controller = \"brakes.rhai\"",
            "controller = \"missing.rhai\"",
        );
    let keys: Vec<String> = problems(&mission("\"launch + -1\"", &brakes))
        .into_iter()
        .map(|p| p.key)
        .collect();
    for key in [
        "rocket.parachutes.main.trigger",
        "rocket.air_brakes.sampling_rate",
        "rocket.air_brakes.reference_area",
        "rocket.air_brakes.controller",
    ] {
        assert!(keys.iter().any(|k| k == key), "{key} not in {keys:?}");
    }
}
