//! The weather file a mission's `source` names, downloaded into the mission's folder
//! (`karman simulate/montecarlo --fetch`; cargo feature `fetch`). The file is written as the
//! service sent it, beside it a provenance record `FILE.provenance.json` (service, request,
//! time of download); the mission then reads it offline like any other data file, and a
//! Monte Carlo study's data fingerprint covers it.

use crate::assemble::environment::{launch_unix_time, weather_earth_radius};
use crate::schema::WeatherSource;
use crate::{Mission, MissionError, Override};
use karman_atmos::fetch::{Download, Fetcher, Request, Service};
use karman_dispersion::files::write_atomic;
use karman_math::PhysicalConstants;
use std::path::{Path, PathBuf};

/// A file downloaded for a mission.
#[derive(Debug, Clone)]
pub struct Fetched {
    /// Where it was written.
    pub path: PathBuf,
    /// What was downloaded.
    pub download: Download,
}

/// The provenance record of a downloaded weather file: `FILE.provenance.json`.
#[must_use]
pub fn provenance_path(file: &Path) -> PathBuf {
    let mut name = file.file_name().unwrap_or_default().to_os_string();
    name.push(".provenance.json");
    file.with_file_name(name)
}

/// Writes a download to `path` (creating its folder) and its provenance beside it, each
/// atomically.
///
/// # Errors
/// The folder or a file cannot be written (the message names it).
pub fn save(download: &Download, request: &Request, path: &Path) -> Result<(), MissionError> {
    let failed = |source: Box<dyn std::error::Error + Send + Sync>| MissionError::Model {
        file: path.to_owned(),
        location: None,
        section: "weather file".into(),
        source,
    };
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| failed(Box::new(e)))?;
    }
    write_atomic(path, &download.bytes).map_err(|e| failed(Box::new(e)))?;
    write_atomic(
        &provenance_path(path),
        download.provenance(request).as_bytes(),
    )
    .map_err(|e| failed(Box::new(e)))
}

/// The download a mission's `[environment.atmosphere]` asks for: its `source` at the launch
/// site and date of `[environment]` (`station` for Wyoming; Open-Meteo's ensemble API when a
/// `member` is given).
///
/// # Errors
/// [`MissionError::Model`] at `environment.atmosphere.source` when the mission names no
/// source, at `environment.date` when it has no launch date.
pub fn request(mission: &Mission) -> Result<Request, MissionError> {
    let env = &mission.spec.environment;
    let atm = &env.atmosphere;
    let Some(source) = atm.source else {
        return Err(mission.model_error(
            "environment.atmosphere",
            "--fetch needs `source` in [environment.atmosphere] (\"open-meteo\", \"gfs\" or \
             \"wyoming\") and the `file` to write",
        ));
    };
    let unix_time = launch_unix_time(mission).ok_or_else(|| {
        mission.model_error(
            "environment.date",
            "a download needs the launch date (with its offset or Z)",
        )
    })?;
    Ok(Request {
        service: match source {
            WeatherSource::OpenMeteo => Service::OpenMeteo,
            WeatherSource::Gfs => Service::Gfs,
            WeatherSource::Wyoming => Service::Wyoming,
        },
        latitude_deg: env.latitude_deg,
        longitude_deg: env.longitude_deg,
        unix_time,
        station: atm.station.clone(),
        ensemble: source == WeatherSource::OpenMeteo && atm.member.is_some(),
        earth_radius: weather_earth_radius(mission),
        standard_gravity: PhysicalConstants::SI.standard_gravity,
    })
}

/// Downloads what the mission at `path` (with `overrides`) names in `source` into its `file`
/// (relative to the mission), with the provenance beside it. The mission is validated first,
/// except that the file need not exist yet.
///
/// # Errors
/// The mission's own errors, [`request`]'s, the download's (naming the service and the
/// request, at `environment.atmosphere.source`), and a file that cannot be written.
pub fn fetch_source(
    path: &Path,
    overrides: &[Override],
    fetcher: &Fetcher,
) -> Result<Fetched, MissionError> {
    let mission = crate::load_with(path, overrides, true)?;
    let request = request(&mission)?;
    let file = mission
        .spec
        .environment
        .atmosphere
        .file
        .as_ref()
        .map(|f| mission.resolve(f))
        .ok_or_else(|| {
            mission.model_error(
                "environment.atmosphere",
                "--fetch needs the `file` to write the download to",
            )
        })?;
    let download = fetcher
        .fetch(&request)
        .map_err(|e| mission.model_error("environment.atmosphere.source", e))?;
    save(&download, &request, &file)?;
    Ok(Fetched {
        path: file,
        download,
    })
}
