//! `--set PATH=VALUE` overrides applied before validation.

use crate::common::fixture;
use karman_mission::schema::{AtmosphereModel, Trigger};
use karman_mission::{MissionError, Override, load};

fn set(items: &[&str]) -> Vec<Override> {
    items
        .iter()
        .map(|o| o.parse().expect("well-formed override"))
        .collect()
}

#[test]
fn overrides_replace_values() {
    let overrides = set(&[
        "flight.inclination=84",
        "rocket.parachutes.main.noise=[0, 8.3, 0.5]",
        "rocket.parachutes.main.trigger=\"apogee\"",
        "environment.atmosphere.model=\"Standard\"",
        "rocket.power_off_drag=[[0, 0.5], [1, 0.6]]",
    ]);
    let mission = load(&fixture("minimal.toml"), &overrides).unwrap_or_else(|e| panic!("{e}"));
    let spec = &mission.spec;
    assert!(
        (spec.flight.inclination_deg - 84.0).abs() < 1e-12,
        "exact TOML integer"
    );
    let main = &spec.rocket.parachutes["main"];
    let expected = [0.0, 8.3, 0.5];
    // The same decimal text parses to the same f64 on both sides.
    assert!(
        main.noise
            .iter()
            .zip(expected)
            .all(|(a, b)| (a - b).abs() < 1e-15)
    );
    assert_eq!(main.trigger, Trigger::Apogee);
    assert_eq!(spec.environment.atmosphere.model, AtmosphereModel::Standard);
}

#[test]
fn overrides_may_set_optional_keys_the_file_omits() {
    let overrides = set(&["flight.max_time=100", "environment.gravity=9.81"]);
    let mission = load(&fixture("minimal.toml"), &overrides).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        (mission.spec.flight.max_time - 100.0).abs() < 1e-12,
        "exact TOML integer"
    );
    assert_eq!(mission.spec.environment.gravity, Some(9.81));
}

#[test]
fn later_overrides_win() {
    let overrides = set(&["flight.heading=10", "flight.heading=20"]);
    let mission = load(&fixture("minimal.toml"), &overrides).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        (mission.spec.flight.heading_deg - 20.0).abs() < 1e-12,
        "exact TOML integer"
    );
}

#[test]
fn override_that_names_nothing_is_an_error() {
    for bad in [
        "flight.spin=3",
        "rocket.parachutes.drogue.lag=1",
        "nothing=1",
    ] {
        match load(&fixture("minimal.toml"), &set(&[bad])) {
            Err(MissionError::Invalid { problems, .. }) => {
                assert_eq!(problems.len(), 1, "{bad}");
                let text = problems[0]
                    .display(std::path::Path::new("m.toml"))
                    .to_string();
                assert!(text.starts_with(&format!("--set {bad}: ")), "{text}");
            }
            other => panic!("{bad}: expected an invalid mission, got {other:?}"),
        }
    }
}

#[test]
fn overrides_reach_array_entries_and_dispersion_entries() {
    use karman_mission::schema::Distribution;
    let mut text = std::fs::read_to_string(fixture("minimal.toml")).expect("fixture");
    text.push_str(
        "\n[dispersion]\nsamples = 10\nseed = 1\n\n[dispersion.vary]\n\
         \"rocket.mass\" = { std = 0.1 }\n\
         \"rocket.power_off_drag\" = { factor = { normal = [1, 0.05] } }\n",
    );
    let overrides = set(&[
        "rocket.inertia.0=0.6",
        "motor.dry_inertia.2=0.002",
        "dispersion.vary.\"rocket.mass\".std=0.5",
        "dispersion.vary.\"rocket.power_off_drag\".factor.normal=[1, 0.1]",
        "dispersion.vary.'rocket.inertia'={ factor = { std = 0.02 } }",
        "dispersion.vary.\"rocket.inertia.2\"={ std = 0.0001 }",
    ]);
    let mission = karman_mission::parse(&text, &fixture("minimal.toml"), &overrides)
        .unwrap_or_else(|e| panic!("{e}"));
    let spec = &mission.spec;
    let bits = |v: [f64; 6]| v.map(f64::to_bits);
    assert_eq!(
        bits(spec.rocket.inertia.0),
        bits([0.6, 0.5, 0.002, 0.0, 0.0, 0.0])
    );
    assert_eq!(spec.motor.dry_inertia.0[2].to_bits(), 0.002f64.to_bits());
    let vary = &spec.dispersion.as_ref().expect("dispersion").vary;
    assert_eq!(vary["rocket.mass"], Distribution::Std(0.5));
    assert_eq!(
        vary["rocket.power_off_drag"],
        Distribution::Factor(Box::new(Distribution::Normal([1.0, 0.1])))
    );
    assert_eq!(
        vary["rocket.inertia"],
        Distribution::Factor(Box::new(Distribution::Std(0.02)))
    );
    assert_eq!(vary["rocket.inertia.2"], Distribution::Std(0.0001));
    // Beyond the array as the file writes it, or an entry that is not there: named errors.
    for (bad, reason) in [
        ("rocket.inertia.3=1", "`rocket.inertia` holds 3 entries"),
        (
            "dispersion.vary.\"rocket.radius\".std=1",
            "the mission has no `dispersion.vary.rocket.radius`",
        ),
    ] {
        match karman_mission::parse(&text, &fixture("minimal.toml"), &set(&[bad])) {
            Err(MissionError::Invalid { problems, .. }) => {
                let text = problems[0]
                    .display(std::path::Path::new("m.toml"))
                    .to_string();
                assert!(text.contains(reason), "{text}");
            }
            other => panic!("{bad}: expected an invalid mission, got {other:?}"),
        }
    }
}
