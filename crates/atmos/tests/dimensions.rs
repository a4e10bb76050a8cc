//! Dimensional analysis of the environment (`karman_math::dimensions`): the ISA, a custom
//! profile and Somigliana gravity built with the constants and inputs of a random unit system
//! give P, T, ρ, a, μ, wind and g at scaled heights equal to the SI values times the factors
//! of their dimensions, and the same (dimensionless) latitude and longitude downrange.

use karman_atmos::{Atmosphere, Curve, Datum, Environment, EnvironmentConfig, Gravity, Profiles};
use karman_math::dimensions::{Dimension, ScaledComparison, test_seeds};
use karman_math::{PhysicalConstants, Units};

/// Agreement required between unit systems: rounding only (the tables are sampled at the
/// same points in both systems, so interpolation errors are identical).
const TOL: f64 = 1e-9;

/// A custom atmosphere (heights m, pressure Pa, temperature K, winds m/s) in SI.
fn custom_profiles(u: &Units) -> Profiles {
    let pts = |pairs: &[[f64; 2]], d: Dimension| -> Curve {
        Curve::Points(
            pairs
                .iter()
                .map(|[h, v]| [u.scale(*h, Dimension::LENGTH), u.scale(*v, d)])
                .collect(),
        )
    };
    Profiles {
        source_name: "custom".into(),
        pressure: Some(pts(
            &[
                [0.0, 101_000.0],
                [1500.0, 84_500.0],
                [4000.0, 61_600.0],
                [9000.0, 30_800.0],
            ],
            Dimension::PRESSURE,
        )),
        temperature: Some(pts(
            &[
                [0.0, 291.0],
                [1500.0, 281.0],
                [4000.0, 264.0],
                [9000.0, 229.0],
            ],
            Dimension::TEMPERATURE,
        )),
        wind_u: pts(
            &[[0.0, 2.0], [2000.0, 9.5], [8000.0, 21.0]],
            Dimension::VELOCITY,
        ),
        wind_v: Curve::Constant(u.scale(-3.5, Dimension::VELOCITY)),
        barometric_points: None,
    }
}

fn environment(u: &Units, atmosphere: Atmosphere, gravity: Gravity) -> Environment {
    let config = EnvironmentConfig {
        earth_model: None,
        latitude_deg: 32.990254,
        longitude_deg: -106.974998,
        elevation: u.scale(1400.0, Dimension::LENGTH),
        datum: Datum::Wgs84,
        gravity,
        atmosphere,
    };
    Environment::new(&config, &PhysicalConstants::SI.in_units(u)).expect("valid environment")
}

fn compare(check: &mut ScaledComparison, name: &str, si: &Environment, sc: &Environment) {
    let u = *check.units();
    check.compare(
        &format!("{name} elevation"),
        si.elevation(),
        sc.elevation(),
        Dimension::LENGTH,
    );
    check.compare(
        &format!("{name} datum radius"),
        si.datum_radius(),
        sc.datum_radius(),
        Dimension::LENGTH,
    );
    for (a, b) in si.earth_rotation_enu().iter().zip(sc.earth_rotation_enu()) {
        check.compare_near(
            &format!("{name} Ω"),
            *a,
            b,
            Dimension::FREQUENCY,
            PhysicalConstants::SI.earth_rotation_rate,
        );
    }
    // Heights below, inside and above the tables (the ISA top is 80 km).
    for z in [
        -300.0, 0.0, 1400.0, 2750.5, 6100.0, 11_500.0, 30_000.0, 95_000.0,
    ] {
        let zs = u.scale(z, Dimension::LENGTH);
        let (a, b) = (si.sample(z), sc.sample(zs));
        let n = |q: &str| format!("{name} {q}({z} m)");
        check.compare(&n("P"), a.pressure, b.pressure, Dimension::PRESSURE);
        check.compare(
            &n("T"),
            a.temperature,
            b.temperature,
            Dimension::TEMPERATURE,
        );
        check.compare(&n("ρ"), a.density, b.density, Dimension::DENSITY);
        check.compare(
            &n("a"),
            a.speed_of_sound,
            b.speed_of_sound,
            Dimension::VELOCITY,
        );
        check.compare(
            &n("μ"),
            a.dynamic_viscosity,
            b.dynamic_viscosity,
            Dimension::VISCOSITY,
        );
        check.compare(&n("g"), a.gravity, b.gravity, Dimension::ACCELERATION);
        for (k, (wa, wb)) in a.wind.iter().zip(b.wind).enumerate() {
            check.compare_near(&n(&format!("wind{k}")), *wa, wb, Dimension::VELOCITY, 1.0);
        }
        // Dimensionless groups the dynamics forms: Mach of a 250 m/s flight and Reynolds
        // number of a 0.127 m body.
        let mach = |s: &karman_atmos::AtmosphereSample, v: f64| v / s.speed_of_sound;
        check.compare(
            &n("Mach"),
            mach(&a, 250.0),
            mach(&b, u.scale(250.0, Dimension::VELOCITY)),
            Dimension::NONE,
        );
        let re = |s: &karman_atmos::AtmosphereSample, v: f64, l: f64| {
            s.density * v * l / s.dynamic_viscosity
        };
        check.compare(
            &n("Re"),
            re(&a, 250.0, 0.127),
            re(
                &b,
                u.scale(250.0, Dimension::VELOCITY),
                u.scale(0.127, Dimension::LENGTH),
            ),
            Dimension::NONE,
        );
        // Barometric height of the pressure at z; at sea level it vanishes and comes out as
        // rounding noise of the table's heights (up to 80 km).
        check.compare_near(
            &n("h_baro(P)"),
            si.barometric_height(a.pressure),
            sc.barometric_height(b.pressure),
            Dimension::LENGTH,
            1000.0,
        );
    }
    // Latitude and longitude are angles: the same in every unit system.
    for (e, nn) in [(1200.0, -800.0), (-25_000.0, 40_000.0)] {
        let (la, lo) = si.geodetic(e, nn);
        let (lb, lob) = sc.geodetic(
            u.scale(e, Dimension::LENGTH),
            u.scale(nn, Dimension::LENGTH),
        );
        check.compare_near(&format!("{name} latitude"), la, lb, Dimension::NONE, 90.0);
        check.compare_near(
            &format!("{name} longitude"),
            lo,
            lob,
            Dimension::NONE,
            180.0,
        );
    }
}

