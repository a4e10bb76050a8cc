//! Every validation mission flown with parachute noise zeroed, against RocketPy 1.13's
//! `reference.json` `summary` — the acceptance of the dynamics issue: apogee within 0.1 %,
//! apogee time within 0.2 %, rail-exit velocity, max speed and max Mach within 0.5 %, impact
//! point within 1 % of the impact distance; plus the same events in the same order, parachute
//! triggers within 0.1 % of their time. The tolerances are `karman_validation`'s, which
//! `cargo xtask validate` applies too.

use crate::common::{calisto_with, flight_name, load_reference, validation_missions};
use karman_mission::Override;
use karman_mission::assemble::flight::simulate;
use karman_mission::report::flight::{SummaryComparison, flight_summary};
use karman_validation::{IMPACT_FRACTION, PARACHUTE_TRIGGER_FRACTION, SUMMARY_PARITY};
use serde_json::Value;

#[test]
fn validate_flight() {
    let Some(missions) = validation_missions() else {
        println!("validate_flight: skipped, the validation folder is absent");
        return;
    };
    assert!(!missions.is_empty(), "no validation mission found");
    let failures = compare_with_references(&missions);
    assert!(
        failures.is_empty(),
        "flight validation failures:\n{}",
        failures.join("\n")
    );
}

/// The further flights of `fixtures/parity` (hybrid and liquid motors that are not among the
/// validation flights), against the RocketPy 1.13 references its `make_references.py` wrote,
/// with the same tolerances.
#[test]
fn validate_further_flights() {
    let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/parity");
    let mut missions: Vec<_> = std::fs::read_dir(&folder)
        .expect("fixtures/parity is in the repository")
        .filter_map(|e| Some(e.ok()?.path().join("mission.toml")))
        .filter(|p| p.is_file())
        .collect();
    missions.sort();
    assert!(missions.len() >= 2, "fixtures/parity: {missions:?}");
    let failures = compare_with_references(&missions);
    assert!(
        failures.is_empty(),
        "further flight failures:\n{}",
        failures.join("\n")
    );
}

