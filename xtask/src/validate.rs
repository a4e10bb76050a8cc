//! `cargo xtask validate [--data DIR]`: fly every validation mission with the release build of
//! `karman` and compare (a) with RocketPy 1.13 (`reference.json` summary, parachute noise
//! zeroed) and (b) with the measured flight (`measured.apogee_agl_m`, and `flight_data.csv`:
//! altitude RMSE over the ascent and the time of apogee).
//!
//! Every validation flight with the device's raw log in its folder is also compared from that
//! log (`karman compare`: read by karman-flightlog, its liftoff found by the reader's rules),
//! beside the comparison with the cleaned `flight_data.csv`.
//!
//! Then (issue 20) the same flights with the drag estimated from the geometry instead of the
//! team's curve (karman-airframe `drag`), against the measured apogee beside the team curve's
//! error; and every OpenRocket design of `fixtures/openrocket` imported, flown and compared
//! with OpenRocket's stored flights (karman-mission `report::openrocket`): the single-stage
//! ones, and (issue 21) the multi-stage ones with their separation times.
//!
//! Prints the tables, writes `target/validation/report.md`, `report.json` and SVG figures,
//! and fails when a parity tolerance, a per-flight measured band or an OpenRocket acceptance
//! tolerance is exceeded.
//!
//! `cargo xtask validate --openrocket DIR` runs the OpenRocket comparison alone on the design
//! folders of `DIR` (each a subfolder holding `design.ork`, `reference.json` and the thrust
//! curves, as `fixtures/openrocket`), with the same acceptance; it writes
//! `target/validation/openrocket.md` and fails on a miss or a design karman refuses (other
//! than the known refusals).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{Context, Result, bail};
use karman_mission::dispersion::files::write_atomic;
use karman_mission::math::csv::{parse_named_columns, read_data_file};
use karman_mission::math::{Extrapolation, Interpolation, PointOrder, Table1};
use karman_validation::{IMPACT_FRACTION, SUMMARY_PARITY, Tolerance};
use serde_json::{Value, json};

/// Per-flight band on |apogee error| against the measured flight, with its reason. A model
/// change that moves a flight outside its band must be explained, not absorbed.
const MEASURED_BANDS: &[(&str, f64, &str)] = &[
    (
        "andromeda",
        0.07,
        "team thrust curve and a drag curve starting near Cd 0; RocketPy +5.2 %",
    ),
    (
        "astra",
        0.08,
        "1 Hz log with a 3-row t = 0 and unsorted drag data; RocketPy −6.3 %",
    ),
    (
        "bella_lui",
        0.02,
        "ERA5 weather, constant Cd 0.43; RocketPy +0.3 %",
    ),
    (
        "camoes",
        0.02,
        "air brakes replaying the team's actuation open-loop, ERA5 weather; RocketPy −0.40 %",
    ),
    (
        "halcyon",
        0.09,
        "hybrid; ERA5 weather, OpenRocket drag curves, COTS altimeter; RocketPy −7.4 %",
    ),
    (
        "hedy",
        0.02,
        "liquid, four tanks; ERA5 weather, CoolProp densities; RocketPy +0.3 %",
    ),
    (
        "juno3",
        0.03,
        "ISA fallback (weather file unpublished); RocketPy −1.9 %",
    ),
    (
        "ndrt_2020",
        0.03,
        "constant Cd 0.44, log in feet; RocketPy −2.0 %",
    ),
    (
        "prometheus_2022",
        0.06,
        "ISA fallback instead of the 2023 reanalysis; RocketPy +4.3 %",
    ),
    (
        "valetudo",
        0.07,
        "ISA, team-reported apogee without data; RocketPy −5.2 %",
    ),
];

struct Flight {
    name: String,
    /// The summary in `"rocketpy_1_13"` equations (the parity run).
    summary: Value,
    /// The summary in `"standard"` equations (the physically consistent form).
    standard: Value,
    reference: Value,
    measured_apogee: Option<f64>,
    /// (t, altitude AGL) measured, and (t, altitude AGL) simulated.
    measured: Vec<(f64, f64)>,
    simulated: Vec<(f64, f64)>,
    failures: Vec<String>,
}

