//! `[[rocket.sensors]]` against RocketPy 1.13 (docs/physics.md §29).
//!
//! RocketPy's figures are in `fixtures/sensors/rocketpy_sensors.json`, written by
//! `fixtures/sensors/rocketpy_sensors.py` (rerun it with RocketPy 1.13.0 installed): six
//! noise-free sensors on the Calisto flight (`fixtures/sensors/calisto_sensors.toml` is the
//! same flight and sensors in the mission format), each reading with the state `u` and the
//! derivative `u_dot` RocketPy measured it from.
//!
//! - The measurement: karman's sensors, built from the mission, measure RocketPy's own
//!   `(u, u_dot)` and must give RocketPy's readings to 1e-9 of the reading's largest
//!   component (for a GNSS fix 1e-8 m on the sphere, about ten units in the last place of
//!   its latitude in degrees), and RocketPy's `relative_position`.
//! - The flight: karman flies the mission and its readings are compared with RocketPy's at
//!   the same instants, within tolerances per phase that are the flights' own agreement (the
//!   states differ by the parity tolerance of the validation flights, not by the sensors).

use std::path::PathBuf;

use karman_mission::assemble::flight::simulate;
use karman_mission::assemble::preflight::prepare;
use karman_mission::assemble::sensors::{self, EnvironmentSurroundings, SensorReadings};
use karman_mission::sensors::Truth;
use serde_json::Value;

fn fixtures() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/sensors")
}

fn reference() -> Value {
    let text = std::fs::read_to_string(fixtures().join("rocketpy_sensors.json")).expect("json");
    serde_json::from_str(&text).expect("valid json")
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect()
}

fn mission() -> karman_mission::Mission {
    karman_mission::load(&fixtures().join("calisto_sensors.toml"), &[]).expect("mission loads")
}

/// The largest difference of `a` and `b` relative to the largest component of `b`; for a
/// GNSS fix, the distance on the sphere of radius `radius` (and the altitude), m.
fn difference(kind: &str, a: &[f64], b: &[f64], radius: f64) -> f64 {
    if kind == "GnssReceiver" {
        let lat = (a[0] - b[0]).to_radians() * radius;
        let lon = (a[1] - b[1]).to_radians() * radius * b[0].to_radians().cos();
        return lat.abs().max(lon.abs()).max((a[2] - b[2]).abs());
    }
    let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let diff = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    if scale > 0.0 { diff / scale } else { diff }
}

#[test]
fn sensors_measure_rocketpy_states_as_rocketpy_does() {
    let reference = reference();
    let mission = mission();
    let models = prepare(&mission, 0).expect("models");
    let mut built = sensors::build(&mission, &models.rocket, 0).expect("sensors");
    let surroundings = EnvironmentSurroundings(&models.environment);
    let radius = reference["earth_radius"].as_f64().expect("radius");
    // The datum radius is RocketPy's `earth_radius`.
    assert!((models.environment.datum_radius() / radius - 1.0).abs() < 1e-12);
    let table = reference["sensors"].as_object().expect("sensors");
    assert_eq!(table.len(), built.len());
    for sensor in &mut built {
        let name = sensor.spec().name.clone();
        let entry = &table[&name];
        let kind = entry["kind"].as_str().expect("kind");
        let relative = numbers(&entry["relative_position"]);
        for (a, b) in sensor.spec().relative_position.iter().zip(&relative) {
            assert!(
                (a - b).abs() < 1e-15,
                "{name}: relative position {a} vs {b}"
            );
        }
        let (mut worst, mut count) = (0.0f64, 0);
        for sample in entry["samples"].as_array().expect("samples") {
            let u: [f64; 13] = numbers(&sample["u"]).try_into().expect("13 states");
            let u_dot: [f64; 13] = numbers(&sample["u_dot"]).try_into().expect("13 rates");
            let expected = numbers(&sample["reading"]);
            let got = sensor.measure(&Truth { u, u_dot }, &surroundings);
            let d = difference(kind, &got[..expected.len()], &expected, radius);
            let t = sample["t"].as_f64().expect("t");
            let bound = if kind == "GnssReceiver" { 1e-8 } else { 1e-9 };
            assert!(
                d <= bound,
                "{name} at t = {t}: {got:?} vs RocketPy {expected:?} ({d:e})"
            );
            worst = worst.max(d);
            count += 1;
        }
        eprintln!("{name}: {count} readings, largest difference {worst:e}");
    }
}

