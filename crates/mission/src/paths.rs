//! The inputs of a mission by dotted path (`rocket.parachutes.Main.cd_s`,
//! `flight.inclination`): listing and resolving them, setting a number, and checking that a
//! `[dispersion.vary]` distribution fits its target. `--set` and the dispersion crate share
//! these paths (mission-format.md, sections `[dispersion]` and "Overrides on the command line").
//!
//! Paths name the keys of the file (so `flight.inclination`, not the field
//! `inclination_deg`); keys the file omits but the schema defaults (e.g. a parachute's `lag`)
//! are inputs too. A numeric segment indexes an array: of tables (`motor.tanks.0.position`)
//! or of numbers (`rocket.inertia.0`, one component; `rocket.inertia`, the whole array, takes
//! `factor` / `offset` on every component). Besides stored keys, four derived knobs exist
//! ([`DerivedKnob`]).
//!
//! A lower stage's inputs are those of its `[[stages]]` entry: `stages.<index>.` before the
//! stage's keys (`stages.0.rocket.mass`, `stages.0.motor.total_impulse`, a knob of the stage's
//! motor, `stages.0.ignition_delay`); `stages.<index>.separation` is the number of the
//! separation trigger: its height above ground, or the delay of `"launch + X"` /
//! `"burnout + X"`.

use crate::schema::{
    AirBrakesCurve, Atol, Curve, DensitySpec, Discretize, Distribution, ExtraMotorSpec,
    MissionSpec, MotorSpec, RocketSpec, StageSpec, SurfaceSpec, Sweep, TankSpec, Trigger,
};
use crate::schema::{Axes, SensorSpec};
use thiserror::Error;

/// A dispersion knob that is not a stored key but scales or shifts a model
/// (mission-format.md "Distributions").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DerivedKnob {
    /// `motor.total_impulse`: rescale the thrust curve to this impulse, N·s.
    TotalImpulse,
    /// `motor.burn_time`: stretch the thrust curve to this burn time, s.
    BurnTime,
    /// `environment.wind_factor`: multiply both wind components.
    WindFactor,
    /// `environment.wind_direction_offset`: rotate the wind by this angle, deg.
    WindDirectionOffset,
}

impl DerivedKnob {
    /// Every knob.
    pub const ALL: [DerivedKnob; 4] = [
        DerivedKnob::TotalImpulse,
        DerivedKnob::BurnTime,
        DerivedKnob::WindFactor,
        DerivedKnob::WindDirectionOffset,
    ];

    /// The knob's dotted path.
    pub fn path(self) -> &'static str {
        match self {
            DerivedKnob::TotalImpulse => "motor.total_impulse",
            DerivedKnob::BurnTime => "motor.burn_time",
            DerivedKnob::WindFactor => "environment.wind_factor",
            DerivedKnob::WindDirectionOffset => "environment.wind_direction_offset",
        }
    }

    /// The knob at `path`, if it is one.
    pub fn from_path(path: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.path() == path)
    }
}

/// What a dotted path names.
#[derive(Debug, Clone, PartialEq)]
pub enum Input<'a> {
    /// A number (a constant curve is a number too).
    Number {
        /// Its nominal value.
        value: f64,
        /// The key holds an integer (a count or an index): only integral values fit.
        integer: bool,
    },
    /// A curve from a file or inline points: only `factor` / `offset` fit.
    Curve(&'a Curve),
    /// The air brakes' `[level, Mach, Cd]` table (a file or inline rows): only `factor` /
    /// `offset` fit, and act on the Cd column.
    Table(&'a AirBrakesCurve),
    /// An array of numbers (`rocket.inertia`), its nominal components: only `factor` /
    /// `offset` fit, and act on every component; one component is a number (`rocket.inertia.0`).
    Array(Vec<f64>),
    /// A derived knob.
    Knob(DerivedKnob),
}

/// Errors of dotted paths.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum PathError {
    /// The path names nothing in the mission.
    #[error("`{path}` names nothing in the mission{}", hint(available))]
    Unknown {
        /// The path.
        path: String,
        /// The keys that exist where the path fails.
        available: Vec<String>,
    },
    /// The path names a value that is not a number or a curve.
    #[error("`{path}` is {found}, not a number")]
    NotNumeric {
        /// The path.
        path: String,
        /// What it names (`a table`, `a string`, ...).
        found: &'static str,
    },
    /// An integer key was given a non-integral value.
    #[error("`{path}` holds an integer; {value} is not one")]
    NotInteger {
        /// The path.
        path: String,
        /// The value.
        value: f64,
    },
}

fn hint(available: &[String]) -> String {
    if available.is_empty() {
        String::new()
    } else {
        format!(" (keys there: {})", available.join(", "))
    }
}

/// The path of the air brakes' drag table.
pub const AIR_BRAKES_CURVE: &str = "rocket.air_brakes.drag_coefficient_curve";

/// The tank and the key within it of a motor's `tanks.<index>.<key>` key.
fn tank_key(key: &str) -> Option<(usize, &str)> {
    let rest = key.strip_prefix("tanks.")?;
    let (index, key) = rest.split_once('.')?;
    Some((index.parse().ok()?, key))
}

/// The lower stage and the path within its `[[stages]]` entry of a `stages.<index>.<path>`
/// path.
pub(crate) fn stage_path(path: &str) -> Option<(usize, &str)> {
    let rest = path.strip_prefix("stages.")?;
    let (index, key) = rest.split_once('.')?;
    Some((index.parse().ok()?, key))
}

