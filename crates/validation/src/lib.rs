//! # karman-validation
//!
//! The validation flights of the repository and the parity karman owes them. The folder
//! `fixtures/validation` is a byte-for-byte copy of the project's validation data: eleven
//! real flights, each a mission file with its data files, RocketPy 1.13's figures for that
//! mission (`reference.json`) and, where the team published it, the measured flight (see the
//! folder's `README.md`). Every test that compares with RocketPy, and `cargo xtask validate`,
//! find the flights through this crate, so that a clone of the repository proves the project's
//! parity claim by itself:
//!
//! - [`data_dir`]: `$KARMAN_VALIDATION_DATA` when set, else `fixtures/validation`.
//! - [`locate`]: that folder checked complete ([`Folder`]), or why it is not ([`Unavailable`]).
//! - [`folder`]: the same for tests. An unavailable folder is a skip with a message on a
//!   developer's machine and a failure (a panic) when the `CI` environment variable is set,
//!   as CI services set it.
//! - [`PENDING`]: the flights that need a model not built yet, skipped by name with a message.
//! - [`SUMMARY_PARITY`], [`IMPACT_FRACTION`], [`PARACHUTE_TRIGGER_FRACTION`]: the tolerances
//!   of the flight summary against `reference.json`, one table for the tests and xtask.
//! - [`netcdf`]: a netCDF classic writer for the tests that author small weather grids.
//!
//! ```
//! let Some(folder) = karman_validation::folder() else { return };
//! for flight in folder.flown() {
//!     assert!(flight.mission().is_file() && flight.reference().is_file());
//! }
//! ```

pub mod netcdf;

use std::fmt;
use std::path::{Path, PathBuf};

/// The environment variable naming another validation folder (it overrides the repository's).
pub const ENV_VAR: &str = "KARMAN_VALIDATION_DATA";

/// Every flight of the repository's folder: it is incomplete without any of them.
pub const FLIGHTS: [&str; 11] = [
    "andromeda",
    "astra",
    "bella_lui",
    "calisto",
    "camoes",
    "halcyon",
    "hedy",
    "juno3",
    "ndrt_2020",
    "prometheus_2022",
    "valetudo",
];

/// A flight that needs a model karman does not have yet: skipped by name until it lands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Pending {
    /// The flight's folder name.
    pub flight: &'static str,
    /// What it needs, and the issue that builds it.
    pub needs: &'static str,
}

/// The flights skipped until their feature lands. The issue that builds a feature removes its
/// flight from this list, and from then on every test and `cargo xtask validate` fly it.
pub const PENDING: &[Pending] = &[];

/// The pending entry of `flight`, if it is skipped.
pub fn pending(flight: &str) -> Option<&'static Pending> {
    PENDING.iter().find(|p| p.flight == flight)
}

/// A relative tolerance on one key of the flight summary: `|karman − RocketPy| / |RocketPy|`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerance {
    /// The summary key (mission-format.md, "The summary").
    pub key: &'static str,
    /// The largest relative error accepted.
    pub relative: f64,
}

/// Parity of the flight summary against RocketPy 1.13 with parachute noise zeroed (the
/// dynamics issue's acceptance): apogee within 0.1 %, apogee time within 0.2 %, rail-exit
/// velocity, largest speed and largest Mach number within 0.5 %.
pub const SUMMARY_PARITY: [Tolerance; 5] = [
    Tolerance {
        key: "apogee_agl_m",
        relative: 1e-3,
    },
    Tolerance {
        key: "apogee_time_s",
        relative: 2e-3,
    },
    Tolerance {
        key: "out_of_rail_velocity_mps",
        relative: 5e-3,
    },
    Tolerance {
        key: "max_speed_mps",
        relative: 5e-3,
    },
    Tolerance {
        key: "max_mach",
        relative: 5e-3,
    },
];

/// The impact point within this fraction of the reference impact distance from the pad.
pub const IMPACT_FRACTION: f64 = 1e-2;

/// Each parachute trigger within this fraction of its reference time (a trigger sits on a
/// sampling instant of its trigger frequency, so it moves with the descent: 0.1 % of 158 s is
/// 16 instants at 105 Hz).
pub const PARACHUTE_TRIGGER_FRACTION: f64 = 1e-3;

/// The repository's validation folder, `fixtures/validation` of the workspace.
pub fn repository_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/validation")
}

/// The validation folder: `$KARMAN_VALIDATION_DATA` when set, else [`repository_dir`].
pub fn data_dir() -> PathBuf {
    std::env::var_os(ENV_VAR).map_or_else(repository_dir, PathBuf::from)
}

/// Whether the run is a CI run: `CI` set to anything but empty, `0` or `false`.
pub fn in_ci() -> bool {
    std::env::var("CI").is_ok_and(|v| !matches!(v.trim(), "" | "0" | "false" | "FALSE" | "False"))
}

