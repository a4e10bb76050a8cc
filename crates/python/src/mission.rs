//! `karman.load` and `karman.Mission`: a validated mission, its overrides, and what it flies.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, OnceLock};
use std::time::Duration;

use karman_fit::{FitError, FitOptions, fit_json, write_fitted};
use karman_mission::assemble::environment::build_environment;
use karman_mission::assemble::flight::{FlightRun, PreparedFlight};
use karman_mission::assemble::motor::build_motor;
use karman_mission::assemble::rocket::build_rocket;
use karman_mission::dispersion::{
    MemoryRun, ProgressMode, RunOptions, RunReport, run_in_memory, run_until,
};
use karman_mission::montecarlo::{MonteCarlo, StudyOverrides};
use karman_mission::report::environment::{default_heights, environment_report};
use karman_mission::report::motor::MotorReport;
use karman_mission::report::rocket::RocketReport;
use karman_mission::{MissionError as RustMissionError, Override};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};

use crate::controller::PythonController;
use crate::convert::{from_json, from_toml, plain, to_toml};
use crate::flight::Flight;
use crate::log::FlightLog;
use crate::study::Study;
use crate::trigger::PythonTrigger;
use crate::{log_error, mission_error};
use karman_mission::model::TriggerCondition;

/// The file name missions built from text or data are given in messages when no `path` is
/// passed (relative data paths then resolve against the working directory).
const UNNAMED: &str = "<mission>";

/// A mission: the TOML text it was read from, the overrides applied to it, the validated
/// result, and its models once built (by the first `simulate`; every change — `set` — makes a
/// new mission, whose models are built again).
#[pyclass(module = "karman")]
#[derive(Clone)]
pub struct Mission {
    text: String,
    overrides: Vec<Override>,
    inner: karman_mission::Mission,
    prepared: OnceLock<Arc<PreparedFlight>>,
    /// Parachute triggers written in Python (`set_trigger`), by parachute name.
    triggers: Vec<(String, Arc<Py<PyAny>>)>,
}

