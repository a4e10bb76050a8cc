//! The 3-DOF point-mass mode (`SimulationMode::ThreeDof`, docs/physics.md §8.5) on the mock
//! models: where it must equal the 6-DOF flight, the attitude it holds, and the weathercock
//! law's turn rate.

use karman_dynamics::equations::{Cursors, Equations};
use karman_dynamics::state::{cross, dot, norm, rotation};
use karman_dynamics::{
    Configuration, EquationsForm, FlightSettings, PhaseKind, SimulationMode, Termination, simulate,
    simulate_from,
};

use crate::mock::{MockAtmosphere, MockRocket};

fn three_dof(rail: f64) -> FlightSettings {
    let mut settings = FlightSettings::new(rail);
    settings.simulation_mode = SimulationMode::ThreeDof;
    settings
}

/// The rocket axis (third column of `K`) of a quaternion.
fn axis(e: [f64; 4]) -> [f64; 3] {
    let k = rotation(e);
    [k[0][2], k[1][2], k[2][2]]
}

/// A vertical flight in still air never turns and its propellant sits at the CDM (`c = 0`,
/// `m̈ = 0`), so the 6-DOF equations reduce to `v̇ = K (T + W + R)/m`: the point mass. Both
/// modes fly the same apogee (to rounding of the same integration) with drag.
#[test]
fn a_vertical_flight_in_still_air_is_the_same_in_both_modes() {
    let atm = MockAtmosphere::default();
    let mut rocket = MockRocket::stable();
    rocket.parachutes.push(MockRocket::drogue());
    let mut six = FlightSettings::new(3.0);
    six.inclination_deg = 90.0;
    let mut three = three_dof(3.0);
    three.inclination_deg = 90.0;
    let a = simulate(&atm, &rocket, &six).unwrap();
    let b = simulate(&atm, &rocket, &three).unwrap();
    let (sa, sb) = (a.summary(&atm, &rocket), b.summary(&atm, &rocket));
    let (ha, hb) = (sa.apogee_agl_m.unwrap(), sb.apogee_agl_m.unwrap());
    assert!(
        (ha - hb).abs() <= 1e-9 * ha,
        "apogee {ha} (6 DOF) vs {hb} (3 DOF)"
    );
    let (ta, tb) = (sa.impact_time_s.unwrap(), sb.impact_time_s.unwrap());
    assert!((ta - tb).abs() <= 1e-9 * ta, "impact {ta} vs {tb}");
    assert!(
        b.points
            .iter()
            .any(|p| matches!(p.phase, PhaseKind::PointMass { .. })),
        "the 3-DOF flight flies the point-mass equations"
    );
    assert!(
        !a.points
            .iter()
            .any(|p| matches!(p.phase, PhaseKind::PointMass { .. }))
    );
}

/// Inclined into a crosswind, the point mass keeps the rail's attitude (no weathercock), its
/// rates stay zero and no moment is reported, while the 6-DOF rocket turns into the wind.
#[test]
fn without_weathercocking_the_attitude_is_the_rails() {
    let atm = MockAtmosphere {
        wind: [6.0, -2.0],
        ..MockAtmosphere::default()
    };
    let mut rocket = MockRocket::stable();
    rocket.parachutes.push(MockRocket::drogue());
    let mut settings = three_dof(3.0);
    settings.inclination_deg = 80.0;
    settings.heading_deg = 30.0;
    let flight = simulate(&atm, &rocket, &settings).unwrap();
    assert_eq!(flight.termination, Termination::Impact);
    let e0 = flight.points[0].state;
    for p in &flight.points {
        if matches!(p.phase, PhaseKind::Parachute(_)) {
            // The descent's integrators carry the frozen attitude to rounding.
            let drift = (6..13)
                .map(|i| (p.state[i] - e0[i]).abs())
                .fold(0.0, f64::max);
            assert!(drift < 1e-12, "t = {}: {drift}", p.t);
        } else {
            assert_eq!(p.state[6..13], e0[6..13], "t = {}", p.t);
        }
    }
    let samples = flight.samples(&atm, &rocket);
    assert!(samples.iter().all(|s| s.moment[..] == [0.0; 3]));
    assert!(samples.iter().all(|s| s.omega_dot[..] == [0.0; 3]));
    // The fins' normal force still acts: the body-frame transverse force is non-zero once
    // the flow meets the fixed axis at an angle.
    assert!(
        samples
            .iter()
            .any(|s| s.force[0].hypot(s.force[1]) > 1e-3 && s.angle_of_attack_deg > 1.0)
    );
    settings.simulation_mode = SimulationMode::SixDof;
    let six = simulate(&atm, &rocket, &settings).unwrap();
    let turned = six.points.iter().any(|p| p.state[6..10] != e0[6..10]);
    assert!(turned, "the 6-DOF rocket turns");
}

