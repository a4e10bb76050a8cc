//! `[flight]` → [`karman_dynamics::FlightSettings`], and [`simulate`]: a whole mission flown
//! (environment, motor and rocket built and checked, then the flight integrated).
//!
//! Defaults are RocketPy 1.13's `Flight` defaults (docs/physics.md §1): inclination 80°, heading
//! 90°, `max_time` 600 s, `rtol` 1e-6, per-state `atol` (1e-3 for positions, velocities and
//! rates, 1e-6 for the quaternion), unbounded step. The schema already applies them; an
//! absent `atol` means the per-state default.

use std::sync::Arc;

use karman_airframe::Rocket;
use karman_atmos::Environment;
use karman_dynamics::{AtmosphereModel, Flight, FlightSettings, Sample, Summary, Termination};
use karman_model::{TriggerCondition, TriggerKind};
use karman_propulsion::Motor;
use karman_script::{AirBrakeController, ControllerRecord, ControllerScript, EnvironmentQuery};
use karman_sensors::{Sensor, Surroundings};

use super::preflight::{Models, prepare};
use super::scripts::{
    self, ControllerCalls, ControllerEnvironment, ControllerProcess, compile_controller,
};
use super::sensors::{self, EnvironmentSurroundings, SensorProcess, SensorReadings};
use crate::{Mission, MissionError};

/// How a flight ended against the end a mission asks for: `None` for a completed flight
/// (ground impact, apogee under `terminate_on_apogee`, a stop or a stage separation asked
/// for by a trigger or controller); otherwise the status word and the
/// explanation: `max_time` (still in the air at `flight.max_time`: it never landed) or
/// `stuck_on_rail` (it never left the rail). `karman simulate` fails with the explanation and
/// a Monte Carlo sample records the status, so both count the same flights as failures.
pub fn early_ending(
    termination: Termination,
    settings: &FlightSettings,
) -> Option<(&'static str, String)> {
    match termination {
        Termination::Impact
        | Termination::Apogee
        | Termination::Terminated
        | Termination::Separation => None,
        Termination::MaxTime => Some((
            "max_time",
            format!(
                "the flight reached max_time ({} s) before landing; raise [flight] max_time",
                crate::error::shown_number(settings.max_time, None)
            ),
        )),
        Termination::StuckOnRail => Some((
            "stuck_on_rail",
            "the rocket never left the rail: at burn-out it was still on it, too slow to coast \
             the rest of the rail against gravity"
                .to_owned(),
        )),
    }
}

/// A flown mission: the models it was built into (shared with the [`PreparedFlight`] that
/// flew it), the settings, and the raw flight.
#[derive(Debug, Clone)]
pub struct FlightRun {
    /// The launch environment.
    pub environment: Arc<Environment>,
    /// The motor.
    pub motor: Arc<Motor>,
    /// The rocket with its motor.
    pub rocket: Arc<Rocket>,
    /// The flight settings used.
    pub settings: FlightSettings,
    /// Stored points, events and integration counters.
    pub flight: Flight,
    /// The warnings of [`prepare`], each starting with the mission key it concerns.
    pub warnings: Vec<String>,
    /// The air-brake controller's record (RocketPy's observed variables and the level after
    /// each call), when the rocket has air brakes.
    pub controller: Option<ControllerRecord>,
    /// The readings of the mission's `[[rocket.sensors]]`, in file order (docs/physics.md
    /// §29).
    pub sensors: Vec<SensorReadings>,
}

impl FlightRun {
    /// The flight summary of the mission contract.
    #[must_use]
    pub fn summary(&self) -> Summary {
        self.flight.summary(&*self.environment, &*self.rocket)
    }

    /// Post-processed quantities at every stored point.
    #[must_use]
    pub fn samples(&self) -> Vec<Sample> {
        self.flight.samples(&*self.environment, &*self.rocket)
    }
}

