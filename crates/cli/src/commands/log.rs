//! `karman log show FILE [--format NAME] [--mapping SPEC] [--json] [--plot DIR]`: read an altimeter or
//! flight-computer log with karman-flightlog and print what it says: format and device,
//! sample count and rate, liftoff (on the device's clock), apogee above ground and its time
//! from liftoff, the highest vertical velocity, the events, and every warning of the reading
//! rules. `--json` prints one object with the keys `format`, `device`, `samples`,
//! `sample_rate_hz`, `velocity_source`, `liftoff_time_s`, `apogee_agl_m`, `apogee_time_s`,
//! `max_vertical_velocity_mps`, `events` (each `kind`, `time_s`, `source`), `reported`,
//! `metadata` and `warnings` (`karman_fit::log_json`, the shape the Python package's
//! `FlightLog.to_dict()` shares). `--plot DIR` draws the altitude, the vertical velocity and
//! (when the log has one) the acceleration against the time from liftoff into
//! `altitude.svg`, `velocity.svg` and `acceleration.svg`.

use anyhow::{Context, Result};
use clap::{Args, Subcommand};
use karman_flightlog::{EventSource, FlightLog, ReadOptions, VelocitySource};
use std::io::Write;
use std::path::PathBuf;

/// `karman log` subcommands.
#[derive(Debug, Subcommand)]
pub enum LogCommand {
    /// Read a log and print its flight: format, device, samples, liftoff, apogee, maximum
    /// vertical velocity, events and warnings.
    Show(ShowArgs),
}

/// Arguments of `karman log`.
#[derive(Debug, Args)]
pub struct LogArgs {
    #[command(subcommand)]
    pub command: LogCommand,
}

/// How a log is read: shared by `log show` and `compare`.
#[derive(Debug, Args)]
pub struct ReadArgs {
    /// The format instead of detecting it: altusmetrum, raven-fip, blueraven,
    /// perfectflite-pf2, stratologger-txt, rrc3, eggtimer, cats-vega.
    #[arg(long, value_name = "NAME")]
    pub format: Option<String>,
    /// Read as a generic CSV through a column mapping, e.g. `time=ts,altitude=alt_ft:ft`
    /// (keys time, altitude, altitude_msl, pressure, velocity, acceleration, temperature,
    /// latitude, longitude, gnss_altitude; units m, ft, s, ms, m/s, ft/s, g, m/s2, Pa, hPa,
    /// atm, C, F, K).
    #[arg(long, value_name = "SPEC")]
    pub mapping: Option<String>,
}

impl ReadArgs {
    /// The reading options these arguments name.
    pub fn options(&self) -> Result<ReadOptions> {
        Ok(ReadOptions::named(
            self.format.as_deref(),
            self.mapping.as_deref(),
        )?)
    }

    /// Reads the log at `path`.
    pub fn read(&self, path: &std::path::Path) -> Result<FlightLog> {
        let options = self.options()?;
        karman_flightlog::read_with(path, &options)
            .with_context(|| format!("cannot read the flight log {}", path.display()))
    }
}

/// Arguments of `karman log show`.
#[derive(Debug, Args)]
pub struct ShowArgs {
    /// The log file.
    #[arg(value_name = "FILE")]
    pub file: PathBuf,
    #[command(flatten)]
    pub read: ReadArgs,
    /// Print one JSON object instead of the text summary.
    #[arg(long)]
    pub json: bool,
    /// Draw altitude, vertical velocity and acceleration (SVG) into this directory.
    #[arg(long, value_name = "DIR")]
    pub plot: Option<PathBuf>,
}

/// Runs `karman log`.
pub fn run(args: &LogArgs) -> Result<()> {
    match &args.command {
        LogCommand::Show(show) => run_show(show),
    }
}

/// One channel of a log as a chart: its file, title, y label and what a sample gives (none
/// where the sample lacks the channel). `log show --plot` and `compare --out` draw these.
pub(crate) struct Channel {
    pub file: &'static str,
    pub title: &'static str,
    pub y_label: &'static str,
    pub pick: fn(&karman_flightlog::Sample) -> Option<f64>,
}

