//! Altus Metrum AltosUI CSV export.
//!
//! Columns (AltosUI's CSV writer, version 6 in the files read): `time` s from boost detect,
//! `state_name` (`boost`, `coast`, `drogue`, `main`, `landed`), `acceleration` m/s² (gravity
//! removed), `pressure` Pa, `altitude` m MSL, `height` m AGL, `speed` m/s, `temperature` °C,
//! then GNSS `latitude`, `longitude` and a second `altitude` column (m MSL, GNSS). Events are
//! the state changes: `coast` burnout, `drogue` drogue (apogee), `main`, `landed`.

use crate::error::FlightLogError;
use crate::format::Format;
use crate::log::EventKind;
use crate::raw::{AltitudeKind, Channel, Column, DeviceEvent, Raw, col, extract, opt};
use crate::table::{Table, number};
use crate::units::Unit;

const NAME: &str = "AltosUI CSV";

pub(crate) fn read(text: &str, file: &str) -> Result<Raw, FlightLogError> {
    let table = Table::read(text, 1, b',', file, None)?;
    let mut raw = Raw::new(Format::AltusMetrum, file, AltitudeKind::Agl);
    let mut columns = vec![
        col(&table, Channel::Time, "time", Unit::Second, NAME)?,
        col(&table, Channel::Altitude, "height", Unit::Metre, NAME)?,
    ];
    columns.extend(opt(
        &table,
        Channel::Velocity,
        "speed",
        Unit::MetrePerSecond,
    ));
    columns.extend(opt(
        &table,
        Channel::Acceleration,
        "acceleration",
        Unit::MetrePerSecondSquared,
    ));
    columns.extend(opt(&table, Channel::Pressure, "pressure", Unit::Pascal));
    columns.extend(opt(
        &table,
        Channel::Temperature,
        "temperature",
        Unit::Celsius,
    ));
    columns.extend(opt(&table, Channel::Latitude, "latitude", Unit::Degree));
    columns.extend(opt(&table, Channel::Longitude, "longitude", Unit::Degree));
    // The GNSS altitude is the second column named `altitude` (the first is barometric MSL).
    if let Some(index) = table
        .header
        .iter()
        .enumerate()
        .filter(|(_, h)| h.eq_ignore_ascii_case("altitude"))
        .nth(1)
        .map(|(i, _)| i)
    {
        columns.push(Column {
            channel: Channel::GnssAltitude,
            index,
            unit: Unit::Metre,
        });
    }
    let state = table.column("state_name");
    let field = |name: &str| {
        table
            .column(name)
            .and_then(|i| table.first.as_ref()?.fields.get(i))
    };
    let serial = field("serial").unwrap_or("?");
    let flight = field("flight").unwrap_or("?");
    let call = field("call").unwrap_or("?");
    raw.device = format!("Altus Metrum serial {serial} (flight {flight}, call sign {call})");
    if table.column("accel_x").is_some() {
        raw.metadata.insert(
            "imu".into(),
            "accel_x/y/z, gyro, mag columns (TeleMega class)".into(),
        );
    }
    if let Some(v) = field("#version") {
        raw.metadata
            .insert("altosui_csv_version".into(), v.to_owned());
    }
    extract(&table, &columns, &[], &mut raw)?;
    if let (Some(state), Some(time)) = (state, table.column("time")) {
        let mut last = String::new();
        let mut rows = table.rows();
        while let Some(row) = rows.next()? {
            let (Some(s), Some(t)) = (row.fields.get(state), row.fields.get(time).and_then(number))
            else {
                continue;
            };
            if s != last {
                let kind = match s {
                    "coast" => Some(EventKind::Burnout),
                    "drogue" => Some(EventKind::Drogue),
                    "main" => Some(EventKind::Main),
                    "landed" => Some(EventKind::Landing),
                    _ => None,
                };
                if let Some(kind) = kind {
                    raw.device_events.push(DeviceEvent { kind, time: t });
                }
                s.clone_into(&mut last);
            }
        }
    }
    Ok(raw)
}
