//! Dimensional analysis of the math layer: tables, functions and quadrature built from data in
//! a random unit system give every result scaled by its dimension (`karman_math::dimensions`,
//! the numericalunits check of RocketPy). Tables carry an abscissa of dimension `X` and an
//! ordinate of dimension `Y`: values scale as `Y`, slopes as `Y/X`, integrals as `Y·X`.

use karman_math::dimensions::{Dimension, ScaledComparison, test_seeds};
use karman_math::{
    Extrapolation, Function, Interpolation, PhysicalConstants, QuadratureOptions, Table1, Units,
    integrate,
};

/// Agreement required between unit systems: a handful of roundings (each operation of the
/// scaled run rounds differently), far below any modelling error.
const TOL: f64 = 1e-9;

/// A thrust-like curve: time (s) → force (N).
const XS: [f64; 7] = [0.0, 0.05, 0.4, 1.1, 2.0, 3.3, 3.9];
const YS: [f64; 7] = [0.0, 1900.0, 2100.0, 1750.0, 1500.0, 600.0, 0.0];
const X_DIM: Dimension = Dimension::TIME;
const Y_DIM: Dimension = Dimension::FORCE;
/// Size of the ordinates and smallest spacing of the abscissae, SI.
const Y_SIZE: f64 = 2100.0;
const X_SPACING: f64 = 0.05;

fn table(u: &Units, interpolation: Interpolation, extrapolation: Extrapolation) -> Table1 {
    let xs = XS.iter().map(|&x| u.scale(x, X_DIM)).collect();
    let ys = YS.iter().map(|&y| u.scale(y, Y_DIM)).collect();
    Table1::new(xs, ys, interpolation, extrapolation).expect("valid table")
}

/// Query points inside and outside the table (SI), including nodes.
fn queries() -> Vec<f64> {
    vec![-0.5, 0.0, 0.03, 0.4, 0.77, 1.1, 2.5, 3.85, 3.9, 5.0]
}

fn check_tables(check: &mut ScaledComparison) {
    let u = *check.units();
    let interpolations = [
        Interpolation::Linear,
        Interpolation::Spline,
        Interpolation::Akima,
        Interpolation::Polynomial,
    ];
    let extrapolations = [
        Extrapolation::Constant,
        Extrapolation::Natural,
        Extrapolation::Zero,
    ];
    for interp in interpolations {
        for extrap in extrapolations {
            let si = table(&Units::SI, interp, extrap);
            let sc = table(&u, interp, extrap);
            let name = format!("{interp:?}/{extrap:?}");
            // Values that vanish (the end of the curve) come out as rounding noise of the
            // size of the data, so the deviations are measured against that size.
            for x in queries() {
                let xs = u.scale(x, X_DIM);
                let (y, dx) = (Y_SIZE, X_SPACING);
                let (a, b) = (si.eval(x), sc.eval(xs));
                check.compare_near(&format!("{name} f({x})"), a, b, Y_DIM, y);
                let (a, b) = (si.derivative(x), sc.derivative(xs));
                check.compare_near(&format!("{name} f'({x})"), a, b, Y_DIM / X_DIM, y / dx);
                let (a, b) = (si.second_derivative(x), sc.second_derivative(xs));
                let d2 = Y_DIM / X_DIM.powi(2);
                check.compare_near(&format!("{name} f''({x})"), a, b, d2, y / (dx * dx));
            }
            for (a, b) in [(0.0, 3.9), (0.2, 2.7), (-1.0, 6.0)] {
                check.compare(
                    &format!("{name} ∫[{a}, {b}]"),
                    si.integral(a, b),
                    sc.integral(u.scale(a, X_DIM), u.scale(b, X_DIM)),
                    Y_DIM * X_DIM,
                );
            }
        }
    }
    // The inverse of a monotone table swaps the dimensions.
    let mono = |u: &Units| {
        let xs = XS.iter().map(|&x| u.scale(x, X_DIM)).collect();
        let ys = XS
            .iter()
            .map(|&x| u.scale(100.0 * x + 7.0 * x * x, Dimension::IMPULSE))
            .collect();
        Table1::new(xs, ys, Interpolation::Linear, Extrapolation::Constant).expect("valid")
    };
    let (si, sc) = (
        mono(&Units::SI).inverse().expect("monotone"),
        mono(&u).inverse().expect("monotone"),
    );
    for j in [0.0, 3.0, 150.0, 400.0] {
        check.compare(
            &format!("inverse({j})"),
            si.eval(j),
            sc.eval(u.scale(j, Dimension::IMPULSE)),
            X_DIM,
        );
    }
    // Sampling a dimensional formula on a scaled interval (numpy linspace).
    let drop = |u: &Units| {
        let g = u.scale(9.80665, Dimension::ACCELERATION);
        let top = u.scale(12.0, Dimension::TIME);
        Table1::sample(
            move |t| 0.5 * g * t * t,
            0.0,
            top,
            40,
            Interpolation::Spline,
            Extrapolation::Natural,
        )
        .expect("valid")
    };
    let (si, sc) = (drop(&Units::SI), drop(&u));
    for t in [0.1, 5.55, 11.9, 13.0] {
        check.compare(
            &format!("sampled fall({t})"),
            si.eval(t),
            sc.eval(u.scale(t, Dimension::TIME)),
            Dimension::LENGTH,
        );
    }
}