/// The `[[extra_motors]]` entry and the path within it of an `extra_motors.<index>.<path>`
/// path.
pub(crate) fn extra_motor_path(path: &str) -> Option<(usize, &str)> {
    let rest = path.strip_prefix("extra_motors.")?;
    let (index, key) = rest.split_once('.')?;
    Some((index.parse().ok()?, key))
}

/// The curve-valued key `key` of a tank (its curves of time and a custom geometry's radius).
fn tank_curve<'a>(tank: &'a TankSpec, key: &str) -> Option<&'a Curve> {
    match key {
        "geometry.radius" => Some(&tank.geometry.radius),
        "temperature" => tank.temperature.as_ref(),
        "pressure" => tank.pressure.as_ref(),
        "liquid_mass_flow_rate_in" => tank.liquid_mass_flow_rate_in.as_ref(),
        "liquid_mass_flow_rate_out" => tank.liquid_mass_flow_rate_out.as_ref(),
        "gas_mass_flow_rate_in" => tank.gas_mass_flow_rate_in.as_ref(),
        "gas_mass_flow_rate_out" => tank.gas_mass_flow_rate_out.as_ref(),
        "ullage" => tank.ullage.as_ref(),
        "liquid_height" => tank.liquid_height.as_ref(),
        "liquid_mass" => tank.liquid_mass.as_ref(),
        "gas_mass" => tank.gas_mass.as_ref(),
        _ => None,
    }
}

/// [`tank_curve`], mutable.
fn tank_curve_mut<'a>(tank: &'a mut TankSpec, key: &str) -> Option<&'a mut Curve> {
    match key {
        "geometry.radius" => Some(&mut tank.geometry.radius),
        "temperature" => tank.temperature.as_mut(),
        "pressure" => tank.pressure.as_mut(),
        "liquid_mass_flow_rate_in" => tank.liquid_mass_flow_rate_in.as_mut(),
        "liquid_mass_flow_rate_out" => tank.liquid_mass_flow_rate_out.as_mut(),
        "gas_mass_flow_rate_in" => tank.gas_mass_flow_rate_in.as_mut(),
        "gas_mass_flow_rate_out" => tank.gas_mass_flow_rate_out.as_mut(),
        "ullage" => tank.ullage.as_mut(),
        "liquid_height" => tank.liquid_height.as_mut(),
        "liquid_mass" => tank.liquid_mass.as_mut(),
        "gas_mass" => tank.gas_mass.as_mut(),
        _ => None,
    }
}

/// Paths of the curve-valued keys (a `Constant` curve among them resolves to a number).
fn curve_at<'a>(spec: &'a MissionSpec, path: &str) -> Option<&'a Curve> {
    if let Some((index, rest)) = extra_motor_path(path) {
        let extra = spec.extra_motors.get(index)?;
        return motor_curve(&extra.motor, rest.strip_prefix("motor.")?);
    }
    if let Some((index, rest)) = stage_path(path) {
        let stage = spec.stages.get(index)?;
        return match rest {
            "stack_power_off_drag" => Some(&stage.stack_power_off_drag),
            "stack_power_on_drag" => Some(&stage.stack_power_on_drag),
            _ => part_curve(&stage.rocket, stage.motor.as_ref(), rest),
        };
    }
    let atm = &spec.environment.atmosphere;
    match path {
        "environment.atmosphere.pressure" => atm.pressure.as_ref(),
        "environment.atmosphere.temperature" => atm.temperature.as_ref(),
        "environment.atmosphere.wind_u" => atm.wind_u.as_ref(),
        "environment.atmosphere.wind_v" => atm.wind_v.as_ref(),
        _ => part_curve(&spec.rocket, Some(&spec.motor), path),
    }
}

/// The curve at `rocket.<key>` or `motor.<key>` of a stage's airframe and motor.
fn part_curve<'a>(
    rocket: &'a RocketSpec,
    motor: Option<&'a MotorSpec>,
    path: &str,
) -> Option<&'a Curve> {
    if let Some(key) = path.strip_prefix("motor.") {
        return motor_curve(motor?, key);
    }
    match path {
        "rocket.power_off_drag" => Some(&rocket.power_off_drag),
        "rocket.power_on_drag" => Some(&rocket.power_on_drag),
        _ => None,
    }
}

/// The curve at `key` of a motor (its thrust, its tanks' curves).
fn motor_curve<'a>(motor: &'a MotorSpec, key: &str) -> Option<&'a Curve> {
    if let Some((index, key)) = tank_key(key) {
        return tank_curve(motor.tanks.get(index)?, key);
    }
    (key == "thrust").then_some(&motor.thrust)
}

/// [`motor_curve`], mutable.
fn motor_curve_mut<'a>(motor: &'a mut MotorSpec, key: &str) -> Option<&'a mut Curve> {
    if let Some((index, key)) = tank_key(key) {
        return tank_curve_mut(motor.tanks.get_mut(index)?, key);
    }
    (key == "thrust").then_some(&mut motor.thrust)
}

