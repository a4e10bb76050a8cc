//! Weather grids in netCDF (docs/physics.md §25.2; classic CDF-1/2/5 and netCDF-4/HDF5, read with
//! the pure-Rust `netcdf-reader`): reanalyses (ERA5 with its current `valid_time`/`pressure_level`
//! names and the legacy `time`/`level` ones), forecasts (GFS-style THREDDS grids) and ensembles.
//!
//! A grid becomes a [`LevelProfile`] at the launch date and site exactly as RocketPy 1.13's
//! `Environment.process_forecast_reanalysis` / `process_ensemble` do it:
//! - variable names from a mapping ("dictionary"); when the requested one does not fit the
//!   file, the first built-in one that does is used (RocketPy `__resolve_dictionary_for_dataset`,
//!   same order);
//! - CF `scale_factor`/`add_offset` unpacking, `_FillValue`/`missing_value` masking; a level
//!   with a masked value in any field is dropped (`mask_and_clean_dataset`);
//! - **time: the nearest time step, a tie going to the earlier one** (`find_time_index`); a
//!   date before the first or after the last step is an error naming both;
//! - space: bilinear interpolation between the grid points around the site
//!   (`bilinear_interpolation`), longitudes normalised to the grid's convention (±180 or
//!   0–360); a site outside the grid is an error naming the grid's span. Projected grids
//!   (NAM, RAP, HRRR: `x`/`y` coordinates with a `LambertConformal_Projection` variable) take
//!   the site projected into `(x, y)` (`geodesic_to_lambert_conformal`, see
//!   `WeatherGrid::lambert_conformal`), then the same bracketing and bilinear interpolation;
//! - THREDDS subsets (NCSS) name the time and level coordinates after the variables'
//!   dimensions (`time1`, `isobaric2`): a mapping whose coordinate is absent takes the
//!   temperature's dimension in that place (karman's addition, so a downloaded subset reads
//!   with the GFS mapping);
//! - geopotential Φ → geopotential height Φ/g0 → geometric height `R H/(R − H)` with `R` the
//!   datum radius at the launch latitude (RocketPy `earth_radius`).
//!
//! Deviation: levels are converted to Pa from their `units` attribute (Pa stays Pa; hPa, mbar,
//! millibars and anything else ×100); RocketPy always multiplies by 100.

use crate::AtmosError;
use crate::isa::geopotential_to_geometric;
use crate::profile::LevelProfile;
use crate::time::{TimeUnits, iso8601};
use netcdf_reader::{NcFile, NcVariable};
use std::panic::AssertUnwindSafe;
use std::path::Path;

/// Names of the variables of a weather file (RocketPy's `WeatherModelMapping` entries).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct GridDictionary {
    /// Name of the mapping ("ECMWF", "GFS", ... or "custom").
    pub name: String,
    /// Time coordinate.
    pub time: String,
    /// Latitude coordinate.
    pub latitude: String,
    /// Longitude coordinate.
    pub longitude: String,
    /// Pressure-level coordinate.
    pub level: String,
    /// Ensemble-member coordinate.
    pub ensemble: Option<String>,
    /// Grid-mapping variable of a projected grid (`LambertConformal_Projection`: `latitude`
    /// and `longitude` then name the projected `y` and `x` coordinates; `LatLon_Projection`:
    /// a plain latitude/longitude grid that must carry it).
    pub projection: Option<String>,
    /// Temperature (K).
    pub temperature: String,
    /// Surface geopotential height (m), sets the file's surface elevation.
    pub surface_geopotential_height: Option<String>,
    /// Surface geopotential (m²/s²), divided by g0 for the surface elevation.
    pub surface_geopotential: Option<String>,
    /// Geopotential height (m) on levels.
    pub geopotential_height: Option<String>,
    /// Geopotential (m²/s²) on levels, used when no geopotential height exists.
    pub geopotential: Option<String>,
    /// Eastward wind (m/s).
    pub u_wind: String,
    /// Northward wind (m/s).
    pub v_wind: String,
}

/// A built-in mapping (RocketPy's `WeatherModelMapping` dictionaries).
struct Spec {
    name: &'static str,
    time: &'static str,
    latitude: &'static str,
    longitude: &'static str,
    level: &'static str,
    ensemble: Option<&'static str>,
    projection: Option<&'static str>,
    temperature: &'static str,
    surface_gph: Option<&'static str>,
    surface_phi: Option<&'static str>,
    gph: Option<&'static str>,
    phi: Option<&'static str>,
    u: &'static str,
    v: &'static str,
}

