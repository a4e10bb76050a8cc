//! Live weather download (docs/physics.md §25.4; cargo feature `fetch`; HTTPS through `reqwest`
//! with rustls, no system TLS library). Each service's answer is kept as it came (the file a
//! mission then reads offline) after checking that it holds a profile at the site and time:
//! - University of Wyoming soundings by station and date (the service's `wsgi/sounding`
//!   TEXT:LIST page), read by [`Sounding::parse_wyoming`];
//! - GFS 0.25° through UCAR THREDDS' NetCDF Subset Service (a small netCDF-3 box around the
//!   site at the launch time), read by [`WeatherGrid`];
//! - Open-Meteo's pressure-level forecast (`/v1/forecast`) or ensemble (`/v1/ensemble`, GFS
//!   ensemble 0.5°) API, JSON read by [`OpenMeteo`]: the launch day and the next, 19 levels
//!   from 1000 to 30 hPa.
//!
//! Every failure is an [`AtmosError::Download`] naming the service and the whole request: no
//! answer within the timeout, an HTTP error status (with the service's reason when it gives
//! one, e.g. a date outside the forecast range), a body cut short, a body that is not in the
//! service's format (it changed, or holds no data for the site and time), a site or date the
//! answer does not cover. The service addresses are fields of [`Endpoints`], so tests point
//! them at a loopback server. Nothing here runs unless called.

use crate::AtmosError;
use crate::grid::{GridRequest, WeatherGrid};
use crate::open_meteo::{LEVELS_HPA, OpenMeteo, QUANTITIES};
use crate::profile::LevelProfile;
use crate::sounding::Sounding;
use crate::time::{iso8601, utc_date};
use chrono::Datelike;
use std::time::{Duration, SystemTime, UNIX_EPOCH};

/// Base addresses of the services.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Endpoints {
    /// Wyoming sounding page, e.g. `https://weather.uwyo.edu/wsgi/sounding`.
    pub wyoming: String,
    /// THREDDS NCSS dataset, e.g.
    /// `https://thredds.ucar.edu/thredds/ncss/grid/grib/NCEP/GFS/Global_0p25deg/Best`.
    pub gfs_ncss: String,
    /// Open-Meteo forecast API, e.g. `https://api.open-meteo.com/v1/forecast`.
    pub open_meteo: String,
    /// Open-Meteo ensemble API, e.g. `https://ensemble-api.open-meteo.com/v1/ensemble`.
    pub open_meteo_ensemble: String,
}

impl Default for Endpoints {
    fn default() -> Self {
        Endpoints {
            wyoming: "https://weather.uwyo.edu/wsgi/sounding".into(),
            gfs_ncss:
                "https://thredds.ucar.edu/thredds/ncss/grid/grib/NCEP/GFS/Global_0p25deg/Best"
                    .into(),
            open_meteo: "https://api.open-meteo.com/v1/forecast".into(),
            open_meteo_ensemble: "https://ensemble-api.open-meteo.com/v1/ensemble".into(),
        }
    }
}

/// A weather service.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Service {
    /// Open-Meteo (JSON).
    OpenMeteo,
    /// GFS through THREDDS NCSS (netCDF).
    Gfs,
    /// University of Wyoming soundings (TEXT:LIST page).
    Wyoming,
}

impl Service {
    /// Every service, by its command-line name.
    pub const ALL: [(&'static str, Service); 3] = [
        ("open-meteo", Service::OpenMeteo),
        ("gfs", Service::Gfs),
        ("wyoming", Service::Wyoming),
    ];

    /// The service of a command-line name (`open-meteo`, `gfs`, `wyoming`).
    #[must_use]
    pub fn parse(name: &str) -> Option<Service> {
        Self::ALL
            .iter()
            .find(|(n, _)| n.eq_ignore_ascii_case(name.trim()))
            .map(|&(_, s)| s)
    }

    /// The command-line name.
    #[must_use]
    pub fn name(self) -> &'static str {
        Self::ALL
            .iter()
            .find(|(_, s)| *s == self)
            .map_or("", |(n, _)| n)
    }

