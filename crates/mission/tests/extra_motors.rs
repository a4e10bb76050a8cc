//! `[[extra_motors]]`: several motors in one rocket, summed into the one motor the airframe
//! flies (`assemble::motors`), on hand-checkable cases: two identical motors lit together are a
//! cluster of two, a motor combined with nothing is itself, an air start's thrust is the sum
//! of the shifted curves, its propellant is conserved, its burn window runs from the first
//! ignition to the last burn-out; mistakes are located; a study of such a mission flies.

use karman_mission::assemble::motors::{PlacedMotor, combined};
use karman_mission::assemble::{flight::simulate, motor::build_motor, rocket::build_rocket};
use karman_mission::montecarlo::{MonteCarlo, StudyOverrides};
use karman_mission::{Location, Mission, MissionError, parse};
use karman_openrocket::{ImportOptions, OrkError, document_text, import};
use std::path::PathBuf;

/// A file of the repository's `fixtures` folder.
fn repo_fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures")
        .join(name)
}

fn text_of(name: &str) -> String {
    std::fs::read_to_string(repo_fixture(name)).expect("fixture readable")
}

fn load(text: &str, name: &str) -> Mission {
    parse(text, &repo_fixture(name), &[]).unwrap_or_else(|e| panic!("{e}"))
}

/// The `[motor]` table of `fixtures/example.toml`, as text (its keys, without the header).
fn example_motor_keys(text: &str) -> String {
    let start = text.find("[motor]\n").expect("[motor]") + "[motor]\n".len();
    let end = text[start..].find("\n\n").expect("end of [motor]") + start;
    text[start..end].to_owned()
}

fn close(a: f64, b: f64, relative: f64) -> bool {
    (a - b).abs() <= relative * a.abs().max(b.abs()).max(1e-300)
}

#[test]
fn two_identical_motors_lit_together_are_a_cluster_of_two() {
    let text = text_of("example.toml");
    let keys = example_motor_keys(&text);
    let pair = load(
        &text.replace(
            "\n[dispersion]",
            &format!(
                "\n[[extra_motors]]\nmotor_position = 1.60\n\n[extra_motors.motor]\n{keys}\n\n[dispersion]"
            ),
        ),
        "pair.toml",
    );
    let cluster = load(
        &text.replace(
            "grains_center_of_mass_position = 0.25\n",
            "grains_center_of_mass_position = 0.25\ncluster_count = 2\n",
        ),
        "cluster.toml",
    );
    let motor = build_motor(&pair).expect("motor");
    let (a, b) = (
        build_rocket(&pair, &motor).expect("pair"),
        build_rocket(&cluster, &motor).expect("cluster"),
    );
    let (ma, mb) = (a.motor(), b.motor());
    assert_eq!(ma.burn_start.to_bits(), mb.burn_start.to_bits());
    assert_eq!(ma.burn_out.to_bits(), mb.burn_out.to_bits());
    assert!(close(ma.exhaust_velocity, mb.exhaust_velocity, 1e-15));
    assert!(close(ma.nozzle_radius, mb.nozzle_radius, 1e-15));
    assert!(close(ma.dry_mass, mb.dry_mass, 1e-15));
    assert!(close(ma.center_of_dry_mass, mb.center_of_dry_mass, 1e-15));
    for i in 0..6 {
        assert!(close(ma.dry_inertia[i], mb.dry_inertia[i], 1e-15), "{i}");
    }
    // The thrust everywhere; the mass properties at the propellant table's nodes, where the
    // cluster's node-wise tables are exact (between them the cluster interpolates its centre
    // of mass linearly, the combination takes the exact ratio).
    for k in 0..=400 {
        let t = -0.1 + 3.0 * f64::from(k) / 400.0;
        assert!(close(a.thrust(t), b.thrust(t), 1e-12), "thrust at {t}");
        assert!(
            close(a.total_mass(t), b.total_mass(t), 1e-14),
            "mass at {t}"
        );
    }
    for &t in mb.propellant_mass.xs() {
        // c is a few centimetres, and 0 once the propellant is gone: an absolute bound.
        let c = (a.com_to_cdm(t), b.com_to_cdm(t));
        assert!((c.0 - c.1).abs() < 1e-14, "c at {t}: {c:?}");
        let (ia, ib) = (a.inertia(t), b.inertia(t));
        for i in 0..3 {
            assert!(close(ia[i], ib[i], 1e-12), "I{i} at {t}: {ia:?} {ib:?}");
        }
    }
    // The flights: the same but for that interpolation between nodes.
    let (fa, fb) = (
        simulate(&pair).expect("pair flies").summary(),
        simulate(&cluster).expect("cluster flies").summary(),
    );
    let apogee = |s: &karman_mission::dynamics::Summary| s.apogee_agl_m.expect("apogee");
    assert!(
        close(apogee(&fa), apogee(&fb), 1e-4),
        "{} vs {}",
        apogee(&fa),
        apogee(&fb)
    );
    assert!(close(fa.max_speed_mps, fb.max_speed_mps, 1e-4));
}

