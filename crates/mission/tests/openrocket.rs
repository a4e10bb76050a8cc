//! `karman import` of every design in `fixtures/openrocket` (OpenRocket 24.12's example
//! designs with their stored flights), flown and compared with OpenRocket. A single-stage
//! design: apogee within 5 %, maximum speed within 3 %, total Cd within 10 % below Mach 0.8
//! and 15 % above, CP within 1 % of the body length and stability margin within 0.1 caliber
//! at launch (rod exit, OpenRocket's first stored CP: karman's estimate at the angle of
//! attack and Mach OpenRocket stored there, Barrowman with Galejs' body lift). A multi-stage
//! design: the top stage's apogee and every separation time within 3 %, the maximum speed
//! reported. A design karman refuses is a miss unless it is a known refusal.
//! The folder walk, the tolerances and the exceptions are
//! `karman_mission::report::openrocket::compare_folder` (the flights) and karman-openrocket
//! (the stored flights, the tolerances and the exceptions), which `cargo xtask validate`
//! reports too (on any folder with `--openrocket DIR`).

use std::path::PathBuf;

use karman_mission::report::openrocket::compare_folder;
use karman_openrocket::{Compared, KNOWN_REFUSALS, STAGED_APOGEE_EXCEPTIONS, design_folders};

fn fixtures() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/openrocket")
}

#[test]
fn validate_openrocket_designs_fly_as_openrocket() {
    let results = compare_folder(&fixtures()).unwrap_or_else(|e| panic!("{e}"));
    let mut failures = Vec::new();
    let (mut single, mut staged) = (0, 0);
    for r in &results {
        print!("{r}");
        match &r.outcome {
            Ok(Compared::Single(sims)) if sims.iter().any(|s| s.outcome.is_ok()) => single += 1,
            Ok(Compared::Staged(sims)) if sims.iter().any(|s| s.outcome.is_ok()) => staged += 1,
            _ => {}
        }
        failures.extend(r.failures());
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(
        single > 0 && staged > 0,
        "{single} single-stage and {staged} multi-stage designs compared"
    );
}

#[test]
fn the_openrocket_exceptions_name_designs_of_the_fixtures() {
    let folders: Vec<String> = design_folders(&fixtures())
        .expect("fixtures/openrocket")
        .iter()
        .filter_map(|d| d.file_name().map(|n| n.to_string_lossy().into_owned()))
        .collect();
    let named = KNOWN_REFUSALS
        .iter()
        .map(|(d, _)| d)
        .chain(STAGED_APOGEE_EXCEPTIONS.iter().map(|(d, _, _)| d));
    for design in named {
        assert!(
            folders.iter().any(|f| f == design),
            "{design} is not a design of fixtures/openrocket"
        );
    }
}

/// The mass at launch of every design that flies as one body (structure, overrides and
/// motors) against OpenRocket's first stored row, which keeps three decimals: within half a
/// gram. A component type whose mass OpenRocket computes differently shows here first.
#[test]
fn validate_openrocket_launch_masses() {
    use karman_mission::assemble::{motor::build_motor, rocket::build_rocket};
    use karman_openrocket::{ImportOptions, import};
    const STORED_HALF_UNIT: f64 = 0.0005;
    let mut failures = Vec::new();
    for dir in design_folders(&fixtures()).expect("fixtures/openrocket") {
        let design = dir.file_name().map(|n| n.to_string_lossy().into_owned());
        let design = design.unwrap_or_default();
        let text = std::fs::read_to_string(dir.join("reference.json")).expect("reference.json");
        let reference: serde_json::Value = serde_json::from_str(&text).expect("JSON");
        for sim in reference["simulations"].as_array().into_iter().flatten() {
            let name = sim["name"].as_str().expect("a name");
            let options = ImportOptions {
                simulation: Some(name.to_owned()),
                output_dir: Some(dir.clone()),
                ..ImportOptions::default()
            };
            // Refusals are the comparison's business.
            let Ok(imported) = import(&dir.join("design.ork"), &options) else {
                continue;
            };
            let mission = karman_mission::parse(&imported.mission, &dir.join("imported.toml"), &[])
                .expect("loads");
            if !mission.spec.stages.is_empty() {
                continue;
            }
            let motor = build_motor(&mission).expect("motor");
            let rocket = build_rocket(&mission, &motor).expect("rocket");
            let ours = rocket.total_mass(0.0);
            let theirs = sim["branches"][0]["ascent"]["mass_kg"][0]
                .as_f64()
                .expect("a stored mass");
            println!("{design:<28} {name:<28} launch mass {ours:.4} / {theirs:.3} kg");
            if (ours - theirs).abs() > STORED_HALF_UNIT {
                failures.push(format!(
                    "{design} {name}: {ours} kg, OpenRocket {theirs} kg"
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