    /// The service as messages name it.
    #[must_use]
    pub fn title(self) -> &'static str {
        match self {
            Service::OpenMeteo => "Open-Meteo",
            Service::Gfs => "GFS (THREDDS NCSS)",
            Service::Wyoming => "University of Wyoming soundings",
        }
    }
}

/// What to download.
#[derive(Debug, Clone, PartialEq)]
pub struct Request {
    /// The service.
    pub service: Service,
    /// Launch latitude (deg).
    pub latitude_deg: f64,
    /// Launch longitude (deg).
    pub longitude_deg: f64,
    /// Launch time, Unix seconds (UTC).
    pub unix_time: f64,
    /// Sounding station (WMO number or ICAO id; Wyoming only).
    pub station: Option<String>,
    /// Every member of the ensemble forecast (Open-Meteo only).
    pub ensemble: bool,
    /// Earth radius (m) for geopotential → geometric heights when checking the answer.
    pub earth_radius: f64,
    /// Standard gravity g0 (m/s²) dividing a grid's geopotential.
    pub standard_gravity: f64,
}

/// A checked answer: its bytes as the service sent them, and where they came from.
#[derive(Debug, Clone, PartialEq)]
pub struct Download {
    /// The service.
    pub service: Service,
    /// The request: the address with its query.
    pub request: String,
    /// The body.
    pub bytes: Vec<u8>,
    /// Time of the download, Unix seconds (UTC).
    pub downloaded_unix: f64,
    /// The profile at the site and time (member 0), as the check read it.
    pub profile: LevelProfile,
    /// Number of ensemble members in the answer (1 without members).
    pub members: usize,
}

impl Download {
    /// The provenance record kept beside the file (JSON): service, request, time of the
    /// download, the request's site and time, and the members.
    #[must_use]
    pub fn provenance(&self, request: &Request) -> String {
        let value = serde_json::json!({
            "service": self.service.name(),
            "request": self.request,
            "downloaded": iso8601(self.downloaded_unix),
            "latitude": request.latitude_deg,
            "longitude": request.longitude_deg,
            "date": iso8601(request.unix_time),
            "station": request.station,
            "members": self.members,
            "bytes": self.bytes.len(),
            "karman": env!("CARGO_PKG_VERSION"),
        });
        let mut text = serde_json::to_string_pretty(&value).unwrap_or_default();
        text.push('\n');
        text
    }
}

/// A blocking HTTP client for the weather services.
#[derive(Debug, Clone)]
pub struct Fetcher {
    client: reqwest::blocking::Client,
    endpoints: Endpoints,
    timeout: Duration,
}

impl Fetcher {
    /// A client whose requests give up after `timeout` (connection and whole answer).
    ///
    /// # Errors
    /// [`AtmosError::Download`] when the TLS backend cannot be set up.
    pub fn new(endpoints: Endpoints, timeout: Duration) -> Result<Fetcher, AtmosError> {
        let client = reqwest::blocking::Client::builder()
            .timeout(timeout)
            .connect_timeout(timeout)
            .user_agent(concat!("karman/", env!("CARGO_PKG_VERSION")))
            .build()
            .map_err(|e| AtmosError::Download {
                service: "HTTP client".into(),
                request: "(setup)".into(),
                message: e.to_string(),
            })?;
        Ok(Fetcher {
            client,
            endpoints,
            timeout,
        })
    }

