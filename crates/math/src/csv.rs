//! Numeric columns from text files (thrust curves, drag curves, profiles).
//!
//! Format: one row per line; fields separated by commas (a line containing a comma) or else
//! by whitespace, each field trimmed; blank lines and lines starting with `#` are skipped; the
//! first remaining line is a header, and skipped, when one of its fields is not a number. Every
//! other field must be a finite number (Rust's `f64` syntax: `1`, `-2.5`, `3e-4`, `.5`), and
//! every data row must have as many fields as the first. A UTF-8 byte-order mark is ignored
//! and bytes that are not UTF-8 are replaced (and then reported as non-numeric). Errors name
//! the file, the 1-based line and column, and the offending text.

use std::path::{Path, PathBuf};

use crate::CsvError;

/// Longest offending text quoted in an error.
const QUOTE_CHARS: usize = 60;

/// Reads a file of numeric columns; returns one `Vec` per column.
///
/// # Errors
/// [`CsvError`] when the file cannot be read or breaks the format of the module docs.
pub fn read_columns(path: impl AsRef<Path>) -> Result<Vec<Vec<f64>>, CsvError> {
    let path = path.as_ref();
    let text = read_text(path)?;
    parse_columns(&text, path)
}

/// Reads a two-column file as `[x, y]` points, in file order.
///
/// # Errors
/// As [`read_columns`]; [`CsvError::WrongColumnCount`] for a row without exactly two fields.
pub fn read_curve(path: impl AsRef<Path>) -> Result<Vec<[f64; 2]>, CsvError> {
    let path = path.as_ref();
    let text = read_text(path)?;
    parse_curve(&text, path)
}

/// Reads a file of rows of exactly `width` numbers each, in file order (e.g. the
/// `[level, Mach, Cd]` rows of an air-brake table).
///
/// # Errors
/// As [`read_columns`]; [`CsvError::WrongColumnCount`] for a row of another width.
pub fn read_rows(path: impl AsRef<Path>, width: usize) -> Result<Vec<Vec<f64>>, CsvError> {
    let path = path.as_ref();
    let text = read_text(path)?;
    let rows = parse_rows(&text, path, Some(width))?;
    Ok(rows
        .values
        .chunks_exact(width.max(1))
        .map(<[f64]>::to_vec)
        .collect())
}

/// Parses text in the format of the module docs into columns; `origin` names the source in
/// errors.
///
/// # Errors
/// As [`read_columns`].
pub fn parse_columns(text: &str, origin: &Path) -> Result<Vec<Vec<f64>>, CsvError> {
    let rows = parse_rows(text, origin, None)?;
    let count = rows.lines.len();
    let mut columns = vec![Vec::with_capacity(count); rows.width];
    for row in rows.values.chunks_exact(rows.width.max(1)) {
        for (column, value) in columns.iter_mut().zip(row) {
            column.push(*value);
        }
    }
    Ok(columns)
}

/// The columns of a text whose first line names them (`time_s,altitude_agl_m`, a trajectory
/// or a measured flight): the names and the numeric columns in that order, under the rules of
/// [`parse_columns`], with as many fields in every row as the header names.
///
/// # Errors
/// As [`read_columns`]; [`CsvError::NoHeader`] when the first line holds numbers only.
pub fn parse_named_columns(
    text: &str,
    origin: &Path,
) -> Result<(Vec<String>, Vec<Vec<f64>>), CsvError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let first = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .find(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let Some((line, header)) = first else {
        return Err(CsvError::NoData {
            path: origin.to_path_buf(),
        });
    };
    let names: Vec<String> = fields(header).map(str::to_owned).collect();
    if names.iter().all(|name| name.parse::<f64>().is_ok()) {
        return Err(CsvError::NoHeader {
            path: origin.to_path_buf(),
            line,
        });
    }
    let rows = parse_rows(text, origin, Some(names.len()))?;
    let mut columns = vec![Vec::with_capacity(rows.lines.len()); rows.width];
    for row in rows.values.chunks_exact(rows.width.max(1)) {
        for (column, value) in columns.iter_mut().zip(row) {
            column.push(*value);
        }
    }
    Ok((names, columns))
}

