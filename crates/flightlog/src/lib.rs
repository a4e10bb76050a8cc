//! Altimeter and flight-computer logs, read into one normalised record.
//!
//! [`read`] (or [`parse`] for bytes in memory) recognises the format from the file's content,
//! never its name ([`detect`], [`Format`]): Altus Metrum AltosUI CSV, Featherweight Raven FIP
//! export (per-channel time columns), Featherweight Blue Raven app CSV, PerfectFlite `.pf2`
//! and StratoLogger text, Missile Works RRC3, Eggtimer, CATS Vega exports, and any CSV
//! through a user's [`ColumnMapping`] (`time=ts,altitude=alt_ft:ft`). Each module's
//! documentation names the columns and units its format writes. Values are converted to SI
//! as the file states them (ft, ft/s, g, °F, atm, hPa, ms); the header's own figures
//! (apogee, ground elevation, deployment times) are kept in [`FlightLog::reported`],
//! [`FlightLog::metadata`] and the device [`Event`]s.
//!
//! # Rules
//! Applied in this order; every rule that drops or changes data says so in
//! [`FlightLog::warnings`] (with a count and the first line), nothing is dropped silently:
//! 1. **Rows.** A row shorter than the columns read need is an error
//!    ([`FlightLogError::TruncatedRow`]), unless it is the file's last row (a log cut off
//!    while being written): skipped with a warning. A row whose time or altitude is not a
//!    finite number in the plausible range (|t| ≤ 10⁶ s, |h| ≤ 200 km, 0 < p ≤ 200 kPa) is
//!    skipped; an unreadable optional value (NaN) leaves that channel empty on that sample.
//! 2. **Clock order.** A row whose time is not later than the last kept row's (a repeated
//!    time, a clock going back) is dropped.
//! 3. **Height above ground.** AGL logs as the device zeroed them (negative start-up
//!    altitudes, a pressure artefact of some devices, are kept as recorded and reported);
//!    MSL logs minus the mean of the first 0.5 s; barometer-only logs as the ISA pressure
//!    altitude above the mean pressure of the first 0.5 s (ISO 2533 troposphere).
//! 4. **Glitch rows.** A sample whose height differs from the last kept one by more than
//!    1500 m/s · Δt + 5 m is dropped; after 5 such rows in a row the next is accepted as a new
//!    level.
//! 5. **Velocity.** The device's vertical velocity where it writes one; otherwise (and on
//!    samples where the device's value is unreadable) the centred least-squares slope of the
//!    height over the samples within ±0.5 s (at most 50 each side, at least one neighbour).
//! 6. **Liftoff.** The first sample at or above 10 m AGL from which the height is still
//!    rising 1 s later by more than 10 m, backed off to the start of that rise: to earlier
//!    samples while each is lower than the next or higher than 1.5 m AGL (pad noise below
//!    that band ends the back-off), at most 2 s back. When the log has an acceleration
//!    channel, the start is instead the first sample of the 2 s before the crossing whose
//!    acceleration exceeds the mean of the first 0.5 s by 2 g (if there is one). Its device time is the
//!    samples' time zero ([`FlightLog::liftoff_device_time_s`]). No such sample is
//!    [`FlightLogError::NoLiftoff`].
//! 7. **Events.** Launch at 0; apogee at the highest sample after liftoff (always derived);
//!    burnout, deployments and landing as the device records them, otherwise burnout at the
//!    highest vertical velocity between liftoff and apogee and landing at the first sample
//!    after apogee at or below 5 m AGL ([`EventSource`] says which).
//!
//! Reading is linear in the file's size and never panics on any input (empty files, binary
//! data, 10 000-column lines, huge numbers, NaN are errors or warnings). Its memory is
//! bounded by the record it returns: the rows are parsed again for each pass a format reader
//! makes instead of being kept as a table, they are read straight into the record's
//! [`Sample`]s, and normalisation works on those in place, so that beside the text (which
//! [`read`] releases before normalising) and the record, reading holds at most three numbers
//! and a line number per row (tested with a counting allocator in `tests/memory.rs`: 128
//! bytes a row in all for a 1 kHz log, of which 104 the record; a 100 MB, 4.9 million-row
//! file peaks at 0.64 GB resident, of which 0.51 GB the record).
//!
//! # Comparison with a simulation
//! [`compare`] sets a log against a simulated flight given as plain series
//! ([`SimulatedFlight`]): apogee and its time, the highest vertical velocity, the RMS
//! altitude and velocity differences over the ascent, the descent rate under each
//! parachute and the landing points; its module documentation states the rules (time axis,
//! pad height, descent bands, GNSS landing point).
//!
//! The modules are private; everything public is re-exported here.

