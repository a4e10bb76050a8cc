//! The compiled calls against Rhai's interpreter: every controller of the repository and
//! random expressions of the compiled subset give the same levels, records and errors.

use karman_script::{
    AirBrakesSetup, Controller, ControllerScript, ControllerSetup, EnvironmentQuery, ScriptError,
};
use proptest::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// An environment whose queries vary with height.
struct Layered;

impl EnvironmentQuery for Layered {
    fn elevation(&self) -> f64 {
        1400.0
    }
    fn wind_velocity_x(&self, h: f64) -> f64 {
        3.0 + h / 1000.0
    }
    fn wind_velocity_y(&self, h: f64) -> f64 {
        -1.0 - h / 2000.0
    }
    fn speed_of_sound(&self, h: f64) -> f64 {
        340.0 - 0.004 * h
    }
    fn density(&self, h: f64) -> f64 {
        1.225 * (-h / 8500.0).exp()
    }
    fn pressure(&self, h: f64) -> f64 {
        101_325.0 * (-h / 8000.0).exp()
    }
    fn temperature(&self, h: f64) -> f64 {
        288.15 - 0.0065 * h
    }
    fn dynamic_viscosity(&self, h: f64) -> f64 {
        1.8e-5 - 1e-10 * h
    }
    fn gravity(&self, h: f64) -> f64 {
        9.80665 - 3e-6 * h
    }
}

fn setup(clamp: bool) -> ControllerSetup {
    ControllerSetup {
        sampling_rate: 20.0,
        air_brakes: AirBrakesSetup {
            clamp,
            override_rocket_drag: false,
            reference_area: 0.0127,
            initial_level: 0.0,
            drag_coefficient: Arc::new(|level, mach| 0.3 + 0.9 * level * (1.0 + 0.2 * mach)),
        },
        burn_start: 0.0,
        burn_out: 3.9,
        environment: Arc::new(Layered),
        initial_observed_variables: Some(vec![0.0, 0.0, 0.0]),
        constants: Vec::new(),
    }
}

/// The state of a climb and descent at `t`: up to apogee at 25 s, then down.
fn state(t: f64) -> [f64; 13] {
    let vz = 250.0 - 10.0 * t;
    let z = 1400.0 + 250.0 * t - 5.0 * t * t;
    [
        0.5 * t,
        20.0 * t,
        z,
        0.5,
        20.0 - 0.3 * t,
        vz,
        0.99,
        0.01,
        -0.02,
        0.1,
        0.01 * t,
        -0.02,
        0.3,
    ]
}

/// Flies `script` through `calls` instants with both paths and compares every result;
/// returns the calls made compiled.
fn same_both_ways(script: &ControllerScript, clamp: bool, calls: usize) -> usize {
    let mut fast = Controller::new(script, setup(clamp)).expect("controller");
    let mut slow = Controller::new(&script.interpreted(), setup(clamp)).expect("controller");
    for j in 0..calls {
        let t = j as f64 / 20.0;
        let mut row = [0.0; 14];
        row[0] = t + 0.03;
        row[1..].copy_from_slice(&state(t + 0.03));
        let a = fast.call(t, &state(t), &row);
        let b = slow.call(t, &state(t), &row);
        match (&a, &b) {
            (Ok(x), Ok(y)) => assert_eq!(x.to_bits(), y.to_bits(), "t = {t}"),
            (Err(x), Err(y)) => assert_eq!(x, y),
            _ => panic!("t = {t}: {a:?} against {b:?}"),
        }
        if b.is_err() {
            break;
        }
    }
    // Bit for bit: NaN levels compare by their bits, the returned values through their JSON
    // (a NaN in a record is `null` in both).
    let (a, b) = (fast.record(), slow.record());
    let bits = |r: &karman_script::ControllerRecord| -> Vec<(u64, u64)> {
        r.levels
            .iter()
            .map(|l| (l.time.to_bits(), l.level.to_bits()))
            .collect()
    };
    assert!(bits(&a) == bits(&b), "levels differ");
    assert!(
        a.observed_variables == b.observed_variables,
        "records differ"
    );
    assert_eq!(slow.compiled_calls(), 0);
    fast.compiled_calls()
}

fn repository() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Every controller script of the repository, with whether it must run compiled.
const SCRIPTS: &[(&str, bool)] = &[
    ("fixtures/airbrakes/apogee_controller.rhai", true),
    ("fixtures/airbrakes/docs_controller.rhai", true),
    ("fixtures/validation/camoes/camoes_controller.rhai", true),
    ("crates/mission/tests/fixtures/brakes.rhai", false),
    ("crates/mission/tests/fixtures/closed_loop.rhai", false),
    ("crates/mission/tests/fixtures/overdrive.rhai", false),
    ("crates/mission/tests/fixtures/runaway.rhai", false),
    ("crates/mission/tests/fixtures/shut.rhai", false),
];

