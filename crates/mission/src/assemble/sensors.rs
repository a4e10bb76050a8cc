//! `[[rocket.sensors]]` bound to a flight: each entry built into a
//! [`karman_sensors::Sensor`] (its position turned into RocketPy's `relative_position`, checked
//! on the rocket) and sampled as a process of the engine at `j / sampling_rate` in every
//! phase, measuring the state and the right-hand side of the equations at each instant
//! (RocketPy's `Flight.__measure_sensors`, docs/physics.md §29.2).
//!
//! Each sensor publishes its reading on the engine's signals ([`signal_name`]): component
//! `c` of sensor `NAME` as `sensors.NAME.c`. The controller (its `sensors` argument) and the
//! trigger expressions (`sensors[i]`, `sensors.NAME`) read the latest value there. A sensor
//! comes after the parachutes and the controller in the flight's processes, so at an instant
//! they share, these read the reading of the sensor's previous instant, as RocketPy 1.13 runs
//! its overshootable time nodes (parachutes, then controllers, then sensors); with
//! `time_overshoot = false` it comes before the controller, as RocketPy measures at its
//! integrator stops (docs/physics.md §29.3).

use karman_airframe::Rocket;
use karman_atmos::Environment;
use karman_dynamics::flight::{Action, Probe, SampledProcess};
use karman_sensors::{NoiseParameters, Sensor, SensorKind, Surroundings, Truth};

use crate::schema::{SensorKindName, SensorSpec};
use crate::{Mission, MissionError};
use karman_script::{SensorSetup, SensorShape};

/// The readings of one sensor over a flight.
#[derive(Debug, Clone, PartialEq)]
pub struct SensorReadings {
    /// The sensor's name.
    pub name: String,
    /// Its kind (what the components are).
    pub kind: SensorKind,
    /// Sampling instants, s.
    pub times: Vec<f64>,
    /// The reading at each instant (the first `kind.components().len()` values are used).
    pub values: Vec<[f64; 3]>,
}

impl SensorReadings {
    /// The column names, units as suffixes as in `trajectory.csv`: `time_s`, then the
    /// kind's components (RocketPy's export labels, e.g. `ax_mps2`, `pressure_pa`,
    /// `latitude_deg`).
    #[must_use]
    pub fn columns(&self) -> Vec<String> {
        std::iter::once("time_s".to_owned())
            .chain(self.kind.components().iter().map(|(name, unit)| {
                let suffix = match *unit {
                    "m/s^2" => "mps2",
                    "rad/s" => "radps",
                    "Pa" => "pa",
                    other => other,
                };
                format!("{name}_{suffix}")
            }))
            .collect()
    }

    /// The readings as CSV text: the header of [`SensorReadings::columns`], then one row per
    /// instant (shortest round-trip formatting, as `trajectory.csv`).
    #[must_use]
    pub fn csv(&self) -> String {
        use std::fmt::Write;
        let n = self.kind.components().len();
        let mut text = self.columns().join(",");
        text.push('\n');
        for (t, v) in self.times.iter().zip(&self.values) {
            let _ = write!(text, "{t}");
            for x in &v[..n] {
                let _ = write!(text, ",{x}");
            }
            text.push('\n');
        }
        text
    }

    /// The readings as a JSON object: `kind`, then one array per column of
    /// [`SensorReadings::columns`] (non-finite values as `null`).
    #[must_use]
    pub fn to_json(&self) -> serde_json::Value {
        let mut object = serde_json::Map::new();
        object.insert("kind".to_owned(), self.kind.name().into());
        let columns = self.columns();
        object.insert("time_s".to_owned(), self.times.clone().into());
        for (i, column) in columns.iter().enumerate().skip(1) {
            let values: Vec<f64> = self.values.iter().map(|v| v[i - 1]).collect();
            object.insert(column.clone(), values.into());
        }
        serde_json::Value::Object(object)
    }
}

/// Largest sensor sampling rate, Hz (documented in docs/mission-format.md): 10 kHz is above
/// any flight computer's logging rate; more only multiplies the sampling instants and the
/// stored readings of a flight (10 minutes at 10 kHz: six million rows).
pub const MAX_SENSOR_SAMPLING_RATE: f64 = 10_000.0;

