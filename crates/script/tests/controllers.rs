//! Rhai controllers: the interface of the contract, the record, clamping, constants, the
//! sandbox and located errors.

use karman_script::{
    AirBrakesSetup, Controller, ControllerScript, ControllerSetup, EnvironmentQuery, ScriptError,
    SensorSetup,
};
use std::path::Path;
use std::sync::Arc;

struct Air;

impl EnvironmentQuery for Air {
    fn elevation(&self) -> f64 {
        107.0
    }
    fn wind_velocity_x(&self, h: f64) -> f64 {
        h / 100.0
    }
    fn wind_velocity_y(&self, h: f64) -> f64 {
        -h / 100.0
    }
    fn speed_of_sound(&self, _: f64) -> f64 {
        340.0
    }
    fn density(&self, _: f64) -> f64 {
        1.2
    }
    fn pressure(&self, _: f64) -> f64 {
        101_325.0
    }
    fn temperature(&self, _: f64) -> f64 {
        288.15
    }
    fn dynamic_viscosity(&self, _: f64) -> f64 {
        1.8e-5
    }
    fn gravity(&self, _: f64) -> f64 {
        9.8
    }
}

pub(crate) fn setup(clamp: bool) -> ControllerSetup {
    ControllerSetup {
        sampling_rate: 10.0,
        air_brakes: AirBrakesSetup {
            clamp,
            override_rocket_drag: true,
            reference_area: 0.016,
            initial_level: 0.0,
            drag_coefficient: Arc::new(|level, mach| level + 10.0 * mach),
        },
        burn_start: 0.0,
        burn_out: 3.72,
        environment: Arc::new(Air),
        initial_observed_variables: Some(vec![0.0, 0.0]),
        constants: Vec::new(),
    }
}

pub(crate) fn compile(source: &str) -> Result<ControllerScript, ScriptError> {
    ControllerScript::compile(Path::new("brakes.rhai"), source)
}

pub(crate) fn controller(source: &str, clamp: bool) -> Controller {
    let script = compile(source).unwrap_or_else(|e| panic!("{e}"));
    Controller::new(&script, setup(clamp)).expect("controller")
}

pub(crate) const STATE: [f64; 13] = [
    1.0, 2.0, 1107.0, 4.0, 5.0, 6.0, 1.0, 0.0, 0.0, 0.0, 0.1, 0.2, 0.3,
];

pub(crate) fn row(t: f64) -> [f64; 14] {
    let mut row = [0.0; 14];
    row[0] = t;
    row[1..].copy_from_slice(&STATE);
    row
}

#[test]
fn camoes_controller_replays_the_deployment() {
    let Some(folder) = karman_validation::folder() else {
        return;
    };
    let Some(camoes) = folder.flight("camoes") else {
        return;
    };
    let file = camoes.dir.join("camoes_controller.rhai");
    let source = std::fs::read_to_string(&file).expect("the camoes controller");
    let script = ControllerScript::compile(&file, &source).expect("camoes compiles");
    let mut c = Controller::new(&script, setup(true)).expect("controller");
    let poly = |t: f64| -0.002906 * t.powf(3.0) + 0.1497 * t.powf(2.0) + -2.563 * t + 14.96;
    for j in 0..200 {
        let t = f64::from(j) / 10.0;
        let level = c.call(t, &STATE, &row(t)).expect("call");
        let expected = if !(3.8..=19.6).contains(&t) {
            0.0
        } else if t <= 11.4 {
            1.0
        } else {
            poly(t).clamp(0.0, 1.0)
        };
        assert_eq!(level.to_bits(), expected.to_bits(), "t = {t}");
    }
    let record = c.record();
    assert_eq!(record.levels.len(), 200);
    assert_eq!(record.observed_variables.len(), 201);
    assert_eq!(record.observed_variables[0], serde_json::json!([0.0, 0.0]));
    assert_eq!(record.observed_variables[51], serde_json::json!([5.0, 1.0]));
}