/// THREDDS-style names on a latitude/longitude grid (GFS).
const THREDDS: Spec = Spec {
    name: "GFS",
    time: "time",
    latitude: "lat",
    longitude: "lon",
    level: "isobaric",
    ensemble: None,
    projection: None,
    temperature: "Temperature_isobaric",
    surface_gph: Some("Geopotential_height_surface"),
    surface_phi: None,
    gph: Some("Geopotential_height_isobaric"),
    phi: None,
    u: "u-component_of_wind_isobaric",
    v: "v-component_of_wind_isobaric",
};

/// THREDDS-style names on a Lambert conformal grid (NAM, RAP, HRRR): `x`/`y` in metres or
/// kilometres.
const LAMBERT: Spec = Spec {
    name: "NAM",
    latitude: "y",
    longitude: "x",
    projection: Some("LambertConformal_Projection"),
    surface_gph: None,
    ..THREDDS
};

/// NOMADS-style (`*_LEGACY`) names.
const NOMADS: Spec = Spec {
    name: "GFS_LEGACY",
    level: "lev",
    temperature: "tmpprs",
    surface_gph: Some("hgtsfc"),
    gph: Some("hgtprs"),
    u: "ugrdprs",
    v: "vgrdprs",
    ..THREDDS
};

/// ECMWF names before the 2024 CDS update.
const ECMWF_V0: Spec = Spec {
    name: "ECMWF_v0",
    time: "time",
    latitude: "latitude",
    longitude: "longitude",
    level: "level",
    ensemble: Some("number"),
    projection: None,
    temperature: "t",
    surface_gph: None,
    surface_phi: None,
    gph: None,
    phi: Some("z"),
    u: "u",
    v: "v",
};

/// Current ECMWF (CDS) names.
const ECMWF: Spec = Spec {
    name: "ECMWF",
    time: "valid_time",
    level: "pressure_level",
    ..ECMWF_V0
};

/// RocketPy 1.13 `WeatherModelMapping.all_dictionaries`, in its order (the fallback order),
/// then karman's aliases `ERA5` (= ECMWF) and `ERA5_LEGACY` (= ECMWF_v0).
const BUILTINS: [Spec; 19] = [
    THREDDS,
    NOMADS,
    Spec {
        name: "AIGFS",
        projection: Some("LatLon_Projection"),
        surface_gph: None,
        ..THREDDS
    },
    LAMBERT,
    Spec {
        name: "NAM_LEGACY",
        ..NOMADS
    },
    ECMWF_V0,
    ECMWF,
    Spec {
        name: "NOAA",
        ..THREDDS
    },
    Spec {
        name: "NOAA_LEGACY",
        ..NOMADS
    },
    Spec {
        name: "RAP",
        ..LAMBERT
    },
    Spec {
        name: "RAP_LEGACY",
        ..NOMADS
    },
    Spec {
        name: "HRRR",
        ..LAMBERT
    },
    Spec {
        name: "CMC",
        ensemble: Some("ens"),
        surface_gph: None,
        ..NOMADS
    },
    Spec {
        name: "GEFS",
        ensemble: Some("ens"),
        surface_gph: None,
        ..NOMADS
    },
    Spec {
        name: "GEFS_LEGACY",
        ensemble: Some("ens"),
        surface_gph: None,
        ..NOMADS
    },
    Spec {
        name: "HIRESW",
        ..NOMADS
    },
    Spec {
        name: "MERRA2",
        temperature: "T",
        surface_gph: None,
        surface_phi: Some("PHIS"),
        gph: Some("H"),
        u: "U",
        v: "V",
        ..NOMADS
    },
    Spec {
        name: "ERA5",
        ..ECMWF
    },
    Spec {
        name: "ERA5_LEGACY",
        ..ECMWF_V0
    },
];

impl GridDictionary {
    fn from_spec(s: &Spec) -> GridDictionary {
        let o = |v: Option<&str>| v.map(str::to_string);
        GridDictionary {
            name: s.name.into(),
            time: s.time.into(),
            latitude: s.latitude.into(),
            longitude: s.longitude.into(),
            level: s.level.into(),
            ensemble: o(s.ensemble),
            projection: o(s.projection),
            temperature: s.temperature.into(),
            surface_geopotential_height: o(s.surface_gph),
            surface_geopotential: o(s.surface_phi),
            geopotential_height: o(s.gph),
            geopotential: o(s.phi),
            u_wind: s.u.into(),
            v_wind: s.v.into(),
        }
    }