/// Readings at RocketPy's instants: RocketPy's and karman's.
fn matched(readings: &SensorReadings, t: f64) -> Option<&[f64; 3]> {
    let key = (t * 1e7).round() as i64;
    let i = readings
        .times
        .binary_search_by_key(&key, |s| (s * 1e7).round() as i64)
        .ok()?;
    Some(&readings.values[i])
}

#[test]
fn a_calisto_flight_reads_what_rocketpy_reads() {
    let reference = reference();
    let run = simulate(&mission()).expect("flies");
    let radius = reference["earth_radius"].as_f64().expect("radius");
    let rail_exit = reference["rail_exit_time"].as_f64().expect("rail exit");
    let apogee = reference["apogee_time"].as_f64().expect("apogee");
    // Tolerances per phase, relative to the reading's largest component (GNSS: metres). They
    // are the flights' own agreement: on the rail the two integrations agree to 1e-5, in the
    // burn the attitude to 0.1 %, and from the coast on the rocket's oscillation and spin
    // differ in phase by a few per cent (the parity tolerances of the validation flights are
    // on apogee, speeds and impact, not on the attitude's phase); the barometer follows the
    // height (5e-5) and the GNSS fix the position (10 m at 3 km).
    let bounds = |kind: &str, t: f64| -> f64 {
        let phase = if t <= rail_exit {
            0
        } else if t < 3.9 {
            1
        } else if t < apogee {
            2
        } else {
            3
        };
        match kind {
            "Barometer" => 5e-5,
            "GnssReceiver" => [1e-2, 1.0, 10.0, 10.0][phase],
            "Gyroscope" => [1e-5, 2e-3, 2e-2, 5e-2][phase],
            _ => [1e-5, 5e-3, 0.1, 0.15][phase],
        }
    };
    let table = reference["sensors"].as_object().expect("sensors");
    for readings in &run.sensors {
        let entry = &table[&readings.name];
        let kind = entry["kind"].as_str().expect("kind");
        // Both sample from t = 0 at j / rate; RocketPy's last reading is before the last
        // step (which finds the impact and is not sampled), karman's too.
        assert_eq!(readings.times[0].to_bits(), 0.0f64.to_bits());
        let last = entry["last_time"].as_f64().expect("last");
        assert!(
            (readings.times.last().expect("readings") - last).abs() < 2.0,
            "{}: last reading {:?} vs RocketPy {last}",
            readings.name,
            readings.times.last()
        );
        let mut worst = [0.0f64; 4];
        for sample in entry["samples"].as_array().expect("samples") {
            let t = sample["t"].as_f64().expect("t");
            let expected = numbers(&sample["reading"]);
            let got = matched(readings, t)
                .unwrap_or_else(|| panic!("{}: no reading at t = {t}", readings.name));
            let d = difference(kind, &got[..expected.len()], &expected, radius);
            let bound = bounds(kind, t);
            assert!(
                d <= bound,
                "{} at t = {t}: {got:?} vs RocketPy {expected:?} ({d:e} > {bound:e})",
                readings.name
            );
            let phase =
                usize::from(t > rail_exit) + usize::from(t >= 3.9) + usize::from(t >= apogee);
            worst[phase] = worst[phase].max(d);
        }
        eprintln!(
            "{}: largest difference rail {:.1e}, burn {:.1e}, coast {:.1e}, descent {:.1e}",
            readings.name, worst[0], worst[1], worst[2], worst[3]
        );
    }
}

/// The Calisto sensor mission with its sensors replaced by `sensors` (TOML text), parsed as
/// if it were the fixture: the error text, or `None` when it loads and prepares.
fn error_of(sensors: &str) -> Option<String> {
    let path = fixtures().join("calisto_sensors.toml");
    let text = std::fs::read_to_string(&path).expect("fixture");
    let start = text.find("[[rocket.sensors]]").expect("sensors");
    let end = text.find("\n[flight]").expect("flight");
    let text = format!("{}{sensors}\n{}", &text[..start], &text[end..]);
    match karman_mission::parse(&text, &path, &[]) {
        Err(e) => Some(crate::common::chain(&e)),
        Ok(mission) => prepare(&mission, 0).err().map(|e| crate::common::chain(&e)),
    }
}

