//! A flight log set against a simulation of the same flight.
//!
//! [`compare`] takes the simulated flight as plain series ([`SimulatedFlight`]: this crate
//! knows nothing of how it was flown) and a read [`FlightLog`], puts both on one time axis
//! from liftoff and computes the figures a team reports after a launch. The rules:
//!
//! 1. **Time axis.** The log's samples are already on the time axis from liftoff (the
//!    crate's rule 6). The simulation's liftoff is its first motion: the last stored point
//!    before its altitude first rises more than [`FIRST_MOTION_M`] above the starting value
//!    ([`first_motion_time`]).
//! 2. **Altitude.** The simulated altitude is counted from its starting value, as an
//!    altimeter counts from the pad (the simulation starts at the height of its reference
//!    point on the pad, not at 0).
//! 3. **Errors** are simulated minus measured; a percentage is relative to the measured value.
//! 4. **Ascent RMS.** Over the log's samples from liftoff to its apogee (both included) that
//!    lie within the simulation's span, against the simulated value linearly interpolated at
//!    each sample's time: the RMS of the altitude and of the vertical-velocity differences.
//! 5. **Descent rates.** Each parachute phase of the simulation runs from its deployment to
//!    the next deployment or to landing and descends through an altitude band. The band's
//!    top 20 % (the canopy opening and the speed settling) and bottom 10 % (the ground) are
//!    left out. The measured rate is the least-squares slope of the log's altitude on time
//!    over its samples after apogee inside the band; the simulated rate is the band's height
//!    over the time the simulation takes to cross it. Under a steady descent both are the
//!    descent rate through the same air. A band the log crosses in fewer than
//!    [`MIN_DESCENT_SAMPLES`] samples or less than [`MIN_DESCENT_SPAN_S`] has no measured rate.
//! 6. **Landing.** When the log has GNSS fixes, its launch point is the last fix at or before
//!    liftoff (the first fix if none is), its landing point the last fix; the offsets east
//!    and north are taken on the sphere of the WGS-84 semi-major axis
//!    ([`karman_math::geodesy::offset`]) and set against the simulation's landing point.

use crate::log::{EventKind, FlightLog, Gnss};
use crate::normalise::least_squares_slope;
use karman_math::constants::PhysicalConstants;
use karman_math::{geodesy, interpolate_clamped};

/// How far above its starting value the simulated altitude must rise to count as motion, m.
pub const FIRST_MOTION_M: f64 = 0.01;
/// Fewest log samples in a descent band for a measured descent rate.
pub const MIN_DESCENT_SAMPLES: usize = 5;
/// Shortest time the log may take through a descent band for a measured descent rate, s.
pub const MIN_DESCENT_SPAN_S: f64 = 1.0;
/// Share of a descent band left out at its top (rule 5).
const BAND_TOP_SKIP: f64 = 0.2;
/// Share of a descent band left out at its bottom (rule 5).
const BAND_BOTTOM_SKIP: f64 = 0.1;

/// A parachute deployment of the simulation.
#[derive(Debug, Clone, PartialEq)]
pub struct Deployment {
    /// The parachute's name.
    pub name: String,
    /// Time, s, on the simulation's own clock.
    pub time_s: f64,
}

/// Where and when the simulated flight landed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SimulatedLanding {
    /// Time, s, on the simulation's own clock.
    pub time_s: f64,
    /// East of the pad, m.
    pub east_m: f64,
    /// North of the pad, m.
    pub north_m: f64,
}

/// A simulated flight as plain series on the simulation's own clock (t = 0 at ignition or
/// wherever it starts), all of the same length, times increasing.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SimulatedFlight {
    /// Time, s.
    pub time_s: Vec<f64>,
    /// Altitude above the ground, m.
    pub altitude_m: Vec<f64>,
    /// Vertical velocity, m/s.
    pub vertical_velocity_mps: Vec<f64>,
    /// Vertical acceleration, m/s².
    pub vertical_acceleration_mps2: Vec<f64>,
    /// The parachute deployments, in time order.
    pub deployments: Vec<Deployment>,
    /// The landing, when the flight reached the ground.
    pub landing: Option<SimulatedLanding>,
}

