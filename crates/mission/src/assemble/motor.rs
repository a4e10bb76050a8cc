//! `[motor]` → [`karman_propulsion::Motor`], as RocketPy 1.13's `SolidMotor` / `GenericMotor`
//! would build it from the same arguments (docs/physics.md §6).
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

use karman_math::PhysicalConstants;
use karman_propulsion::{
    BatesGrains, BurnTime, CoordinateSystem, CylindricalChamber, DEFAULT_DISCRETIZE,
    DEFAULT_PRESSURE, DEFAULT_TEMPERATURE, Fluid, Motor, MotorStructure, PositionedTank,
    PropulsionError, Tank, TankCurve, TankGeometry, TankKind, TankShape, ThrustCurve, ThrustData,
    ThrustOptions, ThrustSource,
};

use crate::schema::{
    Curve, DensitySpec, Discretize, FluidSpec, MotorCoordinateSystem, MotorKind, MotorSpec,
    TankGeometryKind, TankKindName, TankSpec,
};
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
            MotorKind::Solid | MotorKind::Hybrid | MotorKind::Liquid => {
                spec.center_of_dry_mass_position.unwrap_or(0.0)
            }
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
    let grains = |only_radial_burn: bool| BatesGrains {
        number: spec.grain_number.unwrap_or(0),
        density: spec.grain_density.unwrap_or(f64::NAN),
        outer_radius: spec.grain_outer_radius.unwrap_or(f64::NAN),
        initial_inner_radius: spec.grain_initial_inner_radius.unwrap_or(f64::NAN),
        initial_height: spec.grain_initial_height.unwrap_or(f64::NAN),
        separation: spec.grain_separation.unwrap_or(0.0),
        center_of_mass_position: spec.grains_center_of_mass_position.unwrap_or(f64::NAN),
        throat_radius: spec.throat_radius.unwrap_or(DEFAULT_THROAT_RADIUS),
        only_radial_burn: spec.only_radial_burn.unwrap_or(only_radial_burn),
    };
    let motor = match spec.kind {
        MotorKind::Solid => Motor::solid(thrust, structure, grains(false)),
        MotorKind::Hybrid => Motor::hybrid(
            thrust,
            structure,
            grains(true),
            build_tanks(mission)?,
            &PhysicalConstants::SI,
        ),
        MotorKind::Liquid => Motor::liquid(thrust, structure, build_tanks(mission)?),
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
        // The curve's own fault, not the motor's other keys.
        PropulsionError::NoImpulse { .. } => mission.model_error("motor.thrust", e),
        _ => mission.model_error("motor", e),
    })
}

/// The `[[motor.tanks]]` of `mission`, built in order (errors name `motor.tanks.<index>`).
fn build_tanks(mission: &Mission) -> Result<Vec<PositionedTank>, MissionError> {
    mission
        .spec
        .motor
        .tanks
        .iter()
        .enumerate()
        .map(|(index, spec)| {
            let err = |e: PropulsionError| mission.model_error(&tank_key(index, &e), e);
            Ok(PositionedTank {
                tank: build_tank(mission, index, spec).map_err(err)?,
                position: spec.position,
            })
        })
        .collect()
}

/// The mission key a tank's model error belongs to: the parameter's own key where the error
/// names one, else the tank.
fn tank_key(index: usize, e: &PropulsionError) -> String {
    let key = match e {
        PropulsionError::InvalidParameter { name, .. }
        | PropulsionError::Table { what: name, .. } => match *name {
            "tank radius" => "geometry.radius",
            "tank height" => "geometry.height",
            "liquid density" => "liquid.density",
            "gas density" => "gas.density",
            other => other,
        },
        _ => "",
    };
    if key.is_empty() || key.contains(' ') {
        format!("motor.tanks.{index}")
    } else {
        format!("motor.tanks.{index}.{key}")
    }
}

/// A mission curve of time as a tank curve (files read as two columns, inline points sorted
/// stably by time).
fn tank_curve(mission: &Mission, curve: &Curve) -> Result<TankCurve, PropulsionError> {
    let points = match curve {
        Curve::Constant(value) => return Ok(TankCurve::Constant(*value)),
        Curve::Points(_) => curve.sorted_points().unwrap_or_default(),
        Curve::File(path) => karman_math::read_curve(mission.resolve(path))?,
    };
    Ok(TankCurve::Points {
        times: points.iter().map(|p| p[0]).collect(),
        values: points.iter().map(|p| p[1]).collect(),
    })
}

