//! # karman-mission
//!
//! The TOML mission format (`docs/mission-format.md`): parsing with located errors, `--set`
//! overrides, validation, and building the physical model from a mission.
//!
//! ```no_run
//! use karman_mission::{load, Override};
//! use std::path::Path;
//!
//! let tilt: Override = "flight.inclination=84".parse()?;
//! let mission = load(Path::new("mission.toml"), &[tilt])?;
//! println!("{:?}", mission.spec.flight.inclination_deg);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! - [`schema`]: the typed file format ([`schema::MissionSpec`]).
//! - [`load`] / [`parse`]: read, override, deserialize, validate; every error is a
//!   [`MissionError`] naming the file, line, column and key.
//! - [`paths`]: the numeric inputs of a mission by dotted path (overrides, dispersion).
//! - [`montecarlo`]: the `[dispersion]` study of a mission, its samples applied and flown.
//! - [`assemble`]: mission → physics models; [`report`]: outputs.
//!
//! The lower crates are re-exported ([`math`], [`atmos`], [`propulsion`], [`airframe`],
//! [`dynamics`], [`dispersion`]) so the command-line interface depends on this crate only.

pub mod allocator;
pub mod assemble;
mod curves;
pub mod distributions;
mod document;
mod error;
pub mod montecarlo;
mod overrides;
pub mod paths;
pub mod report;
pub mod safety;
pub mod schema;
pub mod solve;
mod validate;
#[cfg(feature = "fetch")]
pub mod weather;

pub use error::{CurveError, Location, MissionError, OverrideError, Problem, ProblemKind};
pub use overrides::Override;

pub use karman_airframe as airframe;
pub use karman_atmos as atmos;
pub use karman_dispersion as dispersion;
pub use karman_dynamics as dynamics;
pub use karman_math as math;
pub use karman_model as model;
pub use karman_propulsion as propulsion;
pub use karman_script as script;
pub use karman_sensors as sensors;

use document::Document;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A loaded, validated mission.
#[derive(Debug, Clone, PartialEq)]
pub struct Mission {
    /// The mission file, as given.
    pub path: PathBuf,
    /// The directory relative data paths are resolved against.
    pub dir: PathBuf,
    /// The mission's content, overrides applied.
    pub spec: schema::MissionSpec,
    /// Where each key was written (file line and column, or the `--set` that gave it).
    pub keys: KeyLocations,
}

/// Where each key of a mission was written, by dotted path (`rocket.motor_position`), so that
/// problems found while building the models name the key's line and column.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct KeyLocations(Arc<BTreeMap<String, Location>>);

impl KeyLocations {
    /// The location of `key`, or of its deepest enclosing table that was written (a defaulted
    /// key is blamed on its section); `None` when nothing on the path was written.
    #[must_use]
    pub fn locate(&self, key: &str) -> Option<&Location> {
        let mut path = key;
        loop {
            if let Some(location) = self.0.get(path) {
                return Some(location);
            }
            path = &path[..path.rfind('.')?];
        }
    }
}

impl Mission {
    /// The error for a model that cannot be built from the mission key (or section)
    /// `section`, located at that key.
    pub fn model_error(
        &self,
        section: &str,
        source: impl Into<Box<dyn std::error::Error + Send + Sync>>,
    ) -> MissionError {
        MissionError::Model {
            file: self.path.clone(),
            location: self.keys.locate(section).cloned(),
            section: section.to_owned(),
            source: source.into(),
        }
    }

    /// A [`MissionError::Flight`] at `section` (located where the mission wrote that key):
    /// the models were built and the flight failed as it flew.
    pub fn flight_error(
        &self,
        section: &str,
        source: impl Into<Box<dyn std::error::Error + Send + Sync>>,
    ) -> MissionError {
        MissionError::Flight {
            file: self.path.clone(),
            location: self.keys.locate(section).cloned(),
            section: section.to_owned(),
            source: source.into(),
        }
    }

    /// A part of this mission flown or built as a mission of its own: `spec` (this mission's
    /// with the part's tables moved to the top), its keys located where the part wrote them,
    /// so that `prefix` + a key under one of `roots` (`stages.0.` + `rocket.mass`) is found
    /// as the bare key (`rocket.mass`) too.
    pub(crate) fn part(&self, spec: schema::MissionSpec, prefix: &str, roots: &[&str]) -> Mission {
        let mut keys = (*self.keys.0).clone();
        for (key, location) in self.keys.0.iter() {
            if let Some(inner) = key.strip_prefix(prefix)
                && roots.iter().any(|root| inner.starts_with(root))
            {
                keys.insert(inner.to_owned(), location.clone());
            }
        }
        Mission {
            path: self.path.clone(),
            dir: self.dir.clone(),
            spec,
            keys: KeyLocations(Arc::new(keys)),
        }
    }

