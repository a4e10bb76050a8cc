//! `karman simulate MISSION [--json] [--out DIR]`: fly a mission once.
//!
//! Warnings about the mission (physical sanity, odd data files) go to stderr. Without `--json`
//! a readable summary (RocketPy's `flight.info()`, figures rounded to what is meaningful;
//! `--verbose` adds the integrator's work); with `--json` the summary object of the
//! mission contract with the warnings under `warnings` (and, with air brakes, the controller's
//! record under `controller`, and with `[[rocket.sensors]]` their readings under `sensors`).
//! `--out DIR` writes `summary.json`, `trajectory.csv` (every
//! post-processed series, units in the header), `sensor_<name>.csv` (each sensor's readings,
//! time and components with units in the header), `controller.json` (with air brakes: the level
//! after each controller call and the observed variables), `flight.kml` (the path in
//! latitude/longitude/altitude for Google Earth) and SVG plots, the whole set at once: written
//! into a temporary folder beside DIR and moved in once every file is written, so a failed
//! rerun leaves the previous set as it was.
//!
//! A multi-stage mission (`[[stages]]`) prints one summary per body (the top stage first,
//! then the lower stages in the order they separated) and the stack's events in one
//! timeline; `--json` gives `bodies` (each `name` and `summary`), `separations`, `timeline`
//! and `warnings`; `--out DIR` writes `summary.json` (that object), one folder per body with
//! its `trajectory.csv` and `flight.kml`, and the altitude and ground-track plots of every
//! body together.

use std::io::Write;
use std::path::Path;

use anyhow::{Context, Result, bail};
use clap::Args;
use karman_mission::assemble::flight::{FlightRun, early_ending, simulate_with_seed};
use karman_mission::assemble::stages::{StagedRun, simulate_staged};
use karman_mission::dispersion::files::{temporary_path, write_atomic};
use karman_mission::dynamics::Sample;
use karman_mission::report::trajectory;

use super::MissionArgs;
use crate::plot::{Series, line_chart, map_chart};

/// Arguments of `karman simulate`.
#[derive(Debug, Args)]
pub struct SimulateArgs {
    #[command(flatten)]
    pub mission: MissionArgs,
    #[command(flatten)]
    pub fetch: super::FetchFlag,
    /// Print the summary as one JSON object (the mission contract's keys).
    #[arg(long)]
    pub json: bool,
    /// Write summary.json, trajectory.csv, flight.kml and SVG plots into this directory.
    #[arg(long, value_name = "DIR")]
    pub out: Option<std::path::PathBuf>,
    /// Seed of the parachute-trigger pressure noise (recorded in summary.json).
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Also print the integrator's work (steps, rejections, evaluations, phases).
    #[arg(long, short)]
    pub verbose: bool,
}

/// Flies the mission and prints or writes the results.
pub fn run(args: &SimulateArgs) -> Result<()> {
    args.fetch.run(&args.mission)?;
    let mission = args.mission.load()?;
    if !mission.spec.stages.is_empty() {
        return run_staged(args, &mission);
    }
    let run = simulate_with_seed(&mission, args.seed)?;
    let summary = run.summary();
    super::print_warnings(&mission, &run.warnings);
    let mut out = std::io::stdout().lock();
    if args.json {
        let mut json = serde_json::to_value(&summary)?;
        json["warnings"] = serde_json::to_value(&run.warnings)?;
        if let Some(record) = &run.controller {
            json["controller"] = record.to_json();
        }
        if !run.sensors.is_empty() {
            json["sensors"] = sensors_json(&run);
        }
        writeln!(out, "{}", serde_json::to_string_pretty(&json)?)?;
    } else {
        writeln!(out, "{summary}")?;
        let stats = run.flight.stats;
        if args.verbose {
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
    }
    if let Some(dir) = &args.out {
        let name = mission.spec.name.as_deref().unwrap_or("karman flight");
        write_whole(dir, |staging| write_outputs(&run, name, args.seed, staging))?;
    }
    match early_ending(summary.termination, &run.settings) {
        None => Ok(()),
        Some((_, message)) => bail!(message),
    }
}

/// The `sensors` object of `--json`: each sensor by name, its kind and one array per column
/// (docs/mission-format.md, `[[rocket.sensors]]`).
fn sensors_json(run: &FlightRun) -> serde_json::Value {
    let mut object = serde_json::Map::new();
    for readings in &run.sensors {
        object.insert(readings.name.clone(), readings.to_json());
    }
    serde_json::Value::Object(object)
}

/// The JSON object of a multi-stage flight (`--json`, `summary.json`).
fn staged_json(run: &StagedRun) -> Result<serde_json::Value> {
    let mut bodies = Vec::new();
    for (i, body) in run.bodies.iter().enumerate() {
        let summary = run.summary(i);
        let mut json = serde_json::to_value(&summary)?;
        json["termination"] = serde_json::to_value(summary.termination)?;
        bodies.push(serde_json::json!({ "name": body.name, "summary": json }));
    }
    let timeline: Vec<serde_json::Value> = run
        .timeline()
        .into_iter()
        .map(|(t, name)| serde_json::json!({ "name": name, "time_s": t }))
        .collect();
    Ok(serde_json::json!({
        "bodies": bodies,
        "separations": run.separations,
        "timeline": timeline,
        "warnings": run.warnings,
    }))
}

/// `karman simulate` of a multi-stage mission (module documentation).
fn run_staged(args: &SimulateArgs, mission: &karman_mission::Mission) -> Result<()> {
    let run = simulate_staged(mission, args.seed)?;
    super::print_warnings(mission, &run.warnings);
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(
            out,
            "{}",
            serde_json::to_string_pretty(&staged_json(&run)?)?
        )?;
    } else {
        writeln!(out, "{}", staged_text(&run))?;
    }
    if let Some(dir) = &args.out {
        let name = mission.spec.name.as_deref().unwrap_or("karman flight");
        write_whole(dir, |staging| write_staged(&run, name, args.seed, staging))?;
    }
    for (i, body) in run.bodies.iter().enumerate() {
        if let Some((_, message)) = early_ending(run.summary(i).termination, &run.settings) {
            bail!("{}: {message}", body.name);
        }
    }
    Ok(())
}