#[test]
fn bad_sensors_are_clear_errors_of_check() {
    let cases: &[(&str, &[&str])] = &[
        // Outside the rocket: beyond the nose tip (1.278 m), and radially.
        (
            "[[rocket.sensors]]\nkind = \"barometer\"\nname = \"b\"\nsampling_rate = 10\nposition = 2.5\n",
            &[
                "rocket.sensors.0.position",
                "outside the rocket",
                "[-1.2",
                "1.278]",
            ],
        ),
        (
            "[[rocket.sensors]]\nkind = \"gnss\"\nname = \"g\"\nsampling_rate = 1\nposition = [0.5, 0, 0]\n",
            &["rocket.sensors.0.position", "largest radius"],
        ),
        // A rate above the documented bound, and not positive.
        (
            "[[rocket.sensors]]\nkind = \"gyroscope\"\nname = \"w\"\nsampling_rate = 20000\nposition = 0\n",
            &["rocket.sensors.0.sampling_rate", "20000", "(0, 10000] Hz"],
        ),
        (
            "[[rocket.sensors]]\nkind = \"gyroscope\"\nname = \"w\"\nsampling_rate = -1\nposition = 0\n",
            &["rocket.sensors.0.sampling_rate", "(0, 10000] Hz"],
        ),
        // Negative variances and densities.
        (
            "[[rocket.sensors]]\nkind = \"accelerometer\"\nname = \"a\"\nsampling_rate = 100\nposition = 0\nnoise_variance = [1, -2, 1]\n",
            &["rocket.sensors.0.noise_variance", "-2", ">= 0"],
        ),
        (
            "[[rocket.sensors]]\nkind = \"barometer\"\nname = \"b\"\nsampling_rate = 10\nposition = 0\nrandom_walk_variance = -0.5\n",
            &["rocket.sensors.0.random_walk_variance", "-0.5"],
        ),
        // A key of another kind, three values on a barometer, an unknown key and kind.
        (
            "[[rocket.sensors]]\nkind = \"barometer\"\nname = \"b\"\nsampling_rate = 10\nposition = 0\norientation = [0, 90, 0]\n",
            &["rocket.sensors.0.orientation", "barometer"],
        ),
        (
            "[[rocket.sensors]]\nkind = \"barometer\"\nname = \"b\"\nsampling_rate = 10\nposition = 0\nconstant_bias = [1, 2, 3]\n",
            &["rocket.sensors.0.constant_bias", "one axis"],
        ),
        (
            "[[rocket.sensors]]\nkind = \"gnss\"\nname = \"g\"\nsampling_rate = 1\nposition = 0\nnoise_density = 1\n",
            &["rocket.sensors.0.noise_density", "gnss"],
        ),
        (
            "[[rocket.sensors]]\nkind = \"gyroscope\"\nname = \"w\"\nsampling_rate = 10\nposition = 0\nbias = 1\n",
            &["bias"],
        ),
        (
            "[[rocket.sensors]]\nkind = \"lidar\"\nname = \"l\"\nsampling_rate = 10\nposition = 0\n",
            &["lidar"],
        ),
        // Names: duplicated, not a file name.
        (
            "[[rocket.sensors]]\nkind = \"barometer\"\nname = \"b\"\nsampling_rate = 10\nposition = 0\n\n[[rocket.sensors]]\nkind = \"gnss\"\nname = \"b\"\nsampling_rate = 1\nposition = 0\n",
            &["rocket.sensors.1.name", "already defined"],
        ),
        (
            "[[rocket.sensors]]\nkind = \"barometer\"\nname = \"../x\"\nsampling_rate = 10\nposition = 0\n",
            &["rocket.sensors.0.name", "letters, digits"],
        ),
        // Ranges and domains.
        (
            "[[rocket.sensors]]\nkind = \"accelerometer\"\nname = \"a\"\nsampling_rate = 100\nposition = 0\nmeasurement_range = [5, -5]\n",
            &["rocket.sensors.0.measurement_range", "low < high"],
        ),
        (
            "[[rocket.sensors]]\nkind = \"accelerometer\"\nname = \"a\"\nsampling_rate = 100\nposition = 0\ncross_axis_sensitivity = 150\n",
            &["rocket.sensors.0.cross_axis_sensitivity", "[0, 100]"],
        ),
        (
            "[[rocket.sensors]]\nkind = \"accelerometer\"\nname = \"a\"\nsampling_rate = 100\nposition = 0\noperating_temperature = -3\n",
            &["rocket.sensors.0.operating_temperature", "kelvin"],
        ),
        (
            "[[rocket.sensors]]\nkind = \"gnss\"\nname = \"g\"\nsampling_rate = 1\nposition = 0\naltitude_accuracy = -1\n",
            &["rocket.sensors.0.altitude_accuracy"],
        ),
        (
            "[[rocket.sensors]]\nkind = \"gyroscope\"\nname = \"w\"\nsampling_rate = 10\nposition = [0, 0]\n",
            &["calisto_sensors.toml:", "[x, y, z], got 2 numbers"],
        ),
        (
            "[[rocket.sensors]]\nkind = \"gyroscope\"\nname = \"w\"\nsampling_rate = nan\nposition = 0\n",
            &[
                "calisto_sensors.toml:",
                "rocket.sensors.0.sampling_rate",
                "NaN",
            ],
        ),
    ];
    for (sensors, needles) in cases {
        let message = error_of(sensors).unwrap_or_else(|| panic!("accepted:\n{sensors}"));
        for needle in *needles {
            assert!(
                message.contains(needle),
                "{needle:?} not in the error of\n{sensors}\n{message}"
            );
        }
    }
    // The same entries written well load, with defaults filled in.
    assert_eq!(
        error_of(
            "[[rocket.sensors]]\nkind = \"barometer\"\nname = \"b\"\nsampling_rate = 10000\nposition = [0, 0.06, -1.2]\nmeasurement_range = 120000\nresolution = 1\n\n[[rocket.sensors]]\nkind = \"gyroscope\"\nname = \"w\"\nsampling_rate = 1\nposition = 0\nmeasurement_range = inf\n"
        ),
        None
    );
}

