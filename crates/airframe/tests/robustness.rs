//! Impossible or questionable inputs: errors or warnings, never a panic or NaN downstream.

use crate::common::small_motor;
use karman_airframe::{
    AirframeError, CoordinateSystem, EllipticalFinsSpec, FreeFormFinsSpec, NoseConeSpec, NoseKind,
    Rocket, RocketInputs, SurfaceInput, SurfaceSpec, Sweep, TailSpec, TrapezoidalFinsSpec,
    inertia_components,
};
use karman_math::{Extrapolation, Interpolation, Table1};
use proptest::prelude::*;

fn nose(position: f64) -> SurfaceInput {
    SurfaceInput {
        pod: None,
        name: "nose".to_owned(),
        position,
        spec: SurfaceSpec::Nose(NoseConeSpec {
            length: 0.2,
            kind: NoseKind::Ogive,
            base_radius: None,
            bluffness: 0.0,
        }),
    }
}

fn fins(position: f64, span: f64, tip: f64) -> SurfaceInput {
    SurfaceInput {
        pod: None,
        name: "fins".to_owned(),
        position,
        spec: SurfaceSpec::TrapezoidalFins(TrapezoidalFinsSpec {
            n: 3,
            root_chord: 0.1,
            tip_chord: tip,
            span,
            sweep: Sweep::Default,
            cant_angle_deg: 0.0,
            angular_position_deg: 0.0,
            radius: None,
            airfoil: None,
        }),
    }
}

fn inputs(surfaces: Vec<SurfaceInput>) -> RocketInputs {
    RocketInputs {
        radius: 0.04,
        mass: 1.0,
        inertia: [0.1, 0.1, 0.001, 0.0, 0.0, 0.0],
        center_of_mass_without_motor: 0.5,
        coordinate_system: CoordinateSystem::TailToNose,
        power_off_drag: Table1::linear(vec![0.0], vec![0.5]).expect("table"),
        power_on_drag: Table1::linear(vec![0.0], vec![0.5]).expect("table"),
        motor_position: 0.0,
        surfaces,
        parachutes: Vec::new(),
        rail_buttons: None,
        eccentricities: Default::default(),
    }
}

/// Everything the equations of motion and reports evaluate is finite.
fn all_finite(r: &Rocket) -> bool {
    let mut values = Vec::new();
    for t in [0.0, 0.25, 0.5, 1.0, 2.0] {
        values.extend([
            r.total_mass(t),
            r.mass_flow_rate(t),
            r.mass_flow_rate_derivative(t),
            r.com_to_cdm(t),
            r.com_to_cdm_rate(t),
            r.center_of_mass(t),
            r.static_margin(t),
            r.thrust(t),
            r.net_thrust(t, 90_000.0),
        ]);
        values.extend(r.inertia(t));
        values.extend(r.inertia_rate(t));
        for mach in [0.0, 0.5, 0.9, 1.1, 3.0] {
            values.push(r.stability_margin(mach, t));
        }
    }
    for mach in [0.0, 0.79, 0.8, 1.0, 1.1, 2.5] {
        values.push(r.cp_position(mach));
        for s in r.surfaces() {
            values.extend([s.cn_alpha(mach), s.roll_forcing(mach), s.roll_damping(mach)]);
        }
    }
    values.iter().all(|v| v.is_finite())
}

#[test]
fn a_sound_rocket_has_no_warnings() {
    let r = Rocket::new(
        inputs(vec![nose(1.0), fins(0.12, 0.08, 0.05)]),
        small_motor(),
    )
    .expect("valid");
    assert!(r.warnings().is_empty(), "{:?}", r.warnings());
    assert!(all_finite(&r));
}

#[test]
fn no_surfaces_is_a_warning_with_finite_margins() {
    let r = Rocket::new(inputs(Vec::new()), small_motor()).expect("flyable");
    assert!(
        r.warnings()
            .iter()
            .any(|w| w.contains("no aerodynamic surfaces"))
    );
    assert!(all_finite(&r));
}

#[test]
fn cancelling_slopes_are_a_warning_with_finite_margins() {
    // A nose (CNα 2) and a boat-tail from r to 0 (CNα −2) cancel at every Mach.
    let tail = SurfaceInput {
        pod: None,
        name: "tail".to_owned(),
        position: 0.2,
        spec: SurfaceSpec::Tail(TailSpec {
            top_radius: 0.04,
            bottom_radius: 1e-9,
            length: 0.1,
            radius: None,
        }),
    };
    let r = Rocket::new(inputs(vec![nose(1.0), tail]), small_motor()).expect("flyable");
    assert!(
        r.warnings().iter().any(|w| w.contains("cancel")),
        "{:?}",
        r.warnings()
    );
    assert!(all_finite(&r));
}

