//! Hybrid and liquid motors through the mission: the liquid fixture (one tank of each kind and
//! geometry) loads, builds and flies; bad tank inputs are located at their key; tank inputs are
//! reachable by `--set`; arbitrary tank numbers never panic the build; and the pointwise sums
//! of liquid motors on different grids and of hybrids match RocketPy 1.13.

use crate::common::fixture;
use karman_mission::assemble::motor::build_motor;
use karman_mission::{Location, MissionError, Override, ProblemKind, load, parse};
use proptest::prelude::*;

fn overrides(items: &[&str]) -> Vec<Override> {
    items
        .iter()
        .map(|o| o.parse().expect("well-formed override"))
        .collect()
}

fn liquid_text() -> String {
    std::fs::read_to_string(fixture("liquid.toml")).expect("fixture readable")
}

#[test]
fn the_liquid_fixture_builds_its_four_tanks() {
    let mission = load(&fixture("liquid.toml"), &[]).expect("loads");
    let motor = build_motor(&mission).expect("builds");
    let tanks = motor.tanks();
    let kinds: Vec<&str> = tanks
        .iter()
        .map(|p| p.tank.spec().kind.class_name())
        .collect();
    assert_eq!(
        kinds,
        [
            "MassFlowRateBasedTank",
            "UllageBasedTank",
            "LevelBasedTank",
            "MassBasedTank"
        ]
    );
    // The tanks are on different grids (the level tank has 50 nodes): the propellant is their
    // pointwise sum, tabulated on the union of the grids.
    for &t in tanks[2].tank.mass().xs().iter().step_by(7) {
        let sum: f64 = tanks.iter().map(|p| p.tank.mass().eval(t)).sum();
        assert!((motor.propellant_mass().eval(t) - sum).abs() < 1e-12, "{t}");
    }
    assert!((motor.propellant_initial_mass() - motor.propellant_mass().eval(0.0)).abs() < 1e-15);
    // The mass tank holds no liquid; the level tank's gas density is read from its (T, p)
    // table at 290 K and 101 325 Pa: on the edge between its first two rows, 1.2210 kg/m³.
    assert!(tanks[3].tank.liquid_mass().eval(2.0).abs() < 1e-15);
    let gas = tanks[2].tank.gas_mass().eval(0.0);
    let volume =
        tanks[2].tank.spec().geometry.total_volume() - tanks[2].tank.spec().geometry.volume(0.08);
    let rho = gas / volume;
    let edge = 1.29 + (290.0 - 273.15) / (300.0 - 273.15) * (1.18 - 1.29);
    assert!((rho - edge).abs() < 1e-9, "{rho}");
    let run = karman_mission::assemble::flight::simulate(&mission).expect("flies");
    let summary = karman_mission::report::flight::flight_summary(&run);
    assert!(summary.apogee_agl_m.is_some_and(|a| a > 100.0));
}

