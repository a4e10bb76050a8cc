//! `--set PATH=VALUE` overrides: a dotted path into the mission document and a TOML value,
//! applied to the parsed document before it is deserialized (mission-format.md "Overrides on
//! the command line").

use crate::error::OverrideError;
use std::fmt;
use std::str::FromStr;

/// One `--set PATH=VALUE` override.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Override {
    /// The argument as given, for messages.
    pub text: String,
    /// The dotted path, split at the dots (`["flight", "inclination"]`).
    pub path: Vec<String>,
    /// The value, TOML syntax (`84`, `[0, 0, 0]`, `"standard"`).
    pub value: String,
}

impl Override {
    /// Builds an override from a dotted path and a value in TOML syntax.
    pub fn new(path: &str, value: &str) -> Result<Self, OverrideError> {
        format!("{path}={value}").parse()
    }
}

impl FromStr for Override {
    type Err = OverrideError;

    fn from_str(text: &str) -> Result<Self, OverrideError> {
        let (path, value) = split_path(text)?;
        let segments = path
            .iter()
            .map(|segment| key(segment, text))
            .collect::<Result<Vec<String>, _>>()?;
        let value = value.trim();
        toml::de::DeValue::parse(value).map_err(|e| OverrideError::Value {
            value: value.to_owned(),
            message: e.message().trim_end().to_owned(),
        })?;
        Ok(Override {
            text: text.to_owned(),
            path: segments,
            value: value.to_owned(),
        })
    }
}

/// The raw segments of the path of `PATH=VALUE` and the value text: the path ends at the
/// first `=` and splits at the dots outside quoted keys (TOML strings, `"..."` with escapes or
/// `'...'`), so `dispersion.vary."rocket.mass".std=0.5` has the segments `dispersion`, `vary`,
/// `"rocket.mass"` and `std`.
fn split_path(text: &str) -> Result<(Vec<&str>, &str), OverrideError> {
    let mut segments = Vec::new();
    let (mut start, mut quote, mut escaped) = (0, None, false);
    for (i, c) in text.char_indices() {
        match quote {
            Some('"') if escaped => escaped = false,
            Some('"') if c == '\\' => escaped = true,
            Some(q) if c == q => quote = None,
            Some(_) => {}
            None => match c {
                '"' | '\'' => quote = Some(c),
                '.' => {
                    segments.push(&text[start..i]);
                    start = i + 1;
                }
                '=' => {
                    segments.push(&text[start..i]);
                    return Ok((segments, &text[i + 1..]));
                }
                _ => {}
            },
        }
    }
    match quote {
        Some(_) => Err(OverrideError::QuotedKey {
            path: text.trim().to_owned(),
            segment: text[start..].trim().to_owned(),
        }),
        None => Err(OverrideError::NoEquals),
    }
}

/// One segment of a path: a bare key (trimmed) or a quoted one (its TOML string's value).
fn key(segment: &str, text: &str) -> Result<String, OverrideError> {
    let path = || {
        text.split_once('=')
            .map_or(text, |(p, _)| p)
            .trim()
            .to_owned()
    };
    let segment = segment.trim();
    if segment.is_empty() {
        return Err(OverrideError::EmptySegment { path: path() });
    }
    if !segment.starts_with(['"', '\'']) {
        return Ok(segment.to_owned());
    }
    match toml::de::DeValue::parse(segment).map(toml::Spanned::into_inner) {
        Ok(toml::de::DeValue::String(key)) if !key.is_empty() => Ok(key.into_owned()),
        _ => Err(OverrideError::QuotedKey {
            path: path(),
            segment: segment.to_owned(),
        }),
    }
}

impl fmt::Display for Override {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.text)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_path_and_value() {
        let o: Override = "rocket.parachutes.Main.noise=[0,0,0]"
            .parse()
            .expect("valid");
        assert_eq!(o.path, ["rocket", "parachutes", "Main", "noise"]);
        assert_eq!(o.value, "[0,0,0]");
        let o: Override = "environment.atmosphere.model=\"standard\""
            .parse()
            .expect("valid");
        assert_eq!(o.value, "\"standard\"");
        // Quoted keys hold dots (and an `=`); the value may hold both too.
        let o: Override = "dispersion.vary.\"rocket.mass\".std=0.5"
            .parse()
            .expect("valid");
        assert_eq!(o.path, ["dispersion", "vary", "rocket.mass", "std"]);
        assert_eq!(o.value, "0.5");
        let o: Override = "dispersion.vary.'a=b'. \"c\\\"d\" = { std = 0.1 }"
            .parse()
            .expect("valid");
        assert_eq!(o.path, ["dispersion", "vary", "a=b", "c\"d"]);
        assert_eq!(o.value, "{ std = 0.1 }");
        let o: Override = "rocket.inertia.0=0.6".parse().expect("valid");
        assert_eq!(o.path, ["rocket", "inertia", "0"]);
    }

    #[test]
    fn rejects_malformed() {
        assert_eq!(
            "flight.inclination".parse::<Override>(),
            Err(OverrideError::NoEquals)
        );
        assert!(matches!(
            "flight..inclination=3".parse::<Override>(),
            Err(OverrideError::EmptySegment { .. })
        ));
        assert!(matches!(
            "environment.atmosphere.model=standard".parse::<Override>(),
            Err(OverrideError::Value { .. })
        ));
        for text in [
            "dispersion.vary.\"rocket.mass.std=0.5",
            "dispersion.vary.\"rocket\"mass.std=0.5",
            "dispersion.vary.\"\".std=0.5",
        ] {
            assert!(
                matches!(
                    text.parse::<Override>(),
                    Err(OverrideError::QuotedKey { .. })
                ),
                "{text}"
            );
        }
    }
}