/// [`curve_at`], mutable.
pub(crate) fn curve_mut<'a>(spec: &'a mut MissionSpec, path: &str) -> Option<&'a mut Curve> {
    if let Some((index, rest)) = extra_motor_path(path) {
        let extra = spec.extra_motors.get_mut(index)?;
        return motor_curve_mut(&mut extra.motor, rest.strip_prefix("motor.")?);
    }
    if let Some((index, rest)) = stage_path(path) {
        let stage = spec.stages.get_mut(index)?;
        return match rest {
            "stack_power_off_drag" => Some(&mut stage.stack_power_off_drag),
            "stack_power_on_drag" => Some(&mut stage.stack_power_on_drag),
            _ => part_curve_mut(&mut stage.rocket, stage.motor.as_mut(), rest),
        };
    }
    let atm = &mut spec.environment.atmosphere;
    match path {
        "environment.atmosphere.pressure" => atm.pressure.as_mut(),
        "environment.atmosphere.temperature" => atm.temperature.as_mut(),
        "environment.atmosphere.wind_u" => atm.wind_u.as_mut(),
        "environment.atmosphere.wind_v" => atm.wind_v.as_mut(),
        _ => part_curve_mut(&mut spec.rocket, Some(&mut spec.motor), path),
    }
}

/// [`part_curve`], mutable.
fn part_curve_mut<'a>(
    rocket: &'a mut RocketSpec,
    motor: Option<&'a mut MotorSpec>,
    path: &str,
) -> Option<&'a mut Curve> {
    if let Some(key) = path.strip_prefix("motor.") {
        return motor_curve_mut(motor?, key);
    }
    match path {
        "rocket.power_off_drag" => Some(&mut rocket.power_off_drag),
        "rocket.power_on_drag" => Some(&mut rocket.power_on_drag),
        _ => None,
    }
}

/// The mission as a TOML table, every defaulted key filled in.
fn as_table(spec: &MissionSpec) -> toml::Table {
    // Serializing plain data into a TOML table cannot fail: every map key is a string
    // and every value is a number, string, datetime, array or table.
    toml::Table::try_from(spec).unwrap_or_default()
}

fn type_name(value: &toml::Value) -> &'static str {
    match value {
        toml::Value::String(_) => "a string",
        toml::Value::Integer(_) => "an integer",
        toml::Value::Float(_) => "a number",
        toml::Value::Boolean(_) => "a boolean",
        toml::Value::Datetime(_) => "a date",
        toml::Value::Array(_) => "an array",
        toml::Value::Table(_) => "a table",
    }
}

/// The value at `path` of `table`, or the error naming where the walk failed. A numeric
/// segment indexes an array: of tables (`motor.tanks.0.position`) or of numbers
/// (`rocket.inertia.0`); arrays of arrays (inline curve points) are not entered.
fn walk<'t>(table: &'t mut toml::Table, path: &str) -> Result<&'t mut toml::Value, PathError> {
    let unknown = |available: Vec<String>| PathError::Unknown {
        path: path.to_owned(),
        available,
    };
    let mut segments = path.split('.');
    let first = segments.next().unwrap_or_default();
    if first == "dispersion" {
        return Err(unknown(Vec::new()));
    }
    let available: Vec<String> = table.keys().cloned().collect();
    let mut here = table.get_mut(first).ok_or_else(|| unknown(available))?;
    for segment in segments {
        here = match here {
            toml::Value::Table(inner) => {
                let available: Vec<String> = inner.keys().cloned().collect();
                inner.get_mut(segment).ok_or_else(|| unknown(available))?
            }
            toml::Value::Array(items) => {
                let count = items.len();
                match segment.parse::<usize>().ok().and_then(|i| items.get_mut(i)) {
                    Some(
                        item @ (toml::Value::Table(_)
                        | toml::Value::Float(_)
                        | toml::Value::Integer(_)),
                    ) => item,
                    _ => return Err(unknown((0..count).map(|i| i.to_string()).collect())),
                }
            }
            _ => return Err(unknown(Vec::new())),
        };
    }
    Ok(here)
}

/// The components of an array of numbers (`None` for anything else, an empty array too).
fn numbers(value: &toml::Value) -> Option<Vec<f64>> {
    let toml::Value::Array(items) = value else {
        return None;
    };
    let values: Option<Vec<f64>> = items
        .iter()
        .map(|item| match item {
            toml::Value::Float(v) => Some(*v),
            toml::Value::Integer(v) => Some(*v as f64),
            _ => None,
        })
        .collect();
    values.filter(|v| !v.is_empty())
}