#[test]
fn bad_tank_inputs_name_their_key_and_line() {
    let path = fixture("liquid.toml");
    // A checked key: located at its value.
    let text = liquid_text().replacen("initial_liquid_mass = 2.5", "initial_liquid_mass = -2.5", 1);
    match parse(&text, &path, &[]) {
        Err(MissionError::Invalid { problems, .. }) => {
            let p = &problems[0];
            assert_eq!(p.key, "motor.tanks.0.initial_liquid_mass");
            assert!(
                matches!(p.location, Location::File { line: 33, .. }),
                "{p:?}"
            );
            assert!(matches!(p.kind, ProblemKind::OutOfRange { .. }));
        }
        other => panic!("{other:?}"),
    }
    // A key of another kind.
    let text = liquid_text().replacen("ullage = [[0", "liquid_mass = 1\nullage = [[0", 1);
    let Err(MissionError::Invalid { problems, .. }) = parse(&text, &path, &[]) else {
        panic!("accepted a liquid_mass in an ullage tank");
    };
    assert_eq!(problems[0].key, "motor.tanks.1.liquid_mass");
    // An overfilled tank is a model error located at the tank.
    let mission = load(
        &path,
        &overrides(&["motor.tanks.0.initial_liquid_mass=5.0"]),
    )
    .expect("loads");
    let error = build_motor(&mission).expect_err("overfilled");
    let source = std::error::Error::source(&error).map(ToString::to_string);
    let text = format!("{error}: {}", source.unwrap_or_default());
    assert!(
        text.contains("motor.tanks.0") && text.contains("exceeds the tank volume"),
        "{text}"
    );
    let MissionError::Model { location, .. } = &error else {
        panic!("{error:?}");
    };
    assert!(location.is_some(), "{error:?}");
    // Density tables RocketPy refuses (two rows; rows on one line of the (T, p) plane): model
    // errors located at the density key.
    let table = "[[273.15, 101325, 1.29], [300, 101325, 1.18], [290, 200000, 2.40]]";
    for (bad, reason) in [
        (
            "[[273.15, 101325, 1.29], [300, 101325, 1.18]]",
            "at least 3 point",
        ),
        (
            "[[273.15, 101325, 1.29], [300, 101325, 1.18], [320, 101325, 1.1]]",
            "on one line",
        ),
    ] {
        let text = liquid_text().replacen(table, bad, 1);
        let mission = parse(&text, &path, &[]).expect("parses");
        let error = build_motor(&mission).expect_err("refused");
        // The whole chain, as every consumer prints it (each error says its own part once).
        let message = crate::common::chain(&error);
        assert!(
            message.contains("motor.tanks.2.gas.density") && message.contains(reason),
            "{message}"
        );
        let MissionError::Model { location, .. } = &error else {
            panic!("{error:?}");
        };
        assert!(
            matches!(location, Some(Location::File { line: 56, .. })),
            "{error:?}"
        );
    }
    // A missing tank list, and a tank list on a solid motor.
    let text = liquid_text();
    let cut = text.find("[[motor.tanks]]").expect("tanks");
    let end = text.find("[rocket]").expect("rocket");
    let without = format!("{}{}", &text[..cut], &text[end..]);
    let Err(MissionError::Invalid { problems, .. }) = parse(&without, &path, &[]) else {
        panic!("a liquid motor without tanks loaded");
    };
    assert_eq!(problems[0].key, "motor.tanks");
}