#[test]
fn arguments_follow_the_contract() {
    let script = compile(
        r#"
        fn controller_function(time, sampling_rate, state, state_history, observed_variables,
                               air_brakes, sensors, environment) {
            let previous = if observed_variables.len() == 0 { -1.0 } else { observed_variables[-1].calls };
            return #{
                time: time,
                rate: sampling_rate,
                z_agl: state[2] - environment.elevation,
                history_rows: state_history.len(),
                history_t: state_history[-1][0],
                vy: state_history[-1][5],
                wz: state[12],
                sensors: sensors.len(),
                wind: environment.wind_velocity_x(1000.0) + environment.wind_velocity_y(500.0),
                rho: environment.density(0.0),
                g: environment.gravity(0.0),
                burn: motor::burn_out_time - motor::burn_start_time,
                cd: air_brakes.drag_coefficient(0.5, 0.1),
                area: air_brakes.reference_area,
                overrides: air_brakes.override_rocket_drag,
                clamps: air_brakes.clamp,
                calls: previous + 1.0,
            };
        }
        "#,
    )
    .expect("compiles");
    let mut s = setup(true);
    s.initial_observed_variables = None;
    let mut c = Controller::new(&script, s).expect("controller");
    c.call(0.1, &STATE, &row(0.15)).expect("first call");
    assert_eq!(c.record().observed_variables[0]["calls"], 0.0);
    c.call(0.2, &STATE, &row(0.25)).expect("second call");
    let record = c.record();
    let last = &record.observed_variables[1];
    assert_eq!(last["time"], 0.2);
    assert_eq!(last["rate"], 10.0);
    assert_eq!(last["z_agl"], 1000.0);
    assert_eq!(last["history_rows"], 1);
    assert_eq!(last["history_t"], 0.25);
    assert_eq!(last["vy"], 5.0);
    assert_eq!(last["wz"], 0.3);
    assert_eq!(last["sensors"], 0);
    assert_eq!(last["wind"], 5.0);
    assert_eq!(last["rho"], 1.2);
    assert_eq!(last["g"], 9.8);
    assert_eq!(last["burn"], 3.72);
    assert_eq!(last["cd"], 1.5);
    assert_eq!(last["area"], 0.016);
    assert_eq!(last["overrides"], true);
    assert_eq!(last["clamps"], true);
    assert_eq!(last["calls"], 1.0);
}

#[test]
fn sensors_hand_over_their_latest_reading() {
    let script = compile(
        r#"
        fn controller_function(time, sampling_rate, state, state_history, observed_variables,
                               air_brakes, sensors) {
            let baro = sensors[0];
            let imu = sensors[1];
            if baro.measurement == () {
                return #{ first: true, time: baro.time, imu: imu.measurement };
            }
            air_brakes.deployment_level = if baro.measurement < 80000.0 { 1.0 } else { 0.0 };
            return #{
                names: baro.name + "," + imu.name,
                kinds: baro.kind + "," + imu.kind,
                p: baro.measurement,
                t: baro.time,
                az: imu.measurement[2],
                n: imu.measurement.len(),
            };
        }
        "#,
    )
    .expect("compiles");
    let mut s = setup(true);
    s.initial_observed_variables = None;
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
    let mut c = Controller::new(&script, s)
        .expect("controller")
        .with_sensors(&sensors);
    assert_eq!(c.sensor_count(), 2);
    // Before any reading: `()` (RocketPy's `None`).
    c.call(0.0, &STATE, &row(0.05)).expect("first call");
    let first = &c.record().observed_variables[0];
    assert_eq!(first["first"], true);
    assert!(first["time"].is_null() && first["imu"].is_null(), "{first}");
    c.set_sensor(0, 0.09, [79_000.0, 0.0, 0.0]);
    c.set_sensor(1, 0.09, [0.5, -0.25, 9.5]);
    c.set_sensor(7, 0.09, [0.0; 3]); // past the list: ignored
    let level = c.call(0.1, &STATE, &row(0.15)).expect("second call");
    assert_eq!(level.to_bits(), 1.0f64.to_bits());
    let last = &c.record().observed_variables[1];
    assert_eq!(last["names"], "baro,imu");
    assert_eq!(last["kinds"], "barometer,accelerometer");
    assert_eq!(last["p"], 79_000.0);
    assert_eq!(last["t"], 0.09);
    assert_eq!(last["az"], 9.5);
    assert_eq!(last["n"], 3);
    // A script that writes into its copy of the array does not change the next call's.
    let vandal = compile(
        r#"
        fn controller_function(time, sampling_rate, state, state_history, observed_variables,
                               air_brakes, sensors) {
            let kind = sensors[0].kind;
            sensors[0] = 5.0;
            return kind;
        }
        "#,
    )
    .expect("compiles");
    let mut c = Controller::new(&vandal, setup(true))
        .expect("controller")
        .with_sensors(&sensors);
    c.call(0.0, &STATE, &row(0.05)).expect("first call");
    c.call(0.1, &STATE, &row(0.15)).expect("second call");
    let record = c.record();
    assert_eq!(record.observed_variables.last().unwrap(), "barometer");
}

