//! The environment of every validation mission against RocketPy 1.13's `reference.json`
//! (`environment`): pressure and density within 0.1 %, temperature within 0.1 K, speed of
//! sound within 0.05 %, wind components within 0.05 m/s, gravity at launch within 1e-6
//! (relative) — the acceptance of the atmosphere issue.

use crate::common::{flight_name, load_reference, validation_missions};
use karman_mission::assemble::environment::build_environment;
use karman_mission::report::environment::{EnvironmentReport, environment_report};
use serde_json::Value;

fn column(reference: &Value, key: &str) -> Vec<f64> {
    reference["environment"][key]
        .as_array()
        .unwrap_or_else(|| panic!("reference.json lacks environment.{key}"))
        .iter()
        .map(|v| v.as_f64().unwrap_or(f64::NAN))
        .collect()
}

/// Largest relative (or absolute) deviation of `ours` from `theirs` (NaN if any is NaN).
fn worst(ours: &[f64], theirs: &[f64], relative: bool) -> f64 {
    assert_eq!(ours.len(), theirs.len());
    ours.iter()
        .zip(theirs)
        .map(|(a, b)| {
            if relative {
                ((a - b) / b).abs()
            } else {
                (a - b).abs()
            }
        })
        .fold(
            0.0,
            |acc: f64, d| if d.is_nan() || d > acc { d } else { acc },
        ) // NaN sticks
}

