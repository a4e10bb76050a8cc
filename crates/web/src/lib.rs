//! # karman-web
//!
//! karman in the browser: the mission crate compiled to WebAssembly (`wasm32-unknown-unknown`,
//! through `wasm-bindgen`) behind a handful of functions that the static page of `web/`
//! calls. `cargo xtask web` builds the page; the README says how to open it.
//!
//! A page has no file system: the files a mission names (thrust, drag and weather files) come
//! in as bytes in a [`Files`] set, which is installed on the thread for the duration of each
//! call ([`karman_mission::math::files::FileSet`]), so the mission resolves its relative
//! paths from it exactly as the command-line program resolves them from disk. Nothing here
//! uses threads, a clock or the network: a Monte Carlo study is flown slice by slice
//! ([`Study::lines`]) by as many Web Workers as the page starts, and the slices joined in
//! index order are the `samples.csv` that `karman montecarlo` writes.
//!
//! - [`check`]: `karman check` of a mission text, its problems located (line, column, key).
//! - [`fly`]: `karman simulate` of a mission: its `--json` text, the files of `--out`
//!   (`summary.json`, `trajectory.csv`, `flight.kml`) and the series of the page's plots.
//! - [`Study`]: the `[dispersion]` study of a mission: the header of `samples.csv` and the
//!   lines of any range of its samples.
//! - [`import_ork`]: `karman import` of an OpenRocket design.
//!
//! Every error is a JSON text (a JavaScript exception on the page, [`Failure`]): the whole
//! message as the command line prints it and each located problem with its file, line,
//! column and key. The same functions are plain Rust functions in a native build, which is
//! how the tests call them.

use std::path::Path;

use karman_mission::assemble::flight::{FlightRun, PreparedFlight, early_ending};
use karman_mission::assemble::scripts::first_call;
use karman_mission::assemble::stages::{prepare_staged, simulate_staged};
use karman_mission::dispersion;
use karman_mission::math::files::FileSet;
use karman_mission::montecarlo::{MonteCarlo, StudyOverrides};
use karman_mission::report::trajectory;
use karman_mission::{Location, Mission, MissionError};
use serde_json::{Value, json};
use wasm_bindgen::prelude::wasm_bindgen;

/// The largest file a [`Files`] set takes, in bytes (64 MiB, the design limit of the
/// OpenRocket reader; a mission's data files are kilobytes).
pub const MAX_FILE_BYTES: usize = 64 << 20;

/// The files a mission names, by file name, each its bytes.
#[wasm_bindgen]
#[derive(Debug, Clone, Default)]
pub struct Files {
    set: FileSet,
}

#[wasm_bindgen]
impl Files {
    /// An empty set.
    #[wasm_bindgen(constructor)]
    #[must_use]
    pub fn new() -> Files {
        Files::default()
    }

    /// Adds (or replaces) the file `name`.
    ///
    /// # Errors
    /// A [`Failure`] for an empty name or a file larger than [`MAX_FILE_BYTES`].
    pub fn add(&mut self, name: &str, bytes: Vec<u8>) -> Result<(), String> {
        if name.trim().is_empty() {
            return Err(Failure::plain("a file without a name").to_json());
        }
        if bytes.len() > MAX_FILE_BYTES {
            return Err(Failure::plain(format!(
                "{name}: {} bytes, larger than the {} MiB a file may have",
                bytes.len(),
                MAX_FILE_BYTES >> 20
            ))
            .to_json());
        }
        self.set.insert(name, bytes);
        Ok(())
    }

    /// The names of the files, in order.
    #[must_use]
    pub fn names(&self) -> Vec<String> {
        self.set.names().map(|n| n.display().to_string()).collect()
    }
}

/// One problem of a failure, where it is when that is known.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Located {
    /// Line in the mission, 1-based.
    pub line: Option<usize>,
    /// Column in the mission, in characters, 1-based.
    pub column: Option<usize>,
    /// The dotted key it concerns (empty for the whole file).
    pub key: String,
    /// The problem as the command line prints it (`file:line:column: key: message`).
    pub message: String,
}

/// Why a call failed: the message of the command line and each located problem.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Failure {
    /// The whole error, every cause after a `: `, as `karman` prints it.
    pub message: String,
    /// The problems located in the mission (none for an error without a place).
    pub problems: Vec<Located>,
}