#[test]
fn surfaces_outside_the_body_are_warnings() {
    let r = Rocket::new(
        inputs(vec![nose(1.0), fins(1.5, 0.08, 0.05)]),
        small_motor(),
    )
    .expect("flyable");
    assert!(
        r.warnings()
            .iter()
            .any(|w| w.contains("ahead of the nose tip")),
        "{:?}",
        r.warnings()
    );
    let r = Rocket::new(
        inputs(vec![nose(1.0), fins(-0.5, 0.08, 0.05)]),
        small_motor(),
    )
    .expect("flyable");
    assert!(
        r.warnings().iter().any(|w| w.contains("aft of the nozzle")),
        "{:?}",
        r.warnings()
    );
    // Fins whose 0.1 m root starts 0.02 m ahead of the nozzle exit hang 0.08 m past the tail.
    let nozzle = Rocket::new(inputs(vec![nose(1.0)]), small_motor())
        .expect("flyable")
        .nozzle_position();
    let r = Rocket::new(
        inputs(vec![nose(1.0), fins(nozzle + 0.02, 0.08, 0.05)]),
        small_motor(),
    )
    .expect("flyable");
    assert!(
        r.warnings()
            .iter()
            .any(|w| w.contains("fin root runs 0.0800 m past the tail")),
        "{:?}",
        r.warnings()
    );
    let mut wide = nose(1.0);
    if let SurfaceSpec::Nose(n) = &mut wide.spec {
        n.base_radius = Some(0.08);
    }
    let r = Rocket::new(inputs(vec![wide]), small_motor()).expect("flyable");
    assert!(
        r.warnings()
            .iter()
            .any(|w| w.contains("exceeds the rocket radius"))
    );
    assert!(all_finite(&r));
}

#[test]
fn impossible_geometry_is_an_error() {
    let bad = |s: Vec<SurfaceInput>| Rocket::new(inputs(s), small_motor()).is_err();
    assert!(bad(vec![fins(0.1, 0.0, 0.05)]), "tip chord with zero span");
    assert!(bad(vec![fins(0.1, -0.05, 0.05)]), "negative span");
    assert!(bad(vec![fins(0.1, 0.05, -0.01)]), "negative tip chord");
    let mut n = nose(1.0);
    if let SurfaceSpec::Nose(s) = &mut n.spec {
        s.length = -0.2;
    }
    assert!(bad(vec![n]), "negative nose length");
    let e = SurfaceInput {
        pod: None,
        name: "e".to_owned(),
        position: 0.1,
        spec: SurfaceSpec::EllipticalFins(EllipticalFinsSpec {
            n: 3,
            root_chord: 0.0,
            span: 0.05,
            cant_angle_deg: 0.0,
            angular_position_deg: 0.0,
            radius: None,
            airfoil: None,
        }),
    };
    assert!(bad(vec![e]), "zero root chord");
    let f = SurfaceInput {
        pod: None,
        name: "f".to_owned(),
        position: 0.1,
        spec: SurfaceSpec::FreeFormFins(FreeFormFinsSpec {
            n: 3,
            shape_points: vec![[0.0, 0.0], [0.1, 0.0]],
            cant_angle_deg: 0.0,
            angular_position_deg: 0.0,
            radius: None,
            airfoil: None,
        }),
    };
    assert!(bad(vec![f]), "degenerate free-form outline");
    let mut i = inputs(vec![nose(1.0)]);
    i.radius = 0.0;
    assert!(matches!(
        Rocket::new(i, small_motor()),
        Err(AirframeError::NotPositive { .. })
    ));
    let mut i = inputs(vec![nose(1.0)]);
    i.mass = -1.0;
    assert!(Rocket::new(i, small_motor()).is_err());
    let mut i = inputs(vec![nose(1.0)]);
    i.inertia[0] = -0.1;
    assert!(Rocket::new(i, small_motor()).is_err());
    let mut m = small_motor();
    m.coordinate_system_sign = 0.5;
    assert!(Rocket::new(inputs(vec![nose(1.0)]), m).is_err());
    assert!(inertia_components("rocket", &[1.0, 2.0]).is_err());
    assert_eq!(
        inertia_components("rocket", &[1.0, 2.0, 3.0]).expect("3 components")[3..],
        [0.0; 3]
    );
}