#[test]
fn tank_inputs_are_reachable_by_set() {
    let path = fixture("liquid.toml");
    let set = overrides(&[
        "motor.tanks.0.position=0.55",
        "motor.tanks.0.liquid.density=800",
        "motor.tanks.1.geometry.radius=0.125",
        "motor.tanks.3.flux_time=[0, 4.0]",
        "environment.earth_model.latitude=10",
    ]);
    let mission = load(&path, &set).expect("loads");
    let tanks = &mission.spec.motor.tanks;
    assert!((tanks[0].position - 0.55).abs() < 1e-15);
    assert!((tanks[3].flux_time.end - 4.0).abs() < 1e-15);
    let motor = build_motor(&mission).expect("builds");
    assert!((motor.tanks()[0].position - 0.55).abs() < 1e-15);
    let Err(MissionError::Invalid { problems, .. }) =
        load(&path, &overrides(&["motor.tanks.7.position=1"]))
    else {
        panic!("an index past the tanks was accepted");
    };
    assert!(matches!(problems[0].kind, ProblemKind::UnknownPath { .. }));
    // Dotted paths (Monte Carlo): numbers and curves of tanks.
    let spec = &mission.spec;
    for (path, value) in [
        ("motor.tanks.0.initial_liquid_mass", 2.5),
        ("motor.tanks.0.flux_time", 4.5),
        ("motor.tanks.2.discretize", 50.0),
        ("motor.tanks.0.gas_mass_flow_rate_in", 0.02),
    ] {
        match karman_mission::paths::resolve(spec, path).expect(path) {
            karman_mission::paths::Input::Number { value: v, .. } => {
                assert!((v - value).abs() < 1e-12, "{path}");
            }
            other => panic!("{path}: {other:?}"),
        }
    }
    assert!(matches!(
        karman_mission::paths::resolve(spec, "motor.tanks.1.ullage"),
        Ok(karman_mission::paths::Input::Curve(_))
    ));
    let mut varied = spec.clone();
    karman_mission::paths::set_number(&mut varied, "motor.tanks.0.initial_liquid_mass", 2.0)
        .expect("settable");
    assert_eq!(varied.motor.tanks[0].initial_liquid_mass, Some(2.0));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Any number in any tank input: the mission is rejected or builds, never panics.
    #[test]
    fn arbitrary_tank_numbers_never_panic(
        tank in 0usize..4,
        key in prop::sample::select(vec![
            "position", "flux_time", "initial_liquid_mass", "initial_gas_mass",
            "geometry.radius", "geometry.height", "liquid.density", "gas.density",
            "discretize", "ullage", "liquid_height", "gas_mass", "temperature",
            "liquid_mass_flow_rate_out",
        ]),
        value in prop::sample::select(vec![
            "0", "-1", "1e300", "-1e-300", "nan", "inf", "0.5", "1e-9", "100", "[[0, 1]]",
            "[[1, 0], [0, 1]]", "[]", "\"x\"", "true",
        ]),
    ) {
        let item = format!("motor.tanks.{tank}.{key}={value}");
        if let Ok(item) = item.parse::<Override>() {
            if let Ok(mission) = parse(&liquid_text(), &fixture("liquid.toml"), &[item]) {
                let _ = build_motor(&mission);
            }
        }
    }
}

#[test]
fn tanks_without_resampling_keep_their_points_or_are_located_errors() {
    let path = fixture("liquid.toml");
    // The ullage tank keeps its two points.
    let text = liquid_text().replacen("ullage = [[0", "discretize = false\nullage = [[0", 1);
    let mission = parse(&text, &path, &[]).expect("loads");
    let motor = build_motor(&mission).expect("builds");
    assert_eq!(motor.tanks()[1].tank.mass().xs(), [0.0, 4.5]);
    // A mass-flow-rate tank, and a mass tank with a constant mass: RocketPy 1.13 builds
    // neither without resampling.
    for (anchor, key) in [
        ("initial_liquid_mass = 2.5", "motor.tanks.0.discretize"),
        ("liquid_mass = 0", "motor.tanks.3.liquid_mass"),
    ] {
        let text = liquid_text().replacen(anchor, &format!("discretize = false\n{anchor}"), 1);
        let Err(MissionError::Invalid { problems, .. }) = parse(&text, &path, &[]) else {
            panic!("accepted discretize = false before {anchor}");
        };
        assert_eq!(problems[0].key, key);
        assert!(matches!(problems[0].location, Location::File { .. }));
    }
}

