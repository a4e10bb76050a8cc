//! Air-brake controllers written in Rust: RocketPy's `controller_function` as a trait that a
//! user's crate implements ([`AirBrakeController`]), called by the flight exactly where and
//! with what a Rhai controller is called ([`crate::Controller`]): at `t = j / sampling_rate`
//! in every phase, with the state there, the last stored solution row, the latest reading of
//! each sensor and the environment; the level it writes is stored as a Rhai write stores it
//! (clipped to `[0, 1]` when the brakes clamp, docs/physics.md §16.3). The same controller
//! in Rhai and in Rust therefore gives the same flight, bit for bit, when their arithmetic is
//! the same.
//!
//! What a Rhai controller returns is its record (`observed_variables`); a Rust controller
//! keeps what it wants in its own fields, so it has no record and no sandbox: it runs as the
//! user's own code, at native speed.

use std::sync::Arc;

use crate::arguments::stored_level;
use crate::{AirBrakesSetup, EnvironmentQuery};

/// The latest reading of one sensor as a controller sees it (RocketPy's `sensor.measurement`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SensorReading {
    /// When it was taken, s.
    pub time: f64,
    /// The measurement: a barometer's pressure in `[0]` (Pa), the three axes of an
    /// accelerometer (m/s²) or gyroscope (rad/s), or a GNSS fix (latitude and longitude in
    /// degrees, altitude in m).
    pub measurement: [f64; 3],
}

/// What a controller call is given (RocketPy's `controller_function` arguments but the air
/// brakes, which come as [`AirBrakesControl`]).
pub struct ControlInputs<'a> {
    /// The sampling instant, s.
    pub time: f64,
    /// Calls per second, Hz.
    pub sampling_rate: f64,
    /// `[x, y, z, vx, vy, vz, e0, e1, e2, e3, wx, wy, wz]` at `time` (frames as the mission's).
    pub state: &'a [f64; 13],
    /// The last stored solution point, `[t, x, …, wz]` (RocketPy's `state_history[-1]`).
    pub state_history: &'a [f64; 14],
    /// The latest reading of each of the rocket's sensors, in `[[rocket.sensors]]` order;
    /// `None` before a sensor's first reading.
    pub sensors: &'a [Option<SensorReading>],
    /// The atmosphere and gravity at heights above sea level, and the launch elevation.
    pub environment: &'a dyn EnvironmentQuery,
    /// The motor's burn-out time, s (the Rhai controller's `motor::burn_out_time`).
    pub burn_out_time: f64,
}

/// The air brakes as a controller call sees them (RocketPy's `AirBrakes`): the deployment
/// level to read and set, and the brakes' constants.
pub struct AirBrakesControl<'a> {
    setup: &'a AirBrakesSetup,
    level: f64,
}

impl AirBrakesControl<'_> {
    /// The deployment level stored last.
    #[must_use]
    pub fn deployment_level(&self) -> f64 {
        self.level
    }

    /// Sets the deployment level: clipped to `[0, 1]` when the brakes clamp, as a Rhai
    /// script's `air_brakes.deployment_level = value` is.
    pub fn set_deployment_level(&mut self, value: f64) {
        self.level = stored_level(self.setup.clamp, value);
    }

    /// Whether written levels are clipped to `[0, 1]`.
    #[must_use]
    pub fn clamp(&self) -> bool {
        self.setup.clamp
    }

    /// Whether the brakes' curve replaces the rocket's drag while deployed.
    #[must_use]
    pub fn override_rocket_drag(&self) -> bool {
        self.setup.override_rocket_drag
    }

    /// The curve's reference area, m².
    #[must_use]
    pub fn reference_area(&self) -> f64 {
        self.setup.reference_area
    }

    /// The brakes' drag coefficient at `level` and `mach`.
    #[must_use]
    pub fn drag_coefficient(&self, level: f64, mach: f64) -> f64 {
        (self.setup.drag_coefficient)(level, mach)
    }
}

/// An air-brake controller written in Rust, RocketPy's `controller_function`: called at each
/// sampling instant with `inputs`; it reads and sets the deployment level on `air_brakes`.
/// An error ends the flight there, with the message in the flight's error.
pub trait AirBrakeController {
    /// One call at `inputs.time`.
    ///
    /// # Errors
    /// Whatever the controller reports; the flight ends with it.
    fn control(
        &mut self,
        inputs: &ControlInputs<'_>,
        air_brakes: &mut AirBrakesControl<'_>,
    ) -> Result<(), String>;
}

/// A Rust controller's failure, at the instant of the call that reported it.
#[derive(Debug, Clone, PartialEq)]
pub struct NativeError {
    /// The sampling instant, s.
    pub time: f64,
    /// What the controller said.
    pub message: String,
}

impl std::fmt::Display for NativeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the controller failed at the call at t = {} s: {}",
            self.time, self.message
        )
    }
}

impl std::error::Error for NativeError {}

/// A flight's calls of a Rust controller: the brakes' level and sensors between calls.
pub struct NativeController<'c> {
    controller: &'c mut dyn AirBrakeController,
    setup: AirBrakesSetup,
    sampling_rate: f64,
    level: f64,
    burn_out_time: f64,
    environment: Arc<dyn EnvironmentQuery>,
    sensors: Vec<Option<SensorReading>>,
}

