//! Dimensional analysis of the motors (`karman_math::dimensions`): a thrust curve, a solid
//! (BATES) and a generic motor built from inputs in a random unit system — times, forces,
//! lengths, densities, masses, inertias, pressures scaled — and the constants of that system
//! give thrust, impulse, propellant mass, centres of mass and inertias equal to the SI ones
//! times the factors of their dimensions.

use karman_math::dimensions::{Dimension, ScaledComparison, test_seeds};
use karman_math::{Interpolation, PhysicalConstants, Units};
use karman_propulsion::{
    BatesGrains, BurnTime, CoordinateSystem, CylindricalChamber, Motor, MotorStructure,
    ThrustCurve, ThrustData, ThrustOptions, ThrustSource,
};

/// Agreement required between unit systems: rounding only. Every table is sampled at the
/// same (scaled) instants in both systems, because the only time step of the motor models —
/// the solid motor's grid spacing — comes from the scaled constants.
const TOL: f64 = 1e-9;

/// A Cesaroni M1670-like curve (s, N), with a negative tail sample as measured curves have.
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

fn thrust(u: &Units, options: &ThrustOptions) -> ThrustCurve {
    let points: Vec<[f64; 2]> = CURVE
        .iter()
        .map(|[t, f]| [u.scale(*t, Dimension::TIME), u.scale(*f, Dimension::FORCE)])
        .collect();
    let data = ThrustData::from_points("inline", &points).expect("valid points");
    ThrustCurve::new(&ThrustSource::Data(Box::new(data)), options).expect("valid curve")
}

fn structure(u: &Units) -> MotorStructure {
    let i = |v: f64| u.scale(v, Dimension::INERTIA);
    MotorStructure {
        dry_mass: u.scale(1.815, Dimension::MASS),
        dry_inertia: [i(0.125), i(0.125), i(0.002), i(0.0), i(0.0), i(0.0)],
        center_of_dry_mass: u.scale(0.317, Dimension::LENGTH),
        nozzle_position: u.scale(0.0, Dimension::LENGTH),
        nozzle_radius: u.scale(0.033, Dimension::LENGTH),
        coordinate_system: CoordinateSystem::NozzleToCombustionChamber,
        reference_pressure: Some(u.scale(101_325.0, Dimension::PRESSURE)),
    }
}

fn grains(u: &Units, only_radial_burn: bool) -> BatesGrains {
    let l = |v: f64| u.scale(v, Dimension::LENGTH);
    BatesGrains {
        number: 5,
        density: u.scale(1815.0, Dimension::DENSITY),
        outer_radius: l(0.033),
        initial_inner_radius: l(0.015),
        initial_height: l(0.12),
        separation: l(0.005),
        center_of_mass_position: l(0.397),
        throat_radius: l(0.011),
        only_radial_burn,
    }
}

fn chamber(u: &Units) -> CylindricalChamber {
    CylindricalChamber {
        radius: u.scale(0.033, Dimension::LENGTH),
        height: u.scale(0.6, Dimension::LENGTH),
        position: u.scale(0.4, Dimension::LENGTH),
        propellant_initial_mass: u.scale(2.956, Dimension::MASS),
    }
}

