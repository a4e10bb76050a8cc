//! CATS Vega flight-computer exports, one CSV per record type, all on one clock `ts` (s from
//! the device's launch detection):
//! - `ts,id,T,P`: barometer, °C and Pa; the height is the ISA pressure altitude above the
//!   first samples ([`crate::FlightLog`] rule); rows of the first `id` only (a second sensor
//!   would interleave its own rows), the others counted in a warning;
//! - `ts,height,velocity,acceleration`: the device's flight estimate, m AGL, m/s, m/s²;
//! - `ts,filteredAltitudeAGL,filteredAcceleration` (or `filtered_altitude_AGL,…`): m, m/s²;
//! - `ts,id,Ax,…` (IMU) and `ts,latitude,longitude,satellites` (GNSS) have no altitude: an
//!   error says so.

use crate::error::FlightLogError;
use crate::format::Format;
use crate::raw::{AltitudeKind, Channel, Column, Raw, col, extract, opt};
use crate::table::Table;
use crate::units::Unit;

const NAME: &str = "CATS Vega CSV";

pub(crate) fn read(text: &str, file: &str) -> Result<Raw, FlightLogError> {
    let mut table = Table::read(text, 1, b',', file, None)?;
    let time = col(&table, Channel::Time, "ts", Unit::Second, NAME)?;
    if let Some(p) = table.column("P") {
        let mut raw = Raw::new(Format::CatsVega, file, AltitudeKind::Pressure);
        if let Some(id) = table.column("id") {
            let first = table
                .first
                .as_ref()
                .and_then(|r| r.fields.get(id))
                .unwrap_or("")
                .to_owned();
            let other = table.keep_only(id, &first)?;
            if other > 0 {
                raw.warnings.push(format!(
                    "{other} row(s) of sensors other than {first} not read"
                ));
            }
            raw.device = format!("CATS Vega (barometer {first})");
        }
        let mut columns = vec![
            time,
            Column {
                channel: Channel::Altitude,
                index: p,
                unit: Unit::Pascal,
            },
            Column {
                channel: Channel::Pressure,
                index: p,
                unit: Unit::Pascal,
            },
        ];
        columns.extend(opt(&table, Channel::Temperature, "T", Unit::Celsius));
        extract(&table, &columns, &[], &mut raw)?;
        return Ok(raw);
    }
    let mut raw = Raw::new(Format::CatsVega, file, AltitudeKind::Agl);
    let mut columns = vec![time];
    if let Some(h) = opt(&table, Channel::Altitude, "height", Unit::Metre) {
        columns.push(h);
        columns.extend(opt(
            &table,
            Channel::Velocity,
            "velocity",
            Unit::MetrePerSecond,
        ));
        columns.extend(opt(
            &table,
            Channel::Acceleration,
            "acceleration",
            Unit::MetrePerSecondSquared,
        ));
    } else if let Some(h) =
        table.column_where(|h| h.starts_with("filtered") && h.contains("altitude"))
    {
        columns.push(Column {
            channel: Channel::Altitude,
            index: h,
            unit: Unit::Metre,
        });
        if let Some(a) =
            table.column_where(|h| h.starts_with("filtered") && h.contains("acceleration"))
        {
            columns.push(Column {
                channel: Channel::Acceleration,
                index: a,
                unit: Unit::MetrePerSecondSquared,
            });
        }
    } else {
        return Err(FlightLogError::NoAltitude {
            file: file.to_owned(),
            format: Format::CatsVega.name(),
        });
    }
    extract(&table, &columns, &[], &mut raw)?;
    Ok(raw)
}
