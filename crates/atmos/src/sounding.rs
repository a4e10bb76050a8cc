//! Upper-air soundings (docs/physics.md §25.1): University of Wyoming TEXT:LIST pages (the bare
//! table or the whole HTML page the service returns) and NOAA RUC soundings (GSD ASCII format,
//! <https://rucsoundings.noaa.gov/raob_format.html>), turned into profiles as RocketPy does
//! (`Environment.process_wyoming_sounding` of 1.13 and `process_noaaruc_sounding` of 1.2, the last
//! version that had it).
//!
//! \[RP\] quirks kept for parity: a Wyoming sounding's pressure, temperature and barometric
//! height use the *reported* (geopotential) heights, only its winds use heights converted to
//! geometric; a RUC sounding uses its heights as they are. Wyoming rows with a missing field
//! are skipped whole (a row with a field that is not a number is an error); RUC rows are
//! filtered per quantity (missing value 99999). Wyoming wind speeds are in the unit the header
//! names: `SKNT` knots (legacy pages), `SPED` m/s (current pages), as RocketPy 1.13 reads them.

use crate::AtmosError;
use crate::curve::Curve;
use crate::error::snippet;
use crate::isa::geopotential_to_geometric;
use crate::profile::{LevelProfile, Profiles};

/// Which service a sounding came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SoundingFormat {
    /// University of Wyoming TEXT:LIST.
    Wyoming,
    /// NOAA RUC soundings, GSD format.
    NoaaRuc,
}

/// One reported level. A field is `None` when the sounding lacks it at this level.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SoundingLevel {
    /// Pressure (Pa).
    pub pressure_pa: Option<f64>,
    /// Height as reported (m; geopotential metres for Wyoming).
    pub height_m: f64,
    /// Temperature (K).
    pub temperature_k: Option<f64>,
    /// Direction the wind comes from (deg, clockwise from north).
    pub wind_direction_deg: Option<f64>,
    /// Wind speed (m/s).
    pub wind_speed_mps: Option<f64>,
}

/// A parsed sounding.
#[derive(Debug, Clone, PartialEq)]
pub struct Sounding {
    /// The service format.
    pub format: SoundingFormat,
    /// Levels in the order of the file.
    pub levels: Vec<SoundingLevel>,
    /// Station elevation (m ASL) when the text gives it. RocketPy replaces the launch
    /// elevation with it; karman keeps the mission's elevation and only reports this value.
    pub station_elevation_m: Option<f64>,
    /// File name, for messages.
    pub source_name: String,
}

/// One knot in m/s (1852 m per hour).
const KNOT: f64 = 1.852 / 3.6;
/// 0 °C in kelvin.
const ZERO_CELSIUS: f64 = 273.15;

