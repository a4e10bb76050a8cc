//! From a [`Raw`] log on the device's clock to a [`FlightLog`] on the time axis from liftoff.
//! The rules are those of the crate documentation, in this order: clock order, height above
//! ground, glitch rows, velocity, liftoff, events.

use crate::error::FlightLogError;
use crate::log::{Event, EventKind, EventSource, FlightLog, Sample, VelocitySource};
use crate::raw::{AltitudeKind, DeviceEvent, Raw, Tally};
use crate::units::pressure_height;
use std::cmp::Ordering;

/// Height above ground the climb must pass to count as a flight, m.
pub const LIFTOFF_HEIGHT_M: f64 = 10.0;
/// The climb must still be going this long after the threshold crossing, s…
pub const RISE_CHECK_S: f64 = 1.0;
/// … by at least this much more height, m.
pub const RISE_GAIN_M: f64 = 10.0;
/// Heights above this are never the ground in the back-off to the start of the rise, m.
pub const GROUND_BAND_M: f64 = 1.5;
/// With an accelerometer, liftoff is where the acceleration first exceeds the pad's by this
/// (2 g), m/s².
pub const LIFTOFF_ACCELERATION_MPS2: f64 = 2.0 * 9.80665;
/// Longest back-off from the threshold crossing to the start of the rise, s.
pub const BACKOFF_MAX_S: f64 = 2.0;
/// The ground level of MSL and pressure logs: the mean over the first this many seconds, s.
pub const GROUND_WINDOW_S: f64 = 0.5;
/// A step between kept samples faster than this is a glitch, m/s (above any amateur
/// rocket's speed)…
pub const GLITCH_SPEED_MPS: f64 = 1500.0;
/// … plus this allowance for samples very close in time, m.
pub const GLITCH_MARGIN_M: f64 = 5.0;
/// After this many consecutive glitch rows, the next row is accepted as the new level.
pub const GLITCH_RUN: usize = 5;
/// Half-width of the least-squares window of the derivative velocity, s.
pub const VELOCITY_HALF_WINDOW_S: f64 = 0.5;
/// At most this many neighbours on each side enter that window (bounds the work per sample).
pub const VELOCITY_MAX_NEIGHBOURS: usize = 50;
/// Landing: the first sample after apogee at or below this height, m AGL.
pub const LANDING_HEIGHT_M: f64 = 5.0;
/// Samples before the climb lower than minus this are reported, m.
pub const NEGATIVE_REPORT_M: f64 = 10.0;

/// Keeps, in place and in order, the samples (and their lines) that `keep` accepts, given
/// each sample's line and the last sample kept before it.
fn retain_after(
    samples: &mut Vec<Sample>,
    lines: &mut Vec<usize>,
    mut keep: impl FnMut(&Sample, usize, Option<&Sample>) -> bool,
) {
    let mut kept: usize = 0;
    for i in 0..samples.len() {
        let last = kept.checked_sub(1).map(|k| &samples[k]);
        if keep(&samples[i], lines[i], last) {
            samples.swap(kept, i);
            lines.swap(kept, i);
            kept += 1;
        }
    }
    samples.truncate(kept);
    lines.truncate(kept);
}

/// Keeps the samples whose time is later than the last kept one; the others (repeated
/// times, a clock going back) are dropped and reported.
fn clock_order(samples: &mut Vec<Sample>, lines: &mut Vec<usize>, warnings: &mut Vec<String>) {
    let mut repeated = Tally::default();
    let mut backwards = Tally::default();
    retain_after(samples, lines, |s, line, last| {
        let Some(last) = last else { return true };
        match s.time_s.partial_cmp(&last.time_s) {
            Some(Ordering::Greater) => true,
            Some(Ordering::Equal) => {
                repeated.add(line);
                false
            }
            _ => {
                backwards.add(line);
                false
            }
        }
    });
    if repeated.count > 0 {
        warnings.push(format!(
            "{} row(s) repeat the time of the row before and were dropped (first at line {})",
            repeated.count, repeated.first_line
        ));
    }
    if backwards.count > 0 {
        warnings.push(format!(
            "{} row(s) with a clock going back were dropped (first at line {})",
            backwards.count, backwards.first_line
        ));
    }
}

