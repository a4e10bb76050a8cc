//! Thrust files: [`ThrustData::load`] reads a file and picks its reader from the extension,
//! as RocketPy's `Motor` does (`.eng` RASP, `.rse` RockSim XML, anything else two columns).
//! The readers depend on [`crate::data`] only; this module sits above both.

use std::path::Path;

use crate::{PropulsionError, ThrustData};

impl ThrustData {
    /// Reads a thrust file: `.eng` (RASP), `.rse` (RockSim XML) or, for any other extension,
    /// a two-column CSV (comma- or whitespace-separated, optional header line). Only regular
    /// files are opened ([`karman_math::read_data_file`]); a UTF-8 byte-order mark, CRLF
    /// line ends and tabs are accepted by every reader.
    ///
    /// # Errors
    /// [`PropulsionError::Io`] when the file cannot be read, and the reader's errors (each
    /// naming the file, line and offending text).
    pub fn load(path: &Path) -> Result<ThrustData, PropulsionError> {
        let source_name = path.display().to_string();
        let bytes = karman_math::read_data_file(path).map_err(|e| PropulsionError::Io {
            source_name: source_name.clone(),
            message: e.to_string(),
        })?;
        let text = String::from_utf8_lossy(&bytes);
        let extension = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .unwrap_or_default();
        match extension.as_str() {
            "eng" => crate::eng::parse(&text, &source_name),
            "rse" => crate::rse::parse(&text, &source_name),
            _ => crate::csv::parse(&text, &source_name),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_file_names_the_file() {
        let e = ThrustData::load(Path::new("/nonexistent/motor.eng")).unwrap_err();
        assert!(e.to_string().contains("/nonexistent/motor.eng"), "{e}");
    }

    #[test]
    fn a_directory_is_refused() {
        let e = ThrustData::load(Path::new(env!("CARGO_MANIFEST_DIR"))).unwrap_err();
        assert!(
            e.to_string().contains("not a regular file (a directory)"),
            "{e}"
        );
    }
}