    /// The built-in mappings, in RocketPy's fallback order.
    #[must_use]
    pub fn builtins() -> Vec<GridDictionary> {
        BUILTINS.iter().map(Self::from_spec).collect()
    }

    /// A built-in mapping by name, case-insensitively (`"GFS"`, `"AIGFS"`, `"NAM"`, `"RAP"`,
    /// `"HRRR"`, `"ECMWF"`, `"ECMWF_v0"`, `"NOAA"`, `"GEFS"`, `"CMC"`, `"HIRESW"`, `"MERRA2"`,
    /// `"ERA5"`, ... and their `_LEGACY` forms).
    ///
    /// # Errors
    /// [`AtmosError::UnknownName`] listing the known names.
    pub fn builtin(name: &str) -> Result<GridDictionary, AtmosError> {
        let key = name.trim();
        let alias = match key.to_ascii_uppercase().as_str() {
            "CMC_LEGACY" => "CMC",
            "HIRESW_LEGACY" => "HIRESW",
            "MERRA2_LEGACY" => "MERRA2",
            _ => key,
        };
        BUILTINS
            .iter()
            .find(|s| s.name.eq_ignore_ascii_case(alias))
            .map(Self::from_spec)
            .ok_or_else(|| AtmosError::UnknownName {
                what: "weather dictionary".into(),
                name: name.into(),
                known: BUILTINS
                    .iter()
                    .map(|s| s.name)
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }

    /// This mapping with the time and level coordinates a THREDDS subset renamed: NCSS names
    /// them after the variables' own dimensions (`time1`, `isobaric2`, ...), so when the
    /// mapping's coordinate is not in the file, the temperature's dimension in that place
    /// (the first for time, the second for levels) is used if the file has it as a variable.
    fn adapted_to(&self, file: &NcFile) -> GridDictionary {
        let mut out = self.clone();
        let Ok(var) = file.variable(&self.temperature) else {
            return out;
        };
        let dims: Vec<&str> = var.dimensions().iter().map(|d| d.name.as_str()).collect();
        let has = |n: &str| file.variable(n).is_ok();
        if dims.len() >= 4 {
            if !has(&out.time) && has(dims[0]) {
                out.time = dims[0].to_owned();
            }
            if !has(&out.level) && has(dims[1]) {
                out.level = dims[1].to_owned();
            }
        }
        out
    }

    /// Variables of this mapping missing from the file (empty when it fits).
    fn missing_in(&self, file: &NcFile) -> Vec<String> {
        let has = |n: &str| file.variable(n).is_ok();
        let mut missing: Vec<String> = [
            &self.time,
            &self.latitude,
            &self.longitude,
            &self.level,
            &self.temperature,
            &self.u_wind,
            &self.v_wind,
        ]
        .into_iter()
        .filter(|n| !has(n))
        .cloned()
        .collect();
        if let Some(p) = self.projection.as_deref().filter(|p| !has(p)) {
            missing.push(p.to_owned());
        }
        let gph = self.geopotential_height.as_deref().is_some_and(has);
        let phi = self.geopotential.as_deref().is_some_and(has);
        if !gph && !phi {
            let names: Vec<&str> = [
                self.geopotential_height.as_deref(),
                self.geopotential.as_deref(),
            ]
            .into_iter()
            .flatten()
            .collect();
            missing.push(format!("geopotential ({})", names.join(" or ")));
        }
        missing
    }
}

/// What to extract from a grid.
#[derive(Debug, Clone, PartialEq)]
pub struct GridRequest {
    /// Requested mapping (`None`: the first built-in one that fits).
    pub dictionary: Option<GridDictionary>,
    /// Launch date, Unix seconds (UTC).
    pub unix_time: f64,
    /// Launch latitude (deg).
    pub latitude_deg: f64,
    /// Launch longitude (deg).
    pub longitude_deg: f64,
    /// Ensemble member (`None`: member 0 when the file has members).
    pub member: Option<usize>,
    /// Earth radius (m) for geopotential → geometric height: the datum radius at the site.
    pub earth_radius: f64,
    /// Standard gravity g0 (m/s²) dividing geopotential.
    pub standard_gravity: f64,
}

/// An opened weather grid.
pub struct WeatherGrid {
    file: NcFile,
    name: String,
}

impl std::fmt::Debug for WeatherGrid {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("WeatherGrid")
            .field("name", &self.name)
            .finish_non_exhaustive()
    }
}

impl WeatherGrid {
    /// Opens a netCDF file.
    ///
    /// # Errors
    /// [`AtmosError::NetCdf`] when the file is missing, truncated or not netCDF.
    pub fn open(path: &Path) -> Result<WeatherGrid, AtmosError> {
        let name = path.display().to_string();
        let bytes = karman_math::read_data_file(path).map_err(|e| AtmosError::NetCdf {
            file: name.clone(),
            message: e.to_string(),
        })?;
        Self::from_bytes(bytes, &name)
    }

