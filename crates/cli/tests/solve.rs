//! `karman solve`: a target apogee by the mass on Calisto, and the errors of a target out of
//! reach, reversed bounds, an unknown output and an input that is not a real number.

use crate::common::{failure, karman};
use std::path::PathBuf;

fn calisto() -> Option<String> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/validation/calisto/mission.toml");
    if path.is_file() {
        Some(path.to_str().expect("utf-8").to_owned())
    } else {
        assert!(
            std::env::var_os("CI").is_none(),
            "{} is missing",
            path.display()
        );
        println!("skipped: {} not found", path.display());
        None
    }
}

#[test]
fn validate_solve_hits_a_target_apogee_by_the_mass_within_twelve_flights() {
    let Some(mission) = calisto() else { return };
    let output = karman(&[
        "solve",
        &mission,
        "--target",
        "apogee_agl_m=3048",
        "--vary",
        "rocket.mass",
        "--json",
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).expect("JSON");
    let flights = json["flights"].as_u64().expect("flights");
    let value = json["value"].as_f64().expect("value");
    let achieved = json["achieved"].as_f64().expect("achieved");
    assert!(flights <= 12, "{flights} flights");
    assert!((achieved - 3048.0).abs() < 0.1, "{achieved}");
    assert_eq!(
        json["trials"].as_array().expect("trials").len() as u64,
        flights
    );
    // The value flies the apogee reported: `simulate --set` of it, to the last digit.
    let set = format!("rocket.mass={value}");
    let flown = karman(&["simulate", &mission, "--set", &set, "--json"]);
    assert!(flown.status.success());
    let summary: serde_json::Value = serde_json::from_slice(&flown.stdout).expect("JSON");
    let apogee = summary["apogee_agl_m"].as_f64().expect("apogee");
    assert_eq!(
        apogee.to_bits(),
        achieved.to_bits(),
        "{apogee} vs {achieved}"
    );
    // A heavier rocket for a lower apogee: the mass grows past the nominal.
    assert!(value > json["nominal"].as_f64().expect("nominal"));
}

#[test]
fn solve_says_clearly_what_cannot_be_solved() {
    let Some(mission) = calisto() else { return };
    let run = |extra: &[&str]| {
        let mut args = vec!["solve", mission.as_str()];
        args.extend_from_slice(extra);
        failure(&args)
    };
    let text = run(&["--target", "apogee_agl_m=9000", "--vary", "rocket.mass"]);
    assert!(
        text.contains("no value of rocket.mass within [7.213, 21.639] reaches apogee_agl_m = 9000"),
        "{text}"
    );
    let text = run(&[
        "--target",
        "apogee_agl_m=3048",
        "--vary",
        "rocket.mass",
        "--bounds",
        "20,10",
    ]);
    assert!(text.contains("LO < HI, got 20,10"), "{text}");
    let text = run(&[
        "--target",
        "apogee_agl_m=3048",
        "--vary",
        "rocket.mass",
        "--bounds",
        "x,10",
    ]);
    assert!(text.contains("expected two numbers LO,HI"), "{text}");
    let text = run(&["--target", "apogee_ft=3048", "--vary", "rocket.mass"]);
    assert!(
        text.contains("`apogee_ft` is not a summary output"),
        "{text}"
    );
    let text = run(&["--target", "apogee_agl_m", "--vary", "rocket.mass"]);
    assert!(text.contains("expected OUTPUT=VALUE"), "{text}");
    let text = run(&[
        "--target",
        "apogee_agl_m=3048",
        "--vary",
        "rocket.surfaces.fins.n",
    ]);
    assert!(
        text.contains("an integer") && text.contains("rocket.surfaces.fins.n"),
        "{text}"
    );
    let text = run(&[
        "--target",
        "apogee_agl_m=3048",
        "--vary",
        "rocket.power_off_drag",
    ]);
    assert!(text.contains("a curve"), "{text}");
    let text = run(&["--target", "apogee_agl_m=3048", "--vary", "rocket.mas"]);
    assert!(text.contains("rocket.mas"), "{text}");
    // Two flights cannot converge to a millimetre: the budget is reported with the best value.
    let text = run(&[
        "--target",
        "apogee_agl_m=3048",
        "--vary",
        "rocket.mass",
        "--max-flights",
        "3",
    ]);
    assert!(
        text.contains("after 3 flights") && text.contains("raise --max-flights"),
        "{text}"
    );
}
