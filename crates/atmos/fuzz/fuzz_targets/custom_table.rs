//! Fuzz target: the two-column table parser of custom atmosphere profiles, and building an
//! environment from what it accepts, never panic.
#![no_main]

use karman_atmos::{Atmosphere, Curve, Environment, EnvironmentConfig, Profiles, parse_table};
use karman_math::PhysicalConstants;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    if let Ok(points) = parse_table(&text, "fuzz") {
        let profiles = Profiles {
            pressure: Some(Curve::Points(points.clone())),
            temperature: Some(Curve::Points(points.clone())),
            ..Profiles::wind_only("fuzz", Curve::Points(points.clone()), Curve::Points(points))
        };
        let config = EnvironmentConfig {
            earth_model: None,
            atmosphere: Atmosphere::Profiles(profiles),
            ..Default::default()
        };
        if let Ok(env) = Environment::new(&config, &PhysicalConstants::SI) {
            let _ = env.sample(1000.0);
        }
    }
});
