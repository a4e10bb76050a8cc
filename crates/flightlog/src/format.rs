//! The log formats, recognised from the file's content (its header lines and column names),
//! never from its name.

use crate::error::FlightLogError;
use std::fmt;
use std::str::FromStr;

/// A log format this crate reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Format {
    /// Altus Metrum AltosUI CSV export (TeleMetrum, TeleMega, EasyMega, …): first header
    /// field `#version`, columns `time`, `state_name`, `height` (m AGL), `speed` (m/s), …
    AltusMetrum,
    /// Featherweight Interface Program (FIP) export of a Raven: each channel has its own time
    /// column (`Time-Axial Accel (Gs)`, `Time (s)`, …) and its own rate.
    RavenFip,
    /// Featherweight Blue Raven phone-app CSV: `Year,Month,Day,Time,Flight_Time_(s),…`,
    /// altitude in feet, temperature in °F, pressure in atm.
    BlueRaven,
    /// PerfectFlite `.pf2` (StratoLoggerCF and others): a `PerfectFlite …` header block with
    /// the device's apogee and deployment times, then `Data: (Time, Altitude, Velocity, …)`.
    PerfectFlitePf2,
    /// PerfectFlite StratoLogger tab-separated text download: `Time  Altitude  Temp.  Voltage`,
    /// altitude in feet AGL, temperature with a literal `F`.
    StratoLoggerText,
    /// Missile Works RRC3 (mDACS) CSV: `time,altitude,pressure,velocity,temperature,events,…`
    /// in m, hPa, m/s, °C.
    Rrc3,
    /// Eggtimer CSV: `T,Alt,Veloc,FAlt|Filt_Alt,FVeloc,…` with T in ms, feet and ft/s, event
    /// columns holding the altitude at which each event happened.
    Eggtimer,
    /// CATS Vega exports: `ts,id,T,P` (barometer), `ts,height,velocity,acceleration` (flight
    /// info), `ts,filteredAltitudeAGL,…` (filtered data); the IMU and GNSS exports are
    /// recognised but carry no altitude.
    CatsVega,
    /// Any CSV read through a user column mapping ([`crate::ColumnMapping`]).
    Generic,
}

impl Format {
    /// Every format, in the order detection tries them.
    pub const ALL: [Format; 9] = [
        Format::AltusMetrum,
        Format::RavenFip,
        Format::BlueRaven,
        Format::PerfectFlitePf2,
        Format::StratoLoggerText,
        Format::Rrc3,
        Format::Eggtimer,
        Format::CatsVega,
        Format::Generic,
    ];

    /// The short name used by `--format` and in JSON.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Format::AltusMetrum => "altusmetrum",
            Format::RavenFip => "raven-fip",
            Format::BlueRaven => "blueraven",
            Format::PerfectFlitePf2 => "perfectflite-pf2",
            Format::StratoLoggerText => "stratologger-txt",
            Format::Rrc3 => "rrc3",
            Format::Eggtimer => "eggtimer",
            Format::CatsVega => "cats-vega",
            Format::Generic => "generic",
        }
    }

    /// The device family the format comes from, as shown to users.
    #[must_use]
    pub fn device_family(self) -> &'static str {
        match self {
            Format::AltusMetrum => "Altus Metrum",
            Format::RavenFip => "Featherweight Raven",
            Format::BlueRaven => "Featherweight Blue Raven",
            Format::PerfectFlitePf2 | Format::StratoLoggerText => "PerfectFlite StratoLogger",
            Format::Rrc3 => "Missile Works RRC3",
            Format::Eggtimer => "Eggtimer",
            Format::CatsVega => "CATS Vega",
            Format::Generic => "unknown device",
        }
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Format {
    type Err = FlightLogError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let wanted = s.trim().to_ascii_lowercase();
        Format::ALL
            .into_iter()
            .find(|f| f.name() == wanted)
            .ok_or_else(|| FlightLogError::UnknownFormatName {
                name: s.to_owned(),
                known: Format::ALL.map(Format::name).join(", "),
            })
    }
}

/// The fields of a header line split at commas or tabs, trimmed, lower-cased.
fn fields(line: &str) -> Vec<String> {
    let sep = if line.contains('\t') && !line.contains(',') {
        '\t'
    } else {
        ','
    };
    line.split(sep)
        .map(|f| f.trim().trim_matches('"').to_ascii_lowercase())
        .collect()
}

/// The format of a log from its text, or `None` (a generic CSV needs a mapping). Looks only
/// at the first non-empty line, but for `.pf2` whose first line names PerfectFlite.
#[must_use]
pub fn detect(text: &str) -> Option<Format> {
    let first = text.lines().find(|l| !l.trim().is_empty())?;
    let first = first.trim_start_matches('\u{feff}');
    if first.trim_start().starts_with("PerfectFlite") {
        return Some(Format::PerfectFlitePf2);
    }
    let f = fields(first);
    let has = |name: &str| f.iter().any(|x| x == name);
    if f.first().is_some_and(|x| x == "#version") && has("time") && has("height") {
        return Some(Format::AltusMetrum);
    }
    if f.iter().any(|x| x.starts_with("time-"))
        || (f.iter().any(|x| x.starts_with("time")) && f.iter().any(|x| x.contains("(ft-agl)")))
    {
        return Some(Format::RavenFip);
    }
    if f.starts_with(&["year".into(), "month".into(), "day".into(), "time".into()])
        && has("flight_time_(s)")
        && has("baro_altitude_agl_(feet)")
    {
        return Some(Format::BlueRaven);
    }
    if first.contains('\t')
        && f.len() >= 2
        && f[0] == "time"
        && f[1] == "altitude"
        && f.iter().any(|x| x.starts_with("temp"))
    {
        return Some(Format::StratoLoggerText);
    }
    if [
        "time",
        "altitude",
        "pressure",
        "velocity",
        "temperature",
        "events",
    ]
    .iter()
    .all(|c| has(c))
    {
        return Some(Format::Rrc3);
    }
    if f.len() >= 3
        && f[0] == "t"
        && f[1] == "alt"
        && f[2] == "veloc"
        && has("fveloc")
        && (has("falt") || has("filt_alt"))
    {
        return Some(Format::Eggtimer);
    }
    if f.first().is_some_and(|x| x == "ts") {
        let baro = has("id") && has("t") && has("p");
        let info = has("height") && has("velocity");
        let filtered = f.iter().any(|x| x.starts_with("filtered"));
        let imu = has("id") && has("ax");
        let gnss = has("latitude") && has("longitude");
        if baro || info || filtered || imu || gnss {
            return Some(Format::CatsVega);
        }
    }
    None
}
