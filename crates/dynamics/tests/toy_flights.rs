//! Whole flights of the analytic mock rocket, checked against closed-form results.

use karman_dynamics::{FlightSettings, Termination, simulate};

use crate::mock::{MockAtmosphere, MockRocket};

/// Vertical powered ascent in vacuum with constant thrust `T` and mass flow `q`: the
/// Tsiolkovsky solution with gravity. Returns (apogee above launch, apogee time, burn-out
/// velocity).
fn vacuum_apogee(r: &MockRocket, g: f64) -> (f64, f64, f64) {
    let tb = r.burn_time;
    let m0 = r.dry_mass + r.propellant;
    let m1 = r.dry_mass;
    let q = r.propellant / tb;
    let ve = r.thrust / q;
    let v1 = ve * (m0 / m1).ln() - g * tb;
    let z1 = ve * (tb - (m1 / q) * (m0 / m1).ln()) - 0.5 * g * tb * tb;
    (z1 + v1 * v1 / (2.0 * g), tb + v1 / g, v1)
}

#[test]
fn vacuum_vertical_flight_matches_tsiolkovsky() {
    let atm = MockAtmosphere {
        rho0: 0.0,
        ..MockAtmosphere::default()
    };
    let rocket = MockRocket::stable();
    let mut settings = FlightSettings::new(3.0);
    settings.inclination_deg = 90.0;
    // The mock's thrust drops as a step at burn-out, which an embedded error estimate only
    // resolves with tight tolerances (with the defaults the burn-out step keeps ~0.2 % of
    // apogee error); tight tolerances make this a convergence check of the whole engine.
    settings.rtol = 1e-11;
    settings.atol = [1e-11; 13];
    let flight = simulate(&atm, &rocket, &settings).unwrap();
    let s = flight.summary(&atm, &rocket);
    let (apogee, t_apogee, _) = vacuum_apogee(&rocket, atm.g);
    let agl = s.apogee_agl_m.unwrap();
    // Tolerance: the tight integration tolerances above, accumulated over the steps; the coast
    // is a parabola, which the dense output reproduces exactly.
    assert!(
        (agl - apogee).abs() / apogee < 1e-7,
        "apogee {agl} vs {apogee}"
    );
    assert!(
        (s.apogee_time_s.unwrap() - t_apogee).abs() < 1e-6,
        "apogee time"
    );
    // Free fall from apogee: impact sqrt(2h/g) later, at sqrt(2 g h).
    let t_fall = (2.0 * apogee / atm.g).sqrt();
    assert_eq!(flight.termination, Termination::Impact);
    assert!((s.impact_time_s.unwrap() - (t_apogee + t_fall)).abs() < 1e-6);
    assert!((s.impact_velocity_mps.unwrap() - atm.g * t_fall).abs() / (atm.g * t_fall) < 1e-7);
    // Vertical flight stays on the axis.
    assert!(s.impact_x_m.unwrap().abs() < 1e-6 && s.impact_y_m.unwrap().abs() < 1e-6);
}

#[test]
fn rail_exit_speed_matches_constant_acceleration() {
    let atm = MockAtmosphere {
        rho0: 0.0,
        ..MockAtmosphere::default()
    };
    let rocket = MockRocket::stable();
    let mut settings = FlightSettings::new(3.0);
    settings.inclination_deg = 90.0;
    let flight = simulate(&atm, &rocket, &settings).unwrap();
    let s = flight.summary(&atm, &rocket);
    // Travel to the upper button: rail − |nozzle − upper| = 3.0 − |−1.0 − 0.2| = 1.8 m.
    let travel = 1.8;
    // Rail motion: z'' = T/m(t) − g; integrate the exact solution numerically by bisection
    // on z(t) = travel with the closed form of the vacuum ascent.
    let (m0, q, ve) = (11.0, 0.5, 800.0 / 0.5);
    let z = |t: f64| {
        let m = m0 - q * t;
        ve * (t - (m / q) * (m0 / m).ln()) - 0.5 * atm.g * t * t
    };
    let (mut lo, mut hi) = (0.0, 2.0);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if z(mid) < travel { lo = mid } else { hi = mid }
    }
    let t_exit = 0.5 * (lo + hi);
    let v_exit = ve * (m0 / (m0 - q * t_exit)).ln() - atm.g * t_exit;
    assert!((s.out_of_rail_time_s.unwrap() - t_exit).abs() < 1e-6);
    assert!((s.out_of_rail_velocity_mps.unwrap() - v_exit).abs() / v_exit < 1e-6);
}