/// Parses two-column text into `[x, y]` points; `origin` names the source in errors.
///
/// # Errors
/// As [`read_curve`].
pub fn parse_curve(text: &str, origin: &Path) -> Result<Vec<[f64; 2]>, CsvError> {
    Ok(parse_curve_rows(text, origin)?.points)
}

/// The points of a two-column text and the 1-based line each came from.
#[derive(Debug, Clone, PartialEq)]
pub struct CurveRows {
    /// The `[x, y]` points in file order.
    pub points: Vec<[f64; 2]>,
    /// The line of each point.
    pub lines: Vec<usize>,
}

/// [`parse_curve`] with the line of every point, for readers that check the points further
/// (e.g. increasing times) and must name the line of a point they reject.
///
/// # Errors
/// As [`read_curve`].
pub fn parse_curve_rows(text: &str, origin: &Path) -> Result<CurveRows, CsvError> {
    let rows = parse_rows(text, origin, Some(2))?;
    Ok(CurveRows {
        points: rows.values.chunks_exact(2).map(|r| [r[0], r[1]]).collect(),
        lines: rows.lines,
    })
}

/// Reads the whole of a data file, refusing anything but a regular file (a directory, a FIFO
/// or a device) before opening it: opening a FIFO for reading waits for a writer, and a
/// device may never end. With a [`FileSet`](crate::files::FileSet) installed on the thread,
/// the file is the set's and the file system is not read.
///
/// # Errors
/// The I/O error; [`std::io::ErrorKind::InvalidInput`] for a file that is not regular.
pub fn read_data_file(path: impl AsRef<Path>) -> std::io::Result<Vec<u8>> {
    let path = path.as_ref();
    if let Some(given) = crate::files::installed_read(path) {
        return given;
    }
    let kind = std::fs::metadata(path)?.file_type();
    if !kind.is_file() {
        let what = if kind.is_dir() {
            "a directory"
        } else {
            "a FIFO, socket or device"
        };
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!("not a regular file ({what})"),
        ));
    }
    std::fs::read(path)
}