/// What `path` names in `spec`.
pub fn resolve<'a>(spec: &'a MissionSpec, path: &str) -> Result<Input<'a>, PathError> {
    if let Some(knob) = DerivedKnob::from_path(path) {
        return Ok(Input::Knob(knob));
    }
    // A lower stage's motor has the motor knobs; its separation trigger is a number.
    if let Some((index, rest)) = stage_path(path)
        && let Some(stage) = spec.stages.get(index)
    {
        if let Some(knob @ (DerivedKnob::TotalImpulse | DerivedKnob::BurnTime)) =
            DerivedKnob::from_path(rest)
            && stage.motor.is_some()
        {
            return Ok(Input::Knob(knob));
        }
        if rest == "separation"
            && let Some(value) = separation_number(&stage.separation)
        {
            return Ok(Input::Number {
                value,
                integer: false,
            });
        }
    }
    if path == AIR_BRAKES_CURVE
        && let Some(ab) = &spec.rocket.air_brakes
        && !matches!(ab.drag_coefficient_curve, AirBrakesCurve::Constant(_))
    {
        return Ok(Input::Table(&ab.drag_coefficient_curve));
    }
    if let Some(curve) = curve_at(spec, path) {
        return Ok(match curve {
            Curve::Constant(value) => Input::Number {
                value: *value,
                integer: false,
            },
            Curve::Points(_) | Curve::File(_) => Input::Curve(curve),
        });
    }
    // A tank's flux time is addressed as a number: its end.
    let tank = match (stage_path(path), extra_motor_path(path)) {
        (Some((index, rest)), _) => spec
            .stages
            .get(index)
            .and_then(|s| Some((s.motor.as_ref()?, rest.strip_prefix("motor.")?))),
        (None, Some((index, rest))) => spec
            .extra_motors
            .get(index)
            .and_then(|e| Some((&e.motor, rest.strip_prefix("motor.")?))),
        (None, None) => path.strip_prefix("motor.").map(|rest| (&spec.motor, rest)),
    };
    if let Some((motor, rest)) = tank
        && let Some((index, "flux_time")) = tank_key(rest)
        && let Some(tank) = motor.tanks.get(index)
    {
        return Ok(Input::Number {
            value: tank.flux_time.end,
            integer: false,
        });
    }
    let mut table = as_table(spec);
    match walk(&mut table, path)? {
        toml::Value::Float(value) => Ok(Input::Number {
            value: *value,
            integer: false,
        }),
        toml::Value::Integer(value) => Ok(Input::Number {
            value: *value as f64,
            integer: true,
        }),
        other => numbers(other)
            .map(Input::Array)
            .ok_or_else(|| PathError::NotNumeric {
                path: path.to_owned(),
                found: type_name(other),
            }),
    }
}

/// The number of a separation trigger: its height, or the delay after launch or burn-out.
fn separation_number(trigger: &Trigger) -> Option<f64> {
    match trigger {
        Trigger::HeightAboveGround(value) | Trigger::Launch(value) | Trigger::Burnout(value) => {
            Some(*value)
        }
        Trigger::Apogee | Trigger::Expression(_) => None,
    }
}

/// Every numeric input of `spec` by dotted path with its nominal value, in file order
/// (defaulted keys included; the components of an array of numbers by their index,
/// `rocket.inertia.0`).
pub fn numeric_inputs(spec: &MissionSpec) -> Vec<(String, f64)> {
    fn collect(table: &toml::Table, prefix: &str, out: &mut Vec<(String, f64)>) {
        for (key, value) in table {
            let path = if prefix.is_empty() {
                key.clone()
            } else {
                format!("{prefix}.{key}")
            };
            match value {
                toml::Value::Float(v) => out.push((path, *v)),
                toml::Value::Integer(v) => out.push((path, *v as f64)),
                toml::Value::Table(inner) if path != "dispersion" => collect(inner, &path, out),
                toml::Value::Array(items) => {
                    for (index, item) in items.iter().enumerate() {
                        let path = format!("{path}.{index}");
                        match item {
                            toml::Value::Table(inner) => collect(inner, &path, out),
                            toml::Value::Float(v) => out.push((path, *v)),
                            toml::Value::Integer(v) => out.push((path, *v as f64)),
                            _ => {}
                        }
                    }
                }
                _ => {}
            }
        }
    }
    let mut out = Vec::new();
    collect(&as_table(spec), "", &mut out);
    out
}

/// A numeric slot of the typed mission, by the dotted path of its key.
enum Slot<'a> {
    Float(&'a mut f64),
    Integer(&'a mut u32),
}

/// The stored number at `path` in the typed mission: the same keys the file form has (an
/// optional key only when present, a curve or a trigger only when it is a number), reached
/// without a round trip through TOML, so a Monte Carlo sample sets its inputs in nanoseconds.
/// The integration test `typed_slots_match_the_file_form` checks it against the TOML form of
/// every fixture and validation mission.
fn slot<'a>(spec: &'a mut MissionSpec, path: &str) -> Option<Slot<'a>> {
    use Slot::{Float, Integer};
    if let Some((index, rest)) = stage_path(path) {
        return stage_slot(spec.stages.get_mut(index)?, rest);
    }
    if let Some((index, rest)) = extra_motor_path(path) {
        return extra_motor_slot(spec.extra_motors.get_mut(index)?, rest);
    }
    if let Some((array, index)) = path.rsplit_once('.')
        && let Ok(index) = index.parse::<usize>()
    {
        if array == "flight.atol" {
            return match spec.flight.atol.as_mut()? {
                Atol::PerState(values) => values.get_mut(index).map(Float),
                Atol::Scalar(_) => None,
            };
        }
        return part_component(&mut spec.rocket, Some(&mut spec.motor), array, index).map(Float);
    }
    let (section, rest) = path.split_once('.')?;
    match section {
        "environment" => {
            let env = &mut spec.environment;
            Some(match rest {
                "latitude" => Float(&mut env.latitude_deg),
                "longitude" => Float(&mut env.longitude_deg),
                "elevation" => Float(&mut env.elevation),
                "gravity" => Float(env.gravity.as_mut()?),
                "max_expected_height" => Float(env.max_expected_height.as_mut()?),
                "earth_model.latitude" => Float(env.earth_model.as_mut()?.latitude_deg.as_mut()?),
                "earth_model.gravity_max_height" => {
                    Float(env.earth_model.as_mut()?.gravity_max_height.as_mut()?)
                }
                "atmosphere.member" => Integer(env.atmosphere.member.as_mut()?),
                "atmosphere.pressure" => constant(env.atmosphere.pressure.as_mut()?)?,
                "atmosphere.temperature" => constant(env.atmosphere.temperature.as_mut()?)?,
                "atmosphere.wind_u" => constant(env.atmosphere.wind_u.as_mut()?)?,
                "atmosphere.wind_v" => constant(env.atmosphere.wind_v.as_mut()?)?,
                _ => return None,
            })
        }
        "motor" => motor_slot(&mut spec.motor, rest),
        "rocket" => rocket_slot(&mut spec.rocket, rest),
        "flight" => {
            let f = &mut spec.flight;
            Some(Float(match rest {
                "rail_length" => &mut f.rail_length,
                "inclination" => &mut f.inclination_deg,
                "heading" => &mut f.heading_deg,
                "max_time" => &mut f.max_time,
                "rtol" => &mut f.rtol,
                "max_time_step" => &mut f.max_time_step,
                "weathercock_coeff" => f.weathercock_coeff.as_mut()?,
                "atol" => match f.atol.as_mut()? {
                    Atol::Scalar(value) => value,
                    Atol::PerState(_) => return None,
                },
                _ => return None,
            }))
        }
        _ => None,
    }
}

