//! Dimensional analysis of the flight engine (`karman_math::dimensions`): a Calisto-like
//! rocket (docs/physics.md §13: M1670-like solid motor, von Kármán nose, canted fins with an
//! airfoil, tail, drogue and main parachutes with trigger noise, rail buttons) over the ISA
//! with a wind profile, built directly through the crate APIs from inputs in a random unit
//! system, with the flight settings of that system — rail length, `atol` of each state in its
//! unit, step bounds and `max_time` scaled.
//!
//! - The equations of motion (rail, 6-DOF, parachute) evaluated at scaled states give every
//!   derivative, force and moment scaled by its unit, to rounding.
//! - A whole flight gives the same dimensionless results (Mach, margins) and every
//!   dimensional one (apogee, its time, impact point and distance, out-of-rail velocity, …)
//!   scaled by its unit, to rounding (tolerance 1e-9).

use karman_airframe::{
    Airfoil, AngleUnit, CoordinateSystem, MotorProperties, NoseConeSpec, NoseKind, Parachute,
    ParachuteSpec, RailButtons, Rocket, RocketInputs, SurfaceInput, SurfaceSpec, Sweep, TailSpec,
    TrapezoidalFinsSpec, TriggerKind,
};
use karman_atmos::{Atmosphere, Curve, Datum, Environment, EnvironmentConfig, Gravity, Profiles};
use karman_dynamics::equations::{CanopyState, Cursors, Equations};
use karman_dynamics::state::State;
use karman_dynamics::{
    Configuration, DEFAULT_ATOL, EquationsForm, Flight, FlightSettings, PhaseKind, Summary,
    simulate,
};
use karman_math::dimensions::{Dimension, ScaledComparison, test_seeds};
use karman_math::{PhysicalConstants, Table1, Units};
use karman_propulsion::{
    BatesGrains, BurnTime, Motor, MotorStructure, ThrustCurve, ThrustData, ThrustOptions,
    ThrustSource,
};

/// Agreement required between unit systems: rounding only, as for the model crates.
const TOL: f64 = 1e-9;

const L: Dimension = Dimension::LENGTH;
const T: Dimension = Dimension::TIME;
const M: Dimension = Dimension::MASS;
const V: Dimension = Dimension::VELOCITY;

/// A Cesaroni M1670-like thrust curve (s, N).
const CURVE: [[f64; 2]; 9] = [
    [0.0, 0.0],
    [0.055, 100.0],
    [0.092, 1500.0],
    [0.1, 2000.0],
    [0.15, 2200.0],
    [0.8, 1900.0],
    [2.0, 1600.0],
    [3.4, 500.0],
    [3.9, 0.0],
];

fn environment(u: &Units, c: &PhysicalConstants) -> Environment {
    let wind = |pairs: &[[f64; 2]]| {
        Curve::Points(
            pairs
                .iter()
                .map(|[h, w]| [u.scale(*h, L), u.scale(*w, V)])
                .collect(),
        )
    };
    let config = EnvironmentConfig {
        earth_model: None,
        latitude_deg: 32.990254,
        longitude_deg: -106.974998,
        elevation: u.scale(1400.0, L),
        datum: Datum::Sirgas2000,
        gravity: Gravity::Somigliana,
        atmosphere: Atmosphere::Profiles(Profiles::wind_only(
            "winds",
            wind(&[[0.0, 2.0], [2000.0, 6.0], [6000.0, 12.0]]),
            wind(&[[0.0, -1.0], [4000.0, 3.0]]),
        )),
    };
    Environment::new(&config, c).expect("valid environment")
}

fn motor(u: &Units, c: &PhysicalConstants) -> MotorProperties {
    let l = |v: f64| u.scale(v, L);
    let points: Vec<[f64; 2]> = CURVE
        .iter()
        .map(|[t, f]| [u.scale(*t, T), u.scale(*f, Dimension::FORCE)])
        .collect();
    let data = ThrustData::from_points("inline", &points).expect("valid points");
    let options = ThrustOptions {
        burn_time: Some(BurnTime::End(u.scale(3.9, T))),
        ..ThrustOptions::default()
    };
    let thrust =
        ThrustCurve::new(&ThrustSource::Data(Box::new(data)), &options).expect("valid curve");
    let i = |v: f64| u.scale(v, Dimension::INERTIA);
    let motor = Motor::solid_with(
        thrust,
        MotorStructure {
            dry_mass: u.scale(1.815, M),
            dry_inertia: [i(0.125), i(0.125), i(0.002), i(0.0), i(0.0), i(0.0)],
            center_of_dry_mass: l(0.317),
            nozzle_position: l(0.0),
            nozzle_radius: l(0.033),
            coordinate_system: karman_propulsion::CoordinateSystem::NozzleToCombustionChamber,
            reference_pressure: Some(u.scale(90_000.0, Dimension::PRESSURE)),
        },
        BatesGrains {
            number: 5,
            density: u.scale(1815.0, Dimension::DENSITY),
            outer_radius: l(0.033),
            initial_inner_radius: l(0.015),
            initial_height: l(0.12),
            separation: l(0.005),
            center_of_mass_position: l(0.397),
            throat_radius: l(0.011),
            only_radial_burn: false,
        },
        c,
    )
    .expect("valid motor");
    karman_mission::assemble::motor::motor_properties(&motor)
}

