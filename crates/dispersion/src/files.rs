//! The files of an output directory, its lock, atomic writes and the checked reading of
//! `samples.csv`.

use crate::csv::{self, Counts};
use crate::error::DispersionError;
use crate::sampling::draw;
use crate::study::Record;
use std::fs::{File, OpenOptions};
use std::io::{BufRead, BufReader, Write as _};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// The lock of an output directory: one run (or merge) writes a study at a time.
pub const LOCK_FILE: &str = "study.lock";
/// The study's identity (seed, samples, inputs, outputs, shard, fingerprint).
pub const STUDY_FILE: &str = "study.json";
/// One row per sample, in index order.
pub const SAMPLES_FILE: &str = "samples.csv";
/// Counts, statistics and ellipses.
pub const SUMMARY_FILE: &str = "summary.json";
/// Landing points and ellipses for Google Earth.
pub const KML_FILE: &str = "dispersion.kml";
/// Landing scatter with its ellipses.
pub const LANDING_PLOT_FILE: &str = "landing.svg";
/// Histogram of the chosen output (the apogee).
pub const HISTOGRAM_PLOT_FILE: &str = "apogee_histogram.svg";

/// What a scan of `samples.csv` found.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Scan {
    /// Complete, valid rows (the first positions of the shard).
    pub rows: u64,
    /// Those rows by status.
    pub counts: Counts,
    /// Byte length of the header and those rows; anything after it is a partial line.
    pub valid_len: u64,
    /// Whether the header line is complete.
    pub has_header: bool,
    /// The first and the last complete row (the same row once when there is one): position,
    /// line number and text, for a resume to fly them again.
    pub ends: Vec<(u64, u64, String)>,
}

/// Scans `samples.csv` of `record`: the header must be the study's and every complete row
/// must be the next sample of the shard with the inputs the study draws for it. A trailing
/// line without its newline (an interrupted write) is not counted. A missing file scans as
/// empty.
pub(crate) fn scan(path: &Path, record: &Record) -> Result<Scan, DispersionError> {
    let mut scan = Scan {
        rows: 0,
        counts: Counts::default(),
        valid_len: 0,
        has_header: false,
        ends: Vec::new(),
    };
    let file = match File::open(path) {
        Ok(file) => file,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(scan),
        Err(e) => return Err(DispersionError::io(path)(e)),
    };
    let study = record.study();
    let header = csv::header(&study.columns());
    let corrupt = |line: u64, reason: String| DispersionError::CorruptSamples {
        file: path.to_owned(),
        line,
        reason,
    };
    let mut reader = BufReader::new(file);
    let mut buffer = Vec::new();
    let mut line_number = 0u64;
    let shard_len = record.shard.len(record.samples);
    loop {
        buffer.clear();
        let n = reader
            .read_until(b'\n', &mut buffer)
            .map_err(DispersionError::io(path))?;
        if n == 0 || buffer.last() != Some(&b'\n') {
            // End of file, or a partial last line.
            if !scan.has_header && !header.as_bytes().starts_with(&buffer) {
                return Err(corrupt(1, "not the header of this study".to_owned()));
            }
            return Ok(scan);
        }
        line_number += 1;
        let text = std::str::from_utf8(&buffer)
            .map_err(|_| corrupt(line_number, "not UTF-8 text".to_owned()))?;
        if !scan.has_header {
            if text != header {
                return Err(corrupt(1, "not the header of this study".to_owned()));
            }
            scan.has_header = true;
        } else {
            let row = csv::parse(
                text.trim_end_matches('\n'),
                study.inputs.len(),
                study.outputs.len(),
            )
            .map_err(|reason| corrupt(line_number, reason))?;
            if scan.rows >= shard_len {
                return Err(corrupt(
                    line_number,
                    format!(
                        "more rows than the {shard_len} samples of shard {}",
                        record.shard
                    ),
                ));
            }
            let expected = record.shard.index(scan.rows);
            if row.index != expected {
                return Err(corrupt(
                    line_number,
                    format!("sample {} where sample {expected} was expected", row.index),
                ));
            }
            let drawn = draw(record.seed, row.index, &study.inputs);
            let same = drawn
                .iter()
                .zip(&row.inputs)
                .all(|(a, b)| a.to_bits() == b.to_bits());
            if !same {
                return Err(corrupt(
                    line_number,
                    "its inputs are not the study's draws for this sample (written by another \
                     version or another study)"
                        .to_owned(),
                ));
            }
            scan.counts.add(&row.status);
            let kept = (scan.rows, line_number, text.to_owned());
            match scan.ends.len() {
                0 | 1 => scan.ends.push(kept),
                _ => scan.ends[1] = kept,
            }
            scan.rows += 1;
        }
        scan.valid_len += n as u64;
    }
}

