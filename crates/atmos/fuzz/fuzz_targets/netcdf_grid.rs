//! Fuzz target: opening arbitrary bytes as a weather grid and extracting a profile returns
//! errors, never panics.
#![no_main]

use karman_atmos::{GridRequest, WeatherGrid};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(grid) = WeatherGrid::from_bytes(data.to_vec(), "fuzz.nc") {
        let request = GridRequest {
            dictionary: None,
            unix_time: 1.6e9,
            latitude_deg: 40.0,
            longitude_deg: -8.0,
            member: None,
            earth_radius: 6.371e6,
            standard_gravity: 9.80665,
        };
        let _ = grid.profile(&request);
    }
});