#[test]
fn the_record_is_handed_back_and_unit_records_nothing() {
    let script = compile(
        r#"
        fn controller_function(time, sampling_rate, state, state_history, observed_variables, air_brakes) {
            if time < 0.25 { return (); }
            let n = if observed_variables.len() == 0 { 0.0 } else { observed_variables[-1].n };
            return #{ n: n + 1.0, t: time };
        }
        "#,
    )
    .expect("compiles");
    let mut s = setup(true);
    s.initial_observed_variables = None;
    let mut c = Controller::new(&script, s).expect("controller");
    for j in 0..6 {
        let t = f64::from(j) / 10.0;
        c.call(t, &STATE, &row(t)).expect("call");
    }
    let record = c.record();
    assert_eq!(record.levels.len(), 6);
    let ns: Vec<f64> = record
        .observed_variables
        .iter()
        .map(|v| v["n"].as_f64().expect("n"))
        .collect();
    assert_eq!(ns, [1.0, 2.0, 3.0]);
}

#[test]
fn levels_above_one_are_clamped_or_kept() {
    let source = r#"
        fn controller_function(time, sampling_rate, state, state_history, observed_variables, air_brakes) {
            air_brakes.deployment_level = 1.5;
            let read_back = air_brakes.deployment_level;
            air_brakes.deployment_level = read_back - 3.0;
            air_brakes.deployment_level = air_brakes.deployment_level + 2.0 + time;
            return read_back;
        }
    "#;
    let mut clamped = controller(source, true);
    // 1.5 → 1; 1 − 3 → 0; 0 + 2 + 0.1 → 1.
    assert_eq!(
        clamped
            .call(0.1, &STATE, &row(0.1))
            .expect("call")
            .to_bits(),
        1.0f64.to_bits()
    );
    assert_eq!(clamped.record().observed_variables[1], 1.0);
    let mut kept = controller(source, false);
    // 1.5; −1.5; −1.5 + 2.1.
    let level = kept.call(0.1, &STATE, &row(0.1)).expect("call");
    assert_eq!(level.to_bits(), (-1.5f64 + 2.0 + 0.1).to_bits());
    assert_eq!(kept.record().observed_variables[1], 1.5);
}

#[test]
fn the_initial_level_is_clamped_and_kept_without_writes() {
    let script = compile(
        "fn controller_function(time, sampling_rate, state, state_history, observed_variables, air_brakes) { () }",
    )
    .expect("compiles");
    let mut s = setup(true);
    s.air_brakes.initial_level = 2.0;
    let mut c = Controller::new(&script, s).expect("controller");
    assert_eq!(c.level().to_bits(), 1.0f64.to_bits());
    assert_eq!(
        c.call(0.0, &STATE, &row(0.0)).expect("call").to_bits(),
        1.0f64.to_bits()
    );
}

#[test]
fn mission_constants_replace_the_script_s() {
    let source = r#"
        const TARGET = 3000.0;
        const GAIN = 0.5;
        fn controller_function(time, sampling_rate, state, state_history, observed_variables, air_brakes) {
            air_brakes.deployment_level = global::GAIN;
            return global::TARGET;
        }
    "#;
    let script = compile(source).expect("compiles");
    assert_eq!(
        script.constants(),
        [("TARGET".to_owned(), 3000.0), ("GAIN".to_owned(), 0.5)]
    );
    let mut s = setup(true);
    s.constants = vec![("GAIN".into(), 0.25), ("TARGET".into(), 1e-7)];
    let mut c = Controller::new(&script, s).expect("controller");
    assert_eq!(
        c.call(0.0, &STATE, &row(0.0)).expect("call").to_bits(),
        0.25f64.to_bits()
    );
    assert_eq!(c.record().observed_variables[1], 1e-7);
    let mut s = setup(true);
    s.constants = vec![("OTHER".into(), 1.0)];
    let error = Controller::new(&script, s).unwrap_err();
    assert!(error.message.contains("`OTHER`"), "{error}");
}

#[test]
fn compile_errors_are_located() {
    let error = compile(
        "fn controller_function(time, sampling_rate, state, state_history, observed_variables, air_brakes) {\n    let x = ;\n}",
    )
    .unwrap_err();
    assert_eq!(error.position, Some((2, 13)), "{error}");
    assert!(
        error.to_string().starts_with("brakes.rhai:2:13: "),
        "{error}"
    );
    let undefined = compile(
        "fn controller_function(time, sampling_rate, state, state_history, observed_variables, air_brakes) {\n    air_brakes.deployment_level = levle;\n}",
    )
    .unwrap_err();
    assert_eq!(undefined.position.map(|p| p.0), Some(2), "{undefined}");
    let missing = compile("fn controller(a) { a }").unwrap_err();
    assert!(missing.message.contains("controller_function"), "{missing}");
    let wrong = compile("fn controller_function(a, b) { a }").unwrap_err();
    assert!(wrong.message.contains("6, 7 or 8"), "{wrong}");
}