#[test]
fn drogue_fires_at_first_sample_after_apogee_and_descends_at_terminal_speed() {
    let atm = MockAtmosphere {
        wind: [3.0, -1.0],
        ..MockAtmosphere::default()
    };
    let mut rocket = MockRocket::stable();
    rocket.parachutes.push(MockRocket::drogue());
    let mut settings = FlightSettings::new(3.0);
    settings.inclination_deg = 85.0;
    settings.heading_deg = 30.0;
    let flight = simulate(&atm, &rocket, &settings).unwrap();
    let s = flight.summary(&atm, &rocket);
    let t_apogee = s.apogee_time_s.unwrap();
    let ev = &flight.parachute_events[0];
    // Sampling at 100 Hz: the trigger is the first instant j/100 after apogee.
    assert!(ev.trigger_time > t_apogee && ev.trigger_time - t_apogee <= 0.01 + 1e-9);
    assert!((ev.trigger_time * 100.0 - (ev.trigger_time * 100.0).round()).abs() < 1e-9);
    assert!((ev.inflation_time - ev.trigger_time - 1.0).abs() < 1e-12);
    // Terminal vertical speed under canopy at the ground: m g = ½ ρ cd_s v² (wind is
    // horizontal and uniform, so the horizontal drift speed matches the wind).
    let rho = atm.rho0 * (-atm.elevation / 8500.0_f64).exp();
    let v_term = (2.0 * rocket.dry_mass * atm.g / (rho * 1.0)).sqrt();
    let (_, u) = flight.impact.unwrap();
    // Tolerance 1 %: density varies by ~1 % over the last seconds of descent.
    assert!(
        (u[5].abs() - v_term).abs() / v_term < 0.01,
        "vz {} vs {v_term}",
        u[5]
    );
    assert!(
        (u[3] - 3.0).abs() < 0.05 && (u[4] + 1.0).abs() < 0.05,
        "drift with the wind"
    );
    let names: Vec<&str> = s.events.iter().map(|e| e.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "rail_exit",
            "burnout",
            "apogee",
            "parachute:drogue",
            "impact"
        ]
    );
    assert!(s.events.windows(2).all(|w| w[0].time_s <= w[1].time_s));
}

#[test]
fn terminate_on_apogee_stops_there() {
    let atm = MockAtmosphere::default();
    let rocket = MockRocket::stable();
    let mut settings = FlightSettings::new(3.0);
    settings.terminate_on_apogee = true;
    let flight = simulate(&atm, &rocket, &settings).unwrap();
    let s = flight.summary(&atm, &rocket);
    assert_eq!(flight.termination, Termination::Apogee);
    assert!((flight.t_final - s.apogee_time_s.unwrap()).abs() < 1e-12);
    assert!(s.impact_time_s.is_none() && s.impact_velocity_mps.is_none());
    let last = flight.points.last().unwrap();
    assert!(
        last.state[5].abs() < 1e-3,
        "vertical speed at apogee {}",
        last.state[5]
    );
}

#[test]
fn samples_follow_the_stored_points() {
    let atm = MockAtmosphere {
        wind: [4.0, 0.0],
        ..MockAtmosphere::default()
    };
    let mut rocket = MockRocket::stable();
    rocket.parachutes.push(MockRocket::drogue());
    let mut settings = FlightSettings::new(3.0);
    settings.inclination_deg = 88.0;
    let flight = simulate(&atm, &rocket, &settings).unwrap();
    let samples = flight.samples(&atm, &rocket);
    assert_eq!(samples.len(), flight.points.len());
    assert!(samples.windows(2).all(|w| w[0].t <= w[1].t), "time order");
    let s = flight.summary(&atm, &rocket);
    let max_speed = samples.iter().map(|x| x.speed).fold(0.0, f64::max);
    assert!((max_speed - s.max_speed_mps).abs() < 1e-12);
    // At rest on the rail (heading east, 88°) the free stream is the 4 m/s east wind: the
    // angle between the axis and the oncoming flow is acos(−b3·ŵ) = 90° + 2°.
    let first = &samples[0];
    assert!(first.speed.abs() < 1e-12);
    assert!(
        (first.angle_of_attack_deg - 92.0).abs() < 1e-9,
        "{}",
        first.angle_of_attack_deg
    );
    // Attitude: the rail direction (inclination 88°) at launch.
    assert!((first.attitude_angle_deg - 88.0).abs() < 1e-9);
    // Under the canopy the mass is the dry mass and there is no thrust.
    let last = samples.last().unwrap();
    assert!((last.mass - rocket.dry_mass).abs() < 1e-12 && last.net_thrust.abs() < 1e-12);
    // Every sample is finite.
    assert!(
        samples
            .iter()
            .all(|x| x.mach.is_finite() && x.dynamic_pressure.is_finite())
    );
}

#[test]
fn noisy_triggers_replay_from_their_seed() {
    use karman_dynamics::TriggerKind;
    let atm = MockAtmosphere::default();
    let mut rocket = MockRocket::stable();
    let mut main = MockRocket::drogue();
    main.name = "main".into();
    main.trigger = TriggerKind::HeightAboveGround(300.0);
    // 300 Pa of noise is ~25 m of barometric height: the trigger instant depends on the draws.
    main.noise = [0.0, 300.0, 0.5];
    main.lag = 0.0;
    rocket.parachutes.push(main);
    let fly = |seed: u64| {
        let mut settings = FlightSettings::new(3.0);
        settings.noise_seed = seed;
        let flight = simulate(&atm, &rocket, &settings).unwrap();
        assert_eq!(flight.noise_seed, seed);
        flight.parachute_events[0].trigger_time
    };
    let (a, b) = (fly(1), fly(1));
    assert!(
        (a - b).abs() < f64::MIN_POSITIVE,
        "same seed, same trigger: {a} vs {b}"
    );
    let others: Vec<f64> = (2..6).map(fly).collect();
    assert!(
        others.iter().any(|t| (t - a).abs() > 1e-9),
        "other seeds move the trigger"
    );
}
