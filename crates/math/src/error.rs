//! The error types of karman-math: [`MathError`] for building and using functions, and
//! [`CsvError`] for reading numeric columns from text files (it names the file, line, column
//! and offending text, so a user can fix the data).

use std::path::PathBuf;

use thiserror::Error;

/// Errors raised when building or evaluating functions from data.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum MathError {
    /// A table needs at least `needed` points.
    #[error("a table needs at least {needed} point(s), got {got}")]
    TooFewPoints {
        /// Minimum number of points for the requested interpolation.
        needed: usize,
        /// Number of points given.
        got: usize,
    },
    /// The x and y columns have different lengths.
    #[error("x has {x} values but y has {y}")]
    LengthMismatch {
        /// Length of the x column.
        x: usize,
        /// Length of the y column.
        y: usize,
    },
    /// A value is NaN or infinite.
    #[error("point {index}: value {value} is not finite")]
    NotFinite {
        /// Zero-based index of the point.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// The abscissae are not strictly increasing (or, for a table that allows repeated
    /// abscissae, they decrease).
    #[error("point {index}: x = {x} does not increase (previous x = {previous})")]
    NotIncreasing {
        /// Zero-based index of the point.
        index: usize,
        /// The offending abscissa.
        x: f64,
        /// The abscissa before it.
        previous: f64,
    },
    /// The values of a table are not strictly monotone, so it has no inverse.
    #[error("point {index}: y = {y} breaks strict monotonicity (previous y = {previous})")]
    NotMonotone {
        /// Zero-based index of the point.
        index: usize,
        /// The offending value.
        y: f64,
        /// The value before it.
        previous: f64,
    },
    /// Finite samples whose interpolant is not: its coefficients overflow (samples extremely
    /// close together or extremely large).
    #[error("interval {interval}: the interpolant's coefficients are not finite")]
    InterpolantNotFinite {
        /// Zero-based index of the first such interval (0 for a single polynomial).
        interval: usize,
    },
    /// The operation needs a tabulated function.
    #[error("{operation} needs a tabulated function")]
    NotTabulated {
        /// What was asked.
        operation: &'static str,
    },
    /// A linear system is singular to working precision.
    #[error("the {size}×{size} linear system is singular")]
    Singular {
        /// Dimension of the system.
        size: usize,
    },
    /// An interval `[a, b]` is empty, reversed where that is not allowed, or not finite.
    #[error("invalid interval [{a}, {b}]")]
    InvalidInterval {
        /// Lower end.
        a: f64,
        /// Upper end.
        b: f64,
    },
    /// Adaptive quadrature used its evaluation budget (or could not split further) before
    /// reaching the requested tolerance.
    #[error(
        "quadrature did not converge: value {value}, error estimate {abs_error} > tolerance \
         {tolerance} after {evaluations} evaluations"
    )]
    QuadratureNotConverged {
        /// Best value found.
        value: f64,
        /// Its absolute error estimate.
        abs_error: f64,
        /// The tolerance that was asked for.
        tolerance: f64,
        /// Number of integrand evaluations spent.
        evaluations: usize,
    },
    /// An N-dimensional grid axis is not usable.
    #[error("grid axis {axis}: {reason}")]
    BadAxis {
        /// Zero-based axis index.
        axis: usize,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// A point of a scattered table repeats an earlier one.
    #[error("point {index} repeats point {first}")]
    RepeatedPoint {
        /// Zero-based index of the repeat.
        index: usize,
        /// Zero-based index of the point it repeats.
        first: usize,
    },
    /// The points of a scattered table of two variables all lie on one line.
    #[error("the points all lie on one line")]
    Collinear,
    /// The number of values does not match the grid or the point dimension.
    #[error("expected {expected} values, got {got}")]
    WrongSize {
        /// Expected count.
        expected: usize,
        /// Count given.
        got: usize,
    },
}

/// Errors raised when reading numeric columns from a text file.
///
/// Lines and columns are 1-based, as a text editor shows them.
#[derive(Debug, Error, Clone, PartialEq, Eq)]
pub enum CsvError {
    /// The file could not be read.
    #[error("{}: cannot read: {message}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's message.
        message: String,
    },
    /// A field is not a number.
    #[error("{}:{line}: column {column}: '{text}' is not a number", path.display())]
    NotNumeric {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The offending field.
        text: String,
    },
    /// A field is NaN or infinite.
    #[error("{}:{line}: column {column}: '{text}' is not finite", path.display())]
    NotFinite {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The offending field.
        text: String,
    },
    /// A comma-separated line has an empty field.
    #[error("{}:{line}: column {column} is empty", path.display())]
    EmptyField {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
    },
    /// A line has a different number of fields from the first data line (or from the
    /// number the caller needs).
    #[error("{}:{line}: expected {expected} columns, found {found}", path.display())]
    WrongColumnCount {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// Expected number of fields.
        expected: usize,
        /// Fields found.
        found: usize,
    },
    /// The file has no data line.
    #[error("{}: no data rows", path.display())]
    NoData {
        /// The file.
        path: PathBuf,
    },
    /// A file read by column names has no header line naming its columns.
    #[error("{}:{line}: expected a header line naming the columns", path.display())]
    NoHeader {
        /// The file.
        path: PathBuf,
        /// 1-based line of the first row, numbers instead of names.
        line: usize,
    },
}
