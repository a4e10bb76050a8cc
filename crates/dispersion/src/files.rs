//! The files of an output directory and the checked reading of `samples.csv`.

use crate::csv;
use crate::error::DispersionError;
use crate::sampling::draw;
use crate::study::Record;
use std::fs::File;
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};

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
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Scan {
    /// Complete, valid rows (the first positions of the shard).
    pub rows: u64,
    /// Of them, failed samples.
    pub failed: u64,
    /// Byte length of the header and those rows; anything after it is a partial line.
    pub valid_len: u64,
    /// Whether the header line is complete.
    pub has_header: bool,
}

/// Scans `samples.csv` of `record`: the header must be the study's and every complete row
/// must be the next sample of the shard with the inputs the study draws for it. A trailing
/// line without its newline (an interrupted write) is not counted. A missing file scans as
/// empty.
pub(crate) fn scan(path: &Path, record: &Record) -> Result<Scan, DispersionError> {
    let mut scan = Scan {
        rows: 0,
        failed: 0,
        valid_len: 0,
        has_header: false,
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
            scan.rows += 1;
            scan.failed += u64::from(row.error.is_some());
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

/// Writes `text` to `path` atomically (a temporary file renamed over it).
pub(crate) fn write_atomic(path: &Path, text: &[u8]) -> Result<(), DispersionError> {
    let mut temporary = path.as_os_str().to_owned();
    temporary.push(".tmp");
    let temporary = PathBuf::from(temporary);
    std::fs::write(&temporary, text).map_err(DispersionError::io(&temporary))?;
    std::fs::rename(&temporary, path).map_err(DispersionError::io(path))
}
