//! Validation against RocketPy 1.13 (`../shared/validation/*/reference.json`): the total
//! impulse and maximum thrust of the missions whose thrust curve is a CSV file, computed here
//! from the file with [`read_curve`], a linear zero-extrapolated [`Table1`] (RocketPy's
//! motor thrust function, physics.md §6.1) and its exact integral and maximum on
//! `[0, burn_time]`. Also every CSV curve of the validation missions must load.

use std::path::PathBuf;

use karman_math::{Extrapolation, Function, Interpolation, PointOrder, Table1, read_curve};

/// The validation folder, or `None` (with a message) when it is absent.
fn validation_dir() -> Option<PathBuf> {
    let dir = std::env::var_os("KARMAN_VALIDATION_DATA").map_or_else(
        || PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/validation"),
        PathBuf::from,
    );
    if dir.is_dir() {
        Some(dir)
    } else {
        println!("skipped: validation data not found at {}", dir.display());
        None
    }
}

fn missions(dir: &PathBuf) -> Vec<(PathBuf, toml::Table)> {
    let mut out: Vec<(PathBuf, toml::Table)> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.join("mission.toml").is_file())
        .map(|p| {
            let text = std::fs::read_to_string(p.join("mission.toml")).unwrap();
            let table: toml::Table = text.parse().unwrap();
            (p, table)
        })
        .collect();
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

fn csv_entry<'a>(table: &'a toml::Table, section: &str, key: &str) -> Option<&'a str> {
    table
        .get(section)?
        .get(key)?
        .as_str()
        .filter(|s| s.ends_with(".csv"))
}

#[test]
fn validate_csv_thrust_total_impulse_and_max_thrust() {
    let Some(dir) = validation_dir() else { return };
    let mut checked = 0;
    for (folder, mission) in missions(&dir) {
        let Some(file) = csv_entry(&mission, "motor", "thrust") else {
            continue;
        };
        // Missions that reshape the curve or give [start, end] are the motor crate's business.
        let motor = &mission["motor"];
        let Some(burn_time) = motor.get("burn_time").and_then(toml::Value::as_float) else {
            continue;
        };
        if motor.get("reshape_thrust_curve").is_some() {
            continue;
        }
        let points = read_curve(folder.join(file)).unwrap();
        let table = Table1::from_points(
            &points,
            Interpolation::Linear,
            Extrapolation::Zero,
            PointOrder::SortStably,
        )
        .unwrap();
        let reference: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(folder.join("reference.json")).unwrap())
                .unwrap();
        let impulse_ref = reference["motor"]["total_impulse_ns"].as_f64().unwrap();
        let max_ref = reference["motor"]["max_thrust_n"].as_f64().unwrap();
        let impulse = table.integral(0.0, burn_time);
        let max = Function::table(table)
            .maximum(0.0, burn_time)
            .unwrap()
            .value;
        let (e_impulse, e_max) = (
            (impulse - impulse_ref).abs() / impulse_ref,
            (max - max_ref).abs() / max_ref,
        );
        println!(
            "{}: impulse {impulse} vs {impulse_ref} (rel {e_impulse:.1e}), max {max} vs {max_ref} (rel {e_max:.1e})",
            folder.display()
        );
        // Same data, same (exact) trapezoid integral: agreement to rounding.
        assert!(e_impulse < 1e-12, "{}", folder.display());
        assert!(e_max < 1e-12, "{}", folder.display());
        checked += 1;
    }
    assert!(
        checked > 0,
        "no mission with a CSV thrust curve and a burn_time"
    );
}

#[test]
fn validation_csv_curves_load() {
    let Some(dir) = validation_dir() else { return };
    let mut repeated = 0;
    let mut loaded = 0;
    for (folder, mission) in missions(&dir) {
        let keys = [
            ("motor", "thrust"),
            ("rocket", "power_off_drag"),
            ("rocket", "power_on_drag"),
        ];
        for (section, key) in keys {
            let Some(file) = csv_entry(&mission, section, key) else {
                continue;
            };
            let points = read_curve(folder.join(file)).unwrap();
            let table = Table1::from_points(
                &points,
                Interpolation::Linear,
                Extrapolation::Constant,
                PointOrder::SortStably,
            )
            .unwrap();
            repeated += table.xs().windows(2).filter(|w| w[1] <= w[0]).count();
            loaded += 1;
        }
    }
    assert!(loaded > 0);
    // astra's drag curve repeats two Mach numbers (RocketPy sorts and keeps them).
    assert!(
        repeated >= 2,
        "expected the repeated Mach numbers of astra's drag curve"
    );
}
