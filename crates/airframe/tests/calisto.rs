//! Calisto (plain fins, docs/physics.md §13 "measured" RocketPy 1.13 values) against a hand-built
//! motor. docs/physics.md §13 quotes 6–8 significant digits; tolerances are a few units of the last
//! quoted digit unless a reason is given.

use crate::common::calisto;

fn assert_close(what: &str, got: f64, want: f64, tol: f64) {
    assert!(
        (got - want).abs() <= tol,
        "{what}: got {got}, want {want} ± {tol}"
    );
}

#[test]
fn validate_calisto_mass_properties() {
    let Some(r) = calisto(false) else { return };
    assert_close("m_dry", r.dry_mass(), 16.241, 1e-9);
    assert_close("z_CDM", r.center_of_dry_mass(), -0.104_825_4, 1e-7);
    assert_close("z_CM(0)", r.center_of_mass(0.0), -0.220_798_1, 1e-7);
    assert_close("dry I11", r.dry_inertia()[0], 7.864_455, 1e-6);
    // t, m, ṁ, c, I11, I33 (docs/physics.md §13 table).
    let rows = [
        (0.0, 19.196_912, 0.0, 0.115_973, 9.638_151, 0.037_942),
        (1.0, 18.309_184, -0.997_673, 0.085_078, 9.105_133, 0.037_563),
        (2.0, 17.336_282, -0.931_946, 0.047_585, 8.521_357, 0.036_977),
        (3.0, 16.465_893, -0.809_322, 0.010_287, 7.999_317, 0.036_235),
        (3.9, 16.241, 0.0, 0.0, 7.864_455, 0.036),
    ];
    for (t, m, mdot, c, i11, i33) in rows {
        assert_close(&format!("m({t})"), r.total_mass(t), m, 2e-6);
        assert_close(&format!("mdot({t})"), r.mass_flow_rate(t), mdot, 2e-6);
        assert_close(&format!("c({t})"), r.com_to_cdm(t), c, 2e-6);
        let i = r.inertia(t);
        assert_close(&format!("I11({t})"), i[0], i11, 2e-6);
        assert_close(&format!("I22({t})"), i[1], i11, 2e-6);
        assert_close(&format!("I33({t})"), i[2], i33, 2e-6);
    }
}

#[test]
fn validate_calisto_offset_rates() {
    let Some(r) = calisto(false) else { return };
    // ċ quoted to 7 digits; RocketPy's value is the slope of its LSODA-grid segment holding t,
    // ours that of a 1 ms grid: they agree to O(h·c̈) ≈ 1e-4 relative.
    for (t, cdot) in [
        (1.0, -3.640_481e-2),
        (2.0, -3.793_025e-2),
        (3.0, -3.651_363e-2),
    ] {
        assert_close(&format!("cdot({t})"), r.com_to_cdm_rate(t), cdot, 5e-5);
    }
    assert!(
        r.com_to_cdm_rate(3.95).abs() < 1e-15,
        "no offset rate after burn-out"
    );
    assert!(r.com_to_cdm_accel(1.0).abs() < 1e-15);
    // İ11 is the slope of I11(t): compare with a centred difference away from nodes.
    let h = 1e-4;
    let fd = (r.inertia(1.00005 + h)[0] - r.inertia(1.00005 - h)[0]) / (2.0 * h);
    assert_close("Idot11", r.inertia_rate(1.00005)[0], fd, 1e-6 * fd.abs());
    assert!(r.inertia_rate(5.0).iter().all(|v| v.abs() < 1e-15));
    assert!(r.mass_flow_rate_derivative(5.0).abs() < 1e-15);
}

#[test]
fn validate_calisto_surfaces_and_nozzle() {
    let Some(r) = calisto(false) else { return };
    let s = r.surfaces();
    assert_close("nose p_z", s[0].cp_body[2], 1.103_680_4, 1e-7);
    assert_close("fins p_z", s[1].cp_body[2], -0.994_734_6, 1e-7);
    assert_close("tail p_z", s[2].cp_body[2], -1.117_961_4, 1e-7);
    assert_close("d_n", r.nozzle_to_cdm(), 1.150_174_6, 1e-7);
    let g = r.nozzle_gyration();
    assert_close("S11", g[0], 0.330_997_6, 1e-7);
    assert_close("S22", g[1], 0.330_997_6, 1e-7);
    assert_close("S33", g[2], 0.000_544_5, 1e-7);
    assert_close(
        "reference area",
        r.reference_area(),
        std::f64::consts::PI * 0.0635 * 0.0635,
        1e-15,
    );
    assert_close(
        "fin reference length",
        s[1].reference_length(),
        0.127,
        1e-15,
    );
    // Roll coefficients of the set (docs/physics.md §7.6, cant 0.5°).
    assert_close(
        "roll forcing",
        s[1].roll_forcing(0.0),
        7.596_73 * 0.5f64.to_radians(),
        1e-5,
    );
    assert_close("roll damping", s[1].roll_damping(0.0), 14.879_16, 1e-4);
    assert!(s[0].roll_forcing(0.5).abs() < 1e-15 && s[2].roll_damping(0.5).abs() < 1e-15);
}

