//! The real Wyoming sounding of the shared data (Jokioinen, 2006-04-10 12Z) through the
//! whole environment.

use crate::common::shared_dir;
use karman_atmos::{Atmosphere, Environment, EnvironmentConfig, Sounding};
use karman_math::PhysicalConstants;

#[test]
fn jokioinen_sounding_builds_an_environment() {
    let Some(shared) = shared_dir("jokioinen_sounding_builds_an_environment") else {
        return;
    };
    let path = shared.join("data/weather/wyoming_02963_2006-04-10T12Z.txt");
    let text = std::fs::read_to_string(&path).expect("sounding file");
    let s = Sounding::parse_wyoming(&text, "jokioinen").expect("parses");
    // The file has 81 data rows; the 1000 hPa and 30 hPa rows lack fields and are skipped.
    let first = s.levels[0];
    assert!((first.pressure_pa.unwrap_or(0.0) - 99_200.0).abs() < 1e-9);
    assert!((first.height_m - 103.0).abs() < 1e-12);
    let last = s.levels[s.levels.len() - 1];
    assert!((last.height_m - 23_604.0).abs() < 1e-12);
    let c = PhysicalConstants::SI;
    let radius = karman_atmos::Datum::Wgs84.radius(60.8, &c);
    let config = EnvironmentConfig {
        earth_model: None,
        latitude_deg: 60.8,
        longitude_deg: 23.5,
        elevation: 103.0,
        atmosphere: Atmosphere::Profiles(s.profiles(radius).expect("profiles")),
        ..EnvironmentConfig::default()
    };
    let env = Environment::new(&config, &c).expect("environment");
    // At a reported level the tables return the level's values: 850 hPa at 1325 m, −6.5 °C.
    assert!((env.pressure(1325.0) - 85_000.0).abs() < 1e-9);
    assert!((env.temperature(1325.0) - 266.65).abs() < 1e-9);
    assert!((env.barometric_height(85_000.0) - 1325.0).abs() < 1e-9);
    // Density node-wise P/(R T) at that level.
    assert!((env.density(1325.0) - 85_000.0 / (c.air_gas_constant * 266.65)).abs() < 1e-12);
    // Wind 3 kt from 280° at 850 hPa blows toward 100°: mostly east, a little south.
    let [u, v] = env.wind(karman_atmos::isa::geopotential_to_geometric(1325.0, radius));
    assert!(u > 1.5 && v < 0.0, "{u} {v}");
}