fn check_functions(check: &mut ScaledComparison) {
    let u = *check.units();
    // Mass flow −T/v̄_e, then a weighted integral ∫ ṁ(t)·t dt (kg·s) by Gauss–Kronrod, and
    // a closure: drag ½ ρ v² C_d A.
    let build = |u: &Units| {
        let thrust = Function::table(table(u, Interpolation::Spline, Extrapolation::Zero));
        let ve = u.scale(2038.0, Dimension::VELOCITY);
        let mdot = -thrust / ve;
        let rho = u.scale(1.1, Dimension::DENSITY);
        let area = u.scale(0.0081, Dimension::AREA);
        let drag = Function::analytic(move |v| 0.5 * rho * v * v * 0.45 * area);
        (mdot, drag)
    };
    let (si, sc) = (build(&Units::SI), build(&u));
    let t_end = u.scale(3.9, Dimension::TIME);
    let weighted = |f: &Function| f * Function::analytic(|t| t);
    // The integrand has dimension kg; its integral kg·s. The tolerance of the quadrature is
    // a dimensional input too: the absolute one is expressed in the units of the integral.
    let options = |u: &Units| QuadratureOptions {
        abs_tol: u.scale(1e-12, Dimension::MASS * Dimension::TIME),
        ..QuadratureOptions::default()
    };
    let q_si = weighted(&si.0)
        .integral_with(0.0, 3.9, &options(&Units::SI))
        .expect("converges");
    let q_sc = weighted(&sc.0)
        .integral_with(0.0, t_end, &options(&u))
        .expect("converges");
    check.compare(
        "∫ ṁ t dt",
        q_si.value,
        q_sc.value,
        Dimension::MASS * Dimension::TIME,
    );
    let m_si = si.0.integral(0.0, 3.9).expect("exact").value;
    let m_sc = sc.0.integral(0.0, t_end).expect("exact").value;
    check.compare("∫ ṁ dt", m_si, m_sc, Dimension::MASS);
    let peak_si = si.0.minimum(0.0, 3.9).expect("extremum");
    let peak_sc = sc.0.minimum(0.0, t_end).expect("extremum");
    check.compare("min ṁ", peak_si.value, peak_sc.value, Dimension::MASS_FLOW);
    check.compare("argmin ṁ", peak_si.x, peak_sc.x, Dimension::TIME);
    for v in [30.0, 150.0, 310.0] {
        let vs = u.scale(v, Dimension::VELOCITY);
        check.compare("drag", si.1.eval(v), sc.1.eval(vs), Dimension::FORCE);
        // Central difference of a closure. Its step ε^⅓·max(1, |x|) has a floor of 1 in the
        // unit of x (a dimensional literal of `Function::derivative`), so for |x| < 1 the
        // scaled run uses a different physical step; a quadratic's central difference is
        // exact for any step, so only rounding differs here.
        check.compare(
            "d drag / dv",
            si.1.derivative(v),
            sc.1.derivative(vs),
            Dimension::FORCE / Dimension::VELOCITY,
        );
    }
    // Product and quotient of dimensional functions: power T·v and T/m.
    let v = |u: &Units| {
        Function::table(
            Table1::linear(
                vec![0.0, u.scale(3.9, Dimension::TIME)],
                vec![0.0, u.scale(280.0, Dimension::VELOCITY)],
            )
            .expect("valid"),
        )
    };
    let power =
        |u: &Units| Function::table(table(u, Interpolation::Linear, Extrapolation::Zero)) * v(u);
    let (p_si, p_sc) = (power(&Units::SI), power(&u));
    for t in [0.3, 2.2] {
        let ts = u.scale(t, Dimension::TIME);
        check.compare(
            "power",
            p_si.eval(t),
            p_sc.eval(ts),
            Dimension::FORCE * Dimension::VELOCITY,
        );
        check.compare(
            "d power / dt",
            p_si.derivative(t),
            p_sc.derivative(ts),
            Dimension::FORCE * Dimension::ACCELERATION,
        );
    }
}

