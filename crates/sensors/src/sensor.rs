//! The four sensors of RocketPy 1.13 (`rocketpy/sensors/accelerometer.py`, `gyroscope.py`,
//! `barometer.py`, `gnss_receiver.py`) and what each measures from the flight's state `u`
//! and its derivative `u̇` at an instant (docs/physics.md §29.2).

use crate::error::SensorError;
use crate::frame::{Mat3, Vec3, add, cross, matmul, mul, rotation, sensor_to_body, transpose};
use crate::noise::{NoiseParameters, NoiseState, quantize, temperature_drift};

/// What a sensor is, with the parameters only that kind has.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SensorKind {
    /// RocketPy's `Accelerometer`: the acceleration at the sensor, in its frame, m/s².
    Accelerometer {
        /// Add `(0, 0, −g)` to the inertial acceleration (RocketPy's `consider_gravity`,
        /// default false; `g` as RocketPy evaluates it, docs/physics.md §29.2).
        consider_gravity: bool,
    },
    /// RocketPy's `Gyroscope`: the body rates in the sensor's frame, rad/s.
    Gyroscope {
        /// Rate error per unit of acceleration felt, per axis, (rad/s)/(m/s²).
        acceleration_sensitivity: [f64; 3],
    },
    /// RocketPy's `Barometer`: the static pressure at the sensor's height, Pa.
    Barometer,
    /// RocketPy's `GnssReceiver`: latitude and longitude (deg) and altitude (m ASL) of the
    /// sensor.
    Gnss {
        /// Standard deviation of each horizontal coordinate, m.
        position_accuracy: f64,
        /// Standard deviation of the altitude, m.
        altitude_accuracy: f64,
    },
}

impl SensorKind {
    /// The kind's name in the mission format (`kind = "…"`).
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            SensorKind::Accelerometer { .. } => "accelerometer",
            SensorKind::Gyroscope { .. } => "gyroscope",
            SensorKind::Barometer => "barometer",
            SensorKind::Gnss { .. } => "gnss",
        }
    }

    /// The reading's components: name and unit (RocketPy's export labels).
    #[must_use]
    pub fn components(&self) -> &'static [(&'static str, &'static str)] {
        match self {
            SensorKind::Accelerometer { .. } => {
                &[("ax", "m/s^2"), ("ay", "m/s^2"), ("az", "m/s^2")]
            }
            SensorKind::Gyroscope { .. } => &[("wx", "rad/s"), ("wy", "rad/s"), ("wz", "rad/s")],
            SensorKind::Barometer => &[("pressure", "Pa")],
            SensorKind::Gnss { .. } => {
                &[("latitude", "deg"), ("longitude", "deg"), ("altitude", "m")]
            }
        }
    }

    /// Whether the kind has an orientation and inertial-sensor parameters (cross-axis
    /// sensitivity).
    #[must_use]
    pub fn is_inertial(&self) -> bool {
        matches!(
            self,
            SensorKind::Accelerometer { .. } | SensorKind::Gyroscope { .. }
        )
    }
}

/// A sensor as built from a mission: its kind, rate, place on the rocket and noise.
#[derive(Debug, Clone, PartialEq)]
pub struct SensorSpec {
    /// Unique name in the flight.
    pub name: String,
    /// Kind and kind-specific parameters.
    pub kind: SensorKind,
    /// Sampling rate `f`, Hz: readings at `j / f`.
    pub sampling_rate: f64,
    /// RocketPy's `relative_position`: the vector from the centre of dry mass to the sensor
    /// in body axes, m (docs/physics.md §29.2: the user's `(x, y, z)` minus
    /// `(0, 0, csys·z_CDM)`).
    pub relative_position: Vec3,
    /// Mounting: the 3-1-3 Euler angles (roll, pitch, roll 2) of the sensor's axes in the
    /// body frame, degrees (inertial sensors; RocketPy's `orientation` tuple).
    pub orientation_deg: Vec3,
    /// Cross-axis sensitivity, % (inertial sensors).
    pub cross_axis_sensitivity: f64,
    /// The noise model (docs/physics.md §29.1). A GNSS receiver uses none of it (RocketPy's
    /// `GnssReceiver` has only its accuracies).
    pub noise: NoiseParameters,
}

impl SensorSpec {
    /// A noise-free sensor of `kind` at `relative_position`, sampled at `sampling_rate`, with
    /// RocketPy's defaults otherwise.
    #[must_use]
    pub fn new(name: &str, kind: SensorKind, sampling_rate: f64, relative_position: Vec3) -> Self {
        Self {
            name: name.to_owned(),
            kind,
            sampling_rate,
            relative_position,
            orientation_deg: [0.0; 3],
            cross_axis_sensitivity: 0.0,
            noise: NoiseParameters::default(),
        }
    }
}