/// The overrides of a `{path: value}` dict, values given as Python data.
fn overrides_of(overrides: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<Override>> {
    let mut out = Vec::new();
    for (path, value) in overrides.into_iter().flat_map(|d| d.iter()) {
        let path: String = path.extract()?;
        out.push(override_of(&path, &value)?);
    }
    Ok(out)
}

/// One override: a dotted path and a Python value written as a TOML value.
fn override_of(path: &str, value: &Bound<'_, PyAny>) -> PyResult<Override> {
    let value = to_toml(value, path)?;
    Override::new(path, &value.to_string()).map_err(|e| override_error(path, &e))
}

/// The exception of an override that is malformed before it reaches the mission.
fn override_error(path: &str, error: &karman_mission::OverrideError) -> PyErr {
    crate::MissionError::new_err(format!("--set `{path}`: {error}"))
}

impl Mission {
    fn parse(text: String, path: &Path, overrides: Vec<Override>) -> PyResult<Self> {
        let inner =
            karman_mission::parse(&text, path, &overrides).map_err(|e| mission_error(&e))?;
        Ok(Mission {
            text,
            overrides,
            inner,
            prepared: OnceLock::new(),
            triggers: Vec::new(),
        })
    }

    /// The mission's models, built and checked on first use and kept (copies of the mission
    /// share them; they never change, since a change makes a new mission).
    fn prepared(&self) -> Result<Arc<PreparedFlight>, RustMissionError> {
        if let Some(prepared) = self.prepared.get() {
            return Ok(Arc::clone(prepared));
        }
        let prepared = Arc::new(PreparedFlight::new(&self.inner)?);
        Ok(Arc::clone(self.prepared.get_or_init(|| prepared)))
    }

    /// The validated mission.
    pub fn inner(&self) -> &karman_mission::Mission {
        &self.inner
    }

    /// Flies `prepared` once with the GIL released, its air brakes driven by `controller`
    /// when one is given (`simulate`).
    fn fly_prepared(
        &self,
        py: Python<'_>,
        prepared: &PreparedFlight,
        seed: u64,
        controller: Option<Py<PyAny>>,
    ) -> PyResult<FlightRun> {
        let mission = &self.inner;
        let Some(function) = controller else {
            return py
                .detach(|| prepared.fly(mission, seed))
                .map_err(|e| mission_error(&e));
        };
        let scalar = mission
            .spec
            .rocket
            .sensors
            .iter()
            .map(|s| s.kind.as_str() == "barometer")
            .collect();
        let mut controller = PythonController::new(py, function, scalar)?;
        let flown = py.detach(|| prepared.fly_with_controller(mission, seed, &mut controller));
        match (flown, controller.error.take()) {
            (Ok(run), _) => Ok(run),
            // Ctrl-C stays an interruption, not a flight's failure.
            (Err(_), Some(error))
                if error.is_instance_of::<pyo3::exceptions::PyKeyboardInterrupt>(py) =>
            {
                Err(error)
            }
            (Err(e), _) => Err(mission_error(&e)),
        }
    }
}

/// Reads a mission file, applies `overrides` (`{"flight.inclination": 84}`: the dotted paths
/// of `--set`, values as Python data) and validates it.
#[pyfunction]
#[pyo3(signature = (path, overrides = None))]
pub fn load(path: PathBuf, overrides: Option<&Bound<'_, PyDict>>) -> PyResult<Mission> {
    let overrides = overrides_of(overrides)?;
    // Read through the mission crate first: its messages for unreadable or non-UTF-8 files.
    karman_mission::load(&path, &overrides).map_err(|e| mission_error(&e))?;
    let text = std::fs::read_to_string(&path).map_err(|source| {
        mission_error(&RustMissionError::Read {
            file: path.clone(),
            source,
        })
    })?;
    Mission::parse(text, &path, overrides)
}

#[pymethods]
impl Mission {
    /// A mission from TOML text; `path` names it in messages and its folder resolves relative
    /// data paths (default: the working directory).
    #[staticmethod]
    #[pyo3(signature = (text, path = None))]
    fn from_toml(text: String, path: Option<PathBuf>) -> PyResult<Self> {
        let path = path.unwrap_or_else(|| PathBuf::from(UNNAMED));
        Mission::parse(text, &path, Vec::new())
    }

    /// A mission from Python data shaped like the TOML file (`{"environment": {...},
    /// "motor": {...}, ...}`); `path` as in `from_toml`.
    #[staticmethod]
    #[pyo3(signature = (data, path = None))]
    fn from_dict(data: &Bound<'_, PyDict>, path: Option<PathBuf>) -> PyResult<Self> {
        let toml::Value::Table(table) = to_toml(data.as_any(), "")? else {
            return Err(PyValueError::new_err("a mission is a dict"));
        };
        let text = toml::to_string(&table)
            .map_err(|e| PyValueError::new_err(format!("cannot write the mission as TOML: {e}")))?;
        Mission::from_toml(text, path)
    }

    /// Sets one input by its dotted path (`mission.set("flight.inclination", 84)`, the paths
    /// of `--set`) and validates the mission again; on error the mission is unchanged.
    fn set(&mut self, path: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let mut overrides = self.overrides.clone();
        overrides.push(override_of(path, value)?);
        let triggers = std::mem::take(&mut self.triggers);
        *self = Mission::parse(self.text.clone(), &self.inner.path, overrides)?;
        self.triggers = triggers;
        Ok(())
    }

    /// Fires the parachute `name` by `function`, RocketPy's `trigger(p, h, y[, sensors])`
    /// written in Python, in every later `simulate` (as its `triggers` argument does; that
    /// argument wins for the names it gives). The mission's own trigger stays in its TOML.
    /// `None` removes the function. Raises `MissionError` for a parachute the mission does
    /// not have, `TypeError` for a function that is not RocketPy's trigger.
    fn set_trigger(
        &mut self,
        py: Python<'_>,
        name: &str,
        function: Option<Py<PyAny>>,
    ) -> PyResult<()> {
        if !self.inner.spec.rocket.parachutes.contains_key(name) {
            let error = self.inner.model_error(
                "rocket.parachutes",
                format!("no parachute {name:?} to trigger"),
            );
            return Err(mission_error(&error));
        }
        self.triggers.retain(|(n, _)| n != name);
        if let Some(function) = function {
            let sensors = &self.inner.spec.rocket.sensors;
            PythonTrigger::new(py, name, function.clone_ref(py), sensors)?;
            self.triggers.push((name.to_owned(), Arc::new(function)));
        }
        Ok(())
    }

    /// An independent copy (to vary one mission several ways).
    fn copy(&self) -> Self {
        self.clone()
    }

    fn __copy__(&self) -> Self {
        self.clone()
    }

    fn __deepcopy__(&self, _memo: &Bound<'_, PyAny>) -> Self {
        self.clone()
    }

    /// The mission, overrides applied, as TOML text (every default written out; relative
    /// data paths stay relative to the mission's folder).
    fn to_toml(&self) -> PyResult<String> {
        toml::to_string(&self.inner.spec)
            .map_err(|e| PyRuntimeError::new_err(format!("cannot write the mission as TOML: {e}")))
    }

    /// The mission, overrides applied, as Python data (the shape `from_dict` takes).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let value = toml::Value::try_from(&self.inner.spec)
            .map_err(|e| PyRuntimeError::new_err(format!("cannot convert the mission: {e}")))?;
        from_toml(py, &value)
    }

    /// The mission's `name`, if it has one.
    #[getter]
    fn name(&self) -> Option<String> {
        self.inner.spec.name.clone()
    }

    /// The mission file (or the name given to `from_toml`/`from_dict`).
    #[getter]
    fn path(&self) -> PathBuf {
        self.inner.path.clone()
    }

    /// The overrides applied, as `PATH=VALUE` texts.
    #[getter]
    fn overrides(&self) -> Vec<String> {
        self.overrides.iter().map(|o| o.text.clone()).collect()
    }

    /// The models the mission builds, as `karman inspect --json` shows them:
    /// `{"environment": ..., "motor": ..., "rocket": ...}`, tables as numpy arrays.
    /// `heights` (m above sea level) and `times` (s) choose the sample points.
    #[pyo3(signature = (heights = None, times = None))]
    fn inspect<'py>(
        &self,
        py: Python<'py>,
        heights: Option<Vec<f64>>,
        times: Option<Vec<f64>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let mission = &self.inner;
        let value = py
            .detach(|| -> Result<serde_json::Value, RustMissionError> {
                let environment = build_environment(mission)?;
                let motor = build_motor(mission)?;
                let rocket = build_rocket(mission, &motor)?;
                let heights = heights.unwrap_or_else(|| {
                    default_heights(
                        environment.elevation(),
                        mission.spec.environment.max_expected_height,
                    )
                });
                let motor_report = MotorReport::at(&motor, times.as_deref());
                Ok(serde_json::json!({
                    "environment": environment_report(&environment, &heights),
                    "motor": motor_report,
                    "rocket": RocketReport::new(&rocket),
                }))
            })
            .map_err(|e| mission_error(&e))?;
        from_json(py, &value)
    }

    /// Flies the mission once (the GIL is released meanwhile); `seed` seeds the parachute
    /// trigger noise. The models are built and checked by the first call and kept for the
    /// next ones until the mission changes. Raises `MissionError` when the models cannot be
    /// built or flown. `controller`, a Python function with RocketPy's
    /// `controller_function(time, sampling_rate, state, state_history, observed_variables,
    /// air_brakes[, sensors])` signature, drives the air brakes of `[rocket.air_brakes]` in
    /// place of the mission's Rhai script, called where the script would be; an exception it
    /// raises ends the flight with `MissionError` holding its traceback, Ctrl-C raises
    /// `KeyboardInterrupt`. `triggers` (`{"main": function}`) fires the named parachutes by
    /// Python functions with RocketPy's `trigger(p, h, y[, sensors])` signature instead of
    /// their mission triggers: called at each of the parachute's sampling instants (ascent
    /// included), a true result fires it; an exception it raises stops its calls and is raised
    /// when the flight returns.
    #[pyo3(signature = (seed = 0, controller = None, triggers = None))]
    fn simulate(
        &self,
        py: Python<'_>,
        seed: u64,
        controller: Option<Py<PyAny>>,
        triggers: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Flight> {
        let mission = &self.inner;
        let mut prepared = self.prepared().map_err(|e| mission_error(&e))?;
        let mut functions: Vec<(String, Py<PyAny>)> = self
            .triggers
            .iter()
            .map(|(name, f)| (name.clone(), f.clone_ref(py)))
            .collect();
        for (name, function) in triggers.into_iter().flat_map(|d| d.iter()) {
            let name: String = name.extract().map_err(|_| {
                pyo3::exceptions::PyTypeError::new_err("triggers: keys are parachute names")
            })?;
            functions.retain(|(n, _)| *n != name);
            functions.push((name, function.unbind()));
        }
        let mut python_triggers = Vec::new();
        if !functions.is_empty() {
            let sensors = &mission.spec.rocket.sensors;
            for (name, function) in functions {
                let trigger = PythonTrigger::new(py, &name, function, sensors)?;
                python_triggers.push((name, trigger));
            }
            let conditions = python_triggers
                .iter()
                .map(|(name, t)| (name.clone(), Arc::clone(t) as Arc<dyn TriggerCondition>))
                .collect();
            prepared = Arc::new(
                prepared
                    .with_triggers(mission, conditions)
                    .map_err(|e| mission_error(&e))?,
            );
        }
        let run = self.fly_prepared(py, &prepared, seed, controller);
        for (_, trigger) in &python_triggers {
            if let Some(error) = trigger.take_error() {
                return Err(error);
            }
        }
        let run = run?;
        let name = mission
            .spec
            .name
            .clone()
            .unwrap_or_else(|| "karman flight".to_owned());
        Ok(Flight::new(run, name, seed))
    }

    /// A Monte Carlo study of the mission, in memory: `samples` and `seed` default to the
    /// mission's `[dispersion]`, `vary` (`{path: distribution}` as in `[dispersion.vary]`)
    /// replaces its inputs, `threads` defaults to one per core. The study is kept in memory;
    /// `out` also writes the files of `karman montecarlo --out` there (resumable). The GIL is released; Ctrl-C stops the study
    /// between samples (raising `KeyboardInterrupt`). `progress` shows a progress bar.
    #[pyo3(signature = (samples = None, seed = None, threads = None, vary = None, out = None, progress = true))]
    #[allow(clippy::too_many_arguments)]
    fn montecarlo(
        &self,
        py: Python<'_>,
        samples: Option<u64>,
        seed: Option<u64>,
        threads: Option<usize>,
        vary: Option<&Bound<'_, PyDict>>,
        out: Option<PathBuf>,
        progress: bool,
    ) -> PyResult<Study> {
        let mission = match vary {
            None => self.clone(),
            Some(vary) => {
                let table = to_toml(vary.as_any(), "dispersion.vary")?;
                let item = if self.inner.spec.dispersion.is_some() {
                    Override::new("dispersion.vary", &table.to_string())
                } else {
                    let samples = samples.ok_or_else(|| {
                        PyValueError::new_err(
                            "the mission has no [dispersion] table: give samples= with vary=",
                        )
                    })?;
                    Override::new(
                        "dispersion",
                        &format!(
                            "{{ samples = {samples}, seed = {}, vary = {table} }}",
                            seed.unwrap_or(0)
                        ),
                    )
                }
                .map_err(|e| override_error("dispersion.vary", &e))?;
                let mut overrides = self.overrides.clone();
                overrides.push(item);
                Mission::parse(self.text.clone(), &self.inner.path, overrides)?
            }
        };
        let study = MonteCarlo::new(&mission.inner, StudyOverrides { samples, seed })
            .map_err(|e| mission_error(&e))?;
        let options = RunOptions {
            threads,
            shard: None,
            progress: ProgressMode::Hidden,
        };
        let total = study.study().samples;
        let reporter: Option<Py<PyAny>> = if progress {
            Some(
                py.import("karman._progress")?
                    .getattr("Progress")?
                    .call1((total,))?
                    .unbind(),
            )
        } else {
            None
        };
        let stop = AtomicBool::new(false);
        let done = AtomicU64::new(0);
        let (result, interrupted) = py.detach(|| {
            std::thread::scope(|scope| {
                let (finished, wait) = std::sync::mpsc::channel::<()>();
                let (study, out, options, stop, done) = (&study, &out, &options, &stop, &done);
                let worker = scope.spawn(move || {
                    let fly = |index, values: &[f64]| {
                        let outcome = study.fly(index, values);
                        done.fetch_add(1, Ordering::Relaxed);
                        outcome
                    };
                    let result = match out {
                        // The CLI's files, then the rows read back from its samples.csv.
                        Some(dir) => run_until(study.study(), dir, options, stop, fly)
                            .map(|report| Run::Written(dir.clone(), report)),
                        None => run_in_memory(study.study(), options, stop, fly).map(Run::Memory),
                    };
                    let _ = finished.send(());
                    result
                });
                let mut interrupted: Option<PyErr> = None;
                while wait.recv_timeout(POLL).is_err() {
                    Python::attach(|py| {
                        if interrupted.is_none()
                            && let Err(error) = py.check_signals()
                        {
                            stop.store(true, Ordering::Relaxed);
                            interrupted = Some(error);
                        }
                        if let Some(reporter) = &reporter {
                            let _ = reporter
                                .bind(py)
                                .call_method1("update", (done.load(Ordering::Relaxed),));
                        }
                    });
                }
                (worker.join(), interrupted)
            })
        });
        if let Some(reporter) = &reporter {
            reporter
                .bind(py)
                .call_method1("close", (done.load(Ordering::Relaxed),))?;
        }
        if let Some(error) = interrupted {
            return Err(error);
        }
        let run = result
            .map_err(|_| PyRuntimeError::new_err("the Monte Carlo runner panicked"))?
            .map_err(|e| mission_error(&e))?;
        match run {
            Run::Memory(run) => Study::new(study.study(), run.rows, &run.report, None),
            Run::Written(dir, report) => Study::read(study.study(), &report, &dir),
        }
    }

    /// Fits the inputs named in `vary` (dotted paths such as `"rocket.power_off_drag"`,
    /// `"motor.total_impulse"`, `"rocket.parachutes.Main.cd_s"`, `"rocket.mass"`; one path or
    /// a list) to a flight log (`karman.read_log`), as `karman fit` does: the factors on
    /// their nominal values that make the simulation match the log best in least squares
    /// over the phase each acts on, within `max_flights` flights, every flight seeded with
    /// `seed`. Returns the dict of `karman fit --json` (`flights`, `converged`,
    /// `termination`, `clock_offset_s`, `correlation_inflation`, `warnings`, `inputs`,
    /// `phases`). `out` writes the mission file with the fitted values (a commented copy, as
    /// `karman fit -o`). The GIL is released during the fit. Raises `MissionError` for an
    /// input that cannot be fitted or a flight that fails, `LogError` for a log that cannot
    /// be compared with the flight or has too few samples in a phase.
    #[pyo3(signature = (log, vary, max_flights = FitOptions::default().max_flights, seed = 0, out = None))]
    fn fit<'py>(
        &self,
        py: Python<'py>,
        log: PyRef<'py, FlightLog>,
        vary: &Bound<'py, PyAny>,
        max_flights: usize,
        seed: u64,
        out: Option<PathBuf>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let vary: Vec<String> = if vary.is_instance_of::<PyString>() {
            vec![vary.extract()?]
        } else {
            vary.extract()?
        };
        if let Some(out) = &out
            && std::path::absolute(out).ok() == std::path::absolute(&self.inner.path).ok()
        {
            return Err(mission_error(&FitError::Write {
                file: out.display().to_string(),
                reason: "the fitted copy would replace the mission itself; write it elsewhere"
                    .to_owned(),
            }));
        }
        let options = FitOptions {
            vary,
            max_flights,
            seed,
        };
        let file = log.file();
        let log = log.inner();
        let mission = &self.inner;
        let value = py
            .detach(|| -> Result<serde_json::Value, FitError> {
                let result = karman_fit::fit(mission, log, &options)?;
                if let Some(out) = &out {
                    write_fitted(mission, &result, &file, out)?;
                }
                Ok(fit_json(&file, &result))
            })
            .map_err(|e| match e {
                FitError::Compare(_) | FitError::TooFewSamples { .. } => log_error(&e),
                _ => mission_error(&e),
            })?;
        plain(py, &value)
    }

    /// The value of the input `vary` (a dotted path, `"rocket.mass"`) at which the summary
    /// output `target` (`{"apogee_agl_m": 3048}`, one output) reaches its value within
    /// `tolerance` (the output's units), as `karman solve` finds it: Brent's bracketing root
    /// finder within `bounds` (`(low, high)`, default the nominal value ∓ 50 %), at most
    /// `max_flights` flights, each seeded with `seed`. Returns the dict of
    /// `karman solve --json` (`input`, `value`, `nominal`, `output`, `target`, `achieved`,
    /// `bounds`, `flights`, `trials`, `method`). The GIL is released. Raises `MissionError`
    /// for a target no value within the bounds reaches, reversed bounds, an unknown output or
    /// input, a failed flight, or no convergence within the budget.
    #[pyo3(signature = (target, vary, bounds = None, tolerance = None, max_flights = None, seed = 0))]
    #[allow(clippy::too_many_arguments)]
    fn solve<'py>(
        &self,
        py: Python<'py>,
        target: &Bound<'py, PyDict>,
        vary: String,
        bounds: Option<(f64, f64)>,
        tolerance: Option<f64>,
        max_flights: Option<usize>,
        seed: u64,
    ) -> PyResult<Bound<'py, PyAny>> {
        if target.len() != 1 {
            return Err(PyValueError::new_err(format!(
                "target takes one output and its value, e.g. {{\"apogee_agl_m\": 3048}}; got {} entries",
                target.len()
            )));
        }
        let Some((output, value)) = target.iter().next() else {
            return Err(PyValueError::new_err("target is empty"));
        };
        let output: String = output.extract()?;
        let value: f64 = value.extract()?;
        let defaults = karman_mission::solve::SolveOptions::new(vary, output, value);
        let options = karman_mission::solve::SolveOptions {
            bounds: bounds.map(|(low, high)| [low, high]),
            tolerance: tolerance.unwrap_or(defaults.tolerance),
            max_flights: max_flights.unwrap_or(defaults.max_flights),
            seed,
            ..defaults
        };
        let mission = &self.inner;
        let solution = py
            .detach(|| karman_mission::solve::solve(mission, &options))
            .map_err(|e| mission_error(&e))?;
        plain(py, &solution)
    }

    fn __repr__(&self) -> String {
        match &self.inner.spec.name {
            Some(name) => format!(
                "<karman.Mission {name:?} from {}>",
                self.inner.path.display()
            ),
            None => format!("<karman.Mission from {}>", self.inner.path.display()),
        }
    }
}

/// How often a running study looks for Ctrl-C and updates its progress display.
const POLL: Duration = Duration::from_millis(50);

/// A finished study: kept in memory, or written to the `out=` folder.
enum Run {
    Memory(MemoryRun),
    Written(PathBuf, RunReport),
}