fn check_quadrature(check: &mut ScaledComparison) {
    let u = *check.units();
    // Work of a drag force along a path: ∫ k x^{3/2} e^{-x/L} dx (N·m), with the absolute
    // tolerance expressed in the units of the result.
    let run = |u: &Units| {
        let k = u.scale(40.0, Dimension::FORCE / Dimension::new(1.5, 0.0, 0.0, 0.0));
        let l = u.scale(800.0, Dimension::LENGTH);
        let options = QuadratureOptions {
            abs_tol: u.scale(1e-12, Dimension::FORCE * Dimension::LENGTH),
            ..QuadratureOptions::default()
        };
        integrate(
            move |x: f64| k * x.powf(1.5) * (-x / l).exp(),
            0.0,
            u.scale(3000.0, Dimension::LENGTH),
            &options,
        )
        .expect("converges")
    };
    let (si, sc) = (run(&Units::SI), run(&u));
    check.compare(
        "work integral",
        si.value,
        sc.value,
        Dimension::FORCE * Dimension::LENGTH,
    );
}

fn check_constants(check: &mut ScaledComparison) {
    let u = *check.units();
    let si = PhysicalConstants::SI;
    let sc = si.in_units(&u);
    let l0 = si.isa_layers[1];
    let l0s = sc.isa_layers[1];
    // Every constant scales by its dimension …
    let pairs = [
        (
            "g0",
            si.standard_gravity,
            sc.standard_gravity,
            Dimension::ACCELERATION,
        ),
        (
            "R",
            si.air_gas_constant,
            sc.air_gas_constant,
            Dimension::GAS_CONSTANT,
        ),
        (
            "Sutherland B",
            si.sutherland_b,
            sc.sutherland_b,
            Dimension::VISCOSITY / Dimension::new(0.0, 0.0, 0.0, 0.5),
        ),
        (
            "Sutherland S",
            si.sutherland_s,
            sc.sutherland_s,
            Dimension::TEMPERATURE,
        ),
        (
            "ISA radius",
            si.isa_earth_radius,
            sc.isa_earth_radius,
            Dimension::LENGTH,
        ),
        (
            "table top",
            si.table_top_height,
            sc.table_top_height,
            Dimension::LENGTH,
        ),
        (
            "a",
            si.wgs84_semi_major_axis,
            sc.wgs84_semi_major_axis,
            Dimension::LENGTH,
        ),
        (
            "γ_e",
            si.wgs84_equatorial_gravity,
            sc.wgs84_equatorial_gravity,
            Dimension::ACCELERATION,
        ),
        (
            "Ω",
            si.earth_rotation_rate,
            sc.earth_rotation_rate,
            Dimension::FREQUENCY,
        ),
        (
            "P0",
            l0.base_pressure,
            l0s.base_pressure,
            Dimension::PRESSURE,
        ),
        (
            "T0",
            l0.base_temperature,
            l0s.base_temperature,
            Dimension::TEMPERATURE,
        ),
        (
            "lapse",
            l0.lapse_rate,
            l0s.lapse_rate,
            Dimension::TEMPERATURE / Dimension::LENGTH,
        ),
    ];
    for (name, a, b, d) in pairs {
        check.compare(name, a, b, d);
    }
    // … and the dimensionless groups the models are built on are unchanged.
    let groups = |c: &PhysicalConstants| {
        let l = c.isa_layers[1];
        [
            // Barometric exponent g0/(β R).
            c.standard_gravity / (l.lapse_rate * c.air_gas_constant),
            // Scale height over Earth radius R T0/(g0 R_E).
            c.air_gas_constant * l.base_temperature / (c.standard_gravity * c.isa_earth_radius),
            // Somigliana m = ω² a² b / GM against its definition ω² a / γ_e (to first order).
            c.earth_rotation_rate.powi(2) * c.wgs84_semi_major_axis / c.wgs84_equatorial_gravity,
            // Sutherland temperature ratio and the ideal-gas pressure ratio of layers.
            c.sutherland_s / l.base_temperature,
            c.isa_layers[2].base_pressure / l.base_pressure,
            c.heat_capacity_ratio,
        ]
    };
    for (i, (a, b)) in groups(&si).into_iter().zip(groups(&sc)).enumerate() {
        check.compare(&format!("group {i}"), a, b, Dimension::NONE);
    }
}

