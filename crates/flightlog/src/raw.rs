//! What a format reader hands to the normalisation: samples on the device's own clock in SI
//! units, the device's events and figures, and the warnings of reading.
//!
//! [`extract`] applies the row rules shared by every columnar format:
//! - a row with fewer fields than the columns read need is an error
//!   ([`FlightLogError::TruncatedRow`]) unless it is the last row of the file, which is skipped
//!   with a warning (a log cut off while being written);
//! - a row whose time or altitude (pressure for barometer-only logs) is not a finite number,
//!   or lies outside the plausible range (|t| ≤ 10⁶ s, |h| ≤ 200 km, 0 < p ≤ 200 kPa), is
//!   skipped, and the count and first line are reported as a warning;
//! - an unreadable optional value (NaN, text) leaves that channel empty for that sample, and
//!   the count per channel is reported as a warning.

use crate::error::FlightLogError;
use crate::format::Format;
use crate::log::{EventKind, Gnss, Reported, Sample};
use crate::table::{Table, number};
use crate::units::Unit;
use std::collections::BTreeMap;

/// Largest plausible |time| on a device clock, s.
const MAX_TIME: f64 = 1e6;
/// Largest plausible |altitude|, m.
const MAX_ALTITUDE: f64 = 2e5;
/// Largest plausible pressure, Pa.
const MAX_PRESSURE: f64 = 2e5;

/// What the primary altitude value of a raw sample is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum AltitudeKind {
    /// Height above ground as the device zeroed it, m.
    Agl,
    /// Height above sea level, m: the ground is the first sample's.
    Msl,
    /// Static pressure, Pa: the height is the ISA pressure altitude above the first samples'.
    Pressure,
}

/// A channel a column can feed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Channel {
    Time,
    Altitude,
    Velocity,
    Acceleration,
    Pressure,
    Temperature,
    Latitude,
    Longitude,
    GnssAltitude,
}

impl Channel {
    fn name(self) -> &'static str {
        match self {
            Channel::Time => "time",
            Channel::Altitude => "altitude",
            Channel::Velocity => "velocity",
            Channel::Acceleration => "acceleration",
            Channel::Pressure => "pressure",
            Channel::Temperature => "temperature",
            Channel::Latitude => "latitude",
            Channel::Longitude => "longitude",
            Channel::GnssAltitude => "GNSS altitude",
        }
    }
}

/// One column read: which channel, which field, in which unit.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Column {
    pub channel: Channel,
    pub index: usize,
    pub unit: Unit,
}

/// An event the device itself recorded, on its own clock.
#[derive(Debug, Clone, Copy)]
pub(crate) struct DeviceEvent {
    pub kind: EventKind,
    pub time: f64,
}

/// A log as read, before normalisation.
pub(crate) struct Raw {
    pub format: Format,
    pub device: String,
    pub file: String,
    pub altitude: AltitudeKind,
    /// The rows read, in the record's own [`Sample`] type so that normalisation works in
    /// place (no second copy of a large log): until then on the device's clock
    /// (`time_s`), `altitude_agl_m` holding the primary altitude value (AGL or MSL height,
    /// m, or pressure, Pa, as [`Raw::altitude`] says), `vertical_velocity_mps` the device's
    /// velocity or NaN where it has none.
    pub samples: Vec<Sample>,
    /// The 1-based line of each of `samples`.
    pub lines: Vec<usize>,
    /// An acceleration channel on its own clock (FIP exports), (device time s, m/s²).
    pub acceleration_channel: Vec<(f64, f64)>,
    pub device_events: Vec<DeviceEvent>,
    pub metadata: BTreeMap<String, String>,
    pub reported: Reported,
    pub warnings: Vec<String>,
}

impl Raw {
    pub fn new(format: Format, file: &str, altitude: AltitudeKind) -> Raw {
        Raw {
            format,
            device: format.device_family().to_owned(),
            file: file.to_owned(),
            altitude,
            samples: Vec::new(),
            lines: Vec::new(),
            acceleration_channel: Vec::new(),
            device_events: Vec::new(),
            metadata: BTreeMap::new(),
            reported: Reported::default(),
            warnings: Vec::new(),
        }
    }
}

/// Counts of a skipped or mended kind of row: how many, and the first line (shared by the
/// reading and the normalising rules' warnings).
#[derive(Default)]
pub(crate) struct Tally {
    pub(crate) count: usize,
    pub(crate) first_line: usize,
}

impl Tally {
    pub(crate) fn add(&mut self, line: usize) {
        if self.count == 0 {
            self.first_line = line;
        }
        self.count += 1;
    }
}

/// A field as an SI number within the plausible range of its channel, or `None`.
fn value(fields: &csv::StringRecord, column: Column, strip: &[char]) -> Option<f64> {
    let text = fields.get(column.index)?;
    let text = text.trim().trim_end_matches(strip);
    let v = column.unit.to_si(number(text)?);
    let plausible = match column.channel {
        Channel::Time => v.abs() <= MAX_TIME,
        Channel::Altitude | Channel::GnssAltitude => v.abs() <= MAX_ALTITUDE,
        Channel::Pressure => v > 0.0 && v <= MAX_PRESSURE,
        _ => v.abs() <= 1e9,
    };
    plausible.then_some(v)
}

