//! Dotted input paths shared by `--set` and `[dispersion.vary]`.

use crate::common::{fixture, validation_missions};
use karman_mission::paths::{self, DerivedKnob, Input, PathError};
use karman_mission::schema::Distribution;
use karman_mission::{MissionError, load};

#[test]
fn numeric_inputs_include_defaults_in_file_order() {
    let mission = load(&fixture("minimal.toml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    let inputs = paths::numeric_inputs(&mission.spec);
    let names: Vec<&str> = inputs.iter().map(|(p, _)| p.as_str()).collect();
    for expected in [
        "environment.latitude",
        "motor.grain_number",
        "rocket.mass",
        "rocket.power_off_drag",
        "rocket.surfaces.fins.span",
        "rocket.parachutes.main.lag",
        "rocket.parachutes.main.sampling_rate",
        "rocket.inertia.0",
        "rocket.inertia.5",
        "rocket.parachutes.main.noise.1",
        "flight.inclination",
    ] {
        assert!(
            names.contains(&expected),
            "{expected} missing from {names:?}"
        );
    }
    let position = |name: &str| names.iter().position(|n| *n == name);
    assert!(position("rocket.surfaces.nose.length") < position("rocket.surfaces.fins.span"));
    assert!(
        !names.contains(&"rocket.power_on_drag"),
        "a file curve is not a number"
    );
}

#[test]
fn resolve_numbers_curves_and_knobs() {
    let mission = load(&fixture("minimal.toml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    let spec = &mission.spec;
    assert_eq!(
        paths::resolve(spec, "rocket.mass"),
        Ok(Input::Number {
            value: 3.0,
            integer: false
        })
    );
    assert_eq!(
        paths::resolve(spec, "motor.grain_number"),
        Ok(Input::Number {
            value: 2.0,
            integer: true
        })
    );
    assert!(matches!(
        paths::resolve(spec, "rocket.power_on_drag"),
        Ok(Input::Curve(_))
    ));
    assert_eq!(
        paths::resolve(spec, "environment.wind_factor"),
        Ok(Input::Knob(DerivedKnob::WindFactor))
    );
    // An array of numbers: as a whole, and by component (a 3-number inertia has six).
    assert_eq!(
        paths::resolve(spec, "rocket.inertia"),
        Ok(Input::Array(vec![0.5, 0.5, 0.002, 0.0, 0.0, 0.0]))
    );
    assert_eq!(
        paths::resolve(spec, "rocket.inertia.2"),
        Ok(Input::Number {
            value: 0.002,
            integer: false
        })
    );
    assert!(matches!(
        paths::resolve(spec, "rocket.inertia.6"),
        Err(PathError::Unknown { .. })
    ));
    // Inline curve points are a curve, not numbers by index.
    assert!(matches!(
        paths::resolve(spec, "motor.thrust.1.1"),
        Err(PathError::Unknown { .. })
    ));
    assert!(matches!(
        paths::resolve(spec, "rocket.surfaces.nose.kind"),
        Err(PathError::NotNumeric { .. })
    ));
    assert!(matches!(
        paths::resolve(spec, "rocket.parachutes.drogue.lag"),
        Err(PathError::Unknown { .. })
    ));
}

#[test]
fn set_number_changes_one_input() {
    let mut spec = load(&fixture("minimal.toml"), &[])
        .unwrap_or_else(|e| panic!("{e}"))
        .spec;
    paths::set_number(&mut spec, "rocket.surfaces.fins.span", 0.1).expect("settable");
    paths::set_number(&mut spec, "rocket.power_off_drag", 0.5).expect("constant curve");
    paths::set_number(&mut spec, "motor.grain_number", 4.0).expect("integral");
    assert_eq!(
        paths::resolve(&spec, "rocket.surfaces.fins.span"),
        Ok(Input::Number {
            value: 0.1,
            integer: false
        })
    );
    assert_eq!(spec.motor.grain_number, Some(4));
    assert!(matches!(
        paths::set_number(&mut spec, "motor.grain_number", 2.5),
        Err(PathError::NotInteger { .. })
    ));
}

#[test]
fn distributions_must_fit_their_target() {
    let number = Input::Number {
        value: 1.0,
        integer: false,
    };
    let integer = Input::Number {
        value: 1.0,
        integer: true,
    };
    let factor = |d| Distribution::Factor(Box::new(d));
    assert!(paths::check_distribution(&number, &Distribution::Std(0.1)).is_ok());
    assert!(paths::check_distribution(&number, &Distribution::Std(-0.1)).is_err());
    assert!(paths::check_distribution(&number, &Distribution::Uniform([2.0, 1.0])).is_err());
    assert!(
        paths::check_distribution(&number, &Distribution::Triangular([0.0, 2.0, 1.0])).is_err()
    );
    assert!(paths::check_distribution(&integer, &Distribution::Std(1.0)).is_err());
    assert!(paths::check_distribution(&integer, &Distribution::Choice(vec![0.0, 1.0])).is_ok());
    assert!(paths::check_distribution(&integer, &Distribution::Choice(vec![0.5])).is_err());
    let curve = karman_mission::schema::Curve::File("drag.csv".into());
    let curve = Input::Curve(&curve);
    assert!(paths::check_distribution(&curve, &Distribution::Std(0.1)).is_err());
    assert!(paths::check_distribution(&curve, &factor(Distribution::Normal([1.0, 0.05]))).is_ok());
    assert!(paths::check_distribution(&number, &factor(factor(Distribution::Std(0.1)))).is_err());
    let array = Input::Array(vec![0.5, 0.5, 0.002]);
    assert!(paths::check_distribution(&array, &Distribution::Std(0.1)).is_err());
    assert!(paths::check_distribution(&array, &factor(Distribution::Normal([1.0, 0.05]))).is_ok());
}

#[test]
fn validation_vary_paths_all_resolve() {
    let Some(missions) = validation_missions() else {
        println!("skipped: validation data folder not found");
        return;
    };
    let mut checked = 0;
    for path in missions {
        let mission = load(&path, &[]).unwrap_or_else(|e| panic!("{e}"));
        for (key, distribution) in mission.spec.dispersion.iter().flat_map(|d| &d.vary) {
            let input = paths::resolve(&mission.spec, key).unwrap_or_else(|e| panic!("{e}"));
            paths::check_distribution(&input, distribution)
                .unwrap_or_else(|e| panic!("{key}: {e}"));
            checked += 1;
        }
    }
    assert!(checked > 50, "only {checked} vary entries found");
}

#[test]
fn bad_vary_entries_are_located() {
    let mut text = std::fs::read_to_string(fixture("minimal.toml")).expect("fixture readable");
    text.push_str(
        "\n[dispersion]\nsamples = 10\nseed = 1\n\n[dispersion.vary]\n\
         \"rocket.mass\" = { std = 0.1 }\n\
         \"rocket.spin\" = { std = 0.1 }\n\
         \"rocket.power_on_drag\" = { std = 0.1 }\n",
    );
    match karman_mission::parse(&text, &fixture("vary.toml"), &[]) {
        Err(MissionError::Invalid { problems, .. }) => {
            let keys: Vec<&str> = problems.iter().map(|p| p.key.as_str()).collect();
            assert_eq!(
                keys,
                [
                    "dispersion.vary.rocket.spin",
                    "dispersion.vary.rocket.power_on_drag"
                ]
            );
            let lines: Vec<_> = problems.iter().map(|p| p.location.clone()).collect();
            assert_eq!(
                lines,
                [
                    karman_mission::Location::File {
                        line: 68,
                        column: 1
                    },
                    karman_mission::Location::File {
                        line: 69,
                        column: 1
                    }
                ]
            );
        }
        other => panic!("expected an invalid mission, got {other:?}"),
    }
}

#[test]
fn validate_set_number_round_trips_every_mission() {
    let Some(missions) = validation_missions() else {
        println!("skipped: validation data folder not found");
        return;
    };
    for path in missions {
        let original = load(&path, &[]).unwrap_or_else(|e| panic!("{e}")).spec;
        let Ok(Input::Number { value, .. }) = paths::resolve(&original, "rocket.mass") else {
            panic!("{}: rocket.mass is not a number", path.display());
        };
        let mut spec = original.clone();
        paths::set_number(&mut spec, "rocket.mass", value).expect("settable");
        assert_eq!(
            spec,
            original,
            "{}: set_number changed more than one value",
            path.display()
        );
        paths::set_number(&mut spec, "rocket.mass", value + 1.0).expect("settable");
        assert_ne!(spec, original);
    }
}

/// Sets `path` the slow, obviously right way: through the TOML form of the mission. A numeric
/// segment indexes an array (of tables, or of numbers as the last segment).
fn set_through_toml(
    spec: &karman_mission::schema::MissionSpec,
    path: &str,
    value: f64,
) -> karman_mission::schema::MissionSpec {
    let mut root = toml::Value::Table(toml::Table::try_from(spec).expect("serializable"));
    let mut here = &mut root;
    for segment in path.split('.') {
        here = match here {
            toml::Value::Table(table) => table
                .get_mut(segment)
                .unwrap_or_else(|| panic!("{path}: no key {segment}")),
            toml::Value::Array(items) => {
                let index: usize = segment
                    .parse()
                    .unwrap_or_else(|_| panic!("{path}: {segment} is not an index"));
                &mut items[index]
            }
            _ => panic!("{path}: {segment} inside a value"),
        };
    }
    *here = match here {
        toml::Value::Integer(_) => toml::Value::Integer(value as i64),
        _ => toml::Value::Float(value),
    };
    root.try_into().expect("deserializes")
}

/// Every optional numeric key of the format present at least once, with surfaces of every
/// type: the minimal fixture plus these keys.
const EVERY_KEY: &str = r#"
[environment]
gravity = 9.79
max_expected_height = 5000
[environment.atmosphere]
model = "custom"
pressure = 101325
temperature = 288
wind_u = 2
wind_v = -1
[motor]
reference_pressure = 90000
propellant_initial_mass = 1.0
burn_time = [0.05, 2.2]
reshape_thrust_curve = [2.0, 500]
[rocket.rail_buttons]
upper_position = 0.1
lower_position = -0.5
[rocket.surfaces.nose]
bluffness = 0.1
base_radius = 0.04
[rocket.surfaces.fins]
sweep_length = 0.02
cant_angle = 0.5
radius = 0.04
[rocket.surfaces.ellipse]
type = "elliptical_fins"
n = 4
span = 0.05
root_chord = 0.08
position = -0.4
[rocket.surfaces.freeform]
type = "free_form_fins"
n = 3
shape_points = [[0, 0], [0.08, 0.05], [0.1, 0]]
position = -0.3
[rocket.surfaces.tail]
type = "tail"
top_radius = 0.04
bottom_radius = 0.03
length = 0.05
position = -0.75
[rocket.parachutes.main]
radius = 1.0
height = 1.0
porosity = 0.04
[flight]
atol = 0.001
max_time_step = 0.5
"#;

/// The minimal fixture with the keys of [`EVERY_KEY`] merged in.
fn every_key_mission() -> karman_mission::schema::MissionSpec {
    fn merge(base: &mut toml::Table, extra: toml::Table) {
        for (key, value) in extra {
            match (base.get_mut(&key), value) {
                (Some(toml::Value::Table(b)), toml::Value::Table(e)) => merge(b, e),
                (_, value) => {
                    base.insert(key, value);
                }
            }
        }
    }
    let minimal = load(&fixture("minimal.toml"), &[])
        .unwrap_or_else(|e| panic!("{e}"))
        .spec;
    let mut table = toml::Table::try_from(&minimal).expect("serializable");
    merge(&mut table, EVERY_KEY.parse().expect("valid TOML"));
    toml::Value::Table(table).try_into().expect("deserializes")
}

/// [`every_key_mission`] with a lower stage of the same airframe and motor, separating at a
/// height: every key of `[rocket]` and `[motor]` under `stages.0.`, and the stage's own.
fn every_key_stage_mission() -> karman_mission::schema::MissionSpec {
    use karman_mission::schema::{Curve, StageSpec, Trigger};
    let mut spec = every_key_mission();
    spec.stages.push(StageSpec {
        name: Some("booster".to_owned()),
        separation: Trigger::HeightAboveGround(150.0),
        sampling_rate: 50.0,
        ignition_delay: 0.5,
        stack_power_off_drag: Curve::Constant(0.6),
        stack_power_on_drag: Curve::Points(vec![[0.0, 0.5], [1.0, 0.7]]),
        tumble_drag_area: None,
        motor: Some(spec.motor.clone()),
        rocket: spec.rocket.clone(),
    });
    spec
}

#[test]
fn stage_inputs_resolve_by_their_dotted_paths() {
    let mission = load(&fixture("../../../../fixtures/two_stage.toml"), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    let mut spec = mission.spec.clone();
    let number = |value: f64| Input::Number {
        value,
        integer: false,
    };
    for (path, expected) in [
        ("stages.0.rocket.mass", number(1.1)),
        ("stages.0.ignition_delay", number(1.0)),
        ("stages.0.sampling_rate", number(100.0)),
        // The delay of `"burnout + 0.5"`.
        ("stages.0.separation", number(0.5)),
        ("stages.0.motor.dry_mass", number(0.95)),
        (
            "stages.0.motor.grain_number",
            Input::Number {
                value: 3.0,
                integer: true,
            },
        ),
        ("stages.0.rocket.parachutes.booster_chute.cd_s", number(1.2)),
        (
            "stages.0.motor.total_impulse",
            Input::Knob(DerivedKnob::TotalImpulse),
        ),
        (
            "stages.0.motor.burn_time",
            Input::Knob(DerivedKnob::BurnTime),
        ),
    ] {
        assert_eq!(paths::resolve(&spec, path), Ok(expected), "{path}");
    }
    for curve in [
        "stages.0.stack_power_off_drag",
        "stages.0.rocket.power_on_drag",
        "stages.0.motor.thrust",
    ] {
        assert!(
            matches!(paths::resolve(&spec, curve), Ok(Input::Curve(_))),
            "{curve}"
        );
    }
    assert!(matches!(
        paths::resolve(&spec, "stages.0.rocket.inertia"),
        Ok(Input::Array(_))
    ));
    // Wind knobs are the environment's, not a stage's; stage 1 does not exist.
    for path in [
        "stages.0.environment.wind_factor",
        "stages.1.rocket.mass",
        "stages.0.ignition_dlay",
    ] {
        assert!(
            matches!(paths::resolve(&spec, path), Err(PathError::Unknown { .. })),
            "{path}"
        );
    }
    paths::set_number(&mut spec, "stages.0.separation", 0.8).expect("a delay");
    paths::set_number(&mut spec, "stages.0.rocket.inertia.2", 0.002).expect("a component");
    paths::set_number(&mut spec, "stages.0.motor.dry_inertia.0", 0.02).expect("a component");
    let stage = &spec.stages[0];
    assert_eq!(
        stage.separation,
        karman_mission::schema::Trigger::Burnout(0.8)
    );
    assert_eq!(stage.rocket.inertia.0[2].to_bits(), 0.002_f64.to_bits());
    let motor = stage.motor.as_ref().expect("motor");
    assert_eq!(motor.dry_inertia.0[0].to_bits(), 0.02_f64.to_bits());
    // The top stage is untouched.
    assert_eq!(spec.rocket, mission.spec.rocket);
    assert_eq!(spec.motor, mission.spec.motor);
}

#[test]
fn typed_slots_match_the_file_form() {
    let mut specs = vec![every_key_mission(), every_key_stage_mission()];
    specs.extend(
        validation_missions()
            .unwrap_or_default()
            .iter()
            .map(|p| load(p, &[]).unwrap_or_else(|e| panic!("{e}")).spec),
    );
    // A mission of several motors: its `[[extra_motors]]` entries' own keys and motors.
    let airstart =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/airstart.toml");
    specs.push(load(&airstart, &[]).unwrap_or_else(|e| panic!("{e}")).spec);
    // Sensors: scalar keys, per-axis keys as one number and as three, positions, ranges.
    let sensors = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/sensors");
    for name in ["calisto_sensors.toml", "calisto_sensor_study.toml"] {
        specs.push(
            load(&sensors.join(name), &[])
                .unwrap_or_else(|e| panic!("{e}"))
                .spec,
        );
    }
    let mut seen = std::collections::BTreeSet::new();
    for spec in &specs {
        for (path, value) in paths::numeric_inputs(spec) {
            let new = value + 1.0;
            let mut typed = spec.clone();
            paths::set_number(&mut typed, &path, new).unwrap_or_else(|e| panic!("{path}: {e}"));
            assert_eq!(typed, set_through_toml(spec, &path, new), "{path}");
            // Keys under a name (surfaces, parachutes) counted once per key.
            let parts: Vec<&str> = path.split('.').collect();
            let key = match parts.as_slice() {
                ["rocket", "surfaces" | "parachutes", _, key] => format!("{}.{key}", parts[1]),
                _ => path.clone(),
            };
            seen.insert(key);
        }
    }
    // The every-key mission reaches every slot kind: a sample of them must have been seen.
    for key in [
        "extra_motors.0.ignition_delay",
        "extra_motors.0.motor_position",
        "extra_motors.0.motor.dry_inertia.0",
        "extra_motors.0.motor.propellant_initial_mass",
        "environment.gravity",
        "environment.atmosphere.wind_v",
        "motor.reference_pressure",
        "rocket.rail_buttons.angular_position",
        "surfaces.sweep_length",
        "surfaces.top_radius",
        "surfaces.n",
        "parachutes.porosity",
        "parachutes.trigger",
        "flight.atol",
        "flight.max_time_step",
        "rocket.inertia.0",
        "rocket.inertia.5",
        "motor.dry_inertia.3",
        "motor.burn_time.0",
        "motor.reshape_thrust_curve.1",
        "rocket.parachutes.main.noise.2",
        "rocket.sensors.0.constant_bias",
        "rocket.sensors.0.sampling_rate",
        "rocket.sensors.0.position.2",
        "rocket.sensors.1.noise_density.2",
        "rocket.sensors.1.orientation.1",
        "stages.0.separation",
        "stages.0.sampling_rate",
        "stages.0.ignition_delay",
        "stages.0.stack_power_off_drag",
        "stages.0.rocket.mass",
        "stages.0.rocket.inertia.5",
        "stages.0.rocket.rail_buttons.angular_position",
        "stages.0.rocket.parachutes.main.noise.2",
        "stages.0.motor.reference_pressure",
        "stages.0.motor.dry_inertia.3",
        "stages.0.motor.burn_time.0",
        "stages.0.motor.reshape_thrust_curve.1",
    ] {
        assert!(seen.contains(key), "{key} not exercised: {seen:?}");
    }
    // Not numbers: a curve of points, an apogee trigger, a string.
    let mut spec = specs[0].clone();
    assert!(paths::set_number(&mut spec, "motor.thrust", 1.0).is_err());
    assert!(paths::set_number(&mut spec, "rocket.surfaces.nose.kind", 1.0).is_err());
    assert!(paths::set_number(&mut spec, "rocket.nothing", 1.0).is_err());
    assert_eq!(spec, specs[0]);
}