/// A tank's fluid; `what` (`"liquid density"` or `"gas density"`) names its table in errors.
fn fluid(
    mission: &Mission,
    spec: &FluidSpec,
    what: &'static str,
) -> Result<Fluid, PropulsionError> {
    match &spec.density {
        DensitySpec::Constant(rho) => Ok(Fluid::constant(&spec.name, *rho)),
        DensitySpec::Rows(rows) => Fluid::tabulated(&spec.name, rows, what),
        DensitySpec::File(path) => {
            let rows = karman_math::read_columns(mission.resolve(path))?;
            let rows: Vec<[f64; 3]> = rows
                .iter()
                .map(|r| match r.as_slice() {
                    &[t, p, rho] => Ok([t, p, rho]),
                    _ => Err(PropulsionError::InvalidParameter {
                        name: what,
                        value: r.len() as f64,
                        reason: "a density file needs three columns: temperature, pressure, density",
                    }),
                })
                .collect::<Result<_, _>>()?;
            Fluid::tabulated(&spec.name, &rows, what)
        }
    }
}

fn build_tank(mission: &Mission, index: usize, spec: &TankSpec) -> Result<Tank, PropulsionError> {
    let g = &spec.geometry;
    let number = |curve: &Curve| match curve {
        Curve::Constant(v) => *v,
        Curve::Points(_) | Curve::File(_) => f64::NAN,
    };
    let shape = match g.kind {
        TankGeometryKind::Cylindrical => TankShape::Cylindrical {
            radius: number(&g.radius),
            height: g.height.unwrap_or(f64::NAN),
            spherical_caps: g.spherical_caps,
        },
        TankGeometryKind::Spherical => TankShape::Spherical {
            radius: number(&g.radius),
        },
        TankGeometryKind::Custom => match tank_curve(mission, &g.radius)? {
            TankCurve::Points { times, values } => TankShape::Custom {
                heights: times,
                radii: values,
            },
            TankCurve::Constant(_) => TankShape::Custom {
                heights: Vec::new(),
                radii: Vec::new(),
            },
        },
    };
    let curve = |c: &Option<Curve>, default: f64| {
        c.as_ref()
            .map_or(Ok(TankCurve::Constant(default)), |c| tank_curve(mission, c))
    };
    let kind = match spec.kind {
        TankKindName::MassFlowRate => TankKind::MassFlowRate {
            initial_liquid_mass: spec.initial_liquid_mass.unwrap_or(f64::NAN),
            initial_gas_mass: spec.initial_gas_mass.unwrap_or(f64::NAN),
            liquid_in: curve(&spec.liquid_mass_flow_rate_in, 0.0)?,
            liquid_out: curve(&spec.liquid_mass_flow_rate_out, 0.0)?,
            gas_in: curve(&spec.gas_mass_flow_rate_in, 0.0)?,
            gas_out: curve(&spec.gas_mass_flow_rate_out, 0.0)?,
        },
        TankKindName::Ullage => TankKind::Ullage(curve(&spec.ullage, f64::NAN)?),
        TankKindName::Level => TankKind::Level(curve(&spec.liquid_height, f64::NAN)?),
        TankKindName::Mass => TankKind::Mass {
            liquid: curve(&spec.liquid_mass, f64::NAN)?,
            gas: curve(&spec.gas_mass, f64::NAN)?,
        },
    };
    let discretize = match spec.discretize {
        None | Some(Discretize::Flag(true)) => Some(DEFAULT_DISCRETIZE),
        Some(Discretize::Nodes(n)) => Some(n as usize),
        // No resampling: the curves keep their own points (RocketPy's `discretize=None`).
        Some(Discretize::Flag(false)) => None,
    };
    let constants = PhysicalConstants::SI;
    Tank::new(
        karman_propulsion::TankSpec {
            name: spec.name.clone().unwrap_or_else(|| format!("tank {index}")),
            kind,
            geometry: TankGeometry::new(shape, &constants)?,
            flux_time: (spec.flux_time.start, spec.flux_time.end),
            liquid: fluid(mission, &spec.liquid, "liquid density")?,
            gas: fluid(mission, &spec.gas, "gas density")?,
            discretize,
            temperature: curve(&spec.temperature, DEFAULT_TEMPERATURE)?,
            pressure: curve(&spec.pressure, DEFAULT_PRESSURE)?,
        },
        &constants,
    )
}

/// The thrust source named by `motor.thrust`: a constant, inline points or a file read now.
///
/// # Errors
/// [`MissionError::Model`] (section `motor.thrust`) for unreadable or malformed thrust data,
/// naming the file, line and value.
pub fn thrust_source(mission: &Mission) -> Result<ThrustSource, MissionError> {
    let source =
        read_thrust(mission, &mission.spec.motor).map_err(model_err(mission, "motor.thrust"))?;
    // A burn longer than any flight (a curve to t = 1e9 s) cannot be flown to its end.
    let max = crate::validate::MAX_FLIGHT_TIME;
    if let ThrustSource::Data(data) = &source
        && let Some(&end) = data.times.last()
        && end > max
    {
        return Err(mission.model_error(
            "motor.thrust",
            format!(
                "{}: the curve ends at t = {} s, after the longest flight karman flies ({max} s)",
                data.source_name,
                karman_math::text::number(end)
            ),
        ));
    }
    Ok(source)
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
