//! # karman-python
//!
//! The `karman` Python package's extension module (`karman._karman`), built with PyO3 for the
//! stable ABI of CPython 3.10 and later (`pip install ./crates/python`, maturin). It binds
//! the mission crate's public API — load, overrides, model reports, one flight, a Monte Carlo
//! study — and the flight-log crates' (read a log, compare it with a flight, fit a mission
//! to it), and hands results to Python as numpy arrays:
//!
//! ```python
//! import karman
//! mission = karman.load("fixtures/example.toml", overrides={"flight.inclination": 84})
//! flight = mission.simulate(seed=0)
//! print(flight.apogee_agl_m, flight["altitude_agl"].max())
//! study = mission.montecarlo(samples=200, seed=1, threads=2)
//! print(study.outputs["apogee_agl_m"].std())
//! ```
//!
//! - `mission.rs`: `karman.load`, `karman.Mission` (`from_toml`, `from_dict`, `set`, `to_toml`,
//!   `inspect`, `simulate`, `montecarlo`); every mission error is a `karman.MissionError`
//!   carrying the command-line interface's located message.
//! - `flight.rs`: `karman.Flight`, the summary of `karman simulate --json` and every
//!   trajectory series of `trajectory.csv`.
//! - `log.rs`: `karman.read_log`, `karman.FlightLog`: an altimeter log read by
//!   karman-flightlog, the figures of `karman log show --json` and the samples as numpy
//!   arrays; `Flight.compare(log)` and `Mission.fit(log, vary=...)` set a log against a
//!   flight (karman-flightlog's comparison) and fit the mission's inputs to it (karman-fit),
//!   returning the dicts of `karman compare --json` and `karman fit --json` (karman-fit's
//!   JSON shapes, one definition for both); every log error is a `karman.LogError`.
//! - `study.rs`: `karman.Study`, a Monte Carlo study in memory, run by the same runner as
//!   `karman montecarlo` (the same rows and summary; `out=` writes the CLI's files), with the
//!   GIL released and Ctrl-C stopping it between samples.
//!
//! The pure-Python half of the package (`python/karman`: plots, progress display, the
//! RocketPy adapter `karman.rocketpy.from_rocketpy`) and the type stubs live beside this
//! crate; its tests are the pytest suite in `tests/`.

mod controller;
mod convert;
mod flight;
mod log;
mod mission;
mod study;
mod trigger;

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

create_exception!(
    karman,
    MissionError,
    PyValueError,
    "A mission that cannot be read, overridden, validated, built or flown; the message is the \
     command-line interface's, with file, line, column and key."
);

create_exception!(
    karman,
    LogError,
    PyValueError,
    "A flight log that cannot be read or compared with a flight; the message names the file \
     and, where one line is at fault, the line."
);

/// The message of an error and its sources, as the command-line interface prints it
/// (`outer: inner: ...`).
pub(crate) fn chain(error: &dyn std::error::Error) -> String {
    let mut text = error.to_string();
    let mut source = error.source();
    while let Some(inner) = source {
        text.push_str(": ");
        text.push_str(&inner.to_string());
        source = inner.source();
    }
    text
}

/// A [`MissionError`] exception from any error of the mission crate.
pub(crate) fn mission_error(error: &dyn std::error::Error) -> PyErr {
    MissionError::new_err(chain(error))
}

/// A [`LogError`] exception from an error of karman-flightlog.
pub(crate) fn log_error(error: &dyn std::error::Error) -> PyErr {
    LogError::new_err(chain(error))
}

/// The extension module `karman._karman`.
#[pymodule]
fn _karman(m: &Bound<'_, PyModule>) -> PyResult<()> {
    karman_mission::allocator::keep_freed_heap();
    m.add("MissionError", m.py().get_type::<MissionError>())?;
    m.add("LogError", m.py().get_type::<LogError>())?;
    m.add_class::<mission::Mission>()?;
    m.add_class::<flight::Flight>()?;
    m.add_class::<study::Study>()?;
    m.add_class::<log::FlightLog>()?;
    m.add_class::<controller::PyAirBrakes>()?;
    m.add_class::<controller::PySensorReading>()?;
    m.add_function(wrap_pyfunction!(mission::load, m)?)?;
    m.add_function(wrap_pyfunction!(log::read_log, m)?)?;
    m.add("SERIES", flight::series_names())?;
    m.add("SUMMARY_KEYS", karman_mission::montecarlo::OUTPUTS.to_vec())?;
    Ok(())
}