#[test]
fn every_controller_of_the_repository_runs_the_same_both_ways() {
    for &(file, compiled) in SCRIPTS {
        let path = repository().join(file);
        let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{file}: {e}"));
        let script = ControllerScript::compile(&path, &text).unwrap_or_else(|e| panic!("{e}"));
        let reason = script.interpreted_because();
        if compiled {
            assert_eq!(reason, None, "{file}");
        }
        let expected = |calls: usize| if reason.is_none() { calls } else { 0 };
        println!("{file}: {}", reason.unwrap_or("compiled"));
        for clamp in [true, false] {
            let fast = same_both_ways(&script, clamp, 800);
            // The repository's compiled controllers never need the interpreter.
            assert_eq!(fast, expected(800), "{file}");
        }
    }
}

const HEADER: &str = "const K = 2.5;\nconst N = 3;\n\
    fn controller_function(time, sampling_rate, state, state_history, observed_variables, \
    air_brakes, sensors, environment) {\n";

fn script(body: &str) -> Result<ControllerScript, ScriptError> {
    ControllerScript::compile(Path::new("random.rhai"), &format!("{HEADER}{body}\n}}\n"))
}

#[test]
fn the_subset_compiles_and_the_rest_is_interpreted() {
    for body in [
        "let a = state_history[-1][5]; let b = state[-13]; a + b",
        "air_brakes.deployment_level += 0.25 * time; air_brakes.deployment_level",
        "if state[5] > 0.0 && !(time < 1.0) { return [time, global::K]; } ()",
        "let x = if time > 2.0 { 1.0 } else { -1 }; x *= 2.0; [x, motor::burn_out_time]",
        "{ let y = sqrt(abs(state[3])); return y ** 1.5 % 0.7; }",
        "air_brakes.drag_coefficient(0.5, environment.speed_of_sound(state[2]) / 340.0)",
    ] {
        let compiled = script(body).unwrap_or_else(|e| panic!("{body}: {e}"));
        assert_eq!(compiled.interpreted_because(), None, "{body}");
        assert!(same_both_ways(&compiled, true, 200) > 0, "{body}");
    }
    for body in [
        "let s = 0.0; for i in 0..3 { s += state[i]; } s",
        "observed_variables[-1]",
        "#{ a: 1.0 }",
        "let i = 2; state[i]",
        "\"text\"",
    ] {
        let interpreted = script(body).unwrap_or_else(|e| panic!("{body}: {e}"));
        assert!(interpreted.interpreted_because().is_some(), "{body}");
        assert_eq!(same_both_ways(&interpreted, true, 50), 0, "{body}");
    }
}

/// A random expression of the subset (and some that leave it at run time: integer
/// arithmetic, type mismatches), as Rhai source.
fn expression() -> impl Strategy<Value = String> {
    let leaf = prop_oneof![
        (-3i64..4).prop_map(|i| i.to_string()),
        prop_oneof![
            Just(0.0f64),
            Just(-0.0),
            Just(1e-300),
            -5.0f64..5.0,
            1e3f64..1e6
        ]
        .prop_map(|x| format!("{x:?}")),
        (0usize..13).prop_map(|i| format!("state[{i}]")),
        (-14i64..0).prop_map(|i| format!("state_history[-1][{}]", i)),
        Just("time".to_owned()),
        Just("sampling_rate".to_owned()),
        Just("true".to_owned()),
        Just("false".to_owned()),
        Just("global::K".to_owned()),
        Just("global::N".to_owned()),
        Just("motor::burn_out_time".to_owned()),
        Just("air_brakes.deployment_level".to_owned()),
        Just("air_brakes.reference_area".to_owned()),
        Just("air_brakes.clamp".to_owned()),
        Just("environment.elevation".to_owned()),
    ];
    leaf.prop_recursive(4, 24, 3, |inner| {
        let op = prop_oneof![
            Just("+"),
            Just("-"),
            Just("*"),
            Just("/"),
            Just("%"),
            Just("**"),
            Just("<"),
            Just("<="),
            Just(">"),
            Just(">="),
            Just("=="),
            Just("!="),
            Just("&&"),
            Just("||"),
        ];
        let function = prop_oneof![
            Just("sqrt"),
            Just("exp"),
            Just("ln"),
            Just("log"),
            Just("sin"),
            Just("cos"),
            Just("tan"),
            Just("abs"),
        ];
        let query = prop_oneof![
            Just("density"),
            Just("gravity"),
            Just("speed_of_sound"),
            Just("wind_velocity_x"),
            Just("pressure"),
        ];
        prop_oneof![
            (inner.clone(), op, inner.clone()).prop_map(|(a, op, b)| format!("({a} {op} {b})")),
            inner.clone().prop_map(|a| format!("-({a})")),
            inner.clone().prop_map(|a| format!("!({a})")),
            (function, inner.clone()).prop_map(|(f, a)| format!("{f}({a})")),
            (query, inner.clone()).prop_map(|(q, a)| format!("environment.{q}({a})")),
            (inner.clone(), inner.clone(), inner.clone())
                .prop_map(|(c, a, b)| format!("if {c} {{ {a} }} else {{ {b} }}")),
            (inner.clone(), inner.clone())
                .prop_map(|(a, b)| format!("air_brakes.drag_coefficient({a}, {b})")),
            (inner.clone(), inner).prop_map(|(a, b)| format!("[{a}, {b}]")),
        ]
    })
}

