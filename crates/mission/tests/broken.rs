//! Broken missions give located errors: the file, line, column and key of every problem.
//! The text people read is snapshotted (insta); absolute paths are redacted.

use crate::common::fixture;
use karman_mission::{Location, MissionError, Override, ProblemKind, load, parse};
use std::path::Path;

/// The minimal fixture with `edits` (`from` → `to`, each `from` must occur) applied.
fn edited(edits: &[(&str, &str)]) -> String {
    let mut text = std::fs::read_to_string(fixture("minimal.toml")).expect("fixture readable");
    for (from, to) in edits {
        assert!(text.contains(from), "fixture has no {from:?}");
        text = text.replacen(from, to, 1);
    }
    text
}

/// Loads `text` as if it were `tests/fixtures/broken.toml` and returns the error text with
/// the fixture folder redacted.
fn error_text(text: &str, overrides: &[&str]) -> String {
    let overrides: Vec<Override> = overrides
        .iter()
        .map(|o| o.parse().expect("well-formed override"))
        .collect();
    let path = fixture("broken.toml");
    match parse(text, &path, &overrides) {
        Ok(_) => panic!("the broken mission loaded"),
        Err(error) => redact(&error.to_string()),
    }
}

fn redact(text: &str) -> String {
    let dir = fixture("");
    text.replace(&dir.display().to_string(), "[fixtures]/")
        .replace("[fixtures]//", "[fixtures]/")
}

fn problems(text: &str, overrides: &[Override]) -> Vec<karman_mission::Problem> {
    match parse(text, &fixture("broken.toml"), overrides) {
        Err(MissionError::Invalid { problems, .. }) => problems,
        other => panic!("expected an invalid mission, got {other:?}"),
    }
}