#[test]
fn validate_calisto_cp_and_margins() {
    let Some(r) = calisto(false) else { return };
    assert_close("z_CP(0)", r.cp_position(0.0), -0.499_426_4, 1e-7);
    assert_close("static margin t=0", r.static_margin(0.0), 2.193_924, 1e-6);
    assert_close(
        "static margin burn-out",
        r.static_margin(r.burn_out()),
        3.107_094,
        1e-6,
    );
    // The static-margin spline starts at its first sample, the margin with the Mach-0 CP.
    assert_eq!(
        r.stability_margin(0.0, 0.0).to_bits(),
        r.static_margin(0.0).to_bits(),
        "stability margin M=0"
    );
    // The CP moves aft with Mach as the fin slope grows (β falls).
    assert!(r.cp_position(0.8) < r.cp_position(0.3));
}

#[test]
fn validate_calisto_drag_curves() {
    let Some(r) = calisto(false) else { return };
    assert_close(
        "Cd_off(0.3)",
        r.drag_coefficient(false, 0.3),
        0.381_505_764,
        1e-9,
    );
    assert_close(
        "Cd_off(0.86)",
        r.drag_coefficient(false, 0.86),
        0.434_619_667,
        1e-9,
    );
    // The power-on curve is chosen by the flag: its first row (validation/calisto/
    // powerOnDragCurve.csv) is held below the first Mach (constant extrapolation).
    let first = crate::common::validation_dir()
        .map(|d| crate::common::drag(&d, "calisto/powerOnDragCurve.csv").ys()[0])
        .expect("data folder present");
    assert_close("Cd_on(0)", r.drag_coefficient(true, 0.0), first, 1e-15);
    assert_close(
        "Cd_on(0.3)",
        r.drag_coefficient(true, 0.3),
        0.381_505_764,
        1e-9,
    );
}

#[test]
fn validate_calisto_airfoil_reference() {
    // validation/calisto/reference.json (NACA 0012 fins): fins cn_alpha_mach0
    // 6.279880822469548, cp_position_mach0_m −0.5000358729772216.
    let Some(r) = calisto(true) else { return };
    let fins = &r.surfaces()[1];
    assert_close("CNα fins", fins.cn_alpha(0.0), 6.279_880_822_469_548, 1e-12);
    assert_close(
        "z_CP(0)",
        r.cp_position(0.0),
        -0.500_035_872_977_221_6,
        1e-12,
    );
}

#[test]
fn validate_calisto_recovery_data() {
    let Some(r) = calisto(false) else { return };
    let p = r.parachutes();
    assert_eq!(p.len(), 2);
    assert_eq!(p[0].name, "main");
    assert!((p[0].radius - 1.5).abs() < 1e-15 && (p[1].sampling_rate - 105.0).abs() < 1e-15);
    let b = r.rail_buttons().expect("buttons");
    assert!((b.angular_position_rad - std::f64::consts::FRAC_PI_4).abs() < 1e-15);
    assert!(r.warnings().is_empty(), "{:?}", r.warnings());
}

