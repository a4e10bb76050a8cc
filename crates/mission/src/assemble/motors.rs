//! `[[extra_motors]]`: several motors in one rocket (mission-format.md, "Several motors"), and
//! [`ThrustCache`], the thrust data of all of a mission's motors read once (docs/physics.md
//! §24.2).
//!
//! The airframe flies one [`MotorProperties`]; a rocket with motors besides `[motor]` flies
//! their sum, [`combined`], built once before the flight:
//!
//! - each motor is first the single motor it would be alone (its cluster,
//!   [`super::motor::clustered`]), then moved to its ignition time
//!   ([`super::motor::delayed`]), then placed in the coordinates of `[motor]` (its origin at
//!   `rocket.motor_position`, its orientation): a position `z` of motor `k`, whose origin is
//!   at `p_k` in rocket coordinates with orientation `s_k = csys_r · csys_m,k`, is
//!   `s_0 (p_k − p_0) + s_0 s_k z` in those coordinates;
//! - thrust: the sum of the thrust curves on the union of their times, with a step where one
//!   of them steps (an ignition or burn-out with a jump); exact, since the curves are linear
//!   between their points (a combination refuses another interpolation);
//! - propellant: each motor's propellant (or each of its parts, for a liquid or hybrid motor)
//!   is one part of [`MotorProperties::propellant_parts`], which the airframe sums pointwise
//!   at every instant: `m_p = Σ m_i`, `z_p = Σ m_i z_i / m_p`, `I11_p = Σ (I_i + m_i (z_i −
//!   z_p)²)` (the parallel-axis theorem, Steiner; every motor on the rocket's axis or a
//!   cluster about it, whose own lateral offsets its `I11` already holds), so no ratio is
//!   interpolated between nodes; the roll inertia `I33` is the sum of the motors' (each about
//!   the rocket's axis), tabulated on the union of their times. The standard equations fly
//!   the derivative of that mass (`Σ dm_i/dt`, each motor's own slope);
//! - dry mass: summed, at the combined centre of dry mass, with the lateral inertias moved
//!   there by the parallel-axis theorem;
//! - burn window: from the first ignition to the last burn-out (the power-on drag applies over
//!   it, and a `"burnout + X"` trigger counts from the last burn-out);
//! - `rocketpy_1_13` mass flow `−T/v̄_e`: one exhaust velocity for the whole, the total
//!   impulse over the total propellant mass `Σ I_k / Σ m_p0,k`, so that the flow integrates
//!   to the propellant burnt; exact when the motors share their exhaust velocity;
//! - nozzle exit radius: `√(Σ r_k²)`, the radius of the total exit area (as a cluster's,
//!   [`super::motor::cluster_exit_radius`]), which the power-on base drag of the drag
//!   estimate sees; the pressure-thrust correction (`reference_pressure`), which would need the
//!   exit area of the motors burning at each instant, is refused for a combination;
//! - nozzle position: the aftmost nozzle exit of the motors. The launch checks take the nozzle
//!   as the rocket's aft end (the nozzle on the airframe, the rail length from the nozzle to
//!   the upper button), so the aftmost exit is the one they need. The 6-DOF equations use the
//!   nozzle in their variable-mass terms: the lever arm `d_n` from the centre of dry mass and
//!   the jet-damping gyration `ṁ (r_n²/4 + d_n²/4, r_n²/4 + d_n²/4, r_n²/2)` (docs/physics.md
//!   §5.6, Ceotto et al. 2021). With one exit for all motors these are exact when the nozzles
//!   end in one plane (the usual air start, motor tubes flush with the aft end) up to the `r_n²`
//!   terms, which, as for a cluster, take the total exit area with the total mass flow rather
//!   than each nozzle with its own flow; those are small beside `d_n²` (a few cm² against a
//!   lever arm of a metre or so).

use karman_airframe::{MotorProperties, RigidMass};
use karman_math::{Extrapolation, Interpolation, MathError, Table1};
use karman_model::PropellantPart;
use karman_propulsion::{Motor, ThrustSource};
use std::borrow::Cow;

use super::motor::{build_motor, build_motor_with, thrust_source};
use super::motor::{clustered, delayed, motor_properties};
use super::stage_view::{in_stage, stage_mission};
use crate::schema::{Curve, RocketCoordinateSystem};
use crate::{Mission, MissionError};

