//! `karman weather fetch|show`: launch-day weather.
//!
//! - `fetch --source open-meteo|gfs|wyoming --lat --lon --date [--station ID] [--ensemble]
//!   -o FILE` downloads once (the only command besides `--fetch` that uses the network) and
//!   writes the service's answer as it came (Open-Meteo JSON, GFS netCDF, the Wyoming page)
//!   with `FILE.provenance.json` beside it (service, request, time of download).
//! - `show FILE [--lat --lon --date] [--member N] [--plot DIR] [--json]` prints the profile a
//!   mission would read from the file (pressure, temperature, wind speed and the direction it
//!   blows from, by height) and writes SVG charts of it. Offline.
//!
//! The services' addresses can be changed with the environment variables
//! `KARMAN_OPEN_METEO_URL`, `KARMAN_OPEN_METEO_ENSEMBLE_URL`, `KARMAN_GFS_NCSS_URL` and
//! `KARMAN_WYOMING_URL` (a mirror, a test server), the timeout with `KARMAN_WEATHER_TIMEOUT`
//! (seconds, default 60).

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use clap::{Args, Subcommand, ValueEnum};
use karman_mission::atmos::{
    Datum, GridDictionary, GridRequest, LevelProfile, OpenMeteo, Sounding, WeatherGrid,
};
use karman_mission::math::PhysicalConstants;

use crate::plot::{Series, line_chart};

/// `karman weather` subcommands.
#[derive(Debug, Subcommand)]
pub enum WeatherCommand {
    /// Download the forecast or sounding for a site and time into a file missions read
    /// offline, with its provenance beside it.
    #[cfg(feature = "fetch")]
    Fetch(FetchArgs),
    /// Print the profile a weather file gives at a site and time; --plot writes SVG charts.
    Show(ShowArgs),
}

/// Arguments of `karman weather`.
#[derive(Debug, Args)]
pub struct WeatherArgs {
    #[command(subcommand)]
    pub command: WeatherCommand,
}

/// A weather service.
#[cfg(feature = "fetch")]
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum Source {
    /// Open-Meteo pressure-level forecast (JSON).
    OpenMeteo,
    /// GFS 0.25° through UCAR THREDDS' NetCDF Subset Service (netCDF).
    Gfs,
    /// University of Wyoming sounding (TEXT:LIST page); needs --station.
    Wyoming,
}

/// Arguments of `karman weather fetch`.
#[cfg(feature = "fetch")]
#[derive(Debug, Args)]
pub struct FetchArgs {
    /// The service.
    #[arg(long, value_enum)]
    pub source: Source,
    /// Launch latitude, deg (north positive).
    #[arg(long, allow_negative_numbers = true)]
    pub lat: f64,
    /// Launch longitude, deg (east positive).
    #[arg(long, allow_negative_numbers = true)]
    pub lon: f64,
    /// Launch time, UTC unless an offset is given: `2026-12-02T14:00Z`,
    /// `2026-12-02T15:00:00+01:00`, `2026-12-02 14:00`.
    #[arg(long)]
    pub date: String,
    /// Sounding station, WMO number or ICAO id (Wyoming).
    #[arg(long)]
    pub station: Option<String>,
    /// Every member of the ensemble forecast (Open-Meteo's ensemble API).
    #[arg(long)]
    pub ensemble: bool,
    /// The file to write.
    #[arg(short = 'o', long = "out", value_name = "FILE")]
    pub out: PathBuf,
}

