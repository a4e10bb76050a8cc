//! The scripts of a mission bound to its flight: trigger expressions and time triggers as the
//! engine's [`TriggerCondition`]s, and the air-brake controller as a sampled process of the
//! engine whose deployment level is control input [`AIR_BRAKES_CONTROL`] of the
//! configuration (docs/physics.md §16.4, §17).

use std::sync::Arc;

use karman_airframe::{AIR_BRAKES_CONTROL, Rocket};
use karman_atmos::Environment;
use karman_dynamics::DynamicsError;
use karman_dynamics::flight::{Action, Connections, Probe, SampledProcess, SignalId};
use karman_model::TriggerCondition;
use karman_script::{
    AirBrakeController, AirBrakesSetup, Controller, ControllerScript, ControllerSetup,
    EnvironmentQuery, Expression, NativeController, ScriptError, TriggerInputs,
};

use crate::schema::AirBrakesSpec;
use crate::{Mission, MissionError};

/// A trigger expression as an engine trigger condition: RocketPy's `trigger(p, h, y,
/// sensors)`, the sensor readings it reads ([`Expression::reads`]) taken from the signals
/// the flight's sensors publish (`super::sensors::signal_name`).
#[derive(Debug)]
pub struct ExpressionTrigger {
    expression: Expression,
    /// The signal of each of the expression's reads, in its order.
    signals: Vec<String>,
}

impl ExpressionTrigger {
    /// The trigger of `expression`, parsed for the rocket's `sensors` (in file order).
    #[must_use]
    pub fn new(expression: Expression, sensors: &[crate::schema::SensorSpec]) -> Self {
        let signals = expression
            .reads()
            .iter()
            .map(|&(sensor, component)| {
                let name = sensors.get(sensor).map_or("", |s| s.name.as_str());
                super::sensors::signal_name(name, component)
            })
            .collect();
        Self {
            expression,
            signals,
        }
    }
}

impl TriggerCondition for ExpressionTrigger {
    fn fires(&self, t: f64, pressure: f64, height: f64, state: &[f64; 13]) -> bool {
        self.fires_reading(t, pressure, height, state, &[])
    }

    fn signals(&self) -> &[String] {
        &self.signals
    }

    fn fires_reading(
        &self,
        _t: f64,
        pressure: f64,
        height: f64,
        state: &[f64; 13],
        signals: &[f64],
    ) -> bool {
        let inputs = TriggerInputs {
            pressure,
            height,
            state: *state,
        };
        self.expression.evaluate_with(&inputs, signals)
    }
}

/// `"launch + X"` and `"burnout + X"`: fires at the first sampling instant at or after `t`
/// (RocketPy 1.14: `t >= delay`, `t >= burn_out_time + delay`).
#[derive(Debug)]
pub struct AfterTime(pub f64);

impl TriggerCondition for AfterTime {
    fn fires(&self, t: f64, _pressure: f64, _height: f64, _state: &[f64; 13]) -> bool {
        t >= self.0
    }
}

/// The controller script of a mission's air brakes, compiled (once per mission).
///
/// # Errors
/// [`MissionError::Model`] (section `rocket.air_brakes.controller`) when the script cannot be
/// read or does not compile; `Ok(None)` without air brakes.
pub fn compile_controller(mission: &Mission) -> Result<Option<ControllerScript>, MissionError> {
    let Some(ab) = &mission.spec.rocket.air_brakes else {
        return Ok(None);
    };
    let file = mission.resolve(&ab.controller);
    let fail = |source: Box<dyn std::error::Error + Send + Sync>| {
        mission.model_error("rocket.air_brakes.controller", source)
    };
    let bytes = karman_math::read_data_file(&file).map_err(|e| fail(Box::new(e)))?;
    let text = String::from_utf8(bytes).map_err(|e| fail(Box::new(e)))?;
    ControllerScript::compile(&file, &text)
        .map(Some)
        .map_err(|e| fail(Box::new(e)))
}