/// Usage of `cargo xtask validate`.
const USAGE: &str = "cargo xtask validate [--data DIR] | cargo xtask validate --openrocket DIR";

/// What `validate` was asked for.
#[derive(Debug, PartialEq)]
enum Request {
    /// Everything: the validation flights of the folder ([`karman_validation::data_dir`]
    /// without `--data`) and the OpenRocket designs of `fixtures/openrocket`.
    All(PathBuf),
    /// `--openrocket DIR`: the OpenRocket comparison alone, on the design folders of `DIR`.
    OpenRocket(PathBuf),
}

fn request(args: &[String]) -> Result<Request> {
    match args {
        [flag, dir] if flag == "--openrocket" => Ok(Request::OpenRocket(PathBuf::from(dir))),
        _ => Ok(Request::All(data_dir(args)?)),
    }
}

/// Runs the validation; `args` are the arguments after `validate`.
pub fn run(root: &Path, args: &[String]) -> Result<()> {
    let data = match request(args)? {
        Request::All(data) => data,
        Request::OpenRocket(dir) => return run_openrocket(root, &dir),
    };
    let folder = karman_validation::open(&data)?;
    crate::cargo(root, &["build", "--release", "--package", "karman"])?;
    let exe = crate::target_dir(root).join("release/karman");
    let out = crate::target_dir(root).join("validation");
    std::fs::create_dir_all(&out)?;
    let mut flights = Vec::new();
    for flight in &folder.flights {
        if let Some(pending) = karman_validation::pending(&flight.name) {
            eprintln!(
                "xtask: validation flight {} skipped: it needs {}",
                flight.name, pending.needs
            );
            continue;
        }
        flights.push(
            fly(&exe, &flight.dir, &out)
                .with_context(|| format!("flight {}", flight.dir.display()))?,
        );
    }
    let mut report = report_markdown(&flights);
    report += &raw_log_report(&exe, &folder, &flights)?;
    report += &estimated_drag_report(&data, &flights);
    let (openrocket, openrocket_failures) = openrocket_report(&root.join("fixtures/openrocket"))?;
    report += &openrocket;
    print!("{report}");
    write_atomic(&out.join("report.md"), report.as_bytes())?;
    write_atomic(
        &out.join("report.json"),
        serde_json::to_string_pretty(&report_json(&flights))?.as_bytes(),
    )?;
    write_figures(&flights, &out)?;
    eprintln!(
        "xtask: report written to {}",
        out.join("report.md").display()
    );
    let failed: Vec<String> = flights
        .iter()
        .flat_map(|f| f.failures.iter().map(|m| format!("{}: {m}", f.name)))
        .chain(openrocket_failures)
        .collect();
    if !failed.is_empty() {
        bail!("validation failed:\n  {}", failed.join("\n  "));
    }
    Ok(())
}

/// `--openrocket DIR`: the OpenRocket comparison on the design folders of `DIR` (the layout
/// of `fixtures/openrocket`), written to `target/validation/openrocket.md`; fails on an
/// acceptance miss.
fn run_openrocket(root: &Path, dir: &Path) -> Result<()> {
    let (report, failures) = openrocket_report(dir)?;
    print!("{report}");
    let out = crate::target_dir(root).join("validation");
    std::fs::create_dir_all(&out)?;
    write_atomic(&out.join("openrocket.md"), report.as_bytes())?;
    eprintln!(
        "xtask: report written to {}",
        out.join("openrocket.md").display()
    );
    if !failures.is_empty() {
        bail!("OpenRocket comparison failed:\n  {}", failures.join("\n  "));
    }
    Ok(())
}

/// `--data DIR`, else `$KARMAN_VALIDATION_DATA`, else the repository's `fixtures/validation`
/// ([`karman_validation::data_dir`]).
pub fn data_dir(args: &[String]) -> Result<PathBuf> {
    match args {
        [] => Ok(karman_validation::data_dir()),
        [flag, dir] if flag == "--data" => Ok(PathBuf::from(dir)),
        _ => bail!("unexpected arguments {args:?} (usage: {USAGE})"),
    }
}

