//! Missile Works RRC3 CSV, as exported by mDACS: `time,altitude,pressure,velocity,
//! temperature,events,voltages`. The header states no units; read as the metric export:
//! s, m AGL, hPa (= mbar), m/s, °C. A log exported in feet must be read with a column
//! mapping instead. The `events` column names events (`Drogue`, `Main`, `Apogee`); the first
//! row naming each is its device event. Rows near the end of a log may lack the temperature
//! (`30.45,10700.59,191.25,7215.777, Drogue,,`): the event is then one field to the left, so
//! any field of a row naming an event counts, and the temperature reads as unreadable.

use crate::error::FlightLogError;
use crate::format::Format;
use crate::log::EventKind;
use crate::raw::{AltitudeKind, Channel, DeviceEvent, Raw, col, extract, opt};
use crate::table::{Table, number};
use crate::units::Unit;

const NAME: &str = "RRC3 CSV";

pub(crate) fn read(text: &str, file: &str) -> Result<Raw, FlightLogError> {
    let table = Table::read(text, 1, b',', file, None)?;
    let mut raw = Raw::new(Format::Rrc3, file, AltitudeKind::Agl);
    let mut columns = vec![
        col(&table, Channel::Time, "time", Unit::Second, NAME)?,
        col(&table, Channel::Altitude, "altitude", Unit::Metre, NAME)?,
    ];
    columns.extend(opt(
        &table,
        Channel::Pressure,
        "pressure",
        Unit::Hectopascal,
    ));
    columns.extend(opt(
        &table,
        Channel::Velocity,
        "velocity",
        Unit::MetrePerSecond,
    ));
    columns.extend(opt(
        &table,
        Channel::Temperature,
        "temperature",
        Unit::Celsius,
    ));
    extract(&table, &columns, &[], &mut raw)?;
    if let Some(t) = table.column("time") {
        let mut rows = table.rows();
        while let Some(row) = rows.next()? {
            let Some(time) = row.fields.get(t).and_then(number) else {
                continue;
            };
            // Any field naming an event: the rows near the end of a log that lost their
            // temperature carry the event one field to the left of the `events` column.
            let kind = row
                .fields
                .iter()
                .find_map(|f| match f.to_ascii_lowercase().as_str() {
                    "drogue" | "apogee" => Some(EventKind::Drogue),
                    "main" => Some(EventKind::Main),
                    _ => None,
                });
            if let Some(kind) = kind
                && !raw.device_events.iter().any(|d| d.kind == kind)
            {
                raw.device_events.push(DeviceEvent { kind, time });
            }
        }
    }
    Ok(raw)
}