/// The error and its causes, `: ` between them (anyhow's `{:#}`, what `karman` prints).
fn chain(error: &dyn std::error::Error) -> String {
    let mut text = error.to_string();
    let mut source = error.source();
    while let Some(cause) = source {
        text.push_str(": ");
        text.push_str(&cause.to_string());
        source = cause.source();
    }
    text
}

/// Line and column of a location in the file (none for a `--set`).
fn place(location: Option<&Location>) -> (Option<usize>, Option<usize>) {
    match location {
        Some(Location::File { line, column }) => (Some(*line), Some(*column)),
        _ => (None, None),
    }
}

impl Failure {
    /// A failure without a place.
    fn plain(message: impl Into<String>) -> Self {
        Failure {
            message: message.into(),
            problems: Vec::new(),
        }
    }

    /// The failure of a mission error, its problems located.
    fn of(error: &MissionError) -> Self {
        let message = chain(error);
        let one = |location: Option<&Location>, key: &str| {
            let (line, column) = place(location);
            vec![Located {
                line,
                column,
                key: key.to_owned(),
                message: message.clone(),
            }]
        };
        let problems = match error {
            MissionError::Syntax { line, column, .. }
            | MissionError::NotText { line, column, .. } => one(
                Some(&Location::File {
                    line: *line,
                    column: *column,
                }),
                "",
            ),
            MissionError::Invalid { file, problems } => problems
                .iter()
                .map(|problem| {
                    let (line, column) = place(Some(&problem.location));
                    Located {
                        line,
                        column,
                        key: problem.key.clone(),
                        message: problem.display(file).to_string(),
                    }
                })
                .collect(),
            MissionError::Model {
                location, section, ..
            }
            | MissionError::Flight {
                location, section, ..
            } => one(location.as_ref(), section),
            MissionError::Curve { key, .. } => one(None, key),
            MissionError::Read { .. } | MissionError::BadOverride { .. } => Vec::new(),
        };
        Failure { message, problems }
    }

    /// The JSON text the page receives: `{"message": ..., "problems": [{"line", "column",
    /// "key", "message"}]}`.
    #[must_use]
    pub fn to_json(&self) -> String {
        let problems: Vec<Value> = self
            .problems
            .iter()
            .map(|p| {
                json!({
                    "line": p.line,
                    "column": p.column,
                    "key": p.key,
                    "message": p.message,
                })
            })
            .collect();
        json!({ "message": self.message, "problems": problems }).to_string()
    }
}

impl From<MissionError> for Failure {
    fn from(error: MissionError) -> Self {
        Failure::of(&error)
    }
}

impl From<serde_json::Error> for Failure {
    fn from(error: serde_json::Error) -> Self {
        Failure::plain(error.to_string())
    }
}

/// The mission `text`, named `name` in messages, parsed and validated (its files read from
/// the installed set).
fn parse(name: &str, text: &str) -> Result<Mission, Failure> {
    Ok(karman_mission::parse(text, Path::new(name), &[])?)
}

/// Runs `f` with `files` installed and turns its failure into the page's JSON text.
fn within<T>(files: &Files, f: impl FnOnce() -> Result<T, Failure>) -> Result<T, String> {
    files.set.with(f).map_err(|failure| failure.to_json())
}

/// The error of a nominal flight that ended early (as `karman check` words it).
fn ended_early(mission: &Mission, body: Option<&str>, message: &str) -> Failure {
    let body = body.map_or_else(String::new, |b| format!("{b}: "));
    Failure::plain(format!(
        "{}: the nominal flight (seed 0): {body}{message}",
        mission.path.display()
    ))
}

/// `karman check` of the mission `text` (named `name`, e.g. `mission.toml`): it loads,
/// validates, its models build and its nominal flight flies. Returns the warnings, as a
/// JSON array of `file: warning: text` lines.
///
/// # Errors
/// The [`Failure`] JSON text of the first failing stage (all problems of the validation).
#[wasm_bindgen]
pub fn check(name: &str, text: &str, files: &Files) -> Result<String, String> {
    within(files, || {
        let mission = parse(name, text)?;
        let warnings = if mission.spec.stages.is_empty() {
            let prepared = PreparedFlight::new(&mission)?;
            if let Some(script) = prepared.script() {
                first_call(&mission, script, prepared.rocket(), prepared.environment())?;
            }
            let run = prepared.fly(&mission, 0)?;
            if let Some((_, message)) = early_ending(run.summary().termination, &run.settings) {
                return Err(ended_early(&mission, None, &message));
            }
            prepared.warnings().to_vec()
        } else {
            let warnings = prepare_staged(&mission, 0)?;
            let run = simulate_staged(&mission, 0)?;
            for (i, body) in run.bodies.iter().enumerate() {
                if let Some((_, message)) = early_ending(run.summary(i).termination, &run.settings)
                {
                    return Err(ended_early(&mission, Some(&body.name), &message));
                }
            }
            warnings
        };
        let lines: Vec<String> = warnings
            .iter()
            .map(|w| format!("{}: warning: {w}", mission.path.display()))
            .collect();
        Ok(serde_json::to_string(&lines)?)
    })
}