fn fly(exe: &Path, dir: &Path, out: &Path) -> Result<Flight> {
    let name = dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mission_path = dir.join("mission.toml");
    let mission = karman_mission::load(&mission_path, &[])
        .map_err(|e| anyhow::anyhow!("{e}"))
        .context("mission does not load")?;
    let flight_out = out.join(&name);
    // The parity run flies RocketPy 1.13's equations (with its outputs written); the second,
    // the standard ones, for the report's comparison with the measured flight.
    let summary_of = |equations: &str, out: Option<&Path>| -> Result<Value> {
        let mut cmd = Command::new(exe);
        cmd.arg("simulate").arg(&mission_path).arg("--json");
        if let Some(out) = out {
            cmd.arg("--out").arg(out);
        }
        cmd.arg("--set")
            .arg(format!("flight.equations=\"{equations}\""));
        for chute in mission.spec.rocket.parachutes.keys() {
            cmd.arg("--set")
                .arg(format!("rocket.parachutes.{chute}.noise=[0,0,0]"));
        }
        let output = cmd.output().context("could not run karman")?;
        if !output.status.success() {
            bail!(
                "karman simulate failed: {}",
                String::from_utf8_lossy(&output.stderr)
            );
        }
        serde_json::from_slice(&output.stdout).context("summary JSON")
    };
    let summary = summary_of("rocketpy_1_13", Some(&flight_out))?;
    let standard = summary_of("standard", None)?;
    let reference: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("reference.json"))?)?;
    let measured_apogee = reference["measured"]["apogee_agl_m"].as_f64();
    let measured = match dir.join("flight_data.csv") {
        p if p.is_file() => read_series(&p, "time_s", "altitude_agl_m")?,
        _ => Vec::new(),
    };
    let simulated = read_series(
        &flight_out.join("trajectory.csv"),
        "time_s",
        "altitude_agl_m",
    )?;
    let mut flight = Flight {
        name,
        summary,
        standard,
        reference,
        measured_apogee,
        measured,
        simulated,
        failures: vec![],
    };
    flight.failures = check(&flight);
    Ok(flight)
}

/// Reads two named columns of a CSV with `#` comment lines and a header (karman-math's CSV
/// reader); a column is found by its name, or by its name followed by a unit (`time_s (s)`).
pub fn read_series(path: &Path, xcol: &str, ycol: &str) -> Result<Vec<(f64, f64)>> {
    let text = read_data_file(path).with_context(|| format!("cannot read {}", path.display()))?;
    let (names, columns) = parse_named_columns(&String::from_utf8_lossy(&text), path)?;
    let find = |c: &str| {
        names
            .iter()
            .position(|n| n == c || n.starts_with(&format!("{c} ")))
            .with_context(|| format!("{}: no column {c}", path.display()))
    };
    let (ix, iy) = (find(xcol)?, find(ycol)?);
    Ok(columns[ix]
        .iter()
        .copied()
        .zip(columns[iy].iter().copied())
        .collect())
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(f64::MIN_POSITIVE)
}

fn num(v: &Value, key: &str) -> Option<f64> {
    v.get(key).and_then(Value::as_f64)
}

fn check(f: &Flight) -> Vec<String> {
    let r = &f.reference["summary"];
    let mut failures = Vec::new();
    for Tolerance { key, relative: tol } in SUMMARY_PARITY {
        match (num(&f.summary, key), num(r, key)) {
            (Some(k), Some(p)) if rel(k, p) > tol => failures.push(format!(
                "{key}: karman {k:.4} vs RocketPy {p:.4} ({:.3} % > {:.2} %)",
                100.0 * rel(k, p),
                100.0 * tol
            )),
            (None, Some(p)) => failures.push(format!("{key}: missing (RocketPy {p})")),
            _ => {}
        }
    }
    if let (Some(kx), Some(ky), Some(px), Some(py)) = (
        num(&f.summary, "impact_x_m"),
        num(&f.summary, "impact_y_m"),
        num(r, "impact_x_m"),
        num(r, "impact_y_m"),
    ) {
        let miss = (kx - px).hypot(ky - py);
        let dist = px.hypot(py);
        if miss > IMPACT_FRACTION * dist {
            failures.push(format!(
                "impact point {miss:.2} m from RocketPy's (> {:.0} % of {dist:.1} m)",
                100.0 * IMPACT_FRACTION
            ));
        }
    }
    if let (Some(m), Some(k)) = (f.measured_apogee, num(&f.summary, "apogee_agl_m")) {
        let band = MEASURED_BANDS.iter().find(|(n, _, _)| *n == f.name);
        match band {
            Some(&(_, b, why)) if rel(k, m) > b => failures.push(format!(
                "apogee {k:.1} m vs measured {m:.1} m: {:.2} % outside the {:.0} % band ({why})",
                100.0 * rel(k, m),
                100.0 * b
            )),
            None => failures.push("a measured apogee but no band in MEASURED_BANDS".to_owned()),
            _ => {}
        }
    }
    failures
}

