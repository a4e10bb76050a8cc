//! Dimensional analysis of the airframe (`karman_math::dimensions`): a Calisto-like rocket
//! built from inputs in a random unit system (lengths, masses, inertias, times, thrust,
//! pressures, parachute rates scaled; angles, Mach numbers and coefficients unchanged) with
//! the constants of that system gives the same normal-force slopes, static and stability
//! margins, and CP positions, masses and inertias scaled by their dimensions.

use karman_airframe::{
    Airfoil, AngleUnit, CoordinateSystem, EllipticalFinsSpec, FreeFormFinsSpec, MotorProperties,
    NoseConeSpec, NoseKind, Parachute, ParachuteSpec, RailButtons, Rocket, RocketInputs,
    SurfaceInput, SurfaceSpec, Sweep, TailSpec, TrapezoidalFinsSpec, TriggerKind,
};
use karman_math::dimensions::{Dimension, ScaledComparison, test_seeds};
use karman_math::{Extrapolation, Interpolation, PhysicalConstants, Table1, Units, linspace};

/// Agreement required between unit systems: rounding only.
const TOL: f64 = 1e-9;

const L: Dimension = Dimension::LENGTH;
const T: Dimension = Dimension::TIME;

/// Calisto-like motor data (docs/physics.md §6: M1670, 5 BATES grains) as plain tables. With
/// `common_grid` every propellant table shares the thrust grid (RocketPy's node-wise
/// arithmetic); otherwise the centre of mass is on its own grid and the rocket evaluates its
/// mass properties pointwise (the generic-motor path, with a numerical second derivative).
fn motor(u: &Units, common_grid: bool) -> MotorProperties {
    let burn = 3.9;
    let grid = linspace(0.0, burn, 40);
    let ts = |xs: &[f64]| xs.iter().map(|&t| u.scale(t, T)).collect::<Vec<_>>();
    let thrust: Vec<f64> = grid
        .iter()
        .map(|&t| u.scale(2000.0 * (1.0 - (t / burn).powi(4)), Dimension::FORCE))
        .collect();
    let mp0 = 2.956;
    let ve = 2038.0;
    // m_p(t) = m_p0 − ∫T/v̄_e, closed form of the quartic thrust above.
    let mp = |t: f64| (mp0 - 2000.0 * (t - t.powi(5) / (5.0 * burn.powi(4))) / ve).max(0.0);
    let tab = |xs: &[f64], ys: Vec<f64>, interp, extrap| {
        Table1::new(ts(xs), ys, interp, extrap).expect("valid table")
    };
    let lin = Interpolation::Linear;
    let hold = Extrapolation::Constant;
    let m = |v: f64| u.scale(v, Dimension::MASS);
    let i = |v: f64| u.scale(v, Dimension::INERTIA);
    let l = |v: f64| u.scale(v, L);
    let com_grid = if common_grid {
        grid.clone()
    } else {
        linspace(0.0, burn, 7)
    };
    let com: Vec<f64> = com_grid
        .iter()
        .map(|&t| l(0.397 + 0.01 * t / burn))
        .collect();
    MotorProperties {
        thrust: tab(&grid, thrust, lin, Extrapolation::Zero),
        burn_start: 0.0,
        burn_out: u.scale(burn, T),
        exhaust_velocity: u.scale(ve, Dimension::VELOCITY),
        propellant_mass: tab(&grid, grid.iter().map(|&t| m(mp(t))).collect(), lin, hold),
        mass_flow: None,
        propellant_center_of_mass: tab(&com_grid, com, lin, hold),
        propellant_i11: tab(
            &grid,
            grid.iter().map(|&t| i(0.11 * mp(t) / mp0)).collect(),
            lin,
            hold,
        ),
        propellant_i33: tab(
            &grid,
            grid.iter().map(|&t| i(0.0022 * mp(t) / mp0)).collect(),
            lin,
            hold,
        ),
        propellant_parts: Vec::new(),
        dry_mass: m(1.815),
        center_of_dry_mass: l(0.317),
        dry_inertia: [i(0.125), i(0.125), i(0.002), i(0.0), i(0.0), i(0.0)],
        nozzle_position: l(0.0),
        nozzle_radius: l(0.033),
        coordinate_system_sign: 1.0,
        reference_pressure: Some(u.scale(101_325.0, Dimension::PRESSURE)),
    }
}