impl Sounding {
    /// Parses a Wyoming TEXT:LIST sounding: either the bare table (title, dashed rule, header,
    /// units, dashed rule, rows) or the HTML page with the table in the first `<PRE>` block and
    /// the station information (with "Station elevation") in the second.
    ///
    /// # Errors
    /// [`AtmosError::Parse`] for a header without a wind-speed column, a row with a field that
    /// is not a number, or a complete row (11 fields) with an impossible value;
    /// [`AtmosError::Empty`] when no table or no complete row is found.
    pub fn parse_wyoming(text: &str, source_name: &str) -> Result<Sounding, AtmosError> {
        let (table, table_line0, station) = split_pre_blocks(text);
        let lines: Vec<&str> = table.lines().collect();
        let rules: Vec<usize> = lines
            .iter()
            .enumerate()
            .filter(|(_, l)| {
                let t = l.trim();
                t.len() >= 10 && t.chars().all(|c| c == '-')
            })
            .map(|(i, _)| i)
            .take(2)
            .collect();
        let Some(&start) = rules.get(1) else {
            return Err(AtmosError::Empty {
                source_name: source_name.into(),
                what: "the Wyoming TEXT:LIST table (two dashed rules around its header)".into(),
            });
        };
        // The header names the wind-speed column: SKNT in knots (the legacy CGI pages), SPED
        // in m/s (the current WSGI pages), as RocketPy 1.13 reads it.
        let header = lines.get(rules[0] + 1).copied().unwrap_or("");
        let speed_unit = if header.split_whitespace().any(|c| c == "SKNT") {
            KNOT
        } else if header.split_whitespace().any(|c| c == "SPED") {
            1.0
        } else {
            return Err(AtmosError::Parse {
                source_name: source_name.into(),
                line: table_line0 + rules[0] + 2,
                message: "the header names no wind speed column (SKNT in knots or SPED in m/s)"
                    .into(),
                text: snippet(header),
            });
        };
        let mut levels = Vec::new();
        for (i, line) in lines.iter().enumerate().skip(start + 1) {
            let t = line.trim();
            if t.is_empty() {
                continue;
            }
            if t.contains(':') || t.starts_with(|c: char| c.is_ascii_alphabetic() || c == '<') {
                break; // end of the table (station information follows)
            }
            let fields: Vec<&str> = t.split_whitespace().collect();
            let err = |message: &str| AtmosError::Parse {
                source_name: source_name.into(),
                line: table_line0 + i + 1,
                message: message.into(),
                text: snippet(line),
            };
            // A row that does not parse is an error, never the end of the table.
            let nums: Option<Vec<f64>> = fields.iter().map(|f| f.parse::<f64>().ok()).collect();
            let Some(n) = nums.filter(|n| n.iter().all(|v| v.is_finite())) else {
                return Err(err("expected a row of numbers"));
            };
            if n.len() != 11 {
                continue; // RocketPy keeps only rows with every column
            }
            if n[0] <= 0.0 || n[7] < 0.0 {
                return Err(err("pressure must be positive and wind speed non-negative"));
            }
            levels.push(SoundingLevel {
                pressure_pa: Some(n[0] * 100.0),
                height_m: n[1],
                temperature_k: Some(n[2] + ZERO_CELSIUS),
                wind_direction_deg: Some(n[6]),
                wind_speed_mps: Some(n[7] * speed_unit),
            });
        }
        if levels.is_empty() {
            return Err(AtmosError::Empty {
                source_name: source_name.into(),
                what: "the Wyoming sounding (no row with all 11 columns)".into(),
            });
        }
        let station_elevation_m = station
            .lines()
            .chain(text.lines())
            .find_map(|l| l.trim().strip_prefix("Station elevation:"))
            .and_then(|v| v.split_whitespace().next())
            .and_then(|v| v.parse::<f64>().ok())
            .filter(|v| v.is_finite());
        Ok(Sounding {
            format: SoundingFormat::Wyoming,
            levels,
            station_elevation_m,
            source_name: source_name.into(),
        })
    }