/// A mission ready to fly: its models built and checked ([`prepare`]) and its air-brake
/// controller compiled, once, so that it flies any number of times (seeds) without rebuilding
/// them. [`simulate_with_seed`] prepares and flies once; the Python package's `Mission` keeps
/// one until the mission changes.
#[derive(Debug, Clone)]
pub struct PreparedFlight {
    environment: Arc<Environment>,
    motor: Arc<Motor>,
    rocket: Arc<Rocket>,
    /// The settings with trigger-noise seed 0 ([`PreparedFlight::fly`] sets the seed).
    settings: FlightSettings,
    warnings: Vec<String>,
    script: Option<ControllerScript>,
}

impl PreparedFlight {
    /// Builds and checks the models of `mission` and compiles its controller.
    ///
    /// # Errors
    /// [`prepare`]'s [`MissionError`]s and the controller script's.
    pub fn new(mission: &Mission) -> Result<Self, MissionError> {
        let Models {
            environment,
            motor,
            rocket,
            settings,
            warnings,
        } = prepare(mission, 0)?;
        Ok(PreparedFlight {
            environment: Arc::new(environment),
            motor: Arc::new(motor),
            rocket: Arc::new(rocket),
            settings,
            warnings,
            script: compile_controller(mission)?,
        })
    }

    /// The prepared flight with the parachutes named in `triggers` fired by the given
    /// conditions instead of their mission triggers (RocketPy's callable `trigger(p, h, y[,
    /// sensors])`, written in a host language: the Python package's `Mission.simulate(triggers=…)`).
    ///
    /// # Errors
    /// [`MissionError::Model`] at `rocket.parachutes` naming a parachute the mission does not
    /// have.
    pub fn with_triggers(
        &self,
        mission: &Mission,
        triggers: Vec<(String, Arc<dyn TriggerCondition>)>,
    ) -> Result<Self, MissionError> {
        let mut rocket = (*self.rocket).clone();
        for (name, condition) in triggers {
            rocket = rocket
                .with_parachute_trigger(&name, TriggerKind::Custom(condition))
                .ok_or_else(|| {
                    let known: Vec<&str> = mission
                        .spec
                        .rocket
                        .parachutes
                        .keys()
                        .map(String::as_str)
                        .collect();
                    mission.model_error(
                        "rocket.parachutes",
                        format!(
                            "no parachute {name:?} to trigger (the rocket's: {})",
                            if known.is_empty() {
                                "none".to_owned()
                            } else {
                                known.join(", ")
                            }
                        ),
                    )
                })?;
        }
        Ok(PreparedFlight {
            rocket: Arc::new(rocket),
            ..self.clone()
        })
    }

    /// The warnings of [`prepare`], each starting with the mission key it concerns.
    #[must_use]
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    /// The launch environment.
    #[must_use]
    pub fn environment(&self) -> &Environment {
        &self.environment
    }

    /// The rocket with its motor.
    #[must_use]
    pub fn rocket(&self) -> &Rocket {
        &self.rocket
    }

    /// The mission's air-brake controller, compiled, if it has one.
    #[must_use]
    pub fn script(&self) -> Option<&ControllerScript> {
        self.script.as_ref()
    }

    /// Flies the prepared models of `mission` (the mission they were prepared from) with
    /// parachute trigger noise seeded by `seed` (recorded in the flight).
    ///
    /// # Errors
    /// [`MissionError::Flight`] with section `flight` when the flight cannot be integrated (a
    /// non-finite state, a stiff or unstable model), or the controller's section for a
    /// script error.
    pub fn fly(&self, mission: &Mission, seed: u64) -> Result<FlightRun, MissionError> {
        self.fly_controlled(mission, seed, self.script.as_ref().into())
    }

    /// [`PreparedFlight::fly`] with the air brakes driven by `controller`, written in Rust,
    /// instead of the mission's Rhai script: called at the same instants with the same
    /// arguments (`karman_script::AirBrakeController`), so that a controller written in both
    /// gives the same flight. The mission must have `[rocket.air_brakes]` (its curve and
    /// `sampling_rate`; its `controller` script is not run). The run has no controller record.
    ///
    /// # Errors
    /// As [`PreparedFlight::fly`]; the controller's errors end the flight with section
    /// `rocket.air_brakes.controller`.
    pub fn fly_with_controller(
        &self,
        mission: &Mission,
        seed: u64,
        controller: &mut dyn AirBrakeController,
    ) -> Result<FlightRun, MissionError> {
        self.fly_controlled(mission, seed, Control::Native(controller))
    }

