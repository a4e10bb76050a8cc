//! Unflyable rockets end with an error or a flagged summary, in bounded time.

use std::time::{Duration, Instant};

use karman_dynamics::{DynamicsError, FlightSettings, Termination, simulate};

use crate::mock::{MockAtmosphere, MockRocket, MockSurface};

/// Generous wall-clock bound for one debug-build flight of the mock rocket.
const BOUND: Duration = Duration::from_secs(20);

#[test]
fn motor_too_weak_to_leave_the_rail_is_flagged() {
    let atm = MockAtmosphere::default();
    let mut rocket = MockRocket::stable();
    rocket.thrust = 50.0; // < m g ≈ 108 N
    let start = Instant::now();
    let flight = simulate(&atm, &rocket, &FlightSettings::new(3.0)).unwrap();
    assert!(start.elapsed() < BOUND);
    assert_eq!(flight.termination, Termination::StuckOnRail);
    let s = flight.summary(&atm, &rocket);
    assert!(s.out_of_rail_time_s.is_none() && s.apogee_agl_m.is_none());
    assert!(s.impact_time_s.is_none());
}

#[test]
fn max_time_reached_is_flagged() {
    let atm = MockAtmosphere::default();
    let rocket = MockRocket::stable();
    let mut settings = FlightSettings::new(3.0);
    settings.max_time = 5.0;
    let flight = simulate(&atm, &rocket, &settings).unwrap();
    assert_eq!(flight.termination, Termination::MaxTime);
    assert!((flight.t_final - 5.0).abs() < 1e-12);
    let s = flight.summary(&atm, &rocket);
    assert!(s.impact_time_s.is_none() && s.out_of_rail_time_s.is_some());
}

#[test]
fn negative_margin_rocket_ends_in_bounded_time() {
    // Fins ahead of the CDM and the nose behind it: statically unstable.
    let atm = MockAtmosphere {
        wind: [5.0, 0.0],
        ..MockAtmosphere::default()
    };
    let mut rocket = MockRocket::stable();
    rocket.surfaces = vec![
        MockSurface {
            cp: [0.0, 0.0, -0.8],
            cn_alpha: 2.0,
        },
        MockSurface {
            cp: [0.0, 0.0, 0.9],
            cn_alpha: 6.0,
        },
    ];
    let start = Instant::now();
    let result = simulate(&atm, &rocket, &FlightSettings::new(3.0));
    assert!(start.elapsed() < BOUND);
    match result {
        Ok(flight) => {
            let s = flight.summary(&atm, &rocket);
            assert!(s.max_speed_mps.is_finite() && s.max_acceleration_mps2.is_finite());
            assert!(matches!(
                flight.termination,
                Termination::Impact | Termination::MaxTime
            ));
        }
        Err(e) => assert!(matches!(
            e,
            DynamicsError::StepTooSmall { .. } | DynamicsError::TooManySteps { .. }
        )),
    }
}

#[test]
fn nan_in_a_curve_is_an_error() {
    let atm = MockAtmosphere::default();
    let mut rocket = MockRocket::stable();
    rocket.cd = f64::NAN;
    let err = simulate(&atm, &rocket, &FlightSettings::new(3.0)).unwrap_err();
    assert!(matches!(err, DynamicsError::NonFinite { .. }), "{err}");
}

#[test]
fn rail_shorter_than_button_offset_is_rejected() {
    let atm = MockAtmosphere::default();
    let rocket = MockRocket::stable();
    let err = simulate(&atm, &rocket, &FlightSettings::new(1.0)).unwrap_err();
    assert!(matches!(
        err,
        DynamicsError::InvalidSetting {
            name: "rail_length",
            ..
        }
    ));
}