/// One motor of a combination: its properties (clustered and moved to its ignition time) in
/// its own coordinates, and where its coordinate origin sits in rocket coordinates.
#[derive(Debug, Clone)]
pub struct PlacedMotor {
    /// The motor as it would fly alone, ignition time included.
    pub properties: MotorProperties,
    /// Its origin, rocket coordinates, m.
    pub position: f64,
}

/// Why motors cannot be combined.
#[derive(Debug, thiserror::Error)]
pub enum CombineError {
    /// A thrust curve that is not linear between its points.
    #[error(
        "motor {index}'s thrust curve is not linear between its points; several motors are \
         summed on the union of their thrust-curve times, which needs `interpolation = \"linear\"`"
    )]
    NonLinearThrust {
        /// The motor, 0 for `[motor]`.
        index: usize,
    },
    /// The pressure-thrust correction.
    #[error(
        "motor {index} has a `reference_pressure`; the pressure-thrust correction of several \
         motors (each exit area only while its motor burns) is not supported yet"
    )]
    ReferencePressure {
        /// The motor, 0 for `[motor]`.
        index: usize,
    },
    /// A motor whose mass flow is tabulated apart from its propellant mass.
    #[error("motor {index} has a mass-flow table of its own, which cannot be combined")]
    MassFlowTable {
        /// The motor, 0 for `[motor]`.
        index: usize,
    },
    /// No motor at all.
    #[error("no motor to combine")]
    NoMotor,
    /// A table that cannot be formed.
    #[error(transparent)]
    Table(#[from] MathError),
}

/// The thrust data of every motor of a mission (`[motor]`, each `[stages.motor]`, each
/// `[[extra_motors]]` entry's), read once, each with the `thrust` key it was read from: a
/// multi-stage flight builds its motors from them, and a Monte Carlo study reads its thrust
/// files once for all its samples.
#[derive(Debug, Clone)]
pub struct ThrustCache(Vec<(Curve, ThrustSource)>);

impl ThrustCache {
    /// Reads the thrust of every motor of `mission`.
    ///
    /// # Errors
    /// The thrust readers' errors, named by the motor's key.
    pub fn read(mission: &Mission) -> Result<Self, MissionError> {
        let mut cache = Self(vec![(
            mission.spec.motor.thrust.clone(),
            thrust_source(mission)?,
        )]);
        for (index, stage) in mission.spec.stages.iter().enumerate() {
            if let Some(motor) = &stage.motor
                && !cache.holds(&motor.thrust)
            {
                let source = thrust_source(&stage_mission(mission, index))
                    .map_err(|e| in_stage(e, index))?;
                cache.0.push((motor.thrust.clone(), source));
            }
        }
        for (index, extra) in mission.spec.extra_motors.iter().enumerate() {
            if !cache.holds(&extra.motor.thrust) {
                let source = thrust_source(&extra_motor_mission(mission, index))
                    .map_err(|e| in_extra(e, index))?;
                cache.0.push((extra.motor.thrust.clone(), source));
            }
        }
        Ok(cache)
    }

    fn find(&self, thrust: &Curve) -> Option<&ThrustSource> {
        self.0
            .iter()
            .find_map(|(curve, source)| (curve == thrust).then_some(source))
    }

    fn holds(&self, thrust: &Curve) -> bool {
        self.find(thrust).is_some()
    }

    /// The `[motor]` of `vehicle` (a mission in the same folder: one vehicle of a stack, one
    /// extra motor alone, a Monte Carlo sample), from the thrust read once when its `thrust`
    /// key is one of those read, else read now (a sample that varies the curve).
    ///
    /// # Errors
    /// The motor builder's errors.
    pub fn motor(&self, vehicle: &Mission) -> Result<Motor, MissionError> {
        build_motor_with(vehicle, &*self.source(vehicle)?)
    }

    /// The thrust data of `vehicle`'s `[motor]`, as [`ThrustCache::motor`] takes it.
    ///
    /// # Errors
    /// The thrust readers' errors, for a curve not read before.
    pub fn source(&self, vehicle: &Mission) -> Result<Cow<'_, ThrustSource>, MissionError> {
        Ok(match self.find(&vehicle.spec.motor.thrust) {
            Some(source) => Cow::Borrowed(source),
            None => Cow::Owned(thrust_source(vehicle)?),
        })
    }
}

