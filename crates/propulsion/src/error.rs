//! The error type of karman-propulsion.
//!
//! Errors on user data name the data source (a file path, or a label such as "inline thrust
//! table" chosen by the caller), the 1-based line (or point number for inline data) and the
//! offending value, so a user can fix the input.

use karman_math::{CsvError, MathError};
use thiserror::Error;

/// Everything that can go wrong while reading thrust data or building a motor.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum PropulsionError {
    /// A thrust file could not be read.
    #[error("{source_name}: cannot read: {message}")]
    Io {
        /// The file.
        source_name: String,
        /// The operating system's message.
        message: String,
    },
    /// A CSV thrust file is unreadable or malformed (the error names file, line, column and
    /// text).
    #[error(transparent)]
    Csv(#[from] CsvError),
    /// A field is not a finite number, or a line does not have the expected fields.
    #[error("{source_name}:{line}: {reason}: '{text}'")]
    Malformed {
        /// The file or data label.
        source_name: String,
        /// 1-based line (point number for inline data).
        line: usize,
        /// The offending text.
        text: String,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// Thrust-curve times must not decrease (a repeated time is a step).
    #[error("{source_name}:{line}: time {time} s goes back in time (previous time {previous} s)")]
    TimeNotIncreasing {
        /// The file or data label.
        source_name: String,
        /// 1-based line (point number for inline data).
        line: usize,
        /// The offending time, s.
        time: f64,
        /// The time before it, s.
        previous: f64,
    },
    /// Negative thrust in a motor file format that only allows non-negative thrust.
    #[error("{source_name}:{line}: negative thrust {thrust} N")]
    NegativeThrust {
        /// The file or data label.
        source_name: String,
        /// 1-based line (point number for inline data).
        line: usize,
        /// The offending thrust, N.
        thrust: f64,
    },
    /// The source holds fewer thrust points than a curve needs.
    #[error("{source_name}: {found} thrust point(s), at least {needed} needed")]
    TooFewPoints {
        /// The file or data label.
        source_name: String,
        /// Points found.
        found: usize,
        /// Points needed.
        needed: usize,
    },
    /// Every point of a thrust curve is at one time: the curve has no burn.
    #[error("{source_name}: every thrust point is at t = {time} s: the curve has no duration")]
    NoDuration {
        /// The file or data label.
        source_name: String,
        /// The one time of every point.
        time: f64,
    },
    /// A repeated time (a step) in a thrust curve whose interpolation is not linear.
    #[error(
        "{source_name}: the time {time} s repeats (a step), which only a linear thrust curve \
         takes; use interpolation = \"linear\" or remove the repeated point"
    )]
    RepeatedTime {
        /// The file or data label.
        source_name: String,
        /// The repeated time, s.
        time: f64,
    },
    /// A RockSim `.rse` file is not well-formed enough to read.
    #[error("{source_name}:{line}: malformed RockSim XML: {reason}")]
    Xml {
        /// The file.
        source_name: String,
        /// 1-based line.
        line: usize,
        /// What is wrong.
        reason: String,
    },
    /// A numeric motor parameter is outside its physical range.
    #[error("{name} = {value}: {reason}")]
    InvalidParameter {
        /// The parameter (RocketPy's argument name).
        name: &'static str,
        /// The value given.
        value: f64,
        /// The constraint it breaks.
        reason: &'static str,
    },
    /// The burn interval is empty or does not overlap the thrust data.
    #[error(
        "burn time [{start}, {end}] s is empty or outside the thrust data [{data_start}, {data_end}] s"
    )]
    InvalidBurnTime {
        /// Requested start, s.
        start: f64,
        /// Requested end, s.
        end: f64,
        /// First time of the thrust data, s.
        data_start: f64,
        /// Last time of the thrust data, s.
        data_end: f64,
    },
    /// A constant thrust needs an explicit burn time.
    #[error("a constant thrust needs a burn_time")]
    MissingBurnTime,
    /// The thrust curve has zero total impulse, so no exhaust velocity can be derived.
    #[error("thrust curve has total impulse {impulse} N·s over the burn; it must be positive")]
    NoImpulse {
        /// The computed impulse, N·s.
        impulse: f64,
    },
    /// The average exhaust velocity `v̄_e = I_tot / m_p0` is zero or not a number, or the mass
    /// flow `−T/v̄_e` it gives overflows (an impulse tiny against the propellant mass).
    #[error(
        "exhaust velocity {exhaust_velocity} m/s (total impulse {impulse} N·s / initial \
         propellant mass {initial_mass} kg) gives no finite mass flow at the peak thrust \
         {peak_thrust} N"
    )]
    ExhaustVelocity {
        /// The total impulse, N·s.
        impulse: f64,
        /// The initial propellant mass, kg.
        initial_mass: f64,
        /// Their ratio, m/s.
        exhaust_velocity: f64,
        /// The largest thrust magnitude of the curve, N.
        peak_thrust: f64,
    },
    /// A tank's fluids over- or underfill it at a node of its time grid (RocketPy's
    /// consistency checks of `Tank`).
    #[error("tank '{tank}': {quantity} {value} at t = {time} s {reason} {limit}")]
    TankContents {
        /// The tank's name.
        tank: String,
        /// The quantity, with its unit.
        quantity: &'static str,
        /// Time of the grid node, s.
        time: f64,
        /// The value there.
        value: f64,
        /// The limit it breaks.
        limit: f64,
        /// How it breaks it.
        reason: &'static str,
    },
    /// A table could not be built from the derived values.
    #[error("{what}: {error}")]
    Table {
        /// Which table.
        what: &'static str,
        /// The underlying error (in the message, not a source of its own: a chain printed
        /// whole would say it twice).
        error: MathError,
    },
}

impl PropulsionError {
    /// Wraps a [`MathError`] raised while building the table `what`.
    pub(crate) fn table(what: &'static str) -> impl FnOnce(MathError) -> PropulsionError {
        move |error| PropulsionError::Table { what, error }
    }
}