    /// Parses a NOAA RUC sounding in GSD ASCII format: line type 1 carries the station
    /// elevation (column 6), types 4–9 the levels (pressure in 0.1 hPa, height m, temperature
    /// in 0.1 °C, dew point, wind direction deg, wind speed in knots — or m/s when the type-3
    /// line says `ms`); 99999 marks a missing value.
    ///
    /// # Errors
    /// [`AtmosError::Parse`] for a level line whose fields are not numbers,
    /// [`AtmosError::Empty`] when no level has a height and a pressure.
    pub fn parse_noaa_ruc(text: &str, source_name: &str) -> Result<Sounding, AtmosError> {
        const MISSING: f64 = 99_999.0;
        let mut station_elevation_m = None;
        let mut speed_unit = KNOT;
        let mut levels = Vec::new();
        for (i, line) in text.lines().enumerate() {
            let fields: Vec<&str> = line.split_whitespace().collect();
            let Some(&kind) = fields.first() else {
                continue;
            };
            let err = |message: &str| AtmosError::Parse {
                source_name: source_name.into(),
                line: i + 1,
                message: message.into(),
                text: snippet(line),
            };
            match kind {
                "1" => {
                    station_elevation_m = fields
                        .get(5)
                        .and_then(|v| v.parse::<f64>().ok())
                        .filter(|v| v.is_finite() && (*v - MISSING).abs() > 0.5);
                }
                "3" if fields.last().is_some_and(|u| u.eq_ignore_ascii_case("ms")) => {
                    speed_unit = 1.0;
                }
                "4" | "5" | "6" | "7" | "8" | "9" => {
                    if fields.len() < 7 {
                        return Err(err("a level line needs 7 columns"));
                    }
                    let nums: Option<Vec<f64>> =
                        fields[1..7].iter().map(|f| f.parse::<f64>().ok()).collect();
                    let Some(n) = nums.filter(|n| n.iter().all(|v| v.is_finite())) else {
                        return Err(err("expected numbers"));
                    };
                    let have = |v: f64| (v - MISSING).abs() > 0.5;
                    if !have(n[1]) {
                        continue; // no height: nothing can be placed
                    }
                    levels.push(SoundingLevel {
                        pressure_pa: have(n[0]).then_some(n[0] * 10.0).filter(|p| *p > 0.0),
                        height_m: n[1],
                        temperature_k: have(n[2]).then_some(n[2] / 10.0 + ZERO_CELSIUS),
                        wind_direction_deg: (have(n[4]) && have(n[5])).then_some(n[4]),
                        wind_speed_mps: (have(n[4]) && have(n[5])).then_some(n[5] * speed_unit),
                    });
                }
                _ => {}
            }
        }
        if !levels.iter().any(|l| l.pressure_pa.is_some()) {
            return Err(AtmosError::Empty {
                source_name: source_name.into(),
                what: "the RUC sounding (no level with height and pressure)".into(),
            });
        }
        Ok(Sounding {
            format: SoundingFormat::NoaaRuc,
            levels,
            station_elevation_m,
            source_name: source_name.into(),
        })
    }

    /// The levels that have pressure, temperature and wind, as one column with geometric
    /// heights (Wyoming's geopotential heights converted with `earth_radius`), for display.
    #[must_use]
    pub fn level_profile(&self, earth_radius: f64) -> LevelProfile {
        let mut out = LevelProfile {
            surface_elevation_m: self.station_elevation_m,
            ..LevelProfile::default()
        };
        for l in &self.levels {
            let (Some(p), Some(t), Some(d), Some(s)) = (
                l.pressure_pa,
                l.temperature_k,
                l.wind_direction_deg,
                l.wind_speed_mps,
            ) else {
                continue;
            };
            let (sin, cos) = d.to_radians().sin_cos();
            out.pressure_pa.push(p);
            out.height_m.push(match self.format {
                SoundingFormat::Wyoming => geopotential_to_geometric(l.height_m, earth_radius),
                SoundingFormat::NoaaRuc => l.height_m,
            });
            out.temperature_k.push(t);
            out.wind_u_mps.push(-s * sin);
            out.wind_v_mps.push(-s * cos);
        }
        out
    }

