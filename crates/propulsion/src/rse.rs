//! RockSim `.rse` engine files (XML).
//!
//! The file holds `<engine-database><engine-list><engine …><data><eng-data t="…" f="…"
//! m="…" cg="…"/>…</data></engine></engine-list></engine-database>`. As RocketPy's
//! `Motor.import_rse` (rocketpy/motors/motor.py), the first `<engine>` element is read: its
//! attributes `code`, `mfg`, `dia`/`len` (mm), `propWt`/`initWt` (g) and `delays` give the
//! [`MotorHeader`], and its `<eng-data>` elements the `(t, f)` points, used as they are (no
//! point is prepended). Unlike RocketPy, a missing `t` or `f` attribute is an error rather
//! than a silent zero, times must not go back (a repeated time is a step) and thrust must be
//! non-negative.
//!
//! The text is parsed by a conforming XML parser (`roxmltree`): a file that is not
//! well-formed XML is an error naming the line, entities and character references are
//! decoded, and a UTF-8 byte-order mark is ignored.

use roxmltree::{Document, Node, ParsingOptions};

use crate::PropulsionError;
use crate::data::{MotorHeader, PointsBuilder, ThrustData, ThrustFormat, parse_number};

/// Attributes one XML element may have before the text is refused unparsed: the XML parser
/// compares every attribute of an element with every other (duplicates are an error), so an
/// element of 100,000 attributes (a megabyte of text) would take minutes. RockSim and
/// OpenRocket write at most a dozen; the `.ork` reader (karman-openrocket) applies the same
/// limit.
pub const MAX_XML_ATTRIBUTES: usize = 1000;

/// The 1-based line and attribute count of the first element of `text` with more than
/// [`MAX_XML_ATTRIBUTES`] attributes, `None` when there is none. A linear scan of the start
/// tags (an `=` outside quotes is one attribute), which skips comments, CDATA sections,
/// processing instructions and declarations; it never rejects a document the parser would
/// read in reasonable time, and what it lets through the parser checks in full.
pub fn crowded_element(text: &str) -> Option<(usize, usize)> {
    let bytes = text.as_bytes();
    let mut line = 1;
    let mut i = 0;
    let skip_to = |from: usize, end: &[u8]| {
        bytes[from..]
            .windows(end.len())
            .position(|w| w == end)
            .map_or(bytes.len(), |p| from + p + end.len())
    };
    while i < bytes.len() {
        match bytes[i] {
            b'\n' => {
                line += 1;
                i += 1;
            }
            b'<' => {
                let rest = &bytes[i..];
                let end = if rest.starts_with(b"<!--") {
                    skip_to(i + 4, b"-->")
                } else if rest.starts_with(b"<![CDATA[") {
                    skip_to(i + 9, b"]]>")
                } else if rest.starts_with(b"<!") || rest.starts_with(b"<?") {
                    skip_to(i + 2, b">")
                } else {
                    let (start_line, mut count, mut quote) = (line, 0, None);
                    let mut j = i + 1;
                    while j < bytes.len() {
                        let b = bytes[j];
                        match quote {
                            Some(q) if b == q => quote = None,
                            Some(_) => {}
                            None if b == b'"' || b == b'\'' => quote = Some(b),
                            None if b == b'=' => count += 1,
                            None if b == b'>' => break,
                            None => {}
                        }
                        j += 1;
                    }
                    if count > MAX_XML_ATTRIBUTES {
                        return Some((start_line, count));
                    }
                    j
                };
                line += bytes[i..end.min(bytes.len())]
                    .iter()
                    .filter(|&&b| b == b'\n')
                    .count();
                i = end.max(i + 1);
            }
            _ => i += 1,
        }
    }
    None
}

