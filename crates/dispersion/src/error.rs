//! The crate's one error type.

use std::path::PathBuf;
use thiserror::Error;

/// Everything that can go wrong in a dispersion study.
#[derive(Debug, Error)]
pub enum DispersionError {
    /// A distribution's parameters are not valid (negative standard deviation, `low > high`,
    /// a non-finite number, an empty choice).
    #[error("input `{input}`: {reason}")]
    InvalidDistribution {
        /// The varied input's name (its dotted path).
        input: String,
        /// Why.
        reason: String,
    },
    /// A valid distribution that does not fit what it varies (a `choice` of fractions for an
    /// integer, a `std` for a curve).
    #[error("input `{input}`: {reason}")]
    DoesNotFit {
        /// The varied input's name.
        input: String,
        /// Why.
        reason: String,
    },
    /// The study itself is not valid (no samples, duplicate names, unknown output names).
    #[error("invalid study: {reason}")]
    InvalidStudy {
        /// Why.
        reason: String,
    },
    /// A `--shard K/N` argument that is not `K/N` with `1 <= K <= N`.
    #[error("invalid shard `{text}`: expected K/N with 1 <= K <= N (e.g. 2/8)")]
    InvalidShard {
        /// The argument as given.
        text: String,
    },
    /// Reading or writing a file failed. (The operating system's error is part of the
    /// message, not a separate source, so that an error chain names it once.)
    #[error("{}: {error}", path.display())]
    Io {
        /// The file or directory.
        path: PathBuf,
        /// The operating system's error.
        error: std::io::Error,
    },
    /// The output directory holds a different study, so it cannot be resumed.
    #[error(
        "{} holds a different study (differs in: {}); use another --out directory or remove it",
        dir.display(),
        fields.join(", ")
    )]
    StudyMismatch {
        /// The output directory.
        dir: PathBuf,
        /// The `study.json` fields that differ (`seed`, `samples`, `inputs`, ...).
        fields: Vec<String>,
    },
    /// Another run (or merge) holds the output directory's lock.
    #[error(
        "{} is being written by another karman run (its study.lock is held); wait for that run \
         to finish or use another directory",
        dir.display()
    )]
    Locked {
        /// The output directory.
        dir: PathBuf,
    },
    /// A kept row of `samples.csv`, flown again on resume, does not give the same row: the
    /// model changed since it was written (another program version, or data the fingerprint
    /// does not cover).
    #[error(
        "{}, line {line}: sample {index} flown again gives another row than the one kept \
         (the model changed since it was written); use another --out directory or remove it",
        file.display()
    )]
    ChangedOutputs {
        /// The file.
        file: PathBuf,
        /// 1-based line number of the kept row.
        line: u64,
        /// The sample index.
        index: u64,
    },
    /// An output directory without `study.json` holds a file the study would write (a
    /// `summary.json` of the user's own): it is not a study's folder, and nothing is replaced.
    #[error(
        "{} holds {file} but no study.json: it is not a study's folder, and the study would replace that file; use another --out directory",
        dir.display()
    )]
    ForeignOutput {
        /// The output directory.
        dir: PathBuf,
        /// The file the study would replace.
        file: &'static str,
    },
    /// `samples.csv` exists without the `study.json` that identifies it.
    #[error("{} has samples.csv but no study.json; it was not written by this program", dir.display())]
    MissingStudy {
        /// The output directory.
        dir: PathBuf,
    },
    /// A complete row of `samples.csv` is malformed (only a trailing partial line is
    /// expected after an interruption, and that one is dropped).
    #[error("{}, line {line}: {reason}", file.display())]
    CorruptSamples {
        /// The file.
        file: PathBuf,
        /// 1-based line number.
        line: u64,
        /// What is wrong.
        reason: String,
    },
    /// A kept row of `samples.csv` whose digest is not the digest of its cells: a cell was
    /// edited after the row was written. Nothing is changed; the folder can be moved aside.
    #[error(
        "{}, line {line}: sample {index} was altered after it was written (its digest \
         {stored:016x} is not the digest of its cells, {computed:016x}){detail}; nothing was \
         changed: move the folder aside and run the study again into another --out directory",
        file.display()
    )]
    TamperedRow {
        /// The file.
        file: PathBuf,
        /// 1-based line number of the row.
        line: u64,
        /// The sample index.
        index: u64,
        /// The digest the row holds.
        stored: u64,
        /// The digest of its other cells.
        computed: u64,
        /// What differs, when known (a resume flies the sample again to say which cells
        /// changed): empty, or `; ` and the cells.
        detail: String,
        /// The row as kept (without its newline).
        row: String,
    },
    /// `study.json` of another version of the file layout.
    #[error(
        "{}: {reason}; it is neither resumed nor merged: move the folder aside and run the study \
         again into another --out directory",
        path.display()
    )]
    OtherVersion {
        /// The file.
        path: PathBuf,
        /// The version it holds.
        version: u32,
        /// Which version it is and what this one reads.
        reason: String,
    },
    /// The output directory's lock file was removed or replaced while the run held it, and
    /// the run cannot hold its replacement (another program locked it, or the directory
    /// itself cannot be locked on this system): the run stops rather than risk a second
    /// writer.
    #[error(
        "{}: study.lock was removed or replaced while this run held it, and another program \
         may be writing the folder; stopped so that no two runs write one study (the rows \
         written are kept: run again to resume)",
        dir.display()
    )]
    LockLost {
        /// The output directory.
        dir: PathBuf,
    },
    /// `study.json` cannot be read back.
    #[error("{}: {message}", path.display())]
    Json {
        /// The file.
        path: PathBuf,
        /// The parser's message.
        message: String,
    },
    /// Shard outputs that do not make up one complete study.
    #[error("cannot merge: {reason}")]
    Merge {
        /// Why.
        reason: String,
    },
    /// The run was stopped before every sample of the shard was written
    /// ([`crate::run_until`]); running it again resumes it.
    #[error("{}: interrupted after {written} of {total} samples; run again to resume", dir.display())]
    Interrupted {
        /// The output directory.
        dir: PathBuf,
        /// Samples of the shard in `samples.csv`.
        written: u64,
        /// Samples in the shard.
        total: u64,
    },
    /// A study in memory ([`crate::run_in_memory`]) was stopped before every sample was
    /// flown.
    #[error("stopped after {written} of {total} samples")]
    Stopped {
        /// Samples flown, in index order from the first.
        written: u64,
        /// Samples in the study.
        total: u64,
    },
    /// The worker thread pool could not be created.
    #[error("cannot start {threads} worker threads: {message}")]
    ThreadPool {
        /// Threads asked for.
        threads: usize,
        /// The error.
        message: String,
    },
    /// Drawing a plot failed.
    #[error("{}: cannot draw the plot: {message}", path.display())]
    Plot {
        /// The SVG file.
        path: PathBuf,
        /// The plotting library's message.
        message: String,
    },
}

impl DispersionError {
    /// Wraps an I/O error with the path it concerns.
    pub(crate) fn io(path: impl Into<PathBuf>) -> impl FnOnce(std::io::Error) -> Self {
        let path = path.into();
        move |error| DispersionError::Io { path, error }
    }
}