/// The weathercock law turns the axis toward the relative wind at `k sin θ` (θ the angle
/// between them), within the plane of the two: checked on the quaternion rate by a
/// first-order step of the attitude. Head-on into the wind the rate is `k`; aligned, zero.
#[test]
fn weathercocking_turns_the_axis_at_k_sin_theta() {
    let atm = MockAtmosphere::default();
    let rocket = MockRocket::stable();
    let eq = Equations::new(&atm, &rocket, EquationsForm::Standard);
    let (configuration, cursors) = (&Configuration::default(), &mut Cursors::default());
    let k = 0.7;
    let h = 1e-7;
    // The angle between two vectors, well conditioned at small angles.
    let angle = |a: [f64; 3], b: [f64; 3]| norm(cross(a, b)).atan2(dot(a, b));
    let state = |e: [f64; 4], v: [f64; 3]| {
        [
            0.0, 0.0, 1000.0, v[0], v[1], v[2], e[0], e[1], e[2], e[3], 0.0, 0.0, 0.0,
        ]
    };
    // The attitude after a step `h` of the quaternion rate at (e, v), and the derivative.
    let mut turn = |e: [f64; 4], v: [f64; 3]| {
        let u = state(e, v);
        let d = eq.point_mass(5.0, &u, k, configuration, cursors);
        let held = eq.point_mass(5.0, &u, 0.0, configuration, cursors);
        // No angular state, no moment; the translation does not depend on k; held: no turn.
        assert_eq!(d.u_dot[10..13], [0.0; 3]);
        assert_eq!(d.moment[..], [0.0; 3]);
        assert_eq!(held.u_dot[0..6], d.u_dot[0..6]);
        assert_eq!(held.u_dot[6..10], [0.0; 4]);
        let stepped = [
            e[0] + h * d.u_dot[6],
            e[1] + h * d.u_dot[7],
            e[2] + h * d.u_dot[8],
            e[3] + h * d.u_dot[9],
        ];
        axis(stepped)
    };
    // A rocket pitched over by 20° (a rotation about east), in the mock's still air: the
    // relative wind comes from the direction of the velocity.
    let half = 10f64.to_radians();
    let pitched = [half.cos(), half.sin(), 0.0, 0.0];
    for v in [[0.0, 0.0, 100.0], [30.0, 60.0, 40.0], [0.0, 0.0, -100.0]] {
        let target = [v[0] / norm(v), v[1] / norm(v), v[2] / norm(v)];
        let a0 = axis(pitched);
        let a1 = turn(pitched, v);
        let theta = angle(a0, target);
        let rate = (theta - angle(a1, target)) / h;
        assert!(
            (rate - k * theta.sin()).abs() < 1e-6 * k,
            "θ = {theta}: rate {rate} vs k sin θ = {}",
            k * theta.sin()
        );
        let moved = [a1[0] - a0[0], a1[1] - a0[1], a1[2] - a0[2]];
        assert!(dot(cross(a0, target), moved).abs() < 1e-6 * norm(moved));
    }
    // Upright and falling straight down: head-on, the axis turns at k about a perpendicular.
    let up = [1.0, 0.0, 0.0, 0.0];
    let a1 = turn(up, [0.0, 0.0, -50.0]);
    let rate = angle([0.0, 0.0, 1.0], a1) / h;
    assert!((rate - k).abs() < 1e-6 * k, "head-on rate {rate} vs {k}");
    // Upright and climbing straight up: aligned, nothing turns.
    assert_eq!(turn(up, [0.0, 0.0, 50.0])[..], [0.0, 0.0, 1.0]);
}

