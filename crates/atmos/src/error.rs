//! The error type of karman-atmos.

use karman_math::MathError;
use thiserror::Error;

/// Everything that can go wrong while building an [`crate::Environment`] or reading weather
/// data. Errors on user data name the source (file or inline table), the line or row and the
/// offending value where there is one.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum AtmosError {
    /// A tabulated profile could not be turned into a table.
    #[error("{source_name}: {quantity} profile: {error}")]
    Table {
        /// File or description of the data.
        source_name: String,
        /// Which profile (pressure, temperature, wind_u, ...).
        quantity: String,
        /// The underlying table error.
        error: MathError,
    },
    /// A profile or table has no usable point.
    #[error("{source_name}: {what} has no usable data point")]
    Empty {
        /// File or description of the data.
        source_name: String,
        /// What was empty.
        what: String,
    },
    /// A pressure-level profile with a single usable level: its pressure, temperature and
    /// wind would be one constant value at every height.
    #[error(
        "{source_name}: {what}: only the {level_hpa} hPa level has temperature, height and \
         wind; a profile needs at least two levels"
    )]
    OneLevel {
        /// File or description of the data.
        source_name: String,
        /// Which profile (member and hour).
        what: String,
        /// The one level, hPa.
        level_hpa: f64,
    },
    /// A line of a text table (custom profile or sounding) could not be parsed.
    #[error("{source_name}, line {line}: {message}: `{text}`")]
    Parse {
        /// File or description of the data.
        source_name: String,
        /// One-based line number.
        line: usize,
        /// What was wrong.
        message: String,
        /// The offending text (truncated to 80 characters).
        text: String,
    },
    /// A numeric input is out of its valid range.
    #[error("{what} = {value} is invalid: {reason}")]
    InvalidValue {
        /// The input.
        what: String,
        /// Its value.
        value: f64,
        /// Why it is rejected.
        reason: String,
    },
    /// A pressure profile that is not strictly monotonic has no barometric-height inverse.
    #[error(
        "{source_name}: pressure is not strictly monotonic in height (at {height} m), so \
             it has no inverse for barometric height"
    )]
    NotInvertible {
        /// File or description of the data.
        source_name: String,
        /// Height at which monotonicity breaks.
        height: f64,
    },
    /// A data file could not be read.
    #[error("{file}: cannot read: {message}")]
    Io {
        /// The file.
        file: String,
        /// The system's message.
        message: String,
    },
    /// A download failed or returned something unusable (feature `fetch`).
    #[error("{service}: {message} (request: {request})")]
    Download {
        /// The service ("Open-Meteo", "GFS (THREDDS NCSS)", "University of Wyoming").
        service: String,
        /// The request: the address with its query, shortened to 240 characters for a
        /// one-line message.
        request: String,
        /// What went wrong (timeout, HTTP status, a body cut short or in another format).
        message: String,
    },
    /// A data file (or a downloaded body) is not in the format it should be.
    #[error("{source_name}: not {expected}: {message}")]
    Format {
        /// File or address of the data.
        source_name: String,
        /// The format expected.
        expected: String,
        /// What is wrong.
        message: String,
    },
    /// A netCDF file could not be opened or read.
    #[error("{file}: cannot read netCDF: {message}")]
    NetCdf {
        /// The file.
        file: String,
        /// The reader's message.
        message: String,
    },
    /// A netCDF file lacks variables the chosen dictionary needs.
    #[error(
        "{file}: no variable mapping fits this file (tried `{dictionary}` and the built-in \
             ones): missing {missing}"
    )]
    MissingVariables {
        /// The file.
        file: String,
        /// Name of the requested dictionary.
        dictionary: String,
        /// The variables missing for the requested dictionary.
        missing: String,
    },
    /// A netCDF variable does not have the expected shape.
    #[error("{file}: variable `{variable}`: {message}")]
    BadVariable {
        /// The file.
        file: String,
        /// The variable.
        variable: String,
        /// What is wrong.
        message: String,
    },
    /// The launch date is outside the times covered by a weather file.
    #[error("{file}: launch date {date} is outside the file's times ({first} to {last})")]
    DateOutsideFile {
        /// The file.
        file: String,
        /// The requested date (ISO 8601, UTC).
        date: String,
        /// First time in the file (ISO 8601, UTC).
        first: String,
        /// Last time in the file (ISO 8601, UTC).
        last: String,
    },
    /// The launch site is outside the grid of a weather file.
    #[error(
        "{file}: launch {axis} {value}{unit} is outside the grid, which spans {first}{unit} \
         to {last}{unit}"
    )]
    SiteOutsideGrid {
        /// The file.
        file: String,
        /// "latitude" or "longitude" ("projected x" or "projected y" on a projected grid).
        axis: String,
        /// The unit of the coordinate ("°", or the projected grid's " m" / " km").
        unit: String,
        /// The requested coordinate.
        value: f64,
        /// First grid coordinate.
        first: f64,
        /// Last grid coordinate.
        last: f64,
    },
    /// The requested ensemble member does not exist.
    #[error("{file}: ensemble member {member} does not exist (the file has members 0 to {last})")]
    NoSuchMember {
        /// The file.
        file: String,
        /// The requested member.
        member: usize,
        /// The last member index.
        last: usize,
    },
    /// A name (dictionary, datum) is not recognised.
    #[error("unknown {what} `{name}`; known: {known}")]
    UnknownName {
        /// What kind of name.
        what: String,
        /// The name given.
        name: String,
        /// The accepted names.
        known: String,
    },
    /// A date-dependent model was requested without a launch date.
    #[error("{file}: a launch date is required to read this weather file")]
    DateRequired {
        /// The file.
        file: String,
    },
}

/// User text quoted in an error message, cut to 80 characters ([`karman_math::text`]).
pub(crate) fn snippet(text: &str) -> String {
    karman_math::text::shorten(text, 80).into_owned()
}