/// Why two flights cannot be compared.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CompareError {
    /// The simulated series are not a flight: their lengths differ, there are fewer than two
    /// points, a value is not finite or the time does not increase.
    #[error("the simulated flight cannot be compared: {0}")]
    Simulation(String),
    /// The simulated flight never leaves the pad.
    #[error(
        "the simulated flight never leaves the pad (its altitude never rises {FIRST_MOTION_M} m above the start)"
    )]
    NoMotion,
}

/// The headline figures of one flight, on the time axis from liftoff.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Figures {
    /// Apogee above the pad, m.
    pub apogee_m: f64,
    /// Apogee time, s.
    pub apogee_time_s: f64,
    /// Highest vertical velocity, m/s.
    pub max_vertical_velocity_mps: f64,
    /// Landing time, s, when the flight landed.
    pub landing_time_s: Option<f64>,
}

/// One parachute phase's descent rates (rule 5).
#[derive(Debug, Clone, PartialEq)]
pub struct DescentPhase {
    /// The parachute flown in this phase.
    pub parachute: String,
    /// The altitude band over which the rates are taken, `[bottom, top]`, m above the pad.
    pub band_m: [f64; 2],
    /// The simulation's descent rate (positive down), m/s.
    pub simulated_rate_mps: f64,
    /// The log's descent rate (positive down), m/s, when the log crosses the band.
    pub measured_rate_mps: Option<f64>,
    /// Number of log samples in the band.
    pub measured_samples: usize,
}

impl DescentPhase {
    /// Simulated minus measured rate relative to the measured one, %.
    #[must_use]
    pub fn error_pct(&self) -> Option<f64> {
        self.measured_rate_mps
            .map(|m| 100.0 * (self.simulated_rate_mps - m) / m)
    }
}

/// The landing points of both flights, east and north of their pads (rule 6).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LandingPoints {
    /// The log's landing point `[east, north]`, m.
    pub measured_m: [f64; 2],
    /// The simulation's landing point `[east, north]`, m.
    pub simulated_m: [f64; 2],
}

impl LandingPoints {
    /// The log's drift from the pad, m.
    #[must_use]
    pub fn measured_drift_m(&self) -> f64 {
        self.measured_m[0].hypot(self.measured_m[1])
    }
    /// The simulation's drift from the pad, m.
    #[must_use]
    pub fn simulated_drift_m(&self) -> f64 {
        self.simulated_m[0].hypot(self.simulated_m[1])
    }
    /// Distance between the two landing points, m.
    #[must_use]
    pub fn distance_m(&self) -> f64 {
        (self.simulated_m[0] - self.measured_m[0]).hypot(self.simulated_m[1] - self.measured_m[1])
    }
}

/// A log set against a simulation: the figures of both and their differences.
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    /// The simulation's liftoff on its own clock, s (rule 1): add it to a time from liftoff
    /// to read the simulation's series.
    pub simulated_liftoff_s: f64,
    /// The simulation's starting altitude, m (rule 2): subtract it from the simulated
    /// altitudes to count them from the pad.
    pub simulated_pad_altitude_m: f64,
    /// The simulation's figures.
    pub simulated: Figures,
    /// The log's figures.
    pub measured: Figures,
    /// Log samples in the ascent comparison (rule 4).
    pub ascent_samples: usize,
    /// RMS of the altitude difference over the ascent, m.
    pub ascent_rms_altitude_m: f64,
    /// RMS of the vertical-velocity difference over the ascent, m/s.
    pub ascent_rms_velocity_mps: f64,
    /// One entry per parachute phase of the simulation.
    pub descent: Vec<DescentPhase>,
    /// Both landing points, when the log has GNSS fixes and the simulation landed.
    pub landing: Option<LandingPoints>,
}

impl Comparison {
    /// Simulated minus measured apogee, m.
    #[must_use]
    pub fn apogee_error_m(&self) -> f64 {
        self.simulated.apogee_m - self.measured.apogee_m
    }
    /// The apogee error relative to the measured apogee, %.
    #[must_use]
    pub fn apogee_error_pct(&self) -> f64 {
        100.0 * self.apogee_error_m() / self.measured.apogee_m
    }
    /// Simulated minus measured apogee time, s.
    #[must_use]
    pub fn apogee_time_error_s(&self) -> f64 {
        self.simulated.apogee_time_s - self.measured.apogee_time_s
    }
    /// The maximum vertical velocity's error relative to the measured one, %.
    #[must_use]
    pub fn max_velocity_error_pct(&self) -> f64 {
        100.0 * (self.simulated.max_vertical_velocity_mps - self.measured.max_vertical_velocity_mps)
            / self.measured.max_vertical_velocity_mps
    }
    /// Simulated minus measured landing time, s, when both landed.
    #[must_use]
    pub fn landing_time_error_s(&self) -> Option<f64> {
        Some(self.simulated.landing_time_s? - self.measured.landing_time_s?)
    }
}