/// The sensors of `mission` for `rocket`, their noise seeded with `seed` (sensor `i` draws
/// from its own stream, keyed by the seed and `i`).
///
/// # Errors
/// [`MissionError::Model`] with section `rocket.sensors.<i>.<key>` for a sensor outside the
/// rocket (axially beyond its nose tip or aft end, radially beyond its largest radius) or a
/// parameter out of its domain.
pub fn build(mission: &Mission, rocket: &Rocket, seed: u64) -> Result<Vec<Sensor>, MissionError> {
    let (aft, fore, radius) = extent(rocket);
    let csys = rocket.csys();
    let cdm = rocket.center_of_dry_mass();
    let mut sensors = Vec::with_capacity(mission.spec.rocket.sensors.len());
    for (i, entry) in mission.spec.rocket.sensors.iter().enumerate() {
        let key = |k: &str| format!("rocket.sensors.{i}.{k}");
        let [x, y, z] = entry.position.0;
        let radial = x.hypot(y);
        let inside = (aft..=fore).contains(&z) && radial <= radius;
        if !inside {
            return Err(mission.model_error(
                &key("position"),
                format!(
                    "sensor `{}` at [{x}, {y}, {z}] m is outside the rocket: its axis spans \
                     [{aft}, {fore}] m and its largest radius is {radius} m",
                    entry.name
                ),
            ));
        }
        // RocketPy's `relative_position = position − csys·(0, 0, z_CDM)` (docs/physics.md §29.2).
        let relative = [x, y, z - csys * cdm];
        let spec = sensor_spec(entry, relative);
        let sensor = Sensor::new(spec, seed, i as u64).map_err(|e| {
            let karman_sensors::SensorError::Parameter { name, .. } = &e;
            mission.model_error(&key(name), e.clone())
        })?;
        sensors.push(sensor);
    }
    Ok(sensors)
}

/// The axial span `[aft, fore]` of `rocket` in its coordinates (its surfaces from their
/// reference points to their aft ends, and the nozzle) and its largest radius, m.
fn extent(rocket: &Rocket) -> (f64, f64, f64) {
    let csys = rocket.csys();
    let nozzle = rocket.nozzle_position();
    let (mut lo, mut hi) = (nozzle, nozzle);
    let mut radius = rocket.radius();
    for s in rocket.surfaces() {
        let end = s.position - csys * s.geometry.length();
        lo = lo.min(s.position).min(end);
        hi = hi.max(s.position).max(end);
        radius = radius.max(s.geometry.max_radius());
    }
    (lo, hi, radius)
}

/// The engine-side spec of a mission entry, RocketPy's defaults where a key is absent.
fn sensor_spec(entry: &SensorSpec, relative_position: [f64; 3]) -> karman_sensors::SensorSpec {
    let kind = match entry.kind {
        SensorKindName::Accelerometer => SensorKind::Accelerometer {
            consider_gravity: entry.consider_gravity.unwrap_or(false),
        },
        SensorKindName::Gyroscope => SensorKind::Gyroscope {
            acceleration_sensitivity: entry
                .acceleration_sensitivity
                .map_or([0.0; 3], |a| a.values()),
        },
        SensorKindName::Barometer => SensorKind::Barometer,
        SensorKindName::Gnss => SensorKind::Gnss {
            position_accuracy: entry.position_accuracy.unwrap_or(0.0),
            altitude_accuracy: entry.altitude_accuracy.unwrap_or(0.0),
        },
    };
    let d = NoiseParameters::default();
    let axes =
        |v: Option<crate::schema::Axes>, default: [f64; 3]| v.map_or(default, |a| a.values());
    let noise = NoiseParameters {
        measurement_range: entry.measurement_range.map_or(d.measurement_range, |r| r.0),
        resolution: entry.resolution.unwrap_or(d.resolution),
        noise_density: axes(entry.noise_density, d.noise_density),
        noise_variance: axes(entry.noise_variance, d.noise_variance),
        random_walk_density: axes(entry.random_walk_density, d.random_walk_density),
        random_walk_variance: axes(entry.random_walk_variance, d.random_walk_variance),
        constant_bias: axes(entry.constant_bias, d.constant_bias),
        operating_temperature: entry
            .operating_temperature
            .unwrap_or(d.operating_temperature),
        temperature_bias: axes(entry.temperature_bias, d.temperature_bias),
        temperature_scale_factor: axes(entry.temperature_scale_factor, d.temperature_scale_factor),
    };
    karman_sensors::SensorSpec {
        name: entry.name.clone(),
        kind,
        sampling_rate: entry.sampling_rate,
        relative_position,
        orientation_deg: entry.orientation.unwrap_or([0.0; 3]),
        cross_axis_sensitivity: entry.cross_axis_sensitivity.unwrap_or(0.0),
        noise,
    }
}

