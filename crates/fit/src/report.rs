//! The JSON shapes of a log, a comparison and a fit: one definition for `karman log show
//! --json`, `karman compare --json` and `karman fit --json`, and for the Python package's
//! `FlightLog.to_dict()`, `Flight.compare()` and `Mission.fit()`.

use karman_flightlog::{Comparison, EventSource, FlightLog, VelocitySource};
use serde_json::{Value, json};

use crate::fit::{Fit, Nominal};

/// A JSON number, or `null` for a value that is not finite.
fn number(value: f64) -> Value {
    if value.is_finite() {
        json!(value)
    } else {
        Value::Null
    }
}

/// A log as `karman log show --json` prints it: `format`, `device`, `samples`,
/// `sample_rate_hz`, `velocity_source`, `liftoff_time_s`, `apogee_agl_m`, `apogee_time_s`,
/// `max_vertical_velocity_mps`, `max_vertical_velocity_time_s`, `events` (each `kind`,
/// `time_s`, `source`), `reported`, `metadata` and `warnings`.
#[must_use]
pub fn log_json(log: &FlightLog) -> Value {
    let apogee = log.apogee();
    let (vmax, vmax_time) = log.max_vertical_velocity();
    let events: Vec<Value> = log
        .events
        .iter()
        .map(|e| {
            json!({
                "kind": e.kind.name(),
                "time_s": e.time_s,
                "source": match e.source {
                    EventSource::Device => "device",
                    EventSource::Derived => "derived",
                },
            })
        })
        .collect();
    json!({
        "format": log.format.name(),
        "device": log.device,
        "samples": log.samples.len(),
        "sample_rate_hz": log.median_rate_hz(),
        "velocity_source": match log.velocity_source {
            VelocitySource::Device => "device",
            VelocitySource::Derivative => "derivative",
        },
        "liftoff_time_s": log.liftoff_device_time_s,
        "apogee_agl_m": apogee.altitude_agl_m,
        "apogee_time_s": apogee.time_s,
        "max_vertical_velocity_mps": vmax,
        "max_vertical_velocity_time_s": vmax_time,
        "events": events,
        "reported": {
            "apogee_agl_m": log.reported.apogee_agl_m,
            "ground_elevation_m": log.reported.ground_elevation_m,
            "max_velocity_mps": log.reported.max_velocity_mps,
        },
        "metadata": log.metadata,
        "warnings": log.warnings,
    })
}

/// The simulation's figures of a comparison, as the `simulation` object of `karman compare
/// --json`: `liftoff_time_s`, `apogee_m`, `apogee_time_s`, `max_vertical_velocity_mps`,
/// `landing_time_s`.
#[must_use]
pub fn simulation_json(comparison: &Comparison) -> Value {
    let c = comparison;
    json!({
        "liftoff_time_s": c.simulated_liftoff_s,
        "apogee_m": c.simulated.apogee_m,
        "apogee_time_s": c.simulated.apogee_time_s,
        "max_vertical_velocity_mps": c.simulated.max_vertical_velocity_mps,
        "landing_time_s": c.simulated.landing_time_s,
    })
}

/// One log set against the simulation, as an entry of the `logs` list of `karman compare
/// --json`; `file` names the log. Keys: `file`, `format`, `device`, `apogee_m`,
/// `apogee_time_s`, `apogee_error_m`, `apogee_error_pct`, `apogee_time_error_s`,
/// `max_vertical_velocity_mps`, `max_velocity_error_pct`, `ascent_samples`,
/// `ascent_rms_altitude_m`, `ascent_rms_velocity_mps`, `landing_time_s`,
/// `landing_time_error_s`, `descent_rate_error_pct` (per parachute name), `descent` (per
/// phase: `parachute`, `band_m`, `simulated_rate_mps`, `measured_rate_mps`,
/// `measured_samples`, `error_pct`), `landing` (`measured_m`, `simulated_m`,
/// `measured_drift_m`, `simulated_drift_m`, `distance_m`, or `null`) and `warnings` (the
/// reader's). Values that are not finite are `null`.
#[must_use]
pub fn comparison_json(file: &str, log: &FlightLog, comparison: &Comparison) -> Value {
    let c = comparison;
    let descent: Vec<Value> = c
        .descent
        .iter()
        .map(|p| {
            json!({
                "parachute": p.parachute,
                "band_m": p.band_m,
                "simulated_rate_mps": p.simulated_rate_mps,
                "measured_rate_mps": p.measured_rate_mps,
                "measured_samples": p.measured_samples,
                "error_pct": p.error_pct(),
            })
        })
        .collect();
    let errors: serde_json::Map<String, Value> = c
        .descent
        .iter()
        .map(|p| (p.parachute.clone(), json!(p.error_pct())))
        .collect();
    let landing = c.landing.map_or(Value::Null, |l| {
        json!({
            "measured_m": l.measured_m,
            "simulated_m": l.simulated_m,
            "measured_drift_m": l.measured_drift_m(),
            "simulated_drift_m": l.simulated_drift_m(),
            "distance_m": l.distance_m(),
        })
    });
    json!({
        "file": file,
        "format": log.format.name(),
        "device": log.device,
        "apogee_m": c.measured.apogee_m,
        "apogee_time_s": c.measured.apogee_time_s,
        "apogee_error_m": c.apogee_error_m(),
        "apogee_error_pct": c.apogee_error_pct(),
        "apogee_time_error_s": c.apogee_time_error_s(),
        "max_vertical_velocity_mps": c.measured.max_vertical_velocity_mps,
        "max_velocity_error_pct": number(c.max_velocity_error_pct()),
        "ascent_samples": c.ascent_samples,
        "ascent_rms_altitude_m": number(c.ascent_rms_altitude_m),
        "ascent_rms_velocity_mps": number(c.ascent_rms_velocity_mps),
        "landing_time_s": c.measured.landing_time_s,
        "landing_time_error_s": c.landing_time_error_s(),
        "descent_rate_error_pct": errors,
        "descent": descent,
        "landing": landing,
        "warnings": log.warnings,
    })
}

/// A fit as `karman fit --json` prints it; `log` names the log. Keys: `log`, `flights`,
/// `converged`, `termination`, `clock_offset_s` (`[value, std]` or `null`),
/// `correlation_inflation`, `warnings`, `inputs` (each `path`, `factor`, `factor_std`, and
/// for a number `nominal`, `value`, `value_std`) and `phases` (each `phase`, `unit`,
/// `samples`, `rms_before`, `rms_after`).
#[must_use]
pub fn fit_json(log: &str, fit: &Fit) -> Value {
    let inputs: Vec<Value> = fit
        .inputs
        .iter()
        .map(|i| {
            let mut entry = json!({
                "path": i.path,
                "factor": i.factor,
                "factor_std": i.factor_std,
            });
            if let Nominal::Number(nominal) = i.nominal {
                entry["nominal"] = json!(nominal);
                entry["value"] = json!(i.value());
                entry["value_std"] = json!(i.value_std());
            }
            entry
        })
        .collect();
    let phases: Vec<Value> = fit
        .phases
        .iter()
        .map(|p| {
            json!({
                "phase": p.phase.to_string(),
                "unit": p.phase.unit(),
                "samples": p.samples,
                "rms_before": p.rms_before,
                "rms_after": p.rms_after,
            })
        })
        .collect();
    json!({
        "log": log,
        "flights": fit.flights,
        "converged": fit.converged,
        "termination": fit.termination,
        "clock_offset_s": fit.clock_offset_s,
        "correlation_inflation": fit.correlation_inflation,
        "warnings": fit.warnings,
        "inputs": inputs,
        "phases": phases,
    })
}
