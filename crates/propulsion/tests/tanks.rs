//! Tanks, liquid and hybrid motors (physics.md §15): a hybrid whose oxidiser tank is empty is
//! its solid grain; a liquid motor's propellant is the sum of its tanks; and the tank, liquid
//! and hybrid formulas scale with their units (`karman_math::dimensions`).

use karman_math::dimensions::{Dimension, ScaledComparison, test_seeds};
use karman_math::{PhysicalConstants, Units};
use karman_propulsion::{
    BatesGrains, CoordinateSystem, Fluid, Motor, MotorStructure, PositionedTank, Tank, TankCurve,
    TankGeometry, TankKind, TankShape, TankSpec, ThrustCurve, ThrustData, ThrustOptions,
    ThrustSource,
};

/// A hybrid-like thrust curve (s, N).
const CURVE: [[f64; 2]; 6] = [
    [0.0, 0.0],
    [0.1, 1200.0],
    [0.3, 2000.0],
    [3.0, 1900.0],
    [4.6, 1500.0],
    [5.0, 0.0],
];

fn thrust(u: &Units) -> ThrustCurve {
    let points: Vec<[f64; 2]> = CURVE
        .iter()
        .map(|[t, f]| [u.scale(*t, Dimension::TIME), u.scale(*f, Dimension::FORCE)])
        .collect();
    let data = ThrustData::from_points("inline", &points).expect("valid points");
    ThrustCurve::new(
        &ThrustSource::Data(Box::new(data)),
        &ThrustOptions::default(),
    )
    .expect("valid curve")
}

fn structure(u: &Units) -> MotorStructure {
    let i = |v: f64| u.scale(v, Dimension::INERTIA);
    MotorStructure {
        dry_mass: u.scale(10.0, Dimension::MASS),
        dry_inertia: [i(1.6), i(1.6), i(0.03), 0.0, 0.0, 0.0],
        center_of_dry_mass: u.scale(0.78, Dimension::LENGTH),
        nozzle_position: 0.0,
        nozzle_radius: u.scale(0.014, Dimension::LENGTH),
        coordinate_system: CoordinateSystem::NozzleToCombustionChamber,
        reference_pressure: None,
    }
}

fn grain(u: &Units) -> BatesGrains {
    let l = |v: f64| u.scale(v, Dimension::LENGTH);
    BatesGrains {
        number: 1,
        density: u.scale(920.0, Dimension::DENSITY),
        outer_radius: l(0.043),
        initial_inner_radius: l(0.0225),
        initial_height: l(0.31),
        separation: 0.0,
        center_of_mass_position: l(0.385),
        throat_radius: l(0.007),
        only_radial_burn: true,
    }
}

/// A mass-flow tank at `position` holding `liquid` kg drained at `rate` kg/s and pressurised
/// with `gas_in` kg/s, in the unit system `u`.
fn tank(
    u: &Units,
    shape: TankShape,
    position: f64,
    liquid: f64,
    rate: f64,
    gas_in: f64,
) -> PositionedTank {
    let c = PhysicalConstants::SI.in_units(u);
    let flow = |v: f64| TankCurve::Constant(u.scale(v, Dimension::MASS_FLOW));
    let spec = TankSpec {
        name: "tank".into(),
        kind: TankKind::MassFlowRate {
            initial_liquid_mass: u.scale(liquid, Dimension::MASS),
            initial_gas_mass: 0.0,
            liquid_in: flow(0.0),
            liquid_out: flow(rate),
            gas_in: flow(gas_in),
            gas_out: flow(0.0),
        },
        geometry: TankGeometry::new(shape, &c).expect("valid geometry"),
        flux_time: (0.0, u.scale(5.0, Dimension::TIME)),
        liquid: Fluid::constant("liquid", u.scale(960.0, Dimension::DENSITY)),
        gas: Fluid::constant("gas", u.scale(300.0, Dimension::DENSITY)),
        discretize: 100,
        temperature: TankCurve::Constant(u.scale(273.15, Dimension::TEMPERATURE)),
        pressure: TankCurve::Constant(u.scale(101_325.0, Dimension::PRESSURE)),
    };
    PositionedTank {
        tank: Tank::new(spec, &c).expect("valid tank"),
        position: u.scale(position, Dimension::LENGTH),
    }
}

fn cylinder(u: &Units, caps: bool) -> TankShape {
    TankShape::Cylindrical {
        radius: u.scale(0.07, Dimension::LENGTH),
        height: u.scale(0.32, Dimension::LENGTH),
        spherical_caps: caps,
    }
}

