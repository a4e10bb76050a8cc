//! Air-brake controllers written in Python: RocketPy's `controller_function(time,
//! sampling_rate, state, state_history, observed_variables, air_brakes[, sensors])` called by
//! the flight where the mission's Rhai controller would be (`karman_script::AirBrakeController`),
//! with RocketPy's arguments: `state` a list of the 13 state values, `state_history` a list
//! holding the last stored solution point `[t, x, …, wz]`, `observed_variables` the list of
//! every value the function returned other than `None` (RocketPy's), `air_brakes` an object
//! whose `deployment_level` the function reads and sets (clipped to [0, 1] when the brakes
//! clamp, as a Rhai write is), `sensors` a list with each sensor's latest reading
//! (`measurement`: a float for a barometer, a tuple of three otherwise; `None` before the
//! first). An exception ends the flight with its traceback in the error; Ctrl-C interrupts the
//! flight at the next call.

use karman_mission::script::{AirBrakeController, AirBrakesControl, ControlInputs, stored_level};
use pyo3::prelude::*;
use pyo3::types::{PyList, PyTuple};

/// The `air_brakes` argument of a Python controller.
#[pyclass(module = "karman", name = "AirBrakes")]
pub struct PyAirBrakes {
    level: f64,
    clamp: bool,
    reference_area: f64,
    override_rocket_drag: bool,
}

#[pymethods]
impl PyAirBrakes {
    /// The deployment level (0 shut, 1 fully open); set it to deploy the brakes.
    #[getter]
    fn deployment_level(&self) -> f64 {
        self.level
    }

    #[setter]
    fn set_deployment_level(&mut self, value: f64) {
        self.level = stored_level(self.clamp, value);
    }

    /// Whether written levels are clipped to [0, 1].
    #[getter]
    fn clamp(&self) -> bool {
        self.clamp
    }

    /// The brakes' reference area, m².
    #[getter]
    fn reference_area(&self) -> f64 {
        self.reference_area
    }

    /// Whether the brakes' curve replaces the rocket's drag while deployed.
    #[getter]
    fn override_rocket_drag(&self) -> bool {
        self.override_rocket_drag
    }
}

/// The `sensors` argument's items: one sensor's latest reading.
#[pyclass(module = "karman", name = "SensorReading", frozen)]
pub struct PySensorReading {
    /// The measurement: a float (barometer) or a tuple of three floats; `None` before the
    /// sensor's first reading.
    #[pyo3(get)]
    pub(crate) measurement: Py<PyAny>,
    /// When it was taken, s (`None` before the first reading).
    #[pyo3(get)]
    pub(crate) time: Option<f64>,
}

/// A Python callable as the flight's air-brake controller.
pub struct PythonController {
    function: Py<PyAny>,
    /// Whether the function takes `sensors` (seven parameters) or not (six).
    with_sensors: bool,
    /// RocketPy's `observed_variables`.
    observed: Py<PyList>,
    /// Whether each sensor is a barometer (one value) or has three.
    scalar: Vec<bool>,
    /// The exception that ended the flight, if one did.
    pub error: Option<PyErr>,
}

impl PythonController {
    /// `function` as a controller of a rocket whose sensors are barometers where `scalar`
    /// says so.
    ///
    /// # Errors
    /// `TypeError` when `function` is not callable or takes neither six nor seven arguments.
    pub fn new(py: Python<'_>, function: Py<PyAny>, scalar: Vec<bool>) -> PyResult<Self> {
        let bound = function.bind(py);
        if !bound.is_callable() {
            return Err(pyo3::exceptions::PyTypeError::new_err(
                "controller: not callable (RocketPy's controller_function(time, sampling_rate, \
                 state, state_history, observed_variables, air_brakes[, sensors]))",
            ));
        }
        let inspect = py.import("inspect")?;
        let parameters = inspect
            .call_method1("signature", (bound,))?
            .getattr("parameters")?
            .len()?;
        let with_sensors = match parameters {
            6 => false,
            7 => true,
            n => {
                return Err(pyo3::exceptions::PyTypeError::new_err(format!(
                    "controller: takes {n} parameters; RocketPy's controller_function takes 6 \
                     (time, sampling_rate, state, state_history, observed_variables, \
                     air_brakes) or 7 (and sensors)"
                )));
            }
        };
        Ok(PythonController {
            function,
            with_sensors,
            observed: PyList::empty(py).unbind(),
            scalar,
            error: None,
        })
    }

    /// One call, with the GIL held.
    fn call(
        &self,
        py: Python<'_>,
        inputs: &ControlInputs<'_>,
        air_brakes: &mut AirBrakesControl<'_>,
    ) -> PyResult<()> {
        py.check_signals()?;
        let brakes = Py::new(
            py,
            PyAirBrakes {
                level: air_brakes.deployment_level(),
                clamp: air_brakes.clamp(),
                reference_area: air_brakes.reference_area(),
                override_rocket_drag: air_brakes.override_rocket_drag(),
            },
        )?;
        let state = PyList::new(py, inputs.state.iter().copied())?;
        let history = PyList::new(py, [PyList::new(py, inputs.state_history.iter().copied())?])?;
        let mut args: Vec<Py<PyAny>> = vec![
            inputs.time.into_pyobject(py)?.into_any().unbind(),
            inputs.sampling_rate.into_pyobject(py)?.into_any().unbind(),
            state.into_any().unbind(),
            history.into_any().unbind(),
            self.observed.clone_ref(py).into_any(),
            brakes.clone_ref(py).into_any(),
        ];
        if self.with_sensors {
            let mut sensors = Vec::with_capacity(inputs.sensors.len());
            for (reading, scalar) in inputs.sensors.iter().zip(&self.scalar) {
                let (measurement, time) = match reading {
                    None => (py.None(), None),
                    Some(r) if *scalar => (
                        r.measurement[0].into_pyobject(py)?.into_any().unbind(),
                        Some(r.time),
                    ),
                    Some(r) => (
                        PyTuple::new(py, r.measurement)?.into_any().unbind(),
                        Some(r.time),
                    ),
                };
                sensors.push(Py::new(py, PySensorReading { measurement, time })?);
            }
            args.push(PyList::new(py, sensors)?.into_any().unbind());
        }
        let returned = self.function.bind(py).call1(PyTuple::new(py, args)?)?;
        if !returned.is_none() {
            self.observed.bind(py).append(returned)?;
        }
        air_brakes.set_deployment_level(brakes.borrow(py).level);
        Ok(())
    }
}

impl AirBrakeController for PythonController {
    fn control(
        &mut self,
        inputs: &ControlInputs<'_>,
        air_brakes: &mut AirBrakesControl<'_>,
    ) -> Result<(), String> {
        Python::attach(|py| {
            self.call(py, inputs, air_brakes).map_err(|error| {
                let text = traceback_text(py, &error);
                self.error = Some(error);
                text
            })
        })
    }
}

/// The exception's traceback as Python prints it.
fn traceback_text(py: Python<'_>, error: &PyErr) -> String {
    let formatted = py.import("traceback").and_then(|tb| {
        tb.call_method1(
            "format_exception",
            (error.get_type(py), error.value(py), error.traceback(py)),
        )
    });
    match formatted.and_then(|lines| lines.extract::<Vec<String>>()) {
        Ok(lines) => format!(
            "the Python controller raised:\n{}",
            lines.concat().trim_end()
        ),
        Err(_) => format!("the Python controller raised {error}"),
    }
}
