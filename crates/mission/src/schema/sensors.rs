//! `[[rocket.sensors]]`: RocketPy 1.13's sensors (`Rocket.add_sensor` with an
//! `Accelerometer`, `Gyroscope`, `Barometer` or `GnssReceiver`; docs/physics.md §29). Every
//! noise key is optional and defaults to RocketPy's value; a key that does not apply to the
//! kind is reported by `karman check`.

use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::{Deserialize, Serialize, Serializer};
use std::fmt;

/// `kind` of a sensor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SensorKindName {
    /// RocketPy `Accelerometer`.
    Accelerometer,
    /// RocketPy `Gyroscope`.
    Gyroscope,
    /// RocketPy `Barometer`.
    Barometer,
    /// RocketPy `GnssReceiver`.
    Gnss,
}

impl SensorKindName {
    /// The kind as written in the file.
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            SensorKindName::Accelerometer => "accelerometer",
            SensorKindName::Gyroscope => "gyroscope",
            SensorKindName::Barometer => "barometer",
            SensorKindName::Gnss => "gnss",
        }
    }

    /// Whether the kind is an inertial sensor (orientation, cross-axis sensitivity, values
    /// per axis).
    #[must_use]
    pub fn is_inertial(self) -> bool {
        matches!(
            self,
            SensorKindName::Accelerometer | SensorKindName::Gyroscope
        )
    }
}

/// One `[[rocket.sensors]]` entry.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SensorSpec {
    /// What the sensor is.
    pub kind: SensorKindName,
    /// Unique name; the readings go to `sensor_<name>.csv`.
    pub name: String,
    /// Readings per second, Hz.
    pub sampling_rate: f64,
    /// Position in the rocket's coordinates, m: a number (on the axis) or `[x, y, z]`.
    pub position: SensorPosition,
    /// Mounting of an inertial sensor: 3-1-3 Euler angles `[roll, pitch, roll2]`, deg;
    /// RocketPy default `[0, 0, 0]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub orientation: Option<[f64; 3]>,
    /// Saturation: `m` (the range `[−m, m]`) or `[low, high]`; RocketPy default unbounded.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub measurement_range: Option<MeasurementRange>,
    /// Quantisation step, sensor units; RocketPy default 0 (none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub resolution: Option<f64>,
    /// White-noise density, sensor units/√Hz; default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub noise_density: Option<Axes>,
    /// Variance of the white noise's unit normal; default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub noise_variance: Option<Axes>,
    /// Random-walk density, sensor units·√Hz; default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub random_walk_density: Option<Axes>,
    /// Variance of the random walk's unit normal; default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub random_walk_variance: Option<Axes>,
    /// Constant bias, sensor units; default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub constant_bias: Option<Axes>,
    /// Operating temperature, K; default 298.15 (no temperature drift).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub operating_temperature: Option<f64>,
    /// Temperature bias, sensor units/K; default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub temperature_bias: Option<Axes>,
    /// Temperature scale factor, %/K; default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub temperature_scale_factor: Option<Axes>,
    /// Cross-axis sensitivity of an inertial sensor, %; default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cross_axis_sensitivity: Option<f64>,
    /// Accelerometer: subtract gravity (RocketPy's `consider_gravity`); default false.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub consider_gravity: Option<bool>,
    /// Gyroscope: rate error per unit acceleration, (rad/s)/(m/s²); default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub acceleration_sensitivity: Option<Axes>,
    /// GNSS: standard deviation of each horizontal coordinate, m; default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub position_accuracy: Option<f64>,
    /// GNSS: standard deviation of the altitude, m; default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub altitude_accuracy: Option<f64>,
}

impl SensorSpec {
    /// The keys set that `kind` does not take, in file-format order.
    #[must_use]
    pub fn keys_not_for_kind(&self) -> Vec<&'static str> {
        use SensorKindName::{Accelerometer, Gnss, Gyroscope};
        let kind = self.kind;
        let noise = kind != Gnss;
        let checks: [(&'static str, bool, bool); 16] = [
            (
                "orientation",
                self.orientation.is_some(),
                kind.is_inertial(),
            ),
            ("measurement_range", self.measurement_range.is_some(), noise),
            ("resolution", self.resolution.is_some(), noise),
            ("noise_density", self.noise_density.is_some(), noise),
            ("noise_variance", self.noise_variance.is_some(), noise),
            (
                "random_walk_density",
                self.random_walk_density.is_some(),
                noise,
            ),
            (
                "random_walk_variance",
                self.random_walk_variance.is_some(),
                noise,
            ),
            ("constant_bias", self.constant_bias.is_some(), noise),
            (
                "operating_temperature",
                self.operating_temperature.is_some(),
                noise,
            ),
            ("temperature_bias", self.temperature_bias.is_some(), noise),
            (
                "temperature_scale_factor",
                self.temperature_scale_factor.is_some(),
                noise,
            ),
            (
                "cross_axis_sensitivity",
                self.cross_axis_sensitivity.is_some(),
                kind.is_inertial(),
            ),
            (
                "consider_gravity",
                self.consider_gravity.is_some(),
                kind == Accelerometer,
            ),
            (
                "acceleration_sensitivity",
                self.acceleration_sensitivity.is_some(),
                kind == Gyroscope,
            ),
            (
                "position_accuracy",
                self.position_accuracy.is_some(),
                kind == Gnss,
            ),
            (
                "altitude_accuracy",
                self.altitude_accuracy.is_some(),
                kind == Gnss,
            ),
        ];
        checks
            .into_iter()
            .filter(|(_, set, applies)| *set && !applies)
            .map(|(key, _, _)| key)
            .collect()
    }