/// Calls the air-brake controller of `mission` once as its flight's first call is made, so
/// that `karman check` reports what that call would end the flight with (a run-time type
/// error, an unknown property or method, a limit of the sandbox, a value the record refuses),
/// located in the script: at t = 0 s, the rocket at rest on the pad (at the launch site's
/// elevation, upright, not turning), with the arguments the flight passes, on a controller of
/// its own (the flight's starts afresh): its sensors unread (`()`), or, with `time_overshoot =
/// false`, where the flight measures them first, each reading the pad at rest.
///
/// # Errors
/// [`MissionError::Flight`] (section `rocket.air_brakes.controller`), the message the flight
/// would end with; [`controller`]'s errors.
pub fn first_call(
    mission: &Mission,
    script: &ControllerScript,
    rocket: &Rocket,
    environment: &Environment,
) -> Result<(), MissionError> {
    let queries = Arc::new(ControllerEnvironment::new(
        Arc::new(environment.clone()),
        1.0,
        0.0,
    ));
    let mut controller = controller(mission, script, rocket, queries)?;
    let mut state = [0.0; 13];
    state[2] = environment.elevation();
    state[6] = 1.0;
    if !mission.spec.flight.time_overshoot {
        // The flight measures the sensors before the controller at t = 0 (docs/physics.md
        // §29.3): hand the call a reading of each, the pad at rest (where the flight's first
        // call sees `()` instead, it gets `()` here too).
        let surroundings = super::sensors::EnvironmentSurroundings(environment);
        let truth = karman_sensors::Truth {
            u: state,
            u_dot: [0.0; 13],
        };
        for (i, mut sensor) in super::sensors::build(mission, rocket, 0)?
            .into_iter()
            .enumerate()
        {
            controller.set_sensor(i, 0.0, sensor.measure(&truth, &surroundings));
        }
    }
    let mut row = [0.0; 14];
    row[1..].copy_from_slice(&state);
    controller
        .call(0.0, &state, &row)
        .map(|_| ())
        .map_err(|e| mission.flight_error("rocket.air_brakes.controller", e))
}

/// The environment a controller queries: the flight's, with its wind scaled and turned as
/// the flight's (`factor`, and the rotation `sin`, `cos`; identity for a plain flight).
pub struct ControllerEnvironment {
    environment: Arc<Environment>,
    factor: f64,
    sin: f64,
    cos: f64,
}

impl ControllerEnvironment {
    /// The environment with the wind multiplied by `factor` and turned clockwise by
    /// `offset_deg` (as `super::environment::WindAdjusted`).
    #[must_use]
    pub fn new(environment: Arc<Environment>, factor: f64, offset_deg: f64) -> Self {
        let (sin, cos) = offset_deg.to_radians().sin_cos();
        Self {
            environment,
            factor,
            sin,
            cos,
        }
    }

    fn wind(&self, h: f64) -> [f64; 2] {
        let [u, v] = self.environment.wind(h);
        if self.factor.to_bits() == 1.0f64.to_bits() && self.sin.to_bits() == 0 {
            return [u, v];
        }
        [
            self.factor * (u * self.cos + v * self.sin),
            self.factor * (-u * self.sin + v * self.cos),
        ]
    }
}

impl EnvironmentQuery for ControllerEnvironment {
    fn elevation(&self) -> f64 {
        self.environment.elevation()
    }
    fn wind_velocity_x(&self, height: f64) -> f64 {
        self.wind(height)[0]
    }
    fn wind_velocity_y(&self, height: f64) -> f64 {
        self.wind(height)[1]
    }
    fn speed_of_sound(&self, height: f64) -> f64 {
        self.environment.speed_of_sound(height)
    }
    fn density(&self, height: f64) -> f64 {
        self.environment.density(height)
    }
    fn pressure(&self, height: f64) -> f64 {
        self.environment.pressure(height)
    }
    fn temperature(&self, height: f64) -> f64 {
        self.environment.temperature(height)
    }
    fn dynamic_viscosity(&self, height: f64) -> f64 {
        self.environment.dynamic_viscosity(height)
    }
    fn gravity(&self, height: f64) -> f64 {
        self.environment.gravity(height)
    }
}

