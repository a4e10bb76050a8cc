//! The error type of karman-flightlog.
//!
//! Every error on a log names the file (or the label the caller gave for in-memory text) and,
//! where one line is at fault, its 1-based line number, so that a user can open the file there.

use thiserror::Error;

/// Everything that stops a log from being read. Problems that leave a usable log (glitch rows,
/// out-of-order clocks, a truncated final row) are not errors: they are listed in
/// [`crate::FlightLog::warnings`].
#[derive(Debug, Error, Clone, PartialEq)]
pub enum FlightLogError {
    /// The file could not be read.
    #[error("{file}: cannot read: {message}")]
    Io {
        /// The file.
        file: String,
        /// The operating system's message.
        message: String,
    },
    /// The file holds no bytes, or only white space.
    #[error("{file}: the file is empty")]
    Empty {
        /// The file.
        file: String,
    },
    /// The file is not text (a NUL byte or mostly control characters).
    #[error("{file}:{line}: binary data, not a text log (byte offset {offset})")]
    Binary {
        /// The file.
        file: String,
        /// 1-based line of the first offending byte.
        line: usize,
        /// 0-based byte offset of the first offending byte.
        offset: usize,
    },
    /// No known format matches the file's header and no column mapping was given.
    #[error(
        "{file}:{line}: unknown log format (header '{header}'); name the format with \
         --format or give a column mapping such as 'time=t,altitude=alt:ft'"
    )]
    UnknownFormat {
        /// The file.
        file: String,
        /// 1-based line of the header looked at.
        line: usize,
        /// The start of that line (at most 120 characters).
        header: String,
    },
    /// A format name that is not one of [`crate::Format::ALL`].
    #[error("unknown format name '{name}' (known: {known})")]
    UnknownFormatName {
        /// The name given.
        name: String,
        /// The known names, comma-separated.
        known: String,
    },
    /// The file does not have the layout of the format it was named or detected as.
    #[error("{file}:{line}: not a {format} log: {reason}")]
    WrongFormat {
        /// The file.
        file: String,
        /// 1-based line.
        line: usize,
        /// The format's name.
        format: &'static str,
        /// What is missing.
        reason: String,
    },
    /// A column mapping string that cannot be parsed.
    #[error("column mapping '{spec}': {reason}")]
    Mapping {
        /// The mapping as given.
        spec: String,
        /// What is wrong with it.
        reason: String,
    },
    /// A column mapping names a column that the header does not have.
    #[error("{file}:{line}: the mapping names column '{column}', which the header does not have")]
    MissingColumn {
        /// The file.
        file: String,
        /// 1-based line of the header.
        line: usize,
        /// The column named.
        column: String,
    },
    /// A data row before the last one has fewer fields than the columns read need.
    #[error("{file}:{line}: truncated row: {found} field(s), {needed} needed")]
    TruncatedRow {
        /// The file.
        file: String,
        /// 1-based line.
        line: usize,
        /// Fields found.
        found: usize,
        /// Fields needed.
        needed: usize,
    },
    /// The format carries no altitude or pressure (e.g. a CATS IMU or GNSS export).
    #[error("{file}: this {format} file has no altitude or pressure channel to read a flight from")]
    NoAltitude {
        /// The file.
        file: String,
        /// The format's name.
        format: &'static str,
    },
    /// No data row could be read.
    #[error("{file}: no readable data rows")]
    NoSamples {
        /// The file.
        file: String,
    },
    /// The altitude never rises as a flight does (see the crate's liftoff rule).
    #[error(
        "{file}: no liftoff found: the altitude never rises above {threshold_m} m AGL and keeps \
         rising (highest {max_altitude_m:.1} m)"
    )]
    NoLiftoff {
        /// The file.
        file: String,
        /// The liftoff threshold, m.
        threshold_m: f64,
        /// The highest altitude read, m AGL.
        max_altitude_m: f64,
    },
}
