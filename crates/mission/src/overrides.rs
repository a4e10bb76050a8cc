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
        let (path, value) = text.split_once('=').ok_or(OverrideError::NoEquals)?;
        let path = path.trim();
        let segments: Vec<String> = path.split('.').map(|s| s.trim().to_owned()).collect();
        if segments.iter().any(String::is_empty) {
            return Err(OverrideError::EmptySegment {
                path: path.to_owned(),
            });
        }
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
    }
}