/// Arguments of `karman weather show`.
#[derive(Debug, Args)]
pub struct ShowArgs {
    /// The weather file: Open-Meteo JSON (`.json`), a netCDF grid (`.nc`), or a sounding.
    #[arg(value_name = "FILE")]
    pub file: PathBuf,
    /// Site latitude, deg (grids and forecasts).
    #[arg(long, allow_negative_numbers = true)]
    pub lat: Option<f64>,
    /// Site longitude, deg (grids and forecasts).
    #[arg(long, allow_negative_numbers = true)]
    pub lon: Option<f64>,
    /// Time, UTC unless an offset is given (grids and forecasts).
    #[arg(long)]
    pub date: Option<String>,
    /// Ensemble member (default 0).
    #[arg(long)]
    pub member: Option<usize>,
    /// Variable mapping of a netCDF grid (default: detected).
    #[arg(long)]
    pub dictionary: Option<String>,
    /// A sounding's format.
    #[arg(long, value_enum, default_value_t = SoundingKind::Wyoming)]
    pub format: SoundingKind,
    /// Print the profile as JSON.
    #[arg(long)]
    pub json: bool,
    /// Write temperature, pressure, wind speed and wind direction charts (SVG) here.
    #[arg(long, value_name = "DIR")]
    pub plot: Option<PathBuf>,
}

/// A sounding's text format.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum SoundingKind {
    /// University of Wyoming TEXT:LIST.
    Wyoming,
    /// NOAA RUC.
    NoaaRuc,
}

/// Runs a `weather` subcommand.
pub fn run(args: &WeatherArgs) -> Result<()> {
    match &args.command {
        #[cfg(feature = "fetch")]
        WeatherCommand::Fetch(args) => fetch(args),
        WeatherCommand::Show(args) => show(args),
    }
}

/// Unix seconds of a date given on the command line (UTC unless it carries an offset).
fn parse_date(text: &str) -> Result<f64> {
    use chrono::{DateTime, NaiveDateTime};
    let t = text.trim();
    if let Ok(d) = DateTime::parse_from_rfc3339(t) {
        return Ok(d.timestamp() as f64);
    }
    for format in ["%Y-%m-%dT%H:%M%#z", "%Y-%m-%d %H:%M%#z"] {
        if let Ok(d) = DateTime::parse_from_str(t, format) {
            return Ok(d.timestamp() as f64);
        }
    }
    let bare = t.trim_end_matches(['Z', 'z']);
    for format in [
        "%Y-%m-%dT%H:%M:%S",
        "%Y-%m-%dT%H:%M",
        "%Y-%m-%d %H:%M:%S",
        "%Y-%m-%d %H:%M",
    ] {
        if let Ok(d) = NaiveDateTime::parse_from_str(bare, format) {
            return Ok(d.and_utc().timestamp() as f64);
        }
    }
    bail!("--date `{text}` is not a date and time such as 2026-12-02T14:00Z")
}

/// The Earth radius of geopotential heights at a latitude (the missions' default datum).
fn earth_radius(latitude_deg: f64) -> f64 {
    Datum::Sirgas2000.radius(latitude_deg, &PhysicalConstants::SI)
}

/// The client with the addresses and timeout of the environment (module docs).
#[cfg(feature = "fetch")]
pub fn fetcher() -> Result<karman_mission::atmos::fetch::Fetcher> {
    use karman_mission::atmos::fetch::{Endpoints, Fetcher};
    let mut endpoints = Endpoints::default();
    for (variable, field) in [
        ("KARMAN_OPEN_METEO_URL", &mut endpoints.open_meteo),
        (
            "KARMAN_OPEN_METEO_ENSEMBLE_URL",
            &mut endpoints.open_meteo_ensemble,
        ),
        ("KARMAN_GFS_NCSS_URL", &mut endpoints.gfs_ncss),
        ("KARMAN_WYOMING_URL", &mut endpoints.wyoming),
    ] {
        if let Ok(url) = std::env::var(variable) {
            *field = url;
        }
    }
    let timeout = match std::env::var("KARMAN_WEATHER_TIMEOUT") {
        Ok(text) => text
            .trim()
            .parse::<f64>()
            .ok()
            .filter(|s| s.is_finite() && *s > 0.0 && *s <= 3600.0)
            .ok_or_else(|| {
                anyhow::anyhow!(
                    "KARMAN_WEATHER_TIMEOUT = `{text}` is not a number of seconds in (0, 3600]"
                )
            })?,
        Err(_) => 60.0,
    };
    Ok(Fetcher::new(
        endpoints,
        std::time::Duration::from_secs_f64(timeout),
    )?)
}

