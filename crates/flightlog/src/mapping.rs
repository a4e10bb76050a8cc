//! The generic CSV: a user's column mapping, `key=column[:unit],…`.
//!
//! Keys: `time` (required), one of `altitude` (AGL), `altitude_msl` (the ground is the first
//! samples' level) or `pressure` (ISA pressure altitude above the first samples), and
//! optionally `velocity`, `acceleration`, `temperature`, `latitude`, `longitude`,
//! `gnss_altitude` (and `pressure` beside an altitude). A unit after the last `:`; without
//! one the SI unit (°C for temperature, degrees for angles). Columns are header names,
//! matched ASCII case-insensitively. The delimiter is the header line's most frequent of
//! `,`, `;` and tab.

use crate::error::FlightLogError;
use crate::format::Format;
use crate::raw::{AltitudeKind, Channel, Column, Raw, extract};
use crate::table::Table;
use crate::units::Unit;
use std::str::FromStr;

/// What a mapping key feeds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Key {
    Time,
    Altitude,
    AltitudeMsl,
    Pressure,
    Velocity,
    Acceleration,
    Temperature,
    Latitude,
    Longitude,
    GnssAltitude,
}

impl Key {
    fn parse(text: &str) -> Option<Key> {
        Some(match text {
            "time" => Key::Time,
            "altitude" | "altitude_agl" => Key::Altitude,
            "altitude_msl" => Key::AltitudeMsl,
            "pressure" => Key::Pressure,
            "velocity" => Key::Velocity,
            "acceleration" => Key::Acceleration,
            "temperature" => Key::Temperature,
            "latitude" => Key::Latitude,
            "longitude" => Key::Longitude,
            "gnss_altitude" => Key::GnssAltitude,
            _ => return None,
        })
    }

    fn default_unit(self) -> Unit {
        match self {
            Key::Time => Unit::Second,
            Key::Altitude | Key::AltitudeMsl | Key::GnssAltitude => Unit::Metre,
            Key::Pressure => Unit::Pascal,
            Key::Velocity => Unit::MetrePerSecond,
            Key::Acceleration => Unit::MetrePerSecondSquared,
            Key::Temperature => Unit::Celsius,
            Key::Latitude | Key::Longitude => Unit::Degree,
        }
    }
}

/// One entry of a mapping.
#[derive(Debug, Clone, PartialEq)]
struct Entry {
    key: Key,
    column: String,
    unit: Unit,
}

/// A user's mapping of CSV columns to a log's channels, e.g.
/// `time=ts,altitude=alt_ft:ft,velocity=v:ft/s` (module documentation above lists the keys
/// and units).
#[derive(Debug, Clone, PartialEq)]
pub struct ColumnMapping {
    spec: String,
    entries: Vec<Entry>,
}

