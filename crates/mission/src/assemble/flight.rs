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
use karman_dynamics::{
    AtmosphereModel, DEFAULT_ATOL, Flight, FlightSettings, Sample, Summary, Termination,
};
use karman_propulsion::Motor;
use karman_script::{ControllerRecord, ControllerScript, EnvironmentQuery};
use karman_sensors::{Sensor, Surroundings};

use super::preflight::{Models, prepare};
use super::scripts::{self, ControllerEnvironment, ControllerProcess, compile_controller};
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

/// The flight settings of a mission, with the trigger-noise `seed` of its parachutes.
#[must_use]
pub fn flight_settings(mission: &Mission, seed: u64) -> FlightSettings {
    let spec = &mission.spec.flight;
    let mut settings = FlightSettings::new(spec.rail_length);
    settings.inclination_deg = spec.inclination_deg;
    settings.heading_deg = spec.heading_deg;
    settings.max_time = spec.max_time;
    settings.terminate_on_apogee = spec.terminate_on_apogee;
    settings.rtol = spec.rtol;
    settings.atol = spec.atol.map_or(DEFAULT_ATOL, |a| a.per_state());
    settings.max_time_step = spec.max_time_step;
    settings.noise_seed = seed;
    settings.equations = spec.equations.into();
    settings.simulation_mode = spec.simulation_mode.into();
    settings.weathercock_coefficient = spec.weathercock_coeff.unwrap_or(0.0);
    if let Some(ab) = &mission.spec.rocket.air_brakes
        && spec.time_overshoot
        && ab.sampling_rate > 0.0
    {
        // Deviation from RocketPy: a level written by the controller acts from the end of
        // the solver step holding the call (docs/physics.md §16.4); steps at most one sampling
        // interval long keep that delay as short as RocketPy's LSODA steps make it. The
        // bound covers the free flight, where the level is in the equations (§16.1), and the
        // steps whose instants are not sampled (rail exit, the impact); the parachute
        // descents otherwise keep the solver's steps (`FlightSettings::control_max_time_step`).
        // The bound is what parity needs: with steps of up to 2 or 5 intervals, or unbounded,
        // camoes' apogee is 0.11, 0.08 or 0.10 % above RocketPy's (0.03 % bounded) and the
        // levels of fixtures/airbrakes/calisto_apogee.toml differ from RocketPy's by 0.005.
        settings.control_max_time_step = 1.0 / ab.sampling_rate;
    }
    settings
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

    /// The warnings of [`prepare`], each starting with the mission key it concerns.
    #[must_use]
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    /// Flies the prepared models of `mission` (the mission they were prepared from) with
    /// parachute trigger noise seeded by `seed` (recorded in the flight).
    ///
    /// # Errors
    /// [`MissionError::Flight`] with section `flight` when the flight cannot be integrated (a
    /// non-finite state, a stiff or unstable model), or the controller's section for a
    /// script error.
    pub fn fly(&self, mission: &Mission, seed: u64) -> Result<FlightRun, MissionError> {
        let mut settings = self.settings.clone();
        settings.noise_seed = seed;
        let sensors = sensors::build(mission, &self.rocket, seed)?;
        let surroundings = EnvironmentSurroundings(&self.environment);
        let (flight, controller, sensors) = fly_with_sensors(
            mission,
            &*self.environment,
            &self.rocket,
            &settings,
            self.script.as_ref(),
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
        script,
        queries,
        (Vec::new(), &Nowhere),
    )?;
    Ok((flight, record))
}

/// [`fly`] with `sensors` sampled during the flight, measuring with `surroundings`
/// (docs/physics.md §29.2); returns their readings too, in order. The sensors are sampled
/// after the controller at the instants they share. Without sensors or controller the flight
/// is [`karman_dynamics::simulate`]'s, with the same bytes as before sensors existed.
///
/// # Errors
/// As [`fly`].
pub fn fly_with_sensors<A: AtmosphereModel>(
    mission: &Mission,
    atmosphere: &A,
    rocket: &Rocket,
    settings: &FlightSettings,
    script: Option<&ControllerScript>,
    queries: impl FnOnce() -> Arc<dyn EnvironmentQuery>,
    (sensors, surroundings): (Vec<Sensor>, &dyn Surroundings),
) -> Result<(Flight, Option<ControllerRecord>, Vec<SensorReadings>), MissionError> {
    let mut readings = sensors::empty_readings(&sensors);
    let mut controller = match script {
        Some(script) => Some(scripts::controller(mission, script, rocket, queries())?),
        None => None,
    };
    if controller.is_none() && sensors.is_empty() {
        let flight = karman_dynamics::simulate(atmosphere, rocket, settings)
            .map_err(|e| mission.flight_error("flight", e))?;
        return Ok((flight, None, readings));
    }
    let mut error = None;
    let mut processes: Vec<Box<dyn karman_dynamics::flight::SampledProcess + '_>> = Vec::new();
    if let Some(controller) = controller.as_mut() {
        processes.push(Box::new(ControllerProcess {
            controller,
            error: &mut error,
            overshoot: mission.spec.flight.time_overshoot,
        }));
    }
    for (sensor, readings) in sensors.into_iter().zip(readings.iter_mut()) {
        processes.push(Box::new(SensorProcess {
            sensor,
            surroundings,
            readings,
        }));
    }
    let flight = karman_dynamics::simulate_with(atmosphere, rocket, settings, processes)
        .map_err(|e| mission.flight_error("flight", e))?;
    if let Some(error) = error {
        return Err(mission.flight_error("rocket.air_brakes.controller", error));
    }
    Ok((flight, controller.map(|c| c.record()), readings))
}

/// [`simulate_with_seed`] with seed 0.
///
/// # Errors
/// As [`simulate_with_seed`].
pub fn simulate(mission: &Mission) -> Result<FlightRun, MissionError> {
    simulate_with_seed(mission, 0)
}
