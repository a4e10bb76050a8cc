//! Surfaces against RocketPy 1.13.0 itself: the numbers below were printed by
//! `tests/reference/rocketpy_surfaces.py` (kept beside this file) and are copied verbatim.
//! Closed forms agree to rounding (1e-12 relative); the bluff-tip lengths come from RocketPy's
//! `fsolve` (xtol 1.5e-8), so they get 1e-8 relative.

use crate::common::single_surface;
use karman_airframe::{
    EllipticalFinsSpec, FreeFormFinsSpec, NoseConeSpec, NoseKind, SurfaceSpec, Sweep,
    TrapezoidalFinsSpec,
};

fn check(what: &str, got: f64, want: f64, rel: f64) {
    assert!(
        (got - want).abs() <= rel * want.abs().max(1e-300),
        "{what}: got {got:e}, RocketPy {want:e}"
    );
}

#[test]
fn validate_bluff_noses_against_rocketpy() {
    let cases = [
        (
            NoseKind::Ogive,
            0.485_241_628_378_287_44,
            0.225_491_576_687_583_7,
        ),
        (
            NoseKind::VonKarman,
            0.494_490_436_779_639_2,
            0.247_245_218_389_819_6,
        ),
        (
            NoseKind::LvHaack,
            0.511_836_678_651_944_2,
            0.288_164_050_081_044_5,
        ),
        (
            NoseKind::Conical,
            0.408_773_106_248_587_4,
            0.272_515_404_165_724_95,
        ),
        (
            NoseKind::Elliptical,
            0.548_168_589_194_331_8,
            0.182_722_863_064_777_25,
        ),
        (
            NoseKind::Parabolic,
            0.484_348_872_004_737_75,
            0.242_174_436_002_368_88,
        ),
    ];
    for (kind, length, cpz) in cases {
        let s = single_surface(
            SurfaceSpec::Nose(NoseConeSpec {
                length: 0.55829,
                kind,
                base_radius: None,
                bluffness: 0.3,
            }),
            0.0635,
        );
        let karman_airframe::Geometry::Nose { length: got, .. } = s.geometry else {
            panic!("a nose")
        };
        check(&format!("{kind:?} length"), got, length, 1e-8);
        check(&format!("{kind:?} cpz"), s.cp_local, cpz, 1e-8);
        check(&format!("{kind:?} CNα"), s.cn_alpha(0.7), 2.0, 1e-15);
    }
    let s = single_surface(
        SurfaceSpec::Nose(NoseConeSpec {
            length: 0.4,
            kind: NoseKind::PowerSeries(0.5),
            base_radius: None,
            bluffness: 0.0,
        }),
        0.05,
    );
    check("powerseries cpz", s.cp_local, 0.2, 1e-12);
}

#[test]
fn validate_elliptical_fins_against_rocketpy() {
    // (span, CNα at Mach 0/0.5/0.9/1.5, cpz, Y_ma, K_d, K_f, G, C_lf,δ(0), C_ld,ω(0))
    let cases = [
        (
            0.1,
            [
                4.202_409_737_287_804,
                4.380_522_871_571_626,
                4.726_521_235_673_531,
                4.048_382_992_753_697,
            ],
            0.034_559_999_999_999_994,
            0.052_867_173_672_331_166,
            1.260_893_085_504_939,
            0.934_943_000_078_061_2,
            0.000_112_365_005_834_235_79,
            5.185_996_141_297_417,
            8.394_381_672_516_745,
        ),
        (
            0.05,
            [
                1.360_510_450_221_654,
                1.380_924_355_091_191_4,
                1.415_325_480_102_243,
                1.341_220_735_626_119_4,
            ],
            0.034_559_999_999_999_994,
            0.026_433_586_836_165_583,
            1.452_692_586_035_111,
            0.944_175_988_083_651,
            3.464_677_357_889_66e-5,
            1.166_609_793_900_127_9,
            0.859_508_292_461_771_4,
        ),
    ];
    for (span, cn, cpz, yma, kd, kf, g, clf, cld) in cases {
        let s = single_surface(
            SurfaceSpec::EllipticalFins(EllipticalFinsSpec {
                n: 3,
                root_chord: 0.12,
                span,
                cant_angle_deg: 1.0,
                angular_position_deg: 0.0,
                radius: None,
                airfoil: None,
            }),
            0.0635,
        );
        for (mach, want) in [0.0, 0.5, 0.9, 1.5].into_iter().zip(cn) {
            check(
                &format!("span {span} CNα({mach})"),
                s.cn_alpha(mach),
                want,
                1e-12,
            );
        }
        let f = s.fin_aerodynamics().expect("fins");
        check("cpz", s.cp_local, cpz, 1e-12);
        check("Y_ma", f.mean_aerodynamic_span, yma, 1e-12);
        check("K_d", f.roll_damping_interference, kd, 1e-12);
        check("K_f", f.roll_forcing_interference, kf, 1e-12);
        check("G", f.roll_integral, g, 1e-12);
        check("C_lf,δ(0)", f.roll_forcing_derivative(0.0), clf, 1e-12);
        check("C_ld,ω(0)", s.roll_damping(0.0), cld, 1e-12);
        check(
            "forcing",
            s.roll_forcing(0.0),
            clf * 1f64.to_radians(),
            1e-12,
        );
    }
}

