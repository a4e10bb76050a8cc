//! RockSim `.rse` engine files (XML).
//!
//! The file holds `<engine-database><engine-list><engine …><data><eng-data t="…" f="…"
//! m="…" cg="…"/>…</data></engine></engine-list></engine-database>`. As RocketPy's
//! `Motor.import_rse` (rocketpy/motors/motor.py), the first `<engine>` element is read: its
//! attributes `code`, `mfg`, `dia`/`len` (mm), `propWt`/`initWt` (g) and `delays` give the
//! [`MotorHeader`], and its `<eng-data>` elements the `(t, f)` points, used as they are (no
//! point is prepended). Unlike RocketPy, a missing `t` or `f` attribute is an error rather
//! than a silent zero, and times must strictly increase and thrust be non-negative.
//!
//! The reader is a small tolerant tag scanner, not a validating XML parser: it skips the
//! prolog, comments, CDATA and declarations, decodes the five predefined entities in
//! attribute values, and ignores element nesting beyond "inside the first `<engine>`".

use crate::PropulsionError;
use crate::data::{MotorHeader, PointsBuilder, ThrustData, ThrustFormat, parse_number};

/// Parses the text of a RockSim `.rse` file; `source_name` names it in errors.
///
/// # Errors
/// [`PropulsionError::Xml`] for unterminated tags, comments or quotes and a missing
/// `<engine>` element; [`PropulsionError::Malformed`] for a missing or non-numeric
/// attribute; [`PropulsionError::TimeNotIncreasing`], [`PropulsionError::NegativeThrust`],
/// [`PropulsionError::TooFewPoints`] as for the other formats.
pub fn parse(text: &str, source_name: &str) -> Result<ThrustData, PropulsionError> {
    let mut scanner = Scanner {
        text,
        pos: 0,
        line: 1,
        source_name,
    };
    let mut header: Option<MotorHeader> = None;
    let mut points = PointsBuilder::new(source_name, ThrustFormat::Rse);
    while let Some(tag) = scanner.next_tag()? {
        match (&tag, header.is_some()) {
            (
                Tag::Start {
                    name,
                    attributes,
                    line,
                    self_closing,
                },
                false,
            ) if name == "engine" => {
                header = Some(read_header(attributes, source_name, *line)?);
                if *self_closing {
                    break;
                }
            }
            (
                Tag::Start {
                    name,
                    attributes,
                    line,
                    ..
                },
                true,
            ) if name == "eng-data" => {
                let time = required(attributes, "t", source_name, *line)?;
                let thrust = required(attributes, "f", source_name, *line)?;
                if thrust < 0.0 {
                    return Err(points.negative_thrust(*line, thrust));
                }
                points.push(*line, time, thrust)?;
            }
            (Tag::End { name }, true) if name == "engine" => break,
            _ => {}
        }
    }
    if header.is_none() {
        return Err(PropulsionError::Xml {
            source_name: source_name.to_owned(),
            line: scanner.line,
            reason: "no <engine> element".to_owned(),
        });
    }
    points.finish(header, 2)
}

/// The motor description from the `<engine>` attributes.
fn read_header(
    attributes: &[(String, String)],
    source_name: &str,
    line: usize,
) -> Result<MotorHeader, PropulsionError> {
    let text = |key: &str| attribute(attributes, key).unwrap_or("").to_owned();
    let scaled = |key: &str, factor: f64| -> Result<Option<f64>, PropulsionError> {
        attribute(attributes, key)
            .map(|v| parse_number(source_name, line, v).map(|x| x / factor))
            .transpose()
    };
    Ok(MotorHeader {
        designation: text("code"),
        manufacturer: text("mfg"),
        diameter: scaled("dia", 1000.0)?,
        length: scaled("len", 1000.0)?,
        delays: text("delays"),
        propellant_mass: scaled("propWt", 1000.0)?,
        total_mass: scaled("initWt", 1000.0)?,
    })
}