/// The readable report of a multi-stage flight: each body's summary, then the timeline.
#[must_use]
pub fn staged_text(run: &StagedRun) -> String {
    use std::fmt::Write as _;
    let mut text = String::new();
    for (i, body) in run.bodies.iter().enumerate() {
        let _ = writeln!(text, "Body {}: {}", i + 1, body.name);
        let _ = writeln!(text, "{}", run.summary(i));
    }
    let _ = writeln!(text, "Timeline");
    for (t, event) in run.timeline() {
        let _ = writeln!(text, "  {t:>10.4} s  {event}");
    }
    text
}

/// Writes the output set of `--out DIR` whole: `write` fills a temporary folder beside `dir`
/// (`.DIR.PID.N.tmp`), and only once every file is written is the set moved into `dir` (the
/// folder renamed to `dir` when there is none; else each file renamed over the previous one,
/// after checking that every one can be). A run that fails while writing leaves `dir` as it
/// was: never a new `summary.json` beside the previous run's `trajectory.csv`. Files of `dir`
/// that this run does not write are left as they are.
pub(super) fn write_whole(dir: &Path, write: impl FnOnce(&Path) -> Result<()>) -> Result<()> {
    let parent = dir
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    std::fs::create_dir_all(parent)
        .with_context(|| format!("cannot create {}", parent.display()))?;
    let staging = temporary_path(dir);
    // An error names the file under `dir`, where it goes, not the temporary folder.
    let result = write(&staging)
        .map_err(|e| {
            let text = format!("{e:#}");
            anyhow::anyhow!(
                text.replace(&staging.display().to_string(), &dir.display().to_string())
            )
        })
        .and_then(|()| move_in(&staging, dir));
    if staging.exists() {
        let _ = std::fs::remove_dir_all(&staging);
    }
    result
}

/// Moves the written set `staging` into `dir` ([`write_whole`]).
fn move_in(staging: &Path, dir: &Path) -> Result<()> {
    let unchanged = "the previous outputs are left as they were";
    if !dir.exists() {
        match std::fs::rename(staging, dir) {
            Ok(()) => return Ok(()),
            // Another run made it meanwhile: move the files in one by one, as below.
            Err(_) if dir.is_dir() => {}
            Err(e) => {
                return Err(e)
                    .with_context(|| format!("cannot move the outputs into {}", dir.display()));
            }
        }
    }
    if !dir.is_dir() {
        bail!("{} is not a directory; {unchanged}", dir.display());
    }
    let mut names = Vec::new();
    for entry in
        std::fs::read_dir(staging).with_context(|| format!("cannot read {}", staging.display()))?
    {
        names.push(entry?.file_name());
    }
    names.sort();
    // Every target checked before anything is moved.
    for name in &names {
        let target = dir.join(name);
        if let Ok(existing) = std::fs::symlink_metadata(&target) {
            let folder = staging.join(name).is_dir();
            if existing.is_dir() != folder {
                bail!(
                    "cannot replace {}: it is a {} where the outputs have a {}; {unchanged}",
                    target.display(),
                    if existing.is_dir() { "folder" } else { "file" },
                    if folder { "folder" } else { "file" },
                );
            }
        }
    }
    for name in &names {
        let (source, target) = (staging.join(name), dir.join(name));
        if source.is_dir() && target.exists() {
            // A body's folder: the previous one set aside (into the staging folder, removed
            // with it), then the new one moved in.
            let aside = staging.join(format!(".previous.{}", name.to_string_lossy()));
            std::fs::rename(&target, &aside)
                .with_context(|| format!("cannot replace {}", target.display()))?;
        }
        std::fs::rename(&source, &target)
            .with_context(|| format!("cannot move the outputs into {}", target.display()))?;
    }
    Ok(())
}

