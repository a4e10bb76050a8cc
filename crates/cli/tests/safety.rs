//! `karman safety`: the figures of Calisto's flight against the flight itself (the landing
//! energy is ½ m v² of the simulated impact), verdicts and exit code, and bad arguments.

use crate::common::{failure, karman};
use std::path::{Path, PathBuf};

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
fn validate_safety_figures_are_the_flights_own() {
    let Some(mission) = calisto() else { return };
    // Generous thresholds: everything passes and the exit code is 0.
    let output = karman(&[
        "safety",
        &mission,
        "--json",
        "--shear-modulus",
        "2.6e10",
        "--fin-thickness",
        "0.004",
        "--min-rail-speed",
        "20",
        "--max-landing-energy",
        "1000",
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).expect("JSON");
    let checks = json["checks"].as_array().expect("checks");
    let figure = |name: &str| {
        checks
            .iter()
            .find(|c| c["name"] == name)
            .unwrap_or_else(|| panic!("{name} missing"))
            .clone()
    };
    // The flight itself: its summary and its last stored point.
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("karman-cli/safety-calisto");
    let _ = std::fs::remove_dir_all(&dir);
    let run = karman(&["simulate", &mission, "--out", dir.to_str().expect("utf-8")]);
    assert!(run.status.success());
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).expect("summary"))
            .expect("JSON");
    let summary = if summary["summary"].is_object() {
        &summary["summary"]
    } else {
        &summary
    };
    let trajectory = std::fs::read_to_string(dir.join("trajectory.csv")).expect("trajectory");
    let header: Vec<&str> = trajectory
        .lines()
        .next()
        .expect("header")
        .split(',')
        .collect();
    let mass_column = header
        .iter()
        .position(|c| c.starts_with("mass"))
        .expect("mass");
    let last: Vec<&str> = trajectory
        .lines()
        .last()
        .expect("rows")
        .split(',')
        .collect();
    let mass: f64 = last[mass_column].parse().expect("mass");
    let v = summary["impact_velocity_mps"]
        .as_f64()
        .expect("impact speed");
    let energy = figure("landing_kinetic_energy_j")["value"]
        .as_f64()
        .expect("energy");
    assert!(
        (energy - 0.5 * mass * v * v).abs() <= 1e-9 * energy,
        "{energy} vs {}",
        0.5 * mass * v * v
    );
    assert_eq!(figure("descent_rate_mps")["value"].as_f64(), Some(v));
    assert_eq!(
        figure("rail_exit_speed_mps")["value"].as_f64(),
        summary["out_of_rail_velocity_mps"].as_f64()
    );
    assert_eq!(
        figure("max_mach")["value"].as_f64(),
        summary["max_mach"].as_f64()
    );
    let drift = figure("drift_m")["value"].as_f64().expect("drift");
    let (x, y) = (
        summary["impact_x_m"].as_f64().expect("x"),
        summary["impact_y_m"].as_f64().expect("y"),
    );
    assert_eq!(drift.to_bits(), x.hypot(y).to_bits());
    let flutter = figure("flutter_margin.fins");
    assert!(
        flutter["value"].as_f64().expect("margin") > 1.0,
        "{flutter}"
    );
    for c in checks {
        assert_ne!(c["verdict"], "fail", "{c}");
    }
    // Defaults: Calisto leaves its rail at 26 m/s (< 30.48) and lands with 242 J (> 101.7 J).
    let text = failure(&["safety", &mission]);
    assert!(
        text.contains(
            "fails the range-safety rules: rail_exit_speed_mps, landing_kinetic_energy_j"
        ),
        "{text}"
    );
    let output = karman(&["safety", &mission]);
    let table = String::from_utf8_lossy(&output.stdout);
    assert!(
        table.contains("flutter_margin.fins") && table.contains("not assessed"),
        "{table}"
    );
}

#[test]
fn safety_refuses_bad_arguments() {
    let Some(mission) = calisto() else { return };
    let text = failure(&[
        "safety",
        &mission,
        "--shear-modulus=-1",
        "--fin-thickness",
        "0.004",
    ]);
    assert!(
        text.contains("--shear-modulus must be a positive number, got -1"),
        "{text}"
    );
    let text = failure(&["safety", &mission, "--max-drift", "0"]);
    assert!(
        text.contains("--max-drift must be a positive number"),
        "{text}"
    );
}