/// The charted channels: altitude, vertical velocity, acceleration (as the device writes it).
pub(crate) const CHANNELS: [Channel; 3] = [
    Channel {
        file: "altitude.svg",
        title: "Altitude",
        y_label: "altitude above the pad (m)",
        pick: |s| Some(s.altitude_agl_m),
    },
    Channel {
        file: "velocity.svg",
        title: "Vertical velocity",
        y_label: "vertical velocity (m/s)",
        pick: |s| Some(s.vertical_velocity_mps),
    },
    Channel {
        file: "acceleration.svg",
        title: "Acceleration",
        y_label: "acceleration (m/s²)",
        pick: |s| s.acceleration_mps2,
    },
];

impl Channel {
    /// The log's points `(time from liftoff, value)` of this channel.
    pub(crate) fn points(&self, log: &FlightLog) -> Vec<(f64, f64)> {
        log.samples
            .iter()
            .filter_map(|s| (self.pick)(s).map(|v| (s.time_s, v)))
            .collect()
    }
}

/// A log's legend label: its file name (the path when it has none).
pub(crate) fn file_label(path: &std::path::Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

/// The plots of `--plot`: one chart per channel the log has, time from liftoff.
fn plots(log: &FlightLog, file: &std::path::Path, dir: &std::path::Path) -> Result<()> {
    std::fs::create_dir_all(dir)
        .with_context(|| format!("cannot create the directory {}", dir.display()))?;
    let label = file_label(file);
    for channel in &CHANNELS {
        let points = channel.points(log);
        if points.is_empty() {
            continue;
        }
        crate::plot::line_chart(
            &dir.join(channel.file),
            &format!("{}: {label}", channel.title),
            "time from liftoff (s)",
            channel.y_label,
            &[crate::plot::Series {
                label: &label,
                points,
            }],
        )?;
    }
    Ok(())
}

fn run_show(args: &ShowArgs) -> Result<()> {
    let log = args.read.read(&args.file)?;
    if let Some(dir) = &args.plot {
        plots(&log, &args.file, dir)?;
    }
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(
            out,
            "{}",
            serde_json::to_string_pretty(&karman_fit::log_json(&log))?
        )?;
        return Ok(());
    }
    let apogee = log.apogee();
    let (vmax, vmax_time) = log.max_vertical_velocity();
    let first = log.samples.first().map_or(0.0, |s| s.time_s);
    let last = log.samples.last().map_or(0.0, |s| s.time_s);
    writeln!(out, "file:      {}", args.file.display())?;
    writeln!(out, "format:    {}", log.format)?;
    writeln!(out, "device:    {}", log.device)?;
    writeln!(
        out,
        "samples:   {} at {:.1} Hz (median), {first:.2} s to {last:.2} s from liftoff",
        log.samples.len(),
        log.median_rate_hz()
    )?;
    writeln!(
        out,
        "liftoff:   {:.3} s on the device's clock",
        log.liftoff_device_time_s
    )?;
    writeln!(
        out,
        "apogee:    {:.2} m AGL at {:.2} s",
        apogee.altitude_agl_m, apogee.time_s
    )?;
    if let Some(reported) = log.reported.apogee_agl_m {
        writeln!(out, "           (the device reports {reported:.2} m)")?;
    }
    let source = match log.velocity_source {
        VelocitySource::Device => "device",
        VelocitySource::Derivative => "derivative of the altitude",
    };
    writeln!(
        out,
        "max vertical velocity: {vmax:.2} m/s at {vmax_time:.2} s ({source})"
    )?;
    writeln!(out, "events:")?;
    for e in &log.events {
        let source = match e.source {
            EventSource::Device => "device",
            EventSource::Derived => "derived",
        };
        writeln!(
            out,
            "  {:<8} {:>9.2} s  ({source})",
            e.kind.name(),
            e.time_s
        )?;
    }
    if log.warnings.is_empty() {
        writeln!(out, "warnings:  none")?;
    } else {
        writeln!(out, "warnings:")?;
        for w in &log.warnings {
            writeln!(out, "  {w}")?;
        }
    }
    Ok(())
}