#[test]
fn noisy_sensors_replay_bit_for_bit_and_follow_the_seed() {
    let path = fixtures().join("calisto_sensors.toml");
    let text = std::fs::read_to_string(&path).expect("fixture");
    let text = text.replace(
        "name = \"baro\"\nsampling_rate = 50\n",
        "name = \"baro\"\nsampling_rate = 50\nnoise_density = 2.0\nrandom_walk_density = 0.5\n",
    );
    let text = text.replace(
        "name = \"gps\"\nsampling_rate = 10\n",
        "name = \"gps\"\nsampling_rate = 10\nposition_accuracy = 2.5\naltitude_accuracy = 4\n",
    );
    let mission = karman_mission::parse(&text, &path, &[]).expect("mission");
    let fly =
        |seed| karman_mission::assemble::flight::simulate_with_seed(&mission, seed).expect("flies");
    let bits = |run: &karman_mission::assemble::flight::FlightRun| -> Vec<u64> {
        run.sensors
            .iter()
            .flat_map(|r| r.values.iter().flatten().chain(&r.times))
            .map(|v| v.to_bits())
            .collect()
    };
    let (a, b, c) = (fly(3), fly(3), fly(4));
    assert_eq!(bits(&a), bits(&b));
    assert_ne!(bits(&a), bits(&c));
    // The noise-free sensors read the same whatever the seed; the noisy ones differ.
    for (x, y) in a.sensors.iter().zip(&c.sensors) {
        let same = x.values == y.values;
        assert_eq!(
            same,
            !matches!(x.name.as_str(), "baro" | "gps"),
            "{}",
            x.name
        );
    }
    // A noisy barometer's readings scatter about the noise-free one by the model's spread:
    // white noise 2·√50 Pa per reading (the walk adds at most 0.5·√t Pa-ish over the flight).
    let quiet = simulate(&karman_mission::load(&path, &[]).expect("mission")).expect("flies");
    let (noisy, clean) = (&a.sensors[4], &quiet.sensors[4]);
    assert_eq!(noisy.name, "baro");
    let n = noisy.times.len().min(clean.times.len()).min(2000);
    let diffs: Vec<f64> = (1..n)
        .map(|i| {
            (noisy.values[i][0] - clean.values[i][0])
                - (noisy.values[i - 1][0] - clean.values[i - 1][0])
        })
        .collect();
    // Successive differences remove the walk's level: their spread is √2 σ_w (plus the walk's
    // own step, 0.5/√50 Pa, negligible); 2000 readings estimate it within a few per cent.
    let sd = (diffs.iter().map(|d| d * d).sum::<f64>() / diffs.len() as f64).sqrt();
    let expected = std::f64::consts::SQRT_2 * 2.0 * 50f64.sqrt();
    assert!((sd / expected - 1.0).abs() < 0.1, "{sd} vs {expected}");
}