/// The launch environment as the sensors see it: the flight's pressure and gravity tables,
/// the site and the datum radius (RocketPy's `Environment.earth_radius`).
pub struct EnvironmentSurroundings<'e>(pub &'e Environment);

impl Surroundings for EnvironmentSurroundings<'_> {
    fn pressure(&self, h: f64) -> f64 {
        self.0.pressure(h)
    }
    fn gravity(&self, h: f64) -> f64 {
        self.0.gravity(h)
    }
    fn site(&self) -> [f64; 2] {
        [self.0.latitude_deg(), self.0.longitude_deg()]
    }
    fn earth_radius(&self) -> f64 {
        self.0.datum_radius()
    }
}

/// A sensor as a sampled process of the engine: sampled in every phase (the rail too, as
/// RocketPy measures at every time node of every phase) over whole steps (docs/physics.md
/// §29.2's deviation at the apogee step), and at the instant where an action started the
/// phase (RocketPy clears only the parachutes of that node); it never acts. Each instant is
/// measured once: an instant it measured before a process after it acted there (and so cut
/// the phase) is not measured again at the new phase's start. Its readings go to `readings`.
pub struct SensorProcess<'s> {
    /// The sensor.
    pub sensor: Sensor,
    /// What it measures the environment with.
    pub surroundings: &'s dyn Surroundings,
    /// Where its readings go.
    pub readings: &'s mut SensorReadings,
    /// The names of its signals, one per component ([`signal_name`]).
    pub outputs: Vec<&'s str>,
}

impl SampledProcess for SensorProcess<'_> {
    fn rate(&self) -> f64 {
        self.sensor.spec().sampling_rate
    }

    fn outputs(&self) -> &[&str] {
        &self.outputs
    }

    fn on_rail(&self) -> bool {
        true
    }

    fn whole_step(&self) -> bool {
        true
    }

    fn sampled_at_cleared_start(&self) -> bool {
        true
    }

    fn sample(&mut self, probe: &mut Probe<'_>) -> Option<Action> {
        // Instants keyed to 1e-7 s, as the engine merges them.
        let key = |t: f64| (t * 1e7).round() as i64;
        if self
            .readings
            .times
            .last()
            .is_some_and(|&last| key(last) == key(probe.t()))
        {
            return None;
        }
        let (u, u_dot) = probe.state_and_rhs();
        let value = self.sensor.measure(&Truth { u, u_dot }, self.surroundings);
        self.readings.times.push(probe.t());
        self.readings.values.push(value);
        for (c, v) in value.iter().enumerate().take(self.outputs.len()) {
            probe.publish(c, *v);
        }
        None
    }
}

/// The name of the signal on which sensor `name` publishes component `component` of its
/// readings: `sensors.<name>.<component>`.
#[must_use]
pub fn signal_name(name: &str, component: usize) -> String {
    format!("sensors.{name}.{component}")
}

/// The number of components of a reading of `kind` (1 for a barometer, 3 otherwise).
#[must_use]
pub fn components(kind: SensorKindName) -> usize {
    match kind {
        SensorKindName::Barometer => 1,
        SensorKindName::Accelerometer | SensorKindName::Gyroscope | SensorKindName::Gnss => 3,
    }
}

/// The mission's sensors as a trigger expression reads them, in file order.
#[must_use]
pub fn shapes(sensors: &[SensorSpec]) -> Vec<SensorShape<'_>> {
    sensors
        .iter()
        .map(|s| SensorShape {
            name: &s.name,
            kind: s.kind.as_str(),
            components: components(s.kind),
        })
        .collect()
}

/// The mission's sensors as the controller's `sensors` argument describes them.
#[must_use]
pub fn setups(sensors: &[SensorSpec]) -> Vec<SensorSetup> {
    sensors
        .iter()
        .map(|s| SensorSetup {
            name: s.name.clone(),
            kind: s.kind.as_str().to_owned(),
            components: components(s.kind),
        })
        .collect()
}

/// Empty readings for each sensor, in order.
#[must_use]
pub fn empty_readings(sensors: &[Sensor]) -> Vec<SensorReadings> {
    sensors
        .iter()
        .map(|s| SensorReadings {
            name: s.spec().name.clone(),
            kind: s.spec().kind,
            times: Vec::new(),
            values: Vec::new(),
        })
        .collect()
}