/// A random float-valued expression of the subset.
fn float_expression() -> impl Strategy<Value = String> {
    let leaf = prop_oneof![
        prop_oneof![
            Just(0.0f64),
            Just(-0.0),
            Just(1e-300),
            -5.0f64..5.0,
            1e3f64..1e6
        ]
        .prop_map(|x| format!("{x:?}")),
        (0usize..13).prop_map(|i| format!("state[{i}]")),
        (-14i64..0).prop_map(|i| format!("state_history[-1][{i}]")),
        Just("time".to_owned()),
        Just("sampling_rate".to_owned()),
        Just("global::K".to_owned()),
        Just("motor::burn_out_time".to_owned()),
        Just("air_brakes.deployment_level".to_owned()),
        Just("air_brakes.reference_area".to_owned()),
        Just("environment.elevation".to_owned()),
    ];
    leaf.prop_recursive(4, 24, 3, |inner| {
        let op = prop_oneof![
            Just("+"),
            Just("-"),
            Just("*"),
            Just("/"),
            Just("%"),
            Just("**")
        ];
        let function = prop_oneof![
            Just("sqrt"),
            Just("exp"),
            Just("ln"),
            Just("log"),
            Just("sin"),
            Just("cos"),
            Just("tan"),
            Just("abs"),
        ];
        prop_oneof![
            (inner.clone(), op, inner.clone()).prop_map(|(a, op, b)| format!("({a} {op} {b})")),
            inner.clone().prop_map(|a| format!("-({a})")),
            (function, inner.clone()).prop_map(|(f, a)| format!("{f}({a})")),
            inner
                .clone()
                .prop_map(|a| format!("environment.density({a})")),
            (inner.clone(), inner.clone(), inner.clone())
                .prop_map(|(c, a, b)| format!("if {c} > {a} {{ {a} }} else {{ {b} }}")),
            (inner.clone(), inner)
                .prop_map(|(a, b)| format!("air_brakes.drag_coefficient({a}, {b})")),
        ]
    })
}

/// A random boolean expression of the subset.
fn bool_expression() -> impl Strategy<Value = String> {
    let comparison = prop_oneof![
        Just("<"),
        Just("<="),
        Just(">"),
        Just(">="),
        Just("=="),
        Just("!=")
    ];
    let leaf = prop_oneof![
        (float_expression(), comparison, float_expression())
            .prop_map(|(a, op, b)| format!("({a} {op} {b})")),
        Just("true".to_owned()),
        Just("air_brakes.clamp".to_owned()),
    ];
    leaf.prop_recursive(3, 12, 2, |inner| {
        prop_oneof![
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("({a} && {b})")),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("({a} || {b})")),
            inner.prop_map(|a| format!("!({a})")),
        ]
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// Any mix of the subset's values (integers, booleans, arrays, which Rhai may reject at
    /// run time): levels, records and errors agree whether a call runs compiled or
    /// interpreted.
    #[test]
    fn random_expressions_agree_with_the_interpreter(
        value in expression(),
        level in expression(),
        condition in expression(),
    ) {
        let body = format!(
            "let v = {value};\n\
             if {condition} {{ air_brakes.deployment_level = {level}; }}\n\
             let w = v;\n\
             return [w, air_brakes.deployment_level];"
        );
        // Rhai rejects some combinations when it parses them (an array as a condition).
        let compiled = script(&body);
        prop_assume!(compiled.is_ok());
        let compiled = compiled.expect("compiles");
        prop_assert_eq!(compiled.interpreted_because(), None, "{}", body);
        for clamp in [true, false] {
            same_both_ways(&compiled, clamp, 12);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// Float and boolean expressions of the subset: every call runs compiled and agrees with
    /// the interpreter bit for bit.
    #[test]
    fn typed_expressions_run_compiled_and_agree(
        value in float_expression(),
        level in float_expression(),
        condition in bool_expression(),
    ) {
        let body = format!(
            "let v = {value};\n\
             if {condition} {{ air_brakes.deployment_level = {level}; }} else {{ v -= 1.5; }}\n\
             [v, air_brakes.deployment_level, {condition}]"
        );
        let compiled = script(&body).unwrap_or_else(|e| panic!("{body}: {e}"));
        prop_assert_eq!(compiled.interpreted_because(), None, "{}", body);
        for clamp in [true, false] {
            prop_assert_eq!(same_both_ways(&compiled, clamp, 12), 12, "{}", body);
        }
    }
}