/// The series as a linear table of time, held at its ends (a repeated time is a step), or
/// `None` for fewer than two points.
fn series_table(series: &[(f64, f64)]) -> Option<Table1> {
    let points: Vec<[f64; 2]> = series.iter().map(|&(t, h)| [t, h]).collect();
    Table1::from_points(
        &points,
        Interpolation::Linear,
        Extrapolation::Constant,
        PointOrder::SortStably,
    )
    .ok()
}

/// Measured time of apogee (first maximum) and the RMSE of the simulated altitude at the
/// measured times from t = 0 to that apogee.
fn ascent_fit(f: &Flight) -> Option<(f64, f64)> {
    let (t_apo, _) = f
        .measured
        .iter()
        .copied()
        .fold(None::<(f64, f64)>, |best, p| match best {
            Some(b) if b.1 >= p.1 => Some(b),
            _ => Some(p),
        })?;
    let simulated = series_table(&f.simulated)?;
    let ascent: Vec<f64> = f
        .measured
        .iter()
        .filter(|p| p.0 >= 0.0 && p.0 <= t_apo)
        .map(|&(t, h)| (simulated.eval(t) - h).powi(2))
        .collect();
    if ascent.is_empty() {
        return None;
    }
    Some((
        t_apo,
        (ascent.iter().sum::<f64>() / ascent.len() as f64).sqrt(),
    ))
}

fn fmt_opt(v: Option<f64>, digits: usize) -> String {
    v.map_or_else(|| "—".to_owned(), |x| format!("{x:.digits$}"))
}

fn report_markdown(flights: &[Flight]) -> String {
    let mut s = String::from("# karman validation report\n\n");
    s.push_str("Apogees above ground; karman flies RocketPy 1.13's equations (`equations = \"rocketpy_1_13\"`) for the parity columns and the physically consistent ones (`\"standard\"`) for the standard columns.\n\n");
    s.push_str("| flight | karman apogee (m) | RocketPy apogee (m) | parity error | measured apogee (m) | karman vs measured | RocketPy vs measured | standard apogee (m) | standard vs measured | apogee time (s) | measured apogee time (s) | ascent RMSE (m) | rail-exit speed (m/s) | max Mach | status |\n");
    s.push_str("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    let (mut ours, mut theirs) = (Vec::new(), Vec::new());
    for f in flights {
        let r = &f.reference["summary"];
        let k = num(&f.summary, "apogee_agl_m");
        let p = num(r, "apogee_agl_m");
        let std_apogee = num(&f.standard, "apogee_agl_m");
        let parity = k.zip(p).map(|(k, p)| 100.0 * (k - p) / p);
        let vs = |a: Option<f64>| a.zip(f.measured_apogee).map(|(a, m)| 100.0 * (a - m) / m);
        if let (Some(a), Some(b)) = (vs(k), vs(p)) {
            ours.push(a.abs());
            theirs.push(b.abs());
        }
        let fit = ascent_fit(f);
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} % | {} | {} % | {} % | {} | {} % | {} | {} | {} | {} | {} | {} |",
            f.name,
            fmt_opt(k, 2),
            fmt_opt(p, 2),
            fmt_opt(parity, 4),
            fmt_opt(f.measured_apogee, 2),
            fmt_opt(vs(k), 2),
            fmt_opt(vs(p), 2),
            fmt_opt(std_apogee, 2),
            fmt_opt(vs(std_apogee), 2),
            fmt_opt(num(&f.summary, "apogee_time_s"), 3),
            fmt_opt(fit.map(|x| x.0), 2),
            fmt_opt(fit.map(|x| x.1), 1),
            fmt_opt(num(&f.summary, "out_of_rail_velocity_mps"), 3),
            fmt_opt(num(&f.summary, "max_mach"), 4),
            if f.failures.is_empty() {
                "ok".to_owned()
            } else {
                f.failures.join("; ")
            },
        );
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
    let _ = writeln!(
        s,
        "\nMean |apogee error| against the measured flights ({} flights): karman {:.2} %, RocketPy 1.13 {:.2} %.",
        ours.len(),
        mean(&ours),
        mean(&theirs)
    );
    s
}

