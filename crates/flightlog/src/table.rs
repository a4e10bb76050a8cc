//! Delimited text into a header and rows, each row with its 1-based line in the file.
//!
//! Read with the `csv` crate: quoting, ragged rows (`flexible`), fields trimmed. A [`Table`]
//! does not keep its rows: [`Table::read`] parses the header and the first data row, and
//! [`Table::rows`] parses the text for each pass a reader makes, one record at a time (most
//! readers make one). Each pass is linear in the size of the text, and the memory of
//! reading is the text and one record, whatever the number of rows: a 100 MB log costs no
//! table of 5 million parsed rows.

use crate::error::FlightLogError;

/// A header and the data rows under it.
pub(crate) struct Table<'t> {
    /// Header fields, trimmed.
    pub header: Vec<String>,
    /// 1-based line of the header.
    pub header_line: usize,
    /// The first data row of the text, if any (before [`Table::keep_only`]).
    pub first: Option<Row>,
    /// File this came from (for errors and warnings).
    pub file: String,
    text: &'t str,
    first_line: usize,
    delimiter: u8,
    /// Whether the header is the text's first non-empty record (else it was given).
    header_in_text: bool,
    /// Only the rows whose field `.0` is `.1` (or that lack the field) are data rows.
    filter: Option<(usize, String)>,
}

/// One data row.
pub(crate) struct Row {
    /// 1-based line in the file.
    pub line: usize,
    /// Fields, trimmed.
    pub fields: csv::StringRecord,
}

/// A pass over the data rows of a [`Table`], one parsed record at a time.
pub(crate) struct Rows<'a> {
    table: &'a Table<'a>,
    reader: csv::Reader<&'a [u8]>,
    row: Row,
    /// Whether the header record is still ahead in the text.
    header_ahead: bool,
}

impl<'a> Rows<'a> {
    /// The next data row, or `None` at the end of the text.
    ///
    /// # Errors
    /// [`FlightLogError::WrongFormat`] at the line of a record the CSV reader cannot parse.
    pub fn next(&mut self) -> Result<Option<&Row>, FlightLogError> {
        loop {
            if !next_record(
                self.table.text.as_bytes(),
                &mut self.reader,
                &mut self.row,
                self.table.first_line,
                &self.table.file,
            )? {
                return Ok(None);
            }
            if self.header_ahead {
                self.header_ahead = false;
                continue;
            }
            if self.table.keeps(&self.row) {
                return Ok(Some(&self.row));
            }
        }
    }
}

/// The 1-based line of `text` where the record at `position` starts. The CSV reader skips
/// empty lines itself and places the record after them at the first one it skipped, and it
/// ends a CRLF record at its CR, placing the next record at the LF (one line early in every
/// CRLF file); the line terminators from there to the record's first byte are counted here.
fn record_line(text: &[u8], position: Option<&csv::Position>) -> usize {
    let Some(position) = position else { return 0 };
    let mut line = position.line() as usize;
    let start = usize::try_from(position.byte()).unwrap_or(usize::MAX);
    for &b in text.get(start..).unwrap_or_default() {
        match b {
            b'\n' => line += 1,
            b'\r' => {}
            _ => break,
        }
    }
    line
}

/// Reads the next non-empty record of `reader` (over `text`) into `row` (its line counted
/// from `first_line`); `false` at the end of the text.
fn next_record(
    text: &[u8],
    reader: &mut csv::Reader<&[u8]>,
    row: &mut Row,
    first_line: usize,
    file: &str,
) -> Result<bool, FlightLogError> {
    loop {
        match reader.read_record(&mut row.fields) {
            Ok(false) => return Ok(false),
            Ok(true) => {}
            Err(e) => {
                let line = e.position().map_or(0, |p| p.line() as usize);
                return Err(FlightLogError::WrongFormat {
                    file: file.to_owned(),
                    line: line + first_line - 1,
                    format: "CSV",
                    reason: e.to_string(),
                });
            }
        }
        row.line = record_line(text, row.fields.position()) + first_line - 1;
        if !row.fields.iter().all(str::is_empty) {
            return Ok(true);
        }
    }
}

/// The CSV reader of every pass: the same settings each time, so each pass sees the records
/// the first one checked.
fn reader(text: &str, delimiter: u8) -> csv::Reader<&[u8]> {
    csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .delimiter(delimiter)
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes())
}