/// The mean of the raw altitude value over the samples in the first [`GROUND_WINDOW_S`].
fn ground_level(samples: &[Sample]) -> f64 {
    let t0 = samples[0].time_s;
    let mut sum = 0.0;
    let mut n = 0.0;
    for s in samples
        .iter()
        .take_while(|s| s.time_s - t0 <= GROUND_WINDOW_S)
    {
        sum += s.altitude_agl_m;
        n += 1.0;
    }
    sum / n
}

/// Drops glitch rows: a sample whose height differs from the last kept one by more than
/// [`GLITCH_SPEED_MPS`]·Δt + [`GLITCH_MARGIN_M`]. After [`GLITCH_RUN`] glitches in a row the
/// next sample is accepted as a new level (reported).
fn drop_glitches(samples: &mut Vec<Sample>, lines: &mut Vec<usize>, warnings: &mut Vec<String>) {
    let mut glitches = Tally::default();
    let mut run = 0;
    retain_after(samples, lines, |s, line, last| {
        if let Some(last) = last {
            let (h, dt) = (s.altitude_agl_m, s.time_s - last.time_s);
            if (h - last.altitude_agl_m).abs() > GLITCH_SPEED_MPS * dt + GLITCH_MARGIN_M {
                if run < GLITCH_RUN {
                    run += 1;
                    glitches.add(line);
                    return false;
                }
                warnings.push(format!(
                    "line {line}: after {GLITCH_RUN} glitch rows the altitude {h:.1} m is taken \
                     as the new level"
                ));
            }
        }
        run = 0;
        true
    });
    if glitches.count > 0 {
        warnings.push(format!(
            "{} glitch row(s) dropped: altitude jumps faster than {GLITCH_SPEED_MPS} m/s from \
             the row before (first at line {})",
            glitches.count, glitches.first_line
        ));
    }
}

/// The centred least-squares slope of `h` over `t` at each sample, within
/// ±[`VELOCITY_HALF_WINDOW_S`] and at most [`VELOCITY_MAX_NEIGHBOURS`] samples each side.
pub(crate) fn derivative(t: &[f64], h: &[f64]) -> Vec<f64> {
    let n = t.len();
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let mut lo = i;
        while lo > 0
            && i - (lo - 1) <= VELOCITY_MAX_NEIGHBOURS
            && t[i] - t[lo - 1] <= VELOCITY_HALF_WINDOW_S
        {
            lo -= 1;
        }
        let mut hi = i;
        while hi + 1 < n
            && hi + 1 - i <= VELOCITY_MAX_NEIGHBOURS
            && t[hi + 1] - t[i] <= VELOCITY_HALF_WINDOW_S
        {
            hi += 1;
        }
        // At the ends, or with sparse samples, take at least the next neighbour.
        if lo == hi {
            if hi + 1 < n {
                hi += 1;
            } else {
                lo = lo.saturating_sub(1);
            }
        }
        out.push(least_squares_slope(&t[lo..=hi], &h[lo..=hi]));
    }
    out
}

/// The least-squares slope of `y` on `x` (same lengths, at least one point): `Σ(x − x̄)(y −
/// ȳ) / Σ(x − x̄)²`, 0 when every `x` is the same.
pub(crate) fn least_squares_slope(x: &[f64], y: &[f64]) -> f64 {
    let count = x.len() as f64;
    let mean_x = x.iter().sum::<f64>() / count;
    let mean_y = y.iter().sum::<f64>() / count;
    let mut sxx = 0.0;
    let mut sxy = 0.0;
    for (xi, yi) in x.iter().zip(y) {
        sxx += (xi - mean_x) * (xi - mean_x);
        sxy += (xi - mean_x) * (yi - mean_y);
    }
    if sxx > 0.0 { sxy / sxx } else { 0.0 }
}