/// Reads the samples of `table`'s rows through `columns` (which must contain a time and an
/// altitude column; the altitude column of a barometer-only log is its pressure, kind
/// [`AltitudeKind::Pressure`]) into `raw.samples` and `raw.lines`, by the row rules of this
/// module. `strip` lists trailing characters removed from a field before parsing
/// (StratoLogger's `58.7F`). Rows whose time field is empty are not samples of this channel
/// group (a FIP channel that ended): passed over, and counted in a warning but for FIP
/// exports. Returns the number of data rows read.
pub(crate) fn extract(
    table: &Table<'_>,
    columns: &[Column],
    strip: &[char],
    raw: &mut Raw,
) -> Result<usize, FlightLogError> {
    let needed = columns.iter().map(|c| c.index + 1).max().unwrap_or(0);
    let time = columns.iter().find(|c| c.channel == Channel::Time).copied();
    let altitude = columns
        .iter()
        .find(|c| c.channel == Channel::Altitude)
        .copied();
    let (Some(time), Some(altitude)) = (time, altitude) else {
        return Err(FlightLogError::NoAltitude {
            file: table.file.clone(),
            format: raw.format.name(),
        });
    };
    let bound = table.row_bound();
    raw.samples = Vec::with_capacity(bound);
    raw.lines = Vec::with_capacity(bound);
    let mut bad_rows = Tally::default();
    let mut no_time = Tally::default();
    let mut bad_values: BTreeMap<&'static str, Tally> = BTreeMap::new();
    // A short row is an error unless it is the last one: kept here until the next row
    // (line, fields found, whether its time field is empty).
    let mut short_row: Option<(usize, usize, bool)> = None;
    let mut count = 0;
    let mut rows = table.rows();
    while let Some(row) = rows.next()? {
        count += 1;
        if let Some((line, found, no_time_field)) = short_row.take() {
            if no_time_field {
                no_time.add(line);
            } else {
                return Err(FlightLogError::TruncatedRow {
                    file: table.file.clone(),
                    line,
                    found,
                    needed,
                });
            }
        }
        let no_time_field = row.fields.get(time.index).is_none_or(str::is_empty);
        if row.fields.len() < needed {
            short_row = Some((row.line, row.fields.len(), no_time_field));
            continue;
        }
        if no_time_field {
            // No sample of this channel group on this row (a FIP channel that ended).
            no_time.add(row.line);
            continue;
        }
        let (Some(t), Some(h)) = (
            value(&row.fields, time, strip),
            value(&row.fields, altitude, strip),
        ) else {
            bad_rows.add(row.line);
            continue;
        };
        let mut read = Channels::default();
        for c in columns {
            let slot = match c.channel {
                Channel::Time | Channel::Altitude => continue,
                Channel::Velocity => &mut read.velocity,
                Channel::Acceleration => &mut read.acceleration,
                Channel::Pressure => &mut read.pressure,
                Channel::Temperature => &mut read.temperature,
                Channel::Latitude => &mut read.latitude,
                Channel::Longitude => &mut read.longitude,
                Channel::GnssAltitude => &mut read.gnss_altitude,
            };
            *slot = value(&row.fields, *c, strip);
            if slot.is_none() {
                bad_values
                    .entry(c.channel.name())
                    .or_default()
                    .add(row.line);
            }
        }
        raw.samples.push(Sample {
            time_s: t,
            altitude_agl_m: h,
            vertical_velocity_mps: read.velocity.unwrap_or(f64::NAN),
            acceleration_mps2: read.acceleration,
            pressure_pa: read.pressure,
            temperature_k: read.temperature,
            gnss: match (read.latitude, read.longitude) {
                (Some(latitude_deg), Some(longitude_deg)) => Some(Gnss {
                    latitude_deg,
                    longitude_deg,
                    altitude_m: read.gnss_altitude,
                }),
                _ => None,
            },
        });
        raw.lines.push(row.line);
    }
    if let Some((line, found, _)) = short_row {
        raw.warnings.push(format!(
            "line {line}: truncated final row ({found} of {needed} fields) skipped"
        ));
    }
    if bad_rows.count > 0 {
        raw.warnings.push(format!(
            "{} row(s) skipped: time or {} not a plausible number (first at line {})",
            bad_rows.count,
            altitude.channel.name(),
            bad_rows.first_line
        ));
    }
    if no_time.count > 0 && raw.format != Format::RavenFip {
        raw.warnings.push(format!(
            "{} row(s) without a time skipped (first at line {})",
            no_time.count, no_time.first_line
        ));
    }
    for (name, tally) in bad_values {
        raw.warnings.push(format!(
            "{} {name} value(s) unreadable or not finite, left empty (first at line {})",
            tally.count, tally.first_line
        ));
    }
    Ok(count)
}

/// The optional channels of one row as read (each `None` when its column is absent or the
/// value unreadable).
#[derive(Default)]
struct Channels {
    velocity: Option<f64>,
    acceleration: Option<f64>,
    pressure: Option<f64>,
    temperature: Option<f64>,
    latitude: Option<f64>,
    longitude: Option<f64>,
    gnss_altitude: Option<f64>,
}

/// A required column of a format, as a [`Column`].
pub(crate) fn col(
    table: &Table<'_>,
    channel: Channel,
    name: &str,
    unit: Unit,
    format: &'static str,
) -> Result<Column, FlightLogError> {
    Ok(Column {
        channel,
        index: table.require(name, format)?,
        unit,
    })
}

/// An optional column of a format, as a [`Column`] when the header has it.
pub(crate) fn opt(table: &Table<'_>, channel: Channel, name: &str, unit: Unit) -> Option<Column> {
    table.column(name).map(|index| Column {
        channel,
        index,
        unit,
    })
}