/// One flight of the folder.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Flight {
    /// The folder name (`calisto`).
    pub name: String,
    /// The flight's folder.
    pub dir: PathBuf,
}

impl Flight {
    /// Its `mission.toml`.
    pub fn mission(&self) -> PathBuf {
        self.dir.join("mission.toml")
    }

    /// Its RocketPy 1.13 `reference.json`.
    pub fn reference(&self) -> PathBuf {
        self.dir.join("reference.json")
    }
}

/// A complete validation folder.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Folder {
    /// The folder.
    pub dir: PathBuf,
    /// Every flight in it, pending ones included, sorted by name.
    pub flights: Vec<Flight>,
}

impl Folder {
    /// The flights flown: all but the [`PENDING`] ones, each of which is named on standard
    /// output with what it needs.
    pub fn flown(&self) -> Vec<Flight> {
        self.flights
            .iter()
            .filter(|f| match pending(&f.name) {
                Some(p) => {
                    println!("validation flight {} skipped: it needs {}", f.name, p.needs);
                    false
                }
                None => true,
            })
            .cloned()
            .collect()
    }

    /// The `mission.toml` of every flight flown, sorted by flight.
    pub fn missions(&self) -> Vec<PathBuf> {
        self.flown().iter().map(Flight::mission).collect()
    }

    /// The flight named `name` (pending or not), or `None` when the folder lacks it (possible
    /// only in a folder named by [`ENV_VAR`]; the message says so).
    pub fn flight(&self, name: &str) -> Option<&Flight> {
        let found = self.flights.iter().find(|f| f.name == name);
        if found.is_none() {
            println!(
                "validation flight {name} skipped: not in {}",
                self.dir.display()
            );
        }
        found
    }
}

/// Why the validation folder cannot be used.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Unavailable {
    /// The folder does not exist or cannot be read.
    Missing {
        /// The folder.
        dir: PathBuf,
        /// The operating system's message.
        reason: String,
    },
    /// The folder lacks flights or their files.
    Incomplete {
        /// The folder.
        dir: PathBuf,
        /// What is missing, one entry per file or flight (`astra/reference.json`, `hedy/`).
        missing: Vec<String>,
    },
}

impl fmt::Display for Unavailable {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Unavailable::Missing { dir, reason } => write!(
                f,
                "the validation folder {} is missing ({reason})",
                dir.display()
            ),
            Unavailable::Incomplete { dir, missing } => write!(
                f,
                "the validation folder {} is incomplete: no {}",
                dir.display(),
                missing.join(", no ")
            ),
        }
    }
}

impl std::error::Error for Unavailable {}

/// The validation folder ([`data_dir`]) checked complete ([`open`]).
///
/// # Errors
/// [`Unavailable`] naming the folder and what is missing.
pub fn locate() -> Result<Folder, Unavailable> {
    open(&data_dir())
}

/// The validation folder `dir` checked complete: it can be read, holds at least one flight (a
/// folder with a `mission.toml` or a `reference.json`) and every flight holds both; the
/// repository's folder must also hold every flight of [`FLIGHTS`] and its `README.md`
/// (another folder, such as a set of blind flights, holds what it holds).
///
/// # Errors
/// [`Unavailable`] naming the folder and what is missing.
pub fn open(dir: &Path) -> Result<Folder, Unavailable> {
    let repository = repository_dir();
    let is_repository = dir == repository
        || dir
            .canonicalize()
            .ok()
            .zip(repository.canonicalize().ok())
            .is_some_and(|(a, b)| a == b);
    if is_repository {
        check(dir, &FLIGHTS, true)
    } else {
        check(dir, &[], false)
    }
}

/// [`locate`] for tests: the folder, or `None` after printing why it is unavailable; when
/// [`in_ci`], an unavailable folder panics instead, so that CI never passes without flying
/// the validation flights.
///
/// # Panics
/// In CI, when the folder is missing or incomplete.
pub fn folder() -> Option<Folder> {
    settle(locate(), in_ci())
}

/// The folder, or `None` after saying why it is unavailable; a panic instead in `ci`.
fn settle(located: Result<Folder, Unavailable>, ci: bool) -> Option<Folder> {
    match located {
        Ok(folder) => Some(folder),
        Err(e) if ci => panic!("{e} (CI is set: the validation flights must run)"),
        Err(e) => {
            println!("validation skipped: {e}");
            None
        }
    }
}