/// The numeric slot at `path` within a `[[stages]]` entry: its own keys, or its airframe's
/// and motor's as in `[rocket]` and `[motor]`.
fn stage_slot<'a>(stage: &'a mut StageSpec, path: &str) -> Option<Slot<'a>> {
    use Slot::Float;
    if let Some((array, index)) = path.rsplit_once('.')
        && let Ok(index) = index.parse::<usize>()
    {
        return part_component(&mut stage.rocket, stage.motor.as_mut(), array, index).map(Float);
    }
    match path {
        "sampling_rate" => Some(Float(&mut stage.sampling_rate)),
        "ignition_delay" => Some(Float(&mut stage.ignition_delay)),
        "separation" => match &mut stage.separation {
            Trigger::HeightAboveGround(value)
            | Trigger::Launch(value)
            | Trigger::Burnout(value) => Some(Float(value)),
            Trigger::Apogee | Trigger::Expression(_) => None,
        },
        "stack_power_off_drag" => constant(&mut stage.stack_power_off_drag),
        "stack_power_on_drag" => constant(&mut stage.stack_power_on_drag),
        _ => {
            if let Some(rest) = path.strip_prefix("rocket.") {
                rocket_slot(&mut stage.rocket, rest)
            } else {
                motor_slot(stage.motor.as_mut()?, path.strip_prefix("motor.")?)
            }
        }
    }
}

/// The numeric slot at `path` within an `[[extra_motors]]` entry: its own keys, or its
/// motor's as in `[motor]`.
fn extra_motor_slot<'a>(extra: &'a mut ExtraMotorSpec, path: &str) -> Option<Slot<'a>> {
    use Slot::Float;
    match path {
        "motor_position" => Some(Float(&mut extra.motor_position)),
        "ignition_delay" => Some(Float(&mut extra.ignition_delay)),
        _ => {
            let key = path.strip_prefix("motor.")?;
            if let Some((array, index)) = key.rsplit_once('.')
                && let Ok(index) = index.parse::<usize>()
            {
                return motor_component(&mut extra.motor, array, index).map(Float);
            }
            motor_slot(&mut extra.motor, key)
        }
    }
}

/// The numeric slot `key` of a motor.
fn motor_slot<'a>(m: &'a mut MotorSpec, key: &str) -> Option<Slot<'a>> {
    use Slot::{Float, Integer};
    if let Some((index, key)) = tank_key(key) {
        return tank_slot(m.tanks.get_mut(index)?, key);
    }
    Some(match key {
        "thrust" => constant(&mut m.thrust)?,
        "dry_mass" => Float(&mut m.dry_mass),
        "nozzle_position" => Float(&mut m.nozzle_position),
        "nozzle_radius" => Float(&mut m.nozzle_radius),
        "grain_number" => Integer(m.grain_number.as_mut()?),
        "cluster_count" => Integer(m.cluster_count.as_mut()?),
        other => Float(
            match other {
                "center_of_dry_mass_position" => &mut m.center_of_dry_mass_position,
                "throat_radius" => &mut m.throat_radius,
                "reference_pressure" => &mut m.reference_pressure,
                "grain_separation" => &mut m.grain_separation,
                "grain_density" => &mut m.grain_density,
                "grain_outer_radius" => &mut m.grain_outer_radius,
                "grain_initial_inner_radius" => &mut m.grain_initial_inner_radius,
                "grain_initial_height" => &mut m.grain_initial_height,
                "grains_center_of_mass_position" => &mut m.grains_center_of_mass_position,
                "propellant_initial_mass" => &mut m.propellant_initial_mass,
                "chamber_radius" => &mut m.chamber_radius,
                "chamber_height" => &mut m.chamber_height,
                "chamber_position" => &mut m.chamber_position,
                "cluster_radius" => &mut m.cluster_radius,
                _ => return None,
            }
            .as_mut()?,
        ),
    })
}