fn attribute<'a>(attributes: &'a [(String, String)], key: &str) -> Option<&'a str> {
    attributes
        .iter()
        .find(|(k, _)| k == key)
        .map(|(_, v)| v.as_str())
}

fn required(
    attributes: &[(String, String)],
    key: &'static str,
    source_name: &str,
    line: usize,
) -> Result<f64, PropulsionError> {
    match attribute(attributes, key) {
        Some(v) => parse_number(source_name, line, v),
        None => Err(PropulsionError::Malformed {
            source_name: source_name.to_owned(),
            line,
            text: format!("<eng-data> without {key}"),
            reason: "missing attribute",
        }),
    }
}

/// A start or end tag.
enum Tag {
    Start {
        name: String,
        attributes: Vec<(String, String)>,
        line: usize,
        self_closing: bool,
    },
    End {
        name: String,
    },
}

/// Walks the text tag by tag, counting lines.
struct Scanner<'a> {
    text: &'a str,
    pos: usize,
    line: usize,
    source_name: &'a str,
}

impl Scanner<'_> {
    fn error(&self, line: usize, reason: &str) -> PropulsionError {
        PropulsionError::Xml {
            source_name: self.source_name.to_owned(),
            line,
            reason: reason.to_owned(),
        }
    }

    /// Moves to byte offset `to` (a char boundary), counting the newlines passed.
    fn advance(&mut self, to: usize) {
        self.line += self.text[self.pos..to].matches('\n').count();
        self.pos = to;
    }

    /// Skips past `terminator` (searched from the current position).
    fn skip_past(&mut self, terminator: &str, what: &str) -> Result<(), PropulsionError> {
        match self.text[self.pos..].find(terminator) {
            Some(offset) => {
                self.advance(self.pos + offset + terminator.len());
                Ok(())
            }
            None => Err(self.error(self.line, &format!("unterminated {what}"))),
        }
    }

    fn next_tag(&mut self) -> Result<Option<Tag>, PropulsionError> {
        loop {
            let Some(offset) = self.text[self.pos..].find('<') else {
                return Ok(None);
            };
            self.advance(self.pos + offset);
            let rest = &self.text[self.pos..];
            if rest.starts_with("<!--") {
                self.skip_past("-->", "comment")?;
            } else if rest.starts_with("<![CDATA[") {
                self.skip_past("]]>", "CDATA section")?;
            } else if rest.starts_with("<?") {
                self.skip_past("?>", "processing instruction")?;
            } else if rest.starts_with("<!") {
                self.skip_past(">", "declaration")?;
            } else {
                return self.tag().map(Some);
            }
        }
    }

    /// Reads the tag starting at the current `<`.
    fn tag(&mut self) -> Result<Tag, PropulsionError> {
        let line = self.line;
        let body_start = self.pos + 1;
        // Find the closing '>' outside quotes.
        let mut quote: Option<char> = None;
        let mut end = None;
        for (i, c) in self.text[body_start..].char_indices() {
            match (quote, c) {
                (Some(q), c) if c == q => quote = None,
                (Some(_), _) => {}
                (None, '"' | '\'') => quote = Some(c),
                (None, '>') => {
                    end = Some(body_start + i);
                    break;
                }
                (None, '<') => return Err(self.error(line, "'<' inside a tag")),
                _ => {}
            }
        }
        let Some(end) = end else {
            return Err(self.error(
                line,
                if quote.is_some() {
                    "unterminated attribute value"
                } else {
                    "unterminated tag"
                },
            ));
        };
        let body = &self.text[body_start..end];
        self.advance(end + 1);
        if let Some(name) = body.strip_prefix('/') {
            return Ok(Tag::End {
                name: name.trim().to_owned(),
            });
        }
        let (body, self_closing) = match body.strip_suffix('/') {
            Some(b) => (b, true),
            None => (body, false),
        };
        let name_end = body.find(|c: char| c.is_whitespace()).unwrap_or(body.len());
        let name = body[..name_end].to_owned();
        if name.is_empty() {
            return Err(self.error(line, "tag without a name"));
        }
        let attributes = parse_attributes(&body[name_end..])
            .ok_or_else(|| self.error(line, "malformed attribute list"))?;
        Ok(Tag::Start {
            name,
            attributes,
            line,
            self_closing,
        })
    }
}

