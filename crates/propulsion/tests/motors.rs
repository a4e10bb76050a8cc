//! Property tests: building a motor from arbitrary (possibly absurd) inputs returns an error
//! or a motor whose mass properties are finite; it never panics.

use karman_math::Interpolation;
use karman_propulsion::{
    BatesGrains, BurnTime, CoordinateSystem, CylindricalChamber, Motor, MotorStructure,
    ThrustCurve, ThrustData, ThrustOptions, ThrustSource,
};
use proptest::prelude::*;

fn value() -> impl Strategy<Value = f64> {
    prop_oneof![4 => -1.0..10.0f64, 1 => any::<f64>()]
}

fn structure() -> MotorStructure {
    MotorStructure {
        dry_mass: 1.0,
        dry_inertia: [0.1, 0.1, 0.01, 0.0, 0.0, 0.0],
        center_of_dry_mass: 0.3,
        nozzle_position: 0.0,
        nozzle_radius: 0.03,
        coordinate_system: CoordinateSystem::CombustionChamberToNozzle,
        reference_pressure: None,
    }
}

proptest! {
    #[test]
    fn motors_never_panic(
        points in proptest::collection::vec([value(), value()], 0..12),
        burn in proptest::option::of((value(), value())),
        reshape in proptest::option::of((value(), value())),
        spline in any::<bool>(),
        grains in (1u32..4, value(), value(), value(), value(), value()),
        sample_times in proptest::collection::vec(value(), 1..6),
    ) {
        let Ok(data) = ThrustData::from_points("inline", &points) else { return Ok(()) };
        let options = ThrustOptions {
            burn_time: burn.map(|(a, b)| BurnTime::Interval(a, b)),
            reshape: reshape.map(|(t, i)| (BurnTime::End(t), i)),
            interpolation: if spline { Interpolation::Spline } else { Interpolation::Linear },
        };
        let Ok(curve) = ThrustCurve::new(&ThrustSource::Data(Box::new(data)), &options) else { return Ok(()) };
        let (number, density, outer, inner, height, separation) = grains;
        let solid = BatesGrains {
            number,
            density: density * 1000.0,
            outer_radius: outer / 10.0,
            initial_inner_radius: inner / 10.0,
            initial_height: height / 10.0,
            separation: separation / 100.0,
            center_of_mass_position: 0.4,
            throat_radius: 0.01,
            only_radial_burn: number == 2,
        };
        let chamber = CylindricalChamber { radius: outer / 10.0, height: height / 10.0, position: 0.2, propellant_initial_mass: density };
        for motor in [
            Motor::solid(curve.clone(), structure(), solid),
            Motor::generic(curve, structure(), chamber),
        ].into_iter().flatten() {
            for &t in &sample_times {
                let (i11, i33) = motor.inertia(t);
                prop_assert!(motor.total_mass(t).is_finite() && motor.center_of_mass(t).is_finite());
                prop_assert!(i11.is_finite() && i33.is_finite());
                prop_assert!(motor.mass_flow_rate(t).is_finite());
            }
        }
    }
}

/// Regression (found by `motors_never_panic`): an impulse of 3.5e-290 N·s over a grain of
/// density 2.3e167 kg/m³ gives an exhaust velocity `I/m_p0` that underflows to 0, and so a
/// mass flow `−T/v̄_e` of −∞ (NaN outside the burn). The motor is refused instead.
#[test]
fn an_exhaust_velocity_that_underflows_is_refused() {
    let data = ThrustData::from_points("inline", &[[0.0, 0.0], [1.0, 100.0], [2.0, 0.0]]).unwrap();
    let options = ThrustOptions {
        burn_time: None,
        reshape: Some((BurnTime::End(2.0), 3.5e-290)),
        interpolation: Interpolation::Linear,
    };
    let curve = ThrustCurve::new(&ThrustSource::Data(Box::new(data)), &options).unwrap();
    let grains = BatesGrains {
        number: 1,
        density: 2.3e167,
        outer_radius: 0.05,
        initial_inner_radius: 0.02,
        initial_height: 0.1,
        separation: 0.0,
        center_of_mass_position: 0.4,
        throat_radius: 0.01,
        only_radial_burn: false,
    };
    let err = Motor::solid(curve, structure(), grains).unwrap_err();
    assert!(err.to_string().contains("exhaust velocity"), "{err}");
}

/// Regression (found by `motors_never_panic`): a thrust curve with points 2.8e-222 s apart.
/// The generic motor's spline tables on those nodes had overflowing coefficients, so its
/// inertia was NaN; the table is refused instead, and the solid motor stays finite.
#[test]
fn thrust_points_too_close_for_a_spline_are_refused() {
    let points = [
        [0.0, 0.0],
        [2.053885379143911e222, 0.0],
        [5.5918093247383425, 3.21327674432492],
    ];
    let data = ThrustData::from_points("inline", &points).unwrap();
    let options = ThrustOptions {
        burn_time: None,
        reshape: Some((BurnTime::End(1.0211669085730481), 0.8209120123052602)),
        interpolation: Interpolation::Linear,
    };
    let curve = ThrustCurve::new(&ThrustSource::Data(Box::new(data)), &options).unwrap();
    let grains = BatesGrains {
        number: 1,
        density: 6_714.327_510_560_222,
        outer_radius: 2.99942151836678e64,
        initial_inner_radius: 0.0,
        initial_height: 0.27183020695253095,
        separation: 0.0,
        center_of_mass_position: 0.4,
        throat_radius: 0.01,
        only_radial_burn: false,
    };
    let solid = Motor::solid(curve.clone(), structure(), grains).unwrap();
    let (i11, i33) = solid.inertia(0.0);
    assert!(i11.is_finite() && i33.is_finite());
    let chamber = CylindricalChamber {
        radius: 2.99942151836678e64,
        height: 0.27183020695253095,
        position: 0.2,
        propellant_initial_mass: 6.7143275105602225,
    };
    let err = Motor::generic(curve, structure(), chamber).unwrap_err();
    assert!(err.to_string().contains("not finite"), "{err}");
}
