//! Open-Meteo pressure-level forecasts saved as the API's own JSON (docs/physics.md §25.3; the
//! forecast API `/v1/forecast` and the ensemble API `/v1/ensemble`; documentation at
//! <https://open-meteo.com/en/docs>): a profile at one hour and one member, offline.
//!
//! The response holds, under `hourly`, a `time` array and one array per variable and level,
//! named `temperature_850hPa`, `geopotential_height_850hPa`, `wind_speed_850hPa` and
//! `wind_direction_850hPa`; the ensemble API adds `_member01`, `_member02`, ... for the
//! perturbed members (the unsuffixed arrays are the control run, member 0). How a profile is
//! taken from it:
//! - time: the hour nearest the launch, a tie going to the earlier one (as for weather grids);
//!   a launch before the first or after the last hour is an error naming both. Times are Unix
//!   seconds (`timeformat=unixtime`) or ISO 8601 local times shifted by `utc_offset_seconds`;
//! - units from `hourly_units` (°C, °F or K; m/s, km/h, mp/h or kn); without `hourly_units`
//!   the API's defaults (°C, km/h);
//! - the wind direction is the meteorological one (where the wind blows from), so the
//!   eastward wind is `−s sin d` and the northward `−s cos d`;
//! - geopotential height → geometric height `R H/(R − H)` with `R` the datum radius at the
//!   site (as for soundings and grids);
//! - a level with a missing (null) value in any of the four quantities is dropped.

use crate::AtmosError;
use crate::isa::geopotential_to_geometric;
use crate::profile::LevelProfile;
use crate::time::iso8601;
use chrono::NaiveDateTime;
use serde_json::Value;

/// The pressure levels (hPa) the Open-Meteo APIs serve.
pub const LEVELS_HPA: [u32; 19] = [
    1000, 975, 950, 925, 900, 850, 800, 700, 600, 500, 400, 300, 250, 200, 150, 100, 70, 50, 30,
];

/// The four quantities read at every level, as the API names them.
pub const QUANTITIES: [&str; 4] = [
    "temperature",
    "geopotential_height",
    "wind_speed",
    "wind_direction",
];

/// A parsed Open-Meteo response.
#[derive(Debug, Clone, PartialEq)]
pub struct OpenMeteo {
    name: String,
    /// Unix times of the hours.
    times: Vec<f64>,
    /// Grid-cell elevation the API reports (m ASL), if any.
    elevation: Option<f64>,
    /// Number of members (1 for the forecast API).
    members: usize,
    /// The `hourly` object.
    hourly: serde_json::Map<String, Value>,
    /// Kelvin = value × scale + offset.
    temperature: (f64, f64),
    /// m/s per unit of wind speed.
    wind_scale: f64,
}

impl OpenMeteo {
    /// Reads a response; `name` (file or address) is used in messages.
    ///
    /// # Errors
    /// [`AtmosError::Format`] when the bytes are not an Open-Meteo hourly response: not JSON,
    /// an `error` object, no `hourly.time`, times that are not numbers or dates, no level with
    /// all four quantities, a unit it does not know.
    pub fn parse(bytes: &[u8], name: &str) -> Result<OpenMeteo, AtmosError> {
        let bad = |message: String| AtmosError::Format {
            source_name: name.into(),
            expected: "an Open-Meteo hourly JSON response".into(),
            message,
        };
        let json: Value = serde_json::from_slice(bytes).map_err(|e| bad(format!("{e}")))?;
        if json.get("error").and_then(Value::as_bool) == Some(true) {
            let reason = json["reason"].as_str().unwrap_or("no reason given");
            return Err(bad(format!("the service answered with an error: {reason}")));
        }
        let Some(hourly) = json.get("hourly").and_then(Value::as_object).cloned() else {
            return Err(bad("no `hourly` object".into()));
        };
        let offset = json["utc_offset_seconds"].as_f64().unwrap_or(0.0);
        let times = hourly
            .get("time")
            .and_then(Value::as_array)
            .ok_or_else(|| bad("no `hourly.time` array".into()))?
            .iter()
            .enumerate()
            .map(|(i, t)| {
                time_value(t, offset)
                    .ok_or_else(|| bad(format!("hourly.time[{i}] = {t} is not a time")))
            })
            .collect::<Result<Vec<f64>, _>>()?;
        if times.is_empty() {
            return Err(bad("`hourly.time` is empty".into()));
        }
        if let Some(i) = times.windows(2).position(|w| w[1] <= w[0]) {
            return Err(bad(format!(
                "`hourly.time` does not increase at index {}",
                i + 1
            )));
        }
        let units = json.get("hourly_units");
        let unit = |quantity: &str| -> Option<String> {
            let key = format!("{quantity}_{}hPa", LEVELS_HPA[0]);
            units
                .and_then(|u| {
                    u.get(&key).or_else(|| {
                        u.as_object().and_then(|o| {
                            o.iter()
                                .find(|(k, _)| k.starts_with(&format!("{quantity}_")))
                                .map(|(_, v)| v)
                        })
                    })
                })
                .and_then(Value::as_str)
                .map(str::to_owned)
        };
        let temperature = match unit("temperature").as_deref() {
            None | Some("°C" | "C") => (1.0, 273.15),
            Some("°F" | "F") => (5.0 / 9.0, 273.15 - 32.0 * 5.0 / 9.0),
            Some("K") => (1.0, 0.0),
            Some(other) => return Err(bad(format!("unknown temperature unit `{other}`"))),
        };
        let wind_scale = match unit("wind_speed").as_deref() {
            None | Some("km/h") => 1.0 / 3.6,
            Some("m/s") => 1.0,
            Some("mp/h" | "mph") => 0.447_04,
            Some("kn" | "knots") => 1852.0 / 3600.0,
            Some(other) => return Err(bad(format!("unknown wind speed unit `{other}`"))),
        };
        if let Some(other) = unit("geopotential_height").filter(|u| u != "m") {
            return Err(bad(format!("unknown geopotential height unit `{other}`")));
        }
        let mut members = 0usize;
        for key in hourly.keys() {
            let Some(rest) = key.strip_prefix("temperature_") else {
                continue;
            };
            match rest.split_once("hPa") {
                Some((_, "")) => members = members.max(1),
                Some((_, suffix)) => {
                    if let Some(m) = suffix
                        .strip_prefix("_member")
                        .and_then(|n| n.parse::<usize>().ok())
                    {
                        members = members.max(m.saturating_add(1));
                    }
                }
                None => {}
            }
        }
        if members == 0 {
            return Err(bad(
                "no pressure-level temperature (`temperature_1000hPa`, ...)".into(),
            ));
        }
        Ok(OpenMeteo {
            name: name.into(),
            times,
            elevation: json["elevation"].as_f64().filter(|e| e.is_finite()),
            members,
            hourly,
            temperature,
            wind_scale,
        })
    }