fn rocket(u: &Units, c: &PhysicalConstants) -> Rocket {
    let l = |v: f64| u.scale(v, L);
    // Drag vs Mach and lift vs angle (rad) are functions of pure numbers.
    let drag = |k: f64| {
        Table1::linear(
            vec![0.0, 0.3, 0.8, 1.0, 1.2, 2.0],
            vec![0.42 + k, 0.40 + k, 0.45 + k, 0.62 + k, 0.6 + k, 0.48 + k],
        )
        .expect("valid drag")
    };
    let parachute = |name: &str, cd_s: f64, trigger| {
        Parachute::new(&ParachuteSpec {
            name: name.to_owned(),
            cd_s: u.scale(cd_s, Dimension::AREA),
            trigger,
            // A sampling rate is a dimensional input: 105 Hz in the scaled unit of time.
            sampling_rate: Some(u.scale(105.0, Dimension::FREQUENCY)),
            lag: Some(u.scale(1.5, T)),
            noise: Some([0.0, u.scale(8.3, Dimension::PRESSURE), 0.5]),
            radius: Some(l(1.5)),
            height: Some(l(1.5)),
            porosity: Some(0.0432),
            drag_coefficient: None,
        })
        .expect("valid parachute")
    };
    let inputs = RocketInputs {
        radius: l(0.0635),
        mass: u.scale(14.426, M),
        inertia: [6.321, 6.321, 0.034, 0.0, 0.0, 0.0].map(|v| u.scale(v, Dimension::INERTIA)),
        center_of_mass_without_motor: l(0.0),
        coordinate_system: CoordinateSystem::TailToNose,
        power_off_drag: drag(0.0),
        power_on_drag: drag(-0.03),
        motor_position: l(-1.255),
        surfaces: vec![
            SurfaceInput {
                pod: None,
                name: "nose".into(),
                position: l(1.278),
                spec: SurfaceSpec::Nose(NoseConeSpec {
                    length: l(0.55829),
                    kind: NoseKind::VonKarman,
                    base_radius: None,
                    bluffness: 0.0,
                }),
            },
            SurfaceInput {
                pod: None,
                name: "fins".into(),
                position: l(-1.04956),
                spec: SurfaceSpec::TrapezoidalFins(TrapezoidalFinsSpec {
                    n: 4,
                    root_chord: l(0.12),
                    tip_chord: l(0.06),
                    span: l(0.11),
                    sweep: Sweep::Default,
                    cant_angle_deg: 0.5,
                    angular_position_deg: 0.0,
                    radius: None,
                    airfoil: Some(Airfoil {
                        lift_curve: Table1::linear(vec![-0.25, 0.0, 0.25], vec![-1.4, 0.0, 1.4])
                            .expect("valid lift curve"),
                        unit: AngleUnit::Radians,
                    }),
                }),
            },
            SurfaceInput {
                pod: None,
                name: "tail".into(),
                position: l(-1.194656),
                spec: SurfaceSpec::Tail(TailSpec {
                    top_radius: l(0.0635),
                    bottom_radius: l(0.0435),
                    length: l(0.06),
                    radius: None,
                }),
            },
        ],
        parachutes: vec![
            parachute("main", 10.0, TriggerKind::HeightAboveGround(l(800.0))),
            parachute("drogue", 1.0, TriggerKind::Apogee),
        ],
        rail_buttons: Some(RailButtons::new(l(0.0818), l(-0.6182), 45.0).expect("valid")),
        eccentricities: Default::default(),
    };
    Rocket::with_constants(inputs, motor(u, c), c).expect("valid rocket")
}