/// `mission` with `[[extra_motors]]` entry `index`'s motor as its `[motor]` (and no extra
/// motors), its keys located at the entry's, so that the motor builder's errors name them.
pub(crate) fn extra_motor_mission(mission: &Mission, index: usize) -> Mission {
    let mut spec = mission.spec.clone();
    spec.motor = spec.extra_motors[index].motor.clone();
    spec.extra_motors.clear();
    mission.part(spec, &extra_prefix(index), EXTRA_ROOTS)
}

/// The tables of an `[[extra_motors]]` entry built as a mission's own.
const EXTRA_ROOTS: &[&str] = &["motor"];

/// The motor of `[[extra_motors]]` entry `index` alone (one motor of its cluster, at its own
/// time origin), its thrust data from `thrusts` when given, else read now.
///
/// # Errors
/// The motor builder's errors, named by the entry's keys.
pub(crate) fn extra_motor(
    mission: &Mission,
    index: usize,
    thrusts: Option<&ThrustCache>,
) -> Result<Motor, MissionError> {
    let alone = extra_motor_mission(mission, index);
    match thrusts {
        Some(thrusts) => thrusts.motor(&alone),
        None => build_motor(&alone),
    }
    .map_err(|e| in_extra(e, index))
}

/// An error met while building `[[extra_motors]]` entry `index` from its own mission, named by
/// the entry's keys.
fn in_extra(error: MissionError, index: usize) -> MissionError {
    error.in_part(&extra_prefix(index), EXTRA_ROOTS)
}

/// The key prefix of `[[extra_motors]]` entry `index`.
fn extra_prefix(index: usize) -> String {
    format!("extra_motors.{index}.")
}

/// The key of a motor of the combination: `motor` for index 0, else its
/// `[[extra_motors]]` entry's.
fn motor_key(index: usize, key: &str) -> String {
    match index {
        0 => format!("motor.{key}"),
        k => format!("extra_motors.{}.motor.{key}", k - 1),
    }
}

/// `primary` (the `[motor]` of `mission`, clustered and at its ignition time) combined with
/// every `[[extra_motors]]` entry ([`combined`]); `primary` unchanged when there is none.
/// The extra motors' thrust data come from `thrusts` when given, else are read now.
///
/// # Errors
/// The motor builder's errors, named by the entry's keys; [`CombineError`] located at the
/// key that causes it.
pub fn with_extra_motors(
    mission: &Mission,
    primary: MotorProperties,
    thrusts: Option<&ThrustCache>,
) -> Result<MotorProperties, MissionError> {
    let spec = &mission.spec;
    if spec.extra_motors.is_empty() {
        return Ok(primary);
    }
    let mut motors = Vec::with_capacity(spec.extra_motors.len() + 1);
    motors.push(PlacedMotor {
        properties: primary,
        position: spec.rocket.motor_position,
    });
    for (index, extra) in spec.extra_motors.iter().enumerate() {
        let motor = extra_motor(mission, index, thrusts)?;
        let m = &extra.motor;
        let key = |k: &str| format!("extra_motors.{index}.{k}");
        let single = clustered(
            motor_properties(&motor),
            m.cluster_count.unwrap_or(1),
            m.cluster_radius.unwrap_or(0.0),
        )
        .map_err(|e| mission.model_error(&key("motor"), e))?;
        let properties = if extra.ignition_delay == 0.0 {
            single
        } else {
            delayed(single, extra.ignition_delay)
                .map_err(|e| mission.model_error(&key("ignition_delay"), e))?
        };
        motors.push(PlacedMotor {
            properties,
            position: extra.motor_position,
        });
    }
    let csys = match spec.rocket.coordinate_system {
        RocketCoordinateSystem::TailToNose => 1.0,
        RocketCoordinateSystem::NoseToTail => -1.0,
    };
    combined(&motors, csys).map_err(|e| {
        let key = match &e {
            CombineError::NonLinearThrust { index } => motor_key(*index, "interpolation"),
            CombineError::ReferencePressure { index } => motor_key(*index, "reference_pressure"),
            CombineError::MassFlowTable { index } => motor_key(*index, "kind"),
            CombineError::Table(_) | CombineError::NoMotor => "extra_motors".to_owned(),
        };
        mission.model_error(&key, e)
    })
}

