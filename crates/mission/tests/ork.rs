//! OpenRocket designs imported (karman-openrocket) and loaded as missions: a motor cluster
//! mapped onto `[motor] cluster_count`, pod sets onto `[rocket.pods]`, ejection charges,
//! tube fins, unlit motors and imported names that cannot inject TOML. The reader's and
//! writer's own errors are karman-openrocket's tests (`crates/openrocket/tests/ork.rs`).

use karman_mission::schema::Trigger;
use karman_openrocket::{ImportOptions, OrkError, document_text, import};
use std::path::{Path, PathBuf};

fn design(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/openrocket")
        .join(name)
        .join("design.ork")
}

fn tempdir() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("karman-ork-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

#[test]
fn pods_import_as_pod_sets_with_their_mass_at_their_offset() {
    let dir = design("pods_airframes_and_winglets")
        .parent()
        .expect("dir")
        .to_owned();
    let options = ImportOptions {
        simulation: Some("Simulation 3".into()),
        output_dir: Some(dir.clone()),
        ..ImportOptions::default()
    };
    let imported = import(&design("pods_airframes_and_winglets"), &options).expect("imports");
    let mission = karman_mission::parse(&imported.mission, &dir.join("imported.toml"), &[])
        .unwrap_or_else(|e| panic!("{e}\n{}", imported.mission));
    let pods = &mission.spec.rocket.pods;
    let wings = &pods["wing_pods"];
    assert_eq!((wings.count, wings.angular_position_deg), (2, 90.0));
    assert_eq!(wings.surfaces, ["pod_nose", "pod_tail"]);
    assert!(wings.body_length.is_some());
    // The phantom pod: fins on a radius-0 tube, no pod body.
    let stab = &pods["horizontal_stab_pod"];
    assert_eq!((stab.count, stab.body_length), (1, None));
    assert_eq!(stab.surfaces, ["horizontal_stabilizer"]);
    assert!(
        imported.mission.contains("radius = 0.0\n"),
        "{}",
        imported.mission
    );
    // OpenRocket's launch mass and CG (Simulation 3, C6-5): within 1 % and 1 mm (the nose
    // tip is the origin, aft positive).
    let reference: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join("reference.json")).expect("reference"),
    )
    .expect("json");
    let ascent = &reference["simulations"][2]["branches"][0]["ascent"];
    let (mass, cg) = (
        ascent["mass_kg"][0].as_f64().expect("mass"),
        ascent["cg_m"][0].as_f64().expect("cg"),
    );
    let motor = karman_mission::assemble::motor::build_motor(&mission).expect("motor");
    let rocket = karman_mission::assemble::rocket::build_rocket(&mission, &motor).expect("rocket");
    let ours = rocket.total_mass(0.0);
    assert!((ours - mass).abs() < 0.01 * mass, "{ours} vs {mass}");
    let ours_cg = rocket.center_of_mass(0.0);
    assert!((ours_cg - cg).abs() < 1e-3, "{ours_cg} vs {cg}");
    // The drawing keeps the pods out of the body: one body tube from the nose to the tail
    // (a pod's nose and tail are no shells of the body), the three pod surfaces dashed.
    let svg = karman_mission::report::rocket::draw_rocket_svg(&mission, &rocket);
    let tubes = svg.lines().filter(|l| l.contains("#eef2f8")).count();
    assert_eq!(tubes, 1, "{svg}");
    for name in ["pod_nose", "pod_tail", "horizontal_stabilizer"] {
        assert!(
            svg.lines()
                .any(|l| l.contains("stroke-dasharray=\"4 3\"") && l.contains(name)),
            "{name}: {svg}"
        );
    }
}