    /// The per-axis keys given as three values on a scalar sensor (a barometer takes one
    /// number each, as RocketPy's `ScalarSensor`).
    #[must_use]
    pub fn per_axis_keys_on_scalar(&self) -> Vec<&'static str> {
        if self.kind.is_inertial() {
            return Vec::new();
        }
        [
            ("noise_density", self.noise_density),
            ("noise_variance", self.noise_variance),
            ("random_walk_density", self.random_walk_density),
            ("random_walk_variance", self.random_walk_variance),
            ("constant_bias", self.constant_bias),
            ("temperature_bias", self.temperature_bias),
            ("temperature_scale_factor", self.temperature_scale_factor),
        ]
        .into_iter()
        .filter(|(_, v)| matches!(v, Some(Axes::PerAxis(_))))
        .map(|(k, _)| k)
        .collect()
    }
}

/// A sensor's position: a number `z` (on the rocket axis, `[0, 0, z]`) or `[x, y, z]`, in
/// the rocket's coordinates (RocketPy's `add_sensor(position)`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SensorPosition(pub [f64; 3]);

/// A per-axis parameter: one number for every axis, or `[x, y, z]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Axes {
    /// The same value on every axis.
    All(f64),
    /// One value per axis.
    PerAxis([f64; 3]),
}

impl Axes {
    /// The value of each axis.
    #[must_use]
    pub fn values(self) -> [f64; 3] {
        match self {
            Axes::All(v) => [v; 3],
            Axes::PerAxis(v) => v,
        }
    }

    /// The value to set at component `index` (`None`: every component).
    pub fn component_mut(&mut self, index: Option<usize>) -> Option<&mut f64> {
        if let Axes::All(v) = *self
            && index.is_some()
        {
            *self = Axes::PerAxis([v; 3]);
        }
        match (self, index) {
            (Axes::All(v), None) => Some(v),
            (Axes::PerAxis(v), Some(i)) => v.get_mut(i),
            (Axes::PerAxis(_), None) | (Axes::All(_), Some(_)) => None,
        }
    }
}

/// `measurement_range`: `m` for `[−m, m]`, or `[low, high]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeasurementRange(pub [f64; 2]);

/// Reads a number or a sequence of `n` numbers.
fn number_or_seq<'de, D: Deserializer<'de>>(
    deserializer: D,
    n: usize,
    expecting: &'static str,
) -> Result<Result<f64, Vec<f64>>, D::Error> {
    struct V(usize, &'static str);
    impl<'de> Visitor<'de> for V {
        type Value = Result<f64, Vec<f64>>;
        fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            f.write_str(self.1)
        }
        fn visit_i64<E: de::Error>(self, v: i64) -> Result<Self::Value, E> {
            Ok(Ok(v as f64))
        }
        fn visit_u64<E: de::Error>(self, v: u64) -> Result<Self::Value, E> {
            Ok(Ok(v as f64))
        }
        fn visit_f64<E: de::Error>(self, v: f64) -> Result<Self::Value, E> {
            Ok(Ok(v))
        }
        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
            let mut values = Vec::new();
            while let Some(v) = seq.next_element::<f64>()? {
                values.push(v);
            }
            if values.len() == self.0 {
                Ok(Err(values))
            } else {
                Err(de::Error::custom(format!(
                    "expected {}, got {} numbers",
                    self.1,
                    values.len()
                )))
            }
        }
    }
    deserializer.deserialize_any(V(n, expecting))
}

impl<'de> Deserialize<'de> for SensorPosition {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        Ok(
            match number_or_seq(deserializer, 3, "a position z or [x, y, z]")? {
                Ok(z) => SensorPosition([0.0, 0.0, z]),
                Err(v) => SensorPosition([v[0], v[1], v[2]]),
            },
        )
    }
}

impl Serialize for SensorPosition {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.0.serialize(serializer)
    }
}

impl<'de> Deserialize<'de> for Axes {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        Ok(
            match number_or_seq(deserializer, 3, "a number or [x, y, z]")? {
                Ok(v) => Axes::All(v),
                Err(v) => Axes::PerAxis([v[0], v[1], v[2]]),
            },
        )
    }
}

impl Serialize for Axes {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Axes::All(v) => serializer.serialize_f64(*v),
            Axes::PerAxis(v) => v.serialize(serializer),
        }
    }
}

impl<'de> Deserialize<'de> for MeasurementRange {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        Ok(
            match number_or_seq(deserializer, 2, "a bound m or [low, high]")? {
                Ok(m) => MeasurementRange([-m, m]),
                Err(v) => MeasurementRange([v[0], v[1]]),
            },
        )
    }
}

impl Serialize for MeasurementRange {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.0.serialize(serializer)
    }
}