#[test]
fn one_motor_is_its_own_combination() {
    let mission = load(&text_of("example.toml"), "example.toml");
    let motor = build_motor(&mission).expect("motor");
    let rocket = build_rocket(&mission, &motor).expect("rocket");
    let alone = [PlacedMotor {
        properties: rocket.motor().clone(),
        position: 1.6,
    }];
    assert_eq!(&combined(&alone, -1.0).expect("combines"), rocket.motor());
}

#[test]
fn an_air_start_sums_its_motors_shifted_by_their_delays() {
    let mission = load(&text_of("airstart.toml"), "airstart.toml");
    let mut central = mission.clone();
    central.spec.extra_motors.clear();
    let motor = build_motor(&mission).expect("motor");
    let (both, alone) = (
        build_rocket(&mission, &motor).expect("air start"),
        build_rocket(&central, &motor).expect("central motor"),
    );
    // The outboard pair's curve, by hand from the fixture, lit at 3 s.
    let outboard = |t: f64| {
        let points = [
            (0.0, 0.0),
            (0.05, 320.0),
            (0.3, 290.0),
            (1.4, 230.0),
            (1.6, 0.0),
        ];
        let t = t - 3.0;
        points.windows(2).fold(0.0, |value, w| {
            let ((t0, f0), (t1, f1)) = (w[0], w[1]);
            if t > t0 && t <= t1 {
                f0 + (f1 - f0) * (t - t0) / (t1 - t0)
            } else {
                value
            }
        })
    };
    for k in 0..=1000 {
        let t = -0.5 + 6.0 * f64::from(k) / 1000.0;
        let expected = alone.thrust(t) + 2.0 * outboard(t);
        assert!(
            (both.thrust(t) - expected).abs() <= 1e-9 * expected.max(1.0),
            "thrust at {t}: {} vs {expected}",
            both.thrust(t)
        );
    }
    // Burn window: the central motor's ignition to the outboard pair's burn-out.
    assert_eq!(both.burn_start().to_bits(), alone.burn_start().to_bits());
    assert!(
        close(both.burn_out(), 3.0 + 1.6, 1e-15),
        "{}",
        both.burn_out()
    );

    // Mass: the outboard pair (dry 2 × 0.28 kg, propellant 2 × 0.21 kg) rides unburnt until
    // 3 s, then burns all its propellant; nothing else changes.
    let pair_dry = 2.0 * 0.28;
    let pair_propellant = 2.0 * 0.21;
    for t in [0.0, 1.0, 2.0, 2.9] {
        let extra = both.total_mass(t) - alone.total_mass(t);
        assert!(
            close(extra, pair_dry + pair_propellant, 1e-12),
            "{t}: {extra}"
        );
    }
    for t in [4.6, 5.0, 30.0] {
        let extra = both.total_mass(t) - alone.total_mass(t);
        assert!(close(extra, pair_dry, 1e-12), "{t}: {extra}");
    }
    // The standard equations' mass flow integrates to the propellant burnt (trapezoids on a
    // grid fine enough for the piecewise-linear flows: every knot of both curves is on it).
    let (mut burnt, mut cursor) = (0.0, karman_mission::math::Cursor::default());
    let n = 60_000;
    let dt = 6.0 / f64::from(n);
    let mut previous = both.mass_rate_near(0.0, &mut cursor).0;
    for k in 1..=n {
        let rate = both.mass_rate_near(dt * f64::from(k), &mut cursor).0;
        burnt -= 0.5 * (previous + rate) * dt;
        previous = rate;
    }
    let propellant = both.total_mass(0.0) - both.total_mass(6.0);
    assert!(close(burnt, propellant, 1e-3), "{burnt} vs {propellant}");

    // Centre of mass before the air start: the central rocket's and the outboard pair's,
    // mass-weighted (nose-to-tail coordinates; the pair's dry centre 0.12 m and its
    // propellant 0.13 m ahead of their nozzle exits at 1.60 m).
    let t = 2.0;
    let pair_moment = pair_dry * (1.60 - 0.12) + pair_propellant * (1.60 - 0.13);
    let expected = (alone.total_mass(t) * alone.center_of_mass(t) + pair_moment)
        / (alone.total_mass(t) + pair_dry + pair_propellant);
    assert!(
        close(both.center_of_mass(t), expected, 1e-12),
        "{} vs {expected}",
        both.center_of_mass(t)
    );
}