    /// The profiles RocketPy builds from this sounding; `earth_radius` (m, the datum radius
    /// at the launch latitude) converts Wyoming's geopotential heights for the winds.
    ///
    /// # Errors
    /// [`AtmosError::Empty`] when a quantity has no value at any level.
    pub fn profiles(&self, earth_radius: f64) -> Result<Profiles, AtmosError> {
        let wind_height = |h: f64| match self.format {
            SoundingFormat::Wyoming => geopotential_to_geometric(h, earth_radius),
            SoundingFormat::NoaaRuc => h,
        };
        let mut pressure = Vec::new();
        let mut temperature = Vec::new();
        let mut wind_u = Vec::new();
        let mut wind_v = Vec::new();
        for l in &self.levels {
            if let Some(p) = l.pressure_pa {
                pressure.push([l.height_m, p]);
            }
            if let Some(t) = l.temperature_k {
                temperature.push([l.height_m, t]);
            }
            if let (Some(dir), Some(speed)) = (l.wind_direction_deg, l.wind_speed_mps) {
                // Heading (where the air goes) = direction + 180°.
                let heading = ((dir + 180.0) % 360.0).to_radians();
                let h = wind_height(l.height_m);
                wind_u.push([h, speed * heading.sin()]);
                wind_v.push([h, speed * heading.cos()]);
            }
        }
        let need = |v: &Vec<[f64; 2]>, what: &str| {
            if v.is_empty() {
                Err(AtmosError::Empty {
                    source_name: self.source_name.clone(),
                    what: format!("{what} in the sounding"),
                })
            } else {
                Ok(())
            }
        };
        need(&pressure, "pressure")?;
        need(&temperature, "temperature")?;
        need(&wind_u, "wind")?;
        let barometric = pressure.iter().map(|&[h, p]| [p, h]).collect();
        Ok(Profiles {
            source_name: self.source_name.clone(),
            pressure: Some(Curve::Points(pressure)),
            temperature: Some(Curve::Points(temperature)),
            wind_u: Curve::Points(wind_u),
            wind_v: Curve::Points(wind_v),
            barometric_points: Some(barometric),
        })
    }
}

/// Splits a Wyoming page into (table text, line offset of the table, station-info text). A
/// text without `<PRE>` blocks is a bare table.
fn split_pre_blocks(text: &str) -> (&str, usize, &str) {
    let lower = text.to_ascii_lowercase();
    let Some(open) = lower.find("<pre>") else {
        return (text, 0, "");
    };
    let body_start = open + "<pre>".len();
    let body_end = lower[body_start..]
        .find("</pre>")
        .map_or(text.len(), |e| body_start + e);
    let table = &text[body_start..body_end];
    let line0 = text[..body_start].matches('\n').count();
    let rest = &lower[body_end..];
    let station = rest
        .find("<pre>")
        .map(|s| body_end + s + "<pre>".len())
        .map(|s| {
            let e = lower[s..].find("</pre>").map_or(text.len(), |e| s + e);
            &text[s..e]
        })
        .unwrap_or("");
    (table, line0, station)
}

#[cfg(test)]
mod tests {
    use super::*;

    const TABLE: &str = "\
12345 Somewhere Observations at 12Z 10 Apr 2006

-----------------------------------------------------------------------------
   PRES   HGHT   TEMP   DWPT   RELH   MIXR   DRCT   SKNT   THTA   THTE   THTV
    hPa     m      C      C      %    g/kg    deg   knot     K      K      K
-----------------------------------------------------------------------------
 1000.0     38
  992.0    103    1.6    0.8     94   4.11    270     10  275.4  286.7  276.1
  850.0   1325   -6.5  -10.0     76   2.11    180      3  279.3  285.5  279.7
";

    #[test]
    fn wyoming_winds_in_knots_and_in_m_per_s_agree() {
        let knots = Sounding::parse_wyoming(TABLE, "t.txt").expect("parses");
        // The same table from a current page: SPED in m/s.
        let speeds: String = TABLE
            .lines()
            .map(|l| {
                let f: Vec<&str> = l.split_whitespace().collect();
                if f.len() == 11 && f[7].parse::<f64>().is_ok() {
                    let v = f[7].parse::<f64>().unwrap_or(0.0) * KNOT;
                    let mut out: Vec<String> = f.iter().map(|s| (*s).to_owned()).collect();
                    out[7] = format!("{v:.17}");
                    out.join("  ")
                } else {
                    l.replace("SKNT", "SPED").replace("knot", " m/s")
                }
            })
            .collect::<Vec<_>>()
            .join("\n");
        let mps = Sounding::parse_wyoming(&speeds, "t.txt").expect("parses");
        assert_eq!(knots.levels.len(), mps.levels.len());
        for (a, b) in knots.levels.iter().zip(&mps.levels) {
            let (a, b) = (
                a.wind_speed_mps.unwrap_or(-1.0),
                b.wind_speed_mps.unwrap_or(-2.0),
            );
            assert!((a - b).abs() < 1e-12, "{a} vs {b}");
        }
        let no_unit = TABLE.replace("SKNT", "WIND");
        let e = Sounding::parse_wyoming(&no_unit, "t.txt").unwrap_err();
        assert!(e.to_string().contains("line 4"), "{e}");
    }

