//! Multi-stage rockets: the two-stage fixture, the consistency of the flight tree with
//! single-stage flights, and the located errors of `[[stages]]`.

use std::path::{Path, PathBuf};

use karman_mission::assemble::flight::simulate;
use karman_mission::assemble::stage_view::TOP_STAGE;
use karman_mission::assemble::stages::{StagedRun, simulate_staged};
use karman_mission::dynamics::{Summary, Termination};
use karman_mission::{Mission, MissionError, Override, load, parse};

fn repository_fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures")
        .join(name)
}

/// The example mission's text without its `[dispersion]` study (not taken by stacks).
fn example_without_dispersion() -> String {
    let text = std::fs::read_to_string(repository_fixture("example.toml")).expect("example");
    let end = text.find("[dispersion]").expect("the example has a study");
    text[..end].to_owned()
}

/// A mission text read as if it were beside the example (its data files resolve there).
fn beside_example(text: &str, overrides: &[(&str, &str)]) -> Mission {
    let overrides: Vec<Override> = overrides
        .iter()
        .map(|(k, v)| Override::new(k, v).expect("override"))
        .collect();
    parse(text, &repository_fixture("example.toml"), &overrides).unwrap_or_else(|e| panic!("{e}"))
}

/// The example motor's table, as `[stages.motor]`, with `dry` its dry mass and inertia.
fn stage_motor(dry: &str) -> String {
    format!(
        r#"
[stages.motor]
kind = "solid"
thrust = "example_K1960.eng"
{dry}
center_of_dry_mass_position = 0.23
nozzle_position = 0
nozzle_radius = 0.016
throat_radius = 0.0065
grain_number = 3
grain_separation = 0.005
grain_density = 1750
grain_outer_radius = 0.0245
grain_initial_inner_radius = 0.009
grain_initial_height = 0.12
grains_center_of_mass_position = 0.25
"#
    )
}

#[test]
fn the_two_stage_fixture_flies_and_both_bodies_land() {
    let mission = load(&repository_fixture("two_stage.toml"), &[]).expect("loads");
    let run = simulate_staged(&mission, 0).expect("flies");
    let names: Vec<&str> = run.bodies.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(names, [TOP_STAGE, "booster"]);
    let sustainer = run.summary(0);
    let booster = run.summary(1);
    for summary in [&sustainer, &booster] {
        assert_eq!(summary.termination, Termination::Impact);
        assert!(summary.impact_time_s.is_some());
    }
    // Separation 0.5 s after the booster's burn-out (2.75 s), at a 100 Hz sampling instant.
    assert_eq!(run.separations.len(), 1);
    let separation = run.separations[0].time_s;
    assert!((separation - 3.25).abs() < 1e-9, "{separation}");
    // Both bodies share the launch; the sustainer coasts far higher and lands elsewhere.
    assert_eq!(sustainer.out_of_rail_time_s, booster.out_of_rail_time_s);
    assert!(sustainer.apogee_agl_m.unwrap() > 3.0 * booster.apogee_agl_m.unwrap());
    let (sx, sy) = (sustainer.impact_x_m.unwrap(), sustainer.impact_y_m.unwrap());
    let (bx, by) = (booster.impact_x_m.unwrap(), booster.impact_y_m.unwrap());
    assert!((sx - bx).hypot(sy - by) > 10.0);
    // The sustainer's motor lights 1 s after separation: its burn-out is 4.25 s after launch
    // plus the burn (2.75 s).
    let burnout = sustainer
        .events
        .iter()
        .find(|e| e.name == "burnout:sustainer")
        .expect("sustainer burn-out");
    assert!((burnout.time_s - 7.0).abs() < 1e-9, "{}", burnout.time_s);
    // Each body's path starts on the pad and ends at its impact, in time order.
    for body in 0..2 {
        let samples = run.samples(body);
        assert!(samples.windows(2).all(|w| w[0].t < w[1].t));
        assert!(samples[0].altitude_agl.abs() < 1e-9);
        assert!(samples.last().unwrap().altitude_agl.abs() < 1e-6);
    }
    let timeline = run.timeline();
    assert!(timeline.windows(2).all(|w| w[0].0 <= w[1].0));
    assert!(timeline.iter().any(|(_, e)| e == "separation of booster"));
}