impl SimulatedFlight {
    /// The index of its highest point (the first of equal ones); 0 for no points.
    #[must_use]
    pub fn apogee_index(&self) -> usize {
        let mut top = 0;
        for (i, &h) in self.altitude_m.iter().enumerate() {
            if h > self.altitude_m[top] {
                top = i;
            }
        }
        top
    }

    fn check(&self) -> Result<(), CompareError> {
        let n = self.time_s.len();
        let fail = |m: String| Err(CompareError::Simulation(m));
        if [
            self.altitude_m.len(),
            self.vertical_velocity_mps.len(),
            self.vertical_acceleration_mps2.len(),
        ]
        .iter()
        .any(|&len| len != n)
        {
            return fail("its series have different lengths".into());
        }
        if n < 2 {
            return fail(format!("it has {n} point(s)"));
        }
        let series = [
            &self.time_s,
            &self.altitude_m,
            &self.vertical_velocity_mps,
            &self.vertical_acceleration_mps2,
        ];
        if let Some(i) = (0..n).find(|&i| series.iter().any(|s| !s[i].is_finite())) {
            return fail(format!("point {i} has a value that is not a finite number"));
        }
        if let Some(i) = (1..n).find(|&i| self.time_s[i] <= self.time_s[i - 1]) {
            return fail(format!("its time does not increase at point {i}"));
        }
        Ok(())
    }

    /// The altitude at time `t` of its own clock, linearly interpolated (clamped at the ends).
    fn altitude_at(&self, t: f64) -> f64 {
        interpolate_clamped(&self.time_s, &self.altitude_m, t)
    }
}

/// The simulation's liftoff on its own clock (rule 1): the time of the last point before the
/// altitude first exceeds the starting value by [`FIRST_MOTION_M`]; `None` when it never does.
#[must_use]
pub fn first_motion_time(time_s: &[f64], altitude_m: &[f64]) -> Option<f64> {
    let start = *altitude_m.first()?;
    let moving = altitude_m
        .iter()
        .position(|&h| h > start + FIRST_MOTION_M)?;
    Some(time_s[moving.saturating_sub(1)])
}

/// Sets `log` against `simulated` (module documentation, rules 1–6).
///
/// # Errors
/// [`CompareError`] when the simulated series are not a flight or never leave the pad.
pub fn compare(simulated: &SimulatedFlight, log: &FlightLog) -> Result<Comparison, CompareError> {
    simulated.check()?;
    let liftoff = first_motion_time(&simulated.time_s, &simulated.altitude_m)
        .ok_or(CompareError::NoMotion)?;
    let pad = simulated.altitude_m[0];
    let sim = simulated_figures(simulated, liftoff, pad);
    let apogee = log.apogee();
    let measured = Figures {
        apogee_m: apogee.altitude_agl_m,
        apogee_time_s: apogee.time_s,
        max_vertical_velocity_mps: log.max_vertical_velocity().0,
        landing_time_s: log.event(EventKind::Landing).map(|e| e.time_s),
    };

    // Rule 4: the ascent.
    let end = simulated.time_s[simulated.time_s.len() - 1] - liftoff;
    let (mut n, mut sum_h, mut sum_v) = (0_usize, 0.0, 0.0);
    for s in &log.samples {
        if s.time_s < 0.0 || s.time_s > measured.apogee_time_s || s.time_s > end {
            continue;
        }
        let t = s.time_s + liftoff;
        let h = simulated.altitude_at(t) - pad;
        let v = interpolate_clamped(&simulated.time_s, &simulated.vertical_velocity_mps, t);
        sum_h += (h - s.altitude_agl_m).powi(2);
        sum_v += (v - s.vertical_velocity_mps).powi(2);
        n += 1;
    }
    let rms = |sum: f64| {
        if n == 0 {
            f64::NAN
        } else {
            (sum / n as f64).sqrt()
        }
    };

    Ok(Comparison {
        simulated_liftoff_s: liftoff,
        simulated_pad_altitude_m: pad,
        simulated: sim,
        measured,
        ascent_samples: n,
        ascent_rms_altitude_m: rms(sum_h),
        ascent_rms_velocity_mps: rms(sum_v),
        descent: descent_phases(simulated, log, pad, measured.apogee_time_s),
        landing: landing_points(simulated, log),
    })
}

