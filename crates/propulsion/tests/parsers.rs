//! Property tests: the thrust-file readers never panic, whatever the input, and what they
//! accept is a valid curve (finite values, times that never decrease).

use karman_propulsion::{ThrustData, csv, eng, rse};
use proptest::prelude::*;

fn check(result: Result<ThrustData, karman_propulsion::PropulsionError>) {
    if let Ok(d) = result {
        assert_eq!(d.times.len(), d.thrusts.len());
        assert!(d.times.len() >= 2);
        assert!(d.times.windows(2).all(|w| w[0] <= w[1]));
        assert!(d.times.iter().chain(&d.thrusts).all(|v| v.is_finite()));
    }
}

/// Text built from the tokens these formats use, so the generator reaches deep paths.
fn tokens() -> impl Strategy<Value = String> {
    let token = prop_oneof![
        Just("<".to_owned()),
        Just(">".to_owned()),
        Just("/>".to_owned()),
        Just("</engine>".to_owned()),
        Just("<engine ".to_owned()),
        Just("<eng-data ".to_owned()),
        Just("t=\"".to_owned()),
        Just("f='".to_owned()),
        Just("\"".to_owned()),
        Just("<!--".to_owned()),
        Just("-->".to_owned()),
        Just(";".to_owned()),
        Just(",".to_owned()),
        Just(" ".to_owned()),
        Just("\n".to_owned()),
        Just("M1 75 757 0 3 5 CTI\n".to_owned()),
        "-?[0-9]{0,3}(\\.[0-9]{0,3})?(e-?[0-9])?",
        "\\PC{0,4}",
    ];
    proptest::collection::vec(token, 0..40).prop_map(|v| v.concat())
}

proptest! {
    #[test]
    fn eng_never_panics(text in "\\PC{0,200}", structured in tokens()) {
        check(eng::parse(&text, "fuzz.eng"));
        check(eng::parse(&structured, "fuzz.eng"));
    }

    #[test]
    fn rse_never_panics(text in "\\PC{0,200}", structured in tokens()) {
        check(rse::parse(&text, "fuzz.rse"));
        check(rse::parse(&structured, "fuzz.rse"));
    }

    #[test]
    fn csv_never_panics(text in "\\PC{0,200}", structured in tokens()) {
        check(csv::parse(&text, "fuzz.csv"));
        check(csv::parse(&structured, "fuzz.csv"));
    }

    #[test]
    fn inline_points_never_panic(points in proptest::collection::vec(
        [prop_oneof![any::<f64>(), -10.0..10.0f64], prop_oneof![any::<f64>(), -10.0..10.0f64]], 0..20)) {
        check(ThrustData::from_points("inline", &points));
    }
}