/// `--out` of a multi-stage flight (module documentation).
fn write_staged(run: &StagedRun, name: &str, seed: u64, dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let mut json = staged_json(run)?;
    json["seed"] = seed.into();
    write_atomic(
        &dir.join("summary.json"),
        serde_json::to_string_pretty(&json)?.as_bytes(),
    )?;
    let mut altitude = Vec::new();
    let mut track = Vec::new();
    for (i, body) in run.bodies.iter().enumerate() {
        let folder = dir.join(body.name.replace(['/', '\\'], "_"));
        std::fs::create_dir_all(&folder)
            .with_context(|| format!("cannot create {}", folder.display()))?;
        let samples = run.samples(i);
        let view = run.track(i);
        write_atomic(
            &folder.join("trajectory.csv"),
            trajectory::csv(&view, &samples).as_bytes(),
        )?;
        write_atomic(
            &folder.join("flight.kml"),
            trajectory::kml(&view, &format!("{name}: {}", body.name), &samples).as_bytes(),
        )?;
        altitude.push(Series {
            label: body.name.as_str(),
            points: samples.iter().map(|s| (s.t, s.altitude_agl)).collect(),
        });
        track.push(Series {
            label: body.name.as_str(),
            points: samples.iter().map(|s| (s.x, s.y)).collect(),
        });
    }
    line_chart(
        &dir.join("altitude.svg"),
        "Altitude",
        "time (s)",
        "altitude AGL (m)",
        &altitude,
    )?;
    map_chart(
        &dir.join("ground_track.svg"),
        "Ground track",
        "east of the pad (m)",
        "north of the pad (m)",
        &track,
    )
}

/// Writes the files of `--out`, each atomically ([`write_atomic`]): a file is the whole new
/// content or absent (a full disk leaves no truncated file under its name), and an I/O error
/// names the file.
pub(super) fn write_outputs(run: &FlightRun, name: &str, seed: u64, dir: &Path) -> Result<()> {
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
    if let Some(record) = &run.controller {
        std::fs::write(
            dir.join("controller.json"),
            serde_json::to_string_pretty(&record.to_json())?,
        )?;
    }
    let samples = run.samples();
    write_atomic(
        &dir.join("trajectory.csv"),
        trajectory::csv(run, &samples).as_bytes(),
    )?;
    for readings in &run.sensors {
        write_atomic(
            &dir.join(format!("sensor_{}.csv", readings.name)),
            readings.csv().as_bytes(),
        )?;
    }
    write_atomic(
        &dir.join("flight.kml"),
        trajectory::kml(run, name, &samples).as_bytes(),
    )?;
    plots(run, &samples, dir)
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
    map_chart(
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

#[cfg(test)]
mod tests {
    use super::write_whole;
    use std::path::Path;

    fn read(dir: &Path, name: &str) -> String {
        std::fs::read_to_string(dir.join(name)).expect("a file")
    }

    fn entries(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .expect("a folder")
            .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn an_output_set_is_moved_in_whole_or_not_at_all() {
        let tmp = tempfile::tempdir().expect("temporary directory");
        let dir = tmp.path().join("out");
        let set = |summary: &'static str, fail: bool| {
            move |staging: &Path| -> anyhow::Result<()> {
                std::fs::create_dir_all(staging.join("booster"))?;
                std::fs::write(staging.join("summary.json"), summary)?;
                if fail {
                    anyhow::bail!("cannot write {}", staging.join("trajectory.csv").display());
                }
                std::fs::write(staging.join("trajectory.csv"), summary)?;
                std::fs::write(staging.join("booster/trajectory.csv"), summary)?;
                Ok(())
            }
        };
        write_whole(&dir, set("first", false)).expect("a first set");
        assert_eq!(read(&dir, "summary.json"), "first");
        // A rerun that fails partway: the previous set is left, the error names the file
        // under `dir`, and no temporary folder is left.
        let error = write_whole(&dir, set("second", true)).expect_err("fails partway");
        assert!(
            error
                .to_string()
                .contains(&dir.join("trajectory.csv").display().to_string()),
            "{error}"
        );
        assert_eq!(read(&dir, "summary.json"), "first");
        assert_eq!(read(&dir, "trajectory.csv"), "first");
        assert_eq!(entries(tmp.path()), ["out"]);
        // A rerun that succeeds replaces every file, the body's folder included.
        std::fs::write(dir.join("notes.txt"), "mine").expect("a file of the user's");
        write_whole(&dir, set("third", false)).expect("a third set");
        assert_eq!(read(&dir, "summary.json"), "third");
        assert_eq!(read(&dir, "booster/trajectory.csv"), "third");
        assert_eq!(read(&dir, "notes.txt"), "mine");
        assert_eq!(entries(tmp.path()), ["out"]);
        // A folder where a file goes: refused before anything is moved.
        std::fs::remove_file(dir.join("trajectory.csv")).expect("remove");
        std::fs::create_dir(dir.join("trajectory.csv")).expect("a folder in its place");
        let error = write_whole(&dir, set("fourth", false)).expect_err("a folder in the way");
        assert!(error.to_string().contains("left as they were"), "{error}");
        assert_eq!(read(&dir, "summary.json"), "third");
        assert_eq!(entries(tmp.path()), ["out"]);
    }
}