fn parachute(u: &Units, name: &str, cd_s: f64, trigger: TriggerKind, radius: bool) -> Parachute {
    Parachute::new(&ParachuteSpec {
        name: name.to_owned(),
        cd_s: u.scale(cd_s, Dimension::AREA),
        trigger,
        sampling_rate: Some(u.scale(105.0, Dimension::FREQUENCY)),
        lag: Some(u.scale(1.5, T)),
        noise: Some([
            0.0,
            u.scale(8.3, Dimension::PRESSURE),
            0.5, // correlation between consecutive samples: a pure number
        ]),
        radius: radius.then(|| u.scale(1.5, L)),
        height: None,
        porosity: Some(0.0432),
        drag_coefficient: None,
    })
    .expect("valid parachute")
}

/// Calisto (validation/calisto/mission.toml) with every kind of surface, in the units `u`.
fn inputs(u: &Units, coordinate_system: CoordinateSystem) -> RocketInputs {
    let l = |v: f64| u.scale(v, L);
    let s = coordinate_system.sign();
    // Drag and lift curves are functions of pure numbers (Mach, angle in radians).
    let drag = |k: f64| {
        Table1::linear(
            vec![0.0, 0.8, 1.1, 2.0],
            vec![0.40 + k, 0.45 + k, 0.62 + k, 0.5 + k],
        )
        .expect("valid drag")
    };
    let airfoil = Airfoil {
        lift_curve: Table1::linear(vec![-0.2, 0.0, 0.2], vec![-1.1, 0.0, 1.1]).expect("valid"),
        unit: AngleUnit::Radians,
    };
    let surface = |name: &str, position: f64, spec| SurfaceInput {
        pod: None,
        name: name.to_owned(),
        position: l(s * position),
        spec,
    };
    RocketInputs {
        radius: l(0.0635),
        mass: u.scale(14.426, Dimension::MASS),
        inertia: [6.321, 6.321, 0.034, 0.0, 0.0, 0.0].map(|v| u.scale(v, Dimension::INERTIA)),
        center_of_mass_without_motor: l(0.0),
        coordinate_system,
        power_off_drag: drag(0.0),
        power_on_drag: drag(-0.05),
        motor_position: l(s * -1.255),
        surfaces: vec![
            surface(
                "nose",
                1.278,
                SurfaceSpec::Nose(NoseConeSpec {
                    length: l(0.55829),
                    // A bluff tip shortens the cone (RocketPy's 1 mm rule, in the constants).
                    kind: if s > 0.0 {
                        NoseKind::VonKarman
                    } else {
                        NoseKind::Elliptical
                    },
                    base_radius: None,
                    bluffness: 0.1,
                }),
            ),
            surface(
                "fins",
                -1.04956,
                SurfaceSpec::TrapezoidalFins(TrapezoidalFinsSpec {
                    n: 4,
                    root_chord: l(0.12),
                    tip_chord: l(0.06),
                    span: l(0.11),
                    sweep: Sweep::Length(l(0.03)),
                    cant_angle_deg: 0.5,
                    angular_position_deg: 0.0,
                    radius: None,
                    airfoil: Some(airfoil.clone()),
                }),
            ),
            surface(
                "canards",
                0.6,
                SurfaceSpec::EllipticalFins(EllipticalFinsSpec {
                    n: 3,
                    root_chord: l(0.08),
                    span: l(0.05),
                    cant_angle_deg: -0.3,
                    angular_position_deg: 0.0,
                    radius: Some(l(0.0635)),
                    airfoil: None,
                }),
            ),
            surface(
                "free-form",
                -0.5,
                SurfaceSpec::FreeFormFins(FreeFormFinsSpec {
                    n: 3,
                    shape_points: [[0.0, 0.0], [0.03, 0.05], [0.09, 0.05], [0.1, 0.0]]
                        .map(|[x, y]| [l(x), l(y)])
                        .to_vec(),
                    cant_angle_deg: 0.2,
                    angular_position_deg: 0.0,
                    radius: None,
                    airfoil: None,
                }),
            ),
            surface(
                "tail",
                -1.194656,
                SurfaceSpec::Tail(TailSpec {
                    top_radius: l(0.0635),
                    bottom_radius: l(0.0435),
                    length: l(0.06),
                    radius: None,
                }),
            ),
        ],
        parachutes: vec![
            parachute(
                u,
                "main",
                10.0,
                TriggerKind::HeightAboveGround(l(800.0)),
                true,
            ),
            parachute(u, "drogue", 1.0, TriggerKind::Apogee, false),
        ],
        rail_buttons: Some(RailButtons::new(l(s * 0.0818), l(s * -0.6182), 45.0).expect("valid")),
        eccentricities: Default::default(),
    }
}

