//! Featherweight Interface Program (FIP) export of a Raven altimeter.
//!
//! Each channel group starts with its own time column (`Time-Axial Accel (Gs)`, `Time (s)`)
//! followed by its values, each group at its own rate. Read: the group holding
//! `Altitude (Ft-AGL)` (feet above ground) is the altitude channel; `Axial Accel (Gs)`
//! (standard gravities, gravity included, as the sensor reads it) is interpolated onto the
//! altitude times within its span; a `Temperature (F)` column of the altitude group is read.
//! Other columns (the `bILBA` flag strings) are named in the metadata.

use crate::error::FlightLogError;
use crate::format::Format;
use crate::raw::{AltitudeKind, Channel, Column, Raw, extract};
use crate::table::{Table, number};
use crate::units::Unit;

pub(crate) fn read(text: &str, file: &str) -> Result<Raw, FlightLogError> {
    let table = Table::read(text, 1, b',', file, None)?;
    let mut raw = Raw::new(Format::RavenFip, file, AltitudeKind::Agl);
    // Group of each column: the index of the time column before it.
    let mut group_time = Vec::with_capacity(table.header.len());
    let mut current = None;
    for (i, h) in table.header.iter().enumerate() {
        if h.to_ascii_lowercase().starts_with("time") {
            current = Some(i);
        }
        group_time.push(current);
    }
    let lower: Vec<String> = table
        .header
        .iter()
        .map(|h| h.to_ascii_lowercase())
        .collect();
    let altitude = lower
        .iter()
        .position(|h| h.starts_with("altitude") && h.contains("ft"));
    let Some(altitude) = altitude else {
        return Err(FlightLogError::NoAltitude {
            file: file.to_owned(),
            format: Format::RavenFip.name(),
        });
    };
    let Some(alt_time) = group_time[altitude] else {
        return Err(FlightLogError::WrongFormat {
            file: file.to_owned(),
            line: table.header_line,
            format: "Raven FIP",
            reason: "the altitude column has no time column before it".into(),
        });
    };
    let mut columns = vec![
        Column {
            channel: Channel::Time,
            index: alt_time,
            unit: Unit::Second,
        },
        Column {
            channel: Channel::Altitude,
            index: altitude,
            unit: Unit::Foot,
        },
    ];
    let mut unread = Vec::new();
    let mut accel = None;
    for (i, h) in lower.iter().enumerate() {
        if i == altitude || h.starts_with("time") {
            continue;
        }
        if h.starts_with("temperature") && group_time[i] == Some(alt_time) {
            let unit = if h.contains("(c)") {
                Unit::Celsius
            } else {
                Unit::Fahrenheit
            };
            columns.push(Column {
                channel: Channel::Temperature,
                index: i,
                unit,
            });
        } else if h.contains("accel") && h.contains("(gs)") && accel.is_none() {
            accel = group_time[i].map(|t| (t, i));
        } else {
            unread.push(table.header[i].clone());
        }
    }
    if !unread.is_empty() {
        raw.metadata
            .insert("unread_columns".into(), unread.join("; "));
    }
    extract(&table, &columns, &[], &mut raw)?;
    if let Some((t, a)) = accel {
        let mut bad = 0;
        let mut rows = table.rows();
        while let Some(row) = rows.next()? {
            match (
                row.fields.get(t).and_then(number),
                row.fields.get(a).and_then(number),
            ) {
                (Some(time), Some(g)) => raw
                    .acceleration_channel
                    .push((time, Unit::StandardGravity.to_si(g))),
                (None, None) => {}
                _ => bad += 1,
            }
        }
        if bad > 0 {
            raw.warnings.push(format!(
                "{bad} acceleration-channel value(s) unreadable, skipped"
            ));
        }
        raw.metadata.insert(
            "acceleration_channel_samples".into(),
            raw.acceleration_channel.len().to_string(),
        );
    }
    Ok(raw)
}