/// RocketPy 1.13.0's rocket of `fixtures/parity/liquid_docs` with its fuel tank on another
/// grid (`discretize=60`, `flux_time=5.5`): the motor's sums are then pointwise `Function`s.
/// Measured with RocketPy 1.13.0 (`/work/venv-h22`, the mission rebuilt by
/// `fixtures/parity/make_references.py` with those two arguments changed): `rocket.total_mass(t)`,
/// `rocket.com_to_cdm_function(t)` and its `differentiate_complex_step(t)`, `rocket.I_11(t)`
/// and its `differentiate_complex_step(t)`, at the times of `TIMES`.
mod pointwise {
    pub const TIMES: [f64; 10] = [0.013, 0.37, 1.234, 2.5, 3.333, 4.05, 4.999, 5.2, 5.6, 7.0];
    pub const TOTAL_MASS: [f64; 10] = [
        69.38646771264476,
        63.37102256210018,
        50.85460774212517,
        36.770290764467305,
        29.658635386610097,
        24.617833322765836,
        19.239201486727897,
        19.21545868008571,
        19.21478302251894,
        19.21478302251894,
    ];
    pub const COM_TO_CDM: [f64; 10] = [
        0.8274489454017675,
        0.8379347785021258,
        0.8315262445196181,
        0.7383730674931693,
        0.6174550782031785,
        0.4697255932972982,
        0.2019728587305637,
        0.20111688928316976,
        0.2010979258091878,
        0.2010979258091878,
    ];
    pub const COM_TO_CDM_RATE: [f64; 10] = [
        0.039213734773088,
        0.01857759908764062,
        -0.03358947690320813,
        -0.11520799411720191,
        -0.17646531011649136,
        -0.23705582339071066,
        -0.30091467068749445,
        -0.0010202453162490195,
        0.0,
        0.0,
    ];
    pub const I11: [f64; 10] = [
        114.06045993606425,
        108.83626821058772,
        95.04140088237536,
        73.7765151872827,
        60.303828869054755,
        49.50829105991515,
        36.6806000524412,
        36.65760151855136,
        36.65723024640934,
        36.65723024640934,
    ];
    pub const I11_RATE: [f64; 10] = [
        -14.151916103284945,
        -15.139692757488868,
        -16.59063456068377,
        -16.619978828453725,
        -15.638889429723273,
        -14.437827128988346,
        -12.024913515758934,
        -0.01997627738840408,
        0.0,
        0.0,
    ];
}

#[test]
fn tanks_on_different_grids_are_summed_pointwise_as_rocketpy() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/parity/liquid_docs/mission.toml");
    let set = overrides(&["motor.tanks.1.discretize=60", "motor.tanks.1.flux_time=5.5"]);
    let mission = load(&path, &set).expect("loads");
    let motor = build_motor(&mission).expect("builds");
    assert_eq!(motor.propellant_parts().len(), 2);
    let rocket = karman_mission::assemble::rocket::build_rocket(&mission, &motor).expect("rocket");
    let close = |got: f64, want: f64, scale: f64, what: &str, t: f64| {
        assert!(
            (got - want).abs() <= 1e-9 * scale,
            "{what} at {t} s: {got} vs RocketPy {want}"
        );
    };
    for (k, &t) in pointwise::TIMES.iter().enumerate() {
        let p = rocket.mass_properties(t);
        close(
            p.total_mass,
            pointwise::TOTAL_MASS[k],
            70.0,
            "total mass",
            t,
        );
        close(p.com_to_cdm, pointwise::COM_TO_CDM[k], 1.0, "com_to_cdm", t);
        close(
            p.com_to_cdm_rate,
            pointwise::COM_TO_CDM_RATE[k],
            1.0,
            "com_to_cdm rate",
            t,
        );
        close(p.inertia[0], pointwise::I11[k], 115.0, "I11", t);
        close(
            p.inertia_rate[0],
            pointwise::I11_RATE[k],
            17.0,
            "I11 rate",
            t,
        );
    }
}

