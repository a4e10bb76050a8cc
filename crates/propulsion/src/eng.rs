//! RASP `.eng` thrust files (the format of thrustcurve.org, described at
//! <http://www.thrustcurve.org/raspformat.shtml>).
//!
//! Layout: `;` starts a comment (to the end of the line); the first non-comment line is the
//! header `name diameter_mm length_mm delays propellant_kg total_kg manufacturer`; every later
//! non-blank line is one `time thrust` point (s, N). The format asks for strictly increasing
//! times, non-negative thrust and no `(0, 0)` point.
//!
//! Files as teams ship them: a UTF-8 byte-order mark, CRLF line ends and tabs are accepted;
//! a file whose first non-comment line is already a `time thrust` point has lost its header
//! line: every line is read as data and the file carries a warning (the motor description,
//! and with it the dry mass RocketPy would derive, is unknown).
//!
//! As RocketPy's `Motor.import_eng` (rocketpy/motors/motor.py), a `(0, 0)` point is
//! prepended; the propellant and total masses are read as the third- and second-last header
//! fields. Deviation: a file that (against the format) already starts at `t = 0` keeps its own
//! first point instead of receiving a duplicate time.

use crate::PropulsionError;
use crate::data::{MotorHeader, PointsBuilder, ThrustData, ThrustFormat, parse_number};

/// Parses the text of a RASP `.eng` file; `source_name` names it in errors.
///
/// # Errors
/// [`PropulsionError::Malformed`] (header with fewer than 7 fields or non-numeric
/// dimensions/masses, a data line that is not exactly two numbers),
/// [`PropulsionError::TimeNotIncreasing`], [`PropulsionError::NegativeThrust`], and
/// [`PropulsionError::TooFewPoints`] when the file has no header or no data line.
pub fn parse(text: &str, source_name: &str) -> Result<ThrustData, PropulsionError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut header: Option<MotorHeader> = None;
    let mut headerless = false;
    let mut points = PointsBuilder::new(source_name, ThrustFormat::Eng);
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        let content = raw.split(';').next().unwrap_or("").trim();
        if content.is_empty() {
            continue;
        }
        if header.is_none() && !headerless {
            if is_point(content) {
                headerless = true;
            } else {
                header = Some(parse_header(content, source_name, line)?);
                continue;
            }
        }
        let fields: Vec<&str> = content.split_whitespace().collect();
        let [time_text, thrust_text] = fields[..] else {
            return Err(PropulsionError::Malformed {
                source_name: source_name.to_owned(),
                line,
                text: content.to_owned(),
                reason: "expected a time and a thrust",
            });
        };
        let time = parse_number(source_name, line, time_text)?;
        let thrust = parse_number(source_name, line, thrust_text)?;
        if thrust < 0.0 {
            return Err(points.negative_thrust(line, thrust));
        }
        if points.len() == 0 && time > 0.0 {
            points.push(line, 0.0, 0.0)?;
        }
        points.push(line, time, thrust)?;
    }
    let mut data = points.finish(header, 2)?;
    if headerless {
        data.warnings.push(
            "no RASP header line (name diameter length delays propellant-mass total-mass \
             maker): every line was read as a thrust point and the motor description is \
             unknown"
                .to_owned(),
        );
    }
    Ok(data)
}

/// Whether a line is a `time thrust` point (two numbers) rather than a header.
fn is_point(content: &str) -> bool {
    let mut fields = content.split_whitespace();
    matches!(
        (fields.next(), fields.next(), fields.next()),
        (Some(a), Some(b), None) if a.parse::<f64>().is_ok() && b.parse::<f64>().is_ok()
    )
}