impl<'t> Table<'t> {
    /// Reads `text`, whose first line is line `first_line` of the file. The header is
    /// `given` (then every line is data, and `first_line - 1` is the header's line), else the
    /// first non-empty line. Blank lines are skipped.
    pub fn read(
        text: &'t str,
        first_line: usize,
        delimiter: u8,
        file: &str,
        given: Option<Vec<String>>,
    ) -> Result<Table<'t>, FlightLogError> {
        let mut reader = reader(text, delimiter);
        let mut row = Row {
            line: 0,
            fields: csv::StringRecord::new(),
        };
        let header_in_text = given.is_none();
        let (header_line, header) = match given {
            Some(h) => (first_line.saturating_sub(1), h),
            None => {
                if !next_record(text.as_bytes(), &mut reader, &mut row, first_line, file)? {
                    return Err(FlightLogError::Empty {
                        file: file.to_owned(),
                    });
                }
                (row.line, row.fields.iter().map(str::to_owned).collect())
            }
        };
        let first =
            next_record(text.as_bytes(), &mut reader, &mut row, first_line, file)?.then_some(row);
        Ok(Table {
            header,
            header_line,
            first,
            file: file.to_owned(),
            text,
            first_line,
            delimiter,
            header_in_text,
            filter: None,
        })
    }

    /// A pass over the data rows, in file order.
    pub fn rows(&self) -> Rows<'_> {
        Rows {
            table: self,
            reader: reader(self.text, self.delimiter),
            row: Row {
                line: 0,
                fields: csv::StringRecord::new(),
            },
            header_ahead: self.header_in_text,
        }
    }

    /// At least the number of data rows: the text's lines.
    pub fn row_bound(&self) -> usize {
        1 + self.text.bytes().filter(|&b| b == b'\n').count()
    }

    /// Keeps only the data rows whose field `column` is `value` (or that have no such
    /// field); returns how many rows that drops.
    ///
    /// # Errors
    /// As [`Rows::next`].
    pub fn keep_only(&mut self, column: usize, value: &str) -> Result<usize, FlightLogError> {
        let mut dropped = 0;
        let mut rows = self.rows();
        while let Some(row) = rows.next()? {
            if row.fields.get(column).is_some_and(|v| v != value) {
                dropped += 1;
            }
        }
        self.filter = Some((column, value.to_owned()));
        Ok(dropped)
    }

    /// Whether `row` is a data row under the filter.
    fn keeps(&self, row: &Row) -> bool {
        self.filter
            .as_ref()
            .is_none_or(|(column, value)| row.fields.get(*column).is_none_or(|v| v == value))
    }

    /// Index of the first header field equal to `name` (ASCII case-insensitive).
    pub fn column(&self, name: &str) -> Option<usize> {
        self.header
            .iter()
            .position(|h| h.eq_ignore_ascii_case(name))
    }

    /// Index of the first header field that `pred` accepts (lower-cased).
    pub fn column_where(&self, pred: impl Fn(&str) -> bool) -> Option<usize> {
        self.header
            .iter()
            .position(|h| pred(&h.to_ascii_lowercase()))
    }

    /// A column the format requires, or a [`FlightLogError::WrongFormat`] naming it.
    pub fn require(&self, name: &str, format: &'static str) -> Result<usize, FlightLogError> {
        self.column(name)
            .ok_or_else(|| FlightLogError::WrongFormat {
                file: self.file.clone(),
                line: self.header_line,
                format,
                reason: format!("no '{name}' column"),
            })
    }
}

/// A field as a finite number (white space and surrounding quotes ignored), or `None`.
pub(crate) fn number(text: &str) -> Option<f64> {
    let t = text.trim().trim_matches('"').trim();
    t.parse::<f64>().ok().filter(|v| v.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lines(table: &Table<'_>) -> Vec<(usize, String)> {
        let mut out = Vec::new();
        let mut rows = table.rows();
        while let Some(row) = rows.next().expect("parses") {
            out.push((row.line, row.fields.iter().collect::<Vec<_>>().join("|")));
        }
        out
    }

    #[test]
    fn each_pass_gives_the_rows_in_order_with_their_lines() {
        let text = "\n a , b \n1,2\n\n3 , 4\n5,6,7\n";
        let table = Table::read(text, 1, b',', "t.csv", None).expect("reads");
        assert_eq!(table.header, ["a", "b"]);
        assert_eq!(table.header_line, 2);
        assert_eq!(table.first.as_ref().map(|r| r.line), Some(3));
        let expected = vec![(3, "1|2".into()), (5, "3|4".into()), (6, "5|6|7".into())];
        assert_eq!(lines(&table), expected);
        assert_eq!(lines(&table), expected, "a second pass reads the same rows");
        assert!(table.row_bound() >= expected.len());
    }

    #[test]
    fn lines_count_the_blank_lines_of_crlf_text() {
        let table = Table::read("a,b\r\n\r\n\r\n1,2\r\n", 1, b',', "t", None).expect("reads");
        assert_eq!(lines(&table), vec![(4, "1|2".into())]);
        // The CSV reader ends a CRLF record at its CR and places the next one at the LF.
        let table = Table::read("a,b\r\n1,2\r\n3,4\r\n", 1, b',', "t", None).expect("reads");
        assert_eq!(table.header_line, 1);
        assert_eq!(lines(&table), vec![(2, "1|2".into()), (3, "3|4".into())]);
    }

    #[test]
    fn a_given_header_makes_every_line_data() {
        let table = Table::read(
            "1,2\n3,4",
            10,
            b',',
            "t",
            Some(vec!["x".into(), "y".into()]),
        )
        .expect("reads");
        assert_eq!(table.header_line, 9);
        assert_eq!(lines(&table), vec![(10, "1|2".into()), (11, "3|4".into())]);
    }

    #[test]
    fn a_filter_keeps_the_rows_of_one_value_and_counts_the_others() {
        let text = "v,id\n1,A\n2,B\n3,A\n4\n";
        let mut table = Table::read(text, 1, b',', "t", None).expect("reads");
        assert_eq!(table.keep_only(1, "A").expect("parses"), 1);
        assert_eq!(
            lines(&table),
            vec![(2, "1|A".into()), (4, "3|A".into()), (5, "4".into())]
        );
    }

    #[test]
    fn an_empty_text_has_no_header() {
        assert!(matches!(
            Table::read("\n \n", 1, b',', "t", None),
            Err(FlightLogError::Empty { .. })
        ));
    }
}
