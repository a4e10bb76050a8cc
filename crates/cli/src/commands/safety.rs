//! `karman safety MISSION [--shear-modulus PA --fin-thickness M] [--json] [thresholds]`: the
//! range-safety figures of the nominal flight, each with pass / warn / fail against a
//! threshold (`karman_mission::safety`, whose documentation states the formulas and the
//! default rules). Exit code 1 when a figure fails.

use super::MissionArgs;
use anyhow::{Result, bail};
use clap::Args;
use karman_mission::safety::{FinMaterial, SafetyRules, Verdict, safety};
use std::io::Write;

/// Arguments of `karman safety`.
#[derive(Debug, Args)]
pub struct SafetyArgs {
    #[command(flatten)]
    pub mission: MissionArgs,
    /// The fins' shear modulus, Pa (e.g. 2.6e10 for aluminium 6061-T6), for the flutter speed.
    #[arg(long, value_name = "PA", requires = "fin_thickness")]
    pub shear_modulus: Option<f64>,
    /// The fins' thickness, m, for the flutter speed.
    #[arg(long, value_name = "M", requires = "shear_modulus")]
    pub fin_thickness: Option<f64>,
    /// Least rail-exit speed, m/s.
    #[arg(long, value_name = "MPS", default_value_t = SafetyRules::default().min_rail_exit_speed_mps)]
    pub min_rail_speed: f64,
    /// Least stability margin at rail exit and over the powered flight, calibres.
    #[arg(long, value_name = "CAL", default_value_t = SafetyRules::default().min_stability_margin_cal)]
    pub min_margin: f64,
    /// Least thrust-to-weight ratio at rail exit.
    #[arg(long, value_name = "RATIO", default_value_t = SafetyRules::default().min_thrust_to_weight)]
    pub min_thrust_to_weight: f64,
    /// Least flutter margin (flutter speed over airspeed).
    #[arg(long, value_name = "RATIO", default_value_t = SafetyRules::default().min_flutter_margin)]
    pub min_flutter_margin: f64,
    /// Largest landing kinetic energy, J.
    #[arg(long, value_name = "J", default_value_t = SafetyRules::default().max_landing_energy_j)]
    pub max_landing_energy: f64,
    /// Largest descent rate at impact, m/s.
    #[arg(long, value_name = "MPS", default_value_t = SafetyRules::default().max_descent_rate_mps)]
    pub max_descent_rate: f64,
    /// Largest drift from the pad, m.
    #[arg(long, value_name = "M", default_value_t = SafetyRules::default().max_drift_m)]
    pub max_drift: f64,
    /// Seed of the parachute-trigger noise.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Print one JSON object instead of the table.
    #[arg(long)]
    pub json: bool,
}

/// Runs `karman safety`.
pub fn run(args: &SafetyArgs) -> Result<()> {
    let positive = |name: &str, value: f64| {
        if value.is_finite() && value > 0.0 {
            Ok(value)
        } else {
            bail!("--{name} must be a positive number, got {value}")
        }
    };
    let fins = match (args.shear_modulus, args.fin_thickness) {
        (Some(g), Some(t)) => Some(FinMaterial {
            shear_modulus_pa: positive("shear-modulus", g)?,
            thickness_m: positive("fin-thickness", t)?,
        }),
        _ => None,
    };
    let rules = SafetyRules {
        min_rail_exit_speed_mps: positive("min-rail-speed", args.min_rail_speed)?,
        min_stability_margin_cal: args.min_margin,
        min_thrust_to_weight: positive("min-thrust-to-weight", args.min_thrust_to_weight)?,
        min_flutter_margin: positive("min-flutter-margin", args.min_flutter_margin)?,
        max_landing_energy_j: positive("max-landing-energy", args.max_landing_energy)?,
        max_descent_rate_mps: positive("max-descent-rate", args.max_descent_rate)?,
        max_drift_m: positive("max-drift", args.max_drift)?,
    };
    if !args.min_margin.is_finite() {
        bail!("--min-margin must be a number, got {}", args.min_margin);
    }
    let mission = args.mission.load()?;
    let report = safety(&mission, &rules, fins, args.seed)?;
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(out, "{}", serde_json::to_string_pretty(&report)?)?;
    } else {
        let width = report
            .checks
            .iter()
            .map(|c| c.name.len())
            .fold(32, usize::max);
        writeln!(
            out,
            "{:<width$} {:>14} {:>14}  verdict",
            "figure", "value", "threshold"
        )?;
        for c in &report.checks {
            let value = c
                .value
                .map_or_else(|| "-".to_owned(), |v| format!("{v:.4}"));
            let threshold = match (c.kind, c.threshold) {
                (Some(kind), Some(t)) => format!("{kind} {t}"),
                _ => String::new(),
            };
            let verdict = match c.verdict {
                Verdict::Pass => "pass",
                Verdict::Warn => "WARN",
                Verdict::Fail => "FAIL",
                Verdict::None => "-",
            };
            writeln!(
                out,
                "{:<width$} {value:>14} {threshold:>14}  {verdict:<5} {}",
                c.name, c.note
            )?;
        }
    }
    let failed: Vec<&str> = report
        .checks
        .iter()
        .filter(|c| c.verdict == Verdict::Fail)
        .map(|c| c.name.as_str())
        .collect();
    if !failed.is_empty() {
        bail!(
            "the flight fails the range-safety rules: {}",
            failed.join(", ")
        );
    }
    Ok(())
}