    /// Reads a netCDF file held in memory (`name` is used in messages).
    ///
    /// # Errors
    /// [`AtmosError::NetCdf`] when the bytes are not a readable netCDF file.
    pub fn from_bytes(bytes: Vec<u8>, name: &str) -> Result<WeatherGrid, AtmosError> {
        // The reader can panic on some malformed inputs; keep user data from aborting.
        let opened = std::panic::catch_unwind(AssertUnwindSafe(|| NcFile::from_vec(bytes)));
        let file = match opened {
            Ok(Ok(f)) => f,
            Ok(Err(e)) => {
                return Err(AtmosError::NetCdf {
                    file: name.into(),
                    message: e.to_string(),
                });
            }
            Err(_) => {
                return Err(AtmosError::NetCdf {
                    file: name.into(),
                    message: "malformed file (reader failed)".into(),
                });
            }
        };
        Ok(WeatherGrid {
            file,
            name: name.into(),
        })
    }

    /// The dimension names of a variable, if the file has it.
    #[must_use]
    pub fn variable_dimensions(&self, name: &str) -> Option<Vec<String>> {
        let var = self.file.variable(name).ok()?;
        Some(var.dimensions().iter().map(|d| d.name.clone()).collect())
    }

    /// The first built-in mapping whose variables the file has.
    #[must_use]
    pub fn detect_dictionary(&self) -> Option<GridDictionary> {
        let builtins = GridDictionary::builtins();
        let fits = |d: &GridDictionary| d.missing_in(&self.file).is_empty();
        builtins.iter().find(|d| fits(d)).cloned().or_else(|| {
            builtins
                .iter()
                .map(|d| d.adapted_to(&self.file))
                .find(|d| fits(d))
        })
    }

    /// The mapping used for `requested` (RocketPy's fallback rule: the requested one, else
    /// the first built-in one that fits; then the same with the coordinates a THREDDS subset
    /// renamed).
    ///
    /// # Errors
    /// [`AtmosError::MissingVariables`] when no mapping fits.
    pub fn resolve_dictionary(
        &self,
        requested: Option<&GridDictionary>,
    ) -> Result<GridDictionary, AtmosError> {
        let fits = |d: &GridDictionary| d.missing_in(&self.file).is_empty();
        let builtins = GridDictionary::builtins();
        let found = requested
            .filter(|d| fits(d))
            .cloned()
            .or_else(|| builtins.iter().find(|d| fits(d)).cloned())
            .or_else(|| {
                requested
                    .map(|d| d.adapted_to(&self.file))
                    .filter(|d| fits(d))
            })
            .or_else(|| {
                builtins
                    .iter()
                    .map(|d| d.adapted_to(&self.file))
                    .find(|d| fits(d))
            });
        if let Some(d) = found {
            return Ok(d);
        }
        let reference = match requested {
            Some(d) => d.clone(),
            None => GridDictionary::from_spec(&ECMWF),
        };
        Err(AtmosError::MissingVariables {
            file: self.name.clone(),
            dictionary: reference.name.clone(),
            missing: reference.missing_in(&self.file).join(", "),
        })
    }