impl ColumnMapping {
    /// Parses a mapping; errors name the spec and the fault.
    ///
    /// # Errors
    /// An entry without `=`, an unknown key or unit, a unit of the wrong quantity, a key
    /// given twice, no `time`, or none of `altitude`, `altitude_msl`, `pressure`.
    pub fn parse(spec: &str) -> Result<ColumnMapping, FlightLogError> {
        let fail = |reason: String| FlightLogError::Mapping {
            spec: spec.to_owned(),
            reason,
        };
        let mut entries: Vec<Entry> = Vec::new();
        for part in spec.split(',').map(str::trim).filter(|p| !p.is_empty()) {
            let (key, rest) = part
                .split_once('=')
                .ok_or_else(|| fail(format!("'{part}' is not key=column[:unit]")))?;
            let key_text = key.trim().to_ascii_lowercase();
            let key = Key::parse(&key_text).ok_or_else(|| {
                fail(format!(
                    "unknown key '{key_text}' (known: time, altitude, altitude_msl, pressure, \
                     velocity, acceleration, temperature, latitude, longitude, gnss_altitude)"
                ))
            })?;
            let (column, unit) = match rest.rsplit_once(':') {
                Some((column, unit)) => {
                    let u = Unit::parse(unit).ok_or_else(|| {
                        fail(format!(
                            "unknown unit '{unit}' (m, ft, s, ms, m/s, ft/s, g, m/s2, Pa, hPa, \
                             kPa, atm, C, F, K, deg)"
                        ))
                    })?;
                    (column.trim(), u)
                }
                None => (rest.trim(), key.default_unit()),
            };
            if column.is_empty() {
                return Err(fail(format!("no column for '{key_text}'")));
            }
            if unit.quantity() != key.default_unit().quantity() {
                return Err(fail(format!(
                    "'{key_text}' is a {}, the unit {unit:?} a {}",
                    key.default_unit().quantity(),
                    unit.quantity()
                )));
            }
            if entries.iter().any(|e| e.key == key) {
                return Err(fail(format!("'{key_text}' given twice")));
            }
            entries.push(Entry {
                key,
                column: column.to_owned(),
                unit,
            });
        }
        let has = |k: Key| entries.iter().any(|e| e.key == k);
        if !has(Key::Time) {
            return Err(fail("no 'time' column".into()));
        }
        if !(has(Key::Altitude) || has(Key::AltitudeMsl) || has(Key::Pressure)) {
            return Err(fail(
                "no 'altitude', 'altitude_msl' or 'pressure' column".into(),
            ));
        }
        if has(Key::Altitude) && has(Key::AltitudeMsl) {
            return Err(fail("give 'altitude' or 'altitude_msl', not both".into()));
        }
        Ok(ColumnMapping {
            spec: spec.to_owned(),
            entries,
        })
    }

    /// The mapping as given.
    #[must_use]
    pub fn spec(&self) -> &str {
        &self.spec
    }
}

impl FromStr for ColumnMapping {
    type Err = FlightLogError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        ColumnMapping::parse(s)
    }
}

/// The delimiter of a header line: the most frequent of `,`, `;`, tab (`,` on a tie).
fn delimiter(line: &str) -> u8 {
    let count = |c: char| line.matches(c).count();
    let (comma, semicolon, tab) = (count(','), count(';'), count('\t'));
    if tab > comma && tab >= semicolon {
        b'\t'
    } else if semicolon > comma {
        b';'
    } else {
        b','
    }
}

pub(crate) fn read(text: &str, file: &str, mapping: &ColumnMapping) -> Result<Raw, FlightLogError> {
    let first = text.lines().find(|l| !l.trim().is_empty()).unwrap_or("");
    let table = Table::read(text, 1, delimiter(first), file, None)?;
    let has = |k: Key| mapping.entries.iter().any(|e| e.key == k);
    let kind = if has(Key::Altitude) {
        AltitudeKind::Agl
    } else if has(Key::AltitudeMsl) {
        AltitudeKind::Msl
    } else {
        AltitudeKind::Pressure
    };
    let mut raw = Raw::new(Format::Generic, file, kind);
    let mut columns = Vec::new();
    for e in &mapping.entries {
        let index = table
            .column(&e.column)
            .ok_or_else(|| FlightLogError::MissingColumn {
                file: file.to_owned(),
                line: table.header_line,
                column: e.column.clone(),
            })?;
        let channel = match e.key {
            Key::Time => Channel::Time,
            Key::Altitude | Key::AltitudeMsl => Channel::Altitude,
            Key::Pressure => {
                if kind == AltitudeKind::Pressure {
                    columns.push(Column {
                        channel: Channel::Altitude,
                        index,
                        unit: e.unit,
                    });
                }
                Channel::Pressure
            }
            Key::Velocity => Channel::Velocity,
            Key::Acceleration => Channel::Acceleration,
            Key::Temperature => Channel::Temperature,
            Key::Latitude => Channel::Latitude,
            Key::Longitude => Channel::Longitude,
            Key::GnssAltitude => Channel::GnssAltitude,
        };
        columns.push(Column {
            channel,
            index,
            unit: e.unit,
        });
    }
    raw.metadata.insert("mapping".into(), mapping.spec.clone());
    extract(&table, &columns, &[], &mut raw)?;
    Ok(raw)
}