/// RocketPy 1.13.0's hybrid_docs rocket (built by `fixtures/parity/make_references.py`'s
/// `motor` with `Rocket(radius, mass, inertia, drag 0.5, center_of_mass_without_motor,
/// coordinate_system_orientation).add_motor(motor, motor_position)`, rocketpy==1.13.0): at
/// `t`, `total_mass`, `com_to_cdm_function` with its `differentiate_complex_step` and
/// `differentiate(order=2)`, and the inertia tensor's and its derivative's `xx`.
mod hybrid_pointwise {
    pub const TIMES: [f64; 6] = [0.25, 1.0, 1.7, 2.6, 3.3, 3.85];
    pub const FIGURES: [[f64; 6]; 6] = [
        [
            24.240659943852528,
            0.16467826922196713,
            -0.02661255031142055,
            -0.005523359547510154,
            10.728612467958106,
            -0.6931124000905484,
        ],
        [
            22.88642607596033,
            0.14387321513183132,
            -0.028888588760412014,
            -0.006050715484207103,
            10.224424080115002,
            -0.6515444091583762,
        ],
        [
            21.677348510157984,
            0.12280996690808214,
            -0.03125787556670814,
            -0.006675215935558754,
            9.78010510857243,
            -0.6167825393014185,
        ],
        [
            20.20052909236822,
            0.09319565488606513,
            -0.03470718675606761,
            -0.0073968609015651055,
            9.243710403888798,
            -0.5776222466343985,
        ],
        [
            19.11245152292065,
            0.06804677371035955,
            -0.037124769616582044,
            -0.007868705687030797,
            8.851962161028606,
            -0.5414392842485786,
        ],
        [
            18.294756199092763,
            0.04690707548147542,
            -0.03978464410865514,
            -0.008396061623727746,
            8.558806249718652,
            -0.5249311990297493,
        ],
    ];
}

#[test]
fn hybrid_grain_and_tanks_are_summed_pointwise_as_rocketpy() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/parity/hybrid_docs/mission.toml");
    let mission = load(&path, &[]).expect("loads");
    let motor = build_motor(&mission).expect("builds");
    // The grain and the tank (one grid) as two parts.
    assert_eq!(motor.propellant_parts().len(), 2);
    let rocket = karman_mission::assemble::rocket::build_rocket(&mission, &motor).expect("rocket");
    // After the burn the one-pass figures are settled ones: still the individual methods'.
    #[allow(clippy::float_cmp)] // the same arithmetic on the same numbers: equal to the bit.
    for t in [5.2, 8.0, 60.0] {
        let p = rocket.mass_properties(t);
        assert_eq!(p.total_mass, rocket.total_mass(t));
        assert_eq!(p.com_to_cdm, rocket.com_to_cdm(t));
        assert_eq!(p.com_to_cdm_rate, rocket.com_to_cdm_rate(t));
        assert_eq!(p.com_to_cdm_accel, rocket.com_to_cdm_accel(t));
        assert_eq!(p.inertia, rocket.inertia(t));
        assert_eq!(p.inertia_rate, rocket.inertia_rate(t));
    }
    for (&t, want) in hybrid_pointwise::TIMES
        .iter()
        .zip(&hybrid_pointwise::FIGURES)
    {
        let p = rocket.mass_properties(t);
        let got = [
            p.total_mass,
            p.com_to_cdm,
            p.com_to_cdm_rate,
            p.com_to_cdm_accel,
            p.inertia[0],
            p.inertia_rate[0],
        ];
        // The one-pass figures are the individual methods'.
        let single = [
            rocket.total_mass(t),
            rocket.com_to_cdm(t),
            rocket.com_to_cdm_rate(t),
            rocket.com_to_cdm_accel(t),
            rocket.inertia(t)[0],
            rocket.inertia_rate(t)[0],
        ];
        for (a, b) in got.iter().zip(single) {
            assert!(
                (a - b).abs() <= 1e-12 * b.abs().max(1e-3),
                "{a} vs {b} at {t} s"
            );
        }
        // The grain regresses exactly here and by LSODA in RocketPy (on its own output times,
        // linear between them): measured, the mass, c and I11 agree to 4e-6, 2e-5 and 5e-6 of
        // their scale, the rates to 0.5 % and c̈ to 1.2 % (a node-wise sum would give c̈ = 0).
        let scales = [25.0, 0.2, 0.04, 0.008, 11.0, 0.7];
        let tolerances = [1e-5, 5e-5, 1e-2, 3e-2, 2e-5, 1e-2];
        for k in 0..6 {
            assert!(
                (got[k] - want[k]).abs() <= tolerances[k] * scales[k],
                "figure {k} at {t} s: {} vs RocketPy {}",
                got[k],
                want[k]
            );
        }
    }
}