#[test]
fn an_air_start_burns_out_late_and_flies_higher() {
    let mission = load(&text_of("airstart.toml"), "airstart.toml");
    let run = simulate(&mission).expect("flies");
    let mut central = mission.clone();
    central.spec.extra_motors.clear();
    let alone = simulate(&central).expect("flies").summary();
    let summary = run.summary();
    let apogee = |s: &karman_mission::dynamics::Summary| s.apogee_agl_m.expect("apogee");
    assert!(apogee(&summary) > apogee(&alone) + 100.0);
    // Lit later, the outboard pair carries the rocket to a later apogee.
    let mut late = mission.clone();
    late.spec.extra_motors[0].ignition_delay = 6.0;
    let later = simulate(&late).expect("flies").summary();
    assert!(later.apogee_time_s > summary.apogee_time_s);
}

/// The problems of `text` (as `fixtures/<name>`), each as its key and line.
fn located(text: &str, name: &str) -> Vec<(String, usize)> {
    match parse(text, &repo_fixture(name), &[]) {
        Err(MissionError::Invalid { problems, .. }) => problems
            .iter()
            .map(|p| {
                let line = match p.location {
                    Location::File { line, .. } => line,
                    _ => 0,
                };
                (p.key.clone(), line)
            })
            .collect(),
        other => panic!("expected an invalid mission, got {other:?}"),
    }
}

fn line_of(text: &str, needle: &str) -> usize {
    text.lines()
        .position(|l| l.starts_with(needle))
        .unwrap_or_else(|| panic!("no line {needle:?}"))
        + 1
}

/// An ignition after the longest flight (a day) is refused at its key: at 1e15 s the summed
/// thrust curve's times no longer resolve the burn ("does not increase" from the table).
#[test]
fn an_ignition_beyond_any_flight_is_located() {
    let text = text_of("airstart.toml").replace("ignition_delay = 3.0", "ignition_delay = 1e15");
    let found = located(&text, "airstart.toml");
    assert_eq!(
        found,
        vec![(
            "extra_motors.0.ignition_delay".to_owned(),
            line_of(&text, "ignition_delay = 1e15")
        )]
    );
}

