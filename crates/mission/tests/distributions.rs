//! The named distributions of `[dispersion.vary]` (NumPy's parameter names) and truncation:
//! read from a mission, drawn by a study, and every bad parameter a located problem naming
//! the key and the value.

use crate::common::fixture;
use karman_mission::montecarlo::{MonteCarlo, StudyOverrides};
use karman_mission::{MissionError, parse};

fn mission_with(vary: &str) -> Result<karman_mission::Mission, MissionError> {
    let mut text = std::fs::read_to_string(fixture("minimal.toml")).expect("fixture readable");
    text.push_str("\n[dispersion]\nsamples = 10\nseed = 1\n\n[dispersion.vary]\n");
    text.push_str(vary);
    parse(&text, &fixture("vary.toml"), &[])
}

#[test]
fn named_and_truncated_distributions_are_drawn() {
    let mission = mission_with(
        "\"rocket.mass\" = { truncated = { distribution = { gamma = { shape = 400, scale = 0.01 } }, low = 3.8, high = 4.2 } }\n\
         \"flight.inclination\" = { logistic = [85, 0.5] }\n\
         \"flight.heading\" = { laplace = { loc = 30, scale = 2 } }\n\
         \"rocket.parachutes.main.cd_s\" = { factor = { wald = { mean = 1, scale = 400 } } }\n\
         \"rocket.parachutes.main.lag\" = { exponential = { scale = 0.5 } }\n\
         \"environment.wind_factor\" = { gumbel = [1, 0.1] }\n\
         \"motor.grain_number\" = { truncated = { distribution = { poisson = { lam = 5 } }, low = 4, high = 6 } }\n\
         \"rocket.surfaces.fins.n\" = { binomial = { n = 4, p = 1 } }\n\
         \"flight.rail_length\" = { chisquare = { df = 3 } }\n",
    )
    .unwrap_or_else(|e| panic!("{e:#}"));
    let mc =
        MonteCarlo::new(&mission, StudyOverrides::default()).unwrap_or_else(|e| panic!("{e:#}"));
    let study = mc.study();
    assert_eq!(study.inputs.len(), 9);
    for index in 0..200 {
        let values = karman_mission::dispersion::sampling::draw(study.seed, index, &study.inputs);
        assert!((3.8..=4.2).contains(&values[0]), "{values:?}");
        assert!(
            [4.0f64, 5.0, 6.0]
                .iter()
                .any(|v| v.to_bits() == values[6].to_bits()),
            "{values:?}"
        );
        assert_eq!(values[7].to_bits(), 4f64.to_bits());
        assert!(values[8] > 0.0 && values[4] >= 0.0, "{values:?}");
    }
}

/// The problems of a mission whose `[dispersion.vary]` is `vary`, as `key: message` lines.
fn problems(vary: &str) -> Vec<String> {
    match mission_with(vary) {
        Err(MissionError::Invalid { problems, .. }) => problems
            .iter()
            .map(|p| format!("{}: {}", p.key, p.kind))
            .collect(),
        Err(other) => vec![format!("{other:#}")],
        Ok(_) => Vec::new(),
    }
}

#[test]
fn bad_parameters_are_located_problems_naming_key_and_value() {
    let cases = [
        ("{ gamma = { shape = -2, scale = 1 } }", "shape = -2"),
        ("{ gamma = { shape = 2, k = 1 } }", "no parameter `k` (= 1)"),
        ("{ gamma = { shape = 2 } }", "needs `scale`"),
        (
            "{ exponential = [1, 2] }",
            "exponential takes 1 parameter [scale], got 2",
        ),
        ("{ wald = { mean = 1, scale = 0 } }", "scale = 0"),
        ("{ poisson = { lam = -1 } }", "lam = -1"),
        ("{ binomial = { n = 2.5, p = 0.5 } }", "n = 2.5"),
        ("{ binomial = { n = 4, p = 2 } }", "p = 2"),
        ("{ chisquare = { df = 0 } }", "df = 0"),
        ("{ laplace = { loc = 0, scale = -1 } }", "scale = -1"),
        (
            "{ truncated = { distribution = { normal = [4, 0.1] }, low = 5, high = 4.5 } }",
            "low = 5, high = 4.5",
        ),
        (
            "{ truncated = { distribution = { normal = [4, 0.1] }, low = 9 } }",
            "keep 0 of 20000 draws",
        ),
        (
            "{ truncated = { distribution = { std = 0.1 }, low = 3 } }",
            "not `std`",
        ),
        (
            "{ factor = { logistic = { loc = 1, scale = -0.1 } } }",
            "scale = -0.1",
        ),
    ];
    for (entry, expected) in cases {
        let found = problems(&format!("\"rocket.mass\" = {entry}\n"));
        assert!(
            found.len() == 1
                && found[0].starts_with("dispersion.vary.rocket.mass")
                && found[0].contains(expected),
            "{entry}: {found:?}"
        );
    }
    // A bound that is not a number and an unknown key of the truncation are refused by name.
    for entry in [
        "{ truncated = { distribution = { normal = [4, 0.1] }, lo = 3 } }",
        "{ truncated = { distribution = { normal = [4, 0.1] }, low = \"3\" } }",
    ] {
        let found = problems(&format!("\"rocket.mass\" = {entry}\n"));
        assert!(!found.is_empty(), "{entry} accepted");
        assert!(
            found.iter().any(|p| p.contains("rocket.mass")),
            "{entry}: {found:?}"
        );
    }
    // A continuous distribution does not fit an integer input; a Poisson does.
    let found = problems("\"motor.grain_number\" = { gamma = [2, 1] }\n");
    assert!(
        found.len() == 1 && found[0].contains("integer"),
        "{found:?}"
    );
    assert!(problems("\"motor.grain_number\" = { poisson = [5] }\n").is_empty());
}