/// The air brakes of `rocket` as a controller sees them, with the mission's
/// `[rocket.air_brakes]` they were built from.
///
/// # Errors
/// [`MissionError::Model`] (section `rocket.air_brakes`) when the rocket has no air brakes.
fn air_brakes_setup<'m>(
    mission: &'m Mission,
    rocket: &Rocket,
) -> Result<(AirBrakesSetup, &'m AirBrakesSpec), MissionError> {
    let (Some(spec), Some(brakes)) = (&mission.spec.rocket.air_brakes, rocket.air_brakes()) else {
        return Err(mission.model_error("rocket.air_brakes", "the rocket has no air brakes"));
    };
    let curve = brakes.clone();
    let setup = AirBrakesSetup {
        clamp: brakes.clamp(),
        override_rocket_drag: brakes.override_rocket_drag(),
        reference_area: brakes.reference_area(),
        initial_level: brakes.initial_level(),
        drag_coefficient: Arc::new(move |level, mach| curve.drag_coefficient(level, mach)),
    };
    Ok((setup, spec))
}

/// A flight's controller for `rocket`'s air brakes, from the compiled `script`.
///
/// # Errors
/// [`MissionError::Model`] (section `rocket.air_brakes`) when the rocket has no air brakes or
/// the script's top-level statements fail.
pub fn controller(
    mission: &Mission,
    script: &ControllerScript,
    rocket: &Rocket,
    environment: Arc<dyn EnvironmentQuery>,
) -> Result<Controller, MissionError> {
    let (air_brakes, spec) = air_brakes_setup(mission, rocket)?;
    let setup = ControllerSetup {
        sampling_rate: spec.sampling_rate,
        air_brakes,
        burn_start: rocket.burn_start(),
        burn_out: rocket.burn_out(),
        environment,
        initial_observed_variables: spec.initial_observed_variables.clone(),
        constants: spec
            .constants
            .iter()
            .map(|(name, value)| (name.clone(), *value))
            .collect(),
    };
    let sensors = super::sensors::setups(&mission.spec.rocket.sensors);
    Controller::new(script, setup)
        .map(|c| c.with_sensors(&sensors))
        .map_err(|e| mission.model_error("rocket.air_brakes", e))
}

/// The calls of a Rust `controller` of `rocket`'s air brakes in a flight of `mission`, at the
/// sampling rate of its `[rocket.air_brakes]`, with its sensors.
///
/// # Errors
/// [`MissionError::Model`] (section `rocket.air_brakes`) when the rocket has no air brakes.
pub fn native_controller<'c>(
    mission: &Mission,
    controller: &'c mut dyn AirBrakeController,
    rocket: &Rocket,
    environment: Arc<dyn EnvironmentQuery>,
) -> Result<NativeController<'c>, MissionError> {
    let (setup, spec) = air_brakes_setup(mission, rocket)?;
    Ok(NativeController::new(
        controller,
        setup,
        spec.sampling_rate,
        rocket.burn_out(),
        environment,
        mission.spec.rocket.sensors.len(),
    ))
}

/// A flight's calls of its air-brake controller, whichever language it is written in: the
/// Rhai [`Controller`] and the Rust [`NativeController`] are driven by the same
/// [`ControllerProcess`], so they are called at the same instants with the same arguments.
pub trait ControllerCalls {
    /// Calls per second.
    fn sampling_rate(&self) -> f64;
    /// The current deployment level.
    fn level(&self) -> f64;
    /// Hands sensor `index` its latest reading, taken at `time`.
    fn set_sensor(&mut self, index: usize, time: f64, values: [f64; 3]);
    /// One call at sampling instant `time`; the level it leaves.
    ///
    /// # Errors
    /// The controller's error (a Rhai script's located in the script).
    fn call(
        &mut self,
        time: f64,
        state: &[f64; 13],
        last_row: &[f64; 14],
    ) -> Result<f64, Box<dyn std::error::Error + Send + Sync>>;
}