#[cfg(feature = "fetch")]
fn fetch(args: &FetchArgs) -> Result<()> {
    use karman_mission::atmos::fetch::{Request, Service};
    if !(-90.0..=90.0).contains(&args.lat) {
        bail!("--lat {} is not within [-90, 90] deg", args.lat);
    }
    if !(-180.0..=360.0).contains(&args.lon) {
        bail!("--lon {} is not within [-180, 360] deg", args.lon);
    }
    let service = match args.source {
        Source::OpenMeteo => Service::OpenMeteo,
        Source::Gfs => Service::Gfs,
        Source::Wyoming => Service::Wyoming,
    };
    if args.ensemble && service != Service::OpenMeteo {
        bail!("--ensemble is for --source open-meteo");
    }
    match (&args.station, service == Service::Wyoming) {
        (None, true) => bail!(
            "--source wyoming needs --station ID (the sounding station: a WMO number such as \
             72476, or an ICAO id)"
        ),
        (Some(station), false) => bail!(
            "--station {station} is for --source wyoming only (the other sources answer for \
             --lat and --lon)"
        ),
        _ => {}
    }
    let request = Request {
        service,
        latitude_deg: args.lat,
        longitude_deg: args.lon,
        unix_time: parse_date(&args.date)?,
        station: args.station.clone(),
        ensemble: args.ensemble,
        earth_radius: earth_radius(args.lat),
        standard_gravity: PhysicalConstants::SI.standard_gravity,
    };
    let download = fetcher()?.fetch(&request)?;
    karman_mission::weather::save(&download, &request, &args.out)?;
    let mut out = std::io::stdout().lock();
    writeln!(
        out,
        "{}: {} bytes from {} ({} levels at the launch{}); provenance in {}",
        args.out.display(),
        download.bytes.len(),
        service.title(),
        download.profile.pressure_pa.len(),
        if download.members > 1 {
            format!(", {} members", download.members)
        } else {
            String::new()
        },
        karman_mission::weather::provenance_path(&args.out).display()
    )?;
    writeln!(out, "request: {}", download.request)?;
    Ok(())
}

/// The profile of a weather file at the site and time.
fn read_profile(args: &ShowArgs) -> Result<LevelProfile> {
    let name = args.file.display().to_string();
    let extension = args
        .file
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let site = || -> Result<(f64, f64, f64)> {
        match (args.lat, args.lon, &args.date) {
            (Some(lat), Some(lon), Some(date)) => Ok((lat, lon, parse_date(date)?)),
            _ => bail!("{name}: a weather grid or forecast needs --lat, --lon and --date"),
        }
    };
    let read = || {
        karman_mission::math::read_data_file(&args.file)
            .with_context(|| format!("cannot read {name}"))
    };
    Ok(match extension.as_deref() {
        Some("json") => {
            let (lat, _, t) = site()?;
            OpenMeteo::parse(&read()?, &name)?.profile(t, args.member, earth_radius(lat))?
        }
        Some("nc" | "nc4" | "netcdf") => {
            let (lat, lon, t) = site()?;
            let grid = WeatherGrid::open(&args.file)?;
            let dictionary = args
                .dictionary
                .as_deref()
                .map(GridDictionary::builtin)
                .transpose()?;
            grid.profile(&GridRequest {
                dictionary,
                unix_time: t,
                latitude_deg: lat,
                longitude_deg: lon,
                member: args.member,
                earth_radius: earth_radius(lat),
                standard_gravity: PhysicalConstants::SI.standard_gravity,
            })?
        }
        _ => {
            let text = String::from_utf8_lossy(&read()?).into_owned();
            let sounding = match args.format {
                SoundingKind::Wyoming => Sounding::parse_wyoming(&text, &name)?,
                SoundingKind::NoaaRuc => Sounding::parse_noaa_ruc(&text, &name)?,
            };
            sounding.level_profile(earth_radius(args.lat.unwrap_or(0.0)))
        }
    })
}