    fn read(&self, name: &str) -> Result<(Vec<f64>, Vec<usize>, &NcVariable), AtmosError> {
        let var = self.file.variable(name).map_err(|e| self.nc_err(&e))?;
        let data = std::panic::catch_unwind(AssertUnwindSafe(|| {
            self.file.read_variable_unpacked_masked(name)
        }));
        let array = match data {
            Ok(Ok(a)) => a,
            Ok(Err(e)) => return Err(self.bad(name, &e.to_string())),
            Err(_) => return Err(self.bad(name, "malformed data (reader failed)")),
        };
        let shape = array.shape().to_vec();
        let values: Vec<f64> = array.iter().copied().collect();
        if values.len() != shape.iter().product::<usize>() {
            return Err(self.bad(name, "data size does not match its shape"));
        }
        Ok((values, shape, var))
    }

    fn nc_err(&self, e: &netcdf_reader::Error) -> AtmosError {
        AtmosError::NetCdf {
            file: self.name.clone(),
            message: e.to_string(),
        }
    }

    fn bad(&self, variable: &str, message: &str) -> AtmosError {
        AtmosError::BadVariable {
            file: self.name.clone(),
            variable: variable.into(),
            message: message.into(),
        }
    }

    /// A 1-D coordinate variable with at least one finite value everywhere.
    fn coordinate(&self, name: &str) -> Result<(Vec<f64>, &NcVariable), AtmosError> {
        let (v, shape, var) = self.read(name)?;
        if shape.len() > 1 || v.is_empty() || v.iter().any(|x| !x.is_finite()) {
            return Err(self.bad(name, "must be a non-empty 1-D coordinate of finite values"));
        }
        Ok((v, var))
    }

    /// The profile at the requested date, site and member.
    ///
    /// # Errors
    /// Missing variables, unreadable or badly shaped data, a date outside the file, a site
    /// outside the grid, a member that does not exist, or no complete level.
    pub fn profile(&self, request: &GridRequest) -> Result<LevelProfile, AtmosError> {
        let dict = self.resolve_dictionary(request.dictionary.as_ref())?;

        // Time.
        let (times, tvar) = self.coordinate(&dict.time)?;
        let units_text = attribute_text(tvar, "units")
            .ok_or_else(|| self.bad(&dict.time, "has no `units` attribute"))?;
        let units = TimeUnits::parse(&units_text)
            .ok_or_else(|| self.bad(&dict.time, &format!("unreadable units `{units_text}`")))?;
        let times: Vec<f64> = times.iter().map(|&t| units.to_unix(t)).collect();
        let time_index = self.time_index(&times, request.unix_time)?;

        // Space.
        let (lats, _) = self.coordinate(&dict.latitude)?;
        let (lons, xvar) = self.coordinate(&dict.longitude)?;
        let (target_lon, target_lat, axes) = match dict.projection.as_deref() {
            Some(LAMBERT_CONFORMAL) => {
                let kilometres = attribute_text(xvar, "units")
                    .is_some_and(|u| u.trim().to_ascii_lowercase().starts_with("km"));
                let (x, y) = self.lambert_conformal(
                    LAMBERT_CONFORMAL,
                    request.latitude_deg,
                    request.longitude_deg,
                    kilometres,
                )?;
                (x, y, ["projected x", "projected y"])
            }
            _ => (
                request.longitude_deg,
                request.latitude_deg,
                ["longitude", "latitude"],
            ),
        };
        let lon = normalize_longitude(target_lon, lons[0], lons[lons.len() - 1]);
        let lat = target_lat;
        let j = self.bracket(lon, &lons, axes[0], target_lon)?;
        let i = self.bracket(lat, &lats, axes[1], lat)?;
        let (x1, x2, y1, y2) = (lats[i - 1], lats[i], lons[j - 1], lons[j]);
        let bilinear = |z: [f64; 4]| {
            // z = [z11 (lat i−1, lon j−1), z12 (i−1, j), z21 (i, j−1), z22 (i, j)].
            (z[0] * (x2 - lat) * (y2 - lon)
                + z[2] * (lat - x1) * (y2 - lon)
                + z[1] * (x2 - lat) * (lon - y1)
                + z[3] * (lat - x1) * (lon - y1))
                / ((x2 - x1) * (y2 - y1))
        };

        // Levels.
        let (levels, lvar) = self.coordinate(&dict.level)?;
        let level_factor = match attribute_text(lvar, "units").as_deref().map(str::trim) {
            Some("Pa" | "pa" | "pascal" | "Pascal" | "pascals") => 1.0,
            _ => 100.0,
        };
        let levels: Vec<f64> = levels.iter().map(|l| l * level_factor).collect();

        let roles = Roles {
            dict: &dict,
            time_index,
            lat: (i - 1, i),
            lon: (j - 1, j),
        };
        let member = request.member.unwrap_or(0);
        let (height_name, height_scale) = match &dict.geopotential_height {
            Some(n) if self.file.variable(n).is_ok() => (n.clone(), 1.0),
            _ => match &dict.geopotential {
                Some(n) => (n.clone(), 1.0 / request.standard_gravity),
                None => return Err(self.bad("geopotential", "not in the file")),
            },
        };
        let field = |name: &str| -> Result<Vec<f64>, AtmosError> {
            let (values, shape, var) = self.read(name)?;
            let corners = self.corners(name, &values, &shape, var, &roles, member)?;
            Ok(corners.into_iter().map(bilinear).collect())
        };
        let heights = field(&height_name)?;
        let temps = field(&dict.temperature)?;
        let us = field(&dict.u_wind)?;
        let vs = field(&dict.v_wind)?;

        let n = [levels.len(), heights.len(), temps.len(), us.len(), vs.len()]
            .into_iter()
            .min()
            .unwrap_or(0);
        let mut out = LevelProfile::default();
        for k in 0..n {
            let h = geopotential_to_geometric(heights[k] * height_scale, request.earth_radius);
            let row = [levels[k], h, temps[k], us[k], vs[k]];
            if row.iter().any(|v| !v.is_finite()) {
                continue; // masked level (RocketPy drops the row)
            }
            out.pressure_pa.push(levels[k]);
            out.height_m.push(h);
            out.temperature_k.push(temps[k]);
            out.wind_u_mps.push(us[k]);
            out.wind_v_mps.push(vs[k]);
        }
        if out.pressure_pa.is_empty() {
            return Err(AtmosError::Empty {
                source_name: self.name.clone(),
                what: "the profile at the launch site (every level is masked)".into(),
            });
        }

        // Surface elevation, when the mapping names one.
        let surface = [
            (dict.surface_geopotential_height.as_deref(), 1.0),
            (
                dict.surface_geopotential.as_deref(),
                1.0 / request.standard_gravity,
            ),
        ];
        for (name, scale) in surface {
            if let Some(name) = name.filter(|n| self.file.variable(n).is_ok()) {
                let (values, shape, var) = self.read(name)?;
                let corners = self.corners(name, &values, &shape, var, &roles, member)?;
                out.surface_elevation_m = corners
                    .first()
                    .map(|c| bilinear(*c) * scale)
                    .filter(|v| v.is_finite());
                break;
            }
        }
        Ok(out)
    }