#[test]
fn validate_environment() {
    let Some(missions) = validation_missions() else {
        println!("validate_environment: skipped, the validation folder is absent");
        return;
    };
    assert!(!missions.is_empty(), "no validation mission found");
    let mut failures = Vec::new();
    for path in missions {
        let name = flight_name(&path);
        let mission = karman_mission::load(&path, &[]).expect("mission loads");
        let env = build_environment(&mission).expect("environment builds");
        let reference = load_reference(&path);
        let heights = column(&reference, "heights_asl_m");
        let ours: EnvironmentReport = environment_report(&env, &heights);
        let g_ref = reference["environment"]["gravity_mps2_at_launch"]
            .as_f64()
            .unwrap_or(0.0);
        // (quantity, our values, reference, relative?, tolerance)
        let checks = [
            ("pressure", &ours.pressure_pa, "pressure_pa", true, 1e-3),
            ("density", &ours.density_kgpm3, "density_kgpm3", true, 1e-3),
            (
                "temperature",
                &ours.temperature_k,
                "temperature_k",
                false,
                0.1,
            ),
            (
                "speed of sound",
                &ours.speed_of_sound_mps,
                "speed_of_sound_mps",
                true,
                5e-4,
            ),
            (
                "viscosity",
                &ours.dynamic_viscosity_pas,
                "dynamic_viscosity_pas",
                true,
                1e-3,
            ),
            ("wind u", &ours.wind_u_mps, "wind_u_mps", false, 0.05),
            ("wind v", &ours.wind_v_mps, "wind_v_mps", false, 0.05),
        ];
        let mut line = format!("{name:>16}:");
        for (label, values, key, relative, tol) in checks {
            let w = worst(values, &column(&reference, key), relative);
            line.push_str(&format!(" {label} {w:.2e}"));
            if w.is_nan() || w > tol {
                failures.push(format!("{name}: {label} off by {w:e} (tolerance {tol:e})"));
            }
        }
        let g_err = ((ours.gravity_mps2_at_launch - g_ref) / g_ref).abs();
        line.push_str(&format!(" gravity {g_err:.2e}"));
        if g_err.is_nan() || g_err > 1e-6 {
            failures.push(format!("{name}: gravity off by {g_err:e}"));
        }
        println!("{line}");
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Loads the Calisto validation mission with overrides (`None` when the data is absent).
fn calisto_with(overrides: &[&str]) -> Option<karman_mission::Mission> {
    let missions = validation_missions()?;
    let path = missions
        .into_iter()
        .find(|p| p.to_string_lossy().contains("calisto"))?;
    let overrides: Vec<karman_mission::Override> = overrides
        .iter()
        .map(|o| o.parse().expect("override parses"))
        .collect();
    Some(karman_mission::load(&path, &overrides).expect("mission loads"))
}

#[test]
fn custom_atmosphere_wind_profile() {
    // The custom wind of docs/physics.md §13 over the ISA thermodynamics.
    let Some(mission) = calisto_with(&[
        "environment.atmosphere.model=\"custom\"",
        "environment.atmosphere.wind_u=[[0,5],[1400,5],[3000,10],[5000,15]]",
        "environment.atmosphere.wind_v=[[0,-2],[5000,-6]]",
    ]) else {
        println!("custom_atmosphere_wind_profile: skipped, the validation folder is absent");
        return;
    };
    let env = build_environment(&mission).expect("environment builds");
    let [u, v] = env.wind(2200.0);
    assert!(
        (u - 7.5).abs() < 1e-12 && (v + 3.76).abs() < 1e-12,
        "{u} {v}"
    );
    assert!(
        (env.wind(9000.0)[0] - 15.0).abs() < 1e-12,
        "held above the table"
    );
    // ISA thermodynamics kept: docs/physics.md §4.1 spot pressure at 1400 m.
    assert!(((env.pressure(1400.0) - 85596.6788) / 85596.6788).abs() < 1e-8);
}

#[test]
fn sounding_and_bad_sounding_through_the_mission() {
    let Some(dir) = crate::common::validation_dir() else {
        return;
    };
    // A sounding in the University of Wyoming's text layout, written by the test (three
    // mandatory levels; the 850 hPa one is the level asserted below).
    let wyoming =
        std::env::temp_dir().join(format!("karman-sounding-{}-02963.txt", std::process::id()));
    let rows = [
        "02963 Synthetic Observations at 12Z 10 Apr 2006",
        "",
        "-----------------------------------------------------------------------------",
        "   PRES   HGHT   TEMP   DWPT   RELH   MIXR   DRCT   SKNT   THTA   THTE   THTV",
        "    hPa     m      C      C      %    g/kg    deg   knot     K      K      K",
        "-----------------------------------------------------------------------------",
        "  992.0    103    1.6    0.8     94   4.11    240      5  275.4  286.7  276.1",
        "  850.0   1325   -6.5  -10.0     76   2.11    280      3  279.3  285.5  279.7",
        "  700.0   2813  -17.5  -24.5     54   0.76    290     13  283.1  285.5  283.2",
        "  500.0   5240  -36.9  -42.9     54   0.17    245      9  288.0  288.6  288.0",
        "",
    ];
    std::fs::write(&wyoming, rows.join("\n")).expect("temporary sounding written");
    let file = format!(
        "environment.atmosphere.file={:?}",
        wyoming.display().to_string()
    );
    let sounding = [
        "environment.atmosphere.model=\"sounding\"",
        "environment.atmosphere.format=\"wyoming\"",
        "environment.date=2006-04-10T12:00:00Z",
    ];
    let mission =
        calisto_with(&[sounding[0], sounding[1], sounding[2], &file]).expect("calisto mission");
    let env = build_environment(&mission).expect("sounding environment builds");
    assert!(
        (env.pressure(1325.0) - 85_000.0).abs() < 1e-9,
        "850 hPa at 1325 m"
    );
    assert!(
        (env.elevation() - 1400.0).abs() < 1e-12,
        "the mission's elevation is kept"
    );
    // A sounding file that is not a sounding: the error names the section and the file.
    let calisto = dir.join("calisto/mission.toml");
    let bogus = format!(
        "environment.atmosphere.file={:?}",
        calisto.display().to_string()
    );
    let mission =
        calisto_with(&[sounding[0], sounding[1], sounding[2], &bogus]).expect("calisto mission");
    let e = build_environment(&mission).expect_err("not a sounding");
    let chain = format!(
        "{e} / {}",
        std::error::Error::source(&e).map_or(String::new(), |s| s.to_string())
    );
    assert!(
        chain.contains("environment.atmosphere") && chain.contains("mission.toml"),
        "{chain}"
    );
    let _ = std::fs::remove_file(&wyoming);
}