/// Component `index` of the array `key` of a motor (its dry inertia, burn interval, reshape
/// pair, a tank's flux time).
fn motor_component<'a>(motor: &'a mut MotorSpec, key: &str, index: usize) -> Option<&'a mut f64> {
    let pair = |[start, end]: [&'a mut f64; 2]| match index {
        0 => Some(start),
        1 => Some(end),
        _ => None,
    };
    if let Some((tank, "flux_time")) = tank_key(key) {
        let t = &mut motor.tanks.get_mut(tank)?.flux_time;
        return pair([&mut t.start, &mut t.end]);
    }
    match key {
        "dry_inertia" => motor.dry_inertia.0.get_mut(index),
        "burn_time" => {
            let b = motor.burn_time.as_mut()?;
            pair([&mut b.start, &mut b.end])
        }
        "reshape_thrust_curve" => motor.reshape_thrust_curve.as_mut()?.get_mut(index),
        _ => None,
    }
}

/// Component `index` of the array of numbers at `rocket.<key>` or `motor.<key>` (its file
/// form: an inertia always has six components, a burn time two).
fn part_component<'a>(
    rocket: &'a mut RocketSpec,
    motor: Option<&'a mut MotorSpec>,
    array: &str,
    index: usize,
) -> Option<&'a mut f64> {
    if let Some(key) = array.strip_prefix("motor.") {
        return motor_component(motor?, key, index);
    }
    if let Some(rest) = array.strip_prefix("rocket.sensors.") {
        let (i, key) = rest.split_once('.')?;
        let sensor = rocket.sensors.get_mut(i.parse::<usize>().ok()?)?;
        return sensor_component(sensor, key, index);
    }
    if let Some(name) = array
        .strip_prefix("rocket.parachutes.")
        .and_then(|rest| rest.strip_suffix(".noise"))
    {
        return rocket.parachutes.get_mut(name)?.noise.get_mut(index);
    }
    match array {
        "rocket.inertia" => rocket.inertia.0.get_mut(index),
        "rocket.cm_eccentricity" => rocket.cm_eccentricity.as_mut()?.get_mut(index),
        "rocket.cp_eccentricity" => rocket.cp_eccentricity.as_mut()?.get_mut(index),
        "rocket.thrust_eccentricity" => rocket.thrust_eccentricity.as_mut()?.get_mut(index),
        "rocket.air_brakes.initial_observed_variables" => rocket
            .air_brakes
            .as_mut()?
            .initial_observed_variables
            .as_mut()?
            .get_mut(index),
        _ => None,
    }
}

/// The per-axis noise parameter `key` of a sensor (`noise_density`, …), when the file sets it.
fn sensor_axes<'a>(sensor: &'a mut SensorSpec, key: &str) -> Option<&'a mut Axes> {
    match key {
        "noise_density" => sensor.noise_density.as_mut(),
        "noise_variance" => sensor.noise_variance.as_mut(),
        "random_walk_density" => sensor.random_walk_density.as_mut(),
        "random_walk_variance" => sensor.random_walk_variance.as_mut(),
        "constant_bias" => sensor.constant_bias.as_mut(),
        "temperature_bias" => sensor.temperature_bias.as_mut(),
        "temperature_scale_factor" => sensor.temperature_scale_factor.as_mut(),
        "acceleration_sensitivity" => sensor.acceleration_sensitivity.as_mut(),
        _ => None,
    }
}

/// Component `index` of the array `key` of a `[[rocket.sensors]]` entry (its file form:
/// a position always has three components, a measurement range two, a per-axis parameter
/// three when the file gives three).
fn sensor_component<'a>(
    sensor: &'a mut SensorSpec,
    key: &str,
    index: usize,
) -> Option<&'a mut f64> {
    match key {
        "position" => sensor.position.0.get_mut(index),
        "orientation" => sensor.orientation.as_mut()?.get_mut(index),
        "measurement_range" => sensor.measurement_range.as_mut()?.0.get_mut(index),
        _ => match sensor_axes(sensor, key)? {
            Axes::PerAxis(values) => values.get_mut(index),
            Axes::All(_) => None,
        },
    }
}

/// The numeric slot `key` of a `[[rocket.sensors]]` entry: its rate, its scalar noise
/// parameters, and a per-axis parameter the file gives as one number.
fn sensor_slot<'a>(sensor: &'a mut SensorSpec, key: &str) -> Option<&'a mut f64> {
    match key {
        "sampling_rate" => Some(&mut sensor.sampling_rate),
        "resolution" => sensor.resolution.as_mut(),
        "operating_temperature" => sensor.operating_temperature.as_mut(),
        "cross_axis_sensitivity" => sensor.cross_axis_sensitivity.as_mut(),
        "position_accuracy" => sensor.position_accuracy.as_mut(),
        "altitude_accuracy" => sensor.altitude_accuracy.as_mut(),
        _ => match sensor_axes(sensor, key)? {
            Axes::All(value) => Some(value),
            Axes::PerAxis(_) => None,
        },
    }
}

/// The numeric slot `key` of one tank.
fn tank_slot<'a>(tank: &'a mut TankSpec, key: &str) -> Option<Slot<'a>> {
    use Slot::{Float, Integer};
    if tank_curve(tank, key).is_some() {
        return constant(tank_curve_mut(tank, key)?);
    }
    let density = |d: &'a mut DensitySpec| match d {
        DensitySpec::Constant(rho) => Some(Float(rho)),
        DensitySpec::Rows(_) | DensitySpec::File(_) => None,
    };
    match key {
        "position" => Some(Float(&mut tank.position)),
        "flux_time" => Some(Float(&mut tank.flux_time.end)),
        "geometry.height" => Some(Float(tank.geometry.height.as_mut()?)),
        "liquid.density" => density(&mut tank.liquid.density),
        "gas.density" => density(&mut tank.gas.density),
        "initial_liquid_mass" => Some(Float(tank.initial_liquid_mass.as_mut()?)),
        "initial_gas_mass" => Some(Float(tank.initial_gas_mass.as_mut()?)),
        "discretize" => match tank.discretize.as_mut()? {
            Discretize::Nodes(n) => Some(Integer(n)),
            Discretize::Flag(_) => None,
        },
        _ => None,
    }
}