/// Reads the parsed rows of a complete, already scanned `samples.csv`.
pub(crate) fn for_each_row(
    path: &Path,
    inputs: usize,
    outputs: usize,
    mut f: impl FnMut(csv::Row),
) -> Result<(), DispersionError> {
    let file = File::open(path).map_err(DispersionError::io(path))?;
    let mut lines = BufReader::new(file).lines();
    // The header.
    lines
        .next()
        .transpose()
        .map_err(DispersionError::io(path))?;
    for (number, line) in lines.enumerate() {
        let line = line.map_err(DispersionError::io(path))?;
        let row = csv::parse(&line, inputs, outputs).map_err(|reason| {
            DispersionError::CorruptSamples {
                file: path.to_owned(),
                line: number as u64 + 2,
                reason,
            }
        })?;
        f(row);
    }
    Ok(())
}

/// The shard of a record, checked against the study's size.
pub(crate) fn shard_is_complete(scan: &Scan, record: &Record) -> bool {
    scan.rows == record.shard.len(record.samples)
}

/// A temporary file name beside `path`, unique to this process and this call:
/// `.NAME.PID.N.tmp`. Two runs writing into one folder (two `simulate --out` of the same
/// folder) never share a temporary file, and each run removes only its own.
pub fn temporary_path(path: &Path) -> PathBuf {
    static NEXT: AtomicU64 = AtomicU64::new(0);
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    let call = NEXT.fetch_add(1, Ordering::Relaxed);
    path.with_file_name(format!(".{name}.{}.{call}.tmp", std::process::id()))
}

/// Writes `bytes` to `path` atomically: into a temporary file beside it
/// ([`temporary_path`], created new), flushed to the disk, then renamed over `path`. A reader
/// sees the old file or the whole new one, never a part; on an error (a full disk) the
/// temporary file is removed, `path` is left as it was, and the error names `path`.
///
/// # Errors
/// [`DispersionError::Io`] naming `path`.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), DispersionError> {
    let temporary = temporary_path(path);
    let written = OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&temporary)
        .and_then(|mut file| file.write_all(bytes).and_then(|()| file.sync_all()))
        .and_then(|()| std::fs::rename(&temporary, path));
    written.map_err(|e| {
        let _ = std::fs::remove_file(&temporary);
        DispersionError::io(path)(e)
    })
}

/// An exclusive lock on an output directory, held while the value lives. The operating
/// system releases it when the process ends, however it ends (a killed run leaves no stale
/// lock).
#[derive(Debug)]
pub(crate) struct DirLock {
    _file: File,
}

/// Locks the output directory `dir` (creating its [`LOCK_FILE`]); `Locked` when another run
/// holds it. `create` false: a directory without a lock file is not locked (and not touched).
pub(crate) fn lock(dir: &Path, create: bool) -> Result<Option<DirLock>, DispersionError> {
    let path = dir.join(LOCK_FILE);
    let file = if create {
        OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(&path)
    } else {
        match File::open(&path) {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
            other => other,
        }
    }
    .map_err(DispersionError::io(&path))?;
    match fs4::FileExt::try_lock(&file) {
        Ok(()) => Ok(Some(DirLock { _file: file })),
        Err(fs4::TryLockError::WouldBlock) => Err(DispersionError::Locked {
            dir: dir.to_owned(),
        }),
        Err(fs4::TryLockError::Error(e)) => Err(DispersionError::io(&path)(e)),
    }
}