    /// A data path of the mission resolved against its directory (absolute paths unchanged).
    pub fn resolve(&self, relative: &Path) -> PathBuf {
        self.dir.join(relative)
    }

    /// Overrides that set every parachute's trigger noise to `[0, 0, 0]`: the noise-free
    /// flights the RocketPy references were computed with.
    ///
    /// # Errors
    /// [`OverrideError`] for a parachute name that does not make a dotted path.
    pub fn parachute_noise_off(&self) -> Result<Vec<Override>, OverrideError> {
        self.spec
            .rocket
            .parachutes
            .keys()
            .map(|name| Override::new(&format!("rocket.parachutes.{name}.noise"), "[0, 0, 0]"))
            .collect()
    }
}

/// Reads, overrides, deserializes and validates the mission file at `path`.
pub fn load(path: &Path, overrides: &[Override]) -> Result<Mission, MissionError> {
    load_with(path, overrides, false)
}

/// [`load`]; with `fetching`, an atmosphere file that a `source` names need not exist yet.
pub(crate) fn load_with(
    path: &Path,
    overrides: &[Override],
    fetching: bool,
) -> Result<Mission, MissionError> {
    let bytes = karman_math::read_data_file(path).map_err(|source| MissionError::Read {
        file: path.to_owned(),
        source,
    })?;
    let text = match std::str::from_utf8(&bytes) {
        Ok(text) => text,
        Err(error) => {
            let valid = bytes.get(..error.valid_up_to()).unwrap_or_default();
            let prefix = std::str::from_utf8(valid).unwrap_or_default();
            let (line, column) = document::line_column(prefix, prefix.len());
            return Err(MissionError::NotText {
                file: path.to_owned(),
                line,
                column,
            });
        }
    };
    parse_with(text, path, overrides, fetching)
}

/// Whether `problem` is the magnitude bound of [`document::MAX_INPUT_MAGNITUDE`].
fn is_beyond_any_input(problem: &Problem) -> bool {
    matches!(
        problem.kind,
        ProblemKind::OutOfRange { expected, .. } if expected == document::BEYOND_ANY_INPUT
    )
}

/// Parses, overrides, deserializes and validates mission `text`; `path` names the file in
/// messages and its directory resolves relative data paths.
pub fn parse(text: &str, path: &Path, overrides: &[Override]) -> Result<Mission, MissionError> {
    parse_with(text, path, overrides, false)
}

fn parse_with(
    text: &str,
    path: &Path,
    overrides: &[Override],
    fetching: bool,
) -> Result<Mission, MissionError> {
    let mut doc = Document::parse(text).map_err(|e| MissionError::Syntax {
        file: path.to_owned(),
        line: e.line,
        column: e.column,
        message: e.message,
    })?;
    let dir = match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent.to_owned(),
        _ => PathBuf::from("."),
    };
    let invalid = |problems| MissionError::Invalid {
        file: path.to_owned(),
        problems,
    };
    let mut problems = Vec::new();
    for item in overrides {
        if let Err(problem) = doc.apply(item) {
            problems.push(problem);
        }
    }
    problems.extend(doc.non_finite(validate::ALLOW_INFINITE));
    let spec = match doc.deserialize() {
        Ok(spec) => {
            problems.extend(validate::validate(&spec, &doc, &dir, fetching));
            Some(spec)
        }
        Err(schema) => {
            problems.extend(schema);
            None
        }
    };
    // A float beyond any input is reported once: by its key's own range check when it has one.
    let own: std::collections::BTreeSet<String> = problems
        .iter()
        .filter(|p| !is_beyond_any_input(p))
        .map(|p| p.key.clone())
        .collect();
    problems.retain(|p| !is_beyond_any_input(p) || !own.contains(&p.key));
    match spec {
        Some(spec) if problems.is_empty() => Ok(Mission {
            path: path.to_owned(),
            dir,
            spec,
            keys: KeyLocations(Arc::new(doc.key_locations())),
        }),
        _ => {
            // `--set` problems first, then in file order (a stable sort keeps the order of
            // problems at one place).
            problems.sort_by_key(|p| match p.location {
                Location::Override { .. } => (0, 0),
                Location::File { line, column } => (line, column),
            });
            Err(invalid(problems))
        }
    }
}

/// The README's example, compiled and run by `cargo test --doc`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeExample;