#[test]
fn extra_motor_mistakes_are_located() {
    let text = text_of("airstart.toml")
        .replace("ignition_delay = 3.0", "ignition_delay = -1.0")
        .replace(
            "dry_mass = 0.28",
            "dry_mass = -0.28\ninterpolation = \"spline\"",
        )
        .replace(
            "throat_radius = 0.0065\n",
            "throat_radius = 0.0065\nreference_pressure = 101325\n",
        );
    let found = located(&text, "airstart.toml");
    let expected = [
        (
            "extra_motors.0.motor.dry_mass".to_owned(),
            line_of(&text, "dry_mass = -0.28"),
        ),
        (
            "motor.reference_pressure".to_owned(),
            line_of(&text, "reference_pressure"),
        ),
        (
            "extra_motors.0.motor.interpolation".to_owned(),
            line_of(&text, "interpolation = \"spline\""),
        ),
        (
            "extra_motors.0.ignition_delay".to_owned(),
            line_of(&text, "ignition_delay = -1.0"),
        ),
    ];
    for e in &expected {
        assert!(found.contains(e), "{e:?} not in {found:?}");
    }
    assert_eq!(found.len(), expected.len(), "{found:?}");

    // A multi-stage rocket takes no extra motors yet: said at the table.
    let stack = text_of("two_stage.toml");
    let stack = stack.replacen(
        "\n[[stages]]",
        &format!(
            "\n[[extra_motors]]\nmotor_position = 1.60\n\n[extra_motors.motor]\n{}\n\n[[stages]]",
            example_motor_keys(&text_of("example.toml"))
        ),
        1,
    );
    let found = located(&stack, "two_stage.toml");
    assert_eq!(
        found,
        [(
            "extra_motors".to_owned(),
            line_of(&stack, "[[extra_motors]]")
        )]
    );
}

#[test]
fn a_study_of_an_air_start_varies_the_extra_motor_and_repeats() {
    let mission = load(&text_of("airstart.toml"), "airstart.toml");
    let study = MonteCarlo::new(&mission, StudyOverrides::default()).expect("study");
    let columns: Vec<String> = study
        .study()
        .inputs
        .iter()
        .map(karman_mission::dispersion::VariedInput::column)
        .collect();
    assert_eq!(columns[2], "extra_motors.0.ignition_delay");
    assert_eq!(columns[3], "extra_motors.0.motor.dry_mass");
    let values = [4.2, 1960.0, 3.0, 0.28, 1.0, 2.57, 86.0, 30.0];
    let bits = |values: &[Option<f64>]| {
        values
            .iter()
            .map(|v| v.map(f64::to_bits))
            .collect::<Vec<_>>()
    };
    let first = study.fly(5, &values).expect("flies");
    let again = study.fly(5, &values).expect("flies");
    assert_eq!(bits(first.values()), bits(again.values()));
    // A heavier outboard pair flies lower.
    let mut heavier = values;
    heavier[3] = 0.6;
    let apogee = |v: &[Option<f64>]| v[0].expect("apogee");
    assert!(
        apogee(study.fly(5, &heavier).expect("flies").values()) < apogee(first.values()),
        "heavier outboard motors"
    );
}

/// `block` (an inner tube's XML) lit `delay` s after `event` in simulation 1's configuration.
fn lit(block: &str, event: &str, delay: &str) -> String {
    let config = "<ignitionconfiguration configid=\"da326836-0959-4c94-bcd5-49dee07235a4\">";
    let at = block.find(config).expect("simulation 1's ignition");
    let tail = block[at..]
        .replacen(
            "<ignitionevent>automatic</ignitionevent>",
            &format!("<ignitionevent>{event}</ignitionevent>"),
            1,
        )
        .replacen(
            "<ignitiondelay>0.0</ignitiondelay>",
            &format!("<ignitiondelay>{delay}</ignitiondelay>"),
            1,
        );
    format!("{}{tail}", &block[..at])
}