    /// Number of members: 1 for the forecast API, the control run and the perturbed
    /// members for the ensemble API.
    #[must_use]
    pub fn members(&self) -> usize {
        self.members
    }

    /// First and last hour (Unix seconds).
    #[must_use]
    pub fn time_span(&self) -> (f64, f64) {
        (self.times[0], self.times[self.times.len() - 1])
    }

    /// The profile at the hour nearest `unix_time`, of `member` (`None`: member 0), with
    /// geometric heights for the Earth radius `earth_radius`.
    ///
    /// # Errors
    /// [`AtmosError::DateOutsideFile`], [`AtmosError::NoSuchMember`], and
    /// [`AtmosError::Empty`] when no level has all four quantities at that hour,
    /// [`AtmosError::OneLevel`] when only one has.
    pub fn profile(
        &self,
        unix_time: f64,
        member: Option<usize>,
        earth_radius: f64,
    ) -> Result<LevelProfile, AtmosError> {
        let member = member.unwrap_or(0);
        if member >= self.members {
            return Err(AtmosError::NoSuchMember {
                file: self.name.clone(),
                member,
                last: self.members - 1,
            });
        }
        let index = self.hour_index(unix_time)?;
        let suffix = if member == 0 {
            String::new()
        } else {
            format!("_member{member:02}")
        };
        let value = |quantity: &str, level: u32| {
            self.hourly
                .get(&format!("{quantity}_{level}hPa{suffix}"))
                .and_then(|a| a.get(index))
                .and_then(Value::as_f64)
                .filter(|v| v.is_finite())
        };
        let mut out = LevelProfile {
            surface_elevation_m: self.elevation,
            ..LevelProfile::default()
        };
        for level in LEVELS_HPA {
            let [Some(t), Some(z), Some(s), Some(d)] = QUANTITIES.map(|q| value(q, level)) else {
                continue;
            };
            let (sin, cos) = d.to_radians().sin_cos();
            let speed = s * self.wind_scale;
            out.pressure_pa.push(f64::from(level) * 100.0);
            out.height_m
                .push(geopotential_to_geometric(z, earth_radius));
            out.temperature_k
                .push(t * self.temperature.0 + self.temperature.1);
            out.wind_u_mps.push(-speed * sin);
            out.wind_v_mps.push(-speed * cos);
        }
        if out.pressure_pa.is_empty() {
            return Err(AtmosError::Empty {
                source_name: self.name.clone(),
                what: format!(
                    "member {member} at {} (no level has temperature, height and wind)",
                    iso8601(self.times[index])
                ),
            });
        }
        // One level gives constant profiles (pressure and density the same at every height):
        // refused, as a flight in them ends nowhere sensible.
        if let [pressure] = out.pressure_pa[..] {
            return Err(AtmosError::OneLevel {
                source_name: self.name.clone(),
                what: format!("member {member} at {}", iso8601(self.times[index])),
                level_hpa: pressure / 100.0,
            });
        }
        Ok(out)
    }

