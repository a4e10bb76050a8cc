//! The 3-DOF point-mass mode (`[flight] simulation_mode = "3 DOF"`, docs/physics.md §8.5) against
//! RocketPy 1.13's own `simulation_mode="3 DOF"` on the Calisto validation mission: the
//! summary within the parity tolerances of the 6-DOF flights (`karman_validation`: apogee
//! 0.1 %, apogee time 0.2 %, rail-exit velocity, largest speed and Mach number 0.5 %, impact
//! point 1 % of its distance, parachute triggers 0.1 % of their time), and the right-hand side
//! at a test state.
//!
//! The RocketPy figures below were measured for this test (RocketPy 1.13.0, Python 3.11,
//! numpy 2) by a script that rebuilds the Calisto mission (`fixtures/validation/calisto/
//! mission.toml`) line by line as RocketPy objects — standard atmosphere, the `SolidMotor`,
//! the `Rocket` with its nose, fins with the NACA 0012 airfoil, tail, rail buttons and both
//! parachutes with noise (0, 0, 0) — and flies `Flight(rocket, env, rail_length=5.2,
//! inclination=85, heading=0, simulation_mode="3 DOF")`. The weathercocking run sets
//! `rocket.weathercock_coeff = 1.0` on that `Rocket` (RocketPy's 3-DOF equations read the
//! attribute with `getattr`, where `PointMassRocket` stores its argument). The same script in
//! `"6 DOF"` reproduces `reference.json` exactly (apogee 3305.477453854797 m).

use karman_mission::Override;
use karman_mission::assemble::flight::simulate;
use karman_mission::report::flight::{SummaryComparison, flight_summary};
use karman_validation::{IMPACT_FRACTION, PARACHUTE_TRIGGER_FRACTION, SUMMARY_PARITY};