/// The index of the liftoff sample and of the threshold crossing, by the crate's rule, or
/// `None`.
fn liftoff(t: &[f64], h: &[f64], samples: &[Sample]) -> Option<(usize, usize)> {
    let n = t.len();
    let mut k = 0;
    for i in 0..n {
        if h[i] < LIFTOFF_HEIGHT_M {
            continue;
        }
        k = k.max(i);
        while k < n && t[k] < t[i] + RISE_CHECK_S {
            k += 1;
        }
        if k < n && h[k] > h[i] + RISE_GAIN_M {
            // With an accelerometer: the first sample of the 2 s before the crossing whose
            // acceleration exceeds the pad's by LIFTOFF_ACCELERATION_MPS2.
            let pad: Vec<f64> = samples
                .iter()
                .zip(t)
                .take_while(|(_, ti)| **ti - t[0] <= GROUND_WINDOW_S)
                .filter_map(|(s, _)| s.acceleration_mps2)
                .collect();
            if !pad.is_empty() {
                let pad = pad.iter().sum::<f64>() / pad.len() as f64;
                let from = t.partition_point(|&ti| ti < t[i] - BACKOFF_MAX_S);
                if let Some(j) = (from..=i).find(|&j| {
                    samples[j]
                        .acceleration_mps2
                        .is_some_and(|a| a - pad > LIFTOFF_ACCELERATION_MPS2)
                }) {
                    return Some((j, i));
                }
            }
            let mut j = i;
            while j > 0
                && (h[j - 1] < h[j] || h[j - 1] > GROUND_BAND_M)
                && t[i] - t[j - 1] <= BACKOFF_MAX_S
            {
                j -= 1;
            }
            return Some((j, i));
        }
    }
    None
}

/// The acceleration of a separate channel at time `t`, linear between its samples, while
/// `t` lies within it; `cursor` only moves forward (times come in order).
fn channel_at(channel: &[(f64, f64)], cursor: &mut usize, t: f64) -> Option<f64> {
    let first = channel.first()?;
    let last = channel.last()?;
    if t < first.0 || t > last.0 {
        return None;
    }
    while *cursor + 1 < channel.len() && channel[*cursor + 1].0 < t {
        *cursor += 1;
    }
    let (t0, a0) = channel[*cursor];
    let Some(&(t1, a1)) = channel.get(*cursor + 1) else {
        return Some(a0);
    };
    let w = if t1 > t0 {
        ((t - t0) / (t1 - t0)).clamp(0.0, 1.0)
    } else {
        0.0
    };
    Some(a0 + w * (a1 - a0))
}

/// Height above ground in place of the raw altitude value: an altitude above sea level less
/// the ground level (recorded in the metadata and the reported ground elevation), a pressure
/// turned into a height above the ground's pressure.
fn height_above_ground(raw: &mut Raw, samples: &mut [Sample]) {
    match raw.altitude {
        AltitudeKind::Agl => {}
        AltitudeKind::Msl => {
            let ground = ground_level(samples);
            raw.metadata
                .insert("ground_elevation_m".into(), format!("{ground:.2}"));
            raw.reported.ground_elevation_m.get_or_insert(ground);
            for s in samples.iter_mut() {
                s.altitude_agl_m -= ground;
            }
        }
        AltitudeKind::Pressure => {
            let ground = ground_level(samples);
            raw.metadata
                .insert("ground_pressure_pa".into(), format!("{ground:.1}"));
            for s in samples.iter_mut() {
                s.altitude_agl_m = pressure_height(s.altitude_agl_m, ground);
            }
        }
    }
}

/// A separate acceleration channel, its samples kept in clock order (the others dropped with a
/// warning), interpolated onto the samples that have no acceleration of their own.
fn fill_acceleration(raw: &[(f64, f64)], samples: &mut [Sample], warnings: &mut Vec<String>) {
    let mut channel: Vec<(f64, f64)> = Vec::with_capacity(raw.len());
    let mut channel_dropped = 0;
    for &(ct, a) in raw {
        if channel.last().is_none_or(|&(lt, _)| ct > lt) {
            channel.push((ct, a));
        } else {
            channel_dropped += 1;
        }
    }
    if channel_dropped > 0 {
        warnings.push(format!(
            "{channel_dropped} acceleration-channel sample(s) with a clock not going forward dropped"
        ));
    }
    let mut cursor = 0;
    for s in samples.iter_mut() {
        if s.acceleration_mps2.is_none() {
            s.acceleration_mps2 = channel_at(&channel, &mut cursor, s.time_s);
        }
    }
}