    /// Downloads what `request` names and checks that it holds a profile at its site and
    /// time (module docs).
    ///
    /// # Errors
    /// [`AtmosError::Download`] naming the service and the request (also for a Wyoming
    /// request without a station); [`AtmosError::InvalidValue`] for a latitude, longitude or
    /// date that is not one.
    pub fn fetch(&self, request: &Request) -> Result<Download, AtmosError> {
        let (url, query) = self.query(request)?;
        let service = request.service;
        let full = self
            .client
            .get(&url)
            .query(&query)
            .build()
            .map(|r| r.url().to_string())
            .unwrap_or_else(|_| url.clone());
        let shown = karman_math::text::shorten(&full, REQUEST_SHOWN).into_owned();
        let fail = |message: String| AtmosError::Download {
            service: service.title().into(),
            request: shown.clone(),
            message,
        };
        let seconds = self.timeout.as_secs_f64();
        let transport = |e: &reqwest::Error, reading: bool| {
            if e.is_timeout() {
                format!("no complete answer within {seconds} s (timeout)")
            } else if e.is_connect() {
                format!("cannot connect: {}", cause_chain(e))
            } else if reading || e.is_body() || e.is_decode() {
                format!("the answer was cut short: {}", cause_chain(e))
            } else {
                cause_chain(e)
            }
        };
        let response = self
            .client
            .get(&url)
            .query(&query)
            .send()
            .map_err(|e| fail(transport(&e, false)))?;
        let status = response.status();
        let bytes = response
            .bytes()
            .map_err(|e| fail(transport(&e, true)))?
            .to_vec();
        if !status.is_success() {
            return Err(fail(format!(
                "HTTP {status}{}",
                reason(&bytes).map_or_else(String::new, |r| format!(": {r}"))
            )));
        }
        let downloaded_unix = SystemTime::now()
            .duration_since(UNIX_EPOCH)
            .map_or(0.0, |d| d.as_secs_f64());
        let (profile, members) = check(request, &bytes, &full).map_err(|e| {
            fail(match e {
                AtmosError::DateOutsideFile { .. } | AtmosError::SiteOutsideGrid { .. } => {
                    format!("the answer does not cover the launch: {e}")
                }
                _ => format!(
                    "the answer is not what the service sends for a site and time it covers \
                     (did its format change?): {e}"
                ),
            })
        })?;
        Ok(Download {
            service,
            request: full.clone(),
            bytes,
            downloaded_unix,
            profile,
            members,
        })
    }

    /// The address and query of a request.
    fn query(&self, request: &Request) -> Result<(String, Vec<(String, String)>), AtmosError> {
        let (lat, lon, t) = (
            request.latitude_deg,
            request.longitude_deg,
            request.unix_time,
        );
        let invalid = |what: &str, value: f64, reason: &str| AtmosError::InvalidValue {
            what: what.into(),
            value,
            reason: reason.into(),
        };
        if !(-90.0..=90.0).contains(&lat) {
            return Err(invalid("latitude", lat, "must be within ±90°"));
        }
        if !lon.is_finite() {
            return Err(invalid("longitude", lon, "must be finite"));
        }
        let Some(day) = utc_date(t) else {
            return Err(invalid("date", t, "is not a date"));
        };
        let pair = |k: &str, v: String| (k.to_string(), v);
        Ok(match request.service {
            Service::Wyoming => {
                let station = request
                    .station
                    .as_deref()
                    .map(str::trim)
                    .filter(|s| !s.is_empty())
                    .ok_or_else(|| AtmosError::Download {
                        service: Service::Wyoming.title().into(),
                        request: self.endpoints.wyoming.clone(),
                        message: "a sounding is asked for by station: give its WMO number or \
                                  ICAO id"
                            .into(),
                    })?;
                let stamp = iso8601(t).replace('T', " ").replace('Z', "");
                (
                    self.endpoints.wyoming.clone(),
                    vec![
                        pair("datetime", stamp),
                        pair("id", station.to_string()),
                        pair("type", "TEXT:LIST".into()),
                    ],
                )
            }
            Service::Gfs => {
                let mut query: Vec<(String, String)> = [
                    "Temperature_isobaric",
                    "Geopotential_height_isobaric",
                    "u-component_of_wind_isobaric",
                    "v-component_of_wind_isobaric",
                ]
                .iter()
                .map(|v| pair("var", (*v).to_string()))
                .collect();
                for (key, value) in [
                    ("north", lat + 0.5),
                    ("south", lat - 0.5),
                    ("east", lon + 0.5),
                    ("west", lon - 0.5),
                ] {
                    query.push(pair(key, format!("{value:.4}")));
                }
                query.push(pair("horizStride", "1".into()));
                query.push(pair("time", iso8601(t)));
                query.push(pair("accept", "netcdf3".into()));
                (self.endpoints.gfs_ncss.clone(), query)
            }
            Service::OpenMeteo => {
                let hourly: Vec<String> = LEVELS_HPA
                    .iter()
                    .flat_map(|l| QUANTITIES.iter().map(move |q| format!("{q}_{l}hPa")))
                    .collect();
                let next = day.succ_opt().unwrap_or(day);
                let date = |d: chrono::NaiveDate| {
                    format!("{:04}-{:02}-{:02}", d.year(), d.month(), d.day())
                };
                let mut query = vec![
                    pair("latitude", format!("{lat:.5}")),
                    pair("longitude", format!("{lon:.5}")),
                    pair("hourly", hourly.join(",")),
                    pair("wind_speed_unit", "ms".into()),
                    pair("temperature_unit", "celsius".into()),
                    pair("timeformat", "unixtime".into()),
                    pair("start_date", date(day)),
                    pair("end_date", date(next)),
                ];
                let url = if request.ensemble {
                    query.push(pair("models", "gfs05".into()));
                    self.endpoints.open_meteo_ensemble.clone()
                } else {
                    self.endpoints.open_meteo.clone()
                };
                (url, query)
            }
        })
    }
}