/// The exit radius of the combination of `mission`'s motors, `√(Σ r_k²)` over every motor of
/// every cluster (the exit radius of the `[motor]` cluster alone without extra motors).
#[must_use]
pub fn combined_exit_radius(mission: &Mission, primary_radius: f64) -> f64 {
    let spec = &mission.spec;
    let cluster = |m: &crate::schema::MotorSpec, r: f64| {
        super::motor::cluster_exit_radius(r, m.cluster_count.unwrap_or(1))
    };
    let first = cluster(&spec.motor, primary_radius);
    if spec.extra_motors.is_empty() {
        return first;
    }
    spec.extra_motors
        .iter()
        .map(|e| cluster(&e.motor, e.motor.nozzle_radius))
        .fold(first * first, |sum, r| sum + r * r)
        .sqrt()
}

/// The values of `table` just left and just right of `x` (equal where it is continuous): at a
/// repeated abscissa the first and last of its values, at the ends the extrapolation's.
fn limits(table: &Table1, x: f64) -> (f64, f64) {
    let (xs, ys) = (table.xs(), table.ys());
    let first = xs.partition_point(|&v| v < x);
    let end = xs.partition_point(|&v| v <= x);
    if first == end {
        let v = table.eval(x);
        return (v, v);
    }
    let outside = |inner: f64| match table.extrapolation() {
        Extrapolation::Zero => 0.0,
        Extrapolation::Constant | Extrapolation::Natural => inner,
    };
    let left = if first == 0 {
        outside(ys[0])
    } else {
        ys[first]
    };
    let right = if end == xs.len() {
        outside(ys[end - 1])
    } else {
        ys[end - 1]
    };
    (left, right)
}

/// The sorted union of the abscissae of `tables`, each once.
fn union<'a>(tables: impl Iterator<Item = &'a Table1>) -> Vec<f64> {
    let mut xs: Vec<f64> = tables.flat_map(|t| t.xs().iter().copied()).collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    xs
}

/// The sum of the linear `tables` on the union of their abscissae, with a step (a repeated
/// abscissa) wherever one of them steps: exact for linear tables.
fn linear_sum(tables: &[&Table1], extrapolation: Extrapolation) -> Result<Table1, MathError> {
    let xs = union(tables.iter().copied());
    let (mut out_x, mut out_y) = (Vec::with_capacity(xs.len()), Vec::with_capacity(xs.len()));
    for &x in &xs {
        let (left, right) = tables.iter().fold((0.0, 0.0), |(l, r), t| {
            let (a, b) = limits(t, x);
            (l + a, r + b)
        });
        out_x.push(x);
        out_y.push(left);
        if right - left != 0.0 {
            out_x.push(x);
            out_y.push(right);
        }
    }
    Table1::linear_stepwise(out_x, out_y, extrapolation)
}

/// The table of `f(t)` at the abscissae `xs`, linear with held ends (a report's table).
fn tabulated(xs: Vec<f64>, f: impl Fn(f64) -> f64) -> Result<Table1, MathError> {
    let ys = xs.iter().map(|&t| f(t)).collect();
    Table1::new(xs, ys, Interpolation::Linear, Extrapolation::Constant)
}

