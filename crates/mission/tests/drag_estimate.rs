//! `power_off_drag = "estimate"`: the body implied by the surfaces, the estimate's tables,
//! the errors of an incomplete geometry, and a Monte Carlo factor on the estimate.

use crate::common::fixture;
use karman_airframe::{BodySegment, DragGeometry, DragModel, FinCrossSection, FinSetDrag, Profile};
use karman_math::PhysicalConstants;
use karman_mission::assemble::drag::launch_air;
use karman_mission::assemble::flight::simulate;
use karman_mission::assemble::motor::build_motor;
use karman_mission::assemble::motors::ThrustCache;
use karman_mission::assemble::rocket::{EstimateScaling, build_rocket, build_rocket_scaled};
use karman_mission::montecarlo::{MonteCarlo, StudyOverrides};
use karman_mission::{Override, load};

fn load_with(sets: &[(&str, &str)]) -> karman_mission::Mission {
    let overrides: Vec<Override> = sets
        .iter()
        .map(|(p, v)| Override::new(p, v).expect("override"))
        .collect();
    load(&fixture("estimate.toml"), &overrides).unwrap_or_else(|e| panic!("{e}"))
}

/// The fixture's geometry written out: ogive nose 0.2 m from the tip at 0.9 m, a tube of
/// radius 0.04 m to the fins' trailing edge at −0.72 m (1.62 m from the tip), three fins.
fn by_hand() -> DragGeometry {
    let k = 20e-6;
    DragGeometry {
        reference_radius: 0.04,
        body: vec![
            BodySegment {
                name: "nose".into(),
                length: 0.2,
                fore_radius: 0.0,
                aft_radius: 0.04,
                profile: Profile::Ogive(1.0),
                roughness: k,
                drag_override: None,
            },
            BodySegment {
                name: "tube".into(),
                length: 1.42,
                fore_radius: 0.04,
                aft_radius: 0.04,
                profile: Profile::Conical,
                roughness: k,
                drag_override: None,
            },
        ],
        fins: vec![FinSetDrag {
            name: "fins".into(),
            count: 3,
            // RocketPy's default sweep: the tip's trailing edge above the root's.
            outline: vec![[0.0, 0.0], [0.07, 0.08], [0.12, 0.08], [0.12, 0.0]],
            position: 1.5,
            thickness: 0.003,
            cross_section: FinCrossSection::Rounded,
            roughness: k,
        }],
        tube_fins: Vec::new(),
        launch_lugs: Vec::new(),
        rail_buttons: None,
        nozzle_exit_radius: 0.02,
        pods: Vec::new(),
    }
}

#[test]
fn the_estimate_flies_the_geometry_of_the_surfaces() {
    let mission = load_with(&[]);
    let motor = build_motor(&mission).expect("motor");
    let rocket = build_rocket(&mission, &motor).unwrap_or_else(|e| panic!("{e}"));
    let model = DragModel::new(&by_hand(), &PhysicalConstants::SI).expect("geometry");
    let air = launch_air(1400.0, &PhysicalConstants::SI);
    for mach in [0.0, 0.15, 0.5, 0.95, 1.2, 2.0, 3.0] {
        let c = model.components(mach, mach * air.speed_of_sound, air.kinematic_viscosity);
        let off = rocket.drag_coefficient(false, mach);
        let on = rocket.drag_coefficient(true, mach);
        assert!(
            (off - c.power_off()).abs() < 1e-12,
            "Mach {mach}: {off} vs {}",
            c.power_off()
        );
        assert!(
            (on - c.power_on()).abs() < 1e-12,
            "Mach {mach}: {on} vs {}",
            c.power_on()
        );
        // The jet fills a quarter of the base (nozzle 0.02 m, body 0.04 m).
        assert!(on < off);
    }
    let subsonic = rocket.drag_coefficient(false, 0.3);
    assert!((0.25..0.6).contains(&subsonic), "Cd {subsonic}");
}