#[test]
fn the_fixture_is_valid() {
    let mission = load(&fixture("minimal.toml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(mission.spec.rocket.surfaces.len(), 2);
}

#[test]
fn unknown_key_names_key_and_line() {
    let text = edited(&[("tip_chord = 0.05\n", "tip_chord = 0.05\nspam = 3\n")]);
    let found = problems(&text, &[]);
    assert_eq!(found.len(), 1);
    assert_eq!(found[0].key, "rocket.surfaces.fins.spam");
    assert_eq!(
        found[0].location,
        Location::File {
            line: 50,
            column: 1
        }
    );
    insta::assert_snapshot!("unknown_key", error_text(&text, &[]));
}

#[test]
fn wrong_type_is_located() {
    let text = edited(&[("mass = 3.0", "mass = \"heavy\"")]);
    let found = problems(&text, &[]);
    assert_eq!(found[0].key, "rocket.mass");
    assert_eq!(
        found[0].location,
        Location::File {
            line: 31,
            column: 8
        }
    );
    insta::assert_snapshot!("wrong_type", error_text(&text, &[]));
}

#[test]
fn every_schema_error_is_collected() {
    let text = edited(&[
        ("elevation = 1400", "elevation = 1400\naltitude = 3"),
        ("kind = \"ogive\"", "kind = \"ogival\""),
        ("lag = 0.5", "lag = \"late\""),
        ("heading = 10", "heading = 10\nwind = 3"),
    ]);
    let keys: Vec<String> = problems(&text, &[]).into_iter().map(|p| p.key).collect();
    assert_eq!(
        keys,
        [
            "environment.altitude",
            "rocket.surfaces.nose.kind",
            "rocket.parachutes.main.lag",
            "flight.wind"
        ]
    );
    insta::assert_snapshot!("several_errors", error_text(&text, &[]));
}

#[test]
fn missing_key_is_reported() {
    let text = edited(&[("rail_length = 2.0\n", "")]);
    let found = problems(&text, &[]);
    assert_eq!(found.len(), 1);
    assert!(
        matches!(&found[0].kind, ProblemKind::Schema { message } if message.contains("rail_length"))
    );
    insta::assert_snapshot!("missing_key", error_text(&text, &[]));
}

#[test]
fn missing_table_concerns_no_key() {
    // Without the leading comments the file starts with `name = ...` at offset 0.
    let text = edited(&[("[flight]", "[flight_plan]")]);
    let text: Vec<&str> = text.lines().skip_while(|l| l.starts_with('#')).collect();
    let text = text.join("\n");
    let found = problems(&text, &[]);
    let summary: Vec<(&str, String)> = found
        .iter()
        .map(|p| (p.key.as_str(), p.kind.to_string()))
        .collect();
    assert_eq!(
        summary,
        [
            // The whole-document error sorts first (line 1, column 1).
            ("", "missing field `flight`".to_owned()),
            (
                "flight_plan",
                "unknown field `flight_plan`, expected one of `name`, `description`, \
                 `environment`, `motor`, `rocket`, `flight`, `stages`, `extra_motors`, `dispersion`"
                    .to_owned()
            ),
        ]
    );
}

#[test]
fn missing_curve_file_is_located() {
    let text = edited(&[(
        "power_on_drag = \"drag.csv\"",
        "power_on_drag = \"nope.csv\"",
    )]);
    let found = problems(&text, &[]);
    assert_eq!(found[0].key, "rocket.power_on_drag");
    assert_eq!(
        found[0].location,
        Location::File {
            line: 35,
            column: 17
        }
    );
    assert!(matches!(found[0].kind, ProblemKind::File { .. }));
    insta::assert_snapshot!("missing_curve_file", error_text(&text, &[]));
}

#[test]
fn bad_curve_file_names_its_line() {
    let text = edited(&[(
        "power_on_drag = \"drag.csv\"",
        "power_on_drag = \"bad_drag.csv\"",
    )]);
    let found = problems(&text, &[]);
    assert_eq!(found[0].key, "rocket.power_on_drag");
    assert!(matches!(found[0].kind, ProblemKind::Curve { .. }));
    insta::assert_snapshot!("bad_curve_file", error_text(&text, &[]));
}

#[test]
fn bad_trigger_is_located() {
    let text = edited(&[("trigger = 200", "trigger = \"apogeee\"")]);
    let found = problems(&text, &[]);
    assert_eq!(found[0].key, "rocket.parachutes.main.trigger");
    insta::assert_snapshot!("bad_trigger", error_text(&text, &[]));
}

#[test]
fn surface_keys_follow_the_type() {
    let text = edited(&[("kind = \"ogive\"", "kind = \"ogive\"\nspan = 0.1")]);
    let found = problems(&text, &[]);
    assert_eq!(found[0].key, "rocket.surfaces.nose");
    insta::assert_snapshot!("surface_foreign_key", error_text(&text, &[]));
}

#[test]
fn kinds_need_their_keys() {
    let text = edited(&[
        ("kind = \"solid\"", "kind = \"generic\""),
        (
            "[environment.atmosphere]\nmodel = \"standard\"",
            "[environment.atmosphere]\nmodel = \"Reanalysis\"",
        ),
    ]);
    insta::assert_snapshot!("kind_keys", error_text(&text, &[]));
}

#[test]
fn non_finite_numbers_are_rejected() {
    let text = edited(&[
        ("mass = 3.0", "mass = nan"),
        ("heading = 10", "heading = inf"),
    ]);
    let keys: Vec<String> = problems(&text, &[]).into_iter().map(|p| p.key).collect();
    assert_eq!(keys, ["rocket.mass", "flight.heading"]);
    let text = edited(&[("heading = 10", "heading = 10\nmax_time_step = inf")]);
    assert!(
        parse(&text, &fixture("ok.toml"), &[]).is_ok(),
        "inf is a valid max_time_step"
    );
}

/// Eccentricities: beyond the body radius, a centre of mass given with a centre of pressure
/// (RocketPy's `add_cm_eccentricity` sets that itself) and a non-finite offset are each an
/// error at its key; within the radius they load.
#[test]
fn eccentricities_are_checked() {
    let text = edited(&[(
        "mass = 3.0",
        "mass = 3.0\ncm_eccentricity = [0.03, 0.03]\ncp_eccentricity = [0.001, 0.0]\n\
         thrust_eccentricity = [nan, 0.0]",
    )]);
    let found = problems(&text, &[]);
    let keys: Vec<&str> = found.iter().map(|p| p.key.as_str()).collect();
    assert!(keys.contains(&"rocket.cm_eccentricity"), "{found:?}");
    assert!(keys.contains(&"rocket.cp_eccentricity"), "{found:?}");
    assert!(
        keys.iter()
            .any(|k| k.starts_with("rocket.thrust_eccentricity")),
        "{found:?}"
    );
    let radius = found
        .iter()
        .find(|p| p.key == "rocket.cm_eccentricity")
        .expect("the radius problem");
    assert!(
        radius.kind.to_string().contains("body radius"),
        "{radius:?}"
    );
    assert!(
        matches!(radius.location, Location::File { line, .. } if line > 1),
        "located: {radius:?}"
    );
    let fine = edited(&[(
        "mass = 3.0",
        "mass = 3.0\nthrust_eccentricity = [0.002, -0.001]",
    )]);
    let mission = parse(&fine, &fixture("ok.toml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        mission.spec.rocket.thrust_eccentricity,
        Some([0.002, -0.001])
    );
}

#[test]
fn syntax_error_is_located() {
    let text = edited(&[("n = 3", "n = = 3")]);
    match parse(&text, Path::new("broken.toml"), &[]) {
        Err(MissionError::Syntax { line, column, .. }) => assert_eq!((line, column), (46, 5)),
        other => panic!("expected a syntax error, got {other:?}"),
    }
    insta::assert_snapshot!("syntax_error", error_text(&text, &[]));
}

#[test]
fn binary_file_is_not_text() {
    match load(&fixture("binary.toml"), &[]) {
        Err(MissionError::NotText { line, column, .. }) => assert_eq!((line, column), (2, 2)),
        other => panic!("expected a not-text error, got {other:?}"),
    }
}

#[test]
fn missing_mission_file() {
    let error = load(&fixture("absent.toml"), &[]).expect_err("no such file");
    assert!(matches!(error, MissionError::Read { .. }));
}

#[test]
fn bad_override_path_names_the_path() {
    let text = edited(&[]);
    insta::assert_snapshot!(
        "bad_override_paths",
        error_text(
            &text,
            &[
                "rocket.parachutes.mian.lag=3",
                "flight.inclination.x=1",
                "flight.spin=3",
                "flight.heading=\"north\""
            ]
        )
    );
}

#[test]
fn validation_problem_in_override_names_the_override() {
    let text = edited(&[]);
    let o: Override = "rocket.mass=-1".parse().expect("well-formed");
    let found = problems(&text, &[o]);
    assert_eq!(
        found[0].location,
        Location::Override {
            text: "rocket.mass=-1".to_owned()
        }
    );
}

#[test]
fn hybrid_and_liquid_motors_need_tanks() {
    // A hybrid takes the solid motor's keys: only the tanks are missing.
    let text = edited(&[("kind = \"solid\"", "kind = \"hybrid\"")]);
    let found = problems(&text, &[]);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].key, "motor.tanks");
    assert!(matches!(found[0].kind, ProblemKind::MissingKey { .. }));
    let message = error_text(&text, &[]);
    assert!(message.contains("broken.toml:"), "{message}");
    // A liquid motor has no grain: the grain keys are foreign to it.
    let text = edited(&[("kind = \"solid\"", "kind = \"Liquid\"")]);
    let keys: Vec<String> = problems(&text, &[]).into_iter().map(|p| p.key).collect();
    assert!(keys.contains(&"motor.tanks".to_owned()), "{keys:?}");
    assert!(keys.contains(&"motor.grain_density".to_owned()), "{keys:?}");
    assert!(keys.contains(&"motor.throat_radius".to_owned()), "{keys:?}");
}

#[test]
fn simulation_mode_and_weathercock_are_checked() {
    // An unknown mode, located at its value.
    let text = edited(&[(
        "heading = 10\n",
        "heading = 10\nsimulation_mode = \"3dof\"\n",
    )]);
    let found = problems(&text, &[]);
    assert_eq!(found.len(), 1);
    assert_eq!(found[0].key, "flight.simulation_mode");
    assert_eq!(
        found[0].location,
        Location::File {
            line: 61,
            column: 19
        }
    );
    let unknown = error_text(&text, &[]);
    // A weathercock coefficient is a 3-DOF setting.
    let text = edited(&[("heading = 10\n", "heading = 10\nweathercock_coeff = 0.5\n")]);
    let found = problems(&text, &[]);
    assert_eq!(found.len(), 1);
    assert_eq!(found[0].key, "flight.weathercock_coeff");
    assert!(matches!(found[0].kind, ProblemKind::NotApplicable { .. }));
    assert_eq!(
        found[0].location,
        Location::File {
            line: 61,
            column: 21
        }
    );
    let six_dof = error_text(&text, &[]);
    // A negative rate.
    let three = "heading = 10\nsimulation_mode = \"3 DOF\"\n";
    let text = edited(&[("heading = 10\n", three)]);
    let found = problems(
        &text,
        &["flight.weathercock_coeff=-0.5".parse().expect("override")],
    );
    assert_eq!(found.len(), 1);
    assert!(matches!(found[0].kind, ProblemKind::OutOfRange { .. }));
    let negative = error_text(&text, &["flight.weathercock_coeff=-0.5"]);
    // A rate so large it only stiffens the equations (the flight would end at the
    // integrator's step limit): refused by `check`, as the flight would refuse it.
    let found = problems(
        &text,
        &["flight.weathercock_coeff=1e12".parse().expect("override")],
    );
    assert_eq!(found.len(), 1);
    assert!(matches!(found[0].kind, ProblemKind::OutOfRange { .. }));
    insta::assert_snapshot!(
        "simulation_mode",
        format!("{unknown}\n{six_dof}\n{negative}")
    );
    // Both keys in a 3-DOF mission load.
    let text = edited(&[(
        "heading = 10\n",
        "heading = 10\nsimulation_mode = \"3 DOF\"\nweathercock_coeff = 0.5\n",
    )]);
    let mission = parse(&text, &fixture("broken.toml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    let flight = &mission.spec.flight;
    assert_eq!(
        flight.simulation_mode,
        karman_mission::schema::Mode::ThreeDof
    );
    assert_eq!(flight.weathercock_coeff, Some(0.5));
}

#[test]
fn cluster_mistakes_are_located() {
    // No motor at all, and axes inside the rocket's axis: each named at its key and line.
    let text = edited(&[(
        "nozzle_radius = 0.02\n",
        "nozzle_radius = 0.02\ncluster_count = 0\ncluster_radius = -0.01\n",
    )]);
    let found = problems(&text, &[]);
    let keys: Vec<(&str, Location)> = found
        .iter()
        .map(|p| (p.key.as_str(), p.location.clone()))
        .collect();
    assert_eq!(
        keys,
        [
            (
                "motor.cluster_count",
                Location::File {
                    line: 20,
                    column: 17
                }
            ),
            (
                "motor.cluster_radius",
                Location::File {
                    line: 21,
                    column: 18
                }
            ),
        ]
    );
    let text = error_text(&text, &[]);
    assert!(
        text.contains("cluster_count") && text.contains("at least 1 motor"),
        "{text}"
    );
}

#[test]
fn pod_mistakes_are_located() {
    // No pods, a surface that does not exist, a surface carried twice.
    let pods = "[rocket.pods.wings]\ncount = 0\nsurfaces = [\"fins\", \"flaps\"]\n\n\
                [rocket.pods.tail]\nsurfaces = [\"fins\"]\n\n[rocket.parachutes.main]\n";
    let text = edited(&[("[rocket.parachutes.main]\n", pods)]);
    let found = problems(&text, &[]);
    let keys: Vec<&str> = found.iter().map(|p| p.key.as_str()).collect();
    assert_eq!(
        keys,
        [
            "rocket.pods.wings.count",
            "rocket.pods.wings.surfaces",
            "rocket.pods.tail.surfaces",
        ]
    );
    assert!(
        found
            .iter()
            .all(|p| matches!(p.location, Location::File { .. }))
    );
    let text = error_text(&text, &[]);
    assert!(text.contains("at least 1 pod"), "{text}");
    assert!(
        text.contains("flaps") && text.contains("already carried by pod `wings`"),
        "{text}"
    );
    // A well-formed pod set loads: its fins count twice.
    let good = edited(&[(
        "[rocket.parachutes.main]\n",
        "[rocket.pods.wings]\ncount = 2\nangular_position = 45\nsurfaces = [\"fins\"]\n\n[rocket.parachutes.main]\n",
    )]);
    let mission = parse(&good, &fixture("minimal.toml"), &[]).expect("loads");
    let pod = &mission.spec.rocket.pods["wings"];
    assert_eq!((pod.count, pod.angular_position_deg), (2, 45.0));
    let plain = parse(&edited(&[]), &fixture("minimal.toml"), &[]).expect("loads");
    let slope = |m: &karman_mission::Mission| {
        use karman_mission::assemble::{motor::build_motor, rocket::build_rocket};
        let motor = build_motor(m).expect("motor");
        build_rocket(m, &motor).expect("rocket").total_cn_alpha(0.3)
    };
    // Nose 2, and the fin set once per pod.
    let (one, two) = (slope(&plain) - 2.0, slope(&mission) - 2.0);
    assert!((two - 2.0 * one).abs() < 1e-12, "{one} {two}");
}

/// Inputs no flight can be integrated on are refused at their key, before any model is built:
/// a rail longer than a kilometre, a launch from beyond the Kármán line, a fin set of a
/// billion fins. A huge value is shown in exponent form, not in its 301 digits.
#[test]
fn values_beyond_any_flight_are_out_of_range() {
    for (from, to, key, shown) in [
        (
            "rail_length = 2.0",
            "rail_length = 1e300",
            "flight.rail_length",
            "1e300 is out of range",
        ),
        (
            "elevation = 1400",
            "elevation = 1e12",
            "environment.elevation",
            "1000000000000 is out of range",
        ),
        (
            "n = 3",
            "n = 1000000000",
            "rocket.surfaces.fins.n",
            "1000000000 is out of range",
        ),
    ] {
        let found = problems(&edited(&[(from, to)]), &[]);
        assert_eq!(found.len(), 1, "{to}: {found:?}");
        assert_eq!(found[0].key, key);
        let text = found[0].display(Path::new("m.toml")).to_string();
        assert!(text.contains(shown) && text.len() < 200, "{text}");
    }
    for (from, to) in [
        ("rail_length = 2.0", "rail_length = 1000"),
        ("elevation = 1400", "elevation = -400"),
        ("n = 3", "n = 1000"),
    ] {
        load_text(&edited(&[(from, to)]));
    }
}

/// A float beyond any physical input (1e15 in magnitude) is refused at its key, once, before
/// a model is built from it: such a value used to overflow inside the model it fed (a grain
/// spacing of 1e300 m gave "propellant I11: value inf is not finite", naming no key).
#[test]
fn a_float_beyond_any_input_is_refused_at_its_key() {
    for (set, key) in [
        ("motor.grain_separation=1e300", "motor.grain_separation"),
        (
            "rocket.center_of_mass_without_motor=-1e300",
            "rocket.center_of_mass_without_motor",
        ),
        ("rocket.motor_position=2e15", "rocket.motor_position"),
    ] {
        let override_item: Override = set.parse().expect("an override");
        let Err(MissionError::Invalid { problems, .. }) =
            parse(&edited(&[]), &fixture("broken.toml"), &[override_item])
        else {
            panic!("{set} accepted");
        };
        assert_eq!(problems.len(), 1, "{set}: {problems:?}");
        assert_eq!(problems[0].key, key);
        let text = problems[0].display(Path::new("m.toml")).to_string();
        assert!(text.contains("exceeds 1e15") && text.len() < 200, "{text}");
    }
    // An input with its own range reports that range alone.
    let item: Override = "flight.rail_length=1e300".parse().expect("an override");
    let Err(MissionError::Invalid { problems, .. }) =
        parse(&edited(&[]), &fixture("broken.toml"), &[item])
    else {
        panic!("accepted");
    };
    assert_eq!(problems.len(), 1, "{problems:?}");
    assert!(
        !problems[0]
            .display(Path::new("m.toml"))
            .to_string()
            .contains("1e15")
    );
    // 1e15 itself is not refused by the bound.
    load_text(&edited(&[("lag = 0.5", "lag = 1e15")]));
}

/// A `--set` value of 100,000 digits is echoed as its beginning and end, not whole.
#[test]
fn a_huge_override_value_is_cut_in_the_message() {
    let digits = "9".repeat(100_000);
    let text = error_text(&edited(&[]), &[&format!("rocket.mass={digits}")]);
    assert!(
        text.contains("--set rocket.mass=999") && text.contains('…'),
        "{text}"
    );
    assert!(text.len() < 300, "{} characters", text.len());
}

fn load_text(text: &str) {
    if let Err(e) = parse(text, &fixture("broken.toml"), &[]) {
        panic!("{e}");
    }
}
