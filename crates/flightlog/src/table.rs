//! Delimited text into header and rows, each row with its 1-based line in the file.
//!
//! Read with the `csv` crate: quoting, ragged rows (`flexible`), fields trimmed. Linear in the
//! size of the text.

use crate::error::FlightLogError;

/// A header and the data rows under it.
pub(crate) struct Table {
    /// Header fields, trimmed.
    pub header: Vec<String>,
    /// 1-based line of the header.
    pub header_line: usize,
    /// Data rows in file order.
    pub rows: Vec<Row>,
    /// File this came from (for errors and warnings).
    pub file: String,
}

/// One data row.
pub(crate) struct Row {
    /// 1-based line in the file.
    pub line: usize,
    /// Fields, trimmed.
    pub fields: csv::StringRecord,
}

impl Table {
    /// Reads `text`, whose first line is line `first_line` of the file. The header is
    /// `given` (then every line is data, and `first_line - 1` is the header's line), else the
    /// first non-empty line. Blank lines are skipped.
    pub fn read(
        text: &str,
        first_line: usize,
        delimiter: u8,
        file: &str,
        given: Option<Vec<String>>,
    ) -> Result<Table, FlightLogError> {
        let mut reader = csv::ReaderBuilder::new()
            .has_headers(false)
            .flexible(true)
            .delimiter(delimiter)
            .trim(csv::Trim::All)
            .from_reader(text.as_bytes());
        let mut header: Option<(usize, Vec<String>)> =
            given.map(|h| (first_line.saturating_sub(1), h));
        let mut rows = Vec::new();
        let mut record = csv::StringRecord::new();
        loop {
            match reader.read_record(&mut record) {
                Ok(false) => break,
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
            let line = record.position().map_or(0, |p| p.line() as usize) + first_line - 1;
            if record.iter().all(str::is_empty) {
                continue;
            }
            if header.is_none() {
                header = Some((line, record.iter().map(str::to_owned).collect()));
            } else {
                rows.push(Row {
                    line,
                    fields: record.clone(),
                });
            }
        }
        let Some((header_line, header)) = header else {
            return Err(FlightLogError::Empty {
                file: file.to_owned(),
            });
        };
        Ok(Table {
            header,
            header_line,
            rows,
            file: file.to_owned(),
        })
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