/// With weathercocking a flight launched across the wind soon flies with its axis along the
/// relative wind, and its thrust then carries it upwind of the flight that holds the rail's
/// attitude.
#[test]
fn a_weathercocking_flight_points_into_the_relative_wind() {
    let atm = MockAtmosphere {
        wind: [8.0, 0.0],
        ..MockAtmosphere::default()
    };
    let rocket = MockRocket::stable();
    let mut settings = three_dof(3.0);
    settings.inclination_deg = 88.0;
    settings.heading_deg = 0.0;
    settings.terminate_on_apogee = true;
    let held = simulate(&atm, &rocket, &settings).unwrap();
    settings.weathercock_coefficient = 5.0;
    let turned = simulate(&atm, &rocket, &settings).unwrap();
    let samples = turned.samples(&atm, &rocket);
    let (t_exit, _) = turned.rail_exit.unwrap();
    let aoa = samples
        .iter()
        .filter(|s| s.t > t_exit + 1.0 && s.t < rocket.burn_time + 3.0)
        .map(|s| s.angle_of_attack_deg)
        .fold(f64::NAN, f64::max);
    assert!(aoa < 1.0, "largest angle of attack {aoa}°");
    // Turning into the wind (from the west) the thrust pushes upwind: the apogee is west of
    // the held attitude's.
    let x = |f: &karman_dynamics::Flight| f.apogee.unwrap().1[0];
    assert!(x(&turned) < x(&held), "{} vs {}", x(&turned), x(&held));
}

/// A flight resumed from a free-flight state in 3-DOF mode flies the point-mass equations,
/// to the same apogee (tight tolerances, as the 6-DOF resume test of `processes`).
#[test]
fn a_resumed_flight_flies_the_point_mass() {
    let atm = MockAtmosphere {
        wind: [2.0, -1.0],
        ..MockAtmosphere::default()
    };
    let rocket = MockRocket::stable();
    let mut settings = three_dof(3.0);
    settings.inclination_deg = 85.0;
    settings.weathercock_coefficient = 0.5;
    settings.rtol = 1e-12;
    settings.atol = [1e-12; 13];
    let whole = simulate(&atm, &rocket, &settings).unwrap();
    // A stored point of the coast, a few seconds before apogee.
    let p = *whole
        .points
        .iter()
        .find(|p| p.t > rocket.burn_time + 2.0)
        .expect("a coast point");
    assert!(matches!(p.phase, PhaseKind::PointMass { .. }));
    let resumed = simulate_from(
        &atm,
        &rocket,
        &settings,
        p.t,
        p.state,
        p.configuration,
        Vec::new(),
    )
    .unwrap();
    assert!(matches!(
        resumed.points[0].phase,
        PhaseKind::PointMass { weathercock } if weathercock.to_bits() == 0.5f64.to_bits()
    ));
    let (a, b) = (whole.apogee.unwrap().1[2], resumed.apogee.unwrap().1[2]);
    let error = (a - b).abs() / (a - atm.elevation);
    assert!(error < 1e-9, "apogee {a} vs resumed {b}: {error:e}");
}

#[test]
fn a_negative_weathercock_coefficient_is_refused() {
    let atm = MockAtmosphere::default();
    let rocket = MockRocket::stable();
    let mut settings = three_dof(3.0);
    settings.weathercock_coefficient = -1.0;
    let error = simulate(&atm, &rocket, &settings).unwrap_err();
    assert!(error.to_string().contains("weathercock_coeff"), "{error}");
}