#[test]
fn a_massless_stage_without_motor_dropped_at_launch_flies_as_the_stage_above_alone() {
    let single = example_without_dispersion();
    let staged = format!(
        r#"{single}
[[stages]]
name = "nothing"
separation = "launch + 0"
stack_power_off_drag = 0.9
stack_power_on_drag = 0.9

[stages.rocket]
radius = 0.0285
mass = 0
inertia = [0, 0, 0]
center_of_mass_without_motor = 2.0
coordinate_system = "nose_to_tail"
power_off_drag = 0.9
power_on_drag = 0.9
motor_position = 2.5
"#
    );
    let alone = simulate(&beside_example(&single, &[])).expect("flies");
    let run = simulate_staged(&beside_example(&staged, &[]), 0).expect("flies");
    assert_eq!(run.bodies.len(), 1, "a massless stage is not flown");
    let ours = run.summary(0).apogee_agl_m.unwrap();
    let reference = alone.summary().apogee_agl_m.unwrap();
    assert!(
        ((ours - reference) / reference).abs() < 1e-9,
        "{ours} vs {reference}"
    );
    assert_eq!(run.summary(0).impact_time_s, alone.summary().impact_time_s);
}

/// The stack and the stage above are one rigid body after the lower stage's burn-out: a
/// massless lower stage whose motor has no dry mass, the upper motor never lit, and every
/// mass of the upper stage centred at one point, 0.95 m from the nose tip (so the centres of
/// dry mass coincide).
fn identical_after_burnout(separation: &str) -> Mission {
    let single = example_without_dispersion();
    let parachutes = single.find("[rocket.parachutes.drogue]").expect("chutes");
    let flight = single.find("[flight]").expect("flight");
    let top = format!("{}{}", &single[..parachutes], &single[flight..])
        .replace("motor_position = 1.60", "motor_position = 1.18")
        .replace(
            "grains_center_of_mass_position = 0.25",
            "grains_center_of_mass_position = 0.23",
        );
    let text = format!(
        r#"{top}
[[stages]]
name = "ghost"
separation = {separation}
ignition_delay = 5000
stack_power_off_drag = "power_off_drag.csv"
stack_power_on_drag = "power_on_drag.csv"

[stages.rocket]
radius = 0.0285
mass = 0
inertia = [0, 0, 0]
center_of_mass_without_motor = 0.95
coordinate_system = "nose_to_tail"
power_off_drag = "power_off_drag.csv"
power_on_drag = "power_on_drag.csv"
motor_position = 1.18
{}"#,
        stage_motor("dry_mass = 0\ndry_inertia = [0, 0, 0]")
    );
    beside_example(
        &text,
        &[
            ("flight.rtol", "1e-10"),
            ("flight.equations", "\"standard\""),
        ],
    )
}

#[test]
fn a_separation_at_apogee_of_identical_bodies_leaves_the_upper_path_unchanged() {
    let staged = simulate_staged(&identical_after_burnout("\"apogee\""), 0).expect("flies");
    let together =
        simulate_staged(&identical_after_burnout("\"launch + 10000\""), 0).expect("flies");
    assert_eq!(staged.separations.len(), 1);
    assert!(together.separations.is_empty());
    let (ours, reference) = (staged.summary(0), together.summary(0));
    // Identical up to the separation, one step after the apogee.
    assert_eq!(ours.apogee_agl_m, reference.apogee_agl_m);
    assert_eq!(ours.apogee_time_s, reference.apogee_time_s);
    let t = staged.separations[0].time_s;
    assert!(t > ours.apogee_time_s.unwrap() && t < ours.apogee_time_s.unwrap() + 0.011);
    // After it only the integrator's restart differs.
    let close = |a: Option<f64>, b: Option<f64>, scale: f64| {
        let (a, b) = (a.unwrap(), b.unwrap());
        assert!((a - b).abs() < 1e-6 * scale, "{a} vs {b}");
    };
    let range = reference
        .impact_x_m
        .unwrap()
        .hypot(reference.impact_y_m.unwrap());
    close(
        ours.impact_time_s,
        reference.impact_time_s,
        reference.impact_time_s.unwrap(),
    );
    close(ours.impact_x_m, reference.impact_x_m, range);
    close(ours.impact_y_m, reference.impact_y_m, range);
    close(
        ours.impact_velocity_mps,
        reference.impact_velocity_mps,
        100.0,
    );
}

fn staged_problem(stage: &str) -> String {
    let text = format!("{}{stage}", example_without_dispersion());
    match parse(&text, Path::new("m.toml"), &[]) {
        Err(error @ MissionError::Invalid { .. }) => error.to_string(),
        Err(other) => panic!("not a validation error: {other}"),
        Ok(_) => panic!("accepted"),
    }
}