    /// The nearest hour, a tie to the earlier; outside the file's hours → error.
    fn hour_index(&self, t: f64) -> Result<usize, AtmosError> {
        let (first, last) = self.time_span();
        if !(t >= first && t <= last) {
            return Err(AtmosError::DateOutsideFile {
                file: self.name.clone(),
                date: iso8601(t),
                first: iso8601(first),
                last: iso8601(last),
            });
        }
        let right = self
            .times
            .partition_point(|&h| h < t)
            .min(self.times.len() - 1);
        let left = right.saturating_sub(1);
        Ok(
            if (t - self.times[left]).abs() <= (self.times[right] - t).abs() {
                left
            } else {
                right
            },
        )
    }
}

/// A time of `hourly.time`: Unix seconds, or an ISO 8601 local time (`2024-06-01T12:00`)
/// `offset` seconds ahead of UTC.
fn time_value(t: &Value, offset: f64) -> Option<f64> {
    match t {
        Value::Number(n) => n.as_f64().filter(|v| v.is_finite()),
        Value::String(s) => ["%Y-%m-%dT%H:%M", "%Y-%m-%dT%H:%M:%S"]
            .iter()
            .find_map(|f| NaiveDateTime::parse_from_str(s, f).ok())
            .map(|d| d.and_utc().timestamp() as f64 - offset),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn response(extra: &str) -> String {
        format!(
            "{{\"elevation\": 12.0, \"utc_offset_seconds\": 3600, \"hourly_units\": \
             {{\"temperature_1000hPa\": \"°F\", \"wind_speed_1000hPa\": \"kn\"}}, \"hourly\": \
             {{\"time\": [\"2024-06-01T01:00\", \"2024-06-01T02:00\"], \
             \"temperature_1000hPa\": [32, 50], \"geopotential_height_1000hPa\": [100, 110], \
             \"wind_speed_1000hPa\": [10, 20], \"wind_direction_1000hPa\": [90, 0], \
             \"temperature_850hPa\": [20, 30], \"geopotential_height_850hPa\": [1500, 1510], \
             \"wind_speed_850hPa\": [10, 20], \"wind_direction_850hPa\": [90, 0]{extra}}}}}"
        )
    }

    #[test]
    fn units_offsets_and_directions() {
        let om = OpenMeteo::parse(response("").as_bytes(), "om.json").expect("parses");
        assert_eq!(om.members(), 1);
        // 01:00 at UTC+1 is midnight UTC.
        let t0 = crate::time::unix_seconds(2024, 6, 1, 0, 0, 0.0).expect("date");
        assert_eq!(om.time_span(), (t0, t0 + 3600.0));
        let p = om.profile(t0, None, 6.371e6).expect("profile");
        assert!((p.temperature_k[0] - 273.15).abs() < 1e-9);
        // 10 kn from the east blows west.
        assert!((p.wind_u_mps[0] + 10.0 * 1852.0 / 3600.0).abs() < 1e-9);
        assert!(p.wind_v_mps[0].abs() < 1e-9);
        assert_eq!(p.surface_elevation_m, Some(12.0));
        let later = om.profile(t0 + 2000.0, None, 6.371e6).expect("second hour");
        assert!((later.temperature_k[0] - 283.15).abs() < 1e-9);
        let tie = om.profile(t0 + 1800.0, None, 6.371e6).expect("tie");
        assert!(
            (tie.temperature_k[0] - 273.15).abs() < 1e-9,
            "a tie takes the earlier"
        );
    }

    #[test]
    fn a_single_level_is_refused_with_its_file_and_level() {
        let single = response("").replace("_850hPa\"", "_850hPa_member01\"");
        let om = OpenMeteo::parse(single.as_bytes(), "om.json").expect("parses");
        let e = om
            .profile(om.time_span().0, None, 6.371e6)
            .expect_err("one level")
            .to_string();
        assert_eq!(
            e,
            "om.json: member 0 at 2024-06-01T00:00:00Z: only the 1000 hPa level has \
             temperature, height and wind; a profile needs at least two levels"
        );
    }

    #[test]
    fn members_and_errors() {
        let members = ", \"temperature_1000hPa_member02\": [1, 2]";
        let om = OpenMeteo::parse(response(members).as_bytes(), "om.json").expect("parses");
        assert_eq!(om.members(), 3);
        // Member 1 has no data at all, member 2 lacks heights and winds.
        assert!(matches!(
            om.profile(om.time_span().0, Some(2), 6.371e6),
            Err(AtmosError::Empty { .. })
        ));
        assert!(matches!(
            om.profile(om.time_span().0, Some(3), 6.371e6),
            Err(AtmosError::NoSuchMember { last: 2, .. })
        ));
        for (text, needle) in [
            ("{", "EOF"),
            (
                "{\"error\": true, \"reason\": \"Latitude must be in range\"}",
                "Latitude",
            ),
            ("{\"hourly\": {\"time\": []}}", "empty"),
            ("{\"hourly\": {\"time\": [\"noon\"]}}", "not a time"),
            ("{\"hourly\": {\"time\": [3, 2]}}", "does not increase"),
            ("{\"hourly\": {\"time\": [1]}}", "temperature"),
        ] {
            let e = OpenMeteo::parse(text.as_bytes(), "x.json").expect_err(text);
            assert!(e.to_string().contains(needle), "{text}: {e}");
            assert!(e.to_string().contains("x.json"), "{e}");
        }
    }
}