    /// The site in a Lambert conformal grid's `(x, y)` (m, or km when `kilometres`), from the
    /// grid-mapping variable's `latitude_of_projection_origin`,
    /// `longitude_of_central_meridian`, `standard_parallel` (one or two) and `earth_radius`
    /// (default 6 371 229 m): the spherical Lambert conformal conic (Snyder 1987, eq. 15-1 to
    /// 15-3), as RocketPy 1.13's `geodesic_to_lambert_conformal` (longitudes taken modulo
    /// 360° on both sides, as there).
    fn lambert_conformal(
        &self,
        name: &str,
        latitude_deg: f64,
        longitude_deg: f64,
        kilometres: bool,
    ) -> Result<(f64, f64), AtmosError> {
        let var = self.file.variable(name).map_err(|e| self.nc_err(&e))?;
        let number = |attr: &str| -> Result<Vec<f64>, AtmosError> {
            var.attribute(attr)
                .and_then(|a| a.value.as_f64_vec())
                .filter(|v| !v.is_empty() && v.iter().all(|x| x.is_finite()))
                .ok_or_else(|| self.bad(name, &format!("no numeric `{attr}` attribute")))
        };
        let lat0 = number("latitude_of_projection_origin")?[0].to_radians();
        let lon0 = number("longitude_of_central_meridian")?[0].to_radians();
        let parallels = number("standard_parallel")?;
        let radius = match var.attribute("earth_radius") {
            Some(_) => number("earth_radius")?[0],
            None => 6_371_229.0,
        };
        let t = |phi: f64| (std::f64::consts::FRAC_PI_4 + phi / 2.0).tan();
        let phi1 = parallels[0].to_radians();
        let n = match parallels.get(1) {
            Some(p2) => {
                let phi2 = p2.to_radians();
                (phi1.cos() / phi2.cos()).ln() / (t(phi2) / t(phi1)).ln()
            }
            None => phi1.sin(),
        };
        let f = phi1.cos() * t(phi1).powf(n) / n;
        let rho = radius * f / t(latitude_deg.to_radians()).powf(n);
        let rho0 = radius * f / t(lat0).powf(n);
        let theta = n * (longitude_deg.rem_euclid(360.0).to_radians() - lon0);
        let (x, y) = (rho * theta.sin(), rho0 - rho * theta.cos());
        if !(x.is_finite() && y.is_finite()) {
            return Err(self.bad(
                name,
                "its parameters do not project the launch site to a finite point",
            ));
        }
        let scale = if kilometres { 1e-3 } else { 1.0 };
        Ok((x * scale, y * scale))
    }

