//! Sensor readings read by the flight: the air-brake controller's `sensors` argument and
//! trigger expressions `sensors[i]` / `sensors.NAME` (docs/physics.md §29.3,
//! mission-format.md "The controller script" and "Custom triggers").
//!
//! The missions are the Calisto flight of `fixtures/sensors/calisto_sensors.toml` with one
//! noise-free barometer at the centre of dry mass (so that it reads the pressure at the
//! state's height `z` exactly) sampled at the reader's rate. RocketPy 1.13 runs the nodes it
//! samples on the solver's steps (`time_overshoot`, the default) as parachutes, then
//! controllers, then sensors, so a reader at an instant it shares with the barometer reads
//! the barometer's previous reading: the reader of the sensor decides exactly one sampling
//! interval after the same reader of the state, and the two flights are the same bytes up to
//! that first decision.

use std::path::PathBuf;

use karman_mission::assemble::flight::{FlightRun, simulate, simulate_with_seed};
use karman_mission::assemble::preflight::prepare;
use karman_mission::montecarlo::{MonteCarlo, StudyOverrides};

fn fixtures() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/sensors")
}

/// The Calisto sensor mission's text with its sensors replaced by `sensors` (TOML text)
/// and its main parachute's trigger by `main` (a TOML value).
fn text_with(sensors: &str, main: &str) -> String {
    let text = std::fs::read_to_string(fixtures().join("calisto_sensors.toml")).expect("fixture");
    let start = text.find("[[rocket.sensors]]").expect("sensors");
    let end = text.find("\n[flight]").expect("flight");
    let text = format!("{}{sensors}\n{}", &text[..start], &text[end..]);
    text.replacen("trigger = 800", &format!("trigger = {main}"), 1)
}

fn parse(text: &str) -> karman_mission::Mission {
    karman_mission::parse(text, &fixtures().join("calisto_sensors.toml"), &[])
        .unwrap_or_else(|e| panic!("{e}"))
}

/// A noise-free barometer named `baro` at the centre of dry mass, sampled at `rate`, with
/// `extra` keys.
fn barometer_at_cdm(rate: f64, extra: &str) -> String {
    let plain = parse(&text_with("", "800"));
    let rocket = prepare(&plain, 0).expect("models").rocket;
    // RocketPy's relative position `z − csys·z_CDM` is then exactly 0.
    let z = rocket.csys() * rocket.center_of_dry_mass();
    format!(
        "[[rocket.sensors]]\nkind = \"barometer\"\nname = \"baro\"\nsampling_rate = {rate:?}\n\
         position = {z:?}\n{extra}\n"
    )
}

/// Air brakes driven by `controller` at `rate`.
fn air_brakes(controller: &str, rate: f64) -> String {
    format!(
        "[rocket.air_brakes]\ndrag_coefficient_curve = 1.5\nreference_area = 0.05\n\
         controller = \"{controller}\"\nsampling_rate = {rate:?}\n"
    )
}

/// The calls of a flight's controller: `[time, reading time, pressure]` each.
fn calls(run: &FlightRun) -> Vec<[f64; 3]> {
    let record = run.controller.as_ref().expect("a controller");
    record
        .observed_variables
        .iter()
        .map(|v| {
            let row: Vec<f64> = v
                .as_array()
                .expect("array")
                .iter()
                .map(|x| x.as_f64().expect("number"))
                .collect();
            [row[0], row[1], row[2]]
        })
        .collect()
}

/// The index `j` of the sampling instant `t = j / rate`.
fn key(t: f64, rate: f64) -> i64 {
    (t * rate).round() as i64
}

/// The instant of the first call that opened the brakes.
fn first_opening(run: &FlightRun) -> f64 {
    let record = run.controller.as_ref().expect("a controller");
    record
        .levels
        .iter()
        .find(|l| l.level > 0.5)
        .expect("the brakes open")
        .time
}

