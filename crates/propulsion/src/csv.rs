//! Two-column thrust files: `time, thrust` per line (s, N).
//!
//! Read with karman-math's CSV reader ([`karman_math::csv`]): comma- or whitespace-separated
//! fields, blank lines and `#` lines skipped, an optional header line, as RocketPy's
//! `Function` CSV source allows. Times must not decrease (a repeated time is a step). Negative thrust is accepted:
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
    let rows = karman_math::csv::parse_curve_rows(text, Path::new(source_name))?;
    let mut builder = PointsBuilder::new(source_name, ThrustFormat::Csv);
    for ([time, thrust], line) in rows.points.into_iter().zip(rows.lines) {
        builder.push(line, time, thrust)?;
    }
    builder.finish(None, 2)
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