#[test]
fn a_cluster_flies_its_motors_together_at_their_offsets() {
    use karman_mission::assemble::{motor::build_motor, rocket::build_rocket};
    let options = ImportOptions {
        simulation: Some("Simulation 1".into()),
        output_dir: Some(design("clustered_motors").parent().expect("dir").to_owned()),
        ..ImportOptions::default()
    };
    let imported = import(&design("clustered_motors"), &options).expect("imports");
    // OpenRocket's 4-ring: four tubes of radius 9.5 mm, 1.1 diameters apart (closest pair),
    // on a ring of radius 1.1 · 19 mm / √2.
    let radius = 1.1 * 0.019 / 2f64.sqrt();
    assert!(
        imported.mission.contains("cluster_count = 4\n"),
        "{}",
        imported.mission
    );
    let path = design("clustered_motors").with_file_name("imported.toml");
    let cluster = karman_mission::parse(&imported.mission, &path, &[]).expect("loads");
    assert_eq!(cluster.spec.motor.cluster_count, Some(4));
    let r = cluster.spec.motor.cluster_radius.expect("radius");
    assert!((r - radius).abs() < 1e-12, "{r} vs {radius}");
    let mut single = cluster.clone();
    single.spec.motor.cluster_count = None;
    single.spec.motor.cluster_radius = None;
    let motor = build_motor(&cluster).expect("motor");
    let (four, one) = (
        build_rocket(&cluster, &motor).expect("rocket"),
        build_rocket(&single, &motor).expect("rocket"),
    );
    let (m1, m4) = (one.motor(), four.motor());
    for t in [0.1, 0.3, 0.5] {
        assert!((m4.thrust.eval(t) - 4.0 * m1.thrust.eval(t)).abs() < 1e-12);
        assert!((m4.propellant_mass.eval(t) - 4.0 * m1.propellant_mass.eval(t)).abs() < 1e-15);
        let expected = 4.0 * (m1.propellant_i33.eval(t) + m1.propellant_mass.eval(t) * r * r);
        let roll = m4.propellant_i33.eval(t) - expected;
        assert!(roll.abs() <= 1e-12 * expected, "{roll} of {expected}");
    }
    assert!((m4.dry_mass - 4.0 * m1.dry_mass).abs() < 1e-15);
    let lateral = m4.dry_inertia[0] - 4.0 * (m1.dry_inertia[0] + 0.5 * m1.dry_mass * r * r);
    assert!(lateral.abs() < 1e-15, "{lateral}");
    assert!((m4.nozzle_radius - 2.0 * m1.nozzle_radius).abs() < 1e-15);
    // OpenRocket's mass at launch: 0.235 kg, of which 0.065 kg motors.
    let mass = four.total_mass(0.0);
    assert!((mass - 0.235).abs() < 0.01 * 0.235, "{mass}");
}