#[test]
fn mixed_grids_use_pointwise_formulas() {
    // A generic-motor-like layout: propellant mass on another grid than its CM (RocketPy then
    // evaluates c(t) pointwise). c must equal the formula −csys (z_pc − z_CDM) m_p/m.
    let mut m = small_motor();
    m.propellant_mass = Table1::new(
        vec![0.0, 0.3, 0.7, 1.0],
        vec![0.05, 0.035, 0.015, 0.0],
        Interpolation::Spline,
        Extrapolation::Constant,
    )
    .expect("table");
    let r = Rocket::new(inputs(vec![nose(1.0)]), m.clone()).expect("valid");
    for t in [0.0, 0.2, 0.55, 0.9] {
        let mp = m.propellant_mass.eval(t);
        let c = -(0.1 - r.center_of_dry_mass()) * mp / (r.dry_mass() + mp);
        assert!((r.com_to_cdm(t) - c).abs() < 1e-15);
        let h = 1e-6;
        let fd = (r.com_to_cdm(t + h) - r.com_to_cdm(t - h)) / (2.0 * h);
        if t > 0.0 {
            assert!((r.com_to_cdm_rate(t) - fd).abs() < 1e-7, "t {t}");
        }
    }
}

proptest! {
    #[test]
    fn arbitrary_fin_geometry_never_panics_or_gives_nan(
        root in -0.5f64..0.5, tip in -0.5f64..0.5, span in -0.5f64..0.5,
        sweep in -80.0f64..80.0, cant in -10.0f64..10.0, n in 0u32..10,
        position in -2.0f64..2.0, radius in -0.1f64..0.2,
    ) {
        let f = SurfaceInput {
            pod: None,
            name: "fins".to_owned(),
            position,
            spec: SurfaceSpec::TrapezoidalFins(TrapezoidalFinsSpec {
                n, root_chord: root, tip_chord: tip, span,
                sweep: Sweep::AngleDeg(sweep), cant_angle_deg: cant, angular_position_deg: 0.0,
                radius: Some(radius), airfoil: None,
            }),
        };
        if let Ok(r) = Rocket::new(inputs(vec![nose(1.0), f]), small_motor()) {
            prop_assert!(all_finite(&r));
        }
    }

    #[test]
    fn arbitrary_free_form_outline_never_panics_or_gives_nan(
        pts in proptest::collection::vec((-0.3f64..0.3, -0.05f64..0.3), 0..8),
    ) {
        let mut shape = vec![[0.0, 0.0]];
        shape.extend(pts.iter().map(|&(x, y)| [x, y]));
        shape.push([0.2, 0.0]);
        let f = SurfaceInput {
            pod: None,
            name: "fins".to_owned(),
            position: 0.2,
            spec: SurfaceSpec::FreeFormFins(FreeFormFinsSpec {
                n: 4, shape_points: shape, cant_angle_deg: 1.0, angular_position_deg: 0.0, radius: None, airfoil: None,
            }),
        };
        if let Ok(r) = Rocket::new(inputs(vec![nose(1.0), f]), small_motor()) {
            prop_assert!(all_finite(&r));
        }
    }

    #[test]
    fn arbitrary_nose_and_tail_never_panic_or_give_nan(
        length in -0.5f64..1.0, bluff in -0.2f64..1.2, kind in 0usize..7, power in 0.0f64..1.2,
        top in -0.05f64..0.1, bottom in -0.05f64..0.1, tail_len in -0.1f64..0.3,
    ) {
        let kinds = [
            NoseKind::Conical, NoseKind::Ogive, NoseKind::Elliptical, NoseKind::VonKarman,
            NoseKind::LvHaack, NoseKind::Parabolic, NoseKind::PowerSeries(power),
        ];
        let n = SurfaceInput {
            pod: None,
            name: "nose".to_owned(),
            position: 1.0,
            spec: SurfaceSpec::Nose(NoseConeSpec {
                length, kind: kinds[kind], base_radius: None, bluffness: bluff,
            }),
        };
        let t = SurfaceInput {
            pod: None,
            name: "tail".to_owned(),
            position: 0.1,
            spec: SurfaceSpec::Tail(TailSpec {
                top_radius: top, bottom_radius: bottom, length: tail_len, radius: None,
            }),
        };
        if let Ok(r) = Rocket::new(inputs(vec![n, t]), small_motor()) {
            prop_assert!(all_finite(&r));
        }
    }
}