mod altus;
mod blueraven;
mod cats;
mod compare;
mod eggtimer;
mod error;
mod format;
mod log;
mod mapping;
mod normalise;
mod perfectflite;
mod raven;
mod raw;
mod rrc3;
mod table;
mod units;

pub use compare::{
    CompareError, Comparison, Deployment, DescentPhase, FIRST_MOTION_M, Figures, LandingPoints,
    MIN_DESCENT_SAMPLES, MIN_DESCENT_SPAN_S, SimulatedFlight, SimulatedLanding, compare,
    first_motion_time,
};
pub use error::FlightLogError;
pub use format::{Format, detect};
pub use log::{Event, EventKind, EventSource, FlightLog, Gnss, Reported, Sample, VelocitySource};
pub use mapping::ColumnMapping;
pub use normalise::{
    BACKOFF_MAX_S, GLITCH_MARGIN_M, GLITCH_RUN, GLITCH_SPEED_MPS, GROUND_BAND_M, GROUND_WINDOW_S,
    LANDING_HEIGHT_M, LIFTOFF_ACCELERATION_MPS2, LIFTOFF_HEIGHT_M, RISE_CHECK_S, RISE_GAIN_M,
    VELOCITY_HALF_WINDOW_S, VELOCITY_MAX_NEIGHBOURS,
};
pub use units::Unit;

use std::path::Path;

/// How to read a log: a format to use instead of detection, a column mapping (which makes it
/// a [`Format::Generic`] log).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ReadOptions {
    /// The format, instead of detecting it.
    pub format: Option<Format>,
    /// A column mapping: read as a generic CSV.
    pub mapping: Option<ColumnMapping>,
}

impl ReadOptions {
    /// The options a user names as text: a format name (`rrc3`, [`Format`]'s names) and a
    /// column mapping ([`ColumnMapping::parse`]), either absent.
    ///
    /// # Errors
    /// [`FlightLogError`] for an unknown format name or a malformed mapping.
    pub fn named(format: Option<&str>, mapping: Option<&str>) -> Result<Self, FlightLogError> {
        Ok(ReadOptions {
            format: format.map(str::parse::<Format>).transpose()?,
            mapping: mapping.map(ColumnMapping::parse).transpose()?,
        })
    }
}

/// Reads and normalises the log at `path`, its format detected.
///
/// # Errors
/// See [`FlightLogError`]: unreadable, empty or binary file, unknown format, malformed data,
/// no liftoff.
pub fn read(path: impl AsRef<Path>) -> Result<FlightLog, FlightLogError> {
    read_with(path, &ReadOptions::default())
}

