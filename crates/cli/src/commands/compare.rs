//! `karman compare MISSION LOG... [--json] [--out DIR]`: fly the mission once and set each
//! flight log against it on one time axis from liftoff (karman-flightlog's
//! `karman_flightlog::compare`, whose documentation states the rules).
//!
//! Per log: the apogee of both and the error (simulated − measured, m and %), the apogee
//! time error, the error of the highest vertical velocity, the RMS altitude and velocity
//! differences over the ascent, the descent rate under each of the simulation's parachutes,
//! the landing time and, when the log has GNSS fixes, both landing points and their distance.
//! Several logs of one flight (two boards) go in one report, each against the same
//! simulation. A multi-stage mission is compared through its top stage (the body that
//! carries the avionics to apogee).
//!
//! `--json` prints one object: `mission`, `simulation` (`liftoff_time_s`, `apogee_m`,
//! `apogee_time_s`, `max_vertical_velocity_mps`, `landing_time_s`) and `logs`, each with
//! `file`, `format`, `device`, `apogee_m`, `apogee_error_m`, `apogee_error_pct`,
//! `apogee_time_error_s`, `max_vertical_velocity_mps`, `max_velocity_error_pct`,
//! `ascent_samples`, `ascent_rms_altitude_m`, `ascent_rms_velocity_mps`,
//! `landing_time_error_s`, `descent_rate_error_pct` (per parachute name), `descent` (per
//! phase: `parachute`, `band_m`, `simulated_rate_mps`, `measured_rate_mps`,
//! `measured_samples`, `error_pct`), `landing` (`measured_m`, `simulated_m`, `distance_m`)
//! and `warnings` (the reader's): karman-fit's `simulation_json` and `comparison_json`,
//! shared with the Python package's `Flight.compare()`. `--out DIR` writes that object as `comparison.json` and the
//! overlay plots `altitude.svg`, `velocity.svg` and `acceleration.svg` (the simulation and
//! every log, time from liftoff; the acceleration of a log as its device writes it, the
//! simulation's vertical acceleration).

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::Args;
use karman_fit::{comparison_json, simulated_flight, simulation_json};
use karman_flightlog::{Comparison, FlightLog, SimulatedFlight, compare};
use karman_mission::assemble::flight::simulate_with_seed;
use karman_mission::assemble::stages::simulate_staged;
use karman_mission::dispersion::files::write_atomic;
use serde_json::{Value, json};

use super::MissionArgs;
use super::log::{CHANNELS, ReadArgs, file_label};
use crate::plot::{Series, line_chart};

/// Arguments of `karman compare`.
#[derive(Debug, Args)]
pub struct CompareArgs {
    #[command(flatten)]
    pub mission: MissionArgs,
    /// The flight logs (one or several boards of the same flight).
    #[arg(value_name = "LOG", required = true)]
    pub logs: Vec<PathBuf>,
    #[command(flatten)]
    pub read: ReadArgs,
    /// Seed of the parachute-trigger pressure noise of the simulated flight.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Print one JSON object instead of the text report.
    #[arg(long)]
    pub json: bool,
    /// Write comparison.json and the overlay plots into this directory.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
}

/// Flies the mission (its top stage for a multi-stage one).
fn fly(args: &CompareArgs) -> Result<(String, SimulatedFlight)> {
    let mission = args.mission.load()?;
    let name = mission
        .spec
        .name
        .clone()
        .unwrap_or_else(|| args.mission.mission.display().to_string());
    let (samples, summary, warnings) = if mission.spec.stages.is_empty() {
        let run = simulate_with_seed(&mission, args.seed)?;
        (run.samples(), run.summary(), run.warnings)
    } else {
        let run = simulate_staged(&mission, args.seed)?;
        (run.samples(0), run.summary(0), run.warnings)
    };
    super::print_warnings(&mission, &warnings);
    Ok((name, simulated_flight(&samples, &summary)))
}

/// Runs `karman compare`.
pub fn run(args: &CompareArgs) -> Result<()> {
    // Read every log first: a bad log fails before the (longer) flight.
    let logs = args
        .logs
        .iter()
        .map(|path| args.read.read(path))
        .collect::<Result<Vec<FlightLog>>>()?;
    let (name, simulated) = fly(args)?;
    let mut comparisons = Vec::new();
    for (path, log) in args.logs.iter().zip(&logs) {
        let comparison = compare(&simulated, log)
            .with_context(|| format!("cannot compare {} with the mission", path.display()))?;
        comparisons.push(comparison);
    }
    let report = report_json(&name, &args.logs, &logs, &comparisons);
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(out, "{}", serde_json::to_string_pretty(&report)?)?;
    } else {
        write!(
            out,
            "{}",
            report_text(&name, &args.logs, &logs, &comparisons)
        )?;
    }
    if let Some(dir) = &args.out {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("cannot create the directory {}", dir.display()))?;
        let mut text = serde_json::to_string_pretty(&report)?;
        text.push('\n');
        write_atomic(&dir.join("comparison.json"), text.as_bytes())?;
        plots(dir, &simulated, &args.logs, &logs, &comparisons)?;
    }
    Ok(())
}

/// The `--json` object: the mission's name, the simulation's figures and one entry per log
/// (karman-fit's shapes, which the Python package's `Flight.compare()` shares).
fn report_json(name: &str, paths: &[PathBuf], logs: &[FlightLog], cmp: &[Comparison]) -> Value {
    let simulation = cmp.first().map_or(Value::Null, simulation_json);
    let entries: Vec<Value> = paths
        .iter()
        .zip(logs)
        .zip(cmp)
        .map(|((path, log), c)| comparison_json(&path.display().to_string(), log, c))
        .collect();
    json!({ "mission": name, "simulation": simulation, "logs": entries })
}