    /// RocketPy `find_time_index`: nearest step, a tie to the earlier; outside → error.
    fn time_index(&self, times: &[f64], t: f64) -> Result<usize, AtmosError> {
        let n = times.len();
        let ascending = times[0] <= times[n - 1];
        let low = times.partition_point(|&v| if ascending { v < t } else { v > t });
        let right = low.min(n - 1);
        let left = right.saturating_sub(1);
        let index = if (t - times[left]).abs() <= (times[right] - t).abs() {
            left
        } else {
            right
        };
        let chosen = times[index];
        let before = if ascending { t < chosen } else { t > chosen };
        let after = if ascending { t > chosen } else { t < chosen };
        if (index == 0 && before) || (index == n - 1 && after) || !t.is_finite() {
            return Err(AtmosError::DateOutsideFile {
                file: self.name.clone(),
                date: iso8601(t),
                first: iso8601(times[0]),
                last: iso8601(times[n - 1]),
            });
        }
        Ok(index)
    }

    /// RocketPy `find_latitude_index`/`find_longitude_index`: the index `k` with the site
    /// between `coords[k−1]` and `coords[k]`.
    fn bracket(
        &self,
        value: f64,
        coords: &[f64],
        axis: &str,
        requested: f64,
    ) -> Result<usize, AtmosError> {
        let n = coords.len();
        let ascending = coords[0] < coords[n - 1];
        let mut k = coords.partition_point(|&c| if ascending { c < value } else { c > value });
        if k == 0 && (coords[0] - value).abs() <= 1e-9 * value.abs().max(coords[0].abs()) {
            k = 1;
        } else if k == n && (coords[n - 1] - value).abs() <= 0.0 {
            k = n - 1;
        }
        if k == 0 || k == n || !value.is_finite() {
            return Err(AtmosError::SiteOutsideGrid {
                file: self.name.clone(),
                axis: axis.into(),
                unit: if axis.starts_with("projected") {
                    String::new()
                } else {
                    "°".into()
                },
                value: requested,
                first: coords[0],
                last: coords[n - 1],
            });
        }
        Ok(k)
    }

