//! Live weather download (cargo feature `fetch`; HTTPS through `reqwest` with rustls, no
//! system TLS library):
//! - University of Wyoming soundings by station and date (the service's current
//!   `wsgi/sounding` TEXT:LIST page), parsed by [`Sounding::parse_wyoming`];
//! - GFS 0.25° through UCAR THREDDS' NetCDF Subset Service (a small netCDF-3 box around the
//!   site at the launch time), read by [`WeatherGrid`] with the GFS variable names;
//! - Open-Meteo's pressure-level forecast API (JSON): temperature, geopotential height and
//!   wind on 19 levels from 1000 to 30 hPa.
//!
//! The service addresses are fields of [`Endpoints`], so tests point them at a loopback
//! server. Nothing here runs unless called.

use crate::AtmosError;
use crate::grid::{GridDictionary, GridRequest, WeatherGrid};
use crate::isa::geopotential_to_geometric;
use crate::profile::LevelProfile;
use crate::sounding::Sounding;
use crate::time::{iso8601, utc_date};
use chrono::Datelike;
use std::time::Duration;

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
}

impl Default for Endpoints {
    fn default() -> Self {
        Endpoints {
            wyoming: "https://weather.uwyo.edu/wsgi/sounding".into(),
            gfs_ncss:
                "https://thredds.ucar.edu/thredds/ncss/grid/grib/NCEP/GFS/Global_0p25deg/Best"
                    .into(),
            open_meteo: "https://api.open-meteo.com/v1/forecast".into(),
        }
    }
}

/// Open-Meteo's pressure levels (hPa).
const OPEN_METEO_LEVELS: [u32; 19] = [
    1000, 975, 950, 925, 900, 850, 800, 700, 600, 500, 400, 300, 250, 200, 150, 100, 70, 50, 30,
];

/// A blocking HTTP client for the weather services.
#[derive(Debug, Clone)]
pub struct Fetcher {
    client: reqwest::blocking::Client,
    endpoints: Endpoints,
}

impl Fetcher {
    /// A client with a 60 s timeout.
    ///
    /// # Errors
    /// [`AtmosError::Download`] when the TLS backend cannot be set up.
    pub fn new(endpoints: Endpoints) -> Result<Fetcher, AtmosError> {
        let client = reqwest::blocking::Client::builder()
            .timeout(Duration::from_secs(60))
            .user_agent(concat!("karman/", env!("CARGO_PKG_VERSION")))
            .build()
            .map_err(|e| download_err("(client setup)", &e))?;
        Ok(Fetcher { client, endpoints })
    }

    fn get(&self, url: &str, query: &[(String, String)]) -> Result<Vec<u8>, AtmosError> {
        let response = self
            .client
            .get(url)
            .query(query)
            .send()
            .and_then(reqwest::blocking::Response::error_for_status)
            .map_err(|e| download_err(url, &e))?;
        let bytes = response.bytes().map_err(|e| download_err(url, &e))?;
        Ok(bytes.to_vec())
    }

    /// The Wyoming sounding of station `station` (WMO number or ICAO id) at `unix_time`
    /// (a synoptic hour, usually 00Z or 12Z).
    ///
    /// # Errors
    /// Download failures and [`Sounding::parse_wyoming`]'s errors (e.g. no sounding then).
    pub fn wyoming_sounding(&self, station: &str, unix_time: f64) -> Result<Sounding, AtmosError> {
        let stamp = iso8601(unix_time).replace('T', " ").replace('Z', "");
        let query = vec![
            ("datetime".to_string(), stamp),
            ("id".to_string(), station.to_string()),
            ("type".to_string(), "TEXT:LIST".to_string()),
        ];
        let body = self.get(&self.endpoints.wyoming, &query)?;
        let text = String::from_utf8_lossy(&body);
        Sounding::parse_wyoming(
            &text,
            &format!("Wyoming sounding {station} {}", iso8601(unix_time)),
        )
    }

    /// The GFS profile at the site and time through the NetCDF Subset Service: a ±0.5° box,
    /// the time step nearest `unix_time`, then [`WeatherGrid::profile`] (bilinear in space).
    ///
    /// # Errors
    /// Download failures and [`WeatherGrid`]'s errors.
    pub fn gfs_profile(&self, request: &GridRequest) -> Result<LevelProfile, AtmosError> {
        let (lat, lon) = (request.latitude_deg, request.longitude_deg);
        let mut query: Vec<(String, String)> = [
            "Temperature_isobaric",
            "Geopotential_height_isobaric",
            "u-component_of_wind_isobaric",
            "v-component_of_wind_isobaric",
        ]
        .iter()
        .map(|v| ("var".to_string(), (*v).to_string()))
        .collect();
        for (key, value) in [
            ("north", lat + 0.5),
            ("south", lat - 0.5),
            ("east", lon + 0.5),
            ("west", lon - 0.5),
        ] {
            query.push((key.into(), format!("{value:.4}")));
        }
        query.push(("horizStride".into(), "1".into()));
        query.push(("time".into(), iso8601(request.unix_time)));
        query.push(("accept".into(), "netcdf3".into()));
        let body = self.get(&self.endpoints.gfs_ncss, &query)?;
        let grid = WeatherGrid::from_bytes(body, "GFS (THREDDS NCSS)")?;
        // The subset names its time and level dimensions after the variable (time, time1,
        // isobaric, isobaric2, ...): take them from the temperature variable.
        let mut dictionary = GridDictionary::builtin("GFS")?;
        if let Some(dims) = grid.variable_dimensions(&dictionary.temperature) {
            if let [time, level, ..] = dims.as_slice() {
                dictionary.time.clone_from(time);
                dictionary.level.clone_from(level);
            }
        }
        let request = GridRequest {
            dictionary: Some(dictionary),
            ..request.clone()
        };
        grid.profile(&request)
    }

