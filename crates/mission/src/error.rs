//! The error type of karman-mission: every error names the mission file and, where it can,
//! the line, column and dotted key of the problem, or the `--set` override it came from.

use std::fmt;
use std::path::PathBuf;
use thiserror::Error;

/// Where in the input a problem is.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Location {
    /// A position in the mission file, 1-based.
    File {
        /// Line, 1-based.
        line: usize,
        /// Column in characters, 1-based.
        column: usize,
    },
    /// A value given on the command line with `--set`.
    Override {
        /// The override as given, `PATH=VALUE`.
        text: String,
    },
}

/// What is wrong at one place of a mission.
#[derive(Debug, Error)]
pub enum ProblemKind {
    /// The TOML does not fit the schema: an unknown key, a wrong type, a missing key or an
    /// unknown enumeration value (the message is the deserializer's).
    #[error("{message}")]
    Schema {
        /// What the deserializer reported.
        message: String,
    },
    /// A `--set` path (or one of its tables) names nothing in the mission.
    #[error("no such key: {reason}")]
    UnknownPath {
        /// The dotted path.
        path: String,
        /// Why, e.g. which keys exist at the level where the path fails.
        reason: String,
    },
    /// A number is NaN or infinite where a finite value is needed.
    #[error("{value} is not a finite number")]
    NotFinite {
        /// The value.
        value: f64,
    },
    /// A number is outside its valid range.
    #[error("{} is out of range: {expected}", karman_math::text::number(*value))]
    OutOfRange {
        /// The value.
        value: f64,
        /// The valid range, in words.
        expected: &'static str,
    },
    /// A key the chosen model or kind needs is absent.
    #[error("missing key `{key}`, needed by {needed_by}")]
    MissingKey {
        /// The missing key.
        key: &'static str,
        /// The model or kind that needs it, e.g. `a solid motor`.
        needed_by: String,
    },
    /// A key that the chosen model or kind does not use is present.
    #[error("key not used by {model}; remove it")]
    NotApplicable {
        /// The model or kind, e.g. `a generic motor`.
        model: String,
    },
    /// A data file does not exist or cannot be read.
    #[error("cannot read file {}", path.display())]
    File {
        /// The file, resolved against the mission's directory.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A data file has an extension that its key does not accept.
    #[error("file {} has an unsupported extension (expected one of {})", path.display(), expected.join(", "))]
    FileExtension {
        /// The file.
        path: PathBuf,
        /// Accepted extensions.
        expected: &'static [&'static str],
    },
    /// A curve (inline or from a file) is not a valid table.
    #[error("invalid curve")]
    Curve {
        /// What is wrong with it.
        source: CurveError,
    },
    /// A launch date without a UTC offset, or without a time.
    #[error(
        "the date {date} needs a full date, a time and a UTC offset (e.g. 2022-10-14T14:00:00+01:00)"
    )]
    Date {
        /// The date as written.
        date: String,
    },
    /// A value the mission format names but this version of karman cannot model yet.
    #[error("{what} is not supported yet")]
    Unsupported {
        /// What, e.g. `a hybrid motor`.
        what: String,
    },
    /// A parachute trigger expression is not in the expression language.
    #[error("invalid trigger expression{}", quoted_expression(text))]
    Expression {
        /// The expression, as written.
        text: String,
        /// Where in the expression, and why.
        source: karman_script::ExpressionError,
    },
    /// The air-brake controller script does not compile, or the mission sets a constant the
    /// script does not declare.
    #[error("invalid controller script")]
    Script {
        /// The script's file, line, column and message.
        source: Box<karman_script::ScriptError>,
    },
    /// A `[[rocket.sensors]]` entry that cannot be flown as written (a name, a key of another
    /// kind, three values for a one-component sensor).
    #[error("{reason}")]
    Sensor {
        /// Why.
        reason: String,
    },
    /// A `[[stages]]` entry does not fit the stack it belongs to.
    #[error("{reason}")]
    Stage {
        /// Why the stage does not fit.
        reason: String,
    },
    /// A `[dispersion.vary]` entry does not fit its target.
    #[error("{reason}")]
    Distribution {
        /// Why the distribution does not fit.
        reason: String,
    },
}

/// One located problem of a mission.
#[derive(Debug)]
pub struct Problem {
    /// Where it is.
    pub location: Location,
    /// The dotted key it concerns (`rocket.surfaces.fins.span`); empty for the whole file.
    pub key: String,
    /// What is wrong.
    pub kind: ProblemKind,
}