/// The motors of one rocket flown as one: see the module documentation for each quantity.
/// `motors[0]` is `[motor]`, whose coordinates the result is in; `csys` is the rocket's
/// coordinate-system sign (+1 tail to nose). One motor is returned unchanged.
///
/// # Errors
/// [`CombineError`] for a thrust curve that is not linear, a pressure-thrust correction, a
/// motor with a mass-flow table of its own, or a table that cannot be formed.
pub fn combined(motors: &[PlacedMotor], csys: f64) -> Result<MotorProperties, CombineError> {
    let Some(first) = motors.first() else {
        return Err(CombineError::NoMotor);
    };
    if motors.len() == 1 {
        return Ok(first.properties.clone());
    }
    check_combinable(motors)?;
    let s0 = csys * first.properties.coordinate_system_sign;
    let frame = |m: &PlacedMotor| frame_in(first, m, csys);

    let thrusts: Vec<&Table1> = motors.iter().map(|m| &m.properties.thrust).collect();
    let thrust = linear_sum(&thrusts, Extrapolation::Zero)?;

    let parts = parts_in_frame(motors, &frame)?;
    let i33s: Vec<&Table1> = motors
        .iter()
        .map(|m| &m.properties.propellant_i33)
        .collect();
    let propellant_i33 = tabulated(union(i33s.iter().copied()), |t| {
        i33s.iter().map(|i| i.eval(t)).sum()
    })?;
    // The summed propellant at a time, for the report tables (the flight sums the parts).
    let sum = |t: f64| {
        let mass: f64 = parts.iter().map(|p| p.mass.eval(t)).sum();
        let moment: f64 = parts.iter().map(|p| p.moment.eval(t)).sum();
        let z = if mass == 0.0 {
            parts[0].center_of_mass.eval(t)
        } else {
            moment / mass
        };
        let i11 = parts.iter().fold(0.0, |acc, p| {
            let d = p.center_of_mass.eval(t) - z;
            acc + p.i11.eval(t) + p.mass.eval(t) * d * d
        });
        (mass, z, i11)
    };
    let grid = union(
        parts
            .iter()
            .flat_map(|p| [&p.mass, &p.center_of_mass, &p.i11]),
    );
    let propellant_mass = tabulated(grid.clone(), |t| sum(t).0)?;
    let propellant_center_of_mass = tabulated(grid.clone(), |t| sum(t).1)?;
    let propellant_i11 = tabulated(grid, |t| sum(t).2)?;

    let exhaust_velocity = common_exhaust_velocity(motors, first);

    let dry = dry_lump(motors, first, &frame);

    // The aftmost nozzle exit (smallest `csys · z` in rocket coordinates), in `[motor]`'s
    // coordinates; the radius of the total exit area.
    let nozzle_position = motors
        .iter()
        .map(|m| {
            let (a, b) = frame(m);
            a + b * m.properties.nozzle_position
        })
        .fold(f64::NAN, |aft, z| {
            // In `[motor]`'s coordinates, rocket coordinates are `p_0 + s_0 z`.
            if aft.is_nan() || csys * s0 * z < csys * s0 * aft {
                z
            } else {
                aft
            }
        });
    let nozzle_radius = motors
        .iter()
        .map(|m| m.properties.nozzle_radius * m.properties.nozzle_radius)
        .sum::<f64>()
        .sqrt();

    Ok(MotorProperties {
        thrust,
        burn_start: motors
            .iter()
            .map(|m| m.properties.burn_start)
            .fold(f64::INFINITY, f64::min),
        burn_out: motors
            .iter()
            .map(|m| m.properties.burn_out)
            .fold(f64::NEG_INFINITY, f64::max),
        exhaust_velocity,
        propellant_mass,
        mass_flow: None,
        propellant_center_of_mass,
        propellant_i11,
        propellant_i33,
        propellant_parts: parts,
        dry_mass: dry.mass,
        center_of_dry_mass: dry.center,
        dry_inertia: dry.inertia,
        nozzle_position,
        nozzle_radius,
        coordinate_system_sign: first.properties.coordinate_system_sign,
        reference_pressure: None,
    })
}

/// Motor `m`'s coordinate `z` in the coordinates of `first` (`[motor]`): `a + b z`, returned as
/// `(a, b)`, with `csys` the rocket's coordinate-system sign.
fn frame_in(first: &PlacedMotor, m: &PlacedMotor, csys: f64) -> (f64, f64) {
    let s0 = csys * first.properties.coordinate_system_sign;
    let sk = csys * m.properties.coordinate_system_sign;
    (s0 * (m.position - first.position), s0 * sk)
}

/// Refuses the motors [`combined`] cannot sum exactly: a thrust curve that is not linear, a
/// pressure-thrust correction, a mass-flow table of the motor's own.
///
/// # Errors
/// The [`CombineError`] of the first such motor.
fn check_combinable(motors: &[PlacedMotor]) -> Result<(), CombineError> {
    for (index, m) in motors.iter().enumerate() {
        let p = &m.properties;
        if p.thrust.interpolation() != Interpolation::Linear {
            return Err(CombineError::NonLinearThrust { index });
        }
        if p.reference_pressure.is_some() {
            return Err(CombineError::ReferencePressure { index });
        }
        if p.mass_flow.is_some() {
            return Err(CombineError::MassFlowTable { index });
        }
    }
    Ok(())
}

