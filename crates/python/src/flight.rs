//! `karman.Flight`: one flown mission — the summary of `karman simulate --json`, the events,
//! and every series of `trajectory.csv` as numpy arrays.

use std::path::PathBuf;
use std::sync::OnceLock;

use karman_mission::assemble::flight::FlightRun;
use karman_mission::dynamics::{Sample, Summary};
use karman_mission::report::trajectory::{self, SERIES};
use numpy::PyArray1;
use pyo3::exceptions::{PyAttributeError, PyKeyError, PyOSError, PyRuntimeError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{from_json, plain};
use crate::log::FlightLog;
use crate::log_error;

/// The names of the trajectory series, in the column order of `trajectory.csv`.
pub fn series_names() -> Vec<&'static str> {
    SERIES.iter().map(|s| s.name).collect()
}

/// A flown mission. The summary and the trajectory are computed on first use.
#[pyclass(module = "karman", frozen)]
pub struct Flight {
    run: FlightRun,
    name: String,
    seed: u64,
    summary: OnceLock<Summary>,
    samples: OnceLock<Vec<Sample>>,
}

impl Flight {
    /// Wraps a flown mission named `name`, flown with trigger-noise `seed`.
    pub fn new(run: FlightRun, name: String, seed: u64) -> Self {
        Flight {
            run,
            name,
            seed,
            summary: OnceLock::new(),
            samples: OnceLock::new(),
        }
    }

    fn summary_ref(&self) -> &Summary {
        self.summary.get_or_init(|| self.run.summary())
    }

    fn samples_ref(&self) -> &[Sample] {
        self.samples.get_or_init(|| self.run.samples())
    }

    fn summary_json(&self) -> PyResult<serde_json::Value> {
        serde_json::to_value(self.summary_ref()).map_err(|e| PyRuntimeError::new_err(e.to_string()))
    }

    fn column<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let series = trajectory::series_named(name).ok_or_else(|| {
            PyKeyError::new_err(format!(
                "no series `{name}`; the series are {}",
                series_names().join(", ")
            ))
        })?;
        let values: Vec<f64> = self
            .samples_ref()
            .iter()
            .map(|s| series.value(&self.run, s))
            .collect();
        Ok(PyArray1::from_vec(py, values))
    }
}

fn write(path: &PathBuf, text: &str) -> PyResult<()> {
    std::fs::write(path, text)
        .map_err(|e| PyOSError::new_err(format!("cannot write {}: {e}", path.display())))
}