/// What a sensor needs of the environment besides the state: the flight's air and gravity
/// as functions of the height above sea level, and the launch site for a GNSS fix.
pub trait Surroundings {
    /// Static pressure at height `h` m ASL, Pa.
    fn pressure(&self, h: f64) -> f64;
    /// Gravity at height `h` m ASL, m/s².
    fn gravity(&self, h: f64) -> f64;
    /// Latitude and longitude of the launch site (the origin of `x` east, `y` north), deg.
    fn site(&self) -> [f64; 2];
    /// The Earth radius of the site's GNSS conversion (RocketPy's `Environment.earth_radius`),
    /// m.
    fn earth_radius(&self) -> f64;
}

/// The flight at an instant, as a sensor measures it: RocketPy's `u` (the 13-state:
/// position m ASL, velocity, quaternion, body rates) and `u_dot` (the right-hand side of the
/// phase's equations there).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Truth {
    /// The state.
    pub u: [f64; 13],
    /// Its time derivative.
    pub u_dot: [f64; 13],
}

/// A built sensor: its spec, its frame and its random state.
#[derive(Debug, Clone)]
pub struct Sensor {
    spec: SensorSpec,
    /// Sensor-to-body rotation times the cross-axis matrix (RocketPy's
    /// `_total_rotation_sensor_to_body`, applied to body vectors).
    total: Mat3,
    noise: NoiseState,
}

/// Largest cross-axis sensitivity, %: beyond 100 % an axis reads more of the others than of
/// its own.
pub const MAX_CROSS_AXIS_SENSITIVITY: f64 = 100.0;

impl Sensor {
    /// Builds sensor `index` of a flight whose noise is seeded with `seed`.
    ///
    /// # Errors
    /// [`SensorError::Parameter`] for a sampling rate that is not positive and finite, a
    /// non-finite position or orientation, a cross-axis sensitivity outside
    /// `[0, 100]` %, a negative accuracy, or bad noise parameters
    /// ([`NoiseParameters::validate`]).
    pub fn new(spec: SensorSpec, seed: u64, index: u64) -> Result<Self, SensorError> {
        let bad = |name: &'static str, value: f64, reason: &'static str| {
            Err(SensorError::Parameter {
                name,
                value,
                reason,
            })
        };
        let rate = spec.sampling_rate;
        if !(rate.is_finite() && rate > 0.0) {
            return bad("sampling_rate", rate, "must be positive and finite");
        }
        for v in spec.relative_position {
            if !v.is_finite() {
                return bad("position", v, "must be finite");
            }
        }
        for v in spec.orientation_deg {
            if !v.is_finite() {
                return bad("orientation", v, "must be finite");
            }
        }
        let s = spec.cross_axis_sensitivity;
        if !(0.0..=MAX_CROSS_AXIS_SENSITIVITY).contains(&s) {
            return bad("cross_axis_sensitivity", s, "must be in [0, 100] %");
        }
        match spec.kind {
            SensorKind::Gnss {
                position_accuracy,
                altitude_accuracy,
            } => {
                for (name, v) in [
                    ("position_accuracy", position_accuracy),
                    ("altitude_accuracy", altitude_accuracy),
                ] {
                    if !(v.is_finite() && v >= 0.0) {
                        return bad(name, v, "must be finite and non-negative");
                    }
                }
            }
            SensorKind::Gyroscope {
                acceleration_sensitivity,
            } => {
                for v in acceleration_sensitivity {
                    if !v.is_finite() {
                        return bad("acceleration_sensitivity", v, "must be finite");
                    }
                }
            }
            _ => {}
        }
        spec.noise.validate()?;
        // RocketPy's cross-axis matrix 0.01·[[100, s, s], [s, 100, s], [s, s, 100]].
        let c = 0.01 * s;
        let cross_axis = [[1.0, c, c], [c, 1.0, c], [c, c, 1.0]];
        let total = matmul(&sensor_to_body(spec.orientation_deg), &cross_axis);
        Ok(Self {
            spec,
            total,
            noise: NoiseState::new(seed, index),
        })
    }

    /// The spec it was built from.
    #[must_use]
    pub fn spec(&self) -> &SensorSpec {
        &self.spec
    }

    /// Number of components of a reading.
    #[must_use]
    pub fn len(&self) -> usize {
        self.spec.kind.components().len()
    }