/// Files of a validation folder that are never flight logs.
const NOT_LOGS: &[&str] = &["mission.toml", "reference.json", "flight_data.csv"];

/// Every raw flight log of a validation flight's folder: the files `karman log show` reads
/// (the format recognised from the content, as a user's log would be), in name order.
fn raw_logs(exe: &Path, dir: &Path) -> Result<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_file())
        .filter(|p| {
            p.file_name().and_then(|n| n.to_str()).is_some_and(|n| {
                !NOT_LOGS.contains(&n) && !n.ends_with(".nc") && !n.ends_with(".eng")
            })
        })
        .collect();
    files.sort();
    let mut logs = Vec::new();
    for file in files {
        let output = Command::new(exe)
            .arg("log")
            .arg("show")
            .arg(&file)
            .arg("--json")
            .output()
            .context("could not run karman")?;
        if output.status.success() {
            logs.push(file);
        }
    }
    Ok(logs)
}

/// Each validation flight with a raw log in its folder, compared with `karman compare` from
/// that log (read by karman-flightlog, liftoff and apogee found by its rules), beside the
/// comparison with the cleaned `flight_data.csv` above; the same equations and noise-free
/// triggers as the parity run.
fn raw_log_report(
    exe: &Path,
    folder: &karman_validation::Folder,
    flights: &[Flight],
) -> Result<String> {
    let mut s = String::from(
        "\n## Raw flight logs\n\nEach validation flight with the device's own log beside it, \
         compared with `karman compare` (the log read and its liftoff found by karman-flightlog; \
         RocketPy 1.13's equations, parachute noise zeroed, as the parity run), beside the \
         comparison with the cleaned `flight_data.csv`.\n\n",
    );
    s.push_str("| flight | log | format | log apogee (m) | cleaned apogee (m) | apogee error from the log | from the cleaned data | apogee time error (s) | ascent RMS, log (m) | ascent RMSE, cleaned (m) | max vertical velocity error | descent rate errors |\n");
    s.push_str("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for flight in &folder.flights {
        let Some(f) = flights.iter().find(|f| f.name == flight.name) else {
            continue;
        };
        let mission = flight.dir.join("mission.toml");
        let spec = karman_mission::load(&mission, &[])
            .map_err(|e| anyhow::anyhow!("{e}"))?
            .spec;
        for log in raw_logs(exe, &flight.dir)? {
            let mut cmd = Command::new(exe);
            cmd.arg("compare").arg(&mission).arg(&log).arg("--json");
            cmd.arg("--set").arg("flight.equations=\"rocketpy_1_13\"");
            for chute in spec.rocket.parachutes.keys() {
                cmd.arg("--set")
                    .arg(format!("rocket.parachutes.{chute}.noise=[0,0,0]"));
            }
            let output = cmd.output().context("could not run karman")?;
            if !output.status.success() {
                bail!(
                    "karman compare {} failed: {}",
                    log.display(),
                    String::from_utf8_lossy(&output.stderr)
                );
            }
            let report: Value = serde_json::from_slice(&output.stdout).context("compare JSON")?;
            let entry = &report["logs"][0];
            let cleaned = f.measured_apogee;
            let simulated = num(&report["simulation"], "apogee_m");
            let from_cleaned = simulated.zip(cleaned).map(|(k, m)| 100.0 * (k - m) / m);
            let descent: Vec<String> = entry["descent"]
                .as_array()
                .into_iter()
                .flatten()
                .map(|d| match d["error_pct"].as_f64() {
                    Some(e) => format!("{} {e:+.1} %", d["parachute"].as_str().unwrap_or("?")),
                    None => format!("{} not in the log", d["parachute"].as_str().unwrap_or("?")),
                })
                .collect();
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} % | {} % | {} | {} | {} | {} % | {} |",
                f.name,
                log.file_name()
                    .map(|n| n.to_string_lossy())
                    .unwrap_or_default(),
                entry["format"].as_str().unwrap_or("?"),
                fmt_opt(num(entry, "apogee_m"), 1),
                fmt_opt(cleaned, 1),
                fmt_opt(num(entry, "apogee_error_pct"), 2),
                fmt_opt(from_cleaned, 2),
                fmt_opt(num(entry, "apogee_time_error_s"), 2),
                fmt_opt(num(entry, "ascent_rms_altitude_m"), 1),
                fmt_opt(ascent_fit(f).map(|x| x.1), 1),
                fmt_opt(num(entry, "max_velocity_error_pct"), 2),
                if descent.is_empty() {
                    "—".to_owned()
                } else {
                    descent.join(", ")
                },
            );
        }
    }
    Ok(s)
}

