//! # karman-python
//!
//! The `karman` Python package's extension module (`karman._karman`), built with PyO3 for the
//! stable ABI of CPython 3.10 and later (`pip install ./crates/python`, maturin). It binds
//! the mission crate's public API — load, overrides, model reports, one flight, a Monte Carlo
//! study — and hands results to Python as numpy arrays:
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
//! - `study.rs`: `karman.Study`, a Monte Carlo study in memory, run by the same runner as
//!   `karman montecarlo` (same samples, same bytes when written with `out=`), with the GIL
//!   released and Ctrl-C stopping it between samples.
//!
//! The pure-Python half of the package (`python/karman`: plots, progress display, the
//! RocketPy adapter `karman.rocketpy.from_rocketpy`) and the type stubs live beside this
//! crate; its tests are the pytest suite in `tests/`.

mod convert;
mod flight;
mod mission;
mod study;

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

/// The extension module `karman._karman`.
#[pymodule]
fn _karman(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("MissionError", m.py().get_type::<MissionError>())?;
    m.add_class::<mission::Mission>()?;
    m.add_class::<flight::Flight>()?;
    m.add_class::<study::Study>()?;
    m.add_function(wrap_pyfunction!(mission::load, m)?)?;
    m.add("SERIES", flight::series_names())?;
    m.add("SUMMARY_KEYS", karman_mission::montecarlo::OUTPUTS.to_vec())?;
    Ok(())
}
