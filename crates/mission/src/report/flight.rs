//! Flight reports: the summary of the mission contract (keys exactly those of
//! `reference.json`'s `summary`) and its comparison with a reference summary.

use std::fmt;

use serde::Serialize;

pub use karman_dynamics::{EventRecord, Summary as FlightSummary};

use crate::assemble::flight::FlightRun;

/// The summary of a flown mission (serializes to the contract's keys; `Display` prints an
/// aligned table).
#[must_use]
pub fn flight_summary(run: &FlightRun) -> FlightSummary {
    run.summary()
}

/// One scalar of the summary next to its reference value.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ComparedValue {
    /// Summary key.
    pub key: &'static str,
    /// karman's value (`None`: did not occur).
    pub ours: Option<f64>,
    /// The reference value (`None`: null or absent).
    pub reference: Option<f64>,
    /// `ours − reference` when both exist.
    pub difference: Option<f64>,
    /// `|ours − reference| / |reference|` when both exist and the reference is not 0.
    pub relative_error: Option<f64>,
}

/// A summary compared key by key with a reference summary (e.g. a `reference.json`
/// `summary`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SummaryComparison {
    /// The compared scalars in contract order.
    pub values: Vec<ComparedValue>,
}

impl SummaryComparison {
    /// Compares `ours` with a reference given as a lookup from contract key to value
    /// (`None` for null or absent).
    #[must_use]
    pub fn new(ours: &FlightSummary, reference: impl Fn(&str) -> Option<f64>) -> Self {
        let scalars: [(&'static str, Option<f64>); 18] = [
            ("apogee_agl_m", ours.apogee_agl_m),
            ("apogee_asl_m", ours.apogee_asl_m),
            ("apogee_time_s", ours.apogee_time_s),
            ("apogee_x_m", ours.apogee_x_m),
            ("apogee_y_m", ours.apogee_y_m),
            ("out_of_rail_time_s", ours.out_of_rail_time_s),
            ("out_of_rail_velocity_mps", ours.out_of_rail_velocity_mps),
            (
                "out_of_rail_stability_margin",
                ours.out_of_rail_stability_margin,
            ),
            ("initial_static_margin", Some(ours.initial_static_margin)),
            ("burnout_static_margin", Some(ours.burnout_static_margin)),
            ("max_speed_mps", Some(ours.max_speed_mps)),
            ("max_mach", Some(ours.max_mach)),
            (
                "max_dynamic_pressure_pa",
                Some(ours.max_dynamic_pressure_pa),
            ),
            ("max_acceleration_mps2", Some(ours.max_acceleration_mps2)),
            ("impact_time_s", ours.impact_time_s),
            ("impact_x_m", ours.impact_x_m),
            ("impact_y_m", ours.impact_y_m),
            ("impact_velocity_mps", ours.impact_velocity_mps),
        ];
        let values = scalars
            .into_iter()
            .map(|(key, ours)| {
                let reference = reference(key);
                let difference = ours.zip(reference).map(|(a, b)| a - b);
                let relative_error = difference
                    .zip(reference)
                    .filter(|(_, b)| b.abs() > 0.0)
                    .map(|(d, b)| (d / b).abs());
                ComparedValue {
                    key,
                    ours,
                    reference,
                    difference,
                    relative_error,
                }
            })
            .collect();
        Self { values }
    }

    /// The comparison of one key.
    #[must_use]
    pub fn get(&self, key: &str) -> Option<&ComparedValue> {
        self.values.iter().find(|v| v.key == key)
    }
}

impl fmt::Display for SummaryComparison {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "{:<30}{:>14}{:>14}{:>12}{:>11}",
            "quantity", "karman", "reference", "diff", "rel %"
        )?;
        let cell =
            |v: Option<f64>, p: usize| v.map_or_else(|| "—".to_owned(), |x| format!("{x:.p$}"));
        for v in &self.values {
            writeln!(
                f,
                "{:<30}{:>14}{:>14}{:>12}{:>11}",
                v.key,
                cell(v.ours, 4),
                cell(v.reference, 4),
                cell(v.difference, 4),
                cell(v.relative_error.map(|r| 100.0 * r), 4),
            )?;
        }
        Ok(())
    }
}