/// RocketPy 1.13.0's 3-DOF Calisto flight with one weathercock coefficient.
struct Reference {
    /// `weathercock_coeff`, 1/s.
    weathercock: f64,
    /// Summary keys (mission-format.md) and values.
    summary: [(&'static str, f64); 5],
    /// Impact time, s, and point east and north of the pad, m.
    impact: [f64; 3],
    /// Trigger times of the drogue and the main parachute, s.
    triggers: [(&'static str, f64); 2],
}

/// The measured figures (module documentation).
const REFERENCES: [Reference; 2] = [
    Reference {
        weathercock: 0.0,
        summary: [
            ("apogee_agl_m", 3326.5998013418066),
            ("apogee_time_s", 25.990001386352056),
            ("out_of_rail_velocity_mps", 26.207270098401477),
            ("max_speed_mps", 285.8855407326758),
            ("max_mach", 0.8599387108603432),
        ],
        impact: [299.1127181597609, 0.9065935508342247, 386.66178368639254],
        triggers: [
            ("parachute:drogue", 25.990476190476194),
            ("parachute:main", 159.22857142857146),
        ],
    },
    Reference {
        weathercock: 1.0,
        summary: [
            ("apogee_agl_m", 3318.5419580158477),
            ("apogee_time_s", 25.97615250920422),
            ("out_of_rail_velocity_mps", 26.207270098401477),
            ("max_speed_mps", 285.88820752379587),
            ("max_mach", 0.8599675682607808),
        ],
        impact: [298.8903670576918, 0.9087915889590139, 536.5183981115861],
        triggers: [
            ("parachute:drogue", 25.980952380952385),
            ("parachute:main", 159.00000000000003),
        ],
    },
];

/// The Calisto validation mission with parachute noise zeroed, RocketPy 1.13's equations and
/// `overrides`; `None` without the validation folder.
fn calisto(overrides: &[(&str, &str)]) -> Option<karman_mission::Mission> {
    let path = crate::common::validation_dir()?.join("calisto/mission.toml");
    let nominal = karman_mission::load(&path, &[]).expect("Calisto loads");
    let mut items = nominal.parachute_noise_off().expect("noise overrides");
    items.push(Override::new("flight.equations", "\"rocketpy_1_13\"").expect("override"));
    for (p, v) in overrides {
        items.push(Override::new(p, v).expect("override parses"));
    }
    Some(karman_mission::load(&path, &items).expect("Calisto loads with overrides"))
}

#[test]
fn validate_flight_3dof() {
    let mut failures = Vec::new();
    for reference in &REFERENCES {
        let coefficient = reference.weathercock.to_string();
        let mut overrides = vec![("flight.simulation_mode", "\"3 DOF\"")];
        if reference.weathercock > 0.0 {
            overrides.push(("flight.weathercock_coeff", &coefficient));
        }
        let Some(mission) = calisto(&overrides) else {
            println!("validate_flight_3dof: skipped, the validation folder is absent");
            return;
        };
        let run = simulate(&mission).expect("Calisto flies in 3 DOF");
        let summary = flight_summary(&run);
        let theirs = |k: &str| {
            reference
                .summary
                .iter()
                .find(|(key, _)| *key == k)
                .map(|(_, v)| *v)
        };
        let comparison = SummaryComparison::new(&summary, theirs);
        let name = format!("Calisto 3 DOF, weathercock_coeff {coefficient}");
        println!("== {name}\n{comparison}");
        for tolerance in SUMMARY_PARITY {
            let error = comparison
                .get(tolerance.key)
                .and_then(|v| v.relative_error)
                .unwrap_or(f64::INFINITY);
            println!("{name}: {} off by {:.4} %", tolerance.key, 100.0 * error);
            let within = error <= tolerance.relative; // false for NaN
            if !within {
                failures.push(format!(
                    "{name}: {} off by {:.4} % (limit {} %)",
                    tolerance.key,
                    100.0 * error,
                    100.0 * tolerance.relative
                ));
            }
        }
        let [t_impact, x_impact, y_impact] = reference.impact;
        let (x, y) = (
            summary.impact_x_m.unwrap_or(f64::NAN),
            summary.impact_y_m.unwrap_or(f64::NAN),
        );
        let miss = (x - x_impact).hypot(y - y_impact);
        let distance = x_impact.hypot(y_impact);
        let t = summary.impact_time_s.unwrap_or(f64::NAN);
        println!(
            "{name}: impact at {t:.4} s (RocketPy {t_impact:.4} s), ({x:.3}, {y:.3}) m, \
             {miss:.3} m from RocketPy's ({:.3} % of {distance:.1} m)",
            100.0 * miss / distance
        );
        let within = miss <= IMPACT_FRACTION * distance; // false for NaN
        if !within {
            failures.push(format!("{name}: impact point {miss:.2} m off"));
        }
        for (event, t_ref) in reference.triggers {
            let t = summary
                .events
                .iter()
                .find(|e| e.name == event)
                .map_or(f64::NAN, |e| e.time_s);
            let within = (t - t_ref).abs() <= PARACHUTE_TRIGGER_FRACTION * t_ref;
            if !within {
                failures.push(format!("{name}: {event} at {t} s, RocketPy {t_ref} s"));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "3-DOF validation failures:\n{}",
        failures.join("\n")
    );
}

/// RocketPy 1.13's `Flight.u_dot_generalized_3dof` at the 6-DOF derivative test state of
/// docs/physics.md §13 (`validate_flight::validate_equations_of_motion_vectors`), measured on the
/// 3-DOF flights of the module documentation (the airfoil fins of the mission as it is).
#[test]
fn validate_point_mass_vectors() {
    use karman_mission::dynamics::Configuration;
    use karman_mission::dynamics::equations::{Cursors, Equations};
    let Some(mission) = calisto(&[]) else {
        println!("validate_point_mass_vectors: skipped, the validation folder is absent");
        return;
    };
    let env = karman_mission::assemble::environment::build_environment(&mission).expect("env");
    let motor = karman_mission::assemble::motor::build_motor(&mission).expect("motor");
    let rocket = karman_mission::assemble::rocket::build_rocket(&mission, &motor).expect("rocket");
    let eq = Equations::new(
        &env,
        &rocket,
        karman_mission::dynamics::EquationsForm::RocketPy113,
    );
    let (configuration, cursors) = (&Configuration::default(), &mut Cursors::default());
    let e = [0.9230002039, -0.0402990592, 0.0166924169, 0.3823192025];
    let state = [
        1.0, 50.0, 1900.0, 3.0, 40.0, 150.0, e[0], e[1], e[2], e[3], 0.1, -0.2, 3.0,
    ];
    // Relative tolerance 1e-4 of the largest component, as for the 6-DOF vectors (the model
    // tables agree with RocketPy's to ~1e-6).
    let check = |what: &str, ours: &[f64], theirs: &[f64]| {
        let scale = theirs.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let worst = ours
            .iter()
            .zip(theirs)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        println!(
            "{what}: ours {ours:?}, theirs {theirs:?}, worst/max {:.2e}",
            worst / scale
        );
        assert!(worst <= 1e-4 * scale, "{what}: {ours:?} vs {theirs:?}");
    };
    let weathercock_rate = [
        -0.0033132675441224523,
        -0.07588630299652967,
        0.04187968294401964,
        -0.0018285064440816457,
    ];
    for (t, acceleration) in [
        (
            2.0,
            [-1.3172430247411546, -2.380316948485822, 97.01611546845447],
        ),
        (
            5.0,
            [-1.4060769883284898, -12.73700859479294, -12.32366420397588],
        ),
    ] {
        let held = eq.point_mass(t, &state, 0.0, configuration, cursors).u_dot;
        check(
            &format!("3-DOF t={t} acceleration"),
            &held[3..6],
            &acceleration,
        );
        assert_eq!(held[6..13], [0.0; 7], "the attitude is held");
        let turned = eq.point_mass(t, &state, 1.0, configuration, cursors).u_dot;
        check(
            &format!("3-DOF t={t} weathercock quaternion rate"),
            &turned[6..10],
            &weathercock_rate,
        );
        assert_eq!(turned[3..6], held[3..6]);
    }
}