#[test]
fn a_fin_table_must_name_a_fin_set() {
    let text = std::fs::read_to_string(fixture("estimate.toml")).expect("fixture");
    let text = text.replace(
        "[rocket.drag_estimate.fins.fins]\nthickness = 0.003\n",
        "[rocket.drag_estimate.fins.other]\nthickness = 0.003\n",
    );
    let error = karman_mission::parse(&text, &fixture("estimate.toml"), &[])
        .expect_err("unknown fin set")
        .to_string();
    assert!(error.contains("rocket.drag_estimate.fins.other"), "{error}");
}

#[test]
fn an_estimate_without_a_nose_is_refused() {
    let mission = load_with(&[]);
    let mut mission = mission;
    mission.spec.rocket.surfaces.shift_remove("nose");
    let motor = build_motor(&mission).expect("motor");
    let error = build_rocket(&mission, &motor).expect_err("no nose");
    let text = format!(
        "{error}: {}",
        std::error::Error::source(&error)
            .map(ToString::to_string)
            .unwrap_or_default()
    );
    assert!(text.contains("rocket.drag_estimate"), "{text}");
    assert!(text.contains("nose cone"), "{text}");
}

#[test]
fn a_fin_set_without_thickness_is_named() {
    let mut mission = load_with(&[]);
    if let Some(d) = mission.spec.rocket.drag_estimate.as_mut() {
        d.fins.clear();
    }
    let motor = build_motor(&mission).expect("motor");
    let error = build_rocket(&mission, &motor).expect_err("no thickness");
    let text = std::error::Error::source(&error)
        .map(ToString::to_string)
        .unwrap_or_default();
    assert!(text.contains("[rocket.drag_estimate.fins.fins]"), "{text}");
}

#[test]
fn a_factor_or_offset_on_an_estimated_curve_changes_each_samples_estimate() {
    let path = fixture("estimate.toml");
    let text = std::fs::read_to_string(&path).expect("fixture")
        + "\n[dispersion]\nsamples = 4\nseed = 1\n\n[dispersion.vary]\n\
           \"rocket.power_off_drag\" = { factor = { normal = [1, 0.1] } }\n\
           \"rocket.power_on_drag\" = { offset = { normal = [0, 0.02] } }\n";
    let mission = karman_mission::parse(&text, &path, &[]).unwrap_or_else(|e| panic!("{e}"));
    let motor = build_motor(&mission).expect("motor");
    let nominal = build_rocket(&mission, &motor).expect("rocket");
    let scaling = EstimateScaling {
        power_off: [1.25, 0.0],
        power_on: [1.0, 0.02],
    };
    let scaled = build_rocket_scaled(
        &mission,
        &motor,
        scaling,
        &ThrustCache::read(&mission).expect("thrusts"),
    )
    .expect("scaled rocket");
    for mach in [0.1, 0.9, 2.0] {
        let off = nominal.drag_coefficient(false, mach);
        let on = nominal.drag_coefficient(true, mach);
        assert!((scaled.drag_coefficient(false, mach) - 1.25 * off).abs() < 1e-12);
        assert!((scaled.drag_coefficient(true, mach) - (on + 0.02)).abs() < 1e-12);
    }
    let mc = MonteCarlo::new(&mission, StudyOverrides::default()).expect("study");
    let columns: Vec<String> = mc.study().inputs.iter().map(|i| i.column()).collect();
    assert_eq!(
        columns,
        [
            "rocket.power_off_drag:factor",
            "rocket.power_on_drag:offset"
        ]
    );
    let apogee = |values: &[f64]| mc.fly(0, values).expect("flight").values()[0].expect("apogee");
    // Factor 1 and offset 0 fly the nominal estimate exactly; more drag flies lower.
    let neutral = apogee(&[1.0, 0.0]);
    let flown = simulate(&mission).expect("nominal flight").summary();
    assert_eq!(Some(neutral), flown.apogee_agl_m);
    assert!(apogee(&[1.2, 0.0]) < neutral);
    assert!(apogee(&[0.8, 0.0]) > neutral);
    assert!(apogee(&[1.0, 0.05]) < neutral);
}
