//! `karman sweep MISSION --vary PATH=V1,V2,... [--series NAME]... [--window T0:T1] [--out DIR]`: fly one
//! mission with one input set to each of several values (RocketPy paper's dynamic-stability
//! study: the fins moved along the body) and compare the flights.
//!
//! Prints a table of the main summary values per variant and writes into DIR `summary.csv`
//! (the variant's value and every scalar summary key) and one SVG per chosen trajectory
//! series with the variants overlaid (`altitude_agl.svg`, `attitude_angle.svg`, ...). The
//! charts span the flights (to the last variant's last point) unless `--window T0:T1` chooses
//! the time window that matters (`0:5` the rail and the boost, `:30` up to 30 s, `20:` from
//! 20 s): an attitude oscillation after the rail is invisible on a chart that runs to landing.
//!
//! A multi-stage mission flies each variant as a staged flight: the table shows the top
//! stage, `summary.csv` adds each lower stage's columns as a Monte Carlo study's
//! `samples.csv` does (`booster.separation_time_s`, `booster.impact_x_m`, ...), and every
//! body of every variant is a curve of the charts (`PATH=VALUE (booster)`).

use std::fmt::Write as _;
use std::io::Write;
use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use clap::Args;
use karman_mission::Override;
use karman_mission::assemble::flight::simulate_with_seed;
use karman_mission::assemble::stages::simulate_staged;
use karman_mission::montecarlo::{OUTPUTS, stage_outputs, staged_outputs};
use karman_mission::report::trajectory::{self, SERIES};

use super::MissionArgs;
use crate::plot::{Series, line_chart};

/// Arguments of `karman sweep`.
#[derive(Debug, Args)]
pub struct SweepArgs {
    #[command(flatten)]
    pub mission: MissionArgs,
    /// The input to vary and its values, TOML values separated by commas outside brackets
    /// and quotes: `rocket.surfaces.fins.position=-0.5,-0.7,-0.9` or
    /// `rocket.parachutes.main.noise=[0,0,0],[0,8.3,0.5]`.
    #[arg(long, value_name = "PATH=V1,V2,...")]
    pub vary: String,
    /// A trajectory series to overlay (repeatable; default `altitude_agl`), by the names of
    /// trajectory.csv without the unit (`attitude_angle`, `stability_margin`, `mach`, ...).
    #[arg(long = "series", value_name = "NAME")]
    pub series: Vec<String>,
    /// Output directory for summary.csv and the SVG charts.
    #[arg(long, value_name = "DIR", default_value = "sweep")]
    pub out: PathBuf,
    /// Seed of the parachute trigger noise of every variant.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// The charts' time window, s: `T0:T1`, `:T1` or `T0:` (default: the whole flights).
    #[arg(long, value_name = "T0:T1", value_parser = parse_window)]
    pub window: Option<Window>,
}

/// A time window of the charts, s (either end open).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Window {
    /// Start, s.
    pub start: Option<f64>,
    /// End, s.
    pub end: Option<f64>,
}

impl Window {
    /// Whether time `t` lies in the window.
    fn contains(&self, t: f64) -> bool {
        self.start.is_none_or(|s| t >= s) && self.end.is_none_or(|e| t <= e)
    }
}

/// Parses `T0:T1`, `:T1` or `T0:` (finite seconds, `T0 < T1`).
fn parse_window(text: &str) -> Result<Window, String> {
    let (start, end) = text
        .split_once(':')
        .ok_or_else(|| format!("`{text}`: a window is T0:T1, :T1 or T0: (seconds)"))?;
    let bound = |part: &str| -> Result<Option<f64>, String> {
        let part = part.trim();
        if part.is_empty() {
            return Ok(None);
        }
        match part.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(Some(v)),
            _ => Err(format!("`{text}`: `{part}` is not a time in seconds")),
        }
    };
    let window = Window {
        start: bound(start)?,
        end: bound(end)?,
    };
    match (window.start, window.end) {
        (None, None) => Err(format!("`{text}`: give at least one end of the window")),
        (Some(a), Some(b)) if a >= b => Err(format!("`{text}`: the window ends before it starts")),
        _ => Ok(window),
    }
}