/// Reads and normalises the log at `path` with `options`.
///
/// # Errors
/// As [`read`].
pub fn read_with(
    path: impl AsRef<Path>,
    options: &ReadOptions,
) -> Result<FlightLog, FlightLogError> {
    let path = path.as_ref();
    let file = path.display().to_string();
    let io = |message: String| FlightLogError::Io {
        file: file.clone(),
        message,
    };
    // Only a regular file (or a link to one) is read: a FIFO blocks whoever opens it and a
    // device such as `/dev/zero` never ends.
    let metadata = std::fs::metadata(path).map_err(|e| io(e.to_string()))?;
    if !metadata.is_file() {
        return Err(io(
            "not a regular file (a directory, FIFO, socket or device)".to_owned(),
        ));
    }
    let bytes = std::fs::read(path).map_err(|e| io(e.to_string()))?;
    let raw = read_raw(&bytes, &file, options)?;
    // The text is not needed once its rows are read: normalising works without it.
    drop(bytes);
    normalise::normalise(raw)
}

/// How many leading bytes the binary check looks at.
const BINARY_PROBE: usize = 8192;

/// The first byte that makes `bytes` binary: a NUL anywhere in the first 8 KiB, or more than
/// a tenth of those bytes control characters other than tab, CR, LF and FF.
fn binary_offset(bytes: &[u8]) -> Option<usize> {
    let probe = &bytes[..bytes.len().min(BINARY_PROBE)];
    if let Some(i) = probe.iter().position(|&b| b == 0) {
        return Some(i);
    }
    let control = |b: &u8| b.is_ascii_control() && !matches!(b, b'\t' | b'\r' | b'\n' | 0x0c);
    let count = probe.iter().filter(|b| control(b)).count();
    (count * 10 > probe.len()).then(|| probe.iter().position(control).unwrap_or(0))
}

/// Reads and normalises a log held in memory; `file` names it in errors and warnings.
///
/// # Errors
/// As [`read`].
pub fn parse(bytes: &[u8], file: &str, options: &ReadOptions) -> Result<FlightLog, FlightLogError> {
    normalise::normalise(read_raw(bytes, file, options)?)
}

/// Reads the rows of a log held in memory, before normalisation (the format's reader, the
/// row rules of [`raw::extract`]).
fn read_raw(bytes: &[u8], file: &str, options: &ReadOptions) -> Result<raw::Raw, FlightLogError> {
    if bytes.iter().all(u8::is_ascii_whitespace) {
        return Err(FlightLogError::Empty {
            file: file.to_owned(),
        });
    }
    if let Some(offset) = binary_offset(bytes) {
        let line = 1 + bytes[..offset].iter().filter(|&&b| b == b'\n').count();
        return Err(FlightLogError::Binary {
            file: file.to_owned(),
            line,
            offset,
        });
    }
    let text = String::from_utf8_lossy(bytes);
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
    let raw = if let Some(mapping) = &options.mapping {
        mapping::read(text, file, mapping)?
    } else {
        let format = match options.format {
            Some(f) => f,
            None => detect(text).ok_or_else(|| unknown(text, file))?,
        };
        match format {
            Format::AltusMetrum => altus::read(text, file)?,
            Format::RavenFip => raven::read(text, file)?,
            Format::BlueRaven => blueraven::read(text, file)?,
            Format::PerfectFlitePf2 => perfectflite::read_pf2(text, file)?,
            Format::StratoLoggerText => perfectflite::read_text(text, file)?,
            Format::Rrc3 => rrc3::read(text, file)?,
            Format::Eggtimer => eggtimer::read(text, file)?,
            Format::CatsVega => cats::read(text, file)?,
            Format::Generic => {
                return Err(FlightLogError::Mapping {
                    spec: String::new(),
                    reason: "the generic format needs a column mapping".into(),
                });
            }
        }
    };
    Ok(raw)
}

/// The unknown-format error, quoting the first non-empty line.
fn unknown(text: &str, file: &str) -> FlightLogError {
    let (line, header) = text
        .lines()
        .enumerate()
        .find(|(_, l)| !l.trim().is_empty())
        .map_or((1, ""), |(i, l)| (i + 1, l));
    FlightLogError::UnknownFormat {
        file: file.to_owned(),
        line,
        header: header.chars().take(120).collect(),
    }
}

/// The README's example, compiled and run by `cargo test --doc`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeExample;