/// The object of `karman simulate --json` (without the sensors' readings).
fn simulate_json(run: &FlightRun) -> Result<Value, Failure> {
    let mut json = serde_json::to_value(run.summary())?;
    json["warnings"] = serde_json::to_value(&run.warnings)?;
    if let Some(record) = &run.controller {
        json["controller"] = record.to_json();
    }
    Ok(json)
}

/// The `summary.json` of `karman simulate --out` (seed 0).
fn summary_file(run: &FlightRun) -> Result<String, Failure> {
    let summary = run.summary();
    let mut json = serde_json::to_value(&summary)?;
    json["termination"] = serde_json::to_value(summary.termination)?;
    json["seed"] = 0.into();
    json["integration"] = serde_json::to_value(run.flight.stats)?;
    json["warnings"] = serde_json::to_value(&run.warnings)?;
    Ok(serde_json::to_string_pretty(&json)?)
}

/// `karman simulate` of the single-stage mission `text` (seed 0). Returns a JSON object:
/// `json` (the text `--json` prints), `summary_json`, `trajectory_csv` and `kml` (the files
/// of `--out`), `early` (the message of a flight that ended before landing, else null) and
/// `series`: arrays `t`, `altitude`, `speed`, `mach`, `static_margin`, `stability_margin`
/// (the margins over the ascent, `ascent_t`), `x` and `y` (east and north of the pad, m).
///
/// # Errors
/// The [`Failure`] JSON text of the load, the models or the flight; a multi-stage mission
/// is refused (the page flies one body).
#[wasm_bindgen]
pub fn fly(name: &str, text: &str, files: &Files) -> Result<String, String> {
    within(files, || {
        let mission = parse(name, text)?;
        if !mission.spec.stages.is_empty() {
            return Err(Failure::plain(format!(
                "{name}: a multi-stage mission ([[stages]]): the page flies single-stage \
                 missions; fly it with `karman simulate`"
            )));
        }
        let run = PreparedFlight::new(&mission)?.fly(&mission, 0)?;
        let samples = run.samples();
        let title = mission.spec.name.as_deref().unwrap_or("karman flight");
        let summary = run.summary();
        let apogee = summary.apogee_time_s.unwrap_or(f64::INFINITY);
        let ascent: Vec<_> = samples.iter().filter(|s| s.t <= apogee).collect();
        let series = json!({
            "t": samples.iter().map(|s| s.t).collect::<Vec<_>>(),
            "altitude": samples.iter().map(|s| s.altitude_agl).collect::<Vec<_>>(),
            "speed": samples.iter().map(|s| s.speed).collect::<Vec<_>>(),
            "mach": samples.iter().map(|s| s.mach).collect::<Vec<_>>(),
            "x": samples.iter().map(|s| s.x).collect::<Vec<_>>(),
            "y": samples.iter().map(|s| s.y).collect::<Vec<_>>(),
            "ascent_t": ascent.iter().map(|s| s.t).collect::<Vec<_>>(),
            "static_margin": ascent.iter().map(|s| run.rocket.static_margin(s.t)).collect::<Vec<_>>(),
            "stability_margin": ascent.iter().map(|s| s.stability_margin).collect::<Vec<_>>(),
        });
        let early = early_ending(summary.termination, &run.settings).map(|(_, message)| message);
        Ok(json!({
            "json": serde_json::to_string_pretty(&simulate_json(&run)?)?,
            "summary_json": summary_file(&run)?,
            "trajectory_csv": trajectory::csv(&run, &samples),
            "kml": trajectory::kml(&run, title, &samples),
            "early": early,
            "series": series,
        })
        .to_string())
    })
}

/// The `[dispersion]` study of a mission, ready to fly any range of its samples.
#[wasm_bindgen]
#[derive(Debug)]
pub struct Study {
    files: Files,
    study: MonteCarlo,
}