/// Checks `dir`: readable, at least one flight, `mission.toml` and `reference.json` in each,
/// every flight of `required` present, and a `README.md` when `readme`.
fn check(dir: &Path, required: &[&str], readme: bool) -> Result<Folder, Unavailable> {
    let entries = std::fs::read_dir(dir).map_err(|e| Unavailable::Missing {
        dir: dir.to_owned(),
        reason: e.to_string(),
    })?;
    let mut flights = Vec::new();
    let mut missing = Vec::new();
    for entry in entries.flatten() {
        let path = entry.path();
        let (mission, reference) = (path.join("mission.toml"), path.join("reference.json"));
        if !mission.is_file() && !reference.is_file() {
            continue;
        }
        let name = entry.file_name().to_string_lossy().into_owned();
        for file in [&mission, &reference] {
            if !file.is_file() {
                let file_name = file.file_name().unwrap_or_default().to_string_lossy();
                missing.push(format!("{name}/{file_name}"));
            }
        }
        flights.push(Flight { name, dir: path });
    }
    flights.sort_by(|a, b| a.name.cmp(&b.name));
    for name in required {
        if !flights.iter().any(|f| f.name == *name) {
            missing.push(format!("{name}/"));
        }
    }
    if readme && !dir.join("README.md").is_file() {
        missing.push("README.md".to_owned());
    }
    if flights.is_empty() && missing.is_empty() {
        missing.push("flight (a folder with mission.toml and reference.json)".to_owned());
    }
    if missing.is_empty() {
        Ok(Folder {
            dir: dir.to_owned(),
            flights,
        })
    } else {
        missing.sort();
        Err(Unavailable::Incomplete {
            dir: dir.to_owned(),
            missing,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A scratch folder of this test binary.
    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("karman-validation-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("scratch folder");
        dir
    }

    fn flight(dir: &Path, name: &str, files: &[&str]) {
        let folder = dir.join(name);
        std::fs::create_dir_all(&folder).expect("flight folder");
        for file in files {
            std::fs::write(folder.join(file), "").expect("file");
        }
    }

    #[test]
    fn the_repository_folder_is_complete() {
        let folder = check(&repository_dir(), &FLIGHTS, true).expect("fixtures/validation");
        let names: Vec<&str> = folder.flights.iter().map(|f| f.name.as_str()).collect();
        assert_eq!(names, FLIGHTS);
    }

    #[test]
    fn pending_flights_are_flights_of_the_folder_and_are_not_flown() {
        for p in PENDING {
            assert!(FLIGHTS.contains(&p.flight), "{} is not a flight", p.flight);
        }
        let folder = check(&repository_dir(), &FLIGHTS, true).expect("fixtures/validation");
        let flown = folder.flown();
        assert_eq!(flown.len(), FLIGHTS.len() - PENDING.len());
        assert!(flown.iter().all(|f| pending(&f.name).is_none()));
    }

    #[test]
    fn a_missing_folder_is_named() {
        let dir = scratch("missing").join("nothing-here");
        let e = check(&dir, &FLIGHTS, true).expect_err("missing");
        assert!(matches!(e, Unavailable::Missing { .. }));
        assert!(e.to_string().contains("nothing-here"), "{e}");
    }

    #[test]
    fn an_incomplete_folder_names_what_is_missing() {
        let dir = scratch("incomplete");
        flight(&dir, "calisto", &["mission.toml", "reference.json"]);
        flight(&dir, "astra", &["mission.toml"]);
        flight(&dir, "notes", &["todo.txt"]);
        let e = check(&dir, &["astra", "calisto", "hedy"], true).expect_err("incomplete");
        let Unavailable::Incomplete { missing, .. } = &e else {
            panic!("{e}")
        };
        assert_eq!(missing, &["README.md", "astra/reference.json", "hedy/"]);
        // Without required flights (an overriding folder) only the broken flight counts.
        let e = check(&dir, &[], false).expect_err("astra lacks its reference");
        assert!(e.to_string().ends_with("no astra/reference.json"), "{e}");
        std::fs::write(dir.join("astra/reference.json"), "").expect("file");
        let folder = check(&dir, &[], false).expect("complete");
        let names: Vec<&str> = folder.flights.iter().map(|f| f.name.as_str()).collect();
        assert_eq!(names, ["astra", "calisto"]);
    }

    #[test]
    fn an_unavailable_folder_is_a_skip_outside_ci_and_a_failure_in_ci() {
        let dir = scratch("unavailable").join("removed");
        assert!(settle(open(&dir), false).is_none());
        let ci = std::panic::catch_unwind(|| settle(open(&dir), true));
        let message = ci.expect_err("CI fails");
        let text = message.downcast_ref::<String>().expect("a message");
        assert!(
            text.contains("removed") && text.contains("CI is set"),
            "{text}"
        );
        assert!(settle(open(&repository_dir()), true).is_some());
    }

    #[test]
    fn an_empty_folder_is_incomplete() {
        let dir = scratch("empty");
        let e = check(&dir, &[], false).expect_err("no flight");
        assert!(e.to_string().contains("no flight"), "{e}");
    }
}
