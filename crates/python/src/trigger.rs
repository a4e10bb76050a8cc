//! Parachute triggers written in Python: RocketPy's callable `trigger(p, h, y)` or
//! `trigger(p, h, y, sensors)`, called by the flight at each of the parachute's sampling
//! instants while it is pending (ascent included, as RocketPy samples a callable trigger):
//! `p` the noisy pressure signal (Pa), `h` the height above ground derived from it (m), `y`
//! a list of the 13 state values `[x, y, z, vx, vy, vz, e0, e1, e2, e3, w1, w2, w3]`, and
//! `sensors` a list with each of the rocket's sensors' latest reading (`measurement`: a float
//! for a barometer, a tuple of three otherwise; `None` before the first). A true result fires
//! the parachute. An exception stops the calls (the parachute never fires) and is raised when
//! the flight returns.

use std::sync::{Arc, Mutex};

use karman_mission::assemble::sensors::{components, signal_name};
use karman_mission::model::TriggerCondition;
use karman_mission::schema::SensorSpec;
use pyo3::prelude::*;
use pyo3::types::{PyList, PyTuple};

use crate::controller::PySensorReading;

/// A Python callable as a parachute's trigger condition.
pub struct PythonTrigger {
    /// The parachute it fires (for the error).
    parachute: String,
    function: Py<PyAny>,
    /// Whether the function takes `sensors` (four parameters) or not (three).
    with_sensors: bool,
    /// Every component signal of every sensor, in file order (read with `sensors`).
    signals: Vec<String>,
    /// The number of components of each sensor's reading (1: a barometer's float).
    shapes: Vec<usize>,
    /// The first exception the function raised.
    error: Mutex<Option<PyErr>>,
}

impl std::fmt::Debug for PythonTrigger {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PythonTrigger")
            .field("parachute", &self.parachute)
            .field("with_sensors", &self.with_sensors)
            .finish_non_exhaustive()
    }
}

impl PythonTrigger {
    /// `function` as the trigger of `parachute` on a rocket with `sensors`.
    ///
    /// # Errors
    /// `TypeError` when `function` is not callable or takes neither three nor four
    /// parameters.
    pub fn new(
        py: Python<'_>,
        parachute: &str,
        function: Py<PyAny>,
        sensors: &[SensorSpec],
    ) -> PyResult<Arc<Self>> {
        let bound = function.bind(py);
        let signature = "RocketPy's trigger(p, h, y[, sensors])";
        if !bound.is_callable() {
            return Err(pyo3::exceptions::PyTypeError::new_err(format!(
                "triggers[{parachute:?}]: not callable ({signature})"
            )));
        }
        let parameters = py
            .import("inspect")?
            .call_method1("signature", (bound,))?
            .getattr("parameters")?
            .len()?;
        let with_sensors = match parameters {
            3 => false,
            4 => true,
            n => {
                return Err(pyo3::exceptions::PyTypeError::new_err(format!(
                    "triggers[{parachute:?}]: takes {n} parameters; {signature} takes 3 or 4"
                )));
            }
        };
        let shapes: Vec<usize> = sensors.iter().map(|s| components(s.kind)).collect();
        let signals = sensors
            .iter()
            .zip(&shapes)
            .flat_map(|(s, &n)| (0..n).map(move |c| signal_name(&s.name, c)))
            .collect();
        Ok(Arc::new(PythonTrigger {
            parachute: parachute.to_owned(),
            function,
            with_sensors,
            signals,
            shapes,
            error: Mutex::new(None),
        }))
    }

    /// The exception the function raised, if it did (taken: asked once after the flight).
    pub fn take_error(&self) -> Option<PyErr> {
        self.error.lock().ok()?.take()
    }

    /// One call, with the GIL held.
    fn call(
        &self,
        py: Python<'_>,
        pressure: f64,
        height: f64,
        state: &[f64; 13],
        signals: &[f64],
    ) -> PyResult<bool> {
        py.check_signals()?;
        let y = PyList::new(py, state.iter().copied())?;
        let mut args: Vec<Py<PyAny>> = vec![
            pressure.into_pyobject(py)?.into_any().unbind(),
            height.into_pyobject(py)?.into_any().unbind(),
            y.into_any().unbind(),
        ];
        if self.with_sensors {
            let mut readings = Vec::with_capacity(self.shapes.len());
            let mut at = 0;
            for &n in &self.shapes {
                let values = signals.get(at..at + n).unwrap_or(&[]);
                at += n;
                let measurement = if values.len() < n || values.iter().any(|v| v.is_nan()) {
                    py.None()
                } else if n == 1 {
                    values[0].into_pyobject(py)?.into_any().unbind()
                } else {
                    PyTuple::new(py, values)?.into_any().unbind()
                };
                readings.push(Py::new(
                    py,
                    PySensorReading {
                        measurement,
                        time: None,
                    },
                )?);
            }
            args.push(PyList::new(py, readings)?.into_any().unbind());
        }
        self.function
            .bind(py)
            .call1(PyTuple::new(py, args)?)?
            .is_truthy()
    }
}

impl TriggerCondition for PythonTrigger {
    fn fires(&self, t: f64, pressure: f64, height: f64, state: &[f64; 13]) -> bool {
        self.fires_reading(t, pressure, height, state, &[])
    }

    fn signals(&self) -> &[String] {
        if self.with_sensors {
            &self.signals
        } else {
            &[]
        }
    }

    fn fires_reading(
        &self,
        _t: f64,
        pressure: f64,
        height: f64,
        state: &[f64; 13],
        signals: &[f64],
    ) -> bool {
        let Ok(mut error) = self.error.lock() else {
            return false;
        };
        if error.is_some() {
            return false;
        }
        Python::attach(|py| match self.call(py, pressure, height, state, signals) {
            Ok(fires) => fires,
            Err(e) => {
                *error = Some(e);
                false
            }
        })
    }
}