/// RocketPy's default settings with every dimensional one expressed in the units `u`.
fn settings(u: &Units) -> FlightSettings {
    let mut s = FlightSettings::new(u.scale(5.2, L));
    s.inclination_deg = 84.7;
    s.heading_deg = 53.0;
    s.max_time = u.scale(600.0, T);
    s.max_time_step = u.scale(s.max_time_step, T);
    s.rail_max_time_step = u.scale(s.rail_max_time_step, T);
    s.control_max_time_step = u.scale(s.control_max_time_step, T);
    s.min_time_step = u.scale(s.min_time_step, T);
    s.trigger_band = u.scale(s.trigger_band, L);
    // State: position (m), velocity (m/s), quaternion (1), angular velocity (1/s).
    let dims = [L, L, L, V, V, V]
        .into_iter()
        .chain([Dimension::NONE; 4])
        .chain([Dimension::FREQUENCY; 3]);
    for ((a, d), si) in s.atol.iter_mut().zip(dims).zip(DEFAULT_ATOL) {
        *a = u.scale(si, d);
    }
    s.noise_seed = 1234;
    s
}

fn fly(u: &Units) -> (Flight, Summary) {
    let c = PhysicalConstants::SI.in_units(u);
    let (env, rocket) = (environment(u, &c), rocket(u, &c));
    let flight = simulate(&env, &rocket, &settings(u)).expect("the rocket flies");
    let summary = flight.summary(&env, &rocket);
    (flight, summary)
}

fn compare(check: &mut ScaledComparison, si: &(Flight, Summary), sc: &(Flight, Summary)) {
    let ((fa, a), (fb, b)) = (si, sc);
    let mut opt = |name: &str, x: Option<f64>, y: Option<f64>, d: Dimension| match (x, y) {
        (Some(x), Some(y)) => {
            check.compare(name, x, y, d);
        }
        _ => panic!("{name}: {x:?} in SI, {y:?} in the scaled run"),
    };
    opt("apogee AGL", a.apogee_agl_m, b.apogee_agl_m, L);
    opt("apogee time", a.apogee_time_s, b.apogee_time_s, T);
    opt("apogee x", a.apogee_x_m, b.apogee_x_m, L);
    opt("apogee y", a.apogee_y_m, b.apogee_y_m, L);
    opt(
        "out-of-rail time",
        a.out_of_rail_time_s,
        b.out_of_rail_time_s,
        T,
    );
    opt(
        "out-of-rail velocity",
        a.out_of_rail_velocity_mps,
        b.out_of_rail_velocity_mps,
        V,
    );
    opt(
        "out-of-rail stability margin",
        a.out_of_rail_stability_margin,
        b.out_of_rail_stability_margin,
        Dimension::NONE,
    );
    opt("impact time", a.impact_time_s, b.impact_time_s, T);
    opt("impact x", a.impact_x_m, b.impact_x_m, L);
    opt("impact y", a.impact_y_m, b.impact_y_m, L);
    opt(
        "impact velocity",
        a.impact_velocity_mps,
        b.impact_velocity_mps,
        V,
    );
    let impact_distance = |s: &Summary| s.impact_x_m.zip(s.impact_y_m).map(|(x, y)| x.hypot(y));
    opt("impact distance", impact_distance(a), impact_distance(b), L);
    check.compare("max speed", a.max_speed_mps, b.max_speed_mps, V);
    check.compare("max Mach", a.max_mach, b.max_mach, Dimension::NONE);
    check.compare(
        "max dynamic pressure",
        a.max_dynamic_pressure_pa,
        b.max_dynamic_pressure_pa,
        Dimension::PRESSURE,
    );
    check.compare(
        "initial static margin",
        a.initial_static_margin,
        b.initial_static_margin,
        Dimension::NONE,
    );
    check.compare(
        "burn-out static margin",
        a.burnout_static_margin,
        b.burnout_static_margin,
        Dimension::NONE,
    );
    assert_eq!(
        a.events.len(),
        b.events.len(),
        "events {:?} vs {:?}",
        a.events,
        b.events
    );
    for (x, y) in a.events.iter().zip(&b.events) {
        assert_eq!(x.name, y.name);
        check.compare(&format!("event {}", x.name), x.time_s, y.time_s, T);
    }
    for (x, y) in fa.parachute_events.iter().zip(&fb.parachute_events) {
        check.compare(
            &format!("{} trigger", x.name),
            x.trigger_time,
            y.trigger_time,
            T,
        );
    }
    check.compare("final time", fa.t_final, fb.t_final, T);
    println!(
        "steps: SI {} ({} rejected), scaled {} ({} rejected)",
        fa.stats.steps, fa.stats.rejected_steps, fb.stats.steps, fb.stats.rejected_steps
    );
}