/// The `clustered_motors` OpenRocket example (a 4-ring of Estes motors in `Clustered Inner
/// Tube`, lit `cluster_delay` s after launch) with a second motor mount beside the cluster: a
/// copy of its inner tube named `Centre tube`, one motor (no cluster), lit `delay` s after
/// `event`; imported for simulation 1 (Estes A8-3 motors).
fn two_mounts(
    cluster_delay: &str,
    event: &str,
    delay: &str,
) -> Result<karman_openrocket::Imported, OrkError> {
    let dir = repo_fixture("openrocket/clustered_motors");
    let path = dir.join("design.ork");
    let text = document_text(&path, &std::fs::read(&path).expect("fixture")).expect("document");
    let start = text.find("<innertube>").expect("inner tube");
    let end = text[start..].find("</innertube>").expect("end") + start + "</innertube>".len();
    let block = &text[start..end];
    let copy = block
        .replacen("Clustered Inner Tube", "Centre tube", 1)
        .replacen("4-ring", "single", 1);
    let edited = format!(
        "{}{}\n{}{}",
        &text[..start],
        lit(block, "automatic", cluster_delay),
        lit(&copy, event, delay),
        &text[end..]
    );
    let out = std::env::temp_dir().join(format!("karman-extra-motors-{}", std::process::id()));
    std::fs::create_dir_all(&out).expect("temp dir");
    let file = out.join(format!("two_mounts_{event}_{delay}.ork"));
    std::fs::write(&file, edited).expect("write");
    let options = ImportOptions {
        simulation: Some("Simulation 1".into()),
        motors: vec![dir],
        output_dir: None,
    };
    import(&file, &options)
}

fn imported_mission(text: &str) -> Mission {
    parse(text, &std::env::temp_dir().join("two_mounts.toml"), &[])
        .unwrap_or_else(|e| panic!("{e}\n{text}"))
}

#[test]
fn openrocket_motor_mounts_of_one_stage_become_extra_motors() {
    // The centre motor lit 1.5 s after launch: the cluster, lit at launch, is `[motor]`.
    let text = two_mounts("0.0", "launch", "1.5").expect("imports").mission;
    assert!(text.contains("cluster_count = 4\n"), "{text}");
    assert!(
        text.contains("[[extra_motors]]\nname = \"Centre tube\"\nmotor_position = "),
        "{text}"
    );
    assert!(text.contains("ignition_delay = 1.5\n"), "{text}");
    // The parachute opens at the first ejection charge: the cluster's A8-3s, 3 s after their
    // burn-out, a time after launch (`burnout + X` would count from the last burn-out).
    assert!(text.contains("trigger = \"launch + "), "{text}");
    let mission = imported_mission(&text);
    assert_eq!(mission.spec.extra_motors.len(), 1);
    let extra = &mission.spec.extra_motors[0];
    assert_eq!(extra.motor.cluster_count, None);
    // Both tubes end at the same place: the same nozzle exit.
    assert!((extra.motor_position - mission.spec.rocket.motor_position).abs() < 1e-12);
    simulate(&mission).expect("flies");

    // The cluster lit 2 s after launch and the centre motor at launch: the centre motor,
    // lit first, is `[motor]`, the cluster waits.
    let mission = imported_mission(
        &two_mounts("2.0", "automatic", "0.0")
            .expect("imports")
            .mission,
    );
    assert_eq!(mission.spec.motor.cluster_count, None);
    let extra = &mission.spec.extra_motors[0];
    assert_eq!(extra.name.as_deref(), Some("Clustered Inner Tube"));
    assert_eq!(extra.motor.cluster_count, Some(4));
    assert!((extra.ignition_delay - 2.0).abs() < 1e-15);
}

