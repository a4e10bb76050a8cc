//! Two-column thrust files: `time, thrust` per line (s, N).
//!
//! Read with karman-math's CSV reader ([`karman_math::csv`]): comma- or whitespace-separated
//! fields, blank lines and `#` lines skipped, an optional header line, as RocketPy's
//! `Function` CSV source allows. Times must strictly increase. Negative thrust is accepted:
//! measured static-fire curves dip below zero at the end (the Juno III curve does) and
//! RocketPy keeps those values.

use std::path::Path;

use crate::PropulsionError;
use crate::data::{PointsBuilder, ThrustData, ThrustFormat};

/// Parses the text of a two-column thrust file; `source_name` names it in errors.
///
/// # Errors
/// [`PropulsionError::Csv`] for a row without exactly two fields or with a field that is not
/// a finite number, [`PropulsionError::TimeNotIncreasing`], and
/// [`PropulsionError::TooFewPoints`] for a single data row.
pub fn parse(text: &str, source_name: &str) -> Result<ThrustData, PropulsionError> {
    let points = karman_math::csv::parse_curve(text, Path::new(source_name))?;
    let lines = data_lines(text);
    let mut builder = PointsBuilder::new(source_name, ThrustFormat::Csv);
    for (k, [time, thrust]) in points.into_iter().enumerate() {
        builder.push(lines.get(k).copied().unwrap_or(k + 1), time, thrust)?;
    }
    builder.finish(None, 2)
}

/// 1-based line numbers of the data rows, by the reader's rules (blank and `#` lines
/// skipped; the first remaining line skipped when it has a non-numeric field).
fn data_lines(text: &str) -> Vec<usize> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut out = Vec::new();
    let mut first = true;
    for (index, raw) in text.lines().enumerate() {
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let header = first && split(line).any(|f| f.parse::<f64>().is_err());
        first = false;
        if !header {
            out.push(index + 1);
        }
    }
    out
}

fn split(line: &str) -> Box<dyn Iterator<Item = &str> + '_> {
    if line.contains(',') {
        Box::new(line.split(',').map(str::trim))
    } else {
        Box::new(line.split_whitespace())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use karman_math::CsvError;

    #[test]
    fn reads_comma_and_whitespace_with_header() {
        let d = parse("time,thrust\n0,1.5\n0.5, 10\n\n1 -2\n", "c.csv").unwrap();
        assert_eq!(d.times, vec![0.0, 0.5, 1.0]);
        assert_eq!(d.thrusts, vec![1.5, 10.0, -2.0]);
    }

    #[test]
    fn errors_name_line_and_value() {
        let e = parse("0,1\n0.5,abc\n", "c.csv").unwrap_err();
        assert!(
            matches!(&e, PropulsionError::Csv(CsvError::NotNumeric { line: 2, text, .. }) if text == "abc"),
            "{e}"
        );
        assert!(e.to_string().contains("c.csv:2"), "{e}");
        let e = parse("0,1\n0.5,1,2\n", "c.csv").unwrap_err();
        assert!(
            matches!(
                e,
                PropulsionError::Csv(CsvError::WrongColumnCount { line: 2, .. })
            ),
            "{e}"
        );
        let e = parse("# t, f\ntime,thrust\n0,1\n\n1,1\n0.5,2\n", "c.csv").unwrap_err();
        assert!(
            matches!(e, PropulsionError::TimeNotIncreasing { line: 6, .. }),
            "{e}"
        );
        let e = parse("", "c.csv").unwrap_err();
        assert!(
            matches!(e, PropulsionError::Csv(CsvError::NoData { .. })),
            "{e}"
        );
        let e = parse("0,1\n", "c.csv").unwrap_err();
        assert!(
            matches!(e, PropulsionError::TooFewPoints { found: 1, .. }),
            "{e}"
        );
        let e = parse("0,inf\n1,2\n", "c.csv").unwrap_err();
        assert!(
            matches!(e, PropulsionError::Csv(CsvError::NotFinite { line: 1, .. })),
            "{e}"
        );
    }
}
