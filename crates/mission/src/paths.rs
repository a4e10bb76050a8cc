//! The inputs of a mission by dotted path (`rocket.parachutes.Main.cd_s`,
//! `flight.inclination`): listing and resolving them, setting a number, and checking that a
//! `[dispersion.vary]` distribution fits its target. `--set` and the dispersion crate share
//! these paths (mission-format.md, sections `[dispersion]` and "Overrides on the command line").
//!
//! Paths name the keys of the file (so `flight.inclination`, not the field
//! `inclination_deg`); keys the file omits but the schema defaults (e.g. a parachute's `lag`)
//! are inputs too. Besides stored keys, four derived knobs exist ([`DerivedKnob`]).

use crate::schema::{Curve, Distribution, MissionSpec};
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
    /// The mission with the new values does not deserialize (the schema's message).
    #[error("the changed mission is rejected: {message}")]
    Rejected {
        /// Why.
        message: String,
    },
}

fn hint(available: &[String]) -> String {
    if available.is_empty() {
        String::new()
    } else {
        format!(" (keys there: {})", available.join(", "))
    }
}

/// Paths of the curve-valued keys (a `Constant` curve among them resolves to a number).
fn curve_at<'a>(spec: &'a MissionSpec, path: &str) -> Option<&'a Curve> {
    let atm = &spec.environment.atmosphere;
    match path {
        "motor.thrust" => Some(&spec.motor.thrust),
        "rocket.power_off_drag" => Some(&spec.rocket.power_off_drag),
        "rocket.power_on_drag" => Some(&spec.rocket.power_on_drag),
        "environment.atmosphere.pressure" => atm.pressure.as_ref(),
        "environment.atmosphere.temperature" => atm.temperature.as_ref(),
        "environment.atmosphere.wind_u" => atm.wind_u.as_ref(),
        "environment.atmosphere.wind_v" => atm.wind_v.as_ref(),
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

/// The value at `path` of `table`, or the error naming where the walk failed.
fn walk<'t>(table: &'t mut toml::Table, path: &str) -> Result<&'t mut toml::Value, PathError> {
    let unknown = |available: Vec<String>| PathError::Unknown {
        path: path.to_owned(),
        available,
    };
    let segments: Vec<&str> = path.split('.').collect();
    let Some((last, tables)) = segments.split_last() else {
        return Err(unknown(Vec::new()));
    };
    if segments.first() == Some(&"dispersion") {
        return Err(unknown(Vec::new()));
    }
    let mut here = table;
    for segment in tables {
        let available: Vec<String> = here.keys().cloned().collect();
        match here.get_mut(*segment) {
            Some(toml::Value::Table(inner)) => here = inner,
            _ => return Err(unknown(available)),
        }
    }
    let available: Vec<String> = here.keys().cloned().collect();
    here.get_mut(*last).ok_or_else(|| unknown(available))
}

/// What `path` names in `spec`.
pub fn resolve<'a>(spec: &'a MissionSpec, path: &str) -> Result<Input<'a>, PathError> {
    if let Some(knob) = DerivedKnob::from_path(path) {
        return Ok(Input::Knob(knob));
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
        other => Err(PathError::NotNumeric {
            path: path.to_owned(),
            found: type_name(other),
        }),
    }
}

/// Every numeric input of `spec` by dotted path with its nominal value, in file order
/// (defaulted keys included; array elements, e.g. `rocket.inertia`, are not scalar inputs).
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
                _ => {}
            }
        }
    }
    let mut out = Vec::new();
    collect(&as_table(spec), "", &mut out);
    out
}

/// Sets the number at `path` (an integer key needs an integral value); the changed mission
/// must still deserialize.
pub fn set_number(spec: &mut MissionSpec, path: &str, value: f64) -> Result<(), PathError> {
    set_numbers(spec, &[(path, value)])
}

/// Sets several numbers at once (one serialization round trip for all of them, e.g. one
/// Monte Carlo sample); on error `spec` is unchanged.
pub fn set_numbers(spec: &mut MissionSpec, values: &[(&str, f64)]) -> Result<(), PathError> {
    let mut table = as_table(spec);
    for &(path, value) in values {
        let slot = walk(&mut table, path)?;
        *slot = match slot {
            toml::Value::Float(_) => toml::Value::Float(value),
            toml::Value::Integer(_) => {
                if value.fract().abs() > 0.0 || !value.is_finite() {
                    return Err(PathError::NotInteger {
                        path: path.to_owned(),
                        value,
                    });
                }
                toml::Value::Integer(value as i64)
            }
            other => {
                return Err(PathError::NotNumeric {
                    path: path.to_owned(),
                    found: type_name(other),
                });
            }
        };
    }
    *spec = toml::Value::Table(table)
        .try_into()
        .map_err(|e: toml::de::Error| PathError::Rejected {
            message: e.message().trim_end().to_owned(),
        })?;
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
        (Input::Curve(_), _) => {
            Err("a curve only takes `factor = ...` or `offset = ...`".to_owned())
        }
        (Input::Number { integer: true, .. }, Distribution::Choice(values)) => {
            if values.iter().any(|v| v.fract().abs() > 0.0) {
                return Err("an integer input takes integral choices".to_owned());
            }
            well_formed(distribution)
        }
        (Input::Number { integer: true, .. }, _) => {
            Err("an integer input only takes `choice`".to_owned())
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