fn rocket(u: &Units, csys: CoordinateSystem, common_grid: bool) -> Rocket {
    Rocket::with_constants(
        inputs(u, csys),
        motor(u, common_grid),
        &PhysicalConstants::SI.in_units(u),
    )
    .expect("valid rocket")
}

/// Rounding noise ε|c(0)|/h² of the central second difference of the CM offset, SI.
fn difference_noise(rocket: &Rocket) -> f64 {
    let h = PhysicalConstants::SI.time_difference_step;
    f64::EPSILON * rocket.com_to_cdm(0.0).abs() / (h * h)
}

/// Compares a c̈ of the central difference: the SI and scaled values may differ by
/// `NOISE_MULTIPLE` times [`difference_noise`] (whatever their size).
fn check_difference(check: &mut ScaledComparison, what: &str, rocket: &Rocket, si: f64, sc: f64) {
    /// Observed differences reach about two noise units.
    const NOISE_MULTIPLE: f64 = 16.0;
    let noise = difference_noise(rocket);
    let tolerance = NOISE_MULTIPLE * noise / si.abs().max(noise);
    check.record(what, si, sc, Dimension::ACCELERATION, noise, tolerance);
}

fn compare(check: &mut ScaledComparison, name: &str, si: &Rocket, sc: &Rocket) {
    let u = *check.units();
    let n = |q: &str| format!("{name}: {q}");
    let (m, i) = (Dimension::MASS, Dimension::INERTIA);
    check.compare(&n("radius"), si.radius(), sc.radius(), L);
    check.compare(
        &n("A_ref"),
        si.reference_area(),
        sc.reference_area(),
        Dimension::AREA,
    );
    check.compare(&n("dry mass"), si.dry_mass(), sc.dry_mass(), m);
    check.compare(
        &n("z_CDM"),
        si.center_of_dry_mass(),
        sc.center_of_dry_mass(),
        L,
    );
    check.compare(&n("d_n"), si.nozzle_to_cdm(), sc.nozzle_to_cdm(), L);
    for (a, b) in si.nozzle_gyration().iter().zip(sc.nozzle_gyration()) {
        check.compare(&n("S_n"), *a, b, Dimension::AREA);
    }
    for (a, b) in si.dry_inertia().iter().zip(sc.dry_inertia()) {
        check.compare_near(&n("dry inertia"), *a, b, i, 6.0);
    }
    check.compare(&n("burn out"), si.burn_out(), sc.burn_out(), T);
    let c0 = si.com_to_cdm(0.0).abs();
    let c_scale = c0 / si.burn_out();
    let i0 = si.inertia(0.0)[0];
    for time in [0.0, 0.37, 1.0, 2.05, 3.3, 3.9, 5.0] {
        let ts = u.scale(time, T);
        let q = |w: &str| n(&format!("{w}({time} s)"));
        check.compare(&q("m"), si.total_mass(time), sc.total_mass(ts), m);
        let mdot = 2000.0 / si.motor().exhaust_velocity;
        check.compare_near(
            &q("ṁ"),
            si.mass_flow_rate(time),
            sc.mass_flow_rate(ts),
            Dimension::MASS_FLOW,
            mdot,
        );
        check.compare_near(
            &q("m̈"),
            si.mass_flow_rate_derivative(time),
            sc.mass_flow_rate_derivative(ts),
            Dimension::MASS_FLOW / T,
            mdot / si.burn_out(),
        );
        check.compare_near(&q("c"), si.com_to_cdm(time), sc.com_to_cdm(ts), L, c0);
        check.compare_near(
            &q("ċ"),
            si.com_to_cdm_rate(time),
            sc.com_to_cdm_rate(ts),
            Dimension::VELOCITY,
            c_scale,
        );
        // c̈ of the pointwise path is RocketPy's central difference with a 1 µs step
        // (`PhysicalConstants::time_difference_step`): the roundings of c (ε|c|) over h² leave
        // a noise of order ε|c|/h² ≈ 3e-5 m/s² here, which differs between unit systems
        // whatever the step. So c̈ can only agree to that noise (a table's c̈ is exact and
        // agrees to rounding); a step that did not follow the unit of time would change the
        // value by the factor λ_T at a kink of the tables (the failure test below).
        let (a, b) = (si.com_to_cdm_accel(time), sc.com_to_cdm_accel(ts));
        check_difference(check, &q("c̈"), si, a, b);
        check.compare(
            &q("z_CM"),
            si.center_of_mass(time),
            sc.center_of_mass(ts),
            L,
        );
        for (a, b) in si.inertia(time).iter().zip(sc.inertia(ts)) {
            check.compare_near(&q("I"), *a, b, i, i0);
        }
        for (a, b) in si.inertia_rate(time).iter().zip(sc.inertia_rate(ts)) {
            check.compare_near(&q("İ"), *a, b, i / T, i0 / si.burn_out());
        }
        check.compare_near(
            &q("T_net"),
            si.net_thrust(time, 70_000.0),
            sc.net_thrust(ts, u.scale(70_000.0, Dimension::PRESSURE)),
            Dimension::FORCE,
            2000.0,
        );
        check.compare(
            &q("static margin"),
            si.static_margin(time),
            sc.static_margin(ts),
            Dimension::NONE,
        );
        check.compare(
            &q("z_propellant"),
            si.propellant_position(time),
            sc.propellant_position(ts),
            L,
        );
        for mach in [0.0, 0.5, 0.95, 1.4, 2.5] {
            check.compare(
                &q(&format!("stability margin(M {mach})")),
                si.stability_margin(mach, time),
                sc.stability_margin(mach, ts),
                Dimension::NONE,
            );
        }
    }
    for mach in [0.0, 0.3, 0.85, 1.05, 1.6, 3.0] {
        let q = |w: &str| n(&format!("{w}(M {mach})"));
        check.compare(&q("CP"), si.cp_position(mach), sc.cp_position(mach), L);
        check.compare(
            &q("ΣCNα"),
            si.total_cn_alpha(mach),
            sc.total_cn_alpha(mach),
            Dimension::NONE,
        );
        for power in [false, true] {
            check.compare(
                &q("C_D"),
                si.drag_coefficient(power, mach),
                sc.drag_coefficient(power, mach),
                Dimension::NONE,
            );
        }
        for (a, b) in si.surfaces().iter().zip(sc.surfaces()) {
            let s = |w: &str| q(&format!("{} {w}", a.name));
            check.compare(
                &s("CNα"),
                a.cn_alpha(mach),
                b.cn_alpha(mach),
                Dimension::NONE,
            );
            check.compare_near(
                &s("roll forcing"),
                a.roll_forcing(mach),
                b.roll_forcing(mach),
                Dimension::NONE,
                1e-3,
            );
            check.compare_near(
                &s("roll damping"),
                a.roll_damping(mach),
                b.roll_damping(mach),
                Dimension::NONE,
                1e-3,
            );
        }
    }
    for (a, b) in si.surfaces().iter().zip(sc.surfaces()) {
        let s = |w: &str| n(&format!("{} {w}", a.name));
        check.compare(
            &s("A_ref"),
            a.reference_area,
            b.reference_area,
            Dimension::AREA,
        );
        check.compare(&s("d"), a.reference_length(), b.reference_length(), L);
        check.compare(&s("CP local"), a.cp_local, b.cp_local, L);
        for (x, y) in a.cp_body.iter().zip(b.cp_body) {
            check.compare_near(&s("p"), *x, y, L, 1.0);
        }
    }
    for (a, b) in si.parachutes().iter().zip(sc.parachutes()) {
        let p = |w: &str| n(&format!("{} {w}", a.name));
        check.compare(&p("C_D S"), a.cd_s, b.cd_s, Dimension::AREA);
        check.compare(&p("R_p"), a.radius, b.radius, L);
        check.compare(&p("H_p"), a.height, b.height, L);
        check.compare(
            &p("C_a"),
            a.added_mass_coefficient(),
            b.added_mass_coefficient(),
            Dimension::NONE,
        );
    }
    if let (Some(a), Some(b)) = (si.rail_buttons(), sc.rail_buttons()) {
        check.compare(
            &n("buttons distance"),
            a.buttons_distance(),
            b.buttons_distance(),
            L,
        );
        check.compare(
            &n("buttons angle"),
            a.angular_position_rad,
            b.angular_position_rad,
            Dimension::NONE,
        );
    }
}