/// Reads the answer as a mission will: the profile at the site and time, and the members.
fn check(request: &Request, bytes: &[u8], name: &str) -> Result<(LevelProfile, usize), AtmosError> {
    match request.service {
        Service::Wyoming => {
            let text = String::from_utf8_lossy(bytes);
            let sounding = Sounding::parse_wyoming(&text, name)?;
            sounding.profiles(request.earth_radius)?;
            Ok((sounding.level_profile(request.earth_radius), 1))
        }
        Service::Gfs => {
            let grid = WeatherGrid::from_bytes(bytes.to_vec(), name)?;
            let profile = grid.profile(&GridRequest {
                dictionary: None,
                unix_time: request.unix_time,
                latitude_deg: request.latitude_deg,
                longitude_deg: request.longitude_deg,
                member: None,
                earth_radius: request.earth_radius,
                standard_gravity: request.standard_gravity,
            })?;
            Ok((profile, 1))
        }
        Service::OpenMeteo => {
            let om = OpenMeteo::parse(bytes, name)?;
            let profile = om.profile(request.unix_time, None, request.earth_radius)?;
            Ok((profile, om.members()))
        }
    }
}

/// The reason an error answer gives: Open-Meteo's JSON `reason`, else the first line of text.
fn reason(body: &[u8]) -> Option<String> {
    if let Ok(json) = serde_json::from_slice::<serde_json::Value>(body) {
        if let Some(r) = json.get("reason").and_then(serde_json::Value::as_str) {
            return Some(r.to_owned());
        }
    }
    let text = String::from_utf8_lossy(body);
    let line = text
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty() && !l.starts_with('<'))?;
    Some(crate::error::snippet(line))
}

/// An error with its sources, `a: b: c`.
/// How much of a request's address an error message shows: an Open-Meteo query naming every
/// pressure level runs to kilobytes, and the message is one line a person reads.
const REQUEST_SHOWN: usize = 240;

/// The causes of a transport error, innermost last, without the top error's own text
/// (reqwest's names the address, which the message gives once, after the cause); the top
/// text when there is no cause.
fn cause_chain(e: &reqwest::Error) -> String {
    match std::error::Error::source(e) {
        Some(source) => error_chain(source),
        None => e.to_string(),
    }
}

fn error_chain(e: &dyn std::error::Error) -> String {
    let mut text = e.to_string();
    let mut source = e.source();
    while let Some(s) = source {
        let next = s.to_string();
        if !text.contains(&next) {
            text.push_str(": ");
            text.push_str(&next);
        }
        source = s.source();
    }
    text
}