impl ControllerCalls for Controller {
    fn sampling_rate(&self) -> f64 {
        Controller::sampling_rate(self)
    }
    fn level(&self) -> f64 {
        Controller::level(self)
    }
    fn set_sensor(&mut self, index: usize, time: f64, values: [f64; 3]) {
        Controller::set_sensor(self, index, time, values);
    }
    fn call(
        &mut self,
        time: f64,
        state: &[f64; 13],
        last_row: &[f64; 14],
    ) -> Result<f64, Box<dyn std::error::Error + Send + Sync>> {
        Controller::call(self, time, state, last_row).map_err(|e: ScriptError| e.into())
    }
}

impl ControllerCalls for NativeController<'_> {
    fn sampling_rate(&self) -> f64 {
        NativeController::sampling_rate(self)
    }
    fn level(&self) -> f64 {
        NativeController::level(self)
    }
    fn set_sensor(&mut self, index: usize, time: f64, values: [f64; 3]) {
        NativeController::set_sensor(self, index, time, values);
    }
    fn call(
        &mut self,
        time: f64,
        state: &[f64; 13],
        last_row: &[f64; 14],
    ) -> Result<f64, Box<dyn std::error::Error + Send + Sync>> {
        NativeController::call(self, time, state, last_row).map_err(Into::into)
    }
}

/// The controller as a sampled process of the engine: called at `j / sampling_rate` in every
/// phase (the rail too), in time order after the parachutes due at the same instant; a new
/// level acts from the end of the solver step (`time_overshoot`) or from the instant itself.
/// A script error ends the flight there ([`Action::Terminate`]) and is kept in `error`.
/// Before each call it hands the controller the latest reading of each sensor of its
/// `sensors` argument, read from the signals the sensors publish (none before a sensor's
/// first reading: its `measurement` stays `()`).
pub struct ControllerProcess<'c> {
    /// The flight's controller.
    pub controller: &'c mut dyn ControllerCalls,
    /// The first controller error, if any.
    pub error: &'c mut Option<Box<dyn std::error::Error + Send + Sync>>,
    /// RocketPy's `time_overshoot`.
    pub overshoot: bool,
    /// The signal names of each sensor's components, in the order of the controller's
    /// `sensors` argument (`super::sensors::signal_name`).
    pub sensor_signals: &'c [Vec<String>],
    /// Their ids, found when the flight is set up.
    pub sensor_ids: Vec<Vec<SignalId>>,
}

impl SampledProcess for ControllerProcess<'_> {
    fn rate(&self) -> f64 {
        self.controller.sampling_rate()
    }

    fn on_rail(&self) -> bool {
        true
    }

    fn whole_step(&self) -> bool {
        true
    }

    fn connect(&mut self, connections: &Connections<'_>) -> Result<(), DynamicsError> {
        self.sensor_ids = self
            .sensor_signals
            .iter()
            .map(|names| names.iter().map(|n| connections.signal(n)).collect())
            .collect::<Result<_, _>>()?;
        Ok(())
    }

    fn sample(&mut self, probe: &mut Probe<'_>) -> Option<Action> {
        if self.error.is_some() {
            return None;
        }
        for (i, ids) in self.sensor_ids.iter().enumerate() {
            let Some(first) = ids.first().and_then(|id| probe.read(*id)) else {
                continue;
            };
            let mut values = [f64::NAN; 3];
            for (value, id) in values.iter_mut().zip(ids) {
                *value = probe.read(*id).map_or(f64::NAN, |s| s.value);
            }
            self.controller.set_sensor(i, first.t, values);
        }
        let state = probe.state();
        let (t_end, end) = probe.step_end();
        let mut row = [0.0; 14];
        row[0] = t_end;
        row[1..].copy_from_slice(&end);
        let before = self.controller.level();
        match self.controller.call(probe.t(), &state, &row) {
            Ok(level) if level.to_bits() == before.to_bits() => None,
            Ok(value) if self.overshoot => Some(Action::SetControlAfterStep {
                index: AIR_BRAKES_CONTROL,
                value,
            }),
            Ok(value) => Some(Action::SetControl {
                index: AIR_BRAKES_CONTROL,
                value,
            }),
            Err(error) => {
                *self.error = Some(error);
                Some(Action::Terminate)
            }
        }
    }
}