/// A curve's slot when it is a constant.
fn constant(curve: &mut Curve) -> Option<Slot<'_>> {
    match curve {
        Curve::Constant(value) => Some(Slot::Float(value)),
        Curve::Points(_) | Curve::File(_) => None,
    }
}

fn rocket_slot<'a>(rocket: &'a mut RocketSpec, path: &str) -> Option<Slot<'a>> {
    use Slot::Float;
    if let Some(rest) = path.strip_prefix("rail_buttons.") {
        let b = rocket.rail_buttons.as_mut()?;
        return Some(Float(match rest {
            "upper_position" => &mut b.upper_position,
            "lower_position" => &mut b.lower_position,
            "angular_position" => &mut b.angular_position_deg,
            _ => return None,
        }));
    }
    if let Some(rest) = path.strip_prefix("air_brakes.") {
        let ab = rocket.air_brakes.as_mut()?;
        if let Some(name) = rest.strip_prefix("constants.") {
            return ab.constants.get_mut(name).map(Float);
        }
        return Some(Float(match rest {
            "sampling_rate" => &mut ab.sampling_rate,
            "deployment_level" => &mut ab.deployment_level,
            "reference_area" => ab.reference_area.as_mut()?,
            "drag_coefficient_curve" => match &mut ab.drag_coefficient_curve {
                AirBrakesCurve::Constant(value) => value,
                AirBrakesCurve::Rows(_) | AirBrakesCurve::File(_) => return None,
            },
            _ => return None,
        }));
    }
    if let Some(rest) = path.strip_prefix("sensors.") {
        let (index, key) = rest.split_once('.')?;
        let sensor = rocket.sensors.get_mut(index.parse::<usize>().ok()?)?;
        return sensor_slot(sensor, key).map(Float);
    }
    if let Some(rest) = path.strip_prefix("surfaces.") {
        let (name, key) = rest.rsplit_once('.')?;
        return surface_slot(rocket.surfaces.get_mut(name)?, key);
    }
    if let Some(rest) = path.strip_prefix("parachutes.") {
        let (name, key) = rest.rsplit_once('.')?;
        let p = rocket.parachutes.get_mut(name)?;
        return Some(Float(match key {
            "cd_s" => &mut p.cd_s,
            "sampling_rate" => &mut p.sampling_rate,
            "lag" => &mut p.lag,
            "trigger" => match &mut p.trigger {
                Trigger::HeightAboveGround(height) => height,
                Trigger::Apogee
                | Trigger::Launch(_)
                | Trigger::Burnout(_)
                | Trigger::Expression(_) => return None,
            },
            "radius" => p.radius.as_mut()?,
            "height" => p.height.as_mut()?,
            "porosity" => p.porosity.as_mut()?,
            _ => return None,
        }));
    }
    Some(match path {
        "radius" => Float(&mut rocket.radius),
        "mass" => Float(&mut rocket.mass),
        "center_of_mass_without_motor" => Float(&mut rocket.center_of_mass_without_motor),
        "motor_position" => Float(&mut rocket.motor_position),
        "power_off_drag" => constant(&mut rocket.power_off_drag)?,
        "power_on_drag" => constant(&mut rocket.power_on_drag)?,
        _ => return None,
    })
}

fn surface_slot<'a>(surface: &'a mut SurfaceSpec, key: &str) -> Option<Slot<'a>> {
    use Slot::{Float, Integer};
    Some(match surface {
        SurfaceSpec::Nose(s) => Float(match key {
            "length" => &mut s.length,
            "position" => &mut s.position,
            "bluffness" => s.bluffness.as_mut()?,
            "power" => s.power.as_mut()?,
            "base_radius" => s.base_radius.as_mut()?,
            _ => return None,
        }),
        SurfaceSpec::TrapezoidalFins(s) => match key {
            "n" => Integer(&mut s.n),
            "span" => Float(&mut s.span),
            "root_chord" => Float(&mut s.root_chord),
            "tip_chord" => Float(&mut s.tip_chord),
            "position" => Float(&mut s.position),
            "cant_angle" => Float(&mut s.cant_angle_deg),
            "angular_position" => Float(&mut s.angular_position_deg),
            "radius" => Float(s.radius.as_mut()?),
            "sweep_angle" => match s.sweep.as_mut()? {
                Sweep::AngleDeg(angle) => Float(angle),
                Sweep::Length(_) => return None,
            },
            "sweep_length" => match s.sweep.as_mut()? {
                Sweep::Length(length) => Float(length),
                Sweep::AngleDeg(_) => return None,
            },
            _ => return None,
        },
        SurfaceSpec::EllipticalFins(s) => match key {
            "n" => Integer(&mut s.n),
            "span" => Float(&mut s.span),
            "root_chord" => Float(&mut s.root_chord),
            "position" => Float(&mut s.position),
            "cant_angle" => Float(&mut s.cant_angle_deg),
            "angular_position" => Float(&mut s.angular_position_deg),
            "radius" => Float(s.radius.as_mut()?),
            _ => return None,
        },
        SurfaceSpec::FreeFormFins(s) => match key {
            "n" => Integer(&mut s.n),
            "position" => Float(&mut s.position),
            "cant_angle" => Float(&mut s.cant_angle_deg),
            "angular_position" => Float(&mut s.angular_position_deg),
            "radius" => Float(s.radius.as_mut()?),
            _ => return None,
        },
        SurfaceSpec::Tail(s) => Float(match key {
            "top_radius" => &mut s.top_radius,
            "bottom_radius" => &mut s.bottom_radius,
            "length" => &mut s.length,
            "position" => &mut s.position,
            _ => return None,
        }),
        SurfaceSpec::TubeFins(s) => match key {
            "n" => Integer(&mut s.n),
            "length" => Float(&mut s.length),
            "outer_radius" => Float(&mut s.outer_radius),
            "inner_radius" => Float(&mut s.inner_radius),
            "position" => Float(&mut s.position),
            "radius" => Float(s.radius.as_mut()?),
            _ => return None,
        },
    })
}

