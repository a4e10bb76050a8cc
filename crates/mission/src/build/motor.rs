//! `[motor]` → [`karman_propulsion::Motor`], as RocketPy 1.13's `SolidMotor` / `GenericMotor`
//! would build it from the same arguments (physics.md §6).
//!
//! - `thrust`: a number (constant, sampled over `burn_time`), an inline table (sorted by time,
//!   stably) or a file — `.eng` (RASP, a `(0, 0)` point prepended), `.rse` (RockSim XML), or
//!   two numeric columns for any other extension.
//! - `interpolation = "akima"` is Akima's (1970) method, as RocketPy 1.13's `"akima"` (see
//!   [`karman_math::Interpolation::Akima`]), so a RocketPy script translates unchanged.
//! - A generic motor without `center_of_dry_mass_position` takes `chamber_position`
//!   (RocketPy's default; an explicit 0 is kept, where RocketPy's truthiness test would also
//!   replace it); a solid motor's `throat_radius` defaults to 0.01 m.
//!
//! The mission's validation pass has already checked presence and ranges of every key (with
//! their lines; a required key that is somehow absent reaches the model as NaN and is
//! rejected there); errors here come from the thrust data (file, line and value) or from
//! combinations the model rejects, wrapped in [`MissionError::Model`] with section `motor`.

use karman_propulsion::{
    BatesGrains, BurnTime, CoordinateSystem, CylindricalChamber, Motor, MotorStructure,
    PropulsionError, ThrustCurve, ThrustData, ThrustOptions, ThrustSource,
};

use crate::schema::{Curve, MotorCoordinateSystem, MotorKind, MotorSpec};
use crate::{Mission, MissionError};

/// RocketPy's default nozzle throat radius of a solid motor, m (`SolidMotor(throat_radius=0.01)`).
const DEFAULT_THROAT_RADIUS: f64 = 0.01;

/// Builds the motor of `mission`.
///
/// # Errors
/// [`MissionError::Model`] (section `motor` or `motor.thrust`) wrapping the
/// [`PropulsionError`]: an unreadable or malformed thrust file (naming file, line and value),
/// a burn interval outside the data, a parameter the motor model rejects.
pub fn build_motor(mission: &Mission) -> Result<Motor, MissionError> {
    build_motor_with(mission, &thrust_source(mission)?)
}

fn model_err(mission: &Mission, section: &'static str) -> impl Fn(PropulsionError) -> MissionError {
    move |e: PropulsionError| mission.model_error(section, e)
}

/// Builds the motor of `mission` from an already read thrust `source` (the Monte Carlo reads
/// a thrust file once for all its samples); [`build_motor`] reads it with
/// [`thrust_source`].
///
/// # Errors
/// As [`build_motor`], except for reading the thrust data.
pub fn build_motor_with(mission: &Mission, source: &ThrustSource) -> Result<Motor, MissionError> {
    let spec = &mission.spec.motor;
    let options = ThrustOptions {
        burn_time: spec.burn_time.map(|b| BurnTime::Interval(b.start, b.end)),
        reshape: spec
            .reshape_thrust_curve
            .map(|[time, impulse]| (BurnTime::End(time), impulse)),
        interpolation: spec.interpolation.into(),
    };
    let thrust = ThrustCurve::new(source, &options).map_err(|e| {
        let key = match &e {
            PropulsionError::InvalidBurnTime { .. } if spec.reshape_thrust_curve.is_some() => {
                "motor.reshape_thrust_curve"
            }
            PropulsionError::InvalidBurnTime { .. } | PropulsionError::MissingBurnTime => {
                "motor.burn_time"
            }
            _ => "motor.thrust",
        };
        mission.model_error(key, e)
    })?;
    let chamber_position = spec.chamber_position.unwrap_or(0.0);
    let structure = MotorStructure {
        dry_mass: spec.dry_mass,
        dry_inertia: spec.dry_inertia.0,
        center_of_dry_mass: match spec.kind {
            MotorKind::Generic => spec.center_of_dry_mass_position.unwrap_or(chamber_position),
            MotorKind::Solid => spec.center_of_dry_mass_position.unwrap_or(0.0),
            MotorKind::Hybrid | MotorKind::Liquid => return Err(unsupported(mission)),
        },
        nozzle_position: spec.nozzle_position,
        nozzle_radius: spec.nozzle_radius,
        coordinate_system: match spec.coordinate_system {
            MotorCoordinateSystem::NozzleToCombustionChamber => {
                CoordinateSystem::NozzleToCombustionChamber
            }
            MotorCoordinateSystem::CombustionChamberToNozzle => {
                CoordinateSystem::CombustionChamberToNozzle
            }
        },
        reference_pressure: spec.reference_pressure,
    };
    let motor = match spec.kind {
        MotorKind::Solid => Motor::solid(
            thrust,
            structure,
            BatesGrains {
                number: spec.grain_number.unwrap_or(0),
                density: spec.grain_density.unwrap_or(f64::NAN),
                outer_radius: spec.grain_outer_radius.unwrap_or(f64::NAN),
                initial_inner_radius: spec.grain_initial_inner_radius.unwrap_or(f64::NAN),
                initial_height: spec.grain_initial_height.unwrap_or(f64::NAN),
                separation: spec.grain_separation.unwrap_or(0.0),
                center_of_mass_position: spec.grains_center_of_mass_position.unwrap_or(f64::NAN),
                throat_radius: spec.throat_radius.unwrap_or(DEFAULT_THROAT_RADIUS),
                only_radial_burn: false,
            },
        ),
        MotorKind::Hybrid | MotorKind::Liquid => return Err(unsupported(mission)),
        MotorKind::Generic => Motor::generic(
            thrust,
            structure,
            CylindricalChamber {
                radius: spec.chamber_radius.unwrap_or(f64::NAN),
                height: spec.chamber_height.unwrap_or(f64::NAN),
                position: chamber_position,
                propellant_initial_mass: spec.propellant_initial_mass.unwrap_or(f64::NAN),
            },
        ),
    };
    motor.map_err(|e| match &e {
        // A parameter named as in RocketPy is the mission key of the same name.
        PropulsionError::InvalidParameter { name, .. } => {
            mission.model_error(&format!("motor.{name}"), e)
        }
        _ => mission.model_error("motor", e),
    })
}

/// The error for a motor kind the format names but karman does not model yet (`load`
/// rejects it already; a hand-made [`Mission`] gets the same answer here).
fn unsupported(mission: &Mission) -> MissionError {
    mission.model_error(
        "motor.kind",
        format!("a {} motor is not supported yet", mission.spec.motor.kind),
    )
}

/// The thrust source named by `motor.thrust`: a constant, inline points or a file read now.
///
/// # Errors
/// [`MissionError::Model`] (section `motor.thrust`) for unreadable or malformed thrust data,
/// naming the file, line and value.
pub fn thrust_source(mission: &Mission) -> Result<ThrustSource, MissionError> {
    read_thrust(mission, &mission.spec.motor).map_err(model_err(mission, "motor.thrust"))
}

fn read_thrust(mission: &Mission, spec: &MotorSpec) -> Result<ThrustSource, PropulsionError> {
    Ok(match &spec.thrust {
        Curve::Constant(value) => ThrustSource::Constant(*value),
        Curve::Points(points) => ThrustSource::Data(Box::new(ThrustData::from_points(
            &format!("{} [motor].thrust", mission.path.display()),
            points,
        )?)),
        Curve::File(path) => {
            ThrustSource::Data(Box::new(ThrustData::load(&mission.resolve(path))?))
        }
    })
}
