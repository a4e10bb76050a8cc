//! `karman simulate MISSION [--json] [--out DIR]`: fly a mission once.
//!
//! Warnings about the mission (physical sanity, odd data files) go to stderr. Without `--json`
//! a readable summary (RocketPy's `flight.info()`); with `--json` the summary object of the
//! mission contract with the warnings under `warnings`. `--out DIR` writes `summary.json`,
//! `trajectory.csv` (every post-processed series, units in the header), `flight.kml` (the path
//! in latitude/longitude/altitude for Google Earth) and SVG plots.

use std::fmt::Write as _;
use std::io::Write;
use std::path::Path;

use anyhow::{Context, Result, bail};
use clap::Args;
use karman_mission::build::flight::{FlightRun, early_ending, simulate_with_seed};
use karman_mission::dispersion::files::write_atomic;
use karman_mission::dynamics::Sample;

use super::MissionArgs;
use crate::plot::{Series, line_chart};

/// Arguments of `karman simulate`.
#[derive(Debug, Args)]
pub struct SimulateArgs {
    #[command(flatten)]
    pub mission: MissionArgs,
    /// Print the summary as one JSON object (the mission contract's keys).
    #[arg(long)]
    pub json: bool,
    /// Write summary.json, trajectory.csv, flight.kml and SVG plots into this directory.
    #[arg(long, value_name = "DIR")]
    pub out: Option<std::path::PathBuf>,
    /// Seed of the parachute-trigger pressure noise (recorded in summary.json).
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
}

/// Flies the mission and prints or writes the results.
pub fn run(args: &SimulateArgs) -> Result<()> {
    let mission = args.mission.load()?;
    let run = simulate_with_seed(&mission, args.seed)?;
    let summary = run.summary();
    super::print_warnings(&mission, &run.warnings);
    let mut out = std::io::stdout().lock();
    if args.json {
        let mut json = serde_json::to_value(&summary)?;
        json["warnings"] = serde_json::to_value(&run.warnings)?;
        writeln!(out, "{}", serde_json::to_string_pretty(&json)?)?;
    } else {
        writeln!(out, "{summary}")?;
        let stats = run.flight.stats;
        writeln!(
            out,
            "Integration: {} steps ({} rejected, {} Runge–Kutta–Chebyshev), {} right-hand-side \
             evaluations, {} phases",
            stats.steps,
            stats.rejected_steps,
            stats.chebyshev_steps,
            stats.evaluations,
            stats.phases
        )?;
    }
    if let Some(dir) = &args.out {
        write_outputs(
            &run,
            mission.spec.name.as_deref().unwrap_or("karman flight"),
            args.seed,
            dir,
        )?;
    }
    match early_ending(summary.termination, &run.settings) {
        None => Ok(()),
        Some((_, message)) => bail!(message),
    }
}

/// Writes the files of `--out`, each atomically ([`write_atomic`]): a file is the whole new
/// content or absent (a full disk leaves no truncated file under its name), and an I/O error
/// names the file.
fn write_outputs(run: &FlightRun, name: &str, seed: u64, dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let summary = run.summary();
    let mut json = serde_json::to_value(&summary)?;
    json["termination"] = serde_json::to_value(summary.termination)?;
    json["seed"] = seed.into();
    json["integration"] = serde_json::to_value(run.flight.stats)?;
    json["warnings"] = serde_json::to_value(&run.warnings)?;
    write_atomic(
        &dir.join("summary.json"),
        serde_json::to_string_pretty(&json)?.as_bytes(),
    )?;
    let samples = run.samples();
    write_atomic(
        &dir.join("trajectory.csv"),
        trajectory_csv(run, &samples).as_bytes(),
    )?;
    write_atomic(&dir.join("flight.kml"), kml(run, name, &samples).as_bytes())?;
    plots(run, &samples, dir)
}

