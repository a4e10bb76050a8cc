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

use karman_airframe::{MotorProperties, RigidMass};
use karman_math::{PhysicalConstants, Table1};
use karman_model::PropellantPart;
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

/// The motor's tables and constants as the airframe needs them
/// ([`karman_airframe::MotorProperties`]).
///
/// A propellant in parts (a liquid motor whose tanks are on different time grids, a hybrid
/// motor's grain and tanks) is handed over with them ([`MotorProperties::propellant_parts`]),
/// which the rocket sums pointwise as RocketPy does (docs/physics.md §15.3–15.4).
#[must_use]
pub fn motor_properties(motor: &Motor) -> MotorProperties {
    let (i11, i33) = motor.propellant_inertia();
    let propellant_parts = motor.propellant_parts().to_vec();
    MotorProperties {
        thrust: motor.thrust_table().clone(),
        burn_start: motor.burn_start(),
        burn_out: motor.burn_out(),
        exhaust_velocity: motor.exhaust_velocity(),
        propellant_mass: motor.propellant_mass().clone(),
        mass_flow: None,
        propellant_center_of_mass: motor.propellant_center_of_mass().clone(),
        propellant_i11: i11.clone(),
        propellant_i33: i33.clone(),
        propellant_parts,
        dry_mass: motor.dry_mass(),
        center_of_dry_mass: motor.center_of_dry_mass(),
        dry_inertia: motor.dry_inertia(),
        nozzle_position: motor.nozzle_position(),
        nozzle_radius: motor.nozzle_radius(),
        coordinate_system_sign: motor.coordinate_system_sign(),
        reference_pressure: motor.reference_pressure(),
    }
}

/// `motor` ignited `ignition` s after the flight's time origin: every table of time moved by
/// that much (the motor of an upper stage, lit at or after its separation).
///
/// # Errors
/// [`karman_math::MathError`] when the shift rounds two of a table's times together.
pub fn delayed(
    motor: MotorProperties,
    ignition: f64,
) -> Result<MotorProperties, karman_math::MathError> {
    Ok(MotorProperties {
        thrust: motor.thrust.shifted(ignition)?,
        burn_start: motor.burn_start + ignition,
        burn_out: motor.burn_out + ignition,
        propellant_mass: motor.propellant_mass.shifted(ignition)?,
        mass_flow: match &motor.mass_flow {
            Some(table) => Some(table.shifted(ignition)?),
            None => None,
        },
        propellant_center_of_mass: motor.propellant_center_of_mass.shifted(ignition)?,
        propellant_i11: motor.propellant_i11.shifted(ignition)?,
        propellant_i33: motor.propellant_i33.shifted(ignition)?,
        propellant_parts: motor
            .propellant_parts
            .iter()
            .map(|p| {
                Ok(PropellantPart {
                    mass: p.mass.shifted(ignition)?,
                    center_of_mass: p.center_of_mass.shifted(ignition)?,
                    moment: p.moment.shifted(ignition)?,
                    i11: p.i11.shifted(ignition)?,
                })
            })
            .collect::<Result<_, karman_math::MathError>>()?,
        ..motor
    })
}

/// A cluster of `count` copies of `motor` (docs/physics.md §24.1), lit together, their axes at
/// `radius` from the rocket's axis (the `[motor]` keys `cluster_count`, `cluster_radius`): thrust,
/// mass flow, masses and mass moments times `count`, the centres of mass and the exhaust velocity
/// unchanged. Each inertia is the sum over the copies with the parallel-axis theorem: about the
/// roll axis `+ m r²` per copy, about each lateral axis `+ m r²/2` (the mean over the two lateral
/// axes of `m y²` and `m z²`, exact for three or more motors evenly on a ring; karman's rocket is
/// axisymmetric). The propellant's terms are tabulated on the union of the nodes of its inertia and
/// mass tables. The nozzle exit radius becomes [`cluster_exit_radius`]. One motor on the axis is
/// returned unchanged.
///
/// # Errors
/// [`karman_math::MathError`] for a propellant table that cannot be rebuilt.
pub fn clustered(
    motor: MotorProperties,
    count: u32,
    radius: f64,
) -> Result<MotorProperties, karman_math::MathError> {
    if count == 1 && radius == 0.0 {
        return Ok(motor);
    }
    let n = f64::from(count);
    let arm2 = radius * radius;
    // n (I(t) + k m(t)) on the union of the two tables' nodes (the terms of
    // `RigidMass::ring` at each instant), with I's interpolation and
    // extrapolation: exact for two linear tables.
    let with_mass = |inertia: &Table1, mass: &Table1, k: f64| {
        let mut xs: Vec<f64> = inertia.xs().iter().chain(mass.xs()).copied().collect();
        xs.sort_by(f64::total_cmp);
        xs.dedup();
        let ys = xs
            .iter()
            .map(|&t| n * (inertia.eval(t) + k * mass.eval(t)))
            .collect();
        Table1::new(xs, ys, inertia.interpolation(), inertia.extrapolation())
    };
    let dry = RigidMass {
        mass: motor.dry_mass,
        center: motor.center_of_dry_mass,
        inertia: motor.dry_inertia,
    }
    .ring(count, radius);
    Ok(MotorProperties {
        thrust: motor.thrust.scaled(n),
        propellant_mass: motor.propellant_mass.scaled(n),
        mass_flow: motor.mass_flow.as_ref().map(|t| t.scaled(n)),
        propellant_i11: with_mass(&motor.propellant_i11, &motor.propellant_mass, 0.5 * arm2)?,
        propellant_i33: with_mass(&motor.propellant_i33, &motor.propellant_mass, arm2)?,
        propellant_parts: motor
            .propellant_parts
            .iter()
            .map(|p| {
                Ok(PropellantPart {
                    mass: p.mass.scaled(n),
                    center_of_mass: p.center_of_mass.clone(),
                    moment: p.moment.scaled(n),
                    i11: with_mass(&p.i11, &p.mass, 0.5 * arm2)?,
                })
            })
            .collect::<Result<_, karman_math::MathError>>()?,
        dry_mass: dry.mass,
        dry_inertia: dry.inertia,
        nozzle_radius: cluster_exit_radius(motor.nozzle_radius, count),
        ..motor
    })
}

/// The exit radius of one nozzle whose area is that of a cluster of `count` nozzles of
/// `radius`, `radius √count` (the pressure thrust and the power-on base drag see the total
/// exit area).
#[must_use]
pub fn cluster_exit_radius(radius: f64, count: u32) -> f64 {
    radius * f64::from(count).sqrt()
}

/// The `[motor]` cluster of `mission`: `(cluster_count, cluster_radius)`, `(1, 0)` by default.
#[must_use]
pub fn cluster_of(mission: &Mission) -> (u32, f64) {
    let m = &mission.spec.motor;
    (
        m.cluster_count.unwrap_or(1),
        m.cluster_radius.unwrap_or(0.0),
    )
}