#[test]
fn runtime_errors_are_located() {
    let mut c = controller(
        "fn helper(x) {\n    x + \"text\" * 2\n}\nfn controller_function(time, sampling_rate, state, state_history, observed_variables, air_brakes) {\n    air_brakes.deployment_level = helper(time);\n}",
        true,
    );
    let error = c.call(0.0, &STATE, &row(0.0)).unwrap_err();
    assert_eq!(error.position.map(|p| p.0), Some(2), "{error}");
    // An integer where the property takes a float.
    let mut c = controller(
        "fn controller_function(time, sampling_rate, state, state_history, observed_variables, air_brakes) {\n    air_brakes.deployment_level = 1;\n}",
        true,
    );
    let error = c.call(0.0, &STATE, &row(0.0)).unwrap_err();
    assert_eq!(error.position.map(|p| p.0), Some(2), "{error}");
    // The location is said once, as `file:line:column:`, not again in Rhai's words.
    let text = error.to_string();
    assert!(text.starts_with("brakes.rhai:2:"), "{text}");
    assert!(!text.contains("(line"), "{text}");
}

#[test]
fn a_runaway_script_stops_at_its_operation_limit() {
    let mut c = controller(
        "fn controller_function(time, sampling_rate, state, state_history, observed_variables, air_brakes) {\n    let x = 0.0;\n    loop {\n        x += 1.0;\n    }\n}",
        true,
    );
    let error = c.call(0.0, &STATE, &row(0.0)).unwrap_err();
    assert!(error.message.contains("operations"), "{error}");
    // Rhai does not locate a limit reached in a loop: the error points at the function.
    assert_eq!(error.position, Some((1, 1)), "{error}");
    assert!(
        error
            .to_string()
            .starts_with("brakes.rhai:1:1: in `controller_function`"),
        "{error}"
    );
    // Unbounded recursion hits the call depth.
    let mut c = controller(
        "fn down(n) { down(n + 1.0) }\nfn controller_function(time, sampling_rate, state, state_history, observed_variables, air_brakes) {\n    down(0.0)\n}",
        true,
    );
    assert!(c.call(0.0, &STATE, &row(0.0)).is_err());
    // Memory: an array that doubles every turn hits the size limit.
    let mut c = controller(
        "fn controller_function(time, sampling_rate, state, state_history, observed_variables, air_brakes) {\n    let a = [1.0];\n    loop { a += a; }\n}",
        true,
    );
    let error = c.call(0.0, &STATE, &row(0.0)).unwrap_err();
    assert!(error.message.to_lowercase().contains("size"), "{error}");
}

#[test]
fn the_sandbox_has_no_clock_modules_or_eval() {
    for body in [
        "let t = timestamp();",
        "import \"file\" as f;",
        "eval(\"1\");",
        "print(\"hello\"); let x = y;",
        "sleep(100);",
        "sleep(0.5);",
        "let f = Fn(\"sleep\"); f.call(100);",
        "let f = Fn(\"abs\"); for i in 0..100000 { f = f.curry(i); }",
        "let f = Fn(\"abs\"); let g = curry(f, 1);",
    ] {
        let source = format!(
            "fn controller_function(time, sampling_rate, state, state_history, observed_variables, air_brakes) {{\n    {body}\n}}"
        );
        let failed = match compile(&source) {
            Err(_) => true,
            Ok(script) => {
                let mut c = Controller::new(&script, setup(true)).expect("controller");
                c.call(0.0, &STATE, &row(0.0)).is_err()
            }
        };
        assert!(failed, "{body} must fail");
    }
}

#[test]
fn the_closed_loop_fixture_opens_in_proportion_to_the_overshoot() {
    let file =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../mission/tests/fixtures/closed_loop.rhai");
    let source = std::fs::read_to_string(&file).expect("fixture");
    let script = ControllerScript::compile(&file, &source).expect("compiles");
    let mut s = setup(true);
    s.constants = vec![("TARGET".into(), 2500.0)];
    let mut c = Controller::new(&script, s).expect("controller");
    // Before burn-out: nothing recorded, brakes shut.
    assert_eq!(
        c.call(1.0, &STATE, &row(1.0)).expect("call").to_bits(),
        0.0f64.to_bits()
    );
    let mut climbing = STATE;
    climbing[2] = 2500.0;
    climbing[5] = 150.0;
    let level = c.call(5.0, &climbing, &row(5.0)).expect("call");
    assert!(level > 0.0 && level <= 1.0, "{level} {:?}", c.record());
    let record = c.record();
    assert_eq!(record.observed_variables.len(), 2);
    let predicted = record.observed_variables[1]["predicted"]
        .as_f64()
        .expect("predicted");
    assert!(predicted > 2500.0 - 107.0, "{predicted}");
}