/// Splits `V1,V2,...` at the commas that are not inside brackets, braces or quotes.
fn split_values(text: &str) -> Vec<String> {
    let mut values = Vec::new();
    let (mut depth, mut quote, mut current) = (0_i32, None, String::new());
    for c in text.chars() {
        match (quote, c) {
            (Some(q), _) if c == q => quote = None,
            (Some(_), _) => {}
            (None, '"' | '\'') => quote = Some(c),
            (None, '[' | '{') => depth += 1,
            (None, ']' | '}') => depth -= 1,
            (None, ',') if depth == 0 => {
                values.push(std::mem::take(&mut current).trim().to_owned());
                continue;
            }
            _ => {}
        }
        current.push(c);
    }
    values.push(current.trim().to_owned());
    values
}

/// One variant's curve of a series: its legend label and points `(t, value)`.
type Curve = (String, Vec<(f64, f64)>);

/// The summary columns printed for each variant (all of them go to summary.csv).
const SHOWN: [(&str, &str); 6] = [
    ("apogee_agl_m", "apogee AGL (m)"),
    ("apogee_time_s", "apogee time (s)"),
    ("out_of_rail_velocity_mps", "rail exit (m/s)"),
    ("initial_static_margin", "static margin 0"),
    ("out_of_rail_stability_margin", "margin rail exit"),
    ("max_mach", "max Mach"),
];