    /// [`PreparedFlight::fly`] with `control`.
    fn fly_controlled(
        &self,
        mission: &Mission,
        seed: u64,
        control: Control<'_>,
    ) -> Result<FlightRun, MissionError> {
        let mut settings = self.settings.clone();
        settings.noise_seed = seed;
        let sensors = sensors::build(mission, &self.rocket, seed)?;
        let surroundings = EnvironmentSurroundings(&self.environment);
        let (flight, controller, sensors) = fly_with_sensors(
            mission,
            &*self.environment,
            &self.rocket,
            &settings,
            control,
            || {
                Arc::new(ControllerEnvironment::new(
                    Arc::clone(&self.environment),
                    1.0,
                    0.0,
                ))
            },
            (sensors, &surroundings),
        )?;
        Ok(FlightRun {
            environment: Arc::clone(&self.environment),
            motor: Arc::clone(&self.motor),
            rocket: Arc::clone(&self.rocket),
            settings,
            flight,
            warnings: self.warnings.clone(),
            controller,
            sensors,
        })
    }
}

/// Builds and checks the models of `mission` ([`PreparedFlight::new`]) and flies them once,
/// with parachute trigger noise seeded by `seed` (recorded in the flight).
///
/// # Errors
/// [`prepare`]'s [`MissionError`]s, and [`MissionError::Model`] with section `flight` when the
/// flight cannot be integrated (a non-finite state, a stiff or unstable model).
pub fn simulate_with_seed(mission: &Mission, seed: u64) -> Result<FlightRun, MissionError> {
    PreparedFlight::new(mission)?.fly(mission, seed)
}

/// Flies `rocket` in `atmosphere` with `settings`, and with the mission's air-brake
/// controller when `script` is given (its environment queries from `queries`); returns the
/// flight and the controller's record.
///
/// # Errors
/// [`MissionError::Flight`]: section `flight` when the flight cannot be integrated, section
/// `rocket.air_brakes.controller` for a script error (located in the script), which ends
/// the flight.
pub fn fly<A: AtmosphereModel>(
    mission: &Mission,
    atmosphere: &A,
    rocket: &Rocket,
    settings: &FlightSettings,
    script: Option<&ControllerScript>,
    queries: impl FnOnce() -> Arc<dyn EnvironmentQuery>,
) -> Result<(Flight, Option<ControllerRecord>), MissionError> {
    struct Nowhere;
    impl Surroundings for Nowhere {
        fn pressure(&self, _h: f64) -> f64 {
            f64::NAN
        }
        fn gravity(&self, _h: f64) -> f64 {
            f64::NAN
        }
        fn site(&self) -> [f64; 2] {
            [f64::NAN; 2]
        }
        fn earth_radius(&self) -> f64 {
            f64::NAN
        }
    }
    let (flight, record, _) = fly_with_sensors(
        mission,
        atmosphere,
        rocket,
        settings,
        script.into(),
        queries,
        (Vec::new(), &Nowhere),
    )?;
    Ok((flight, record))
}

/// The air-brake controller a flight is flown with.
pub enum Control<'a> {
    /// None: the brakes stay at their level (or the rocket has none).
    None,
    /// The mission's Rhai controller, compiled.
    Script(&'a ControllerScript),
    /// A controller written in Rust, in place of the mission's script.
    Native(&'a mut dyn AirBrakeController),
}

impl<'a> From<Option<&'a ControllerScript>> for Control<'a> {
    fn from(script: Option<&'a ControllerScript>) -> Self {
        script.map_or(Control::None, Control::Script)
    }
}