    #[test]
    fn a_wyoming_row_that_does_not_parse_is_an_error() {
        let bad = TABLE.replace("  850.0   1325", "  850.0   13x5");
        let e = Sounding::parse_wyoming(&bad, "t.txt").unwrap_err();
        assert!(e.to_string().starts_with("t.txt, line 9:"), "{e}");
        let short = TABLE.replace("  850.0   1325   -6.5", "  850.0   1O25");
        let e = Sounding::parse_wyoming(&short, "t.txt").unwrap_err();
        assert!(e.to_string().starts_with("t.txt, line 9:"), "{e}");
    }

    #[test]
    fn bare_wyoming_table() {
        let s = Sounding::parse_wyoming(TABLE, "t.txt").expect("parses");
        assert_eq!(s.levels.len(), 2);
        let l = s.levels[0];
        assert!((l.pressure_pa.unwrap_or(0.0) - 99_200.0).abs() < 1e-9);
        assert!((l.temperature_k.unwrap_or(0.0) - 274.75).abs() < 1e-9);
        let p = s.profiles(6_378_137.0).expect("profiles");
        // Wind from 270° (west) blows east: u = +10 kt, v ≈ 0.
        let Curve::Points(u) = &p.wind_u else {
            panic!("table")
        };
        assert!((u[0][1] - 10.0 * KNOT).abs() < 1e-12);
        assert!(u[0][0] > 103.0); // geometric height above the geopotential one
        assert_eq!(s.station_elevation_m, None);
    }

    #[test]
    fn html_wyoming_page() {
        let page = format!(
            "<HTML><BODY><H2>title</H2>\n<PRE>\n{}</PRE><H3>Station information</H3><PRE>\n\
             Station identifier: XYZ\n Station elevation: 38.0\n</PRE></BODY></HTML>",
            TABLE
                .split_once('\n')
                .map_or("", |x| x.1)
                .trim_start_matches('\n')
        );
        let s = Sounding::parse_wyoming(&page, "page.html").expect("parses");
        assert_eq!(s.levels.len(), 2);
        assert_eq!(s.station_elevation_m, Some(38.0));
    }

    #[test]
    fn malformed_wyoming_rows() {
        let bad = TABLE.replace("  850.0   1325", "  850.0   13x5");
        let e = Sounding::parse_wyoming(&bad, "bad.txt").expect_err("fails");
        assert!(matches!(e, AtmosError::Parse { line: 9, .. }), "{e}");
        assert!(Sounding::parse_wyoming("nothing here", "x").is_err());
    }

    #[test]
    fn ruc_sounding() {
        let text = "    254     12      8   29    Jan    2019\n\
                    \x20     1  23062  72493  37.73 122.22     32  99999\n\
                    \x20     3           OAK                   99999     kt\n\
                    \x20     9  10160     32    137    119    300      7\n\
                    \x20     4  10000    138    134    117  99999  99999\n";
        let s = Sounding::parse_noaa_ruc(text, "ruc.txt").expect("parses");
        assert_eq!(s.station_elevation_m, Some(32.0));
        assert_eq!(s.levels.len(), 2);
        assert!((s.levels[0].pressure_pa.unwrap_or(0.0) - 101_600.0).abs() < 1e-9);
        assert!(s.levels[1].wind_speed_mps.is_none());
        assert!(Sounding::parse_noaa_ruc("      4  10000    1x8", "bad").is_err());
    }
}