#[test]
fn stage_mistakes_are_located_errors() {
    let rocket = |extra: &str| {
        format!(
            r#"
[stages.rocket]
radius = 0.0285
mass = 1
inertia = [0.1, 0.1, 0.001]
center_of_mass_without_motor = 2.0
power_off_drag = 0.9
power_on_drag = 0.9
motor_position = 2.5
{extra}
"#
        )
    };
    let head = "\n[[stages]]\nstack_power_off_drag = 0.6\nstack_power_on_drag = 0.6\n";
    // A motorless stage must separate at launch.
    let text = staged_problem(&format!(
        "{head}separation = \"burnout + 1\"\n{}",
        rocket("coordinate_system = \"nose_to_tail\"")
    ));
    assert!(
        text.contains("stages.0.separation") && text.contains("without a motor"),
        "{text}"
    );
    // ... and so must every stage below it.
    let text = staged_problem(&format!(
        "{head}separation = \"launch + 0\"\n{}{head}separation = \"burnout + 1\"\n{}{}",
        rocket("coordinate_system = \"nose_to_tail\""),
        rocket("coordinate_system = \"nose_to_tail\""),
        stage_motor("dry_mass = 1")
    ));
    assert!(
        text.contains("stages.1.separation") && text.contains("without a motor"),
        "{text}"
    );
    // One coordinate system for the stack.
    let text = staged_problem(&format!(
        "{head}separation = \"launch + 0\"\n{}",
        rocket("")
    ));
    assert!(text.contains("stages.0.rocket.coordinate_system"), "{text}");
    // Keys of the stage's rocket and motor are checked and named under the stage.
    let text = staged_problem(&format!(
        "{head}separation = \"launch + 0\"\n{}{}",
        rocket(
            "coordinate_system = \"nose_to_tail\"\n[stages.rocket.surfaces.fins]\ntype = \"tail\"\ntop_radius = 0.02\nbottom_radius = 0.01\nlength = 0.1\nposition = 2.3"
        ),
        stage_motor("dry_mass = -1")
    ));
    assert!(text.contains("stages.0.motor.dry_mass"), "{text}");
    assert!(text.contains("stages.0.rocket.surfaces.fins"), "{text}");
    // Other commands refuse a stack instead of flying its top stage alone.
    let ok = format!(
        "{}{head}separation = \"launch + 0\"\n{}",
        example_without_dispersion(),
        rocket("coordinate_system = \"nose_to_tail\"")
    );
    let mission = beside_example(&ok, &[]);
    let error = simulate(&mission).expect_err("a stack").to_string();
    assert!(error.contains("stages"), "{error}");
}

/// `fixtures/openrocket/<design>` imported for its first stored simulation.
fn imported(design: &str) -> Mission {
    use karman_openrocket::{ImportOptions, import};
    let dir = repository_fixture("openrocket").join(design);
    let options = ImportOptions {
        simulation: None,
        motors: Vec::new(),
        output_dir: Some(dir.clone()),
    };
    let mission = import(&dir.join("design.ork"), &options)
        .unwrap_or_else(|e| panic!("{design}: {e}"))
        .mission;
    parse(&mission, &dir.join("imported.toml"), &[]).unwrap_or_else(|e| panic!("{design}: {e}"))
}

/// The index of the body called `name` in a staged run.
fn body_index(run: &StagedRun, name: &str) -> usize {
    run.bodies
        .iter()
        .position(|b| b.name == name)
        .unwrap_or_else(|| panic!("no body {name}"))
}

/// The time of the event called `name` in a body's summary, s.
fn event_time(summary: &Summary, name: &str) -> f64 {
    summary
        .events
        .iter()
        .find(|e| e.name == name)
        .map(|e| e.time_s)
        .unwrap_or_else(|| panic!("no {name}: {:?}", summary.events))
}

/// A body's speed at its impact (m/s, downwards) and the terminal speed `√(2 m g / (ρ C_D·A))`
/// of `drag_area` there.
fn landing_and_terminal_speeds(run: &StagedRun, index: usize, drag_area: f64) -> (f64, f64) {
    let segment = &run.segments[*run.bodies[index].segments.last().expect("segments")];
    let last = run.samples(index).last().copied().expect("samples");
    let mass = segment.rocket.total_mass(last.t);
    let (rho, g) = (
        run.environment.density(last.z),
        run.environment.gravity(last.z),
    );
    (-last.vz, (2.0 * mass * g / (rho * drag_area)).sqrt())
}

#[test]
fn the_imported_staged_designs_fly_every_body_to_the_ground() {
    for (design, bodies) in [
        ("two_stage_high_power_rocket", 2),
        ("three_stage_low_power_rocket", 3),
    ] {
        let run = simulate_staged(&imported(design), 0).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(run.bodies.len(), bodies, "{design}");
        for (i, body) in run.bodies.iter().enumerate() {
            let summary = run.summary(i);
            assert_eq!(
                summary.termination,
                Termination::Impact,
                "{design} {}",
                body.name
            );
            let last = run.samples(i).last().copied().expect("samples");
            assert!(
                last.altitude_agl.abs() < 1e-3,
                "{design} {}: {} m",
                body.name,
                last.altitude_agl
            );
        }
        // Every flight of the tree in a bounded number of steps.
        for segment in &run.segments {
            let steps = segment.flight.stats.steps;
            assert!(steps < 5_000, "{design} {}: {steps} steps", segment.vehicle);
        }
    }
}