/// Dimensions of the state `u = (r, v, e, ω)` and of its derivative.
const STATE: [Dimension; 13] = [
    L,
    L,
    L,
    V,
    V,
    V,
    Dimension::NONE,
    Dimension::NONE,
    Dimension::NONE,
    Dimension::NONE,
    Dimension::FREQUENCY,
    Dimension::FREQUENCY,
    Dimension::FREQUENCY,
];

fn scale_state(u: &Units, x: &State) -> State {
    let mut y = *x;
    for (v, d) in y.iter_mut().zip(STATE) {
        *v = u.scale(*v, d);
    }
    y
}

/// The right-hand side of a phase, its loads, in SI or in the scaled units.
fn evaluate<A, B>(
    eq: &Equations<'_, A, B>,
    u: &Units,
    phase: &PhaseKind,
    t: f64,
    x: &State,
) -> karman_dynamics::equations::Derivative
where
    A: karman_dynamics::AtmosphereModel,
    B: karman_dynamics::VehicleModel,
{
    let (t, x) = (u.scale(t, T), scale_state(u, x));
    let (configuration, cursors) = (&Configuration::default(), &mut Cursors::default());
    match phase {
        PhaseKind::Rail => eq.rail(t, &x, configuration, cursors),
        PhaseKind::SixDof => eq.six_dof(t, &x, configuration, cursors),
        PhaseKind::PointMass { weathercock } => eq.point_mass(
            t,
            &x,
            u.scale(*weathercock, Dimension::FREQUENCY),
            configuration,
            cursors,
        ),
        PhaseKind::Parachute(c) => eq.parachute(
            t,
            &x,
            &CanopyState {
                cd_s: u.scale(c.cd_s, Dimension::AREA),
                radius: u.scale(c.radius, L),
                height: u.scale(c.height, L),
                added_mass_coefficient: c.added_mass_coefficient,
            },
            cursors,
        ),
    }
}

/// The equations of motion at the states of an SI flight, in both unit systems. Each state
/// is evaluated at 0.37 of the way to the next solution point, off the table nodes: at a node
/// the one-sided slopes of the tables (RocketPy's `bisect_left` convention) would pick an
/// interval by the rounding of the scaled time, which is not a dimensional matter.
///
/// The 6-DOF loads take the angle of attack as an arctangent of the transverse and axial
/// flow (equations.rs), exact to rounding at any incidence, so every quantity of every phase
/// agrees to [`TOL`].
#[test]
fn equations_of_motion_scale_with_their_units() {
    let si_c = PhysicalConstants::SI;
    let (env, vehicle) = (environment(&Units::SI, &si_c), rocket(&Units::SI, &si_c));
    let flight = simulate(&env, &vehicle, &settings(&Units::SI)).expect("the rocket flies");
    let eq = Equations::new(&env, &vehicle, EquationsForm::Standard);
    for seed in test_seeds(3) {
        let mut check = ScaledComparison::new(seed, TOL);
        let u = *check.units();
        let c = PhysicalConstants::SI.in_units(&u);
        let (env_s, vehicle_s) = (environment(&u, &c), rocket(&u, &c));
        let eq_s = Equations::new(&env_s, &vehicle_s, EquationsForm::Standard);
        let mut counts = [0usize; 4];
        let (mut worst_lift, mut worst_other) = (0.0f64, 0.0f64);
        for pair in flight.points.windows(2) {
            let (p, next) = (&pair[0], &pair[1]);
            let t = p.t + 0.37 * (next.t - p.t);
            // The 6-DOF states are also flown through the 3-DOF point-mass equations, with
            // weathercocking (a rate, 1/s).
            let point_mass = PhaseKind::PointMass { weathercock: 0.5 };
            let kinds: &[PhaseKind] = match p.phase {
                PhaseKind::SixDof => &[PhaseKind::SixDof, point_mass],
                _ => std::slice::from_ref(&p.phase),
            };
            for &phase in kinds {
                let (a, b) = (
                    evaluate(&eq, &Units::SI, &phase, t, &p.state),
                    evaluate(&eq_s, &u, &phase, t, &p.state),
                );
                let k = match phase {
                    PhaseKind::Rail => 0,
                    PhaseKind::SixDof => 1,
                    PhaseKind::Parachute(_) => 2,
                    PhaseKind::PointMass { .. } => 3,
                };
                counts[k] += 1;
                let (tolerance, worst) = match phase {
                    PhaseKind::SixDof => (TOL, &mut worst_lift),
                    _ => (TOL, &mut worst_other),
                };
                let name = |q: &str| format!("{:?} t = {t:.4} s: {q}", phase);
                // Components that vanish (a rate of a frozen attitude) come out as rounding noise
                // of the size of their group.
                let size = |r: std::ops::Range<usize>| {
                    a.u_dot[r].iter().fold(0.0f64, |m, v| m.max(v.abs()))
                };
                let groups = [
                    (0..3, size(0..3)),
                    (3..6, size(3..6)),
                    (6..10, size(6..10)),
                    (10..13, size(10..13)),
                ];
                for (range, magnitude) in groups {
                    for i in range {
                        *worst = worst.max(check.record(
                            &name(&format!("u̇[{i}]")),
                            a.u_dot[i],
                            b.u_dot[i],
                            STATE[i] / T,
                            magnitude,
                            tolerance,
                        ));
                    }
                }
                let fmax = a.force.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let mmax = a.moment.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                for i in 0..3 {
                    let (force, torque) = (Dimension::FORCE, Dimension::FORCE * L);
                    *worst = worst.max(check.record(
                        &name("force"),
                        a.force[i],
                        b.force[i],
                        force,
                        fmax,
                        tolerance,
                    ));
                    *worst = worst.max(check.record(
                        &name("moment"),
                        a.moment[i],
                        b.moment[i],
                        torque,
                        mmax,
                        tolerance,
                    ));
                }
                check.compare_near(
                    &name("net thrust"),
                    a.net_thrust,
                    b.net_thrust,
                    Dimension::FORCE,
                    1.0,
                );
            }
        }
        assert!(
            counts.iter().all(|&n| n > 0),
            "every phase is exercised: {counts:?}"
        );
        let worst = check.finish().unwrap_or_else(|e| panic!("{e}"));
        println!(
            "dynamics (equations): seed {seed}: {counts:?} states, largest relative deviation \
             {worst:e} ({}); derivatives and loads: rail, parachute and 3-DOF {worst_other:e}, \
             6-DOF {worst_lift:e}",
            check.worst().1
        );
    }
}