impl<'c> NativeController<'c> {
    /// The calls of `controller` at `sampling_rate` for brakes `setup` (at their initial
    /// level, clipped when they clamp), with `sensors` sensors, a motor burning out at
    /// `burn_out_time` and `environment`.
    pub fn new(
        controller: &'c mut dyn AirBrakeController,
        setup: AirBrakesSetup,
        sampling_rate: f64,
        burn_out_time: f64,
        environment: Arc<dyn EnvironmentQuery>,
        sensors: usize,
    ) -> Self {
        let level = stored_level(setup.clamp, setup.initial_level);
        NativeController {
            controller,
            setup,
            sampling_rate,
            level,
            burn_out_time,
            environment,
            sensors: vec![None; sensors],
        }
    }

    /// Calls per second.
    #[must_use]
    pub fn sampling_rate(&self) -> f64 {
        self.sampling_rate
    }

    /// The current deployment level.
    #[must_use]
    pub fn level(&self) -> f64 {
        self.level
    }

    /// Hands sensor `index` its latest reading, taken at `time`, for the next calls.
    pub fn set_sensor(&mut self, index: usize, time: f64, measurement: [f64; 3]) {
        if let Some(slot) = self.sensors.get_mut(index) {
            *slot = Some(SensorReading { time, measurement });
        }
    }

    /// Calls the controller at sampling instant `time` with the state there and the last
    /// stored solution row; returns the deployment level it leaves.
    ///
    /// # Errors
    /// [`NativeError`] with the controller's message.
    pub fn call(
        &mut self,
        time: f64,
        state: &[f64; 13],
        last_row: &[f64; 14],
    ) -> Result<f64, NativeError> {
        let inputs = ControlInputs {
            time,
            sampling_rate: self.sampling_rate,
            state,
            state_history: last_row,
            sensors: &self.sensors,
            environment: &*self.environment,
            burn_out_time: self.burn_out_time,
        };
        let mut brakes = AirBrakesControl {
            setup: &self.setup,
            level: self.level,
        };
        self.controller
            .control(&inputs, &mut brakes)
            .map_err(|message| NativeError { time, message })?;
        self.level = brakes.level;
        Ok(self.level)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Still;
    impl EnvironmentQuery for Still {
        fn elevation(&self) -> f64 {
            100.0
        }
        fn wind_velocity_x(&self, _h: f64) -> f64 {
            0.0
        }
        fn wind_velocity_y(&self, _h: f64) -> f64 {
            0.0
        }
        fn speed_of_sound(&self, _h: f64) -> f64 {
            340.0
        }
        fn density(&self, _h: f64) -> f64 {
            1.2
        }
        fn pressure(&self, _h: f64) -> f64 {
            1e5
        }
        fn temperature(&self, _h: f64) -> f64 {
            288.0
        }
        fn dynamic_viscosity(&self, _h: f64) -> f64 {
            1.8e-5
        }
        fn gravity(&self, _h: f64) -> f64 {
            9.81
        }
    }

    /// Opens the brakes to the barometer's pressure over 1e5 Pa once burnt out.
    struct Proportional;
    impl AirBrakeController for Proportional {
        fn control(
            &mut self,
            inputs: &ControlInputs<'_>,
            air_brakes: &mut AirBrakesControl<'_>,
        ) -> Result<(), String> {
            if inputs.time < inputs.burn_out_time {
                return Ok(());
            }
            let Some(baro) = inputs.sensors[0] else {
                return Err("no barometer reading yet".to_owned());
            };
            air_brakes.set_deployment_level(baro.measurement[0] / 1e5);
            Ok(())
        }
    }

    fn setup(clamp: bool) -> AirBrakesSetup {
        AirBrakesSetup {
            clamp,
            override_rocket_drag: false,
            reference_area: 0.01,
            initial_level: 2.0,
            drag_coefficient: Arc::new(|level, mach| level + mach),
        }
    }

    #[test]
    fn levels_are_stored_as_a_script_stores_them() {
        let mut c = Proportional;
        let mut calls = NativeController::new(&mut c, setup(true), 10.0, 1.0, Arc::new(Still), 1);
        // The initial level is clipped as the brakes clamp.
        assert_eq!(calls.level().to_bits(), 1.0f64.to_bits());
        let (state, row) = ([0.0; 13], [0.0; 14]);
        // Before burn-out the level is left as it was.
        assert_eq!(calls.call(0.5, &state, &row), Ok(1.0));
        // After it, without a reading: the controller's error, at its instant.
        let e = calls.call(1.5, &state, &row).expect_err("no reading");
        assert_eq!(e.time.to_bits(), 1.5f64.to_bits());
        assert!(e.to_string().contains("no barometer reading yet"), "{e}");
        calls.set_sensor(0, 1.4, [150_000.0, f64::NAN, f64::NAN]);
        assert_eq!(calls.call(1.6, &state, &row), Ok(1.0));
        calls.set_sensor(0, 1.6, [40_000.0, f64::NAN, f64::NAN]);
        assert_eq!(calls.call(1.7, &state, &row), Ok(0.4));
        // A sensor index past the rocket's is ignored.
        calls.set_sensor(3, 1.7, [0.0; 3]);
        let mut unclamped = Proportional;
        let mut calls =
            NativeController::new(&mut unclamped, setup(false), 10.0, 1.0, Arc::new(Still), 1);
        calls.set_sensor(0, 1.4, [150_000.0, 0.0, 0.0]);
        assert_eq!(calls.call(1.5, &state, &row), Ok(1.5));
    }
}