fn read_text(path: &Path) -> Result<String, CsvError> {
    let bytes = read_data_file(path).map_err(|e| CsvError::Io {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

/// The fields of a line: comma-separated if it has a comma, else whitespace-separated.
fn fields(line: &str) -> impl Iterator<Item = &str> {
    let commas = line.contains(',');
    let (by_comma, by_blank) = if commas {
        (Some(line.split(',').map(str::trim)), None)
    } else {
        (None, Some(line.split_whitespace()))
    };
    by_comma
        .into_iter()
        .flatten()
        .chain(by_blank.into_iter().flatten())
}

/// Numeric rows, stored flat: row `k` is `values[k·width .. (k+1)·width]`, read at line
/// `lines[k]`.
struct Rows {
    width: usize,
    values: Vec<f64>,
    lines: Vec<usize>,
}

fn quote(text: &str) -> String {
    crate::text::shorten(text, QUOTE_CHARS).into_owned()
}

/// Rows of numbers; `width` fixes the number of fields (else the first data row does). Work
/// and memory are linear in the text: one pass, no allocation per row.
fn parse_rows(text: &str, origin: &Path, width: Option<usize>) -> Result<Rows, CsvError> {
    let path = || -> PathBuf { origin.to_path_buf() };
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut rows = Rows {
        width: width.unwrap_or(0),
        values: Vec::new(),
        lines: Vec::new(),
    };
    let mut expected = width;
    let mut header_allowed = true;
    for (index, raw) in text.lines().enumerate() {
        let line_no = index + 1;
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let first_row = std::mem::replace(&mut header_allowed, false);
        if first_row && fields(line).any(|f| f.parse::<f64>().is_err()) {
            continue;
        }
        let start = rows.values.len();
        for (k, field) in fields(line).enumerate() {
            let column = k + 1;
            if field.is_empty() {
                return Err(CsvError::EmptyField {
                    path: path(),
                    line: line_no,
                    column,
                });
            }
            let value: f64 = field.parse().map_err(|_| CsvError::NotNumeric {
                path: path(),
                line: line_no,
                column,
                text: quote(field),
            })?;
            if !value.is_finite() {
                return Err(CsvError::NotFinite {
                    path: path(),
                    line: line_no,
                    column,
                    text: quote(field),
                });
            }
            rows.values.push(value);
        }
        let found = rows.values.len() - start;
        let want = *expected.get_or_insert(found);
        if found != want {
            return Err(CsvError::WrongColumnCount {
                path: path(),
                line: line_no,
                expected: want,
                found,
            });
        }
        rows.width = want;
        rows.lines.push(line_no);
    }
    if rows.lines.is_empty() {
        return Err(CsvError::NoData { path: path() });
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn named_columns_come_with_their_header() {
        let text = "# a comment\ntime_s,altitude_agl_m\n0,1\n0.5,2.5\n";
        let (names, columns) = parse_named_columns(text, Path::new("f.csv")).unwrap();
        assert_eq!(names, ["time_s", "altitude_agl_m"]);
        assert_eq!(columns, [vec![0.0, 0.5], vec![1.0, 2.5]]);
        let e = parse_named_columns("0,1\n1,2\n", Path::new("f.csv")).unwrap_err();
        assert_eq!(
            e,
            CsvError::NoHeader {
                path: "f.csv".into(),
                line: 1
            }
        );
        let e = parse_named_columns("t,h\n0,1,2\n", Path::new("f.csv")).unwrap_err();
        assert!(
            matches!(e, CsvError::WrongColumnCount { line: 2, .. }),
            "{e}"
        );
    }

    fn p() -> &'static Path {
        Path::new("curve.csv")
    }

    #[test]
    fn header_comments_and_separators() {
        let text = "\u{feff}# thrust\nTime (s), Thrust (N)\n\n0, 1\n0.5 , 2e1\n# end\n";
        let pts = parse_curve(text, p()).unwrap();
        assert_eq!(pts, vec![[0.0, 1.0], [0.5, 20.0]]);
        let cols = parse_columns("1 2 3\n4\t5  6\n", p()).unwrap();
        assert_eq!(cols, vec![vec![1.0, 4.0], vec![2.0, 5.0], vec![3.0, 6.0]]);
    }

    #[test]
    fn errors_name_line_column_and_text() {
        let e = parse_curve("x,y\n0,1\n1,abc\n", p()).unwrap_err();
        assert_eq!(
            e,
            CsvError::NotNumeric {
                path: p().into(),
                line: 3,
                column: 2,
                text: "abc".into()
            }
        );
        assert!(
            e.to_string().contains("curve.csv:3: column 2: 'abc'"),
            "{e}"
        );
        let e = parse_curve("0,1\n1,\n", p()).unwrap_err();
        assert!(
            matches!(
                e,
                CsvError::EmptyField {
                    line: 2,
                    column: 2,
                    ..
                }
            ),
            "{e:?}"
        );
        let e = parse_curve("0,1\n1,inf\n", p()).unwrap_err();
        assert!(
            matches!(
                e,
                CsvError::NotFinite {
                    line: 2,
                    column: 2,
                    ..
                }
            ),
            "{e:?}"
        );
        let e = parse_curve("0,nan\n", p()).unwrap_err();
        assert!(
            matches!(
                e,
                CsvError::NotFinite {
                    line: 1,
                    column: 2,
                    ..
                }
            ),
            "{e:?}"
        );
        let e = parse_columns("0,1\n1,2,3\n", p()).unwrap_err();
        assert!(matches!(
            e,
            CsvError::WrongColumnCount {
                line: 2,
                expected: 2,
                found: 3,
                ..
            }
        ));
        let e = parse_curve("0 1 2\n", p()).unwrap_err();
        assert!(matches!(
            e,
            CsvError::WrongColumnCount {
                line: 1,
                expected: 2,
                found: 3,
                ..
            }
        ));
        let e = parse_curve("time,thrust\n# nothing\n", p()).unwrap_err();
        assert!(matches!(e, CsvError::NoData { .. }));
        // Only the first line may be a header.
        let e = parse_curve("0,1\nt,F\n", p()).unwrap_err();
        assert!(matches!(
            e,
            CsvError::NotNumeric {
                line: 2,
                column: 1,
                ..
            }
        ));
        let e = read_curve("/nonexistent/karman/curve.csv").unwrap_err();
        assert!(matches!(e, CsvError::Io { .. }));
    }
}
