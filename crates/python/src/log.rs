//! `karman.read_log` and `karman.FlightLog`: an altimeter or flight-computer log read by
//! karman-flightlog — the figures of `karman log show --json` and the samples as numpy
//! arrays.

use std::path::PathBuf;

use karman_flightlog::{FlightLog as RustFlightLog, ReadOptions, Sample};
use numpy::PyArray1;
use pyo3::prelude::*;

use crate::convert::plain;
use crate::log_error;

/// A flight log read and normalised: SI units, the time axis from liftoff, heights above the
/// ground.
#[pyclass(module = "karman", name = "FlightLog", frozen)]
pub struct FlightLog {
    log: RustFlightLog,
    path: PathBuf,
    json: serde_json::Value,
}

impl FlightLog {
    /// The log read.
    pub fn inner(&self) -> &RustFlightLog {
        &self.log
    }

    /// The file, as given to `read_log` (it names the log in comparisons and fits, as the
    /// command line's argument does).
    pub fn file(&self) -> String {
        self.path.display().to_string()
    }

    /// One value of `karman log show --json` as Python data.
    fn value<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Bound<'py, PyAny>> {
        plain(py, &self.json[key])
    }

    /// One series, NaN where a sample lacks it.
    fn series<'py>(
        &self,
        py: Python<'py>,
        pick: impl Fn(&Sample) -> Option<f64>,
    ) -> Bound<'py, PyArray1<f64>> {
        let values: Vec<f64> = self
            .log
            .samples
            .iter()
            .map(|s| pick(s).unwrap_or(f64::NAN))
            .collect();
        PyArray1::from_vec(py, values)
    }
}

/// Reads an altimeter or flight-computer log: its format detected from its content, or
/// named (`format="rrc3"`, the names of `karman log show --format`), or read as a generic
/// CSV through a column mapping (`mapping="time=ts,altitude=alt_ft:ft"`). Raises
/// `karman.LogError` (a `ValueError`) naming the file and line of what cannot be read.
#[pyfunction]
#[pyo3(signature = (path, format = None, mapping = None))]
pub fn read_log(
    py: Python<'_>,
    path: PathBuf,
    format: Option<&str>,
    mapping: Option<&str>,
) -> PyResult<FlightLog> {
    let options = ReadOptions::named(format, mapping).map_err(|e| log_error(&e))?;
    let log = py
        .detach(|| karman_flightlog::read_with(&path, &options))
        .map_err(|e| log_error(&e))?;
    let json = karman_fit::log_json(&log);
    Ok(FlightLog { log, path, json })
}

#[pymethods]
impl FlightLog {
    /// The file read.
    #[getter]
    fn path(&self) -> PathBuf {
        self.path.clone()
    }

    /// The format read (`"altusmetrum"`, `"rrc3"`, ..., `"generic"`).
    #[getter]
    fn format(&self) -> &'static str {
        self.log.format.name()
    }

    /// The device, as precise as the file says (family, model, serial).
    #[getter]
    fn device(&self) -> &str {
        &self.log.device
    }

    /// Number of samples.
    fn __len__(&self) -> usize {
        self.log.samples.len()
    }

    /// Median sampling rate of the altitude, Hz.
    #[getter]
    fn sample_rate_hz(&self) -> f64 {
        self.log.median_rate_hz()
    }

    /// Where the vertical velocity comes from: `"device"` or `"derivative"` (of the altitude).
    #[getter]
    fn velocity_source<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.value(py, "velocity_source")
    }

    /// Liftoff on the device's own clock, s (the samples' time zero).
    #[getter]
    fn liftoff_time_s(&self) -> f64 {
        self.log.liftoff_device_time_s
    }

    /// The highest altitude above the ground, m.
    #[getter]
    fn apogee_agl_m(&self) -> f64 {
        self.log.apogee().altitude_agl_m
    }

    /// Time of the highest altitude from liftoff, s.
    #[getter]
    fn apogee_time_s(&self) -> f64 {
        self.log.apogee().time_s
    }

    /// The highest vertical velocity, m/s.
    #[getter]
    fn max_vertical_velocity_mps(&self) -> f64 {
        self.log.max_vertical_velocity().0
    }

    /// Time of the highest vertical velocity from liftoff, s.
    #[getter]
    fn max_vertical_velocity_time_s(&self) -> f64 {
        self.log.max_vertical_velocity().1
    }

    /// The events in time order, each `{"kind", "time_s", "source"}` (`kind`: `launch`,
    /// `burnout`, `apogee`, `drogue`, `main`, `landing`; `source`: `device` or `derived`).
    #[getter]
    fn events<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.value(py, "events")
    }

    /// The device's own figures (`apogee_agl_m`, `ground_elevation_m`, `max_velocity_mps`;
    /// `None` where the file states none).
    #[getter]
    fn reported<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.value(py, "reported")
    }

    /// Everything else the header says, as text by lower-case key.
    #[getter]
    fn metadata<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.value(py, "metadata")
    }

    /// What the reading rules changed or could not read (with counts and first lines).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.log.warnings.clone()
    }

    /// The log as `karman log show --json` prints it.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        plain(py, &self.json)
    }

    /// Time from liftoff, s (negative before it).
    #[getter]
    fn time<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.series(py, |s| Some(s.time_s))
    }

    /// Height above the ground, m.
    #[getter]
    fn altitude<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.series(py, |s| Some(s.altitude_agl_m))
    }

    /// Vertical velocity, m/s (the device's, or the derivative of the altitude).
    #[getter]
    fn vertical_velocity<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.series(py, |s| Some(s.vertical_velocity_mps))
    }

    /// Acceleration as the device writes it, m/s² (NaN where a sample has none).
    #[getter]
    fn acceleration<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.series(py, |s| s.acceleration_mps2)
    }

    /// Static pressure, Pa (NaN where a sample has none).
    #[getter]
    fn pressure<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.series(py, |s| s.pressure_pa)
    }

    /// Temperature, K (NaN where a sample has none).
    #[getter]
    fn temperature<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.series(py, |s| s.temperature_k)
    }

    /// GNSS latitude, degrees north (NaN where a sample has no fix).
    #[getter]
    fn latitude<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.series(py, |s| s.gnss.map(|g| g.latitude_deg))
    }

    /// GNSS longitude, degrees east (NaN where a sample has no fix).
    #[getter]
    fn longitude<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.series(py, |s| s.gnss.map(|g| g.longitude_deg))
    }

    /// GNSS altitude above sea level, m (NaN where a sample has no fix or the fix no altitude).
    #[getter]
    fn gnss_altitude<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.series(py, |s| s.gnss.and_then(|g| g.altitude_m))
    }

    fn __repr__(&self) -> String {
        let apogee = self.log.apogee();
        format!(
            "<karman.FlightLog {} ({}, {}): {} samples, apogee {:.1} m AGL at {:.2} s>",
            self.path.display(),
            self.log.format.name(),
            self.log.device,
            self.log.samples.len(),
            apogee.altitude_agl_m,
            apogee.time_s
        )
    }
}
