//! A flown mission as karman-flightlog's plain series.

use karman_flightlog::{Deployment, SimulatedFlight, SimulatedLanding};
use karman_mission::dynamics::{Sample, Summary};

/// The simulated flight of `samples` and `summary` (a flown mission's stored points and
/// summary) as the series [`karman_flightlog::compare`] reads: time, altitude above the
/// ground, vertical velocity and acceleration, the parachute events (`parachute:<name>`)
/// and the impact.
#[must_use]
pub fn simulated_flight(samples: &[Sample], summary: &Summary) -> SimulatedFlight {
    let deployments = summary
        .events
        .iter()
        .filter_map(|e| {
            e.name.strip_prefix("parachute:").map(|name| Deployment {
                name: name.to_owned(),
                time_s: e.time_s,
            })
        })
        .collect();
    let landing = match (
        summary.impact_time_s,
        summary.impact_x_m,
        summary.impact_y_m,
    ) {
        (Some(time_s), Some(east_m), Some(north_m)) => Some(SimulatedLanding {
            time_s,
            east_m,
            north_m,
        }),
        _ => None,
    };
    SimulatedFlight {
        time_s: samples.iter().map(|s| s.t).collect(),
        altitude_m: samples.iter().map(|s| s.altitude_agl).collect(),
        vertical_velocity_mps: samples.iter().map(|s| s.vz).collect(),
        vertical_acceleration_mps2: samples.iter().map(|s| s.az).collect(),
        deployments,
        landing,
    }
}
