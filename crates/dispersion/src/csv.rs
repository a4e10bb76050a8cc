//! The rows of `samples.csv` (RFC 4180): writing them and reading them back.
//!
//! One line per sample: `index,status,error,<inputs>,<outputs>,digest`. `status` is `ok` for a
//! completed flight, the name of the way a flight ended early (`max_time`, `stuck_on_rail`,
//! [`Status::Ended`]) with its message in `error` and the outputs it reached, or `failed` with
//! the error and no outputs; `error` is empty for `ok`; a missing output is an empty field.
//! Numbers are
//! written in Rust's shortest round-trip form (`{:?}`), so reading a row back gives the very
//! same `f64`. Fields with a comma or a quote are quoted with `"` (quotes doubled); line
//! breaks inside a message become spaces, so every row is exactly one line. `digest` is the
//! row's digest ([`digest`]), keyed by the study's fingerprint, which resume and merge check.

use serde::Serialize;
use std::borrow::Cow;
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// How a sample ended.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Status {
    /// The flight the study asked for (status `ok`).
    Completed,
    /// A flight that ended before that (it reached its time limit in the air, never left the
    /// rail): `kind` is the status written (lowercase letters, digits and `_`), `message`
    /// says it in words. Its outputs are kept in `samples.csv` but not in the statistics.
    Ended {
        /// The status word, e.g. `max_time`.
        kind: String,
        /// The explanation.
        message: String,
    },
    /// No flight: the error (status `failed`).
    Failed(String),
}

/// The status written for a failed sample.
pub const FAILED: &str = "failed";
/// The status written for a completed sample.
pub const COMPLETED: &str = "ok";

impl Status {
    /// The word of the `status` column.
    pub fn label(&self) -> &str {
        match self {
            Status::Completed => COMPLETED,
            Status::Ended { kind, .. } => kind,
            Status::Failed(_) => FAILED,
        }
    }

    /// The `error` column: empty for a completed sample.
    pub fn message(&self) -> &str {
        match self {
            Status::Completed => "",
            Status::Ended { message, .. } | Status::Failed(message) => message,
        }
    }

    /// Whether the sample is a completed flight.
    pub fn is_completed(&self) -> bool {
        matches!(self, Status::Completed)
    }
}

/// Whether `kind` can name an early ending: lowercase ASCII letters, digits and `_`, not
/// `ok` or `failed`.
pub fn is_ending_kind(kind: &str) -> bool {
    !kind.is_empty()
        && kind != COMPLETED
        && kind != FAILED
        && kind
            .bytes()
            .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'_')
}

/// Samples counted by how they ended.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize)]
pub struct Counts {
    /// Completed flights: the only ones in the output statistics and the ellipses.
    pub completed: u64,
    /// Flights that ended early ([`Status::Ended`]).
    pub ended_early: u64,
    /// Of them, per status (`max_time`, `stuck_on_rail`, ...).
    pub ended_early_by_status: BTreeMap<String, u64>,
    /// Samples that failed with an error.
    pub failed: u64,
}

impl Counts {
    /// Counts one more sample.
    pub fn add(&mut self, status: &Status) {
        match status {
            Status::Completed => self.completed += 1,
            Status::Ended { kind, .. } => {
                self.ended_early += 1;
                *self.ended_early_by_status.entry(kind.clone()).or_default() += 1;
            }
            Status::Failed(_) => self.failed += 1,
        }
    }

    /// Adds the counts of `other`.
    pub fn merge(&mut self, other: &Counts) {
        self.completed += other.completed;
        self.ended_early += other.ended_early;
        self.failed += other.failed;
        for (kind, n) in &other.ended_early_by_status {
            *self.ended_early_by_status.entry(kind.clone()).or_default() += n;
        }
    }

    /// Every sample counted.
    pub fn total(&self) -> u64 {
        self.completed + self.ended_early + self.failed
    }
}

impl std::fmt::Display for Counts {
    /// `12 completed, 3 ended early (max_time 2, stuck_on_rail 1), 1 failed`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} completed, {} ended early",
            self.completed, self.ended_early
        )?;
        if !self.ended_early_by_status.is_empty() {
            let parts: Vec<String> = self
                .ended_early_by_status
                .iter()
                .map(|(kind, n)| format!("{kind} {n}"))
                .collect();
            write!(f, " ({})", parts.join(", "))?;
        }
        write!(f, ", {} failed", self.failed)
    }
}

/// A message as a row holds it: line breaks become spaces, so that every row is one line.
fn one_line(field: &str) -> String {
    field
        .chars()
        .map(|c| if c == '\n' || c == '\r' { ' ' } else { c })
        .collect()
}

/// A field as it appears in a row.
pub fn escape(field: &str) -> String {
    let flat = one_line(field);
    if flat.contains([',', '"']) {
        format!("\"{}\"", flat.replace('"', "\"\""))
    } else {
        flat
    }
}