/// The thrust options of the cases: as given, clipped to a burn interval, reshaped.
fn options(u: &Units) -> [(&'static str, ThrustOptions); 3] {
    let t = |v: f64| u.scale(v, Dimension::TIME);
    [
        ("as given", ThrustOptions::default()),
        (
            "clipped",
            ThrustOptions {
                burn_time: Some(BurnTime::Interval(t(0.02), t(3.5))),
                ..ThrustOptions::default()
            },
        ),
        (
            "reshaped spline",
            ThrustOptions {
                reshape: Some((BurnTime::End(t(5.2)), u.scale(9000.0, Dimension::IMPULSE))),
                interpolation: Interpolation::Spline,
                ..ThrustOptions::default()
            },
        ),
    ]
}

fn compare_motors(check: &mut ScaledComparison, name: &str, si: &Motor, sc: &Motor) {
    let u = *check.units();
    let n = |q: &str| format!("{name}: {q}");
    let (t, m, l) = (Dimension::TIME, Dimension::MASS, Dimension::LENGTH);
    check.compare(&n("burn start"), si.burn_start(), sc.burn_start(), t);
    check.compare(&n("burn out"), si.burn_out(), sc.burn_out(), t);
    check.compare(
        &n("total impulse"),
        si.total_impulse(),
        sc.total_impulse(),
        Dimension::IMPULSE,
    );
    check.compare(
        &n("average thrust"),
        si.average_thrust(),
        sc.average_thrust(),
        Dimension::FORCE,
    );
    check.compare(
        &n("max thrust"),
        si.max_thrust(),
        sc.max_thrust(),
        Dimension::FORCE,
    );
    check.compare(
        &n("exhaust velocity"),
        si.exhaust_velocity(),
        sc.exhaust_velocity(),
        Dimension::VELOCITY,
    );
    check.compare(
        &n("m_p0"),
        si.propellant_initial_mass(),
        sc.propellant_initial_mass(),
        m,
    );
    check.compare(&n("dry mass"), si.dry_mass(), sc.dry_mass(), m);
    check.compare(
        &n("pressure thrust"),
        si.pressure_thrust(60_000.0),
        sc.pressure_thrust(u.scale(60_000.0, Dimension::PRESSURE)),
        Dimension::FORCE,
    );
    let m0 = si.propellant_initial_mass();
    let mdot0 = si.max_thrust() / si.exhaust_velocity();
    let (i11_0, _) = si.inertia(0.0);
    for time in [
        -1.0, 0.0, 0.03, 0.0931, 0.5, 1.0, 2.0, 2.777, 3.45, 3.9, 4.5, 6.0,
    ] {
        let ts = u.scale(time, t);
        let q = |what: &str| n(&format!("{what}({time} s)"));
        check.compare_near(
            &q("T"),
            si.thrust(time),
            sc.thrust(ts),
            Dimension::FORCE,
            si.max_thrust(),
        );
        check.compare_near(
            &q("ṁ"),
            si.mass_flow_rate(time),
            sc.mass_flow_rate(ts),
            Dimension::MASS_FLOW,
            mdot0,
        );
        check.compare_near(
            &q("m_p"),
            si.propellant_mass().eval(time),
            sc.propellant_mass().eval(ts),
            m,
            m0,
        );
        check.compare(
            &q("z_p"),
            si.propellant_center_of_mass().eval(time),
            sc.propellant_center_of_mass().eval(ts),
            l,
        );
        let ((a11, a33), (b11, b33)) = (si.propellant_inertia(), sc.propellant_inertia());
        check.compare_near(
            &q("I11_p"),
            a11.eval(time),
            b11.eval(ts),
            Dimension::INERTIA,
            i11_0,
        );
        check.compare_near(
            &q("I33_p"),
            a33.eval(time),
            b33.eval(ts),
            Dimension::INERTIA,
            i11_0,
        );
        check.compare(&q("m"), si.total_mass(time), sc.total_mass(ts), m);
        check.compare(
            &q("z_cm"),
            si.center_of_mass(time),
            sc.center_of_mass(ts),
            l,
        );
        let ((c11, c33), (d11, d33)) = (si.inertia(time), sc.inertia(ts));
        check.compare(&q("I11"), c11, d11, Dimension::INERTIA);
        check.compare(&q("I33"), c33, d33, Dimension::INERTIA);
    }
}

#[test]
fn motors_scale_with_their_units() {
    for seed in test_seeds(3) {
        let mut check = ScaledComparison::new(seed, TOL);
        let u = *check.units();
        let c = PhysicalConstants::SI.in_units(&u);
        for ((name, o_si), (_, o_sc)) in options(&Units::SI).into_iter().zip(options(&u)) {
            for radial in [false, true] {
                let solid = |u: &Units, o: &ThrustOptions, c: &PhysicalConstants| {
                    Motor::solid_with(thrust(u, o), structure(u), grains(u, radial), c)
                        .expect("valid motor")
                };
                let si = solid(&Units::SI, &o_si, &PhysicalConstants::SI);
                let sc = solid(&u, &o_sc, &c);
                let label = format!("solid (radial {radial}), {name}");
                compare_motors(&mut check, &label, &si, &sc);
                // Grain regression: bore and height are lengths, Kn a pure number.
                let (g_si, g_sc) = (grains(&Units::SI, radial), grains(&u, radial));
                for time in [0.5, 2.0, 3.0] {
                    let ts = u.scale(time, Dimension::TIME);
                    let a = g_si.state_for_mass(si.propellant_mass().eval(time));
                    let b = g_sc.state_for_mass(sc.propellant_mass().eval(ts));
                    let q = |w: &str| format!("{label}: {w}({time} s)");
                    check.compare(&q("r"), a.inner_radius, b.inner_radius, Dimension::LENGTH);
                    check.compare(&q("h"), a.height, b.height, Dimension::LENGTH);
                    check.compare(&q("Kn"), g_si.kn(a), g_sc.kn(b), Dimension::NONE);
                }
            }
            let generic = |u: &Units, o: &ThrustOptions| {
                Motor::generic(thrust(u, o), structure(u), chamber(u)).expect("valid motor")
            };
            let label = format!("generic, {name}");
            compare_motors(
                &mut check,
                &label,
                &generic(&Units::SI, &o_si),
                &generic(&u, &o_sc),
            );
        }
        // A constant thrust over a burn time (sampled at 50 points, as RocketPy does).
        let constant = |u: &Units| {
            let o = ThrustOptions {
                burn_time: Some(BurnTime::End(u.scale(2.5, Dimension::TIME))),
                ..ThrustOptions::default()
            };
            let source = ThrustSource::Constant(u.scale(1200.0, Dimension::FORCE));
            let curve = ThrustCurve::new(&source, &o).expect("valid curve");
            Motor::generic(curve, structure(u), chamber(u)).expect("valid motor")
        };
        compare_motors(
            &mut check,
            "constant generic",
            &constant(&Units::SI),
            &constant(&u),
        );
        let worst = check.finish().unwrap_or_else(|e| panic!("{e}"));
        println!(
            "propulsion: seed {seed}: largest relative deviation {worst:e} ({})",
            check.worst().1
        );
    }
}

/// The check catches what it exists for: a solid motor built with SI constants from scaled
/// inputs has a grid spacing of 5 ms *in the scaled unit*, a different physical step, so its
/// linearly interpolated inertia between grid nodes differs beyond rounding (this was the
/// hidden `GRID_STEP = 0.005` literal of solid.rs); and a wrong formula (the grain-stack
/// inertia with the grain separation added to an area) is caught too.
#[test]
fn a_dimensionally_wrong_model_is_detected() {
    for seed in test_seeds(3) {
        let mut check = ScaledComparison::new(seed, TOL);
        let u = *check.units();
        let o = ThrustOptions::default();
        let si = Motor::solid(
            thrust(&Units::SI, &o),
            structure(&Units::SI),
            grains(&Units::SI, false),
        )
        .expect("valid motor");
        let sc = Motor::solid(thrust(&u, &o), structure(&u), grains(&u, false)).expect("valid");
        // Between grid nodes (2.0123 s is not on a 5 ms grid of either system unless λ_T is
        // close to a ratio of small integers).
        let time = 2.0123;
        let ts = u.scale(time, Dimension::TIME);
        let (a, b) = (
            si.propellant_inertia().0.eval(time),
            sc.propellant_inertia().0.eval(ts),
        );
        let dev = check.compare("I11_p with an SI grid step", a, b, Dimension::INERTIA);
        if (u.time - 1.0).abs() > 0.05 {
            assert!(dev > TOL, "seed {seed}: deviation {dev:e} not detected");
            assert!(check.finish().is_err());
        }

        let mut check = ScaledComparison::new(seed, TOL);
        let wrong_i11 = |g: &BatesGrains, m: f64| {
            let r2 = g.outer_radius.powi(2) + g.initial_inner_radius.powi(2);
            m * (r2 / 4.0 + g.initial_height.powi(2) / 12.0 + g.separation)
        };
        let (g_si, g_sc) = (grains(&Units::SI, false), grains(&u, false));
        let m = 0.59;
        let ms = u.scale(m, Dimension::MASS);
        check.compare(
            "wrong I11",
            wrong_i11(&g_si, m),
            wrong_i11(&g_sc, ms),
            Dimension::INERTIA,
        );
        if (u.length - 1.0).abs() > 0.05 {
            let e = check.finish().expect_err("a length added to an area");
            assert!(
                e.contains("wrong I11") && e.contains(&seed.to_string()),
                "{e}"
            );
        }
    }
}