/// Every motor's propellant as parts in `[motor]`'s coordinates (`frame`: each motor's
/// coordinate map, [`frame_in`]): a motor without parts is one part; a part's moment table is
/// moved node by node as its centre.
///
/// # Errors
/// A table that cannot be formed.
fn parts_in_frame(
    motors: &[PlacedMotor],
    frame: &dyn Fn(&PlacedMotor) -> (f64, f64),
) -> Result<Vec<PropellantPart>, CombineError> {
    let mut parts = Vec::new();
    for m in motors {
        let p = &m.properties;
        let (a, b) = frame(m);
        let place = |table: &Table1| -> Result<Table1, MathError> {
            let ys = table.ys().iter().map(|&z| a + b * z).collect();
            Table1::on_same_abscissae(table, ys, table.interpolation(), table.extrapolation())
        };
        if p.propellant_parts.is_empty() {
            let mass = &p.propellant_mass;
            let center = place(&p.propellant_center_of_mass)?;
            let moment = mass
                .xs()
                .iter()
                .zip(mass.ys())
                .map(|(&t, &mi)| mi * center.eval(t))
                .collect();
            let moment = Table1::on_same_abscissae(
                mass,
                moment,
                mass.interpolation(),
                mass.extrapolation(),
            )?;
            parts.push(PropellantPart {
                mass: mass.clone(),
                center_of_mass: center,
                moment,
                i11: p.propellant_i11.clone(),
            });
        } else {
            for part in &p.propellant_parts {
                // m_i (a + b z_i) node by node: the moment's table moved as its centre.
                let ys = part
                    .moment
                    .ys()
                    .iter()
                    .zip(part.mass.ys())
                    .map(|(&q, &mi)| a * mi + b * q)
                    .collect();
                let moment = Table1::on_same_abscissae(
                    &part.mass,
                    ys,
                    part.moment.interpolation(),
                    part.moment.extrapolation(),
                )?;
                parts.push(PropellantPart {
                    mass: part.mass.clone(),
                    center_of_mass: place(&part.center_of_mass)?,
                    moment,
                    i11: part.i11.clone(),
                });
            }
        }
    }
    Ok(parts)
}

/// One exhaust velocity for the motors flown as one: the total impulse over the total
/// propellant (each motor's `v_e m_0`), `first`'s when none has propellant.
fn common_exhaust_velocity(motors: &[PlacedMotor], first: &PlacedMotor) -> f64 {
    let initial = |p: &MotorProperties| {
        if p.propellant_parts.is_empty() {
            p.propellant_mass.eval(p.burn_start)
        } else {
            p.propellant_parts
                .iter()
                .map(|q| q.mass.eval(p.burn_start))
                .sum()
        }
    };
    let (mut impulse, mut propellant) = (0.0, 0.0);
    for m in motors {
        let (v, m0) = (m.properties.exhaust_velocity, initial(&m.properties));
        if v.is_finite() && m0 > 0.0 {
            impulse += v * m0;
            propellant += m0;
        }
    }
    if propellant > 0.0 {
        impulse / propellant
    } else {
        first.properties.exhaust_velocity
    }
}

/// The motors' dry masses as one part ([`RigidMass::gathered`]) at their common centre (in
/// `[motor]`'s coordinates through `frame`); `first`'s centre when the total is zero.
fn dry_lump(
    motors: &[PlacedMotor],
    first: &PlacedMotor,
    frame: &dyn Fn(&PlacedMotor) -> (f64, f64),
) -> RigidMass {
    let parts: Vec<RigidMass> = motors
        .iter()
        .map(|m| {
            let (a, b) = frame(m);
            RigidMass {
                mass: m.properties.dry_mass,
                center: a + b * m.properties.center_of_dry_mass,
                inertia: m.properties.dry_inertia,
            }
        })
        .collect();
    RigidMass::gathered(&parts, first.properties.center_of_dry_mass)
}
