//! # karman-sensors
//!
//! The flight sensors of RocketPy 1.13 (`rocketpy/sensors/`): an accelerometer, a gyroscope,
//! a barometer and a GNSS receiver, each at a position and orientation on the rocket, with
//! RocketPy's noise model (docs/physics.md §29).
//!
//! - [`SensorSpec`]: what a mission gives — the [`SensorKind`] (with its kind's parameters),
//!   the sampling rate, RocketPy's `relative_position` (the vector from the centre of dry mass
//!   to the sensor in body axes), the mounting orientation (3-1-3 Euler angles, degrees), the
//!   cross-axis sensitivity and the [`NoiseParameters`] (range, resolution, white noise,
//!   random walk, constant bias, operating temperature with temperature bias and scale drift).
//! - [`Sensor`]: a spec built and checked, with its frame and its own random stream keyed by
//!   the flight's seed and the sensor's index (same seed, same readings, whatever the thread
//!   count). [`Sensor::measure`] turns the flight's state and its derivative at an instant
//!   ([`Truth`]) into a reading, allocation-free; the environment comes through
//!   [`Surroundings`].
//!
//! The crate knows nothing of the engine: the mission crate samples the sensors as sampled
//! processes of the flight (RocketPy's time nodes) and hands each instant's state and
//! right-hand side to [`Sensor::measure`]. Depends on karman-math only.
//!
//! ```
//! use karman_sensors::{Sensor, SensorKind, SensorSpec, Surroundings, Truth};
//!
//! struct Still;
//! impl Surroundings for Still {
//!     fn pressure(&self, h: f64) -> f64 { 101_325.0 - 12.0 * h }
//!     fn gravity(&self, _h: f64) -> f64 { 9.80665 }
//!     fn site(&self) -> [f64; 2] { [32.99, -106.97] }
//!     fn earth_radius(&self) -> f64 { 6.3781e6 }
//! }
//! // A rocket standing still, upright: a barometer 1 m above the centre of dry mass.
//! let mut u = [0.0; 13];
//! u[6] = 1.0;
//! let truth = Truth { u, u_dot: [0.0; 13] };
//! let spec = SensorSpec::new("baro", SensorKind::Barometer, 50.0, [0.0, 0.0, 1.0]);
//! let mut baro = Sensor::new(spec, 7, 0).unwrap();
//! assert_eq!(baro.measure(&truth, &Still)[0], 101_325.0 - 12.0);
//! ```

mod error;
mod frame;
mod noise;
mod sensor;

pub use error::SensorError;
pub use frame::{Mat3, Vec3, euler313_to_quaternion, rotation, sensor_to_body};
pub use noise::NoiseParameters;
pub use sensor::{MAX_CROSS_AXIS_SENSITIVITY, Sensor, SensorKind, SensorSpec, Surroundings, Truth};

#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeExample;
