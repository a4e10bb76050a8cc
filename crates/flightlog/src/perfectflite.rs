//! PerfectFlite downloads: the `.pf2` file with its header block, and the StratoLogger
//! tab-separated text.
//!
//! `.pf2` (as written by PerfectFlite's software, e.g. for the StratoLoggerCF): a first line
//! `PerfectFlite <model>`, `Key: value` lines (`Serial Number`, `Apogee: 15373' AGL`,
//! `Ground Elevation: 225' MSL`, `Drogue At: 26.95 Seconds`, `Main At: …`, …), then
//! `Data: (Time, Altitude, Velocity, Temperature (F), Voltage)` and comma-separated rows: s,
//! ft AGL, ft/s, °F, V. A `'` after a figure is feet. The deployment times are device events.
//!
//! StratoLogger text: header `Time  Altitude  Temp.  Voltage` (tab-separated), rows in s,
//! ft AGL, and the temperature with its unit letter (`58.7F`, or `C`).

use crate::error::FlightLogError;
use crate::format::Format;
use crate::log::EventKind;
use crate::raw::{AltitudeKind, Channel, Column, DeviceEvent, Raw, extract};
use crate::table::{Table, number};
use crate::units::Unit;

/// A header figure `15373' AGL` or `26.95 Seconds`: the leading number and whether it is in
/// feet (a `'` or `ft` after it).
fn figure(value: &str) -> Option<(f64, bool)> {
    let v = value.trim();
    let end = v
        .find(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-' || c == '+'))
        .unwrap_or(v.len());
    let n = number(&v[..end])?;
    let rest = v[end..].trim_start();
    Some((
        n,
        rest.starts_with('\'') || rest.starts_with("ft") || rest.starts_with("feet"),
    ))
}

pub(crate) fn read_pf2(text: &str, file: &str) -> Result<Raw, FlightLogError> {
    let mut raw = Raw::new(Format::PerfectFlitePf2, file, AltitudeKind::Agl);
    let mut offset = 0;
    let mut data = None;
    for (i, line) in text.split_inclusive('\n').enumerate() {
        let number_of_line = i + 1;
        offset += line.len();
        let line = line.trim();
        if i == 0 {
            let model = line.trim_start_matches("PerfectFlite").trim();
            raw.device = format!("PerfectFlite {model}");
            continue;
        }
        if let Some(rest) = line.strip_prefix("Data:") {
            let names: Vec<String> = rest
                .trim()
                .trim_start_matches('(')
                .trim_end_matches(')')
                .split(',')
                .map(|s| s.trim().to_owned())
                .collect();
            data = Some((number_of_line, names));
            break;
        }
        let Some((key, value)) = line.split_once(':') else {
            continue;
        };
        let key = key.trim().to_ascii_lowercase();
        let value = value.trim();
        raw.metadata.insert(key.replace(' ', "_"), value.to_owned());
        match key.as_str() {
            "serial number" => raw.device = format!("{} serial {value}", raw.device),
            "apogee" => {
                if let Some((n, ft)) = figure(value) {
                    raw.reported.apogee_agl_m = Some(if ft { Unit::Foot.to_si(n) } else { n });
                }
            }
            "ground elevation" => {
                if let Some((n, ft)) = figure(value) {
                    raw.reported.ground_elevation_m =
                        Some(if ft { Unit::Foot.to_si(n) } else { n });
                }
            }
            "drogue at" | "main at" => {
                if let Some((t, _)) = figure(value) {
                    let kind = if key == "main at" {
                        EventKind::Main
                    } else {
                        EventKind::Drogue
                    };
                    raw.device_events.push(DeviceEvent { kind, time: t });
                }
            }
            _ => {}
        }
    }
    let Some((data_line, names)) = data else {
        return Err(FlightLogError::WrongFormat {
            file: file.to_owned(),
            line: 1,
            format: "PerfectFlite .pf2",
            reason: "no 'Data:' line".into(),
        });
    };
    let rest = text.get(offset..).unwrap_or("");
    let table = Table::read(rest, data_line + 1, b',', file, Some(names))?;
    let find = |p: &str| table.column_where(|h| h.starts_with(p));
    let (Some(t), Some(h)) = (find("time"), find("altitude")) else {
        return Err(FlightLogError::WrongFormat {
            file: file.to_owned(),
            line: data_line,
            format: "PerfectFlite .pf2",
            reason: "the Data: line names no Time and Altitude".into(),
        });
    };
    let mut columns = vec![
        Column {
            channel: Channel::Time,
            index: t,
            unit: Unit::Second,
        },
        Column {
            channel: Channel::Altitude,
            index: h,
            unit: Unit::Foot,
        },
    ];
    if let Some(v) = find("velocity") {
        columns.push(Column {
            channel: Channel::Velocity,
            index: v,
            unit: Unit::FootPerSecond,
        });
    }
    if let Some(c) = find("temperature") {
        let unit = if table.header[c].contains("(C)") {
            Unit::Celsius
        } else {
            Unit::Fahrenheit
        };
        columns.push(Column {
            channel: Channel::Temperature,
            index: c,
            unit,
        });
    }
    let rows = extract(&table, &columns, &[], &mut raw)?;
    if let Some(n) = raw.metadata.get("numsamps").and_then(|v| number(v))
        && (n as usize) != rows
    {
        raw.warnings.push(format!(
            "the header says NumSamps {n}, the file holds {rows} data rows"
        ));
    }
    Ok(raw)
}

pub(crate) fn read_text(text: &str, file: &str) -> Result<Raw, FlightLogError> {
    let table = Table::read(text, 1, b'\t', file, None)?;
    let mut raw = Raw::new(Format::StratoLoggerText, file, AltitudeKind::Agl);
    let mut columns = vec![
        Column {
            channel: Channel::Time,
            index: 0,
            unit: Unit::Second,
        },
        Column {
            channel: Channel::Altitude,
            index: 1,
            unit: Unit::Foot,
        },
    ];
    if let Some(c) = table.column_where(|h| h.starts_with("temp")) {
        let celsius = table
            .first
            .as_ref()
            .and_then(|r| r.fields.get(c))
            .is_some_and(|v| v.trim_end().ends_with('C'));
        let unit = if celsius {
            Unit::Celsius
        } else {
            Unit::Fahrenheit
        };
        columns.push(Column {
            channel: Channel::Temperature,
            index: c,
            unit,
        });
    }
    extract(&table, &columns, &['F', 'C'], &mut raw)?;
    Ok(raw)
}
