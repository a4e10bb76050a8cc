//! `karman import` of every single-stage design in `fixtures/openrocket` (OpenRocket 24.12's
//! example designs with their stored flights), flown and compared with OpenRocket: apogee
//! within 5 %, maximum speed within 3 %, total Cd within 10 % below Mach 0.8 and 15 % above,
//! CP within 1 % of the body length and stability margin within 0.1 caliber after rod exit.
//! Designs with clusters, pods or tube fins are refused by the importer (tested in `ork`).

use std::path::PathBuf;

use karman_mission::report::openrocket::compare_design;

fn fixtures() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/openrocket")
}

/// The single-stage designs karman imports.
const DESIGNS: [&str; 5] = [
    "a_simple_model_rocket",
    "base_drag_hack_short_wide",
    "chute_release",
    "dual_parachute_deployment",
    "simulation_scripting",
];

#[test]
fn validate_openrocket_designs_fly_as_openrocket() {
    let mut failures = Vec::new();
    for design in DESIGNS {
        let results = compare_design(&fixtures().join(design)).unwrap_or_else(|e| panic!("{design}: {e}"));
        for r in results {
            println!("{design:<28} {r}");
            let mut check = |what: &str, error: f64, limit: f64| {
                if !(error <= limit) {
                    failures.push(format!("{design} {}: {what} {error:.4} > {limit}", r.simulation));
                }
            };
            check("apogee", r.apogee_error(), 0.05);
            check("max speed", r.max_speed_error(), 0.03);
            check("Cd below Mach 0.8", r.cd_subsonic, 0.10);
            if r.cd_transonic.is_finite() {
                check("Cd above Mach 0.8", r.cd_transonic, 0.15);
            }
            check("CP / body length", r.cp_error(), 0.01);
            check("margin (cal)", r.margin_error(), 0.1);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