/// A number as it appears in a row (empty for a missing value).
pub fn number(value: Option<f64>) -> String {
    value.map_or_else(String::new, |v| format!("{v:?}"))
}

/// The header line, newline included.
pub fn header(columns: &[String]) -> String {
    let mut line = columns
        .iter()
        .map(|c| escape(c))
        .collect::<Vec<_>>()
        .join(",");
    line.push('\n');
    line
}

/// The name of the last column of `samples.csv`: each row's digest ([`digest`]).
pub const DIGEST_COLUMN: &str = "digest";

/// The digest of a row whose other cells are `cells` (the row's text before its last comma)
/// in the study of fingerprint `key`: FNV-1a 64 of `key`, a newline and `cells`, as 16
/// lowercase hexadecimal digits. Keyed by the study, a row copied from another study does not
/// verify; covering the index, a row moved to another line does not either. It detects edits
/// (by hand, by a tool, by a damaged disk), not a forger who recomputes it.
pub fn digest(key: &str, cells: &str) -> String {
    let hash = fnv1a64_parts(&[key.as_bytes(), b"\n", cells.as_bytes()]);
    format!("{hash:016x}")
}

/// FNV-1a 64 of the concatenation of `parts`.
fn fnv1a64_parts(parts: &[&[u8]]) -> u64 {
    const OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    parts
        .iter()
        .flat_map(|part| part.iter())
        .fold(OFFSET, |hash, byte| {
            (hash ^ u64::from(*byte)).wrapping_mul(PRIME)
        })
}

/// Checks the digest (last field) of `line` (without its newline) against `key`: `Err` with
/// the digest written (0 when it is not a number) and the digest of the other cells when they
/// differ (or the line has no digest field).
pub fn verify(line: &str, key: &str) -> Result<(), (u64, u64)> {
    let (cells, stored) = line.rsplit_once(',').unwrap_or(("", line));
    let computed = fnv1a64_parts(&[key.as_bytes(), b"\n", cells.as_bytes()]);
    // Lowercase, as written: an edited case is an edit.
    let written = stored.len() == 16
        && stored
            .bytes()
            .all(|b| matches!(b, b'0'..=b'9' | b'a'..=b'f'));
    match u64::from_str_radix(stored, 16) {
        Ok(value) if written && value == computed => Ok(()),
        Ok(value) => Err((value, computed)),
        Err(_) => Err((0, computed)),
    }
}

/// One sample's row, newline included: its status and message, inputs and `values` (for a
/// failed sample, which has none, `outputs` empty fields), then its digest keyed by `key`
/// (the study's fingerprint, [`digest`]).
pub fn row(
    key: &str,
    index: u64,
    inputs: &[f64],
    status: &Status,
    values: &[Option<f64>],
    outputs: usize,
) -> String {
    let mut line = String::with_capacity(32 + 24 * (inputs.len() + outputs));
    // Writing into a String cannot fail.
    let _ = write!(
        line,
        "{index},{},{}",
        status.label(),
        escape(status.message())
    );
    for value in inputs {
        line.push(',');
        line.push_str(&number(Some(*value)));
    }
    match status {
        Status::Failed(_) => line.push_str(&",".repeat(outputs)),
        _ => {
            for value in values {
                line.push(',');
                line.push_str(&number(*value));
            }
        }
    }
    let digest = digest(key, &line);
    line.push(',');
    line.push_str(&digest);
    line.push('\n');
    line
}

/// Why a line is not a row.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum RowError {
    /// A quoted field is not closed, or a quote is followed by something other than a comma.
    Quoting,
}

/// Splits one line (without its newline) into fields: unquoted fields borrowed from the line,
/// quoted ones unescaped (a summary reads every field of every row).
pub fn split(line: &str) -> Result<Vec<Cow<'_, str>>, RowError> {
    let mut fields = Vec::new();
    let mut rest = line;
    loop {
        if let Some(quoted) = rest.strip_prefix('"') {
            let mut field = String::new();
            let mut chars = quoted.char_indices();
            let after = loop {
                match chars.next() {
                    Some((i, '"')) if quoted[i + 1..].starts_with('"') => {
                        chars.next();
                        field.push('"');
                    }
                    Some((i, '"')) => break &quoted[i + 1..],
                    Some((_, c)) => field.push(c),
                    None => return Err(RowError::Quoting),
                }
            };
            fields.push(Cow::Owned(field));
            match after.strip_prefix(',') {
                Some(next) => rest = next,
                None if after.is_empty() => return Ok(fields),
                None => return Err(RowError::Quoting),
            }
        } else {
            let end = rest.find([',', '"']).unwrap_or(rest.len());
            fields.push(Cow::Borrowed(&rest[..end]));
            match rest[end..].chars().next() {
                Some(',') => rest = &rest[end + 1..],
                Some(_) => return Err(RowError::Quoting),
                None => return Ok(fields),
            }
        }
    }
}