/// Fin thickness assumed for the estimate where a validation mission gives none (OpenRocket's
/// default fin, 3 mm with square edges).
const ASSUMED_FIN_THICKNESS: f64 = 0.003;

/// The validation flights flown with `power_off_drag = power_on_drag = "estimate"`: the
/// estimate against the team's curve (mean and largest relative difference, power off, from
/// Mach 0.05 to the flight's max Mach) and the apogee error against the measured flight
/// beside the team curve's.
fn estimated_drag_report(data: &Path, flights: &[Flight]) -> String {
    use karman_mission::assemble::flight::simulate;
    use karman_mission::schema::{
        Curve, DragEstimateSpec, ESTIMATE, FinCrossSection, FinDragSpec, SurfaceFinish, SurfaceSpec,
    };
    let mut s = String::from(
        "\n## Validation flights with the drag estimated from the geometry\n\n\
         Fins assumed 3 mm thick with square edges, regular paint (the missions give neither).\n\n\
         | flight | estimate / team Cd, mean | largest difference | apogee, estimate (m) | vs measured | team curve vs measured |\n|---|---|---|---|---|---|\n",
    );
    for f in flights {
        let path = data.join(&f.name).join("mission.toml");
        let row = (|| -> std::result::Result<String, String> {
            let team = karman_mission::load(&path, &[]).map_err(|e| e.to_string())?;
            let quiet = team.parachute_noise_off().map_err(|e| e.to_string())?;
            let team = karman_mission::load(&path, &quiet).map_err(|e| e.to_string())?;
            let mut mission = team.clone();
            let rocket = &mut mission.spec.rocket;
            rocket.power_off_drag = Curve::File(ESTIMATE.into());
            rocket.power_on_drag = Curve::File(ESTIMATE.into());
            let fins = rocket
                .surfaces
                .iter()
                .filter(|(_, s)| {
                    matches!(
                        s,
                        SurfaceSpec::TrapezoidalFins(_)
                            | SurfaceSpec::EllipticalFins(_)
                            | SurfaceSpec::FreeFormFins(_)
                    )
                })
                .map(|(name, _)| {
                    (
                        name.clone(),
                        FinDragSpec {
                            thickness: ASSUMED_FIN_THICKNESS,
                            cross_section: FinCrossSection::Square,
                            finish: None,
                        },
                    )
                })
                .collect();
            rocket.drag_estimate = Some(DragEstimateSpec {
                body_length: None,
                finish: SurfaceFinish::Normal,
                roughness: None,
                fins,
                launch_lugs: Default::default(),
                overrides: Default::default(),
                rail_buttons: None,
            });
            let run = simulate(&mission).map_err(|e| {
                let source = std::error::Error::source(&e).map(ToString::to_string);
                format!("{e}: {}", source.unwrap_or_default())
            })?;
            let team_motor =
                karman_mission::assemble::motor::build_motor(&team).map_err(|e| e.to_string())?;
            let team_rocket = karman_mission::assemble::rocket::build_rocket(&team, &team_motor)
                .map_err(|e| e.to_string())?;
            let max_mach = num(&f.summary, "max_mach").unwrap_or(0.3).max(0.1);
            let (mut sum, mut worst, mut count) = (0.0, 0.0_f64, 0);
            for i in 0..=50 {
                let m = 0.05 + (max_mach - 0.05) * f64::from(i) / 50.0;
                let ratio =
                    run.rocket.drag_coefficient(false, m) / team_rocket.drag_coefficient(false, m);
                sum += ratio;
                worst = worst.max((ratio - 1.0).abs());
                count += 1;
            }
            let apogee = run.summary().apogee_agl_m;
            let vs = |a: Option<f64>| a.zip(f.measured_apogee).map(|(a, m)| 100.0 * (a - m) / m);
            Ok(format!(
                "| {} | {:.2} | {:.0} % | {} | {} % | {} % |",
                f.name,
                sum / f64::from(count),
                100.0 * worst,
                fmt_opt(apogee, 1),
                fmt_opt(vs(apogee), 2),
                fmt_opt(vs(num(&f.summary, "apogee_agl_m")), 2),
            ))
        })();
        let _ = writeln!(
            s,
            "{}",
            row.unwrap_or_else(|e| format!("| {} | not estimated: {e} | | | | |", f.name))
        );
    }
    s
}