#[test]
fn a_controller_reading_its_barometer_decides_one_reading_after_the_state() {
    let rate = 100.0;
    let sensor = barometer_at_cdm(rate, "");
    let by_sensor = parse(&text_with(
        &format!("{sensor}\n{}", air_brakes("baro_controller.rhai", rate)),
        "800",
    ));
    let by_state = parse(&text_with(
        &format!("{sensor}\n{}", air_brakes("state_controller.rhai", rate)),
        "800",
    ));
    let (a, b) = (
        simulate(&by_sensor).expect("flies"),
        simulate(&by_state).expect("flies"),
    );
    let (t_sensor, t_state) = (first_opening(&a), first_opening(&b));
    assert_eq!(
        key(t_sensor, rate),
        key(t_state, rate) + 1,
        "sensor {t_sensor} s, state {t_state} s"
    );
    assert!(t_state > 3.9, "opened after burn-out: {t_state} s");
    // Up to the state's decision the flights are the same: the barometer's reading at each
    // call is the state's pressure of the call before, bit for bit, taken at that instant.
    let (sa, sb) = (calls(&a), calls(&b));
    assert_eq!(
        sa[0].map(f64::to_bits),
        [0.0, -1.0, -1.0].map(f64::to_bits),
        "no reading before the first"
    );
    let n = sb
        .iter()
        .position(|c| c[0] >= t_state)
        .expect("the decision")
        + 1;
    let baro = &a.sensors[0];
    assert_eq!(baro.name, "baro");
    for (k, (now, pair)) in sa[1..n].iter().zip(sb.windows(2)).enumerate() {
        let (before, same) = (pair[0], pair[1]);
        assert_eq!(now[0].to_bits(), same[0].to_bits(), "call {}", k + 1);
        assert_eq!(
            now[1].to_bits(),
            before[1].to_bits(),
            "reading time, call {}",
            k + 1
        );
        assert_eq!(
            now[2].to_bits(),
            before[2].to_bits(),
            "pressure, call {}",
            k + 1
        );
        // The barometer's own record holds the same readings.
        assert_eq!(baro.times[k].to_bits(), now[1].to_bits());
        assert_eq!(baro.values[k][0].to_bits(), now[2].to_bits());
    }
    eprintln!(
        "state opens the brakes at {t_state} s, the barometer's reader at {t_sensor} s ({n} calls)"
    );
}

#[test]
fn without_time_overshoot_a_controller_reads_the_reading_of_its_instant() {
    // RocketPy's hard-stop nodes measure the sensors before calling the controllers: the
    // reader of the barometer decides at the same instant as the reader of the state.
    let rate = 100.0;
    let sensor = barometer_at_cdm(rate, "");
    let fly = |controller: &str| {
        let text = text_with(
            &format!("{sensor}\n{}", air_brakes(controller, rate)),
            "800",
        )
        .replacen("[flight]\n", "[flight]\ntime_overshoot = false\n", 1);
        simulate(&parse(&text)).expect("flies")
    };
    let (a, b) = (fly("baro_controller.rhai"), fly("state_controller.rhai"));
    let (t_sensor, t_state) = (first_opening(&a), first_opening(&b));
    assert_eq!(
        t_sensor.to_bits(),
        t_state.to_bits(),
        "{t_sensor} s vs {t_state} s"
    );
    let (sa, sb) = (calls(&a), calls(&b));
    let n = sb
        .iter()
        .position(|c| c[0] >= t_state)
        .expect("the decision")
        + 1;
    for (k, (x, y)) in sa[..n].iter().zip(&sb[..n]).enumerate() {
        assert_eq!(x[0].to_bits(), y[0].to_bits(), "call {k}");
        assert_eq!(x[1].to_bits(), y[0].to_bits(), "reading time, call {k}");
        assert_eq!(x[2].to_bits(), y[2].to_bits(), "pressure, call {k}");
    }
    // The control the call sets cuts the phase at the instant; the barometer still reads
    // each instant once.
    let times = &a.sensors[0].times;
    assert!(
        times.windows(2).all(|w| w[1] > w[0]),
        "instants measured twice"
    );
    // After the decision the flights go on alike (the same level from the same instant).
    let apogee = |run: &FlightRun| run.summary().apogee_time_s.map(f64::to_bits);
    assert_eq!(apogee(&a), apogee(&b));
}

#[test]
fn a_trigger_on_a_sensor_fires_one_reading_after_the_state_trigger() {
    let rate = 105.0; // the parachutes' sampling rate in the fixture
    let sensor = barometer_at_cdm(rate, "");
    let fly = |main: &str| simulate(&parse(&text_with(&sensor, main))).expect("flies");
    let main_time = |run: &FlightRun| {
        run.flight
            .parachute_events
            .iter()
            .find(|e| e.name == "main")
            .expect("main fires")
            .trigger_time
    };
    let state = fly("{ expression = \"p < 70000.0\" }");
    let t_state = main_time(&state);
    // The spellings of one reading: by index, by name, RocketPy's `.measurement`.
    for main in [
        "{ expression = \"sensors[0] < 70000.0\" }",
        "{ expression = \"sensors.baro < 70000.0\" }",
        "{ expression = \"sensors[0].measurement < 70000.0\" }",
    ] {
        let run = fly(main);
        let t = main_time(&run);
        assert_eq!(
            key(t, rate),
            key(t_state, rate) + 1,
            "{main}: {t} s vs {t_state} s"
        );
        // Before the state trigger's instant (which cuts the step holding it) the flights
        // store the same points, bit for bit.
        let upto = |run: &FlightRun| -> Vec<u64> {
            run.flight
                .points
                .iter()
                .take_while(|p| p.t < t_state)
                .flat_map(|p| std::iter::once(p.t).chain(p.state))
                .map(f64::to_bits)
                .collect()
        };
        let (a, b) = (upto(&run), upto(&state));
        let first = a.iter().zip(&b).position(|(x, y)| x != y);
        assert!(
            a.len() == b.len() && first.is_none(),
            "{main}: {} vs {} values, first difference at {first:?}",
            a.len(),
            b.len()
        );
    }
    // A component of a three-component reading: an accelerometer's axial reading after
    // burn-out (drag only, negative) combined with the barometer.
    let imu = format!(
        "{sensor}\n[[rocket.sensors]]\nkind = \"accelerometer\"\nname = \"imu\"\n\
         sampling_rate = 105.0\nposition = 0.0\n"
    );
    let run = simulate(&parse(&text_with(
        &imu,
        "{ expression = \"sensors.imu[2] < 0.0 && sensors[0] < 70000.0\" }",
    )))
    .expect("flies");
    assert!(
        (main_time(&run) - t_state).abs() < 1.0,
        "{}",
        main_time(&run)
    );
}