/// Parses `name diameter length delays propellant total manufacturer`.
fn parse_header(
    content: &str,
    source_name: &str,
    line: usize,
) -> Result<MotorHeader, PropulsionError> {
    let fields: Vec<&str> = content.split_whitespace().collect();
    let n = fields.len();
    if n < 7 {
        return Err(PropulsionError::Malformed {
            source_name: source_name.to_owned(),
            line,
            text: content.to_owned(),
            reason: "RASP header needs 7 fields (name diameter length delays propellant-mass total-mass maker)",
        });
    }
    let number = |text: &str| parse_number(source_name, line, text);
    Ok(MotorHeader {
        designation: fields[0].to_owned(),
        diameter: Some(number(fields[1])? / 1000.0),
        length: Some(number(fields[2])? / 1000.0),
        delays: fields[3].to_owned(),
        propellant_mass: Some(number(fields[n - 3])?),
        total_mass: Some(number(fields[n - 2])?),
        manufacturer: fields[n - 1].to_owned(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const M1670: &str =
        "; comment\nM1670-BS 75 757 0 3.101 5.231 CTI \n0.055 100\n0.092 1500 ; c\n\n3.9 0\n";

    #[test]
    fn reads_header_and_prepends_origin() {
        let d = parse(M1670, "m.eng").unwrap();
        assert_eq!(d.times, vec![0.0, 0.055, 0.092, 3.9]);
        assert_eq!(d.thrusts, vec![0.0, 100.0, 1500.0, 0.0]);
        let h = d.header.unwrap();
        assert_eq!(h.designation, "M1670-BS");
        assert_eq!(h.manufacturer, "CTI");
        let dry = h.dry_mass().unwrap();
        assert!((dry - 2.13).abs() < 1e-12, "dry mass {dry}");
        assert!((h.diameter.unwrap() - 0.075).abs() < 1e-15);
    }

    #[test]
    fn errors_name_line_and_value() {
        let e = parse("M 75 757 0 3 5 CTI\n0.1 100\n0.2 1x0\n", "a.eng").unwrap_err();
        assert!(
            matches!(&e, PropulsionError::Malformed { line: 3, text, .. } if text == "1x0"),
            "{e}"
        );
        assert!(e.to_string().starts_with("a.eng:3:"), "{e}");
        // A repeated time is a step (kept); a time going back is an error.
        let d = parse("M 75 757 0 3 5 CTI\n0.2 100\n0.2 50\n0.4 0\n", "a.eng").unwrap();
        assert_eq!(d.times, vec![0.0, 0.2, 0.2, 0.4]);
        let e = parse("M 75 757 0 3 5 CTI\n0.2 100\n0.1 100\n", "a.eng").unwrap_err();
        assert!(
            matches!(e, PropulsionError::TimeNotIncreasing { line: 3, .. }),
            "{e}"
        );
        let e = parse("M 75 757 0 3 5 CTI\n0.2 -100\n", "a.eng").unwrap_err();
        assert!(
            matches!(e, PropulsionError::NegativeThrust { line: 2, .. }),
            "{e}"
        );
        let e = parse("M 75 757 0 3 5 CTI\n0.2 1 3\n", "a.eng").unwrap_err();
        assert!(
            matches!(e, PropulsionError::Malformed { line: 2, .. }),
            "{e}"
        );
        let e = parse("M 75 x 0 3 5 CTI\n0.2 1\n", "a.eng").unwrap_err();
        assert!(
            matches!(e, PropulsionError::Malformed { line: 1, .. }),
            "{e}"
        );
        let e = parse("; only comments\n", "a.eng").unwrap_err();
        assert!(
            matches!(e, PropulsionError::TooFewPoints { found: 0, .. }),
            "{e}"
        );
        let e = parse("M 75 757 0 3 5 CTI\n", "a.eng").unwrap_err();
        assert!(
            matches!(e, PropulsionError::TooFewPoints { found: 0, .. }),
            "{e}"
        );
    }

    #[test]
    fn a_file_without_header_is_all_data_with_a_warning() {
        let with = parse(M1670, "m.eng").unwrap();
        let text = "\u{feff}; no header\r\n0.055\t100\r\n0.092 1500 ; c\r\n\r\n3.9 0\r\n";
        let without = parse(text, "m.eng").unwrap();
        assert_eq!(without.times, with.times);
        assert_eq!(without.thrusts, with.thrusts);
        assert!(without.header.is_none());
        assert_eq!(without.warnings.len(), 1);
        assert!(
            without.warnings[0].starts_with("no RASP header line"),
            "{:?}",
            without.warnings
        );
        assert!(with.warnings.is_empty());
        // A BOM and CRLF line ends before a header change nothing.
        let crlf = format!("\u{feff}{}", M1670.replace('\n', "\r\n"));
        assert_eq!(parse(&crlf, "m.eng").unwrap(), with);
    }

    #[test]
    fn keeps_an_explicit_origin() {
        let d = parse("M 75 757 0 3 5 CTI\n0 0\n1 10\n", "a.eng").unwrap();
        assert_eq!(d.times, vec![0.0, 1.0]);
    }
}