/// Parses `key="value" key2='value'` pairs; `None` when the list is malformed.
fn parse_attributes(mut s: &str) -> Option<Vec<(String, String)>> {
    let mut out = Vec::new();
    loop {
        s = s.trim_start();
        if s.is_empty() {
            return Some(out);
        }
        let eq = s.find('=')?;
        let key = s[..eq].trim();
        if key.is_empty() || key.contains(char::is_whitespace) {
            return None;
        }
        let after = s[eq + 1..].trim_start();
        let quote = after.chars().next().filter(|c| *c == '"' || *c == '\'')?;
        let value_part = &after[1..];
        let close = value_part.find(quote)?;
        out.push((key.to_owned(), decode_entities(&value_part[..close])));
        s = &value_part[close + 1..];
    }
}

/// Decodes the five predefined XML entities.
fn decode_entities(s: &str) -> String {
    s.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&apos;", "'")
        .replace("&amp;", "&")
}

#[cfg(test)]
mod tests {
    use super::*;

    const SAMPLE: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<engine-database>
  <engine-list>
    <!-- a comment with <tags> -->
    <engine mfg="Cesaroni" code="M1670" Type="reload" dia="75." len="757." initWt="5231." propWt="3101." delays="0">
      <comments>text &amp; more</comments>
      <data>
        <eng-data t="0." f="0." m="3101." cg="400."/>
        <eng-data t="0.5" f="1800" m="2900" cg="400"/>
        <eng-data t='3.9' f="0"/>
      </data>
    </engine>
    <engine code="second"><data><eng-data t="9" f="9"/></data></engine>
  </engine-list>
</engine-database>
"#;

    #[test]
    fn reads_first_engine() {
        let d = parse(SAMPLE, "m.rse").unwrap();
        assert_eq!(d.times, vec![0.0, 0.5, 3.9]);
        assert_eq!(d.thrusts, vec![0.0, 1800.0, 0.0]);
        let h = d.header.unwrap();
        assert_eq!(h.designation, "M1670");
        assert!((h.dry_mass().unwrap() - 2.13).abs() < 1e-12);
        assert!((h.diameter.unwrap() - 0.075).abs() < 1e-15);
    }

    #[test]
    fn errors_name_line() {
        let bad = SAMPLE.replace("f=\"1800\"", "f=\"18x0\"");
        let e = parse(&bad, "m.rse").unwrap_err();
        assert!(
            matches!(e, PropulsionError::Malformed { line: 9, .. }),
            "{e}"
        );
        let bad = SAMPLE.replace("t='3.9'", "t='0.2'");
        let e = parse(&bad, "m.rse").unwrap_err();
        assert!(
            matches!(e, PropulsionError::TimeNotIncreasing { line: 10, .. }),
            "{e}"
        );
        let bad = SAMPLE.replace("f=\"1800\"", "f=\"-1\"");
        let e = parse(&bad, "m.rse").unwrap_err();
        assert!(
            matches!(e, PropulsionError::NegativeThrust { line: 9, .. }),
            "{e}"
        );
        let e = parse("<engine-database><engine code=\"x\"", "m.rse").unwrap_err();
        assert!(matches!(e, PropulsionError::Xml { line: 1, .. }), "{e}");
        let e = parse("<a><!-- never closed", "m.rse").unwrap_err();
        assert!(matches!(e, PropulsionError::Xml { .. }), "{e}");
        let e = parse("<a></a>", "m.rse").unwrap_err();
        assert!(e.to_string().contains("no <engine>"), "{e}");
        let e = parse("<engine><data><eng-data f=\"1\"/></data></engine>", "m.rse").unwrap_err();
        assert!(
            matches!(
                e,
                PropulsionError::Malformed {
                    reason: "missing attribute",
                    ..
                }
            ),
            "{e}"
        );
    }
}