/// Parses the text of a RockSim `.rse` file; `source_name` names it in errors.
///
/// # Errors
/// [`PropulsionError::Xml`] for text that is not well-formed XML and a missing `<engine>`
/// element; [`PropulsionError::Malformed`] for a missing or non-numeric attribute;
/// [`PropulsionError::TimeNotIncreasing`], [`PropulsionError::NegativeThrust`],
/// [`PropulsionError::TooFewPoints`] as for the other formats.
pub fn parse(text: &str, source_name: &str) -> Result<ThrustData, PropulsionError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let xml_error = |line: u32, reason: String| PropulsionError::Xml {
        source_name: source_name.to_owned(),
        line: line as usize,
        reason,
    };
    // RockSim files may carry a document type declaration.
    let options = ParsingOptions {
        allow_dtd: true,
        ..ParsingOptions::default()
    };
    if let Some((line, count)) = crowded_element(text) {
        return Err(xml_error(
            line as u32,
            format!("an element with {count} attributes (at most {MAX_XML_ATTRIBUTES})"),
        ));
    }
    let document = Document::parse_with_options(text, options)
        .map_err(|e| xml_error(e.pos().row, e.to_string()))?;
    let line = |node: Node<'_, '_>| document.text_pos_at(node.range().start).row as usize;
    let Some(engine) = document.descendants().find(|n| n.has_tag_name("engine")) else {
        let root = document
            .text_pos_at(document.root_element().range().start)
            .row;
        return Err(xml_error(root, "no <engine> element".to_owned()));
    };
    let header = read_header(engine, source_name, line(engine))?;
    let mut points = PointsBuilder::new(source_name, ThrustFormat::Rse);
    for point in engine.descendants().filter(|n| n.has_tag_name("eng-data")) {
        let at = line(point);
        let time = required(point, "t", source_name, at)?;
        let thrust = required(point, "f", source_name, at)?;
        if thrust < 0.0 {
            return Err(points.negative_thrust(at, thrust));
        }
        points.push(at, time, thrust)?;
    }
    points.finish(Some(header), 2)
}

/// The motor description from the `<engine>` attributes.
fn read_header(
    engine: Node<'_, '_>,
    source_name: &str,
    line: usize,
) -> Result<MotorHeader, PropulsionError> {
    let text = |key: &str| engine.attribute(key).unwrap_or("").to_owned();
    let scaled = |key: &str, factor: f64| -> Result<Option<f64>, PropulsionError> {
        engine
            .attribute(key)
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

fn required(
    point: Node<'_, '_>,
    key: &'static str,
    source_name: &str,
    line: usize,
) -> Result<f64, PropulsionError> {
    match point.attribute(key) {
        Some(v) => parse_number(source_name, line, v),
        None => Err(PropulsionError::Malformed {
            source_name: source_name.to_owned(),
            line,
            text: format!("<eng-data> without {key}"),
            reason: "missing attribute",
        }),
    }
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
        let with_bom = format!("\u{feff}{SAMPLE}");
        assert_eq!(parse(&with_bom, "m.rse"), parse(SAMPLE, "m.rse"));
        let d = parse(SAMPLE, "m.rse").unwrap();
        assert_eq!(d.times, vec![0.0, 0.5, 3.9]);
        assert_eq!(d.thrusts, vec![0.0, 1800.0, 0.0]);
        let h = d.header.unwrap();
        assert_eq!(h.designation, "M1670");
        assert!((h.dry_mass().unwrap() - 2.13).abs() < 1e-12);
        assert!((h.diameter.unwrap() - 0.075).abs() < 1e-15);
    }

    #[test]
    fn an_element_of_too_many_attributes_is_refused_unparsed() {
        assert_eq!(crowded_element(SAMPLE), None);
        let many: String = (0..=MAX_XML_ATTRIBUTES)
            .map(|i| format!(" a{i}='=>'"))
            .collect();
        let crowded = SAMPLE.replace("<engine code=\"second\"", &format!("<engine{many}"));
        assert_eq!(
            crowded_element(&crowded),
            Some((13, MAX_XML_ATTRIBUTES + 1))
        );
        let e = parse(&crowded, "m.rse").unwrap_err();
        assert!(matches!(e, PropulsionError::Xml { line: 13, .. }), "{e}");
        // Inside a comment or CDATA the `=` are text.
        let text = format!("<a><!--<b{many}>--><![CDATA[<b{many}>]]></a>");
        assert_eq!(crowded_element(&text), None);
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
        // Not well-formed: a mismatched end tag, named by its line.
        let bad = SAMPLE.replace("</data>", "</dta>");
        let e = parse(&bad, "m.rse").unwrap_err();
        assert!(matches!(e, PropulsionError::Xml { line: 11, .. }), "{e}");
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