fn report_text(name: &str, paths: &[PathBuf], logs: &[FlightLog], cmp: &[Comparison]) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    let Some(first) = cmp.first() else {
        return s;
    };
    let sim = first.simulated;
    let _ = writeln!(s, "mission:    {name}");
    let _ = writeln!(
        s,
        "simulation: apogee {:.1} m at {:.2} s, max vertical velocity {:.1} m/s (liftoff at {:.3} s of its clock)",
        sim.apogee_m, sim.apogee_time_s, sim.max_vertical_velocity_mps, first.simulated_liftoff_s
    );
    for ((path, log), c) in paths.iter().zip(logs).zip(cmp) {
        let _ = writeln!(
            s,
            "\nlog:        {} ({}, {})",
            path.display(),
            log.format,
            log.device
        );
        let _ = writeln!(
            s,
            "  apogee            {:9.1} m    simulated {:9.1} m    error {:+8.1} m ({:+.2} %)",
            c.measured.apogee_m,
            sim.apogee_m,
            c.apogee_error_m(),
            c.apogee_error_pct()
        );
        let _ = writeln!(
            s,
            "  apogee time       {:9.2} s    simulated {:9.2} s    error {:+8.2} s",
            c.measured.apogee_time_s,
            sim.apogee_time_s,
            c.apogee_time_error_s()
        );
        let _ = writeln!(
            s,
            "  max vert. speed   {:9.1} m/s  simulated {:9.1} m/s  error {:+.2} %",
            c.measured.max_vertical_velocity_mps,
            sim.max_vertical_velocity_mps,
            c.max_velocity_error_pct()
        );
        let _ = writeln!(
            s,
            "  ascent RMS        altitude {:.1} m, vertical velocity {:.1} m/s over {} samples",
            c.ascent_rms_altitude_m, c.ascent_rms_velocity_mps, c.ascent_samples
        );
        for p in &c.descent {
            match p.measured_rate_mps {
                Some(m) => {
                    let _ = writeln!(
                        s,
                        "  descent {:<9} {:9.2} m/s  simulated {:9.2} m/s  error {:+.1} % ({:.0}–{:.0} m, {} samples)",
                        p.parachute,
                        m,
                        p.simulated_rate_mps,
                        p.error_pct().unwrap_or(f64::NAN),
                        p.band_m[0],
                        p.band_m[1],
                        p.measured_samples
                    );
                }
                None => {
                    let _ = writeln!(
                        s,
                        "  descent {:<9} not measured (the log has {} samples in {:.0}–{:.0} m); simulated {:.2} m/s",
                        p.parachute,
                        p.measured_samples,
                        p.band_m[0],
                        p.band_m[1],
                        p.simulated_rate_mps
                    );
                }
            }
        }
        if let Some(e) = c.landing_time_error_s() {
            let _ = writeln!(
                s,
                "  landing time      {:9.1} s    simulated {:9.1} s    error {e:+8.1} s",
                c.measured.landing_time_s.unwrap_or(f64::NAN),
                sim.landing_time_s.unwrap_or(f64::NAN)
            );
        }
        if let Some(l) = c.landing {
            let _ = writeln!(
                s,
                "  landing point     {:.0} m E {:.0} m N (drift {:.0} m); simulated {:.0} m E {:.0} m N (drift {:.0} m); {:.0} m apart",
                l.measured_m[0],
                l.measured_m[1],
                l.measured_drift_m(),
                l.simulated_m[0],
                l.simulated_m[1],
                l.simulated_drift_m(),
                l.distance_m()
            );
        }
        if !log.warnings.is_empty() {
            let _ = writeln!(s, "  reader warnings: {}", log.warnings.len());
        }
    }
    s
}

/// The overlay plots: the simulation (from liftoff, altitude from the pad) and every log, one
/// chart per charted channel ([`super::log::CHANNELS`]).
fn plots(
    dir: &Path,
    simulated: &SimulatedFlight,
    paths: &[PathBuf],
    logs: &[FlightLog],
    cmp: &[Comparison],
) -> Result<()> {
    let Some(first) = cmp.first() else {
        return Ok(());
    };
    let (t0, h0) = (first.simulated_liftoff_s, first.simulated_pad_altitude_m);
    let labels: Vec<String> = paths.iter().map(|p| file_label(p)).collect();
    let simulation = |values: &[f64], shift: f64| -> Vec<(f64, f64)> {
        simulated
            .time_s
            .iter()
            .zip(values)
            .map(|(t, v)| (t - t0, v - shift))
            .collect()
    };
    let simulated_series = [
        simulation(&simulated.altitude_m, h0),
        simulation(&simulated.vertical_velocity_mps, 0.0),
        simulation(&simulated.vertical_acceleration_mps2, 0.0),
    ];
    for (channel, sim_points) in CHANNELS.iter().zip(simulated_series) {
        let mut series = vec![Series {
            label: "simulation",
            points: sim_points,
        }];
        for (label, log) in labels.iter().zip(logs) {
            let points = channel.points(log);
            if !points.is_empty() {
                series.push(Series { label, points });
            }
        }
        line_chart(
            &dir.join(channel.file),
            channel.title,
            "time from liftoff (s)",
            channel.y_label,
            &series,
        )?;
    }
    Ok(())
}
