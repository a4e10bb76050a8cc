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
fn a_rocket_too_slow_to_coast_off_the_rail_after_burn_out_is_stuck() {
    // A 0.1 s burn: at burn-out the rocket is 0.3 m up the rail at about 6 m/s, and its coast
    // against gravity, v²/(2 g sin i), is about 2 m.
    let atm = MockAtmosphere::default();
    let mut rocket = MockRocket::stable();
    rocket.burn_time = 0.1;
    // Nozzle at -1 m, upper button at 0.2 m: the travel is the rail length less 1.2 m.
    let fly = |rail_length: f64| {
        let start = Instant::now();
        let flight = simulate(&atm, &rocket, &FlightSettings::new(rail_length)).unwrap();
        assert!(start.elapsed() < BOUND);
        flight
    };
    // A 20 m rail: the flight ends at burn-out (RocketPy's clipped rail acceleration would
    // keep the speed and creep off the rail seconds later).
    let stuck = fly(21.2);
    assert_eq!(stuck.termination, Termination::StuckOnRail);
    assert_eq!(stuck.t_final.to_bits(), 0.1f64.to_bits());
    let s = stuck.summary(&atm, &rocket);
    assert!(s.out_of_rail_time_s.is_none() && s.apogee_agl_m.is_none());
    let end = stuck.points.last().expect("points").state;
    let travelled = (end[0] * end[0] + end[1] * end[1] + (end[2] - atm.elevation).powi(2)).sqrt();
    let speed = (end[3] * end[3] + end[4] * end[4] + end[5] * end[5]).sqrt();
    let coast = speed * speed / (2.0 * atm.g * 80f64.to_radians().sin());
    assert!(speed > 1.0 && coast > 1.0, "{travelled} m at {speed} m/s");
    // The same burn-out state on rails just within and just beyond its coast.
    let within = fly(1.2 + travelled + 0.99 * coast);
    assert_eq!(within.termination, Termination::Impact);
    let exit = within.rail_exit.expect("rail exit").0;
    assert!(exit > 0.1, "leaves the rail after burn-out: {exit}");
    let beyond = fly(1.2 + travelled + 1.01 * coast);
    assert_eq!(beyond.termination, Termination::StuckOnRail);
    assert_eq!(beyond.t_final.to_bits(), 0.1f64.to_bits());
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