fn simulated_figures(simulated: &SimulatedFlight, liftoff: f64, pad: f64) -> Figures {
    let top = simulated.apogee_index();
    let max_v = simulated
        .vertical_velocity_mps
        .iter()
        .copied()
        .fold(f64::NEG_INFINITY, f64::max);
    Figures {
        apogee_m: simulated.altitude_m[top] - pad,
        apogee_time_s: simulated.time_s[top] - liftoff,
        max_vertical_velocity_mps: max_v,
        landing_time_s: simulated.landing.map(|l| l.time_s - liftoff),
    }
}

/// Rule 5.
fn descent_phases(
    simulated: &SimulatedFlight,
    log: &FlightLog,
    pad: f64,
    measured_apogee_time: f64,
) -> Vec<DescentPhase> {
    let last = simulated.time_s[simulated.time_s.len() - 1];
    let mut phases = Vec::new();
    for (k, deployment) in simulated.deployments.iter().enumerate() {
        let start = deployment.time_s;
        let stop = simulated
            .deployments
            .get(k + 1)
            .map_or_else(
                || simulated.landing.map_or(last, |l| l.time_s),
                |d| d.time_s,
            )
            .min(last);
        if stop <= start {
            continue;
        }
        let top = simulated.altitude_at(start) - pad;
        let bottom = (simulated.altitude_at(stop) - pad).max(0.0);
        if top <= bottom {
            continue;
        }
        let height = top - bottom;
        let band = [
            bottom + BAND_BOTTOM_SKIP * height,
            top - BAND_TOP_SKIP * height,
        ];
        // The simulation's crossing times of the band's edges within the phase.
        let cross = |level: f64| crossing(simulated, pad, start, stop, level);
        let Some((t_top, t_bottom)) = cross(band[1]).zip(cross(band[0])) else {
            continue;
        };
        let simulated_rate = (band[1] - band[0]) / (t_bottom - t_top);
        let (times, heights): (Vec<f64>, Vec<f64>) = log
            .samples
            .iter()
            .filter(|s| s.time_s > measured_apogee_time)
            .filter(|s| (band[0]..=band[1]).contains(&s.altitude_agl_m))
            .map(|s| (s.time_s, s.altitude_agl_m))
            .unzip();
        let span = times.last().copied().unwrap_or(0.0) - times.first().copied().unwrap_or(0.0);
        let measured_rate = (times.len() >= MIN_DESCENT_SAMPLES && span >= MIN_DESCENT_SPAN_S)
            .then(|| -least_squares_slope(&times, &heights));
        phases.push(DescentPhase {
            parachute: deployment.name.clone(),
            band_m: band,
            simulated_rate_mps: simulated_rate,
            measured_rate_mps: measured_rate,
            measured_samples: times.len(),
        });
    }
    phases
}

/// The first time in `[start, stop]` at which the simulated altitude above the pad comes
/// down through `level`, linearly interpolated between stored points.
fn crossing(
    simulated: &SimulatedFlight,
    pad: f64,
    start: f64,
    stop: f64,
    level: f64,
) -> Option<f64> {
    let (t, h) = (&simulated.time_s, &simulated.altitude_m);
    let mut previous = (start, simulated.altitude_at(start) - pad);
    for i in 0..t.len() {
        if t[i] <= start {
            continue;
        }
        let point = if t[i] >= stop {
            (stop, simulated.altitude_at(stop) - pad)
        } else {
            (t[i], h[i] - pad)
        };
        if previous.1 >= level && point.1 <= level {
            let share = if previous.1 > point.1 {
                (previous.1 - level) / (previous.1 - point.1)
            } else {
                0.0
            };
            return Some(previous.0 + share * (point.0 - previous.0));
        }
        if point.0 >= stop {
            break;
        }
        previous = point;
    }
    None
}