#[test]
fn rocket_scales_with_its_units() {
    for seed in test_seeds(3) {
        let mut check = ScaledComparison::new(seed, TOL);
        let u = *check.units();
        for csys in [CoordinateSystem::TailToNose, CoordinateSystem::NoseToTail] {
            for common_grid in [true, false] {
                let name = format!("{csys:?}, common grid {common_grid}");
                let (si, sc) = (
                    rocket(&Units::SI, csys, common_grid),
                    rocket(&u, csys, common_grid),
                );
                assert!(
                    si.warnings().len() == sc.warnings().len(),
                    "seed {seed}: SI warnings {:?}, scaled warnings {:?}",
                    si.warnings(),
                    sc.warnings()
                );
                compare(&mut check, &name, &si, &sc);
            }
        }
        let worst = check.finish().unwrap_or_else(|e| panic!("{e}"));
        println!(
            "airframe: seed {seed}: largest relative deviation {worst:e} ({})",
            check.worst().1
        );
    }
}

/// The check detects a dimensional error: the static margin written with the radius instead
/// of the diameter squared, `(z_CM − z_CP)/d²`, is caught; and a rocket built from scaled
/// inputs but SI constants (the numerical-derivative step then meaning 1 µs of the scaled
/// unit, the hidden `H = 1e-6` of mass.rs before it came from the constants) gives a
/// different c̈ on the pointwise path.
#[test]
fn a_dimensionally_wrong_formula_is_detected() {
    for seed in test_seeds(3) {
        let mut check = ScaledComparison::new(seed, TOL);
        let u = *check.units();
        let csys = CoordinateSystem::TailToNose;
        let (si, sc) = (rocket(&Units::SI, csys, true), rocket(&u, csys, true));
        let wrong = |r: &Rocket, t: f64| {
            (r.center_of_mass(t) - r.cp_position(0.0)) / (2.0 * r.radius()).powi(2)
        };
        check.compare(
            "wrong margin",
            wrong(&si, 1.0),
            wrong(&sc, u.scale(1.0, T)),
            Dimension::NONE,
        );
        if (u.length - 1.0).abs() > 0.05 {
            let e = check.finish().expect_err("a margin per length");
            assert!(
                e.contains("wrong margin") && e.contains(&seed.to_string()),
                "{e}"
            );
        }

        let mut check = ScaledComparison::new(seed, TOL);
        let si = rocket(&Units::SI, csys, false);
        let sc_si_step = Rocket::new(inputs(&u, csys), motor(&u, false)).expect("valid rocket");
        // t = 1 s is a node of the propellant-mass table, where c has a kink: the central
        // difference there is (slope jump)/h, proportional to the step.
        let time = 1.0;
        let (a, b) = (
            si.com_to_cdm_accel(time),
            sc_si_step.com_to_cdm_accel(u.scale(time, T)),
        );
        check_difference(&mut check, "c̈ with an SI step", &si, a, b);
        if (u.time - 1.0).abs() > 0.05 {
            assert!(check.finish().is_err(), "seed {seed}: SI step not detected");
        }
    }
}
