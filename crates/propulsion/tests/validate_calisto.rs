//! The Calisto solid motor (Cesaroni M1670, validation mission `calisto`) against the RocketPy
//! 1.13 figures of docs/physics.md §6.4 and §13: total impulse 6026.35 N·s, m_p0 = 2.955912 kg,
//! v̄_e = 2038.7448 m/s, grain bore r(1 s) = 0.020560 m and height h(1 s) = 0.108879 m, and
//! propellant masses m(t) − m_dry = 2.068184, 1.095282, 0.224893 kg at t = 1, 2, 3 s
//! (rocket masses 18.309184, 17.336282, 16.465893 kg minus the dry mass 16.241 kg).

use std::path::PathBuf;

use karman_math::Interpolation;
use karman_propulsion::{
    BatesGrains, BurnTime, CoordinateSystem, Motor, MotorStructure, ThrustCurve, ThrustData,
    ThrustOptions, ThrustSource,
};

fn calisto_thrust_file() -> Option<PathBuf> {
    let folder = karman_validation::folder()?;
    Some(folder.flight("calisto")?.dir.join("Cesaroni_M1670.eng"))
}

#[test]
fn validate_calisto_solid_motor() {
    let Some(file) = calisto_thrust_file() else {
        return;
    };
    // Inputs: validation/calisto/mission.toml [motor].
    let data = ThrustData::load(&file).expect("thrust file");
    let options = ThrustOptions {
        burn_time: Some(BurnTime::End(3.9)),
        reshape: None,
        interpolation: Interpolation::Linear,
    };
    let curve = ThrustCurve::new(&ThrustSource::Data(Box::new(data)), &options).expect("curve");
    let structure = MotorStructure {
        dry_mass: 1.815,
        dry_inertia: [0.125, 0.125, 0.002, 0.0, 0.0, 0.0],
        center_of_dry_mass: 0.317,
        nozzle_position: 0.0,
        nozzle_radius: 0.033,
        coordinate_system: CoordinateSystem::NozzleToCombustionChamber,
        reference_pressure: None,
    };
    let grains = BatesGrains {
        number: 5,
        density: 1815.0,
        outer_radius: 0.033,
        initial_inner_radius: 0.015,
        initial_height: 0.12,
        separation: 0.005,
        center_of_mass_position: 0.397,
        throat_radius: 0.011,
        only_radial_burn: false,
    };
    let motor = Motor::solid(curve, structure, grains.clone()).expect("motor");
    // Exact arithmetic on the same data: 1e-9 relative covers summation order.
    assert!(
        (motor.total_impulse() / 6026.35 - 1.0).abs() < 1e-9,
        "{}",
        motor.total_impulse()
    );
    // The quoted figures have 7 and 8 significant digits.
    assert!((motor.propellant_initial_mass() - 2.955_912).abs() < 1e-6);
    assert!((motor.exhaust_velocity() - 2038.7448).abs() < 1e-4);
    let state = grains.state_for_mass(motor.propellant_mass().eval(1.0));
    // r and h are quoted to 6 decimals (±5e-7 m).
    assert!(
        (state.inner_radius - 0.020_560).abs() < 6e-7,
        "r(1 s) = {}",
        state.inner_radius
    );
    assert!(
        (state.height - 0.108_879).abs() < 6e-7,
        "h(1 s) = {}",
        state.height
    );
    for (t, expected) in [(1.0, 2.068_184), (2.0, 1.095_282), (3.0, 0.224_893)] {
        let mass = motor.propellant_mass().eval(t);
        // Quoted to 6 decimals (±5e-7 kg); at these times RocketPy's LSODA steps are close.
        assert!(
            (mass - expected).abs() < 6e-7,
            "m_p({t}) = {mass}, RocketPy {expected}"
        );
    }
}