#[pymethods]
impl Flight {
    /// One trajectory series by name (`flight["altitude_agl"]`), a float64 array with one
    /// value per stored point; `karman.SERIES` lists the names, `units` their units.
    fn __getitem__<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.column(py, name)
    }

    /// The times of the stored points, s.
    #[getter]
    fn t<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.column(py, "time")
    }

    /// The series names.
    #[getter]
    fn series(&self) -> Vec<&'static str> {
        series_names()
    }

    /// The unit of each series (`"m"`, `"mps"`, `"deg"`; `""` for pure numbers).
    #[getter]
    fn units<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        for s in SERIES {
            dict.set_item(s.name, s.unit)?;
        }
        Ok(dict)
    }

    /// The summary as `karman simulate --json` prints it (apogee, rail exit, maxima, impact,
    /// events, the mission's warnings; SI units, `None` for what did not happen).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let dict = plain(py, self.summary_ref())?;
        dict.set_item("warnings", self.run.warnings.clone())?;
        Ok(dict)
    }

    /// The mission's warnings (physical sanity, odd data files), each starting with the key
    /// it concerns.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.run.warnings.clone()
    }

    /// The flight's events (`rail exit`, `apogee`, parachute triggers, `impact`), each a dict.
    #[getter]
    fn events<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        plain(py, &self.summary_ref().events)
    }

    /// How the flight ended: `"impact"`, `"apogee"`, `"max_time"`, `"stuck_on_rail"`,
    /// `"terminated"` (by a controller) or `"separation"`.
    #[getter]
    fn termination(&self) -> String {
        serde_json::to_value(self.summary_ref().termination)
            .ok()
            .and_then(|v| v.as_str().map(str::to_owned))
            .unwrap_or_default()
    }

    /// The seed of the parachute trigger noise.
    #[getter]
    fn seed(&self) -> u64 {
        self.seed
    }

    /// The mission's name.
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// Integrator counters: steps, rejected steps, Runge–Kutta–Chebyshev steps,
    /// right-hand-side evaluations, phases.
    #[getter]
    fn integration<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        plain(py, &self.run.flight.stats)
    }

    /// The flight set against a flight log (`karman.read_log`) on one time axis from liftoff,
    /// as one entry of the `logs` list of `karman compare --json`: `apogee_m` (the log's),
    /// `apogee_error_m` and `apogee_error_pct` (simulated − measured, the simulated altitude
    /// counted from the pad), `apogee_time_error_s`, `max_velocity_error_pct`,
    /// `ascent_rms_altitude_m`, `ascent_rms_velocity_mps`, `descent_rate_error_pct`
    /// (`{parachute: %}`), `descent` (per parachute phase), `landing` (`None` without GNSS
    /// fixes), ... Raises `karman.LogError` when the two cannot be compared.
    fn compare<'py>(
        &self,
        py: Python<'py>,
        log: PyRef<'py, FlightLog>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let file = log.file();
        let inner = log.inner();
        let value = py
            .detach(|| {
                let simulated =
                    karman_fit::simulated_flight(self.samples_ref(), self.summary_ref());
                karman_flightlog::compare(&simulated, inner)
                    .map(|c| karman_fit::comparison_json(&file, inner, &c))
            })
            .map_err(|e| log_error(&e))?;
        plain(py, &value)
    }

    /// The rocket's static margin at time `t` (calibres).
    fn static_margin(&self, t: f64) -> f64 {
        self.run.rocket.static_margin(t)
    }

    /// Summary values as attributes: `flight.apogee_agl_m`, `flight.out_of_rail_velocity_mps`.
    fn __getattr__<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        let summary = self.summary_json()?;
        match summary.get(name) {
            Some(value) if name != "events" => from_json(py, value),
            _ => Err(PyAttributeError::new_err(format!(
                "'Flight' object has no attribute '{name}'"
            ))),
        }
    }

    fn __dir__(&self) -> PyResult<Vec<String>> {
        let mut names: Vec<String> = [
            "t",
            "series",
            "units",
            "to_dict",
            "events",
            "termination",
            "seed",
            "name",
            "integration",
            "static_margin",
            "compare",
            "to_pandas",
            "export_csv",
            "export_kml",
            "plot",
        ]
        .iter()
        .map(|s| (*s).to_owned())
        .collect();
        if let serde_json::Value::Object(map) = self.summary_json()? {
            names.extend(map.keys().filter(|k| *k != "events").cloned());
        }
        Ok(names)
    }

    /// Every series as a pandas DataFrame (columns named with their units, as in
    /// `trajectory.csv`); needs pandas.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let pandas = py.import("pandas")?;
        let columns = PyDict::new(py);
        for s in SERIES {
            columns.set_item(s.column(), self.column(py, s.name)?)?;
        }
        pandas.getattr("DataFrame")?.call1((columns,))
    }

    /// Writes `trajectory.csv` (as `karman simulate --out` does) to `path`.
    fn export_csv(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let text = py.detach(|| trajectory::csv(&self.run, self.samples_ref()));
        write(&path, &text)
    }

    /// Writes the flight path as KML (as `karman simulate --out` writes `flight.kml`).
    fn export_kml(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let text = py.detach(|| trajectory::kml(&self.run, &self.name, self.samples_ref()));
        write(&path, &text)
    }

    /// The figures `karman simulate --out` draws (altitude, ground track, speed and Mach,
    /// attitude, stability) with matplotlib; `which` chooses some, `path` saves them (one
    /// file per figure, `{name}` in it replaced), `show` displays them. Returns the
    /// matplotlib figures by name.
    #[pyo3(signature = (which = None, path = None, show = false))]
    fn plot<'py>(
        slf: &Bound<'py, Self>,
        which: Option<Vec<String>>,
        path: Option<String>,
        show: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        slf.py()
            .import("karman._plot")?
            .getattr("plot_flight")?
            .call1((slf, which, path, show))
    }

    fn __repr__(&self) -> String {
        let summary = self.summary_ref();
        match summary.apogee_agl_m {
            Some(apogee) => format!(
                "<karman.Flight {:?}: apogee {apogee:.1} m AGL at {:.2} s, {}>",
                self.name,
                summary.apogee_time_s.unwrap_or(f64::NAN),
                self.termination()
            ),
            None => format!("<karman.Flight {:?}: {}>", self.name, self.termination()),
        }
    }
}
