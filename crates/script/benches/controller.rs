//! One call of a closed-loop air-brake controller (the apogee predictor of the test missions'
//! `closed_loop.rhai`): the per-call cost a controller adds to a flight, arguments built,
//! script run and record kept; and an interpreted controller reading two sensors of its
//! `sensors` argument (their readings stored before each call, as the engine does), against
//! the same script handed no sensors. `cargo xtask bench` prints the median per call.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use karman_script::{
    AirBrakesSetup, Controller, ControllerScript, ControllerSetup, EnvironmentQuery, SensorSetup,
};
use std::hint::black_box;
use std::path::Path;
use std::sync::Arc;

const SCRIPT: &str = include_str!("../../mission/tests/fixtures/closed_loop.rhai");

struct Still;

impl EnvironmentQuery for Still {
    fn elevation(&self) -> f64 {
        1400.0
    }
    fn wind_velocity_x(&self, _: f64) -> f64 {
        2.0
    }
    fn wind_velocity_y(&self, _: f64) -> f64 {
        -1.0
    }
    fn speed_of_sound(&self, _: f64) -> f64 {
        330.0
    }
    fn density(&self, _: f64) -> f64 {
        1.0
    }
    fn pressure(&self, _: f64) -> f64 {
        85_000.0
    }
    fn temperature(&self, _: f64) -> f64 {
        280.0
    }
    fn dynamic_viscosity(&self, _: f64) -> f64 {
        1.7e-5
    }
    fn gravity(&self, _: f64) -> f64 {
        9.79
    }
}

fn controller(c: &mut Criterion) {
    let script =
        ControllerScript::compile(Path::new("closed_loop.rhai"), SCRIPT).expect("compiles");
    let setup = ControllerSetup {
        sampling_rate: 100.0,
        air_brakes: AirBrakesSetup {
            clamp: true,
            override_rocket_drag: false,
            reference_area: 0.01,
            initial_level: 0.0,
            drag_coefficient: Arc::new(|level, mach| 0.8 * level + 0.1 * mach),
        },
        burn_start: 0.0,
        burn_out: 3.9,
        environment: Arc::new(Still),
        initial_observed_variables: None,
        constants: Vec::new(),
    };
    let mut state = [0.0; 13];
    state[2] = 3000.0;
    state[5] = 120.0;
    state[6] = 1.0;
    let mut row = [0.0; 14];
    row[1..].copy_from_slice(&state);
    let mut group = c.benchmark_group("controller");
    group.throughput(Throughput::Elements(1));
    group.bench_function("closed_loop_call", |b| {
        let mut controller = Controller::new(&script, setup.clone()).expect("controller");
        let mut t = 5.0;
        b.iter(|| {
            t += 0.01;
            row[0] = t + 0.005;
            black_box(controller.call(t, &state, &row).expect("call"))
        });
    });
    // A controller reading a barometer and an accelerometer (interpreted: `sensors` is
    // outside the compiled subset), and the same arguments to a script that reads none.
    let reading =
        ControllerScript::compile(Path::new("sensors.rhai"), SENSOR_SCRIPT).expect("compiles");
    let ignoring =
        ControllerScript::compile(Path::new("ignoring.rhai"), IGNORING_SCRIPT).expect("compiles");
    let sensors = [
        SensorSetup {
            name: "baro".into(),
            kind: "barometer".into(),
            components: 1,
        },
        SensorSetup {
            name: "imu".into(),
            kind: "accelerometer".into(),
            components: 3,
        },
    ];
    for (name, script, with) in [
        ("sensor_reading_call", &reading, &sensors[..]),
        ("sensor_ignoring_call", &ignoring, &sensors[..]),
        ("no_sensor_call", &ignoring, &[][..]),
    ] {
        group.bench_function(name, |b| {
            let mut controller = Controller::new(script, setup.clone())
                .expect("controller")
                .with_sensors(with);
            let mut t = 5.0;
            b.iter(|| {
                t += 0.01;
                row[0] = t + 0.005;
                controller.set_sensor(0, t - 0.01, [70_000.0 - t, 0.0, 0.0]);
                controller.set_sensor(1, t - 0.01, [0.1, -0.2, -9.0 - t]);
                black_box(controller.call(t, &state, &row).expect("call"))
            });
        });
    }
    group.finish();
}

/// Reads both sensors and opens the brakes on the barometer (interpreted).
const SENSOR_SCRIPT: &str = "
fn controller_function(time, sampling_rate, state, state_history, observed_variables,
                       air_brakes, sensors) {
    let p = sensors[0].measurement;
    let az = sensors[1].measurement[2];
    if p != () && p < 69990.0 && az < 0.0 {
        air_brakes.deployment_level = 1.0;
    }
    return ();
}
";

/// The same signature, reading no sensor (interpreted: it loops once).
const IGNORING_SCRIPT: &str = "
fn controller_function(time, sampling_rate, state, state_history, observed_variables,
                       air_brakes, sensors) {
    let p = 0.0;
    for i in 0..1 { p = state[2]; }
    if p > 1.0e9 {
        air_brakes.deployment_level = 1.0;
    }
    return ();
}
";

criterion_group!(benches, controller);
criterion_main!(benches);
