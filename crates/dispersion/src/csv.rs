//! The rows of `samples.csv` (RFC 4180): writing them and reading them back.
//!
//! One line per sample: `index,status,error,<inputs>,<outputs>`. `status` is `ok` or
//! `failed`; `error` is empty for `ok`; a missing output is an empty field. Numbers are
//! written in Rust's shortest round-trip form (`{:?}`), so reading a row back gives the very
//! same `f64`. Fields with a comma or a quote are quoted with `"` (quotes doubled); line
//! breaks inside a message become spaces, so every row is exactly one line.

use std::borrow::Cow;
use std::fmt::Write as _;

/// A field as it appears in a row.
pub fn escape(field: &str) -> String {
    let flat: String = field
        .chars()
        .map(|c| if c == '\n' || c == '\r' { ' ' } else { c })
        .collect();
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

/// One sample's row, newline included: its outputs, or for a failed sample the message
/// and `outputs` empty fields.
pub fn row(
    index: u64,
    inputs: &[f64],
    result: Result<&[Option<f64>], &str>,
    outputs: usize,
) -> String {
    let mut line = String::with_capacity(32 + 24 * (inputs.len() + outputs));
    // Writing into a String cannot fail.
    let _ = match result {
        Ok(_) => write!(line, "{index},ok,"),
        Err(message) => write!(line, "{index},failed,{}", escape(message)),
    };
    for value in inputs {
        line.push(',');
        line.push_str(&number(Some(*value)));
    }
    match result {
        Ok(values) => {
            for value in values {
                line.push(',');
                line.push_str(&number(*value));
            }
        }
        Err(_) => line.push_str(&",".repeat(outputs)),
    }
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
    /// `None` for `ok`, the message for `failed`.
    pub error: Option<String>,
    /// Input values.
    pub inputs: Vec<f64>,
    /// Output values (`None`: missing).
    pub outputs: Vec<Option<f64>>,
}

/// Parses a row of a study with `inputs` input and `outputs` output columns; the error
/// says what is wrong.
pub fn parse(line: &str, inputs: usize, outputs: usize) -> Result<Row, String> {
    let fields = split(line).map_err(|_| "badly quoted field".to_owned())?;
    let expected = 3 + inputs + outputs;
    if fields.len() != expected {
        return Err(format!("{} fields, expected {expected}", fields.len()));
    }
    let index = fields[0]
        .parse::<u64>()
        .map_err(|_| format!("index {:?} is not a number", fields[0]))?;
    let error = match fields[1].as_ref() {
        "ok" if fields[2].is_empty() => None,
        "ok" => return Err("status ok with an error message".to_owned()),
        "failed" => Some(fields[2].clone().into_owned()),
        other => return Err(format!("status {other:?} is neither ok nor failed")),
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
    if error.is_some() && output_values.iter().any(Option::is_some) {
        return Err("a failed sample with output values".to_owned());
    }
    Ok(Row {
        index,
        error,
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
        let ok = row(7, &inputs, Ok(&[Some(1.0 / 3.0), None]), 2);
        assert!(ok.ends_with('\n'));
        let parsed = parse(ok.trim_end_matches('\n'), 3, 2).expect("valid row");
        assert_eq!(parsed.index, 7);
        assert_eq!(parsed.error, None);
        assert_eq!(parsed.inputs[1].to_bits(), (-1e-300f64).to_bits());
        assert_eq!(parsed.outputs, vec![Some(1.0 / 3.0), None]);

        let message = "bad \"value\", line\nbreak";
        let failed = row(8, &inputs, Err(message), 2);
        assert_eq!(failed.lines().count(), 1);
        let parsed = parse(failed.trim_end_matches('\n'), 3, 2).expect("valid row");
        assert_eq!(parsed.error.as_deref(), Some("bad \"value\", line break"));
        assert_eq!(parsed.outputs, vec![None, None]);
    }

    #[test]
    fn malformed_rows_are_errors() {
        assert!(parse("1,ok,,2", 2, 0).is_err());
        assert!(parse("x,ok,,2", 1, 0).is_err());
        assert!(parse("1,maybe,,2", 1, 0).is_err());
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