#[test]
fn validate_calisto_mirrored_coordinates_give_the_same_physics() {
    // The same rocket described nose-to-tail (every user position negated): body-axis
    // quantities and margins are unchanged, user-axis positions change sign (docs/physics.md §2.5).
    let Some(dir) = crate::common::validation_dir() else {
        return;
    };
    let motor = crate::common::calisto_motor(&dir);
    let a = karman_airframe::Rocket::new(crate::common::calisto_inputs(&dir, None), motor.clone())
        .expect("valid");
    let mut inputs = crate::common::calisto_inputs(&dir, None);
    inputs.coordinate_system = karman_airframe::CoordinateSystem::NoseToTail;
    inputs.center_of_mass_without_motor = -inputs.center_of_mass_without_motor;
    inputs.motor_position = -inputs.motor_position;
    for s in &mut inputs.surfaces {
        s.position = -s.position;
    }
    inputs.rail_buttons =
        Some(karman_airframe::RailButtons::new(-0.0818, 0.6182, 45.0).expect("valid buttons"));
    let b = karman_airframe::Rocket::new(inputs, motor).expect("valid");
    for t in [0.0, 0.7, 1.9, 3.2, 5.0] {
        assert_close("m", b.total_mass(t), a.total_mass(t), 1e-12);
        assert_close("c", b.com_to_cdm(t), a.com_to_cdm(t), 1e-12);
        assert_close("cdot", b.com_to_cdm_rate(t), a.com_to_cdm_rate(t), 1e-10);
        assert_close("z_CM", b.center_of_mass(t), -a.center_of_mass(t), 1e-12);
        assert_close("SM", b.static_margin(t), a.static_margin(t), 1e-9);
        for (x, y) in b.inertia(t).iter().zip(a.inertia(t)) {
            assert_close("I", *x, y, 1e-12);
        }
    }
    for (x, y) in b.surfaces().iter().zip(a.surfaces()) {
        assert_close("p_z", x.cp_body[2], y.cp_body[2], 1e-12);
    }
    assert_close("z_CP", b.cp_position(0.5), -a.cp_position(0.5), 1e-12);
    assert_close("d_n", b.nozzle_to_cdm(), a.nozzle_to_cdm(), 1e-12);
}

#[test]
fn mass_properties_equal_the_individual_methods() {
    use crate::common::{calisto_inputs, small_motor, validation_dir};
    use karman_airframe::Rocket;
    use karman_math::{Cursor, Extrapolation, Interpolation, Table1};
    let Some(solid) = calisto(false) else { return };
    let Some(dir) = validation_dir() else { return };
    // Propellant I33 on its own grid: the quantities are then looked up one by one.
    let mut motor = small_motor();
    motor.propellant_i33 = Table1::new(
        vec![0.0, 0.3, 1.0],
        vec![1e-5, 7e-6, 0.0],
        Interpolation::Linear,
        Extrapolation::Constant,
    )
    .expect("table");
    let mixed = Rocket::new(calisto_inputs(&dir, None), motor).expect("rocket");
    let same = |a: f64, b: f64| a.to_bits() == b.to_bits();
    for r in [&solid, &mixed] {
        for t in [-1.0, 0.0, 0.01, 0.3, 0.5, 1.0, 2.0, 3.0, 3.9, 3.95, 10.0] {
            let p = r.mass_properties(t);
            assert!(same(p.total_mass, r.total_mass(t)), "m({t})");
            assert!(same(p.mass_flow_rate, r.mass_flow_rate(t)), "ṁ({t})");
            let mddot = r.mass_flow_rate_derivative(t);
            assert!(same(p.mass_flow_rate_derivative, mddot), "m̈({t})");
            assert!(same(p.com_to_cdm, r.com_to_cdm(t)), "c({t})");
            assert!(same(p.com_to_cdm_rate, r.com_to_cdm_rate(t)), "ċ({t})");
            assert!(same(p.com_to_cdm_accel, r.com_to_cdm_accel(t)), "c̈({t})");
            let (i, i_rate) = (r.inertia(t), r.inertia_rate(t));
            assert!(p.inertia.iter().zip(i).all(|(a, b)| same(*a, b)), "I({t})");
            assert!(
                p.inertia_rate.iter().zip(i_rate).all(|(a, b)| same(*a, b)),
                "İ({t})"
            );
        }
        // Cursors carried forward and back through the times (and Mach numbers) change
        // nothing.
        let times = [-1.0, 0.0, 0.01, 0.3, 0.5, 1.0, 2.0, 3.0, 3.9, 3.95, 10.0];
        let (mut on_times, mut on_mach) = ([Cursor::default(); 2], Cursor::default());
        for &t in times.iter().chain(times.iter().rev()) {
            assert_eq!(
                r.mass_properties_near(t, &mut on_times),
                r.mass_properties(t)
            );
            let m = r.total_mass_near(t, &mut on_times[1]);
            assert!(same(m, r.mass_properties(t).total_mass), "m({t}) near");
            let thrust = r.net_thrust_near(t, 80_000.0, &mut on_times[0]);
            assert!(same(thrust, r.net_thrust(t, 80_000.0)), "T({t})");
            let mach = t / 4.0;
            for power_on in [true, false] {
                let cd = r.drag_coefficient_near(power_on, mach, &mut on_mach);
                assert!(same(cd, r.drag_coefficient(power_on, mach)), "Cd({mach})");
            }
        }
    }
}