/// Rule 6.
fn landing_points(simulated: &SimulatedFlight, log: &FlightLog) -> Option<LandingPoints> {
    let landing = simulated.landing?;
    let fixes: Vec<(f64, Gnss)> = log
        .samples
        .iter()
        .filter_map(|s| s.gnss.map(|g| (s.time_s, g)))
        .collect();
    let launch = fixes
        .iter()
        .rev()
        .find(|(t, _)| *t <= 0.0)
        .or_else(|| fixes.first())?
        .1;
    let last = fixes.last()?.1;
    let (east, north) = geodesy::offset(
        launch.latitude_deg,
        launch.longitude_deg,
        last.latitude_deg,
        last.longitude_deg,
        PhysicalConstants::SI.wgs84_semi_major_axis,
    );
    Some(LandingPoints {
        measured_m: [east, north],
        simulated_m: [landing.east_m, landing.north_m],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::Format;
    use crate::log::{Event, EventSource, Sample, VelocitySource};
    use std::collections::BTreeMap;

    /// A flight: 2 s on the pad, a 3 s boost at 60 m/s², coast to apogee, a drogue at apogee
    /// descending at 20 m/s to 300 m, then a main at 6 m/s.
    fn truth(t: f64) -> (f64, f64) {
        let g = 9.80665;
        let (boost, a) = (3.0, 60.0);
        let (h_b, v_b) = (0.5 * a * boost * boost, a * boost);
        let t_apo = boost + v_b / g;
        let h_apo = h_b + v_b * v_b / (2.0 * g);
        let t_main = t_apo + (h_apo - 300.0) / 20.0;
        if t <= 0.0 {
            (0.0, 0.0)
        } else if t < boost {
            (0.5 * a * t * t, a * t)
        } else if t < t_apo {
            let c = t - boost;
            (h_b + v_b * c - 0.5 * g * c * c, v_b - g * c)
        } else if t < t_main {
            (h_apo - 20.0 * (t - t_apo), -20.0)
        } else {
            ((300.0 - 6.0 * (t - t_main)).max(0.0), -6.0)
        }
    }

    fn simulation(offset: f64, pad: f64, scale: f64) -> SimulatedFlight {
        let mut sim = SimulatedFlight::default();
        let mut t = 0.0;
        while t < 200.0 {
            let (h, v) = truth(t - offset);
            sim.time_s.push(t);
            sim.altitude_m.push(pad + h * scale);
            sim.vertical_velocity_mps.push(v * scale);
            sim.vertical_acceleration_mps2.push(0.0);
            t += 0.05;
        }
        let g = 9.80665;
        let t_apo = 3.0 + 180.0 / g;
        let h_apo = 270.0 + 180.0 * 180.0 / (2.0 * g);
        sim.deployments = vec![
            Deployment {
                name: "drogue".into(),
                time_s: offset + t_apo,
            },
            Deployment {
                name: "main".into(),
                time_s: offset + t_apo + (h_apo - 300.0) / 20.0,
            },
        ];
        sim.landing = Some(SimulatedLanding {
            time_s: offset + t_apo + (h_apo - 300.0) / 20.0 + 50.0,
            east_m: 300.0,
            north_m: -400.0,
        });
        sim
    }

    fn log(gnss: bool) -> FlightLog {
        let mut samples = Vec::new();
        let mut t = -1.0;
        while t < 180.0 {
            let (h, v) = truth(t);
            // The pad's GNSS fix at 45° N, 7° E; the last one 500 m east and 200 m south.
            let fix = gnss.then(|| {
                let (e, n) = if t < 150.0 {
                    (0.0, 0.0)
                } else {
                    (500.0, -200.0)
                };
                let (lat, lon) = geodesy::destination(
                    45.0,
                    7.0,
                    e,
                    n,
                    PhysicalConstants::SI.wgs84_semi_major_axis,
                );
                Gnss {
                    latitude_deg: lat,
                    longitude_deg: lon,
                    altitude_m: None,
                }
            });
            samples.push(Sample {
                time_s: t,
                altitude_agl_m: h,
                vertical_velocity_mps: v,
                acceleration_mps2: None,
                pressure_pa: None,
                temperature_k: None,
                gnss: fix,
            });
            t += 0.1;
        }
        FlightLog {
            format: Format::Generic,
            device: "test".into(),
            samples,
            velocity_source: VelocitySource::Device,
            liftoff_device_time_s: 0.0,
            events: vec![Event {
                kind: EventKind::Landing,
                time_s: 165.0,
                source: EventSource::Derived,
            }],
            reported: crate::log::Reported::default(),
            metadata: BTreeMap::new(),
            warnings: Vec::new(),
        }
    }

    #[test]
    fn the_same_flight_has_no_errors_whatever_the_clock_and_pad_height() {
        let c = compare(&simulation(2.0, 1.7, 1.0), &log(false)).unwrap();
        assert!(
            (c.simulated_liftoff_s - 2.0).abs() < 0.051,
            "{}",
            c.simulated_liftoff_s
        );
        assert!(c.apogee_error_m().abs() < 0.05, "{}", c.apogee_error_m());
        assert!(c.apogee_time_error_s().abs() < 0.1);
        assert!(
            c.max_velocity_error_pct().abs() < 1.0,
            "{}",
            c.max_velocity_error_pct()
        );
        assert!(c.ascent_rms_altitude_m < 0.5, "{}", c.ascent_rms_altitude_m);
        assert!(c.ascent_samples > 100);
        assert_eq!(c.descent.len(), 2);
        for (phase, rate) in c.descent.iter().zip([20.0, 6.0]) {
            assert!((phase.simulated_rate_mps - rate).abs() < 0.05, "{phase:?}");
            let measured = phase.measured_rate_mps.unwrap();
            assert!((measured - rate).abs() < 0.05, "{phase:?}");
            assert!(phase.error_pct().unwrap().abs() < 0.5);
        }
        assert!(c.landing.is_none(), "no GNSS in the log");
    }

    #[test]
    fn a_higher_simulation_shows_as_its_errors() {
        let c = compare(&simulation(0.5, 0.0, 1.05), &log(false)).unwrap();
        let expected = 0.05 * c.measured.apogee_m;
        assert!(
            (c.apogee_error_m() - expected).abs() < 0.1,
            "{}",
            c.apogee_error_m()
        );
        assert!((c.apogee_error_pct() - 5.0).abs() < 0.05);
        assert!((c.max_velocity_error_pct() - 5.0).abs() < 0.5);
        assert!(c.ascent_rms_altitude_m > 10.0);
        // 5 % faster descents through the scaled bands.
        for phase in &c.descent {
            assert!((phase.error_pct().unwrap() - 5.0).abs() < 1.5, "{phase:?}");
        }
    }

    #[test]
    fn gnss_fixes_give_the_landing_points() {
        let c = compare(&simulation(0.0, 0.0, 1.0), &log(true)).unwrap();
        let landing = c.landing.unwrap();
        assert!((landing.measured_m[0] - 500.0).abs() < 1e-3, "{landing:?}");
        assert!((landing.measured_m[1] + 200.0).abs() < 1e-3, "{landing:?}");
        assert!((landing.distance_m() - 200.0_f64.hypot(200.0)).abs() < 1e-3);
        assert!((landing.simulated_drift_m() - 500.0).abs() < 1e-9);
    }

    #[test]
    fn malformed_simulations_are_errors() {
        let mut sim = simulation(0.0, 0.0, 1.0);
        sim.altitude_m.pop();
        assert!(matches!(
            compare(&sim, &log(false)),
            Err(CompareError::Simulation(_))
        ));
        let mut sim = simulation(0.0, 0.0, 1.0);
        sim.time_s[10] = sim.time_s[9];
        let error = compare(&sim, &log(false)).unwrap_err();
        assert!(error.to_string().contains("point 10"), "{error}");
        let mut sim = simulation(0.0, 0.0, 1.0);
        sim.vertical_velocity_mps[3] = f64::NAN;
        assert!(compare(&sim, &log(false)).is_err());
        let mut sim = simulation(0.0, 0.0, 1.0);
        sim.altitude_m.iter_mut().for_each(|h| *h = 2.0);
        assert_eq!(compare(&sim, &log(false)), Err(CompareError::NoMotion));
        assert!(compare(&SimulatedFlight::default(), &log(false)).is_err());
    }
}