/// The same check detects a dimensionally wrong formula: the drag acceleration of the
/// parachute phase written with `|v|` instead of `|v|²`, `½ρ C_D S |v| / m`, does not scale
/// as an acceleration.
#[test]
fn a_dimensionally_wrong_formula_is_detected() {
    for seed in test_seeds(3) {
        let mut check = ScaledComparison::new(seed, TOL);
        let u = *check.units();
        let c = PhysicalConstants::SI.in_units(&u);
        let (env, env_s) = (
            environment(&Units::SI, &PhysicalConstants::SI),
            environment(&u, &c),
        );
        let wrong = |e: &Environment, u: &Units| {
            let (z, v) = (u.scale(2500.0, L), u.scale(-24.0, V));
            let (cd_s, m) = (u.scale(10.0, Dimension::AREA), u.scale(16.2, M));
            0.5 * e.density(z) * cd_s * v.abs() / m
        };
        check.compare(
            "wrong drag",
            wrong(&env, &Units::SI),
            wrong(&env_s, &u),
            Dimension::ACCELERATION,
        );
        // ½ρSv/m scales as 1/T, an acceleration as L/T²: equal only if λ_L = λ_T.
        if (u.length / u.time - 1.0).abs() > 1e-6 {
            let e = check.finish().expect_err("a rate is not an acceleration");
            assert!(
                e.contains("wrong drag") && e.contains(&seed.to_string()),
                "{e}"
            );
        }
    }
}

/// A whole flight in two unit systems: the integrator's first step is chosen in a
/// dimensionally consistent way and the parachute sampling instants of a step are selected
/// by their time keys, so both runs take the same steps and agree to rounding.
#[test]
fn flight_scales_with_its_units() {
    let si = fly(&Units::SI);
    for seed in test_seeds(2) {
        let mut check = ScaledComparison::new(seed, TOL);
        let units = *check.units();
        let sc = fly(&units);
        compare(&mut check, &si, &sc);
        let worst = check.finish().unwrap_or_else(|e| panic!("{e}"));
        println!(
            "dynamics (flight): seed {seed}: largest relative deviation {worst:e} ({})",
            check.worst().1
        );
    }
}