#[test]
fn math_layer_scales_with_its_units() {
    for seed in test_seeds(4) {
        let mut check = ScaledComparison::new(seed, TOL);
        check_tables(&mut check);
        check_functions(&mut check);
        check_quadrature(&mut check);
        check_constants(&mut check);
        let worst = check.finish().unwrap_or_else(|e| panic!("{e}"));
        println!(
            "math: seed {seed}: largest relative deviation {worst:e} ({})",
            check.worst().1
        );
    }
}

/// The check is not vacuous: a formula adding a length to an area (the wetted area of a
/// cylinder written `2πr + 2πrL` instead of `2πr² + 2πrL`) is caught for every seed whose
/// length factor is not 1, and a hidden SI literal (a fixed time step of 1e-3 "seconds" in a
/// finite difference) is caught as well.
#[test]
fn a_dimensionally_wrong_formula_is_detected() {
    for seed in test_seeds(4) {
        let mut check = ScaledComparison::new(seed, TOL);
        let u = *check.units();
        let wrong = |r: f64, l: f64| 2.0 * std::f64::consts::PI * (r + r * l);
        let right = |r: f64, l: f64| 2.0 * std::f64::consts::PI * (r * r + r * l);
        let (r, l) = (0.0635, 2.3);
        let (rs, ls) = (u.scale(r, Dimension::LENGTH), u.scale(l, Dimension::LENGTH));
        check.compare("right area", right(r, l), right(rs, ls), Dimension::AREA);
        assert!(check.finish().is_ok(), "{:?}", check.finish());
        check.compare("wrong area", wrong(r, l), wrong(rs, ls), Dimension::AREA);
        let e = check.finish().expect_err("a length added to an area");
        assert!(
            e.contains("wrong area") && e.contains(&seed.to_string()),
            "{e}"
        );

        // A central second difference with a step of 1e-3 that the scaled run does not
        // rescale (a literal meaning "seconds"), applied to x(t) = t⁴ (length).
        let mut check = ScaledComparison::new(seed, TOL);
        const H: f64 = 1e-3;
        let accel = |f: &dyn Fn(f64) -> f64, t: f64| (f(t + H) - 2.0 * f(t) + f(t - H)) / (H * H);
        let t = 2.0;
        let ts = u.scale(t, Dimension::TIME);
        let quartic_si = |t: f64| t.powi(4);
        let quartic_sc = |t: f64| t.powi(4) * u.scale(1.0, Dimension::new(1.0, 0.0, -4.0, 0.0));
        check.compare(
            "second difference of a quartic with an SI step",
            accel(&quartic_si, t),
            accel(&quartic_sc, ts),
            Dimension::ACCELERATION,
        );
        // The truncation error h²·f''''/12 = 2h² is 4e-8 of f'' = 48 at t = 2 s in SI, and
        // 4e-8/λ_T² in the scaled run: detected (> 1e-9) unless λ_T is within 2.5 % of 1.
        if (u.time - 1.0).abs() > 0.05 {
            assert!(check.finish().is_err(), "undetected for seed {seed}");
        }
    }
}
