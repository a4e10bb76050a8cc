//! The rocket of every validation mission against RocketPy 1.13's `reference.json`
//! (`rocket`), the acceptance of the airframe issue: static margin at t = 0 and at burn-out
//! within 0.01 calibre, the Mach-0 centre of pressure within 1 mm, each surface's CNα within
//! 0.1 % and its CP within 1 mm, total mass, dry mass and centre of mass at t = 0 within 0.1 %.
//! The worst errors are printed per mission (`cargo test -- --nocapture`).

use crate::common::{load_reference, validation_missions};
use karman_mission::assemble::motor::build_motor;
use karman_mission::assemble::rocket::build_rocket;
use karman_mission::report::rocket::{RocketReport, draw_rocket_svg};
use serde_json::Value;

fn number(reference: &Value, key: &str) -> f64 {
    reference["rocket"][key]
        .as_f64()
        .unwrap_or_else(|| panic!("reference.json lacks rocket.{key}"))
}

fn relative(ours: f64, theirs: f64) -> f64 {
    (ours - theirs).abs() / theirs.abs()
}

#[test]
fn validate_rocket_against_reference() {
    let Some(missions) = validation_missions() else {
        println!("validation data folder absent: validate_rocket_against_reference skipped");
        return;
    };
    assert!(!missions.is_empty());
    let mut failures = Vec::new();
    println!(
        "{:<16} {:>10} {:>10} {:>10} {:>10} {:>10} {:>10}",
        "mission", "mass rel", "CM rel", "CP mm", "SM0 cal", "SMbo cal", "CNα rel"
    );
    for path in missions {
        let flight = path.parent().and_then(|p| p.file_name()).map_or_else(
            || path.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        );
        let mission = karman_mission::load(&path, &[]).expect("mission loads");
        let motor = build_motor(&mission).expect("motor builds");
        let rocket = build_rocket(&mission, &motor).expect("rocket builds");
        let reference = load_reference(&path);
        let ours = RocketReport::new(&rocket);

        let mass = relative(
            ours.total_mass_t0_kg,
            number(&reference, "total_mass_t0_kg"),
        )
        .max(relative(
            ours.dry_mass_kg,
            number(&reference, "dry_mass_kg"),
        ));
        let cm = relative(
            ours.center_of_mass_t0_m,
            number(&reference, "center_of_mass_t0_m"),
        );
        let mut cp = (ours.cp_position_mach0_m - number(&reference, "cp_position_mach0_m")).abs();
        let sm0 = (ours.static_margin_t0 - number(&reference, "static_margin_t0")).abs();
        let smb = (ours.static_margin_burnout - number(&reference, "static_margin_burnout")).abs();
        let surfaces = reference["rocket"]["surfaces"]
            .as_array()
            .expect("surfaces array");
        assert_eq!(
            surfaces.len(),
            ours.surfaces.len(),
            "{flight}: surface count"
        );
        let mut cn = 0.0f64;
        for (s, r) in ours.surfaces.iter().zip(surfaces) {
            assert_eq!(
                Some(s.name.as_str()),
                r["name"].as_str(),
                "{flight}: surface order"
            );
            let want = r["cn_alpha_mach0"].as_f64().expect("cn_alpha_mach0");
            cn = cn.max(relative(s.cn_alpha_mach0, want));
            cp = cp.max((s.cp_m - r["cp_m"].as_f64().expect("cp_m")).abs());
        }
        println!(
            "{flight:<16} {mass:>10.2e} {cm:>10.2e} {:>10.2e} {sm0:>10.2e} {smb:>10.2e} {cn:>10.2e}",
            cp * 1e3
        );
        let checks = [
            ("mass", mass, 1e-3),
            ("centre of mass", cm, 1e-3),
            ("CP (m)", cp, 1e-3),
            ("static margin t0", sm0, 0.01),
            ("static margin burn-out", smb, 0.01),
            ("surface CNα", cn, 1e-3),
        ];
        for (what, error, tolerance) in checks {
            // `is_nan` too: a NaN error must fail.
            if error.is_nan() || error > tolerance {
                failures.push(format!("{flight}: {what} error {error:e} > {tolerance:e}"));
            }
        }
        // The drawing is well-formed SVG text with both markers.
        let svg = draw_rocket_svg(&mission, &rocket);
        assert!(
            svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"),
            "{flight}"
        );
        assert!(svg.contains("centre of pressure") && svg.contains("centre of mass"));
        assert!(!svg.contains("NaN"), "{flight}: NaN in the drawing");
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn rocket_report_serializes_with_reference_keys() {
    let Some(missions) = validation_missions() else {
        println!("validation data folder absent: skipped");
        return;
    };
    let Some(path) = missions
        .iter()
        .find(|p| p.to_string_lossy().contains("calisto"))
    else {
        return;
    };
    let mission = karman_mission::load(path, &[]).expect("mission loads");
    let motor = build_motor(&mission).expect("motor builds");
    let rocket = build_rocket(&mission, &motor).expect("rocket builds");
    let report = RocketReport::new(&rocket);
    let json: Value = serde_json::to_value(&report).expect("serializable");
    let text = std::fs::read_to_string(path.with_file_name("reference.json")).expect("readable");
    let reference: Value = serde_json::from_str(&text).expect("JSON");
    let keys = |v: &Value| {
        let mut k: Vec<String> = v.as_object().expect("object").keys().cloned().collect();
        k.sort();
        k
    };
    assert_eq!(keys(&json), keys(&reference["rocket"]));
    assert_eq!(
        keys(&json["surfaces"][0]),
        keys(&reference["rocket"]["surfaces"][0])
    );
    // The readable table (`karman inspect`), rounded to its printed digits.
    insta::assert_snapshot!("calisto_rocket_report", report.to_string());
}

#[test]
fn impossible_surface_is_a_model_error_naming_its_table() {
    let Some(missions) = validation_missions() else {
        println!("validation data folder absent: skipped");
        return;
    };
    let Some(path) = missions
        .iter()
        .find(|p| p.to_string_lossy().contains("calisto"))
    else {
        return;
    };
    // A tail with equal radii is a straight tube: the airframe refuses it.
    let set: karman_mission::Override = "rocket.surfaces.tail.bottom_radius=0.0635"
        .parse()
        .expect("override");
    let mission = karman_mission::load(path, &[set]).expect("mission loads");
    let motor = build_motor(&mission).expect("motor builds");
    match build_rocket(&mission, &motor) {
        Err(karman_mission::MissionError::Model { section, .. }) => {
            assert_eq!(section, "rocket.surfaces.tail");
        }
        other => panic!("expected a model error, got {other:?}"),
    }
}

/// RocketPy 1.13.0's rocket time functions at 8 times for three missions, printed by
/// `crates/airframe/tests/reference/rocketpy_time_tables.py` (run on the validation folder):
/// `[t, m, ṁ, m̈, c, ċ, I11, İ11, I33, İ33, z_CM]`.
///
/// Tolerances, relative to each quantity's peak over the rows: the generic motor
/// (Prometheus) and every thrust-derived quantity (ṁ, m̈) follow from the same data by the
/// same arithmetic, 1e-12. For solid motors RocketPy tabulates the grain regression at its
/// LSODA steps (up to ~0.1 s apart) and interpolates linearly, while karman-propulsion
/// tabulates it on its own finer grid: values then agree to 2e-4 of their peak and slopes
/// (ċ, İ) — which are those of different segments — to 0.1 of their peak, the largest
/// departures being near burn-out where the regression rate changes fastest.
const TIME_TABLES: &[(&str, &[[f64; 11]])] = &[
    (
        "calisto",
        &[
            [
                0.0,
                19.196911961392022,
                -0.0,
                -0.8918143460550964,
                0.11597269863647001,
                -3.6507604371079556e-07,
                9.638150889693282,
                -6.6067044254418345e-06,
                0.03794203415863456,
                -4.015515779684602e-09,
                -0.22079814041961146,
            ],
            [
                0.37,
                18.919954684429968,
                -0.9245885232726212,
                -0.24524894516515144,
                0.1066446694200015,
                -0.03158602450961494,
                9.471811839573196,
                -0.5551124157179214,
                0.037836250073918165,
                -0.0003695070738503577,
                -0.2114701112031429,
            ],
            [
                1.0,
                18.30918435402319,
                -0.9976727089318363,
                -0.08240364557549083,
                0.0850777296809563,
                -0.03640481392471032,
                9.105133119631033,
                -0.5988153625700119,
                0.037563271158898626,
                -0.000497981253890025,
                -0.18990317146409774,
            ],
            [
                1.234,
                18.076650789817762,
                -0.9898679065009006,
                0.03335385654246048,
                0.0764824402343101,
                -0.03705835147451299,
                8.965574614801692,
                -0.5940173558137338,
                0.03744192615757204,
                -0.0005394928186365951,
                -0.18130788201745152,
            ],
            [
                2.5,
                16.887476219922412,
                -0.8632762869813333,
                0.1373394092924849,
                0.028832575977661968,
                -0.037028119813307676,
                8.25215252970559,
                -0.5177781582914746,
                0.03662430158027586,
                -0.0007362138305919095,
                -0.13365801776080338,
            ],
            [
                3.3,
                16.305500473832446,
                -0.2599638818750606,
                1.8311921238997992,
                0.00297936981205513,
                -0.011962302017564092,
                7.903132991912513,
                -0.1559131966017973,
                0.03606938074528526,
                -0.0002762381576555784,
                -0.10780481159519655,
            ],
            [
                3.61,
                16.25568501118269,
                -0.09957107173705153,
                0.3433485232312121,
                0.0006803584891730159,
                -0.004687425123265157,
                7.8732606387582535,
                -0.060724761270376994,
                0.036015943990421545,
                -0.00010963869802706717,
                -0.10550580027231445,
            ],
            [
                4.5,
                16.241000001558245,
                0.0,
                0.0,
                7.226336581159936e-11,
                0.0,
                7.864454691061862,
                0.0,
                0.03600000000169693,
                0.0,
                -0.1048254418554048,
            ],
        ],
    ),
    (
        "ndrt_2020",
        &[
            [
                0.0,
                23.32099892838741,
                -0.0,
                -2.528137599783498,
                0.16838825146139488,
                -1.3479217299423155e-06,
                84.73032753986098,
                -5.6515930737006e-05,
                0.1614460742959505,
                -8.092070297027108e-09,
                1.62272807684756,
            ],
            [
                0.37,
                23.05053434720731,
                -0.7756326156135772,
                -0.10112550399134002,
                0.15174658408031017,
                -0.04821700239655302,
                84.04069490189158,
                -1.9758386730743538,
                0.16134196185824382,
                -0.00031410558899149876,
                1.6060864094664755,
            ],
            [
                1.0,
                22.548024078405735,
                -0.8213076349163324,
                -0.08427125332611657,
                0.11976785111097607,
                -0.0534855333715923,
                82.75951424289012,
                -2.095102201569845,
                0.16111401320502203,
                -0.0004165705153305946,
                1.5741076764971411,
            ],
            [
                1.234,
                22.35486554331542,
                -0.8213957956121197,
                0.062231079379286174,
                0.10709241804115777,
                -0.05436355521954333,
                82.26708010228879,
                -2.092840444586332,
                0.16101191235870965,
                -0.0004542092800701223,
                1.561432243427323,
            ],
            [
                2.5,
                21.3647728393747,
                -0.744410116256251,
                0.04424240799621116,
                0.03852443017670615,
                -0.05394210268949576,
                79.74318715652018,
                -1.8973732031330637,
                0.1603232889285135,
                -0.0006415052206936818,
                1.4928642555628713,
            ],
            [
                3.3,
                20.853750376011917,
                -0.15912395480990316,
                2.171224056284652,
                0.000589685201540964,
                -0.010048238805598712,
                78.44062446421898,
                -0.3366920619098289,
                0.15982842499005473,
                -0.00014344883248154026,
                1.4549295105877063,
            ],
            [
                3.61,
                20.84600000054558,
                0.0,
                0.0,
                4.1525862903885943e-11,
                0.0,
                78.42086967406757,
                0.0,
                0.15982000000059413,
                0.0,
                1.4543398254276911,
            ],
            [
                4.5,
                20.84600000054558,
                0.0,
                0.0,
                4.1525862903885943e-11,
                0.0,
                78.42086967406757,
                0.0,
                0.15982000000059413,
                0.0,
                1.4543398254276911,
            ],
        ],
    ),
    (
        "prometheus_2022",
        &[
            [
                0.0,
                20.648,
                -0.0,
                -17.59998902376204,
                0.10151033648628958,
                -0.007150079578893614,
                7.281370542141531,
                -0.10906152813440943,
                0.057653376000000006,
                -0.0006257239349019044,
                0.7333634734598992,
            ],
            [
                0.37,
                20.367516535021768,
                -0.8180347425768913,
                -0.09806185087750569,
                0.0951843880821764,
                -0.018703929875331243,
                7.185751616166112,
                -0.2787481464725756,
                0.057072798563827895,
                -0.0016832216493764822,
                0.7396894218640123,
            ],
            [
                1.0,
                19.834199395752314,
                -0.8678660996584717,
                -0.050650704166203146,
                0.08266257435523836,
                -0.020924636998120798,
                7.0042011255792875,
                -0.29562775465333974,
                0.055989422979040596,
                -0.0017779818017581578,
                0.7522112355909506,
            ],
            [
                1.234,
                19.62973201774535,
                -0.8797183644333633,
                -0.050650704166203146,
                0.07768142650327776,
                -0.021654560166742307,
                6.934535363461574,
                -0.2997757361461368,
                0.055569235681430025,
                -0.0018109684550044023,
                0.7571923834429111,
            ],
            [
                2.5,
                18.51292272793336,
                -0.8553882170227939,
                0.05365818602835172,
                0.048532396362228926,
                -0.02367267554996033,
                6.554051872430941,
                -0.2912272673058634,
                0.05327681166209471,
                -0.001740645764105909,
                0.78634141358396,
            ],
            [
                3.3,
                17.85846680644859,
                -0.7718075589731003,
                0.1188090020972816,
                0.02975671558425618,
                -0.02295382871318418,
                6.331407358068847,
                -0.2627646770283184,
                0.051958656576095726,
                -0.0015700341901261142,
                0.8051170943619327,
            ],
            [
                3.61,
                17.6249152359984,
                -0.734976768322943,
                0.1188090020972816,
                0.02271876789371545,
                -0.022441617907265152,
                6.25182026321164,
                -0.2507414162333719,
                0.05147777113426562,
                -0.0015356658278241448,
                0.8121550420524735,
            ],
            [
                4.5,
                17.007600481956455,
                -0.5220585204976793,
                1.6880592209033696,
                0.0031856745703214436,
                -0.017096022187419766,
                6.041433715913962,
                -0.17778103456191266,
                0.050204753374580115,
                -0.0010824803580059075,
                0.8316881353758674,
            ],
        ],
    ),
];

#[test]
fn validate_rocket_time_tables() {
    let Some(missions) = validation_missions() else {
        println!("validation data folder absent: skipped");
        return;
    };
    let names = [
        "m", "mdot", "mddot", "c", "cdot", "I11", "I11dot", "I33", "I33dot", "z_CM",
    ];
    let exact = [1e-12; 10];
    let solid = [2e-4, 1e-12, 1e-12, 2e-4, 0.1, 2e-4, 0.1, 2e-4, 0.1, 2e-4];
    let mut failures = Vec::new();
    for (flight, rows) in TIME_TABLES {
        let tolerance = if *flight == "prometheus_2022" {
            exact
        } else {
            solid
        };
        let Some(path) = missions
            .iter()
            .find(|p| p.to_string_lossy().contains(flight))
        else {
            continue;
        };
        let mission = karman_mission::load(path, &[]).expect("mission loads");
        let motor = build_motor(&mission).expect("motor builds");
        let rocket = build_rocket(&mission, &motor).expect("rocket builds");
        let mut worst = [0.0f64; 10];
        for row in *rows {
            let t = row[0];
            let i = rocket.inertia(t);
            let di = rocket.inertia_rate(t);
            let ours = [
                rocket.total_mass(t),
                rocket.mass_flow_rate(t),
                rocket.mass_flow_rate_derivative(t),
                rocket.com_to_cdm(t),
                rocket.com_to_cdm_rate(t),
                i[0],
                di[0],
                i[2],
                di[2],
                rocket.center_of_mass(t),
            ];
            for (k, (a, b)) in ours.iter().zip(&row[1..]).enumerate() {
                // Scale: the largest magnitude of the quantity over the rows.
                let scale = rows.iter().fold(0.0f64, |m, r| m.max(r[k + 1].abs()));
                worst[k] = worst[k].max((a - b).abs() / scale.max(1e-300));
            }
        }
        println!("{flight}: worst error / peak");
        for ((n, w), tol) in names.iter().zip(worst).zip(tolerance) {
            println!("  {n:<8} {w:.2e}");
            if w.is_nan() || w > tol {
                failures.push(format!("{flight}: {n} error {w:e} > {tol:e} of its peak"));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