/// Errors of curves read from a mission: inline tables and data files.
#[derive(Debug, Error)]
pub enum CurveError {
    /// The points do not make a table (too few, not finite, ...).
    #[error("not a valid table")]
    Table {
        /// The table error.
        #[from]
        source: karman_math::MathError,
    },
    /// A curve file cannot be read or is not two numeric columns.
    #[error("cannot read the curve file")]
    Csv {
        /// The reader's error (file, line, column, text).
        #[from]
        source: karman_math::CsvError,
    },
}

/// Everything that can go wrong when loading a mission.
#[derive(Debug, Error)]
pub enum MissionError {
    /// The mission file cannot be read.
    #[error("cannot read mission file {}", file.display())]
    Read {
        /// The mission file.
        file: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The mission file is not UTF-8 text (a binary file?).
    #[error("{}:{line}:{column}: not a UTF-8 text file", file.display())]
    NotText {
        /// The mission file.
        file: PathBuf,
        /// Line of the first invalid byte, 1-based.
        line: usize,
        /// Column of the first invalid byte, 1-based.
        column: usize,
    },
    /// The mission file is not valid TOML.
    #[error("{}:{line}:{column}: TOML syntax error: {message}", file.display())]
    Syntax {
        /// The mission file.
        file: PathBuf,
        /// Line, 1-based.
        line: usize,
        /// Column, 1-based.
        column: usize,
        /// The parser's message.
        message: String,
    },
    /// A `--set` argument is not `PATH=VALUE` with a TOML value.
    #[error("--set `{text}`: {reason}")]
    BadOverride {
        /// The argument as given.
        text: String,
        /// What is wrong with it.
        reason: OverrideError,
    },
    /// The mission parses but has problems; all of them are listed.
    #[error("{}", ProblemList { file, problems })]
    Invalid {
        /// The mission file.
        file: PathBuf,
        /// Every problem found, in file order where possible.
        problems: Vec<Problem>,
    },
    /// A model could not be built from a section of the mission (e.g. a thrust file that
    /// fails to parse); the source is the model crate's error.
    #[error("{}", Heading { file, location: location.as_ref(), section, what: "cannot build the model" })]
    Model {
        /// The mission file.
        file: PathBuf,
        /// Where the key `section` was written, when it was.
        location: Option<Location>,
        /// The section or key, e.g. `motor` or `rocket.surfaces.fins`.
        section: String,
        /// The model crate's error.
        source: Box<dyn std::error::Error + Send + Sync>,
    },
    /// The models were built and the flight failed while it flew: the integration (a
    /// non-finite state, a stiff model) or a run-time error of a controller script; the
    /// source says what and when.
    #[error("{}", Heading { file, location: location.as_ref(), section, what: "the flight fails" })]
    Flight {
        /// The mission file.
        file: PathBuf,
        /// Where the key `section` was written, when it was.
        location: Option<Location>,
        /// The section or key, e.g. `flight` or `rocket.air_brakes.controller`.
        section: String,
        /// The engine's or the script's error.
        source: Box<dyn std::error::Error + Send + Sync>,
    },
    /// A curve of the mission could not be turned into a table.
    #[error("{}: curve `{key}`", file.display())]
    Curve {
        /// The mission file.
        file: PathBuf,
        /// The dotted key of the curve, e.g. `rocket.power_off_drag`.
        key: String,
        /// What is wrong.
        source: CurveError,
    },
}

impl MissionError {
    /// This error met while building a part of the mission as a mission of its own
    /// ([`crate::Mission::part`]), named by the part's keys: a model error about a section
    /// under one of `roots` gets `prefix` back (`rocket.mass` → `stages.0.rocket.mass`).
    pub(crate) fn in_part(self, prefix: &str, roots: &[&str]) -> MissionError {
        match self {
            MissionError::Model {
                file,
                location,
                section,
                source,
            } if roots.iter().any(|root| section.starts_with(root)) => MissionError::Model {
                file,
                location,
                section: format!("{prefix}{section}"),
                source,
            },
            MissionError::Flight {
                file,
                location,
                section,
                source,
            } if roots.iter().any(|root| section.starts_with(root)) => MissionError::Flight {
                file,
                location,
                section: format!("{prefix}{section}"),
                source,
            },
            other => other,
        }
    }
}

/// What is wrong with a `--set` argument.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum OverrideError {
    /// No `=` in the argument.
    #[error("expected PATH=VALUE")]
    NoEquals,
    /// The path is empty or has an empty segment.
    #[error("the path `{path}` has an empty segment")]
    EmptySegment {
        /// The path.
        path: String,
    },
    /// A quoted segment of the path is not a TOML string, or is not closed.
    #[error(
        "the path `{path}` has a malformed quoted key `{segment}` (a TOML string: \"rocket.mass\")"
    )]
    QuotedKey {
        /// The path.
        path: String,
        /// The segment.
        segment: String,
    },
    /// The value is not a TOML value.
    #[error("the value `{value}` is not a TOML value ({message}); quote strings: PATH='\"text\"'")]
    Value {
        /// The value text.
        value: String,
        /// The TOML parser's message.
        message: String,
    },
}