/// The OpenRocket designs of `dir` (karman-mission's `report::openrocket::compare_folder`):
/// one line per stored simulation, and the acceptance misses.
fn openrocket_report(dir: &Path) -> Result<(String, Vec<String>)> {
    use karman_mission::report::openrocket::compare_folder;
    let results = compare_folder(dir).map_err(|e| anyhow::anyhow!("{e}"))?;
    let mut s = format!(
        "\n## OpenRocket designs imported and flown ({})\n\n\
         karman / OpenRocket. Single-stage designs: CP and margin at rod exit, at the angle of \
         attack OpenRocket stored there and its roll angle of the flow. Multi-stage designs: the \
         top stage's apogee, maximum speed, worst Cd error per vehicle of its path (the stack \
         first), and each stage separation.\n\n```\n",
        dir.display()
    );
    let mut failures = Vec::new();
    for r in &results {
        let _ = write!(s, "{r}");
        failures.extend(r.failures());
    }
    s.push_str("```\n");
    let _ = writeln!(
        s,
        "\n{} designs, {} with an acceptance miss.",
        results.len(),
        results.iter().filter(|r| !r.failures().is_empty()).count()
    );
    Ok((s, failures))
}

fn report_json(flights: &[Flight]) -> Value {
    Value::Array(
        flights
            .iter()
            .map(|f| {
                json!({
                    "flight": f.name,
                    "karman": f.summary,
                    "karman_standard": f.standard,
                    "rocketpy": f.reference["summary"],
                    "measured_apogee_agl_m": f.measured_apogee,
                    "ascent_fit": ascent_fit(f).map(|(t, rmse)| json!({"measured_apogee_time_s": t, "rmse_m": rmse})),
                    "failures": f.failures,
                })
            })
            .collect(),
    )
}