#[test]
fn a_hybrid_with_an_empty_tank_is_its_grain() {
    let si = Units::SI;
    let c = PhysicalConstants::SI;
    let solid = Motor::solid(thrust(&si), structure(&si), grain(&si)).expect("solid");
    let empty = tank(&si, cylinder(&si, false), 0.93, 0.0, 0.0, 0.0);
    let hybrid =
        Motor::hybrid(thrust(&si), structure(&si), grain(&si), vec![empty], &c).expect("hybrid");
    assert!((hybrid.propellant_initial_mass() - solid.propellant_initial_mass()).abs() < 1e-15);
    assert!((hybrid.exhaust_velocity() - solid.exhaust_velocity()).abs() < 1e-12);
    // The solid motor's grid is part of the hybrid's: at its nodes the values agree.
    for &t in solid.propellant_mass().xs() {
        let (m_s, m_h) = (solid.total_mass(t), hybrid.total_mass(t));
        assert!((m_s - m_h).abs() < 1e-12, "{t}: {m_s} vs {m_h}");
        assert!(
            (solid.center_of_mass(t) - hybrid.center_of_mass(t)).abs() < 1e-12,
            "{t}"
        );
        let ((a11, a33), (b11, b33)) = (solid.inertia(t), hybrid.inertia(t));
        assert!(
            (a11 - b11).abs() < 1e-12 && (a33 - b33).abs() < 1e-12,
            "{t}"
        );
    }
    assert_eq!(hybrid.tanks().len(), 1);
    assert_eq!(hybrid.throat_radius(), Some(0.007));
}

#[test]
fn a_hybrid_grain_burns_what_the_tank_does_not_deliver() {
    let si = Units::SI;
    let c = PhysicalConstants::SI;
    let ox = tank(&si, cylinder(&si, false), 0.93, 4.2, 0.84, 0.0);
    let hybrid =
        Motor::hybrid(thrust(&si), structure(&si), grain(&si), vec![ox], &c).expect("hybrid");
    let m_g0 = std::f64::consts::PI * (0.043f64.powi(2) - 0.0225f64.powi(2)) * 0.31 * 920.0;
    assert!((hybrid.propellant_initial_mass() - (m_g0 + 4.2)).abs() < 1e-12);
    // Grain mass at t: m_g0 − ∫T/v̄_e + 0.84 t; the tank holds 4.2 − 0.84 t.
    let ve = hybrid.exhaust_velocity();
    for t in [0.5, 1.0, 2.0, 3.0] {
        let grain = m_g0 - hybrid.thrust_table().integral(0.0, t) / ve + 0.84 * t;
        let expected = grain + 4.2 - 0.84 * t;
        assert!(
            (hybrid.propellant_mass().eval(t) - expected).abs() < 1e-9,
            "{t}"
        );
    }
}

#[test]
fn a_liquid_motor_sums_its_tanks() {
    let si = Units::SI;
    let fuel = tank(&si, cylinder(&si, true), 0.85, 3.5, 0.45, 0.03);
    let ox = tank(&si, cylinder(&si, true), 1.96, 3.9, 0.56, 0.03);
    let motor =
        Motor::liquid(thrust(&si), structure(&si), vec![fuel.clone(), ox.clone()]).expect("liquid");
    assert!((motor.propellant_initial_mass() - 7.4).abs() < 1e-12);
    // RocketPy's node-wise sums: exact at the common grid's nodes (between them the centre
    // of mass is the spline of the node ratios, not the ratio of the splines).
    let nodes: Vec<f64> = fuel.tank.mass().xs().iter().step_by(9).copied().collect();
    for t in nodes {
        let (mf, mo) = (fuel.tank.mass().eval(t), ox.tank.mass().eval(t));
        let (zf, zo) = (
            0.85 + fuel.tank.center_of_mass().eval(t),
            1.96 + ox.tank.center_of_mass().eval(t),
        );
        let z = (mf * zf + mo * zo) / (mf + mo);
        assert!(
            (motor.propellant_mass().eval(t) - (mf + mo)).abs() < 1e-12,
            "{t}"
        );
        assert!(
            (motor.propellant_center_of_mass().eval(t) - z).abs() < 1e-12,
            "{t}"
        );
        let i = fuel.tank.inertia().eval(t)
            + mf * (zf - z).powi(2)
            + ox.tank.inertia().eval(t)
            + mo * (zo - z).powi(2);
        assert!(
            (motor.propellant_inertia().0.eval(t) - i).abs() < 1e-12,
            "{t}"
        );
        assert!(motor.propellant_inertia().1.eval(t).abs() < 1e-300);
    }
    // Reports: the tanks' exhaust velocity −T/ṁ_tanks; the equations' v̄_e = I/m_p0.
    let flow = -(0.45 - 0.03) - (0.56 - 0.03);
    let t = 1.0;
    assert!((motor.reported_exhaust_velocity(t) - (-motor.thrust(t) / flow)).abs() < 1e-9);
    assert!((motor.exhaust_velocity() - motor.total_impulse() / 7.4).abs() < 1e-9);
    assert!(motor.throat_radius().is_none());
}