/// A parsed row.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// Sample index.
    pub index: u64,
    /// How it ended.
    pub status: Status,
    /// Input values.
    pub inputs: Vec<f64>,
    /// Output values (`None`: missing).
    pub outputs: Vec<Option<f64>>,
}

impl Row {
    /// The row of `samples.csv` written for these values, as [`parse`] reads it back: the
    /// message on one line, and `outputs` missing values for a failed sample (which has
    /// none). A study kept in memory holds these, so that it is the very study its
    /// `samples.csv` would be.
    pub fn of(
        index: u64,
        inputs: Vec<f64>,
        status: Status,
        values: Vec<Option<f64>>,
        outputs: usize,
    ) -> Self {
        let (status, outputs) = match status {
            Status::Completed => (Status::Completed, values),
            Status::Ended { kind, message } => (
                Status::Ended {
                    kind,
                    message: one_line(&message),
                },
                values,
            ),
            Status::Failed(message) => (Status::Failed(one_line(&message)), vec![None; outputs]),
        };
        Row {
            index,
            status,
            inputs,
            outputs,
        }
    }
}

/// Parses a row (without its newline) of a study with `inputs` input and `outputs` output
/// columns, its last field a digest (16 hexadecimal digits; resume, merge and the summary
/// check it against the study's fingerprint); the error says what is wrong.
pub fn parse(line: &str, inputs: usize, outputs: usize) -> Result<Row, String> {
    let fields = split(line).map_err(|_| "badly quoted field".to_owned())?;
    let expected = 4 + inputs + outputs;
    if fields.len() != expected {
        return Err(format!("{} fields, expected {expected}", fields.len()));
    }
    let digest = &fields[expected - 1];
    if digest.len() != 16 || !digest.bytes().all(|b| b.is_ascii_hexdigit()) {
        return Err(format!(
            "its {DIGEST_COLUMN} {digest:?} is not 16 hexadecimal digits"
        ));
    }
    let fields = &fields[..expected - 1];
    let index = fields[0]
        .parse::<u64>()
        .map_err(|_| format!("index {:?} is not a number", fields[0]))?;
    let message = fields[2].clone().into_owned();
    let status = match fields[1].as_ref() {
        COMPLETED if message.is_empty() => Status::Completed,
        COMPLETED => return Err("status ok with an error message".to_owned()),
        FAILED => Status::Failed(message),
        kind if is_ending_kind(kind) => Status::Ended {
            kind: kind.to_owned(),
            message,
        },
        other => {
            return Err(format!(
                "status {other:?} is not ok, failed or an early ending such as max_time"
            ));
        }
    };
    let value = |text: &Cow<'_, str>| -> Result<Option<f64>, String> {
        if text.is_empty() {
            Ok(None)
        } else {
            text.parse::<f64>()
                .map(Some)
                .map_err(|_| format!("{text:?} is not a number"))
        }
    };
    let mut input_values = Vec::with_capacity(inputs);
    for text in &fields[3..3 + inputs] {
        input_values.push(value(text)?.ok_or("an input value is missing")?);
    }
    let mut output_values = Vec::with_capacity(outputs);
    for text in &fields[3 + inputs..] {
        output_values.push(value(text)?);
    }
    if matches!(status, Status::Failed(_)) && output_values.iter().any(Option::is_some) {
        return Err("a failed sample with output values".to_owned());
    }
    Ok(Row {
        index,
        status,
        inputs: input_values,
        outputs: output_values,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_round_trip() {
        let inputs = [0.1, -1e-300, 12345.678];
        let ok = row(
            "k",
            7,
            &inputs,
            &Status::Completed,
            &[Some(1.0 / 3.0), None],
            2,
        );
        assert!(ok.ends_with('\n'));
        let parsed = parse(ok.trim_end_matches('\n'), 3, 2).expect("valid row");
        assert_eq!(parsed.index, 7);
        assert_eq!(parsed.status, Status::Completed);
        assert_eq!(parsed.inputs[1].to_bits(), (-1e-300f64).to_bits());
        assert_eq!(parsed.outputs, vec![Some(1.0 / 3.0), None]);

        let message = "bad \"value\", line\nbreak";
        let failed = row("k", 8, &inputs, &Status::Failed(message.to_owned()), &[], 2);
        assert_eq!(failed.lines().count(), 1);
        let parsed = parse(failed.trim_end_matches('\n'), 3, 2).expect("valid row");
        assert_eq!(
            parsed.status,
            Status::Failed("bad \"value\", line break".to_owned())
        );
        assert_eq!(parsed.outputs, vec![None, None]);

        let ended = Status::Ended {
            kind: "max_time".to_owned(),
            message: "reached max_time, 5 s".to_owned(),
        };
        let line = row("k", 9, &inputs, &ended, &[Some(2.5), None], 2);
        assert!(
            line.starts_with("9,max_time,\"reached max_time, 5 s\","),
            "{line}"
        );
        let parsed = parse(line.trim_end_matches('\n'), 3, 2).expect("valid row");
        assert_eq!(parsed.status, ended);
        assert_eq!(parsed.outputs, vec![Some(2.5), None]);
    }

    #[test]
    fn rows_in_memory_are_the_rows_read_back() {
        let inputs = vec![0.1, f64::NAN, -0.0];
        let statuses = [
            (Status::Completed, vec![Some(1.0 / 3.0), None]),
            (
                Status::Ended {
                    kind: "max_time".to_owned(),
                    message: "still \"up\",\r\nat 5 s".to_owned(),
                },
                vec![Some(f64::INFINITY), Some(2.0)],
            ),
            (Status::Failed("no\nflight, \"x\"".to_owned()), Vec::new()),
        ];
        for (status, values) in statuses {
            let line = row("k", 4, &inputs, &status, &values, 2);
            let read = parse(line.trim_end_matches('\n'), 3, 2).expect("valid row");
            let kept = Row::of(4, inputs.clone(), status, values, 2);
            assert_eq!(kept.status, read.status);
            assert_eq!(kept.index, read.index);
            let bits =
                |v: &[Option<f64>]| v.iter().map(|x| x.map(f64::to_bits)).collect::<Vec<_>>();
            assert_eq!(bits(&kept.outputs), bits(&read.outputs));
            let inputs_bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(inputs_bits(&kept.inputs), inputs_bits(&read.inputs));
        }
    }

    #[test]
    fn the_digest_covers_every_cell_and_the_key() {
        let line = row("k", 3, &[1.5], &Status::Completed, &[Some(2.0)], 1);
        let line = line.trim_end_matches('\n');
        assert!(verify(line, "k").is_ok(), "{line}");
        assert!(parse(line, 1, 1).is_ok());
        // Another study's key, an edited cell, an edited digest: all detected.
        assert!(verify(line, "other").is_err());
        let edited = line.replacen(",2.0,", ",4.0,", 1);
        let (stored, computed) = verify(&edited, "k").expect_err("edited output");
        assert_ne!(stored, computed);
        assert_eq!(
            format!("{stored:016x}"),
            line.rsplit_once(',').expect("digest").1
        );
        let mut forged = line.to_owned();
        forged.pop();
        forged.push(if line.ends_with('0') { '1' } else { '0' });
        assert!(verify(&forged, "k").is_err());
        assert!(verify("", "k").is_err());
        // The digest field must be one.
        assert!(parse("3,ok,,1.5,2.0,xyz", 1, 1).is_err());
        assert!(parse("3,ok,,1.5,2.0", 1, 1).is_err());
    }

    #[test]
    fn counts_by_status() {
        let mut counts = Counts::default();
        let ended = |kind: &str| Status::Ended {
            kind: kind.to_owned(),
            message: String::new(),
        };
        for status in [
            Status::Completed,
            ended("max_time"),
            Status::Failed("x".to_owned()),
            ended("max_time"),
            ended("stuck_on_rail"),
        ] {
            counts.add(&status);
        }
        assert_eq!(counts.total(), 5);
        assert_eq!(
            counts.to_string(),
            "1 completed, 3 ended early (max_time 2, stuck_on_rail 1), 1 failed"
        );
        assert!(is_ending_kind("max_time") && !is_ending_kind("ok") && !is_ending_kind("Max"));
    }

    #[test]
    fn malformed_rows_are_errors() {
        assert!(parse("1,ok,,2", 2, 0).is_err());
        assert!(parse("x,ok,,2", 1, 0).is_err());
        assert!(parse("1,Maybe,,2", 1, 0).is_err());
        assert!(parse("1,max time,,2", 1, 0).is_err());
        assert!(parse("1,ok,,abc", 1, 0).is_err());
        assert!(parse("1,failed,\"unterminated,2", 1, 0).is_err());
        assert!(parse("1,failed,e,2,3", 1, 1).is_err());
        assert_eq!(split("a,\"b,c\",").expect("valid"), ["a", "b,c", ""]);
        assert_eq!(
            split("\"say \"\"hi\"\"\",é,").expect("valid"),
            ["say \"hi\"", "é", ""]
        );
        assert_eq!(split("").expect("valid"), [""]);
        for bad in ["a\"b", "\"ab", "\"a\"b,c", "x,\"y"] {
            assert!(split(bad).is_err(), "{bad}");
        }
    }
}