    /// For each level, the four corner values `[z11, z12, z21, z22]` of a variable.
    fn corners(
        &self,
        name: &str,
        values: &[f64],
        shape: &[usize],
        var: &NcVariable,
        roles: &Roles<'_>,
        member: usize,
    ) -> Result<Vec<[f64; 4]>, AtmosError> {
        let d = roles.dict;
        let dims: Vec<&str> = var.dimensions().iter().map(|x| x.name.as_str()).collect();
        if dims.len() != shape.len() {
            return Err(self.bad(name, "dimension list does not match the data"));
        }
        #[derive(Clone, Copy, PartialEq)]
        enum Role {
            Fixed(usize),
            Level,
            Lat,
            Lon,
        }
        let mut roles_of = Vec::with_capacity(dims.len());
        let mut has_member = false;
        for (k, dim) in dims.iter().enumerate() {
            let role = if *dim == d.time {
                Role::Fixed(roles.time_index)
            } else if *dim == d.level {
                Role::Level
            } else if *dim == d.latitude {
                Role::Lat
            } else if *dim == d.longitude {
                Role::Lon
            } else if d.ensemble.as_deref() == Some(*dim) {
                has_member = true;
                if member >= shape[k] {
                    return Err(AtmosError::NoSuchMember {
                        file: self.name.clone(),
                        member,
                        last: shape[k].saturating_sub(1),
                    });
                }
                Role::Fixed(member)
            } else if shape[k] == 1 {
                Role::Fixed(0)
            } else {
                return Err(self.bad(name, &format!("unexpected dimension `{dim}`")));
            };
            if let Role::Fixed(ix) = role {
                if ix >= shape[k] {
                    return Err(self.bad(name, &format!("index {ix} outside dimension `{dim}`")));
                }
            }
            roles_of.push(role);
        }
        if member > 0 && !has_member {
            return Err(AtmosError::NoSuchMember {
                file: self.name.clone(),
                member,
                last: 0,
            });
        }
        let spatial = roles_of
            .iter()
            .filter(|r| matches!(r, Role::Lat | Role::Lon))
            .count();
        if spatial != 2 {
            return Err(self.bad(name, "needs latitude and longitude dimensions"));
        }
        // Row-major strides.
        let mut strides = vec![1usize; shape.len()];
        for k in (0..shape.len().saturating_sub(1)).rev() {
            strides[k] = strides[k + 1] * shape[k + 1];
        }
        let levels = roles_of
            .iter()
            .zip(shape)
            .find(|(r, _)| **r == Role::Level)
            .map_or(1, |(_, &s)| s);
        let mut out = Vec::with_capacity(levels);
        for level in 0..levels {
            let mut z = [f64::NAN; 4];
            for (c, (li, lj)) in [(0usize, 0usize), (0, 1), (1, 0), (1, 1)]
                .into_iter()
                .enumerate()
            {
                let mut flat = 0usize;
                for (k, role) in roles_of.iter().enumerate() {
                    let ix = match *role {
                        Role::Fixed(ix) => ix,
                        Role::Level => level,
                        Role::Lat => {
                            if li == 0 {
                                roles.lat.0
                            } else {
                                roles.lat.1
                            }
                        }
                        Role::Lon => {
                            if lj == 0 {
                                roles.lon.0
                            } else {
                                roles.lon.1
                            }
                        }
                    };
                    if ix >= shape[k] {
                        return Err(self.bad(name, "grid index outside the variable"));
                    }
                    flat += ix * strides[k];
                }
                z[c] = values.get(flat).copied().unwrap_or(f64::NAN);
            }
            out.push(z);
        }
        Ok(out)
    }
}

/// The grid-mapping variable of Lambert conformal THREDDS grids (NAM, RAP, HRRR).
const LAMBERT_CONFORMAL: &str = "LambertConformal_Projection";

/// Index choices shared by every field.
struct Roles<'a> {
    dict: &'a GridDictionary,
    time_index: usize,
    lat: (usize, usize),
    lon: (usize, usize),
}

fn attribute_text(var: &NcVariable, name: &str) -> Option<String> {
    var.attribute(name).and_then(|a| a.value.as_string())
}

/// RocketPy `_normalize_longitude_value`: map to the grid's convention (±180 or 0–360).
fn normalize_longitude(lon: f64, start: f64, end: f64) -> f64 {
    if start.abs() <= 360.0 && end.abs() <= 360.0 {
        if start < 0.0 || end < 0.0 {
            if lon < 180.0 {
                lon
            } else {
                -180.0 + lon % 180.0
            }
        } else {
            lon.rem_euclid(360.0)
        }
    } else {
        lon
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn longitude_conventions() {
        assert!((normalize_longitude(-8.3, 0.0, 359.75) - 351.7).abs() < 1e-12);
        assert!((normalize_longitude(-8.3, -9.0, -8.0) + 8.3).abs() < 1e-12);
        assert!((normalize_longitude(190.0, -180.0, 180.0) + 170.0).abs() < 1e-12);
    }

    #[test]
    fn dictionaries() {
        assert_eq!(
            GridDictionary::builtin("ecmwf").map(|d| d.time).ok(),
            Some("valid_time".into())
        );
        assert_eq!(
            GridDictionary::builtin("ECMWF_v0").map(|d| d.level).ok(),
            Some("level".into())
        );
        assert!(GridDictionary::builtin("nope").is_err());
    }

    #[test]
    fn garbage_is_an_error_not_a_panic() {
        let e = WeatherGrid::from_bytes(b"CDF\x01garbage".to_vec(), "g.nc").expect_err("fails");
        assert!(e.to_string().contains("g.nc"), "{e}");
        assert!(WeatherGrid::from_bytes(Vec::new(), "e.nc").is_err());
    }
}