/// Builds an environment in the given units.
type Builder = Box<dyn Fn(&Units) -> Environment>;

#[test]
fn environment_scales_with_its_units() {
    for seed in test_seeds(4) {
        let mut check = ScaledComparison::new(seed, TOL);
        let u = *check.units();
        let cases: [(&str, Builder); 4] = [
            (
                "ISA + Somigliana",
                Box::new(|u| environment(u, Atmosphere::Standard, Gravity::Somigliana)),
            ),
            (
                "custom + Somigliana",
                Box::new(|u| {
                    environment(
                        u,
                        Atmosphere::Profiles(custom_profiles(u)),
                        Gravity::Somigliana,
                    )
                }),
            ),
            (
                "custom winds over ISA",
                Box::new(|u| {
                    let winds = custom_profiles(u);
                    let p = Profiles::wind_only("winds", winds.wind_u, winds.wind_v);
                    environment(u, Atmosphere::Profiles(p), Gravity::Somigliana)
                }),
            ),
            (
                "ISA + constant g",
                Box::new(|u| {
                    let g = u.scale(9.81, Dimension::ACCELERATION);
                    environment(u, Atmosphere::Standard, Gravity::Constant(g))
                }),
            ),
        ];
        for (name, build) in &cases {
            compare(&mut check, name, &build(&Units::SI), &build(&u));
        }
        let worst = check.finish().unwrap_or_else(|e| panic!("{e}"));
        println!(
            "atmos: seed {seed}: largest relative deviation {worst:e} ({})",
            check.worst().1
        );
    }
}

/// The check detects a dimensional error in an environment-derived quantity: the dynamic
/// pressure written `ρ v` instead of `½ ρ v²` fails, the correct one passes.
#[test]
fn a_dimensionally_wrong_formula_is_detected() {
    for seed in test_seeds(4) {
        let mut check = ScaledComparison::new(seed, TOL);
        let u = *check.units();
        let (si, sc) = (
            environment(&Units::SI, Atmosphere::Standard, Gravity::Somigliana),
            environment(&u, Atmosphere::Standard, Gravity::Somigliana),
        );
        let (z, v) = (3000.0, 180.0);
        let (zs, vs) = (
            u.scale(z, Dimension::LENGTH),
            u.scale(v, Dimension::VELOCITY),
        );
        let q = |e: &Environment, z: f64, v: f64| 0.5 * e.density(z) * v * v;
        check.compare("q", q(&si, z, v), q(&sc, zs, vs), Dimension::PRESSURE);
        assert!(check.finish().is_ok(), "{:?}", check.finish());
        let wrong = |e: &Environment, z: f64, v: f64| 0.5 * e.density(z) * v;
        check.compare(
            "q written ρv/2",
            wrong(&si, z, v),
            wrong(&sc, zs, vs),
            Dimension::PRESSURE,
        );
        // ρv/2 scales as M L⁻² T⁻¹, a pressure as M L⁻¹ T⁻²: they agree only if λ_L = λ_T.
        if (u.length / u.time - 1.0).abs() > 1e-6 {
            let e = check.finish().expect_err("a mass flux is not a pressure");
            assert!(e.contains("ρv/2") && e.contains(&seed.to_string()), "{e}");
        }
    }
}
