//! The normalised flight log.

use crate::format::Format;
use std::collections::BTreeMap;

/// One sample of a log, on the time axis from liftoff, in SI units.
#[derive(Debug, Clone, PartialEq)]
pub struct Sample {
    /// Time from liftoff, s (negative before it).
    pub time_s: f64,
    /// Height above the ground (the device's zero, or the first samples' level), m.
    pub altitude_agl_m: f64,
    /// Vertical velocity, m/s: the device's, or the smoothing derivative of the altitude
    /// ([`FlightLog::velocity_source`]).
    pub vertical_velocity_mps: f64,
    /// Acceleration as the device writes it (axial for most altimeters; some include
    /// gravity on the pad, some remove it), m/s².
    pub acceleration_mps2: Option<f64>,
    /// Static pressure, Pa.
    pub pressure_pa: Option<f64>,
    /// Temperature, K.
    pub temperature_k: Option<f64>,
    /// GNSS position, when the device logs one on this row.
    pub gnss: Option<Gnss>,
}

/// A GNSS fix.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gnss {
    /// Latitude, degrees north.
    pub latitude_deg: f64,
    /// Longitude, degrees east.
    pub longitude_deg: f64,
    /// Altitude above sea level, m, when given.
    pub altitude_m: Option<f64>,
}

/// Where the vertical velocity of the samples comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VelocitySource {
    /// The device's own velocity column.
    Device,
    /// The centred least-squares slope of the altitude (see the crate documentation).
    Derivative,
}

/// What happened during the flight.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum EventKind {
    /// Liftoff.
    Launch,
    /// Motor burnout.
    Burnout,
    /// Apogee: the highest altitude of the log.
    Apogee,
    /// Drogue (or apogee-channel) deployment.
    Drogue,
    /// Main deployment.
    Main,
    /// Landing.
    Landing,
}

impl EventKind {
    /// The name used in JSON and tables.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            EventKind::Launch => "launch",
            EventKind::Burnout => "burnout",
            EventKind::Apogee => "apogee",
            EventKind::Drogue => "drogue",
            EventKind::Main => "main",
            EventKind::Landing => "landing",
        }
    }
}

/// Whether an event was recorded by the device or derived from the samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EventSource {
    /// Written by the device (a state change, an event column, a header figure).
    Device,
    /// Derived by this crate's rules (see the crate documentation).
    Derived,
}

/// One event on the time axis from liftoff.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Event {
    /// What happened.
    pub kind: EventKind,
    /// Time from liftoff, s.
    pub time_s: f64,
    /// Who says so.
    pub source: EventSource,
}

/// The device's own summary figures, SI, when its file states them.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Reported {
    /// Apogee above ground, m.
    pub apogee_agl_m: Option<f64>,
    /// Ground elevation above sea level, m.
    pub ground_elevation_m: Option<f64>,
    /// Maximum velocity, m/s.
    pub max_velocity_mps: Option<f64>,
}

/// A flight log read and normalised: one record whatever the device.
#[derive(Debug, Clone, PartialEq)]
pub struct FlightLog {
    /// The format read.
    pub format: Format,
    /// The device, as precise as the file says (family, model, serial).
    pub device: String,
    /// The samples, in time order, on the time axis from liftoff.
    pub samples: Vec<Sample>,
    /// Where the vertical velocity comes from.
    pub velocity_source: VelocitySource,
    /// Liftoff time on the device's own clock, s (the samples' time zero).
    pub liftoff_device_time_s: f64,
    /// Events in time order.
    pub events: Vec<Event>,
    /// The device's summary figures.
    pub reported: Reported,
    /// Everything else the header says, as text (keys are lower-case, values as written or
    /// converted to SI with the unit in the key).
    pub metadata: BTreeMap<String, String>,
    /// Everything the reading rules changed or could not read.
    pub warnings: Vec<String>,
}

impl FlightLog {
    /// The sample of the highest altitude (the first of equal ones).
    #[must_use]
    pub fn apogee(&self) -> &Sample {
        let mut best = &self.samples[0];
        for s in &self.samples {
            if s.altitude_agl_m > best.altitude_agl_m {
                best = s;
            }
        }
        best
    }

    /// The highest vertical velocity and its time from liftoff, s.
    #[must_use]
    pub fn max_vertical_velocity(&self) -> (f64, f64) {
        let mut best = (f64::NEG_INFINITY, 0.0);
        for s in &self.samples {
            if s.vertical_velocity_mps > best.0 {
                best = (s.vertical_velocity_mps, s.time_s);
            }
        }
        best
    }

    /// The first event of `kind`.
    #[must_use]
    pub fn event(&self, kind: EventKind) -> Option<&Event> {
        self.events.iter().find(|e| e.kind == kind)
    }

    /// The median sampling rate of the altitude, Hz (0 for fewer than two samples).
    #[must_use]
    pub fn median_rate_hz(&self) -> f64 {
        let mut steps: Vec<f64> = self
            .samples
            .windows(2)
            .map(|w| w[1].time_s - w[0].time_s)
            .collect();
        if steps.is_empty() {
            return 0.0;
        }
        steps.sort_by(f64::total_cmp);
        let median = steps[steps.len() / 2];
        if median > 0.0 { 1.0 / median } else { 0.0 }
    }
}
