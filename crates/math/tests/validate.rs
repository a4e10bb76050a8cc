//! Validation against RocketPy 1.13 (`fixtures/validation/*/reference.json`): the total
//! impulse and maximum thrust of the missions whose thrust curve is a CSV file, computed here
//! from the file with [`read_curve`], a linear zero-extrapolated [`Table1`] (RocketPy's
//! motor thrust function, docs/physics.md §6.1) and its exact integral and maximum on
//! `[0, burn_time]`. Also every CSV curve of the validation missions must load.

use std::path::PathBuf;

use karman_math::{Extrapolation, Function, Interpolation, PointOrder, Table1, read_curve};

/// The folder and parsed `mission.toml` of every validation flight flown (sorted), or `None`
/// when the validation folder is unavailable outside CI ([`karman_validation::folder`]).
fn missions() -> Option<Vec<(PathBuf, toml::Table)>> {
    let flights = karman_validation::folder()?.flown();
    Some(
        flights
            .into_iter()
            .map(|flight| {
                let text = std::fs::read_to_string(flight.mission()).unwrap();
                let table: toml::Table = text.parse().unwrap();
                (flight.dir, table)
            })
            .collect(),
    )
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
    let Some(missions) = missions() else { return };
    let mut checked = 0;
    for (folder, mission) in missions {
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
    let Some(missions) = missions() else { return };
    let mut repeated = 0;
    let mut loaded = 0;
    for (folder, mission) in missions {
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