/// The misaligned Calistos of `fixtures/parity` (a thrust, a centre-of-pressure and a
/// centre-of-mass eccentricity): beyond the summary's parity (`validate_further_flights`), the
/// roll rate at burn-out within 1 % of RocketPy 1.13's `w3` there, and each flight visibly
/// moved from the aligned Calisto's (its impact point more than 1 % of the range away, so that
/// an eccentricity the equations ignored would fail the summary's parity).
#[test]
fn validate_eccentric_flights() {
    let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/parity");
    let aligned = load_reference(&folder.join("../validation/calisto/mission.toml"));
    let aligned = &aligned["summary"];
    let at = |v: &Value, k: &str| v[k].as_f64().expect("a number");
    let mut failures = Vec::new();
    for name in [
        "calisto_thrust_eccentricity",
        "calisto_cp_eccentricity",
        "calisto_cm_eccentricity",
    ] {
        let path = folder.join(name).join("mission.toml");
        let reference = load_reference(&path);
        let nominal = karman_mission::load(&path, &[]).expect("mission loads");
        let mut quiet = nominal.parachute_noise_off().expect("noise overrides");
        quiet.push(Override::new("flight.equations", "\"rocketpy_1_13\"").expect("override"));
        let mission = karman_mission::load(&path, &quiet).expect("mission loads");
        let run = simulate(&mission).expect("mission flies");
        let burn_out = run.rocket.burn_out();
        let point = run
            .flight
            .points
            .iter()
            .min_by(|a, b| (a.t - burn_out).abs().total_cmp(&(b.t - burn_out).abs()))
            .expect("points");
        assert!(
            (point.t - burn_out).abs() < 1e-9,
            "{name}: a point at burn-out"
        );
        let roll = point.state[12];
        let theirs = at(&reference, "roll_rate_at_burnout_rad_s");
        let error = (roll - theirs).abs() / theirs.abs();
        println!(
            "{name}: roll rate at burn-out {roll:.6} rad/s vs {theirs:.6} ({:.4} %)",
            100.0 * error
        );
        if error > 0.01 {
            failures.push(format!(
                "{name}: roll rate at burn-out off by {:.3} %",
                100.0 * error
            ));
        }
        let summary = &reference["summary"];
        let moved = (at(summary, "impact_x_m") - at(aligned, "impact_x_m"))
            .hypot(at(summary, "impact_y_m") - at(aligned, "impact_y_m"));
        let range = at(aligned, "impact_x_m").hypot(at(aligned, "impact_y_m"));
        println!("{name}: impact {moved:.1} m from the aligned flight's ({range:.1} m away)");
        if moved < IMPACT_FRACTION * range {
            failures.push(format!("{name}: the eccentricity barely moves the flight"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Flies each mission as RocketPy 1.13 would (parachute noise zeroed, its equations) and
/// compares the summary with the `reference.json` beside it; returns the misses.
fn compare_with_references(missions: &[std::path::PathBuf]) -> Vec<String> {
    let mut failures = Vec::new();
    for path in missions {
        let path = path.as_path();
        let name = flight_name(path);
        let nominal = karman_mission::load(path, &[]).expect("mission loads");
        let mut quiet = nominal.parachute_noise_off().expect("noise overrides");
        // The references are RocketPy 1.13's: its form of the equations.
        quiet.push(
            karman_mission::Override::new("flight.equations", "\"rocketpy_1_13\"")
                .expect("override parses"),
        );
        let mission = karman_mission::load(path, &quiet).expect("mission loads with overrides");
        let run = simulate(&mission).expect("mission flies");
        let summary = flight_summary(&run);
        let reference = load_reference(path);
        let reference = &reference["summary"];
        let comparison = SummaryComparison::new(&summary, |k| reference.get(k)?.as_f64());
        println!(
            "== {name}: {} steps, {} evaluations\n{comparison}",
            run.flight.stats.steps, run.flight.stats.evaluations
        );
        let mut line = format!("{name:>16}:");
        for karman_validation::Tolerance {
            key,
            relative: tolerance,
        } in SUMMARY_PARITY
        {
            let error = comparison
                .get(key)
                .and_then(|v| v.relative_error)
                .unwrap_or(f64::INFINITY);
            line += &format!(" {key} {:.4} %", 100.0 * error);
            let within = error <= tolerance; // false for NaN
            if !within {
                failures.push(format!(
                    "{name}: {key} off by {:.4} % (limit {} %)",
                    100.0 * error,
                    100.0 * tolerance
                ));
            }
        }
        let impact = |s: &str| reference.get(s).and_then(Value::as_f64);
        if let (Some(rx), Some(ry)) = (impact("impact_x_m"), impact("impact_y_m")) {
            let (x, y) = (
                summary.impact_x_m.unwrap_or(f64::NAN),
                summary.impact_y_m.unwrap_or(f64::NAN),
            );
            let miss = (x - rx).hypot(y - ry);
            let distance = rx.hypot(ry);
            line += &format!(
                " impact miss {miss:.2} m ({:.3} % of {distance:.1} m)",
                100.0 * miss / distance
            );
            let within = miss <= IMPACT_FRACTION * distance; // false for NaN
            if !within {
                failures.push(format!(
                    "{name}: impact point {miss:.2} m from the reference ({distance:.1} m away)"
                ));
            }
        }
        // Events: same names in the same order; parachute triggers within
        // PARACHUTE_TRIGGER_FRACTION of their time.
        let theirs: Vec<(String, f64)> = reference["events"]
            .as_array()
            .map(|a| {
                a.iter()
                    .filter_map(|e| Some((e["name"].as_str()?.to_owned(), e["time_s"].as_f64()?)))
                    .collect()
            })
            .unwrap_or_default();
        let ours: Vec<(String, f64)> = summary
            .events
            .iter()
            .map(|e| (e.name.clone(), e.time_s))
            .collect();
        let names = |v: &[(String, f64)]| v.iter().map(|e| e.0.clone()).collect::<Vec<_>>();
        if names(&ours) != names(&theirs) {
            failures.push(format!(
                "{name}: events {:?} vs reference {:?}",
                names(&ours),
                names(&theirs)
            ));
        }
        for ((event, t), (_, t_ref)) in ours.iter().zip(&theirs) {
            line += &format!(" {event} {:+.4} s", t - t_ref);
            if event.starts_with("parachute:")
                && (t - t_ref).abs() > PARACHUTE_TRIGGER_FRACTION * t_ref
            {
                failures.push(format!(
                    "{name}: {event} at {t:.4} s, reference {t_ref:.4} s"
                ));
            }
        }
        println!("{line}");
    }
    failures
}

/// The right-hand sides at the derivative test vectors of docs/physics.md §13, measured in
/// RocketPy 1.13 on Calisto with plain (no airfoil) fins: the validation Calisto mission with
/// its `airfoil` line removed.
#[test]
fn validate_equations_of_motion_vectors() {
    use karman_dynamics::Configuration;
    use karman_dynamics::equations::{CanopyState, Cursors, Equations};
    let Some(dir) = crate::common::validation_dir() else {
        println!("validate_equations_of_motion_vectors: skipped, the validation folder is absent");
        return;
    };
    let path = dir.join("calisto/mission.toml");
    let text = std::fs::read_to_string(&path).expect("calisto mission");
    let plain: String = text
        .lines()
        .filter(|l| !l.trim_start().starts_with("airfoil"))
        .map(|l| format!("{l}\n"))
        .collect();
    assert_ne!(
        plain.len(),
        text.len(),
        "the Calisto mission has an airfoil line to remove"
    );
    let mission = karman_mission::parse(&plain, &path, &[]).expect("plain-fin Calisto parses");
    let env = karman_mission::assemble::environment::build_environment(&mission).expect("env");
    let motor = karman_mission::assemble::motor::build_motor(&mission).expect("motor");
    let rocket = karman_mission::assemble::rocket::build_rocket(&mission, &motor).expect("rocket");
    let eq = Equations::new(&env, &rocket, karman_dynamics::EquationsForm::RocketPy113);
    let (configuration, cursors) = (&Configuration::default(), &mut Cursors::default());

    let e = [0.9230002039, -0.0402990592, 0.0166924169, 0.3823192025];
    let rail_state = [
        0.0, 0.0, 1400.0, 0.0, 0.0, 0.0, e[0], e[1], e[2], e[3], 0.0, 0.0, 0.0,
    ];
    let state = [
        1.0, 50.0, 1900.0, 3.0, 40.0, 150.0, e[0], e[1], e[2], e[3], 0.1, -0.2, 3.0,
    ];
    // Relative tolerance 1e-4 of the largest component: the vectors are RocketPy's, and the
    // model tables (ISA spline, motor regression, fin slopes) agree with RocketPy's to ~1e-6,
    // which the derivatives amplify (ω̇ divides by the small I33).
    let check = |what: &str, ours: &[f64], theirs: &[f64]| {
        let scale = theirs.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let worst = ours
            .iter()
            .zip(theirs)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        println!(
            "{what}: ours {ours:?}\n{:>w$}theirs {theirs:?}, worst |diff| / max {:.2e}",
            "",
            worst / scale,
            w = what.len() + 2
        );
        assert!(worst <= 1e-4 * scale, "{what}: {ours:?} vs {theirs:?}");
    };

    let rail = eq.rail(0.2, &rail_state, configuration, cursors).u_dot;
    check(
        "rail t=0.2 acceleration",
        &rail[3..6],
        &[0.0, 7.3748643, 84.29508468],
    );
    assert!(
        rail[6..].iter().all(|v| v.abs() < f64::MIN_POSITIVE),
        "attitude frozen on the rail"
    );

    let d2 = eq.six_dof(2.0, &state, configuration, cursors).u_dot;
    check(
        "6-DOF t=2 acceleration",
        &d2[3..6],
        &[-1.32671843, -1.80766570, 96.9709188],
    );
    check(
        "6-DOF t=2 quaternion rate",
        &d2[6..10],
        &[-0.569794609, 0.109420556, -0.0127354715, 1.38769559],
    );
    check(
        "6-DOF t=2 angular acceleration",
        &d2[10..13],
        &[-7.62683550, 8.57087767, 26.7949713],
    );

    let d10 = eq.six_dof(10.0, &state, configuration, cursors).u_dot;
    check(
        "6-DOF t=10 acceleration",
        &d10[3..6],
        &[-1.41997172, -12.7260578, -12.3242761],
    );
    check(
        "6-DOF t=10 angular acceleration",
        &d10[10..13],
        &[-7.41447692, 8.31163979, 27.5081482],
    );

    let canopy = CanopyState {
        cd_s: 1.0,
        radius: 0.4768272,
        height: 0.4768272,
        added_mass_coefficient: 0.99999941,
    };
    let dp = eq.parachute(30.0, &state, &canopy, cursors).u_dot;
    check(
        "parachute t=30 acceleration",
        &dp[3..6],
        &[-14.39058946, -191.67246242, -728.42306466],
    );
}

#[test]
fn too_heavy_to_leave_the_rail_is_flagged() {
    use karman_mission::dynamics::Termination;
    // 400 kg: the M1670's ~2000 N peak thrust cannot lift it.
    let Some(mission) = calisto_with(&[("rocket.mass", "400")]) else {
        println!("too_heavy_to_leave_the_rail_is_flagged: skipped, no validation folder");
        return;
    };
    // The launch check rejects it before the flight, blaming the thrust.
    match simulate(&mission) {
        Err(karman_mission::MissionError::Model {
            section, source, ..
        }) => {
            assert_eq!(section, "motor.thrust");
            assert!(
                source.to_string().starts_with(
                    "the rocket is stuck on the rail: its thrust never exceeds its weight"
                ),
                "{source}"
            );
        }
        other => panic!("expected the launch check's error, got {other:?}"),
    }
    // Flown anyway, the engine ends the flight on the rail in bounded time.
    let env = karman_mission::assemble::environment::build_environment(&mission).expect("env");
    let motor = karman_mission::assemble::motor::build_motor(&mission).expect("motor");
    let rocket = karman_mission::assemble::rocket::build_rocket(&mission, &motor).expect("rocket");
    let settings = karman_mission::assemble::preflight::flight_settings(&mission, 0);
    let start = std::time::Instant::now();
    let flight = karman_mission::dynamics::simulate(&env, &rocket, &settings).expect("flight");
    assert!(start.elapsed() < std::time::Duration::from_secs(30));
    assert_eq!(flight.termination, Termination::StuckOnRail);
    let summary = flight.summary(&env, &rocket);
    assert!(summary.out_of_rail_time_s.is_none() && summary.apogee_agl_m.is_none());
    assert!(summary.impact_time_s.is_none());
}

#[test]
fn max_time_reached_is_flagged() {
    use karman_mission::dynamics::Termination;
    let Some(mission) = calisto_with(&[("flight.max_time", "10")]) else {
        println!("max_time_reached_is_flagged: skipped, no validation folder");
        return;
    };
    let run = simulate(&mission).expect("flies");
    assert_eq!(run.flight.termination, Termination::MaxTime);
    let summary = flight_summary(&run);
    assert!(summary.apogee_agl_m.is_none() && summary.impact_time_s.is_none());
    assert!(summary.out_of_rail_time_s.is_some());
    assert!(summary.events.iter().all(|e| e.time_s <= 10.0));
}

#[test]
fn negative_margin_rocket_ends_in_bounded_time() {
    // Fins moved to the nose: the centre of pressure ends up ahead of the centre of mass.
    let Some(mission) = calisto_with(&[("rocket.surfaces.fins.position", "1.0")]) else {
        println!("negative_margin_rocket_ends_in_bounded_time: skipped, no validation folder");
        return;
    };
    let start = std::time::Instant::now();
    let result = simulate(&mission);
    assert!(start.elapsed() < std::time::Duration::from_secs(60));
    match result {
        Ok(run) => {
            let summary = flight_summary(&run);
            assert!(
                summary.initial_static_margin < 0.0,
                "{}",
                summary.initial_static_margin
            );
            assert!(summary.max_speed_mps.is_finite() && summary.max_acceleration_mps2.is_finite());
        }
        Err(e) => assert!(e.to_string().contains("flight"), "a flight error: {e}"),
    }
}

/// A thrust curve of 200 000 points (a static fire sampled at 67 kHz) flies within the step
/// budget of a phase: its steps do not stop at every knot.
#[test]
fn a_dense_thrust_curve_flies_within_the_step_limits() {
    use std::fmt::Write as _;
    if crate::common::validation_dir().is_none() {
        println!(
            "a_dense_thrust_curve_flies_within_the_step_limits: skipped, no validation folder"
        );
        return;
    }
    let rows = 200_000;
    let mut text = String::with_capacity(rows * 24);
    for k in 0..rows {
        let t = 3.0 * k as f64 / (rows - 1) as f64;
        let thrust = 1500.0 * (std::f64::consts::PI * t / 3.0).sin() + 10.0;
        let _ = writeln!(text, "{t:.9},{thrust:.6}");
    }
    let path = std::env::temp_dir().join(format!("karman-dense-{}.csv", std::process::id()));
    std::fs::write(&path, text).expect("write thrust file");
    let thrust = format!("{:?}", path.display().to_string());
    let mission = calisto_with(&[("motor.thrust", &thrust), ("motor.burn_time", "3")])
        .expect("the validation folder");
    let run = simulate(&mission).expect("the dense curve flies");
    std::fs::remove_file(&path).expect("cleanup");
    assert_eq!(
        run.flight.termination,
        karman_mission::dynamics::Termination::Impact
    );
    assert!(
        run.flight.stats.steps < 20_000,
        "{} steps",
        run.flight.stats.steps
    );
}

/// The two forms of the 6-DOF equations (`[flight] equations`) on Calisto: the standard form's
/// mass flow is the slope of the propellant-mass table, and its apogee differs from RocketPy
/// 1.13's by the lever arms only (docs/physics.md §5.4: a few tenths of a per cent at most).
#[test]
fn standard_and_rocketpy_equations() {
    use karman_mission::dynamics::{MassFlowLaw, VehicleModel};
    use karman_mission::math::Cursor;
    let Some(dir) = crate::common::validation_dir() else {
        println!("standard_and_rocketpy_equations: skipped, the validation folder is absent");
        return;
    };
    let path = dir.join("calisto/mission.toml");
    let fly = |form: &str| {
        let set = Override::new("flight.equations", &format!("\"{form}\"")).expect("parses");
        let mission = karman_mission::load(&path, &[set]).expect("Calisto loads");
        simulate(&mission).expect("flies")
    };
    let (rocketpy, standard) = (fly("rocketpy_1_13"), fly("standard"));
    let apogee = |run: &karman_mission::assemble::flight::FlightRun| {
        run.summary().apogee_agl_m.expect("apogee")
    };
    let (a, b) = (apogee(&rocketpy), apogee(&standard));
    println!("Calisto apogee: rocketpy_1_13 {a} m, standard {b} m");
    assert!((a - b).abs() > 1e-6, "the forms differ");
    assert!((a - b).abs() < 3e-3 * a, "{a} vs {b}");

    let rocket = &standard.rocket;
    let cursors = &mut [Cursor::default(); 2];
    // Off the table's knots, where the central difference is the slope to rounding.
    let (t, h) = (1.0137, 1e-6);
    let flow = rocket.mass(t, MassFlowLaw::MassDerivative, cursors);
    let (before, after) = (rocket.total_mass(t - h), rocket.total_mass(t + h));
    let slope = (after - before) / (2.0 * h);
    assert!(
        (flow.mass_flow_rate - slope).abs() < 1e-6 * slope.abs(),
        "{} vs {slope}",
        flow.mass_flow_rate
    );
    let thrust = rocket.mass(t, MassFlowLaw::ThrustOverExhaustVelocity, cursors);
    assert!((thrust.mass_flow_rate - rocket.mass_flow_rate(t)).abs() < f64::MIN_POSITIVE);
}