/// Column names (with units) and extractors of trajectory.csv.
type Column = (&'static str, fn(&FlightRun, &Sample) -> f64);

const COLUMNS: &[Column] = &[
    ("time_s", |_, s| s.t),
    ("x_m", |_, s| s.x),
    ("y_m", |_, s| s.y),
    ("z_asl_m", |_, s| s.z),
    ("altitude_agl_m", |_, s| s.altitude_agl),
    ("latitude_deg", |r, s| r.environment.geodetic(s.x, s.y).0),
    ("longitude_deg", |r, s| r.environment.geodetic(s.x, s.y).1),
    ("vx_mps", |_, s| s.vx),
    ("vy_mps", |_, s| s.vy),
    ("vz_mps", |_, s| s.vz),
    ("ax_mps2", |_, s| s.ax),
    ("ay_mps2", |_, s| s.ay),
    ("az_mps2", |_, s| s.az),
    ("e0", |_, s| s.e[0]),
    ("e1", |_, s| s.e[1]),
    ("e2", |_, s| s.e[2]),
    ("e3", |_, s| s.e[3]),
    ("omega1_radps", |_, s| s.omega[0]),
    ("omega2_radps", |_, s| s.omega[1]),
    ("omega3_radps", |_, s| s.omega[2]),
    ("alpha1_radps2", |_, s| s.omega_dot[0]),
    ("alpha2_radps2", |_, s| s.omega_dot[1]),
    ("alpha3_radps2", |_, s| s.omega_dot[2]),
    ("speed_mps", |_, s| s.speed),
    ("free_stream_speed_mps", |_, s| s.free_stream_speed),
    ("mach", |_, s| s.mach),
    ("dynamic_pressure_pa", |_, s| s.dynamic_pressure),
    ("angle_of_attack_deg", |_, s| s.angle_of_attack_deg),
    ("path_angle_deg", |_, s| s.path_angle_deg),
    ("attitude_angle_deg", |_, s| s.attitude_angle_deg),
    ("precession_deg", |_, s| s.euler_deg[0]),
    ("nutation_deg", |_, s| s.euler_deg[1]),
    ("spin_deg", |_, s| s.euler_deg[2]),
    ("static_margin_cal", |r, s| r.rocket.static_margin(s.t)),
    ("stability_margin_cal", |_, s| s.stability_margin),
    ("aero_force_r1_n", |_, s| s.force[0]),
    ("aero_force_r2_n", |_, s| s.force[1]),
    ("aero_force_r3_n", |_, s| s.force[2]),
    ("aero_moment_m1_nm", |_, s| s.moment[0]),
    ("aero_moment_m2_nm", |_, s| s.moment[1]),
    ("aero_moment_m3_nm", |_, s| s.moment[2]),
    ("net_thrust_n", |_, s| s.net_thrust),
    ("mass_kg", |_, s| s.mass),
];

fn trajectory_csv(run: &FlightRun, samples: &[Sample]) -> String {
    let mut csv = COLUMNS.iter().map(|c| c.0).collect::<Vec<_>>().join(",");
    csv.push('\n');
    for s in samples {
        let row: Vec<String> = COLUMNS
            .iter()
            .map(|c| format!("{}", (c.1)(run, s)))
            .collect();
        csv.push_str(&row.join(","));
        csv.push('\n');
    }
    csv
}

/// Escapes text for XML.
fn xml_escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The flight path as a KML LineString with absolute altitudes.
fn kml(run: &FlightRun, name: &str, samples: &[Sample]) -> String {
    let name = xml_escape(name);
    let mut coords = String::new();
    for s in samples {
        let (lat, lon) = run.environment.geodetic(s.x, s.y);
        let _ = writeln!(coords, "          {lon:.8},{lat:.8},{:.2}", s.z);
    }
    format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<kml xmlns="http://www.opengis.net/kml/2.2">
  <Document>
    <name>{name}</name>
    <Style id="path"><LineStyle><color>ff0000ff</color><width>3</width></LineStyle></Style>
    <Placemark>
      <name>{name} trajectory</name>
      <styleUrl>#path</styleUrl>
      <LineString>
        <altitudeMode>absolute</altitudeMode>
        <coordinates>
{coords}        </coordinates>
      </LineString>
    </Placemark>
  </Document>
</kml>
"#
    )
}

fn plots(run: &FlightRun, samples: &[Sample], dir: &Path) -> Result<()> {
    let pick = |f: fn(&Sample) -> f64| samples.iter().map(|s| (s.t, f(s))).collect::<Vec<_>>();
    line_chart(
        &dir.join("altitude.svg"),
        "Altitude",
        "time (s)",
        "altitude AGL (m)",
        &[Series {
            label: "altitude",
            points: pick(|s| s.altitude_agl),
        }],
    )?;
    line_chart(
        &dir.join("ground_track.svg"),
        "Ground track",
        "east of the pad (m)",
        "north of the pad (m)",
        &[Series {
            label: "track",
            points: samples.iter().map(|s| (s.x, s.y)).collect(),
        }],
    )?;
    line_chart(
        &dir.join("speed_mach.svg"),
        "Speed and Mach",
        "time (s)",
        "speed (m/s), Mach × 100",
        &[
            Series {
                label: "speed (m/s)",
                points: pick(|s| s.speed),
            },
            Series {
                label: "Mach × 100",
                points: pick(|s| 100.0 * s.mach),
            },
        ],
    )?;
    // Attitude and angle of attack are meaningful while the rocket flies on its own.
    let powered_end = run.summary().apogee_time_s.unwrap_or(f64::INFINITY);
    let ascent: Vec<&Sample> = samples.iter().filter(|s| s.t <= powered_end).collect();
    let pick_ascent =
        |f: fn(&Sample) -> f64| ascent.iter().map(|s| (s.t, f(s))).collect::<Vec<_>>();
    line_chart(
        &dir.join("attitude.svg"),
        "Attitude and angle of attack (ascent)",
        "time (s)",
        "angle (deg)",
        &[
            Series {
                label: "attitude angle",
                points: pick_ascent(|s| s.attitude_angle_deg),
            },
            Series {
                label: "path angle",
                points: pick_ascent(|s| s.path_angle_deg),
            },
            Series {
                label: "angle of attack",
                points: pick_ascent(|s| s.angle_of_attack_deg),
            },
        ],
    )?;
    let margins = ascent
        .iter()
        .map(|s| (s.t, run.rocket.static_margin(s.t)))
        .collect();
    line_chart(
        &dir.join("stability.svg"),
        "Static and stability margin (ascent)",
        "time (s)",
        "margin (calibres)",
        &[
            Series {
                label: "static margin",
                points: margins,
            },
            Series {
                label: "stability margin",
                points: pick_ascent(|s| s.stability_margin),
            },
        ],
    )?;
    Ok(())
}