/// [`fly`] with `sensors` sampled during the flight, measuring with `surroundings`
/// (docs/physics.md §29.2); returns their readings too, in order. The sensors are sampled
/// after the parachutes and the controller at the instants they share, so these read the
/// sensors' previous readings there, except that with `time_overshoot = false` the sensors
/// come before the controller (RocketPy 1.13's orders, docs/physics.md §29.3); the
/// controller's `sensors` argument and the trigger expressions read the sensors' signals,
/// so `sensors` must be the mission's (a flight without them does not start when one of
/// those reads a sensor). Without sensors or controller the flight is
/// [`karman_dynamics::simulate`]'s, with the same bytes as before sensors existed.
///
/// # Errors
/// As [`fly`].
pub fn fly_with_sensors<A: AtmosphereModel>(
    mission: &Mission,
    atmosphere: &A,
    rocket: &Rocket,
    settings: &FlightSettings,
    control: Control<'_>,
    queries: impl FnOnce() -> Arc<dyn EnvironmentQuery>,
    (sensors, surroundings): (Vec<Sensor>, &dyn Surroundings),
) -> Result<(Flight, Option<ControllerRecord>, Vec<SensorReadings>), MissionError> {
    let mut readings = sensors::empty_readings(&sensors);
    let mut script = None;
    let mut native = None;
    match control {
        Control::None => {}
        Control::Script(s) => script = Some(scripts::controller(mission, s, rocket, queries())?),
        Control::Native(c) => {
            native = Some(scripts::native_controller(mission, c, rocket, queries())?);
        }
    }
    let controller: Option<&mut dyn ControllerCalls> = match (&mut script, &mut native) {
        (Some(c), _) => Some(c),
        (None, Some(c)) => Some(c),
        (None, None) => None,
    };
    if controller.is_none() && sensors.is_empty() {
        let flight = karman_dynamics::simulate(atmosphere, rocket, settings)
            .map_err(|e| mission.flight_error("flight", e))?;
        return Ok((flight, None, readings));
    }
    let mut error = None;
    // The signals of each sensor's components (`sensors::signal_name`), which the sensors
    // publish and the controller and the trigger expressions read.
    let signals: Vec<Vec<String>> = sensors
        .iter()
        .map(|s| {
            (0..s.len())
                .map(|c| sensors::signal_name(&s.spec().name, c))
                .collect()
        })
        .collect();
    let overshoot = mission.spec.flight.time_overshoot;
    let mut sensor_processes: Vec<Box<dyn karman_dynamics::flight::SampledProcess + '_>> =
        Vec::new();
    for ((sensor, readings), names) in sensors.into_iter().zip(readings.iter_mut()).zip(&signals) {
        sensor_processes.push(Box::new(SensorProcess {
            sensor,
            surroundings,
            readings,
            outputs: names.iter().map(String::as_str).collect(),
        }));
    }
    let mut processes: Vec<Box<dyn karman_dynamics::flight::SampledProcess + '_>> = Vec::new();
    // RocketPy 1.13's order at an instant (docs/physics.md §29.3): on the solver's steps
    // (`time_overshoot`) the parachutes (the engine puts them first), the controller, then
    // the sensors, which the other two therefore read as of the sensors' previous instant;
    // at its hard stops (`time_overshoot = false`) the sensors before the controller, which
    // reads the reading of the instant.
    if !overshoot {
        processes.append(&mut sensor_processes);
    }
    if let Some(controller) = controller {
        processes.push(Box::new(ControllerProcess {
            controller,
            error: &mut error,
            overshoot,
            sensor_signals: &signals,
            sensor_ids: Vec::new(),
        }));
    }
    processes.append(&mut sensor_processes);
    drop(sensor_processes);
    let flight = karman_dynamics::simulate_with(atmosphere, rocket, settings, processes)
        .map_err(|e| mission.flight_error("flight", e))?;
    if let Some(error) = error {
        return Err(mission.flight_error("rocket.air_brakes.controller", error));
    }
    Ok((flight, script.map(|c| c.record()), readings))
}

/// [`simulate_with_seed`] with seed 0.
///
/// # Errors
/// As [`simulate_with_seed`].
pub fn simulate(mission: &Mission) -> Result<FlightRun, MissionError> {
    simulate_with_seed(mission, 0)
}