#[test]
fn validate_free_form_fins_against_rocketpy() {
    // (outline, A_f, Γ_c, Y_ma, cpz, K_d, G, CNα at Mach 0/0.95/2, C_lf,δ(0), C_ld,ω(0))
    let cases = [
        (
            vec![[0.0, 0.0], [0.08, 0.1], [0.12, 0.1], [0.2, 0.0]],
            0.012,
            0.0,
            0.038_319_088_319_088_32,
            0.065_327_635_327_635_33,
            1.297_954_618_379_857_4,
            0.000_136_698_479_070_786_8,
            [
                5.983_707_571_369_113,
                6.502_610_123_912_928,
                4.997_473_748_745_131,
            ],
            6.461_046_609_746_625,
            14.970_080_672_284_872,
        ),
        (
            vec![
                [0.0, 0.0],
                [0.05, 0.06],
                [0.1, 0.09],
                [0.16, 0.09],
                [0.18, 0.0],
            ],
            0.011_55,
            0.432_801_970_145_770_4,
            0.037_932_457_786_116_32,
            0.068_583_541_796_956_44,
            1.295_828_225_578_871_6,
            0.000_127_472_120_192_307_66,
            [
                5.018_110_635_365_245,
                5.403_491_453_454_621,
                4.253_673_119_722_525,
            ],
            5.304_485_049_388_705,
            11.478_634_093_753_53,
        ),
    ];
    for (shape, area, gamma, yma, cpz, kd, g, cn, clf, cld) in cases {
        let s = single_surface(
            SurfaceSpec::FreeFormFins(FreeFormFinsSpec {
                n: 4,
                shape_points: shape,
                cant_angle_deg: 0.5,
                angular_position_deg: 0.0,
                radius: None,
                airfoil: None,
            }),
            0.0635,
        );
        let f = s.fin_aerodynamics().expect("fins");
        check("A_f", f.fin_area, area, 1e-12);
        assert!(
            (f.mid_chord_sweep - gamma).abs() < 1e-7,
            "Γ_c {} vs {gamma}",
            f.mid_chord_sweep
        );
        check("Y_ma", f.mean_aerodynamic_span, yma, 1e-12);
        check("cpz", s.cp_local, cpz, 1e-12);
        check("K_d", f.roll_damping_interference, kd, 1e-12);
        check("G", f.roll_integral, g, 1e-12);
        for (mach, want) in [0.0, 0.95, 2.0].into_iter().zip(cn) {
            check(&format!("CNα({mach})"), s.cn_alpha(mach), want, 1e-12);
        }
        check("C_lf,δ(0)", f.roll_forcing_derivative(0.0), clf, 1e-12);
        check("C_ld,ω(0)", s.roll_damping(0.0), cld, 1e-12);
    }
}

#[test]
fn validate_six_swept_fins_against_rocketpy() {
    let s = single_surface(
        SurfaceSpec::TrapezoidalFins(TrapezoidalFinsSpec {
            n: 6,
            root_chord: 0.15,
            tip_chord: 0.05,
            span: 0.08,
            sweep: Sweep::AngleDeg(30.0),
            cant_angle_deg: 0.0,
            angular_position_deg: 0.0,
            radius: Some(0.05),
            airfoil: None,
        }),
        0.05,
    );
    for (mach, want) in [
        (0.0, 8.515_062_177_630_135),
        (0.7, 9.026_183_551_915_146),
        (1.2, 9.109_386_545_392_343),
    ] {
        check(&format!("CNα({mach})"), s.cn_alpha(mach), want, 1e-12);
    }
    check("cpz", s.cp_local, 0.046_328_342_306_320_86, 1e-12);
    assert!(s.roll_forcing(0.5).abs() < 1e-15, "no cant, no forcing");
}