#[wasm_bindgen]
impl Study {
    /// The study of the mission `text` as `karman montecarlo` runs it, with `--samples` and
    /// `--seed` when given (`seed` a decimal text: seeds are 64-bit).
    ///
    /// # Errors
    /// The [`Failure`] JSON text of the mission or its `[dispersion]` table, or of a seed
    /// that is not a number.
    #[wasm_bindgen(constructor)]
    pub fn new(
        name: &str,
        text: &str,
        files: &Files,
        samples: Option<u32>,
        seed: Option<String>,
    ) -> Result<Study, String> {
        let study = within(files, || {
            let seed = match seed.as_deref().map(str::trim) {
                None | Some("") => None,
                Some(text) => Some(text.parse::<u64>().map_err(|_| {
                    Failure::plain(format!(
                        "seed {text:?}: not a whole number from 0 to 2^64 − 1"
                    ))
                })?),
            };
            let mission = parse(name, text)?;
            let overrides = StudyOverrides {
                samples: samples.map(u64::from),
                seed,
            };
            Ok(MonteCarlo::new(&mission, overrides)?)
        })?;
        Ok(Study {
            files: files.clone(),
            study,
        })
    }

    /// The number of samples.
    #[must_use]
    pub fn samples(&self) -> u32 {
        u32::try_from(self.study.study().samples).unwrap_or(u32::MAX)
    }

    /// The seed, as a decimal text.
    #[must_use]
    pub fn seed(&self) -> String {
        self.study.study().seed.to_string()
    }

    /// The header line of `samples.csv`, newline included.
    #[must_use]
    pub fn header(&self) -> String {
        dispersion::samples_header(self.study.study())
    }

    /// The `summary.json` of the study whose `samples.csv` is `csv` (the header and every
    /// row, joined in index order): the statistics and the apogee and landing ellipses
    /// `karman montecarlo` writes.
    ///
    /// # Errors
    /// The [`Failure`] JSON text of a line that is not a row of this study (its line number).
    pub fn summary(&self, csv: &str) -> Result<String, String> {
        let study = self.study.study();
        let mut rows = Vec::new();
        for (number, line) in csv.lines().enumerate().skip(1) {
            let row = dispersion::parse_row(line, study.inputs.len(), study.outputs.len())
                .map_err(|e| {
                    Failure::plain(format!("samples.csv:{}: {e}", number + 1)).to_json()
                })?;
            rows.push(row);
        }
        let summary = dispersion::summarize_rows(study, &rows);
        serde_json::to_string_pretty(&summary).map_err(|e| Failure::from(e).to_json())
    }

    /// The lines of `samples.csv` of the samples `first..end` (an index beyond the study has
    /// none), flown on this thread: those `karman montecarlo` writes, byte for byte.
    ///
    /// # Errors
    /// The [`Failure`] JSON text of a study that does not validate.
    pub fn lines(&self, first: u32, end: u32) -> Result<String, String> {
        within(&self.files, || {
            dispersion::sample_lines(
                self.study.study(),
                u64::from(first)..u64::from(end),
                |index, values| self.study.fly(index, values),
            )
            .map_err(|e| Failure::plain(chain(&e)))
        })
    }
}

/// `karman import` of the OpenRocket design `bytes` (a `.ork`, named `name` in messages),
/// its motor found by designation among the `.eng` files of `files`. Returns a JSON object:
/// `mission` (the mission's text, its thrust file named as in `files`) and `warnings`.
///
/// # Errors
/// The [`Failure`] JSON text of the import (the file and component it names).
#[wasm_bindgen]
pub fn import_ork(name: &str, bytes: &[u8], files: &Files) -> Result<String, String> {
    within(files, || {
        let motors = files
            .set
            .names()
            .filter(|n| n.extension().is_some_and(|e| e.eq_ignore_ascii_case("eng")))
            .map(Path::to_path_buf)
            .collect();
        let options = karman_openrocket::ImportOptions {
            simulation: None,
            motors,
            output_dir: None,
        };
        let imported = karman_openrocket::import_bytes(Path::new(name), bytes, &options)
            .map_err(|e| Failure::plain(chain(&e)))?;
        Ok(json!({ "mission": imported.mission, "warnings": imported.warnings }).to_string())
    })
}

/// The README's example, compiled and run by `cargo test --doc`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeExample;
