//! Eggtimer CSV (Quantum: `T,Alt,Veloc,FAlt,FVeloc,…`; Proton: `Filt_Alt`).
//!
//! `T` ms, `Alt` ft AGL (raw barometric), `Veloc` ft/s (raw), `FAlt`/`Filt_Alt` ft,
//! `FVeloc` ft/s (the device's filtered velocity, read as the velocity). The event columns
//! (`LDA` launch detect, `LowV`, `Apogee`, `N-O` nose-over, `Drogue`, `Main`) are 0 until the
//! event, then hold the altitude (ft) at which it happened: the first non-zero row is the
//! event's time; `Apogee`'s value is the device's apogee figure.

use crate::error::FlightLogError;
use crate::format::Format;
use crate::log::EventKind;
use crate::raw::{AltitudeKind, Channel, DeviceEvent, Raw, col, extract};
use crate::table::{Table, number};
use crate::units::Unit;

const NAME: &str = "Eggtimer CSV";

pub(crate) fn read(text: &str, file: &str) -> Result<Raw, FlightLogError> {
    let table = Table::read(text, 1, b',', file, None)?;
    let mut raw = Raw::new(Format::Eggtimer, file, AltitudeKind::Agl);
    let time = col(&table, Channel::Time, "T", Unit::Millisecond, NAME)?;
    let columns = [
        time,
        col(&table, Channel::Altitude, "Alt", Unit::Foot, NAME)?,
        col(
            &table,
            Channel::Velocity,
            "FVeloc",
            Unit::FootPerSecond,
            NAME,
        )?,
    ];
    extract(&table, &columns, &[], &mut raw)?;
    for (name, kind) in [
        ("LDA", None),
        ("LowV", None),
        ("Apogee", None),
        ("N-O", None),
        ("Drogue", Some(EventKind::Drogue)),
        ("Main", Some(EventKind::Main)),
    ] {
        let Some(c) = table.column(name) else {
            continue;
        };
        let mut first = None;
        let mut rows = table.rows();
        while let Some(row) = rows.next()? {
            let v = row.fields.get(c).and_then(number);
            let t = row.fields.get(time.index).and_then(number);
            if let (Some(v), Some(t)) = (v, t)
                && v.abs() > 0.0
            {
                first = Some((Unit::Millisecond.to_si(t), Unit::Foot.to_si(v)));
                break;
            }
        }
        let Some((t, h)) = first else { continue };
        let key = name.to_ascii_lowercase().replace('-', "_");
        raw.metadata
            .insert(format!("{key}_device_time_s"), format!("{t}"));
        raw.metadata
            .insert(format!("{key}_altitude_m"), format!("{h:.2}"));
        if name == "Apogee" {
            raw.reported.apogee_agl_m = Some(h);
        }
        if let Some(kind) = kind {
            raw.device_events.push(DeviceEvent { kind, time: t });
        }
    }
    Ok(raw)
}