/// Flies every variant and writes the table and charts.
pub fn run(args: &SweepArgs) -> Result<()> {
    let Some((path, values)) = args.vary.split_once('=') else {
        bail!("--vary `{}`: expected PATH=V1,V2,...", args.vary);
    };
    let path = path.trim();
    let values = split_values(values);
    if values.iter().any(String::is_empty) {
        bail!("--vary `{}`: an empty value", args.vary);
    }
    let names = if args.series.is_empty() {
        vec!["altitude_agl".to_owned()]
    } else {
        args.series.clone()
    };
    let series: Vec<_> = names
        .iter()
        .map(|name| {
            trajectory::series_named(name).with_context(|| {
                let known: Vec<&str> = SERIES.iter().map(|s| s.name).collect();
                format!(
                    "--series `{name}`: no such series; the series are {}",
                    known.join(", ")
                )
            })
        })
        .collect::<Result<_>>()?;

    let missions = values
        .iter()
        .map(|value| {
            // Each variant's error names the `--vary` value it came from (the mission's
            // own message names the input as an override, `--set PATH=VALUE`).
            let vary = || format!("--vary {path}: the value `{value}`");
            let mut overrides = args.mission.overrides.clone();
            overrides.push(Override::new(path, value).with_context(vary)?);
            karman_mission::load(&args.mission.mission, &overrides).with_context(vary)
        })
        .collect::<Result<Vec<_>>>()?;
    // Every variant has the stages of the first (their columns).
    let staged = missions.first().is_some_and(|m| !m.spec.stages.is_empty());
    let mut columns: Vec<String> = OUTPUTS.iter().map(|s| (*s).to_owned()).collect();
    if let Some(first) = missions.first() {
        columns.extend(stage_outputs(&first.spec));
    }
    let mut csv = format!("{path},{}\n", columns.join(","));
    let mut table = format!("{:<24}", path.rsplit('.').next().unwrap_or(path));
    for (_, title) in SHOWN {
        let _ = write!(table, "{title:>18}");
    }
    table.push('\n');
    let mut curves: Vec<Vec<Curve>> = vec![Vec::new(); series.len()];
    for (value, mission) in values.iter().zip(&missions) {
        let variant = || format!("the variant {path}={value}");
        if mission.spec.stages.is_empty() == staged {
            bail!("{}: it changes whether the mission has stages", variant());
        }
        let label = format!("{path}={value}");
        let cells: Vec<Option<f64>> = if staged {
            let run = simulate_staged(mission, args.seed).with_context(variant)?;
            let (cells, _) = staged_outputs(&run, &mission.spec).map_err(anyhow::Error::msg)?;
            for (body, info) in run.bodies.iter().enumerate() {
                let samples = run.samples(body);
                let track = run.track(body);
                for (chosen, curve) in series.iter().zip(&mut curves) {
                    let points = samples
                        .iter()
                        .map(|s| (s.t, chosen.value(&track, s)))
                        .collect();
                    curve.push((format!("{label} ({})", info.name), points));
                }
            }
            cells
        } else {
            let run = simulate_with_seed(mission, args.seed).with_context(variant)?;
            let summary = serde_json::to_value(run.summary())?;
            let samples = run.samples();
            for (chosen, curve) in series.iter().zip(&mut curves) {
                let points = samples
                    .iter()
                    .map(|s| (s.t, chosen.value(&run, s)))
                    .collect();
                curve.push((label.clone(), points));
            }
            OUTPUTS
                .iter()
                .map(|key| summary.get(key).and_then(serde_json::Value::as_f64))
                .collect()
        };
        if cells.len() != columns.len() {
            bail!(
                "{}: it changes the stages' names or masses (the columns)",
                variant()
            );
        }
        let text: Vec<String> = cells
            .iter()
            .map(|v| v.map_or_else(String::new, |v| v.to_string()))
            .collect();
        let _ = writeln!(csv, "{},{}", csv_field(value), text.join(","));
        let _ = write!(table, "{value:<24}");
        for (key, _) in SHOWN {
            let at = OUTPUTS.iter().position(|o| *o == key);
            let number = at.and_then(|i| cells[i]);
            let cell = number.map_or_else(|| "—".to_owned(), |v| format!("{v:.3}"));
            let _ = write!(table, "{cell:>18}");
        }
        table.push('\n');
    }

    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    std::fs::write(args.out.join("summary.csv"), csv)?;
    for (chosen, curve) in series.iter().zip(&curves) {
        let lines: Vec<Series<'_>> = curve
            .iter()
            .map(|(label, points)| Series {
                label,
                points: points
                    .iter()
                    .copied()
                    .filter(|(t, _)| args.window.is_none_or(|w| w.contains(*t)))
                    .collect(),
            })
            .collect();
        let unit = if chosen.unit.is_empty() {
            String::new()
        } else {
            format!(" ({})", chosen.unit)
        };
        line_chart(
            &args.out.join(format!("{}.svg", chosen.name)),
            &format!("{} for each {path}", chosen.name),
            "time (s)",
            &format!("{}{unit}", chosen.name),
            &lines,
        )?;
    }
    let mut out = std::io::stdout().lock();
    write!(out, "{table}")?;
    writeln!(out, "results in {}", args.out.display())?;
    Ok(())
}

/// A value as one CSV field (quoted when it holds a comma or a quote).
fn csv_field(value: &str) -> String {
    if value.contains([',', '"']) {
        format!("\"{}\"", value.replace('"', "\"\""))
    } else {
        value.to_owned()
    }
}

#[cfg(test)]
mod tests {
    use super::{parse_window, split_values};

    #[test]
    fn windows_parse_with_either_end_open() {
        let w = parse_window("0:5").unwrap();
        assert!(w.contains(0.0) && w.contains(5.0) && !w.contains(5.1) && !w.contains(-0.1));
        let w = parse_window(":30").unwrap();
        assert!(w.start.is_none() && w.contains(-100.0) && !w.contains(31.0));
        let w = parse_window("20:").unwrap();
        assert!(w.end.is_none() && w.contains(1e6) && !w.contains(19.0));
        for bad in ["5", ":", "5:2", "a:3", "1:inf", "nan:"] {
            assert!(parse_window(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn values_split_outside_brackets_and_quotes() {
        assert_eq!(split_values("1, 2,3.5"), ["1", "2", "3.5"]);
        assert_eq!(
            split_values("[0,0,0],[0, 8.3, 0.5]"),
            ["[0,0,0]", "[0, 8.3, 0.5]"]
        );
        assert_eq!(split_values("\"a,b\",'c'"), ["\"a,b\"", "'c'"]);
        assert_eq!(split_values(""), [""]);
    }
}
