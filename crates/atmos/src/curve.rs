//! User profiles of height: a constant or a table of `(height, value)` points, and the parser
//! of the two-column text tables (CSV or whitespace separated, one optional header line) that
//! custom atmospheres load from files (mission-format.md "curve").

use crate::AtmosError;
use crate::error::snippet;
use karman_math::{Extrapolation, Interpolation, Table1};

/// A profile of height above sea level given by the user.
#[derive(Debug, Clone, PartialEq)]
pub enum Curve {
    /// The same value at every height.
    Constant(f64),
    /// `(height m ASL, value)` points in any order; they are sorted by height, stably, and a
    /// repeated height keeps its first value.
    Points(Vec<[f64; 2]>),
}

impl Curve {
    /// Builds the table of this curve (linear, constant extrapolation unless told otherwise).
    /// A constant becomes a one-point table.
    ///
    /// # Errors
    /// [`AtmosError::Empty`] for no points, [`AtmosError::Table`] for non-finite values.
    pub fn to_table(
        &self,
        source_name: &str,
        quantity: &str,
        interpolation: Interpolation,
        extrapolation: Extrapolation,
    ) -> Result<Table1, AtmosError> {
        let (xs, ys) = match self {
            Curve::Constant(v) => (vec![0.0], vec![*v]),
            Curve::Points(points) => sorted_unique(points),
        };
        if xs.is_empty() {
            return Err(AtmosError::Empty {
                source_name: source_name.into(),
                what: format!("the {quantity} profile"),
            });
        }
        Table1::new(xs, ys, interpolation, extrapolation).map_err(|error| AtmosError::Table {
            source_name: source_name.into(),
            quantity: quantity.into(),
            error,
        })
    }

    /// The sorted, de-duplicated abscissae of a tabulated curve (`None` for a constant).
    #[must_use]
    pub fn heights(&self) -> Option<Vec<f64>> {
        match self {
            Curve::Constant(_) => None,
            Curve::Points(p) => Some(sorted_unique(p).0),
        }
    }
}

/// Sorts points by x (stable) and keeps the first of repeated x values.
pub(crate) fn sorted_unique(points: &[[f64; 2]]) -> (Vec<f64>, Vec<f64>) {
    let mut sorted = points.to_vec();
    sorted.sort_by(|a, b| a[0].total_cmp(&b[0]));
    let mut xs: Vec<f64> = Vec::with_capacity(sorted.len());
    let mut ys = Vec::with_capacity(sorted.len());
    for [x, y] in sorted {
        if xs.last().is_some_and(|&last: &f64| (x - last).abs() <= 0.0) {
            continue;
        }
        xs.push(x);
        ys.push(y);
    }
    (xs, ys)
}

/// Parses a two-column numeric table: fields separated by a comma and/or whitespace, blank
/// lines and `#` comments ignored, one optional (non-numeric) header line before the data.
///
/// # Errors
/// [`AtmosError::Parse`] naming the line for a row that is not two finite numbers (or a second
/// header), [`AtmosError::Empty`] when no data row exists.
pub fn parse_table(text: &str, source_name: &str) -> Result<Vec<[f64; 2]>, AtmosError> {
    let mut points = Vec::new();
    let mut header_seen = false;
    for (i, raw) in text.lines().enumerate() {
        let line = raw.trim().trim_start_matches('\u{feff}');
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|f| !f.is_empty())
            .collect();
        let numbers: Vec<Option<f64>> = fields.iter().map(|f| parse_number(f)).collect();
        let err = |message: &str| AtmosError::Parse {
            source_name: source_name.into(),
            line: i + 1,
            message: message.into(),
            text: snippet(raw),
        };
        if numbers.iter().all(Option::is_none) && points.is_empty() && !header_seen {
            header_seen = true;
            continue;
        }
        match numbers.as_slice() {
            [Some(x), Some(y)] if x.is_finite() && y.is_finite() => points.push([*x, *y]),
            [Some(_), Some(_)] => return Err(err("values must be finite")),
            [_, _] => return Err(err("expected two numbers")),
            _ => {
                return Err(err(&format!(
                    "expected two columns, found {}",
                    fields.len()
                )));
            }
        }
    }
    if points.is_empty() {
        return Err(AtmosError::Empty {
            source_name: source_name.into(),
            what: "table".into(),
        });
    }
    Ok(points)
}

/// Parses a number, accepting surrounding double quotes.
fn parse_number(field: &str) -> Option<f64> {
    field
        .trim_matches('"')
        .trim_matches('\'')
        .parse::<f64>()
        .ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_with_header_and_whitespace_tables() {
        let p = parse_table("height,wind\n0, 5\n1000,7.5\n", "t.csv").expect("parses");
        assert_eq!(p, vec![[0.0, 5.0], [1000.0, 7.5]]);
        let q = parse_table("# comment\n0 1\n\n10\t2\n", "t.txt").expect("parses");
        assert_eq!(q, vec![[0.0, 1.0], [10.0, 2.0]]);
    }

    #[test]
    fn errors_name_the_line() {
        let e = parse_table("h,p\n0,1\n5,x\n", "bad.csv").expect_err("fails");
        assert!(matches!(e, AtmosError::Parse { line: 3, .. }), "{e}");
        let e = parse_table("0,1,2\n", "bad.csv").expect_err("fails");
        assert!(e.to_string().contains("line 1"), "{e}");
        assert!(parse_table("a,b\n", "empty.csv").is_err());
        assert!(parse_table("0,inf\n", "inf.csv").is_err());
    }

    #[test]
    fn curve_table_sorts_and_dedupes() {
        let c = Curve::Points(vec![[10.0, 1.0], [0.0, 0.0], [10.0, 5.0]]);
        let t = c
            .to_table(
                "inline",
                "wind_u",
                Interpolation::Linear,
                Extrapolation::Constant,
            )
            .expect("table");
        assert_eq!(t.xs(), &[0.0, 10.0]);
        assert_eq!(t.ys(), &[0.0, 1.0]);
        let k = Curve::Constant(3.0)
            .to_table(
                "inline",
                "t",
                Interpolation::Linear,
                Extrapolation::Constant,
            )
            .expect("table");
        assert!((k.eval(1e4) - 3.0).abs() < 1e-15);
    }
}
