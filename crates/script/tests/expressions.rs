//! Trigger expressions: arbitrary text never panics; accepted expressions evaluate.

use karman_script::{Expression, SensorShape, TriggerInputs};
use proptest::prelude::*;

proptest! {
    #[test]
    fn arbitrary_text_never_panics(text in ".{0,64}") {
        if let Ok(expression) = Expression::parse(&text) {
            let _ = expression.evaluate(&TriggerInputs { pressure: 1.0, height: 2.0, state: [0.5; 13] });
        }
    }

    #[test]
    fn token_soup_never_panics(tokens in proptest::collection::vec(
        prop::sample::select(vec!["vz", "z", "p", "h", "1.0", "2.5e2", "(", ")", "<", "<=", "==",
            "!=", "&&", "||", "!", "-", "+", "*", "/", "abs", "min", ",", "true", "5", ".5"]), 0..16)) {
        let text = tokens.join(" ");
        if let Ok(expression) = Expression::parse(&text) {
            let _ = expression.evaluate(&TriggerInputs { pressure: 1.0, height: 2.0, state: [0.5; 13] });
        }
    }
}

const SENSORS: [SensorShape<'static>; 2] = [
    SensorShape {
        name: "baro",
        kind: "barometer",
        components: 1,
    },
    SensorShape {
        name: "imu",
        kind: "accelerometer",
        components: 3,
    },
];

proptest! {
    #[test]
    fn sensor_token_soup_never_panics(tokens in proptest::collection::vec(
        prop::sample::select(vec!["sensors", "[", "]", ".", "0", "1", "2", "3", "baro", "imu",
            "measurement", "<", "1.0", "&&", "(", ")", "-", "vz", "99999999999999999999"]), 0..16),
        values in proptest::collection::vec(-1e6f64..1e6, 0..5)) {
        let text = tokens.join("");
        if let Ok(expression) = Expression::parse_with(&text, &SENSORS) {
            prop_assert!(expression.reads().iter().all(|&(s, c)| s < 2 && c < SENSORS[s].components));
            let inputs = TriggerInputs { pressure: 1.0, height: 2.0, state: [0.5; 13] };
            let _ = expression.evaluate_with(&inputs, &values);
        }
    }
}

#[test]
fn every_state_name_reads_its_component() {
    for (index, name) in karman_script::expression::STATE_NAMES.iter().enumerate() {
        let expression = Expression::parse(&format!("{name} == 7.0")).expect("valid");
        let mut state = [0.0; 13];
        state[index] = 7.0;
        let inputs = TriggerInputs {
            pressure: 0.0,
            height: 0.0,
            state,
        };
        assert!(expression.evaluate(&inputs), "{name}");
    }
}

proptest! {
    #[test]
    fn arbitrary_scripts_never_panic_the_compiler(text in "(fn|let|const|\\{|\\}|\\(|\\)|;|=|x|1\\.0|\\[|\\]|#|\"|loop|while|import|controller_function|,| |\n|\\.|::){0,40}") {
        let _ = karman_script::ControllerScript::compile(std::path::Path::new("p.rhai"), &text);
    }
}