#[test]
fn imported_missions_load_and_estimate_their_drag() {
    let options = ImportOptions {
        output_dir: Some(design("chute_release").parent().expect("dir").to_owned()),
        ..ImportOptions::default()
    };
    let imported = import(&design("chute_release"), &options).expect("imports");
    assert!(imported.mission.contains("power_off_drag = \"estimate\""));
    let path = design("chute_release").with_file_name("imported.toml");
    karman_mission::parse(&imported.mission, &path, &[]).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn ejection_charges_deploy_their_delay_after_burnout() {
    // A C6-3, C6-5 and C6-7 in the same rocket: the parachute follows each motor's delay,
    // and a design's own deployment delay (0 s here) is the lag.
    let dir = design("a_simple_model_rocket")
        .parent()
        .expect("dir")
        .to_owned();
    for (simulation, delay) in [
        ("Simulation 3 - too short delay", 3.0),
        ("Simulation 4", 5.0),
        ("Simulation 5", 7.0),
    ] {
        let options = ImportOptions {
            simulation: Some(simulation.into()),
            motors: Vec::new(),
            output_dir: Some(dir.clone()),
        };
        let imported = import(&design("a_simple_model_rocket"), &options).expect(simulation);
        let expected = format!("trigger = \"burnout + {delay:?}\"\nlag = 0.0\n");
        assert!(
            imported.mission.contains(&expected),
            "{simulation}:\n{}",
            imported.mission
        );
        assert!(!imported.mission.contains("terminate_on_apogee"));
        let mission = karman_mission::parse(&imported.mission, &dir.join("imported.toml"), &[])
            .unwrap_or_else(|e| panic!("{e}"));
        let chute = mission
            .spec
            .rocket
            .parachutes
            .values()
            .next()
            .expect("a parachute");
        assert_eq!(chute.trigger, Trigger::Burnout(delay), "{simulation}");
    }
}

#[test]
fn tube_fins_import_with_the_touching_radius() {
    // Six tubes touching each other around the body: r = R sin 30° / (1 − sin 30°) = R.
    let dir = design("tube_fin_rocket").parent().expect("dir").to_owned();
    let options = ImportOptions {
        output_dir: Some(dir.clone()),
        ..ImportOptions::default()
    };
    let imported = import(&design("tube_fin_rocket"), &options).expect("imports");
    let mission = karman_mission::parse(&imported.mission, &dir.join("imported.toml"), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    let tubes = mission
        .spec
        .rocket
        .surfaces
        .values()
        .find_map(|s| match s {
            karman_mission::schema::SurfaceSpec::TubeFins(t) => Some(t.clone()),
            _ => None,
        })
        .expect("a tube fin surface");
    let body = tubes.radius.expect("body radius");
    assert_eq!(tubes.n, 6);
    assert!((tubes.outer_radius - body).abs() < 1e-12, "{tubes:?}");
    assert!((tubes.outer_radius - tubes.inner_radius - 3.302e-4).abs() < 1e-9);
}

/// `two_stage_high_power_rocket` with `edit` applied to its document, imported for its
/// second simulation (I59WN sustainer lit at the booster's burn-out, separation at that
/// ignition).
fn edited_two_stage(
    edit: impl Fn(&str) -> String,
) -> Result<karman_openrocket::Imported, OrkError> {
    let path = design("two_stage_high_power_rocket");
    let text = document_text(&path, &std::fs::read(&path).expect("fixture")).expect("document");
    let file = tempdir().join("edited_two_stage.ork");
    std::fs::write(&file, edit(&text)).expect("write");
    let options = ImportOptions {
        simulation: Some("Simulation 2".into()),
        motors: vec![path.parent().expect("dir").to_owned()],
        output_dir: None,
    };
    import(&file, &options)
}

#[test]
fn a_bottom_motor_openrocket_never_lights_rides_as_mass_on_the_stage_above() {
    // The sustainer lit at launch; the booster's motor at the burn-out of a stage below it,
    // which the bottom stage does not have: OpenRocket never lights it.
    let unlit = |separation: &'static str| {
        edited_two_stage(move |t| {
            t.replacen(
                "<ignitionconfiguration configid=\"fadeeef3-4aa4-49e9-9581-71e14fa91c14\">\n                        <ignitionevent>burnout</ignitionevent>",
                "<ignitionconfiguration configid=\"fadeeef3-4aa4-49e9-9581-71e14fa91c14\">\n                        <ignitionevent>launch</ignitionevent>",
                1,
            )
            .replacen(
                "<ignitionconfiguration configid=\"fadeeef3-4aa4-49e9-9581-71e14fa91c14\">\n                    <ignitionevent>automatic</ignitionevent>",
                "<ignitionconfiguration configid=\"fadeeef3-4aa4-49e9-9581-71e14fa91c14\">\n                    <ignitionevent>burnout</ignitionevent>",
                1,
            )
            .replacen(
                "<separationevent>upperignition</separationevent>\n            <separationaltitude>200.0</separationaltitude>",
                &format!("<separationevent>{separation}</separationevent>\n            <separationaltitude>200.0</separationaltitude>"),
                1,
            )
        })
    };
    // Separated at the sustainer's ignition, i.e. at launch: refused by name.
    let e = unlit("upperignition").expect_err("separates at launch");
    assert!(
        e.to_string().contains("Booster") && e.to_string().contains("upperignition"),
        "{e}"
    );
    // Separated at its own motor's burn-out, which never comes: one body, the booster's
    // unlit motor carried whole (its RASP total mass, 0.34944 kg).
    let imported = unlit("burnout").expect("imports");
    assert!(
        !imported.mission.contains("[[stages]]"),
        "{}",
        imported.mission
    );
    assert!(
        imported.warnings.iter().any(|w| w.contains("never lights")),
        "{:?}",
        imported.warnings
    );
    let path = tempdir().join("unlit.toml");
    let one = karman_mission::parse(&imported.mission, &path, &[]).expect("loads");
    let two = karman_mission::parse(
        &edited_two_stage(str::to_owned).expect("imports").mission,
        &path,
        &[],
    )
    .expect("loads");
    let structure = two.spec.rocket.mass + two.spec.stages[0].rocket.mass;
    let carried = one.spec.rocket.mass - structure;
    assert!((carried - 0.34944).abs() < 1e-9, "{carried}");
}

#[test]
fn a_transition_between_equal_radii_is_no_tail() {
    // The base-drag transition made a straight piece of the tube's radius.
    let path = design("base_drag_hack_short_wide");
    let text = document_text(&path, &std::fs::read(&path).expect("fixture")).expect("document");
    let edited = text.replacen(
        "<foreradius>1.5142307692307692E-5</foreradius>",
        "<foreradius>0.03937</foreradius>",
        1,
    );
    assert_ne!(edited, text);
    let file = tempdir().join("equal_transition.ork");
    std::fs::write(&file, edited).expect("write");
    let options = ImportOptions {
        motors: vec![path.parent().expect("dir").to_owned()],
        ..ImportOptions::default()
    };
    let imported = import(&file, &options).expect("imports");
    assert!(
        !imported.mission.contains("type = \"tail\""),
        "{}",
        imported.mission
    );
    assert!(
        imported
            .warnings
            .iter()
            .any(|w| w.contains("Base-Drag Hack Transition") && w.contains("piece of tube")),
        "{:?}",
        imported.warnings
    );
    let mission =
        karman_mission::parse(&imported.mission, &file.with_extension("toml"), &[]).expect("loads");
    karman_mission::assemble::preflight::prepare(&mission, 0).expect("builds");
}

/// Names are the design's to choose, and they reach the mission's comments and warnings: a
/// name holding newlines, quotes, brackets, `#` and TOML of its own must not add a line of
/// TOML. The hostile import (the rocket, nose cone, body tube and a file name so named) has
/// exactly the clean import's tables and the same motor, and reads back as a mission.
#[test]
fn imported_names_cannot_inject_toml() {
    let path = design("two_stage_high_power_rocket");
    let text = document_text(&path, &std::fs::read(&path).expect("fixture")).expect("document");
    let injected = "Evil\n[[extra_motors]]\nthrust = \"x.eng\"\nposition = 0.1\n# \"]'#";
    let entity = "Evil&#10;[motor]&#13;&#10;kind = &quot;generic&quot;&#9;# [x] \\ \"";
    let mut hostile = text.replacen(
        &format!("<name>{}</name>", first_name(&text)),
        &format!("<name>{injected}</name>"),
        1,
    );
    for (i, tag) in ["<nosecone>", "<bodytube>"].iter().enumerate() {
        let at = hostile.find(tag).expect("component") + tag.len();
        let open = hostile[at..].find("<name>").expect("its name") + at + "<name>".len();
        let close = hostile[open..].find("</name>").expect("end") + open;
        let name = if i == 0 { entity } else { injected };
        hostile.replace_range(open..close, name);
    }
    let options = |dir: &Path| ImportOptions {
        simulation: Some("Simulation 2".into()),
        motors: vec![dir.to_owned()],
        output_dir: None,
    };
    let dir = path.parent().expect("dir");
    let clean = import(&path, &options(dir)).expect("clean import");
    let file = tempdir().join("evil\n[motor]\n.ork");
    std::fs::write(&file, &hostile).expect("write");
    let evil = import(&file, &options(dir)).expect("hostile import");
    let tables = |t: &str| -> Vec<String> {
        t.lines()
            .filter(|l| l.trim_start().starts_with('['))
            .map(str::to_owned)
            .collect()
    };
    // The surfaces' table keys come from the (sanitised) names; every other header is the
    // clean import's, and there are as many.
    let (clean_tables, evil_tables) = (tables(&clean.mission), tables(&evil.mission));
    assert_eq!(clean_tables.len(), evil_tables.len(), "{}", evil.mission);
    for (c, e) in clean_tables.iter().zip(&evil_tables) {
        if !c.contains("nose") && !c.contains("body") {
            assert_eq!(c, e, "{}", evil.mission);
        }
    }
    let read = |t: &str, name: &str| {
        karman_mission::parse(t, &tempdir().join(name), &[]).unwrap_or_else(|e| panic!("{e}\n{t}"))
    };
    let (a, b) = (
        read(&clean.mission, "clean.toml"),
        read(&evil.mission, "evil.toml"),
    );
    assert_eq!(format!("{:?}", a.spec.motor), format!("{:?}", b.spec.motor));
    assert_eq!(a.spec.extra_motors.len(), b.spec.extra_motors.len());
    assert_eq!(a.spec.stages.len(), b.spec.stages.len());
    assert!(
        b.spec
            .name
            .as_deref()
            .is_some_and(|n| n.starts_with("Evil [[extra_motors]]"))
    );
    assert!(!evil.mission.contains("\r") && !evil.mission.contains('\t'));
}

/// The content of the first `<name>` element of `xml`.
fn first_name(xml: &str) -> &str {
    let open = xml.find("<name>").expect("a name") + "<name>".len();
    &xml[open..open + xml[open..].find("</name>").expect("end")]
}