/// The error text of `karman check` (load, then prepare) of `text`.
fn check_error(text: &str) -> String {
    let path = fixtures().join("calisto_sensors.toml");
    match karman_mission::parse(text, &path, &[]) {
        Err(e) => crate::common::chain(&e),
        Ok(mission) => match prepare(&mission, 0) {
            Err(e) => crate::common::chain(&e),
            Ok(_) => panic!("accepted:\n{text}"),
        },
    }
}

#[test]
fn bad_sensor_reads_are_located_errors_of_check() {
    let sensor = barometer_at_cdm(50.0, "");
    let imu = format!(
        "{sensor}\n[[rocket.sensors]]\nkind = \"gyroscope\"\nname = \"gyro\"\n\
         sampling_rate = 50.0\nposition = 0.0\n"
    );
    let cases: &[(&str, &str, &[&str])] = &[
        (
            &sensor,
            "sensors.bar < 1.0",
            &["no sensor named `bar`", "0: baro", "character 9"],
        ),
        (
            &sensor,
            "sensors[1] < 1.0",
            &["no sensor at index 1", "character 9"],
        ),
        (
            &sensor,
            "sensors[0][2] < 1.0",
            &["reads one number", "baro", "character 12"],
        ),
        (
            &imu,
            "sensors.gyro < 1.0",
            &["reads 3 numbers", "sensors.gyro[0]"],
        ),
        (&imu, "sensors[1][3] < 1.0", &["components 0 to 2, not 3"]),
        ("", "sensors[0] < 1.0", &["has no [[rocket.sensors]]"]),
    ];
    for (sensors, expression, needles) in cases {
        let text = text_with(sensors, &format!("{{ expression = \"{expression}\" }}"));
        let message = check_error(&text);
        for needle in [
            "calisto_sensors.toml",
            "rocket.parachutes.main.trigger",
            expression,
        ]
        .iter()
        .chain(*needles)
        {
            assert!(
                message.contains(needle),
                "{needle:?} not in the error of {expression:?}:\n{message}"
            );
        }
    }
}

#[test]
fn dispersed_sensor_noise_is_the_same_study_on_one_and_two_threads() {
    // The main parachute fires on the ascent when the noisy barometer reads below 70 kPa: its
    // noise (dispersed by dotted path) moves the deployment, and so the apogee.
    let sensor = barometer_at_cdm(105.0, "noise_density = 20.0\nconstant_bias = 0.0\n");
    let study = "\n[dispersion]\nsamples = 6\nseed = 11\n\n[dispersion.vary]\n\
                 \"rocket.sensors.0.noise_density\" = { uniform = [0.0, 400.0] }\n\
                 \"rocket.sensors.0.constant_bias\" = { std = 2000.0 }\n";
    let text = text_with(&sensor, "{ expression = \"sensors.baro < 70000.0\" }") + study;
    let mission = parse(&text);
    let mc = MonteCarlo::new(&mission, StudyOverrides::default()).expect("study");
    let run = |threads| {
        let options = karman_mission::dispersion::RunOptions {
            threads: Some(threads),
            ..Default::default()
        };
        let stop = std::sync::atomic::AtomicBool::new(false);
        karman_mission::dispersion::run_in_memory(mc.study(), &options, &stop, |i, v| mc.fly(i, v))
            .expect("study runs")
    };
    let (one, two) = (run(1), run(2));
    assert_eq!(one.rows, two.rows);
    assert_eq!(one.report.summary, two.report.summary);
    // The draws reach the sensor: the samples' apogees differ.
    let text = format!("{:?}", one.rows);
    let mut apogees: Vec<String> = one
        .rows
        .iter()
        .map(|r| format!("{:?}", r.outputs.first()))
        .collect();
    apogees.sort();
    apogees.dedup();
    assert!(apogees.len() > 3, "{text}");
    // The noise of a single flight follows the seed: same seed, same bytes.
    let bits = |run: &FlightRun| -> Vec<u64> {
        run.sensors[0]
            .values
            .iter()
            .flatten()
            .map(|v| v.to_bits())
            .collect()
    };
    let (a, b) = (
        simulate_with_seed(&mission, 5).expect("flies"),
        simulate_with_seed(&mission, 5).expect("flies"),
    );
    assert_eq!(bits(&a), bits(&b));
}