/// The flight's events from liftoff (sample `start`, device time `t_liftoff`): the device's
/// where it logged them, else derived (burnout at the fastest climb, apogee at the highest
/// sample, landing at the first sample back under the landing height), in time order.
fn flight_events(
    device_events: &[DeviceEvent],
    t: &[f64],
    h: &[f64],
    out: &[Sample],
    start: usize,
    t_liftoff: f64,
    warnings: &mut Vec<String>,
) -> Vec<Event> {
    let mut apogee = start;
    for i in start..h.len() {
        if h[i] > h[apogee] {
            apogee = i;
        }
    }
    let device = |kind: EventKind| {
        device_events
            .iter()
            .find(|e| e.kind == kind)
            .map(|e| Event {
                kind,
                time_s: e.time - t_liftoff,
                source: EventSource::Device,
            })
    };
    let derived = |kind: EventKind, i: usize| Event {
        kind,
        time_s: t[i] - t_liftoff,
        source: EventSource::Derived,
    };
    let mut events = vec![derived(EventKind::Launch, start)];
    let burnout = device(EventKind::Burnout).or_else(|| {
        let i = (start..=apogee).max_by(|&a, &b| {
            out[a]
                .vertical_velocity_mps
                .total_cmp(&out[b].vertical_velocity_mps)
        })?;
        Some(derived(EventKind::Burnout, i))
    });
    events.extend(burnout);
    events.push(derived(EventKind::Apogee, apogee));
    events.extend(device(EventKind::Drogue));
    events.extend(device(EventKind::Main));
    let landing = device(EventKind::Landing).or_else(|| {
        let i = (apogee..h.len()).find(|&i| h[i] <= LANDING_HEIGHT_M)?;
        Some(derived(EventKind::Landing, i))
    });
    match landing {
        Some(e) => events.push(e),
        None => warnings.push(format!(
            "the log ends before landing (last altitude {:.1} m AGL)",
            h[h.len() - 1]
        )),
    }
    events.sort_by(|a, b| a.time_s.total_cmp(&b.time_s));
    events
}

/// Normalises a raw log by the crate's rules.
pub(crate) fn normalise(mut raw: Raw) -> Result<FlightLog, FlightLogError> {
    let mut warnings = std::mem::take(&mut raw.warnings);
    let mut samples = std::mem::take(&mut raw.samples);
    let mut lines = std::mem::take(&mut raw.lines);
    clock_order(&mut samples, &mut lines, &mut warnings);
    if samples.is_empty() {
        return Err(FlightLogError::NoSamples { file: raw.file });
    }
    height_above_ground(&mut raw, &mut samples);
    drop_glitches(&mut samples, &mut lines, &mut warnings);
    let t: Vec<f64> = samples.iter().map(|s| s.time_s).collect();
    let h: Vec<f64> = samples.iter().map(|s| s.altitude_agl_m).collect();
    fill_acceleration(&raw.acceleration_channel, &mut samples, &mut warnings);
    let Some((start, crossing)) = liftoff(&t, &h, &samples) else {
        return Err(FlightLogError::NoLiftoff {
            file: raw.file,
            threshold_m: LIFTOFF_HEIGHT_M,
            max_altitude_m: h.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        });
    };
    if crossing == 0 {
        warnings.push(format!(
            "the log starts above {LIFTOFF_HEIGHT_M} m AGL: liftoff is taken as its first sample"
        ));
    }
    let t_liftoff = t[start];
    let below: Vec<usize> = (0..crossing)
        .filter(|&i| h[i] < -NEGATIVE_REPORT_M)
        .collect();
    if let Some(&lowest) = below.iter().min_by(|&&a, &&b| h[a].total_cmp(&h[b])) {
        warnings.push(format!(
            "{} sample(s) before the climb read below -{NEGATIVE_REPORT_M} m AGL (lowest {:.1} m \
             at {:.2} s from liftoff, line {}): kept as recorded",
            below.len(),
            h[lowest],
            t[lowest] - t_liftoff,
            lines[lowest]
        ));
    }
    drop(lines);
    // Velocity: the device's where it has one, else the derivative; time from liftoff.
    let has_device_velocity = samples.iter().any(|s| !s.vertical_velocity_mps.is_nan());
    let slope = derivative(&t, &h);
    let velocity_source = if has_device_velocity {
        VelocitySource::Device
    } else {
        VelocitySource::Derivative
    };
    for (s, slope) in samples.iter_mut().zip(&slope) {
        s.time_s -= t_liftoff;
        if s.vertical_velocity_mps.is_nan() {
            s.vertical_velocity_mps = *slope;
        }
    }
    drop(slope);
    let out = samples;
    let events = flight_events(
        &raw.device_events,
        &t,
        &h,
        &out,
        start,
        t_liftoff,
        &mut warnings,
    );
    Ok(FlightLog {
        format: raw.format,
        device: raw.device,
        samples: out,
        velocity_source,
        liftoff_device_time_s: t_liftoff,
        events,
        reported: raw.reported,
        metadata: raw.metadata,
        warnings,
    })
}