#[test]
fn tanks_and_fluid_motors_scale_with_their_units() {
    for seed in test_seeds(3) {
        let mut check = ScaledComparison::new(seed, 1e-9);
        let u = *check.units();
        let c = PhysicalConstants::SI.in_units(&u);
        let motors = |u: &Units, c: &PhysicalConstants| {
            let sphere = TankShape::Spherical {
                radius: u.scale(0.12, Dimension::LENGTH),
            };
            let liquid = Motor::liquid(
                thrust(u),
                structure(u),
                vec![
                    tank(u, cylinder(u, true), 0.85, 3.5, 0.45, 0.03),
                    tank(u, sphere, 1.5, 4.0, 0.7, 0.1),
                ],
            )
            .expect("liquid");
            let hybrid = Motor::hybrid(
                thrust(u),
                structure(u),
                grain(u),
                vec![tank(u, cylinder(u, false), 0.93, 4.2, 0.84, 0.0)],
                c,
            )
            .expect("hybrid");
            (liquid, hybrid)
        };
        let (si, sc) = (motors(&Units::SI, &PhysicalConstants::SI), motors(&u, &c));
        for (name, a, b) in [("liquid", &si.0, &sc.0), ("hybrid", &si.1, &sc.1)] {
            let m0 = a.propellant_initial_mass();
            check.compare(
                &format!("{name}: m_p0"),
                m0,
                b.propellant_initial_mass(),
                Dimension::MASS,
            );
            check.compare(
                &format!("{name}: v̄_e"),
                a.exhaust_velocity(),
                b.exhaust_velocity(),
                Dimension::VELOCITY,
            );
            let (i0, _) = a.inertia(0.0);
            for time in [0.0, 0.4, 1.3, 2.5, 4.1, 4.9, 6.0] {
                let ts = u.scale(time, Dimension::TIME);
                let q = |w: &str| format!("{name}: {w}({time} s)");
                check.compare_near(
                    &q("m"),
                    a.total_mass(time),
                    b.total_mass(ts),
                    Dimension::MASS,
                    m0,
                );
                check.compare(
                    &q("z_cm"),
                    a.center_of_mass(time),
                    b.center_of_mass(ts),
                    Dimension::LENGTH,
                );
                let ((a11, a33), (b11, b33)) = (a.inertia(time), b.inertia(ts));
                check.compare_near(&q("I11"), a11, b11, Dimension::INERTIA, i0);
                check.compare_near(&q("I33"), a33, b33, Dimension::INERTIA, i0);
            }
            for (k, (ta, tb)) in a.tanks().iter().zip(b.tanks()).enumerate() {
                let (ta, tb) = (&ta.tank, &tb.tank);
                check.compare(
                    &format!("{name}: tank {k} volume"),
                    ta.spec().geometry.total_volume(),
                    tb.spec().geometry.total_volume(),
                    Dimension::VOLUME,
                );
                for time in [0.0, 1.7, 3.3] {
                    let ts = u.scale(time, Dimension::TIME);
                    let q = |w: &str| format!("{name}: tank {k} {w}({time} s)");
                    check.compare(
                        &q("liquid height"),
                        ta.liquid_height().eval(time),
                        tb.liquid_height().eval(ts),
                        Dimension::LENGTH,
                    );
                    check.compare(
                        &q("centre of mass"),
                        ta.center_of_mass().eval(time),
                        tb.center_of_mass().eval(ts),
                        Dimension::LENGTH,
                    );
                    check.compare(
                        &q("inertia"),
                        ta.inertia().eval(time),
                        tb.inertia().eval(ts),
                        Dimension::INERTIA,
                    );
                    check.compare(
                        &q("gas mass"),
                        ta.gas_mass().eval(time),
                        tb.gas_mass().eval(ts),
                        Dimension::MASS,
                    );
                }
            }
        }
        let worst = check.finish().unwrap_or_else(|e| panic!("{e}"));
        println!(
            "tanks: seed {seed}: largest relative deviation {worst:e} ({})",
            check.worst().1
        );
    }
}