#[test]
fn sensor_noise_keys_are_dotted_paths() {
    let sensor = barometer_at_cdm(
        50.0,
        "noise_density = 2.0\nresolution = 0.5\nmeasurement_range = [0.0, 120000.0]\n",
    );
    let imu = "[[rocket.sensors]]\nkind = \"accelerometer\"\nname = \"imu\"\nsampling_rate = 100.0\n\
               position = [0.0, 0.0, 0.1]\nnoise_density = [0.1, 0.2, 0.3]\nconstant_bias = 0.05\n\
               orientation = [0.0, 0.0, 0.0]\ncross_axis_sensitivity = 1.0\n";
    let mut mission = parse(&text_with(&format!("{sensor}\n{imu}"), "800"));
    let spec = &mut mission.spec;
    for (path, value) in [
        ("rocket.sensors.0.noise_density", 3.0),
        ("rocket.sensors.0.resolution", 1.0),
        ("rocket.sensors.0.sampling_rate", 20.0),
        ("rocket.sensors.0.measurement_range.1", 110_000.0),
        ("rocket.sensors.0.position.2", 0.25),
        ("rocket.sensors.1.noise_density.2", 0.4),
        ("rocket.sensors.1.constant_bias", 0.07),
        ("rocket.sensors.1.orientation.1", 5.0),
        ("rocket.sensors.1.cross_axis_sensitivity", 2.0),
    ] {
        karman_mission::paths::set_number(spec, path, value)
            .unwrap_or_else(|e| panic!("{path}: {e}"));
        match karman_mission::paths::resolve(spec, path) {
            Ok(karman_mission::paths::Input::Number { value: v, .. }) => {
                assert_eq!(v.to_bits(), value.to_bits(), "{path}");
            }
            other => panic!("{path}: {other:?}"),
        }
    }
    let s = &spec.rocket.sensors;
    assert_eq!(s[0].noise_density.map(|a| a.values()), Some([3.0; 3]));
    assert_eq!(
        s[1].noise_density.map(|a| a.values()),
        Some([0.1, 0.2, 0.4])
    );
    assert_eq!(s[0].sampling_rate.to_bits(), 20.0f64.to_bits());
    // A key the file does not set, and a component of a one-number key, are not inputs.
    assert!(
        karman_mission::paths::set_number(spec, "rocket.sensors.0.random_walk_density", 1.0)
            .is_err()
    );
    assert!(
        karman_mission::paths::set_number(spec, "rocket.sensors.1.constant_bias.0", 1.0).is_err()
    );
    assert!(
        karman_mission::paths::set_number(spec, "rocket.sensors.2.noise_density", 1.0).is_err()
    );
}

#[test]
fn check_s_first_call_sees_the_sensors_as_the_flight_s_first_call() {
    use karman_mission::assemble::scripts::{compile_controller, first_call};
    let sensor = barometer_at_cdm(100.0, "");
    let first = |overshoot: bool| {
        let mut text = text_with(
            &format!(
                "{sensor}\n{}",
                air_brakes("unguarded_controller.rhai", 100.0)
            ),
            "800",
        );
        if !overshoot {
            text = text.replacen("[flight]\n", "[flight]\ntime_overshoot = false\n", 1);
        }
        let mission = parse(&text);
        let models = prepare(&mission, 0).expect("models");
        let script = compile_controller(&mission)
            .expect("compiles")
            .expect("a script");
        let checked = first_call(&mission, &script, &models.rocket, &models.environment);
        let flown = simulate(&mission);
        (
            checked.err().map(|e| crate::common::chain(&e)),
            flown.err().map(|e| crate::common::chain(&e)),
        )
    };
    // On the solver's steps the first call (t = 0) comes before the first reading: check and
    // the flight both fail, in the script.
    let (checked, flown) = first(true);
    let checked = checked.expect("check refuses");
    assert!(checked.contains("unguarded_controller.rhai:5"), "{checked}");
    assert!(
        flown
            .expect("the flight fails")
            .contains("unguarded_controller.rhai:5")
    );
    // Without time overshoot the barometer reads first: both pass.
    assert_eq!(first(false), (None, None));
}