fn write_figures(flights: &[Flight], out: &Path) -> Result<()> {
    use plotters::prelude::*;
    let err = |e: &dyn std::fmt::Display| anyhow::anyhow!("plot: {e}");
    // Simulated vs measured apogee, all flights.
    let points: Vec<(String, f64, f64)> = flights
        .iter()
        .filter_map(|f| {
            Some((
                f.name.clone(),
                f.measured_apogee?,
                num(&f.summary, "apogee_agl_m")?,
            ))
        })
        .collect();
    if !points.is_empty() {
        let mut svg = String::new();
        let root = SVGBackend::with_string(&mut svg, (800, 700)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let top = points.iter().map(|p| p.1.max(p.2)).fold(0.0, f64::max) * 1.1;
        let mut chart = ChartBuilder::on(&root)
            .caption("karman apogee vs measured apogee (AGL)", ("sans-serif", 22))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..top, 0.0..top)
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc("measured apogee (m)")
            .y_desc("simulated apogee (m)")
            .draw()
            .map_err(|e| err(&e))?;
        chart
            .draw_series(LineSeries::new([(0.0, 0.0), (top, top)], &BLACK))
            .map_err(|e| err(&e))?;
        chart
            .draw_series(points.iter().map(|(name, m, k)| {
                EmptyElement::at((*m, *k))
                    + Circle::new((0, 0), 5, BLUE.filled())
                    + Text::new(name.clone(), (8, -8), ("sans-serif", 14))
            }))
            .map_err(|e| err(&e))?;
        root.present().map_err(|e| err(&e))?;
        drop(chart);
        drop(root);
        write_atomic(&out.join("apogee_scatter.svg"), svg.as_bytes())?;
    }
    // Per flight: simulated altitude over the measured one.
    for f in flights
        .iter()
        .filter(|f| !f.measured.is_empty() && !f.simulated.is_empty())
    {
        let mut svg = String::new();
        let root = SVGBackend::with_string(&mut svg, (900, 600)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let all = f.measured.iter().chain(&f.simulated);
        let (t0, t1, h1) = all.fold((0.0_f64, 0.0_f64, 0.0_f64), |(a, b, c), p| {
            (a.min(p.0), b.max(p.0), c.max(p.1))
        });
        let mut chart = ChartBuilder::on(&root)
            .caption(format!("{}: altitude AGL", f.name), ("sans-serif", 22))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(60)
            .build_cartesian_2d(t0..t1, 0.0..h1 * 1.05)
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc("time (s)")
            .y_desc("altitude AGL (m)")
            .draw()
            .map_err(|e| err(&e))?;
        chart
            .draw_series(LineSeries::new(f.measured.iter().copied(), &RED))
            .map_err(|e| err(&e))?
            .label("measured")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], RED));
        chart
            .draw_series(LineSeries::new(f.simulated.iter().copied(), &BLUE))
            .map_err(|e| err(&e))?
            .label("karman")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], BLUE));
        chart
            .configure_series_labels()
            .border_style(BLACK)
            .draw()
            .map_err(|e| err(&e))?;
        root.present().map_err(|e| err(&e))?;
        drop(chart);
        drop(root);
        write_atomic(
            &out.join(format!("{}_altitude.svg", f.name)),
            svg.as_bytes(),
        )?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn series_hold_their_ends_and_are_linear_inside() {
        let s = series_table(&[(0.0, 0.0), (1.0, 10.0), (3.0, 30.0)]).expect("a table");
        assert!((s.eval(-1.0) - 0.0).abs() < 1e-12);
        assert!((s.eval(2.0) - 20.0).abs() < 1e-12);
        assert!((s.eval(9.0) - 30.0).abs() < 1e-12);
        assert!(series_table(&[]).is_none());
    }

    #[test]
    fn the_openrocket_option_names_a_folder() {
        let args = |a: &[&str]| a.iter().map(|s| (*s).to_owned()).collect::<Vec<_>>();
        assert_eq!(
            request(&args(&["--openrocket", "blind"])).expect("a request"),
            Request::OpenRocket(PathBuf::from("blind"))
        );
        assert_eq!(
            request(&args(&["--data", "v"])).expect("a request"),
            Request::All(PathBuf::from("v"))
        );
        assert!(request(&args(&["--openrocket"])).is_err());
        assert!(request(&args(&["--openrocket", "a", "b"])).is_err());
    }

    #[test]
    fn every_measured_flight_has_a_band() {
        let Some(folder) = karman_validation::folder() else {
            return;
        };
        for flight in folder.flown() {
            let text = std::fs::read_to_string(flight.reference()).expect("reference.json");
            let v: Value = serde_json::from_str(&text).expect("reference.json is JSON");
            if v["measured"]["apogee_agl_m"].is_f64() {
                assert!(
                    MEASURED_BANDS.iter().any(|b| b.0 == flight.name),
                    "{} has no band",
                    flight.name
                );
            }
        }
    }
}
