//! Featherweight Blue Raven phone-app CSV (the low-rate export).
//!
//! Columns read: `Flight_Time_(s)` s from the device's launch detect,
//! `Baro_Altitude_AGL_(feet)` ft, `Velocity_Up` ft/s (the device's inertial vertical
//! velocity), `Temperature_(F)` °F, `Baro_Press_(atm)` atm. The flight-summary export beside
//! it is a separate file, not read here.

use crate::error::FlightLogError;
use crate::format::Format;
use crate::raw::{AltitudeKind, Channel, Raw, col, extract, opt};
use crate::table::Table;
use crate::units::Unit;

const NAME: &str = "Blue Raven CSV";

pub(crate) fn read(text: &str, file: &str) -> Result<Raw, FlightLogError> {
    let table = Table::read(text, 1, b',', file, None)?;
    let mut raw = Raw::new(Format::BlueRaven, file, AltitudeKind::Agl);
    let mut columns = vec![
        col(&table, Channel::Time, "Flight_Time_(s)", Unit::Second, NAME)?,
        col(
            &table,
            Channel::Altitude,
            "Baro_Altitude_AGL_(feet)",
            Unit::Foot,
            NAME,
        )?,
    ];
    columns.extend(opt(
        &table,
        Channel::Velocity,
        "Velocity_Up",
        Unit::FootPerSecond,
    ));
    columns.extend(opt(
        &table,
        Channel::Temperature,
        "Temperature_(F)",
        Unit::Fahrenheit,
    ));
    columns.extend(opt(
        &table,
        Channel::Pressure,
        "Baro_Press_(atm)",
        Unit::Atmosphere,
    ));
    extract(&table, &columns, &[], &mut raw)?;
    if let (Some(y), Some(m), Some(d)) = (
        table.column("Year"),
        table.column("Month"),
        table.column("Day"),
    ) && let Some(row) = &table.first
    {
        let f = |i| row.fields.get(i).unwrap_or("?");
        raw.metadata
            .insert("date".into(), format!("{}-{}-{}", f(y), f(m), f(d)));
    }
    Ok(raw)
}