#[test]
fn openrocket_motors_never_lit_ride_as_mass_and_a_late_first_motor_is_refused() {
    // In the launch stage, `burnout` and `ejection` wait for a stage below: OpenRocket never
    // lights the centre motor, which is carried as mass, with a note naming it and the event.
    for event in ["burnout", "ejection", "never"] {
        let imported = two_mounts("0.0", event, "0.0").expect("imports");
        let note = imported
            .warnings
            .iter()
            .find(|w| w.contains("Centre tube"))
            .unwrap_or_else(|| panic!("no note: {:?}", imported.warnings));
        assert!(
            note.contains("never lights") && note.contains(event),
            "{note}"
        );
        let mission = imported_mission(&imported.mission);
        assert!(mission.spec.extra_motors.is_empty());
        assert_eq!(mission.spec.motor.cluster_count, Some(4));
    }
    // Every motor lit after launch: karman lights `[motor]` at launch.
    let e = two_mounts("1.0", "launch", "2.0")
        .expect_err("refused")
        .to_string();
    assert!(
        e.contains("Clustered Inner Tube") && e.contains("1 s after automatic"),
        "{e}"
    );
}

#[test]
fn a_study_varying_only_an_extra_motor_rebuilds_the_rocket() {
    // The extra motors ride on the rocket: a study that varies nothing else must still fly
    // each sample's own motors.
    let text = text_of("airstart.toml");
    let start = text.find("[dispersion.vary]\n").expect("vary") + "[dispersion.vary]\n".len();
    let text = format!(
        "{}\"extra_motors.0.ignition_delay\" = {{ uniform = [2.8, 6.0] }}\n",
        &text[..start]
    );
    let mission = load(&text, "airstart.toml");
    let study = MonteCarlo::new(&mission, StudyOverrides::default()).expect("study");
    let apogee_time = |delay: f64| study.fly(1, &[delay]).expect("flies").values()[2];
    assert!(apogee_time(6.0) > apogee_time(3.0));
}

#[test]
fn a_study_reads_every_thrust_and_curve_file_once() {
    // The air start with its outboard motors' thrust in a file beside the mission: once the
    // study is set up, the samples (which rebuild the rocket and its extra motors) must not
    // read the thrust or curve files again, so removing them changes nothing.
    let dir = std::env::temp_dir().join(format!("karman-extra-motors-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let inline = "thrust = [[0, 0], [0.05, 320], [0.3, 290], [1.4, 230], [1.6, 0]]";
    let text = text_of("airstart.toml");
    assert!(text.contains(inline), "the fixture's outboard thrust");
    let text = text.replace(inline, "thrust = \"outboard.csv\"");
    std::fs::write(dir.join("airstart.toml"), &text).expect("mission written");
    std::fs::write(
        dir.join("outboard.csv"),
        "0,0\n0.05,320\n0.3,290\n1.4,230\n1.6,0\n",
    )
    .expect("thrust written");
    let copied = [
        "example_K1960.eng",
        "power_off_drag.csv",
        "power_on_drag.csv",
    ];
    for file in copied {
        std::fs::copy(repo_fixture(file), dir.join(file)).expect("fixture copied");
    }
    let mission = parse(&text, &dir.join("airstart.toml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    let study = MonteCarlo::new(&mission, StudyOverrides::default()).expect("study");
    let values = [4.2, 1960.0, 3.0, 0.28, 1.0, 2.57, 86.0, 30.0];
    let before = study.fly(3, &values).expect("flies");
    for file in copied.iter().chain(&["outboard.csv"]) {
        std::fs::remove_file(dir.join(file)).expect("removed");
    }
    let after = study
        .fly(3, &values)
        .expect("flies without its thrust files");
    let bits = |values: &[Option<f64>]| {
        values
            .iter()
            .map(|v| v.map(f64::to_bits))
            .collect::<Vec<_>>()
    };
    assert_eq!(bits(before.values()), bits(after.values()));
    // And the same data as the inline curve.
    let nominal = MonteCarlo::new(
        &load(&text_of("airstart.toml"), "airstart.toml"),
        StudyOverrides::default(),
    )
    .expect("study");
    assert_eq!(
        bits(nominal.fly(3, &values).expect("flies").values()),
        bits(before.values())
    );
    std::fs::remove_dir_all(&dir).expect("temp dir removed");
}