/// Sets the number at `path` (an integer key needs an integral value that fits).
///
/// # Errors
/// [`PathError::Unknown`] / [`PathError::NotNumeric`] (from [`resolve`]) when `path` names no
/// stored number, [`PathError::NotInteger`] for a non-integral value of an integer key.
pub fn set_number(spec: &mut MissionSpec, path: &str, value: f64) -> Result<(), PathError> {
    match slot(spec, path) {
        Some(Slot::Float(x)) => *x = value,
        Some(Slot::Integer(n)) => {
            let integral = value.is_finite() && value.fract().abs() <= 0.0;
            if !integral || value < 0.0 || value > f64::from(u32::MAX) {
                return Err(PathError::NotInteger {
                    path: path.to_owned(),
                    value,
                });
            }
            *n = value as u32;
        }
        None => {
            // Not a stored number: say what the path names instead.
            let found = match resolve(spec, path)? {
                Input::Curve(_) | Input::Table(_) => "a curve",
                Input::Array(_) => "an array",
                Input::Knob(_) => "a derived knob",
                Input::Number { .. } => "a number without a typed slot",
            };
            return Err(PathError::NotNumeric {
                path: path.to_owned(),
                found,
            });
        }
    }
    Ok(())
}

/// Checks that `distribution` is well formed and fits `input`; the error says why not.
pub fn check_distribution(input: &Input<'_>, distribution: &Distribution) -> Result<(), String> {
    match (input, distribution) {
        (_, Distribution::Factor(inner) | Distribution::Offset(inner)) => {
            if matches!(**inner, Distribution::Factor(_) | Distribution::Offset(_)) {
                return Err(
                    "`factor` and `offset` take a plain distribution, not another \
                            `factor` or `offset`"
                        .to_owned(),
                );
            }
            if matches!(input, Input::Number { integer: true, .. }) {
                return Err("an integer input only takes `choice`".to_owned());
            }
            well_formed(inner)
        }
        (Input::Curve(_) | Input::Table(_), _) => {
            Err("a curve only takes `factor = ...` or `offset = ...`".to_owned())
        }
        (Input::Array(_), _) => Err("an array only takes `factor = ...` or `offset = ...` (on \
             every component); vary one component by its index, `PATH.0`"
            .to_owned()),
        (Input::Number { integer: true, .. }, Distribution::Choice(values)) => {
            if values.iter().any(|v| v.fract().abs() > 0.0) {
                return Err("an integer input takes integral choices".to_owned());
            }
            well_formed(distribution)
        }
        (Input::Number { integer: true, .. }, _) if crate::distributions::is_integral(distribution) => {
            well_formed(distribution)
        }
        (Input::Number { integer: true, .. }, _) => {
            Err("an integer input only takes `choice`, `poisson` or `binomial` (or a truncation of one)".to_owned())
        }
        _ => well_formed(distribution),
    }
}

fn well_formed(distribution: &Distribution) -> Result<(), String> {
    let ok = match distribution {
        Distribution::Std(std) => *std >= 0.0,
        Distribution::Normal([_, std]) => *std >= 0.0,
        Distribution::Uniform([low, high]) => low <= high,
        Distribution::Triangular([low, mode, high]) => low <= mode && mode <= high && low < high,
        Distribution::Lognormal([_, sigma]) => *sigma >= 0.0,
        Distribution::Choice(values) => !values.is_empty(),
        Distribution::Factor(inner) | Distribution::Offset(inner) => {
            return well_formed(inner);
        }
        // The named and truncated distributions: their parameters by NumPy's names, checked
        // as the dispersion crate checks them (the message names each value).
        _ => return crate::distributions::problem(distribution).map_or(Ok(()), Err),
    };
    if ok {
        Ok(())
    } else {
        Err(match distribution {
            Distribution::Std(_) | Distribution::Normal(_) => "a standard deviation must be >= 0",
            Distribution::Uniform(_) => "uniform needs [low, high] with low <= high",
            Distribution::Triangular(_) => {
                "triangular needs [low, mode, high] with low <= mode <= high and low < high"
            }
            Distribution::Lognormal(_) => "lognormal needs [mu, sigma] with sigma >= 0",
            _ => "choice needs at least one value",
        }
        .to_owned())
    }
}