#[test]
fn an_unstable_spent_stage_tumbles_after_its_separation_at_niskanens_terminal_speed() {
    let mission = imported("three_stage_low_power_rocket");
    let run = simulate_staged(&mission, 0).expect("flies");
    // The bottom stage: three trapezoidal fins (root 0.08 m, tip 0.03 m, span 0.04 m) on a
    // body 0.56 − 0.48 m long, 0.025 m across (Niskanen's eq. 3.99, η(3) = 1.50).
    let fins = 1.42 * 1.50 * (0.08 + 0.03) / 2.0 * 0.04;
    let body = 0.56 * (0.56 - 0.48) * 0.025;
    let drag_area = fins + body;
    let summary = run.summary(body_index(&run, "Booster stage 2"));
    let event = |name: &str| event_time(&summary, name);
    // Statically unstable alone, it turns over right after its separation and tumbles
    // there (OpenRocket's stored flight: 0.32 s after the separation).
    let separation = event("separation:Booster stage 2");
    let tumble = event("tumble");
    assert!(
        tumble > separation && tumble < separation + 0.5 && tumble < event("apogee"),
        "{separation} {tumble}"
    );
    // It lands at the terminal speed of its drag area, m g = ½ ρ v² C_D·A; a given
    // `tumble_drag_area` replaces the estimate.
    let landing_speed = |run: &StagedRun, drag_area: f64| {
        landing_and_terminal_speeds(run, body_index(run, "Booster stage 2"), drag_area)
    };
    let (ours, terminal) = landing_speed(&run, drag_area);
    assert!(
        (ours - terminal).abs() < 0.01 * terminal,
        "{ours} vs {terminal}"
    );
    let mut given = mission.clone();
    given.spec.stages[1].tumble_drag_area = Some(4.0 * drag_area);
    let run = simulate_staged(&given, 0).expect("flies");
    let (ours, terminal) = landing_speed(&run, 4.0 * drag_area);
    assert!(
        (ours - terminal).abs() < 0.01 * terminal,
        "{ours} vs {terminal}"
    );
}

#[test]
fn a_stage_without_parachutes_or_body_lengths_needs_its_tumble_drag_area() {
    let mut mission = imported("three_stage_low_power_rocket");
    mission.spec.stages[1].rocket.drag_estimate = None;
    mission.spec.stages[1].stack_power_off_drag = karman_mission::schema::Curve::Constant(0.6);
    mission.spec.stages[1].stack_power_on_drag = karman_mission::schema::Curve::Constant(0.6);
    let error = simulate_staged(&mission, 0).expect_err("no estimate");
    let mut error: &dyn std::error::Error = &error;
    let mut text = error.to_string();
    while let Some(source) = error.source() {
        text = format!("{text}: {source}");
        error = source;
    }
    let error = text;
    assert!(
        error.contains("stages.1") && error.contains("tumble_drag_area"),
        "{error}"
    );
    mission.spec.stages[1].tumble_drag_area = Some(0.005);
    simulate_staged(&mission, 0).expect("flies");
}

#[test]
fn a_stable_spent_stage_without_parachutes_tumbles_past_its_apogee() {
    let path = repository_fixture("two_stage.toml");
    let text = std::fs::read_to_string(&path).expect("fixture");
    let start = text
        .find("[stages.rocket.parachutes.booster_chute]")
        .expect("the booster's chute");
    let end = text.find("[dispersion]").expect("a study");
    let text = format!(
        "{}{}",
        &text[..start],
        &text[end..].replace(
            "\"stages.0.rocket.parachutes.booster_chute.cd_s\" = { std = 0.1 }\n",
            ""
        )
    )
    .replace(
        "ignition_delay = 1.0\n",
        "ignition_delay = 1.0\ntumble_drag_area = 0.05\n",
    );
    let mission = parse(&text, &path, &[]).expect("mission");
    let run = simulate_staged(&mission, 0).expect("flies");
    let index = body_index(&run, "booster");
    let summary = run.summary(index);
    assert_eq!(summary.termination, Termination::Impact);
    let event = |name: &str| event_time(&summary, name);
    // The first 100 Hz sampling instant past its apogee.
    let (apogee, tumble) = (event("apogee"), event("tumble"));
    assert!(
        tumble > apogee && tumble <= apogee + 0.01 + 1e-9,
        "{apogee} {tumble}"
    );
    // Lands at the terminal speed of the given drag area.
    let (ours, terminal) = landing_and_terminal_speeds(&run, index, 0.05);
    assert!(
        (ours - terminal).abs() < 0.01 * terminal,
        "{ours} vs {terminal}"
    );
}