/// One level for display: height, pressure, temperature, wind speed, direction it blows from.
struct Level {
    height_m: f64,
    pressure_pa: f64,
    temperature_k: f64,
    speed_mps: f64,
    from_deg: f64,
}

fn levels(profile: &LevelProfile) -> Vec<Level> {
    let mut rows: Vec<Level> = (0..profile.pressure_pa.len())
        .map(|k| {
            let (u, v) = (profile.wind_u_mps[k], profile.wind_v_mps[k]);
            Level {
                height_m: profile.height_m[k],
                pressure_pa: profile.pressure_pa[k],
                temperature_k: profile.temperature_k[k],
                speed_mps: u.hypot(v),
                from_deg: (-u).atan2(-v).to_degrees().rem_euclid(360.0),
            }
        })
        .collect();
    rows.sort_by(|a, b| a.height_m.total_cmp(&b.height_m));
    rows
}

fn show(args: &ShowArgs) -> Result<()> {
    let profile = read_profile(args)?;
    let rows = levels(&profile);
    let mut out = std::io::stdout().lock();
    if args.json {
        let value = serde_json::json!({
            "file": args.file.display().to_string(),
            "surface_elevation_m": profile.surface_elevation_m,
            "levels": rows.iter().map(|r| serde_json::json!({
                "height_m": r.height_m,
                "pressure_pa": r.pressure_pa,
                "temperature_k": r.temperature_k,
                "wind_speed_mps": r.speed_mps,
                "wind_direction_deg": r.from_deg,
            })).collect::<Vec<_>>(),
        });
        writeln!(out, "{}", serde_json::to_string_pretty(&value)?)?;
    } else {
        writeln!(out, "{}", args.file.display())?;
        if let Some(z) = profile.surface_elevation_m {
            writeln!(out, "surface elevation in the file: {z:.1} m")?;
        }
        writeln!(
            out,
            "{:>10} {:>10} {:>9} {:>10} {:>9}",
            "height m", "p hPa", "T °C", "wind m/s", "from deg"
        )?;
        for r in &rows {
            writeln!(
                out,
                "{:>10.1} {:>10.2} {:>9.2} {:>10.2} {:>9.1}",
                r.height_m,
                r.pressure_pa / 100.0,
                r.temperature_k - 273.15,
                r.speed_mps,
                r.from_deg
            )?;
        }
    }
    if let Some(dir) = &args.plot {
        plot(&rows, dir)?;
    }
    Ok(())
}

/// A chart: file stem, title, axis label, `(value, height)` points.
type Chart = (&'static str, &'static str, &'static str, Vec<(f64, f64)>);

/// Temperature, pressure, wind speed and direction against height.
fn plot(rows: &[Level], dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let series = |f: &dyn Fn(&Level) -> f64| rows.iter().map(|r| (f(r), r.height_m)).collect();
    let charts: [Chart; 4] = [
        (
            "temperature",
            "Temperature",
            "temperature (°C)",
            series(&|r| r.temperature_k - 273.15),
        ),
        (
            "pressure",
            "Pressure",
            "pressure (hPa)",
            series(&|r| r.pressure_pa / 100.0),
        ),
        (
            "wind_speed",
            "Wind speed",
            "wind speed (m/s)",
            series(&|r| r.speed_mps),
        ),
        (
            "wind_direction",
            "Wind direction (where it blows from)",
            "direction (deg from north)",
            series(&|r| r.from_deg),
        ),
    ];
    for (file, title, x_label, points) in charts {
        line_chart(
            &dir.join(format!("{file}.svg")),
            title,
            x_label,
            "height ASL (m)",
            &[Series {
                label: file,
                points,
            }],
        )?;
    }
    Ok(())
}
