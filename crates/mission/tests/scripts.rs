//! Air brakes, controller scripts and scripted parachute triggers in mission files: what the
//! schema accepts, what validation reports (with the script's file, line and column), and
//! the dotted paths that reach them.

use crate::common::fixture;
use karman_mission::schema::{AirBrakesCurve, Trigger};
use karman_mission::{MissionError, Override, ProblemKind, parse, paths};
use std::sync::Arc;

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

#[test]
fn an_air_brake_sampling_rate_above_10_khz_is_refused_by_check() {
    // 1e5 Hz would multiply the controller calls until the flight's step limit: `check`
    // refuses it as it refuses a parachute's.
    let fast = BRAKES.replace("sampling_rate = 20", "sampling_rate = 1e5");
    let found = problems(&mission("200", &fast));
    let rate = found
        .iter()
        .find(|p| p.key == "rocket.air_brakes.sampling_rate")
        .unwrap_or_else(|| panic!("no sampling-rate problem in {found:?}"));
    assert!(
        format!("{:?}", rate.kind).contains("(0, 10000] Hz"),
        "{rate:?}"
    );
    let fine = BRAKES.replace("sampling_rate = 20", "sampling_rate = 10000");
    load(&mission("200", &fine), &[]).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn the_air_brake_table_takes_factor_and_offset_only() {
    use karman_mission::schema::Distribution;
    let m = load(&mission("200", BRAKES), &[]).unwrap_or_else(|e| panic!("{e}"));
    let input = paths::resolve(&m.spec, paths::AIR_BRAKES_CURVE).expect("resolves");
    assert!(matches!(input, paths::Input::Table(_)));
    let factor = Distribution::Factor(Box::new(Distribution::Normal([1.0, 0.05])));
    assert!(paths::check_distribution(&input, &factor).is_ok());
    assert!(paths::check_distribution(&input, &Distribution::Std(0.1)).is_err());
    let constant = BRAKES.replace(
        "drag_coefficient_curve = [[0.0, 0.1, 0.0], [1.0, 0.1, 0.8], [0.0, 0.9, 0.0], [1.0, 0.9, 1.1]]",
        "drag_coefficient_curve = 0.9",
    );
    let m = load(&mission("200", &constant), &[]).unwrap_or_else(|e| panic!("{e}"));
    let input = paths::resolve(&m.spec, paths::AIR_BRAKES_CURVE).expect("resolves");
    assert!(matches!(input, paths::Input::Number { .. }));
}

/// The mission with `brakes` and `sets` applied, flown.
fn fly(
    trigger: &str,
    brakes: &str,
    sets: &[(&str, &str)],
) -> Result<karman_mission::assemble::flight::FlightRun, MissionError> {
    let m = load(&mission(trigger, brakes), sets)?;
    karman_mission::assemble::flight::simulate(&m)
}

fn brakes_with(script: &str, extra: &str) -> String {
    format!(
        "[rocket.air_brakes]\ndrag_coefficient_curve = [[0.0, 0.1, 0.0], [1.0, 0.1, 0.8], \
         [0.0, 0.9, 0.0], [1.0, 0.9, 1.1]]\ncontroller = \"{script}\"\nsampling_rate = 20\n{extra}"
    )
}

/// The environment, rocket and flight settings of `mission`.
fn models(
    mission: &karman_mission::Mission,
) -> (
    Arc<karman_mission::atmos::Environment>,
    karman_mission::airframe::Rocket,
    karman_mission::dynamics::FlightSettings,
) {
    use karman_mission::assemble::{environment, motor, preflight, rocket};
    let env = Arc::new(environment::build_environment(mission).unwrap_or_else(|e| panic!("{e}")));
    let motor = motor::build_motor(mission).unwrap_or_else(|e| panic!("{e}"));
    let rocket = rocket::build_rocket(mission, &motor).unwrap_or_else(|e| panic!("{e}"));
    (env, rocket, preflight::flight_settings(mission, 0))
}

fn same_flight(a: &karman_mission::dynamics::Flight, b: &karman_mission::dynamics::Flight) {
    assert_eq!(a.points.len(), b.points.len());
    for (p, q) in a.points.iter().zip(&b.points) {
        assert_eq!(p.t.to_bits(), q.t.to_bits());
        for (x, y) in p.state.iter().zip(&q.state) {
            assert_eq!(x.to_bits(), y.to_bits());
        }
    }
}

#[test]
fn shut_brakes_fly_as_no_brakes_bit_for_bit() {
    // Without overshoot the steps are the solver's own; with it they are at most one sampling
    // interval long, so the flight without brakes gets the same limit.
    let bare = fly("200", "", &[]).unwrap_or_else(|e| panic!("{e}"));
    let shut = fly(
        "200",
        &brakes_with("shut.rhai", ""),
        &[("flight.time_overshoot", "false")],
    )
    .unwrap_or_else(|e| panic!("{e}"));
    same_flight(&bare.flight, &shut.flight);
    let record = shut.controller.expect("record");
    assert!(record.levels.iter().all(|r| r.level.to_bits() == 0));
    // With overshoot the free-flight steps are at most one sampling interval long (the rail
    // and the descents are not bounded by it): the flight without brakes with that bound.
    let bare = load(&mission("200", ""), &[]).unwrap_or_else(|e| panic!("{e}"));
    let (environment, rocket, mut settings) = models(&bare);
    settings.control_max_time_step = 0.05;
    let (bare, _) = karman_mission::assemble::flight::fly(
        &bare,
        &*environment,
        &rocket,
        &settings,
        None,
        || unreachable!("no controller"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let shut = fly("200", &brakes_with("shut.rhai", ""), &[]).unwrap_or_else(|e| panic!("{e}"));
    same_flight(&bare, &shut.flight);
    // Called at j / 20 from launch, the rail included, in order.
    let times: Vec<f64> = shut
        .controller
        .expect("record")
        .levels
        .iter()
        .map(|r| r.time)
        .collect();
    assert_eq!(times[0].to_bits(), 0.0f64.to_bits());
    assert_eq!(times[1].to_bits(), 0.05f64.to_bits());
    assert!(times.windows(2).all(|w| w[1] > w[0]));
}

#[test]
fn a_runaway_controller_ends_the_flight_with_its_location() {
    let error = fly("200", &brakes_with("runaway.rhai", ""), &[])
        .map(|_| ())
        .unwrap_err();
    let text = format!(
        "{error}: {}",
        std::error::Error::source(&error)
            .map(ToString::to_string)
            .unwrap_or_default()
    );
    assert!(text.contains("runaway.rhai:2:1"), "{text}");
    assert!(text.contains("operations"), "{text}");
}

#[test]
fn levels_above_one_are_clamped_unless_clamp_is_off() {
    let clamped =
        fly("200", &brakes_with("overdrive.rhai", ""), &[]).unwrap_or_else(|e| panic!("{e}"));
    let free = fly("200", &brakes_with("overdrive.rhai", "clamp = false"), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    let max = |run: &karman_mission::assemble::flight::FlightRun| {
        run.controller
            .as_ref()
            .expect("record")
            .levels
            .iter()
            .map(|r| r.level)
            .fold(0.0, f64::max)
    };
    assert_eq!(max(&clamped).to_bits(), 1.0f64.to_bits());
    assert_eq!(max(&free).to_bits(), 1.5f64.to_bits());
    // More drag with the level kept at 1.5 (the curve extrapolates).
    assert!(free.summary().apogee_agl_m < clamped.summary().apogee_agl_m);
    let bare = fly("200", "", &[]).unwrap_or_else(|e| panic!("{e}"));
    assert!(clamped.summary().apogee_agl_m < bare.summary().apogee_agl_m);
}

#[test]
fn triggers_by_time_burnout_and_expression() {
    let deploy = |trigger: &str| {
        let run = fly(trigger, "", &[]).unwrap_or_else(|e| panic!("{trigger}: {e}"));
        run.flight.parachute_events[0].trigger_time
    };
    // The first sampling instant (100 Hz) at or after the time, ascent included.
    assert!((deploy("\"launch + 2.5\"") - 2.5).abs() < 1e-12);
    let burn_out = 2.2;
    let t = deploy("\"burnout + 1.0\"");
    assert!(
        t >= burn_out + 1.0 && t < burn_out + 1.0 + 0.01 + 1e-12,
        "{t}"
    );
    // On the ascent, below 20 m/s: before the apogee.
    let run = fly("{ expression = \"vz < 20.0 && z > 1500.0\" }", "", &[])
        .unwrap_or_else(|e| panic!("{e}"));
    let fired = run.flight.parachute_events[0].trigger_time;
    let apogee = run.summary().apogee_time_s.expect("apogee");
    assert!(fired < apogee, "{fired} {apogee}");
}

/// Camoes (air brakes with the team's open-loop controller, a custom drogue trigger) against
/// RocketPy 1.13: the summary within the tolerances of the other flights, and the recorded
/// deployment level at every call equal to the notebook's schedule of that call's time.
#[test]
fn validate_camoes() {
    let Some(dir) = crate::common::validation_dir() else {
        println!("skipped: validation data folder not found");
        return;
    };
    let path = dir.join("camoes/mission.toml");
    let equations = Override::new("flight.equations", "\"rocketpy_1_13\"").expect("override");
    let mission = karman_mission::load(&path, &[equations]).unwrap_or_else(|e| panic!("{e}"));
    let run =
        karman_mission::assemble::flight::simulate(&mission).unwrap_or_else(|e| panic!("{e}"));
    let reference = crate::common::load_reference(&path);
    let r = &reference["summary"];
    let s = serde_json::to_value(run.summary()).expect("summary");
    let rel = |key: &str| {
        let (k, r) = (s[key].as_f64().expect(key), r[key].as_f64().expect(key));
        ((k - r) / r).abs()
    };
    for (key, tolerance) in [
        ("apogee_agl_m", 1e-3),
        ("apogee_time_s", 2e-3),
        ("out_of_rail_velocity_mps", 5e-3),
        ("max_speed_mps", 5e-3),
    ] {
        println!("camoes {key}: {:.4} %", 100.0 * rel(key));
        assert!(rel(key) < tolerance, "{key}: {} against {}", s[key], r[key]);
    }
    let range = r["impact_x_m"]
        .as_f64()
        .unwrap()
        .hypot(r["impact_y_m"].as_f64().unwrap());
    let miss = (s["impact_x_m"].as_f64().unwrap() - r["impact_x_m"].as_f64().unwrap())
        .hypot(s["impact_y_m"].as_f64().unwrap() - r["impact_y_m"].as_f64().unwrap());
    println!("camoes impact: {:.4} % of range", 100.0 * miss / range);
    assert!(miss / range < 1e-2);
    // The drogue fires on the ascent (vz < 5 m/s above 300 m), before the apogee.
    let drogue = run.flight.parachute_events[0].trigger_time;
    assert!(drogue < s["apogee_time_s"].as_f64().unwrap());
    assert!((drogue - 22.5175).abs() < 0.02, "drogue at {drogue}");
    // The schedule of camoes_controller.rhai (C pow, as the script's `**`), clipped.
    let schedule = |t: f64| {
        let level = if t <= 11.4 {
            1.0
        } else {
            -0.002906 * t.powf(3.0) + 0.1497 * t.powf(2.0) + -2.563 * t + 14.96
        };
        let level = if (3.8..=19.6).contains(&t) {
            level
        } else {
            0.0
        };
        level.clamp(0.0, 1.0)
    };
    let record = run.controller.expect("record");
    // RocketPy 1.13: 1082 calls from 0 to 108.3 s, 1083 records with the initial one.
    assert!(
        (1075..=1090).contains(&record.levels.len()),
        "{}",
        record.levels.len()
    );
    assert_eq!(record.observed_variables.len(), record.levels.len() + 1);
    for (call, observed) in record.levels.iter().zip(&record.observed_variables[1..]) {
        assert_eq!(
            call.level.to_bits(),
            schedule(call.time).to_bits(),
            "t = {}",
            call.time
        );
        assert_eq!(observed[0].as_f64().unwrap().to_bits(), call.time.to_bits());
        assert_eq!(
            observed[1].as_f64().unwrap().to_bits(),
            call.level.to_bits()
        );
    }
}

/// A mission of the repository's `fixtures/airbrakes` folder, flown with RocketPy 1.13's
/// equations.
fn fly_airbrakes(name: &str) -> karman_mission::assemble::flight::FlightRun {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/airbrakes")
        .join(name);
    let equations = Override::new("flight.equations", "\"rocketpy_1_13\"").expect("override");
    let mission = karman_mission::load(&path, &[equations]).unwrap_or_else(|e| panic!("{e}"));
    karman_mission::assemble::flight::simulate(&mission).unwrap_or_else(|e| panic!("{e}"))
}

/// The summary of `run` against RocketPy's figures `reference` (summary key, value) within
/// the tolerances of the validation flights (`karman_validation::SUMMARY_PARITY`).
fn summary_parity(
    flight: &str,
    run: &karman_mission::assemble::flight::FlightRun,
    reference: &[(&str, f64)],
) {
    let s = serde_json::to_value(run.summary()).expect("summary");
    for tolerance in karman_validation::SUMMARY_PARITY {
        let r = reference
            .iter()
            .find(|(key, _)| *key == tolerance.key)
            .map(|(_, value)| *value)
            .expect("a reference figure for every tolerance");
        let k = s[tolerance.key].as_f64().expect(tolerance.key);
        let error = ((k - r) / r).abs();
        println!("{flight} {}: {:+.4} %", tolerance.key, 100.0 * (k - r) / r);
        assert!(
            error < tolerance.relative,
            "{flight} {}: {k} against {r}",
            tolerance.key
        );
    }
}

/// RocketPy's "Air Brakes" user guide flown as fixtures/airbrakes/calisto_docs.toml (its
/// controller, a closed loop on the vertical speed, at 10 Hz, time_overshoot = false, to
/// apogee). The figures are RocketPy 1.13.0's for exactly that mission: the page's Python
/// (controller_function, add_air_brakes with air_brakes_cd.csv, Flight(rail_length=5.2,
/// inclination=85, heading=0, time_overshoot=False, terminate_on_apogee=True)) on the Calisto
/// validation flight's rocket, motor and ISA atmosphere, run in a scratch script (not kept);
/// the levels are those of `get_controller_observed_variables()` at the times given.
#[test]
fn validate_airbrakes_docs() {
    let run = fly_airbrakes("calisto_docs.toml");
    summary_parity(
        "airbrakes calisto_docs",
        &run,
        &[
            ("apogee_agl_m", 3000.391113819249),
            ("apogee_time_s", 23.360233082859637),
            ("out_of_rail_velocity_mps", 26.203027914774793),
            ("max_speed_mps", 285.9585357012037),
            ("max_mach", 0.8601636959780354),
        ],
    );
    let record = run.controller.expect("record");
    // RocketPy: the level ramps at 0.2/s from 1500 m AGL (7.3 s) to 1, clamped.
    for (t, level) in [
        (4.0, 0.0),
        (8.0, 0.14),
        (12.0, 0.940_000_000_000_000_5),
        (16.0, 1.0),
        (22.0, 1.0),
    ] {
        let call = record
            .levels
            .iter()
            .find(|r| (r.time - t).abs() < 1e-9)
            .unwrap_or_else(|| panic!("no call at {t} s"));
        assert!((call.level - level).abs() < 1e-9, "{t} s: {}", call.level);
    }
    // The record: the initial entry, then one per call from burn-out (3.9 s) on.
    let observed = &record.observed_variables;
    assert_eq!(observed[0], serde_json::json!([0.0, 0.0, 0.0]));
    assert!((observed[1][0].as_f64().unwrap() - 3.9).abs() < 1e-9);
}

/// Calisto with the guide's air brakes driven at 100 Hz by a proportional controller on the
/// predicted apogee (fixtures/airbrakes/calisto_apogee.toml, time_overshoot left true, to the
/// ground). The figures are RocketPy 1.13.0's for exactly that mission (apogee_controller.rhai
/// written in Python line for line, its parachutes with noise zeroed), from a scratch script
/// (not kept); the levels are those of `get_controller_observed_variables()` at the times
/// given.
#[test]
fn validate_airbrakes_apogee() {
    let run = fly_airbrakes("calisto_apogee.toml");
    summary_parity(
        "airbrakes calisto_apogee",
        &run,
        &[
            ("apogee_agl_m", 3046.7598677104115),
            ("apogee_time_s", 24.619815488918565),
            ("out_of_rail_velocity_mps", 26.207270098401477),
            ("max_speed_mps", 285.9596195562594),
            ("max_mach", 0.8601644986275152),
        ],
    );
    let s = run.summary();
    let (x, y) = (-5.116480540228628, 613.1858079097015);
    let miss = (s.impact_x_m.expect("impact") - x).hypot(s.impact_y_m.expect("impact") - y);
    println!(
        "airbrakes calisto_apogee impact: {:.4} % of range",
        100.0 * miss / x.hypot(y)
    );
    assert!(miss / x.hypot(y) < karman_validation::IMPACT_FRACTION);
    // The level the controller left at its calls, against RocketPy's at the same instants
    // (the predictions differ by under a metre, the levels by under 0.003 over the climb).
    let record = run.controller.expect("record");
    for (t, level) in [
        (3.9, 0.534_232_095_893_759_9),
        (4.5, 0.365_837_755_737_968_1),
        (6.0, 0.236_160_424_120_811_5),
        (8.0, 0.185_445_564_065_956_22),
        (12.0, 0.192_117_439_190_098_6),
        (16.0, 0.188_093_323_149_118_09),
        (20.0, 0.185_719_302_365_074_33),
        (24.0, 0.186_919_854_272_991_88),
    ] {
        let call = record
            .levels
            .iter()
            .find(|r| (r.time - t).abs() < 1e-9)
            .unwrap_or_else(|| panic!("no call at {t} s"));
        assert!(
            (call.level - level).abs() < 5e-3,
            "{t} s: {} against {level}",
            call.level
        );
    }
    // Shut from the apogee on.
    let apogee = s.apogee_time_s.expect("apogee");
    assert!(
        record
            .levels
            .iter()
            .filter(|r| r.time > apogee + 0.01)
            .all(|r| r.level == 0.0)
    );
}

/// Every air-brake mission of the repository flown with its controller compiled and with
/// every call interpreted by Rhai: the same flight and record, bit for bit.
#[test]
fn compiled_controllers_fly_as_the_interpreter_bit_for_bit() {
    use karman_mission::assemble::scripts::{ControllerEnvironment, compile_controller};
    let mut paths: Vec<std::path::PathBuf> = ["calisto_apogee.toml", "calisto_docs.toml"]
        .iter()
        .map(|name| {
            std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("../../fixtures/airbrakes")
                .join(name)
        })
        .collect();
    if let Some(dir) = crate::common::validation_dir() {
        paths.push(dir.join("camoes/mission.toml"));
    }
    for path in paths {
        let mission = karman_mission::load(&path, &[]).unwrap_or_else(|e| panic!("{e}"));
        let (environment, rocket, settings) = models(&mission);
        let script = compile_controller(&mission)
            .unwrap_or_else(|e| panic!("{e}"))
            .expect("a controller");
        assert_eq!(script.interpreted_because(), None, "{}", path.display());
        let fly = |script| {
            karman_mission::assemble::flight::fly(
                &mission,
                &*environment,
                &rocket,
                &settings,
                Some(script),
                || {
                    Arc::new(ControllerEnvironment::new(
                        Arc::clone(&environment),
                        1.0,
                        0.0,
                    ))
                },
            )
            .unwrap_or_else(|e| panic!("{e}"))
        };
        let (compiled, a) = fly(&script);
        let (interpreted, b) = fly(&script.interpreted());
        same_flight(&compiled, &interpreted);
        assert_eq!(compiled.parachute_events, interpreted.parachute_events);
        let (a, b) = (a.expect("record"), b.expect("record"));
        assert_eq!(a.to_json(), b.to_json(), "{}", path.display());
        assert!(
            a.levels
                .iter()
                .zip(&b.levels)
                .all(|(x, y)| x.level.to_bits() == y.level.to_bits()),
            "{}",
            path.display()
        );
    }
}

/// Camoes's controller (the open-loop replay of the team's actuation,
/// `fixtures/validation/camoes/camoes_controller.rhai`) written in Rust flies the Rhai
/// controller's flight, bit for bit: the validation flight's parity with RocketPy 1.13 holds
/// for a controller in either language.
#[test]
fn camoes_with_its_controller_in_rust_flies_the_rhai_flight() {
    use karman_mission::assemble::flight::PreparedFlight;
    use karman_mission::script::{AirBrakeController, AirBrakesControl, ControlInputs};
    struct Replay;
    impl AirBrakeController for Replay {
        fn control(
            &mut self,
            inputs: &ControlInputs<'_>,
            air_brakes: &mut AirBrakesControl<'_>,
        ) -> Result<(), String> {
            let time = inputs.time;
            // Rhai's `**` with a float exponent is `powf`; its sums run left to right.
            let mut level = if time <= 11.4 {
                1.0
            } else {
                -0.002906 * time.powf(3.0) + 0.1497 * time.powf(2.0) + -2.563 * time + 14.96
            };
            if time > 19.6 {
                level = 0.0;
            }
            if time < 3.8 {
                level = 0.0;
            }
            air_brakes.set_deployment_level(level);
            Ok(())
        }
    }
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/validation/camoes/mission.toml");
    let mission = karman_mission::load(&path, &[]).expect("camoes loads");
    let prepared = PreparedFlight::new(&mission).expect("prepares");
    let rhai = prepared.fly(&mission, 0).expect("Rhai flies");
    let rust = prepared
        .fly_with_controller(&mission, 0, &mut Replay)
        .expect("Rust flies");
    assert!(rhai.flight.points.len() > 100);
    assert_eq!(
        crate::common::point_bits(&rhai),
        crate::common::point_bits(&rust)
    );
    assert_eq!(
        format!("{:?}", rhai.summary()),
        format!("{:?}", rust.summary())
    );
}