/// A `--set PATH=VALUE` argument as a message echoes it: the path whole, the value cut to
/// [`karman_math::text::SHOWN_CHARS`] characters (a 100,000-digit number is not repeated).
/// A number for a message with `decimals` digits after the point (as Rust writes it when
/// `None`), unless its magnitude is absurd (1e9 or more) or too small for those digits: then
/// as [`karman_math::text::number`] shows it, so that `1e300` does not become 301 digits
/// and `1e-300` not a zero.
pub(crate) fn shown_number(value: f64, decimals: Option<usize>) -> String {
    let tiny = 10f64.powi(-i32::try_from(decimals.unwrap_or(4)).unwrap_or(4));
    match decimals {
        _ if value.is_finite() && value != 0.0 && !(tiny..1e9).contains(&value.abs()) => {
            format!("{value:e}")
        }
        Some(decimals) => format!("{value:.decimals$}"),
        None => karman_math::text::number(value),
    }
}

fn shown_override(text: &str) -> String {
    match text.split_once('=') {
        Some((path, value)) => format!("{path}={}", karman_math::text::value(value)),
        None => karman_math::text::value(text).into_owned(),
    }
}

/// Formats the heading of [`MissionError::Model`] and [`MissionError::Flight`]:
/// `file:line:column: `key`: WHAT` (`cannot build the model`, `the flight fails`), or
/// `--set PATH=VALUE: ...` for a key given on the command line.
struct Heading<'a> {
    file: &'a PathBuf,
    location: Option<&'a Location>,
    section: &'a str,
    what: &'a str,
}

impl fmt::Display for Heading<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.location {
            Some(Location::File { line, column }) => {
                write!(f, "{}:{line}:{column}: ", self.file.display())?;
            }
            Some(Location::Override { text }) => {
                write!(
                    f,
                    "{}: --set {}: ",
                    self.file.display(),
                    shown_override(text)
                )?;
            }
            None => write!(f, "{}: ", self.file.display())?,
        }
        write!(f, "`{}`: {}", self.section, self.what)
    }
}

/// Formats the problems of [`MissionError::Invalid`], one per line.
struct ProblemList<'a> {
    file: &'a PathBuf,
    problems: &'a [Problem],
}

impl fmt::Display for ProblemList<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let count = self.problems.len();
        write!(
            f,
            "{}: {count} problem{}",
            self.file.display(),
            if count == 1 { "" } else { "s" }
        )?;
        for problem in self.problems {
            write!(f, "\n  {}", problem.display(self.file))?;
        }
        Ok(())
    }
}

impl Problem {
    /// Formats the problem as `file:line:column: key: message` (or `--set PATH=VALUE: key:
    /// message`), with the whole chain of sources.
    pub fn display<'a>(&'a self, file: &'a std::path::Path) -> impl fmt::Display + 'a {
        DisplayProblem {
            problem: self,
            file,
        }
    }
}

struct DisplayProblem<'a> {
    problem: &'a Problem,
    file: &'a std::path::Path,
}

impl fmt::Display for DisplayProblem<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.problem.location {
            Location::File { line, column } => {
                write!(f, "{}:{line}:{column}: ", self.file.display())?;
            }
            Location::Override { text } => write!(f, "--set {}: ", shown_override(text))?,
        }
        if !self.problem.key.is_empty() {
            write!(f, "`{}`: ", self.problem.key)?;
        }
        write!(f, "{}", self.problem.kind)?;
        let mut source = std::error::Error::source(&self.problem.kind);
        while let Some(cause) = source {
            write!(f, ": {cause}")?;
            source = cause.source();
        }
        Ok(())
    }
}

/// The most characters of an expression an error quotes.
const QUOTED_EXPRESSION_CHARS: usize = 80;

/// ` "TEXT"` for an error: the expression's first [`QUOTED_EXPRESSION_CHARS`] characters,
/// control characters escaped, and the length of what was cut.
fn quoted_expression(text: &str) -> String {
    let count = text.chars().count();
    let head: String = text.chars().take(QUOTED_EXPRESSION_CHARS).collect();
    let head = head.escape_debug();
    if count > QUOTED_EXPRESSION_CHARS {
        format!(" \"{head}…\" ({count} characters)")
    } else {
        format!(" \"{head}\"")
    }
}