    /// The Open-Meteo pressure-level profile at the site, at the forecast hour nearest
    /// `unix_time` (a tie goes to the earlier hour). Levels with a missing value are dropped;
    /// geopotential heights become geometric with `earth_radius`.
    ///
    /// # Errors
    /// Download failures, a malformed response, a time outside the returned day.
    pub fn open_meteo_profile(
        &self,
        latitude_deg: f64,
        longitude_deg: f64,
        unix_time: f64,
        earth_radius: f64,
    ) -> Result<LevelProfile, AtmosError> {
        let mut hourly = Vec::new();
        for l in OPEN_METEO_LEVELS {
            for q in [
                "temperature",
                "geopotential_height",
                "wind_speed",
                "wind_direction",
            ] {
                hourly.push(format!("{q}_{l}hPa"));
            }
        }
        let day = utc_date(unix_time).unwrap_or_default();
        let date = format!("{:04}-{:02}-{:02}", day.year(), day.month(), day.day());
        let query = vec![
            ("latitude".to_string(), format!("{latitude_deg:.5}")),
            ("longitude".to_string(), format!("{longitude_deg:.5}")),
            ("hourly".to_string(), hourly.join(",")),
            ("wind_speed_unit".to_string(), "ms".to_string()),
            ("timeformat".to_string(), "unixtime".to_string()),
            ("start_date".to_string(), date.clone()),
            ("end_date".to_string(), date),
        ];
        let url = self.endpoints.open_meteo.clone();
        let body = self.get(&url, &query)?;
        parse_open_meteo(&body, unix_time, earth_radius, &url)
    }
}

/// Reads an Open-Meteo hourly pressure-level response.
fn parse_open_meteo(
    body: &[u8],
    unix_time: f64,
    earth_radius: f64,
    url: &str,
) -> Result<LevelProfile, AtmosError> {
    let bad = |message: &str| AtmosError::Download {
        url: url.into(),
        message: message.into(),
    };
    let json: serde_json::Value =
        serde_json::from_slice(body).map_err(|e| bad(&format!("not JSON: {e}")))?;
    let hourly = &json["hourly"];
    let times: Vec<f64> = hourly["time"]
        .as_array()
        .ok_or_else(|| bad("no hourly.time"))?
        .iter()
        .map(|t| t.as_f64().unwrap_or(f64::NAN))
        .collect();
    if times.is_empty() || times.iter().any(|t| !t.is_finite()) {
        return Err(bad("hourly.time is empty or not numeric"));
    }
    let (first, last) = (times[0], times[times.len() - 1]);
    if !(unix_time >= first && unix_time <= last) {
        return Err(AtmosError::DateOutsideFile {
            file: url.into(),
            date: iso8601(unix_time),
            first: iso8601(first),
            last: iso8601(last),
        });
    }
    let right = times
        .partition_point(|&t| t < unix_time)
        .min(times.len() - 1);
    let left = right.saturating_sub(1);
    let index = if (unix_time - times[left]).abs() <= (times[right] - unix_time).abs() {
        left
    } else {
        right
    };
    let value = |name: String| {
        hourly[name.as_str()]
            .get(index)
            .and_then(serde_json::Value::as_f64)
    };
    let mut out = LevelProfile {
        surface_elevation_m: json["elevation"].as_f64(),
        ..LevelProfile::default()
    };
    for l in OPEN_METEO_LEVELS {
        let t = value(format!("temperature_{l}hPa"));
        let z = value(format!("geopotential_height_{l}hPa"));
        let s = value(format!("wind_speed_{l}hPa"));
        let dir = value(format!("wind_direction_{l}hPa"));
        let (Some(t), Some(z), Some(s), Some(dir)) = (t, z, s, dir) else {
            continue;
        };
        let heading = ((dir + 180.0) % 360.0).to_radians();
        out.pressure_pa.push(f64::from(l) * 100.0);
        out.height_m
            .push(geopotential_to_geometric(z, earth_radius));
        out.temperature_k.push(t + 273.15);
        out.wind_u_mps.push(s * heading.sin());
        out.wind_v_mps.push(s * heading.cos());
    }
    if out.pressure_pa.is_empty() {
        return Err(bad(
            "no pressure level has all of temperature, height and wind",
        ));
    }
    Ok(out)
}

fn download_err(url: &str, e: &reqwest::Error) -> AtmosError {
    AtmosError::Download {
        url: url.into(),
        message: e.to_string(),
    }
}