    /// Always false: a reading has at least one component.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The reading at an instant of the flight (its first [`Sensor::len`] components;
    /// the others are 0), advancing the sensor's noise state. Allocation-free.
    pub fn measure(&mut self, truth: &Truth, surroundings: &dyn Surroundings) -> [f64; 3] {
        let (u, u_dot) = (&truth.u, &truth.u_dot);
        let r = self.spec.relative_position;
        let p = &self.spec.noise;
        let rate = self.spec.sampling_rate;
        match self.spec.kind {
            SensorKind::Accelerometer { consider_gravity } => {
                // RocketPy evaluates gravity at `u[3]` (the x velocity, where the height `u[2]`
                // is meant); kept for parity, it only matters with `consider_gravity` and a
                // gravity that varies with height.
                let g = if consider_gravity {
                    surroundings.gravity(u[3])
                } else {
                    0.0
                };
                let inertial = [u_dot[3], u_dot[4], u_dot[5] - g];
                let value = lever_arm(inertial, u, u_dot, r);
                let to_sensor = matmul(&self.total, &transpose(&rotation(quaternion(u))));
                let mut a = mul(&to_sensor, value);
                self.noise.apply(p, rate, &mut a, 3);
                temperature_drift(p, &mut a, 3);
                quantize(p, &mut a, 3);
                a
            }
            SensorKind::Gyroscope {
                acceleration_sensitivity,
            } => {
                let omega = [u[10], u[11], u[12]];
                let mut w = mul(&self.total, omega);
                self.noise.apply(p, rate, &mut w, 3);
                temperature_drift(p, &mut w, 3);
                if acceleration_sensitivity.iter().any(|s| *s != 0.0) {
                    // RocketPy adds the inertial acceleration (not turned into the body frame)
                    // to the body-frame lever-arm terms before the sensor rotation.
                    let felt = lever_arm([u_dot[3], u_dot[4], u_dot[5]], u, u_dot, r);
                    let felt = mul(&self.total, felt);
                    for i in 0..3 {
                        w[i] += acceleration_sensitivity[i] * felt[i];
                    }
                }
                quantize(p, &mut w, 3);
                w
            }
            SensorKind::Barometer => {
                let height = u[2] + mul(&rotation(quaternion(u)), r)[2];
                let mut value = [surroundings.pressure(height), 0.0, 0.0];
                self.noise.apply(p, rate, &mut value, 1);
                temperature_drift(p, &mut value, 1);
                quantize(p, &mut value, 1);
                value
            }
            SensorKind::Gnss {
                position_accuracy,
                altitude_accuracy,
            } => {
                let offset = mul(&rotation(quaternion(u)), r);
                let [x, y, z] = add(offset, [u[0], u[1], u[2]]);
                let x = x + position_accuracy * self.noise.normal();
                let y = y + position_accuracy * self.noise.normal();
                let altitude = z + altitude_accuracy * self.noise.normal();
                let [lat, lon] = surroundings.site();
                let (latitude, longitude) =
                    great_circle(lat, lon, x, y, surroundings.earth_radius());
                [latitude, longitude, altitude]
            }
        }
    }
}

/// The quaternion of the state.
#[inline]
fn quaternion(u: &[f64; 13]) -> [f64; 4] {
    [u[6], u[7], u[8], u[9]]
}

/// `a + ω̇ × r + ω × (ω × r)` with the body rates and their derivative of the state
/// (RocketPy's acceleration at the sensor, summed in its order).
#[inline]
fn lever_arm(a: Vec3, u: &[f64; 13], u_dot: &[f64; 13], r: Vec3) -> Vec3 {
    let omega = [u[10], u[11], u[12]];
    let omega_dot = [u_dot[10], u_dot[11], u_dot[12]];
    add(add(a, cross(omega_dot, r)), cross(omega, cross(omega, r)))
}

/// Latitude and longitude (deg) of the point `(x east, y north)` m from the site, as
/// RocketPy's `GnssReceiver.measure` computes them: the drift `√(x² + y²)`, the bearing
/// `2π − atan2(−x, y)` in degrees, and `tools.inverted_haversine` on a sphere of radius
/// `radius`.
fn great_circle(lat0: f64, lon0: f64, x: f64, y: f64, radius: f64) -> (f64, f64) {
    let drift = (x * x + y * y).sqrt();
    let bearing = (2.0 * std::f64::consts::PI - (-x).atan2(y)) * (180.0 / std::f64::consts::PI);
    let (lat0, lon0) = (lat0.to_radians(), lon0.to_radians());
    let delta = drift / radius;
    let b = bearing.to_radians();
    let lat1 = (lat0.sin() * delta.cos() + lat0.cos() * delta.sin() * b.cos()).asin();
    let lon1 =
        lon0 + (b.sin() * delta.sin() * lat0.cos()).atan2(delta.cos() - lat0.sin() * lat1.sin());
    (lat1.to_degrees(), lon1.to_degrees())
}
