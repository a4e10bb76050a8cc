//! Weather grids: synthetic netCDF files authored here (time choice, bilinear interpolation,
//! longitude conventions, members, every error) and the validation ERA5 files (corruption).

use crate::common::{Var, classic_nc, classic_nc_numeric};
use karman_atmos::time::unix_seconds;
use karman_atmos::{AtmosError, GridDictionary, GridRequest, WeatherGrid};

const G0: f64 = 9.80665;
const LATS: [f64; 2] = [41.0, 40.0];
const LONS: [f64; 2] = [350.0, 351.0];
const LEVELS_HPA: [f64; 3] = [1000.0, 850.0, 700.0];
const BASE_HEIGHT: [f64; 3] = [100.0, 1500.0, 3000.0];

/// A field linear in latitude and longitude (so bilinear interpolation is exact), varying
/// with time step, level and member.
fn field(kind: f64, step: usize, member: usize, level: usize, lat: f64, lon: f64) -> f64 {
    match kind as u8 {
        0 => G0 * (BASE_HEIGHT[level] + 2.0 * (lat - 40.0) + 3.0 * (lon - 350.0)),
        1 => 290.0 - 5.0 * level as f64 + 0.1 * lat + step as f64,
        2 => 1.0 + level as f64 + 0.5 * lat - 0.25 * lon + 10.0 * step as f64 + member as f64,
        _ => -2.0 + 0.2 * lat + 0.1 * lon - 10.0 * step as f64,
    }
}

/// The synthetic grid: 2 time steps (0 h and 6 h after 2020-01-01), 3 levels, 2×2 points;
/// `members` > 1 adds an ensemble dimension `number`; `skip` leaves one variable out.
fn synthetic(members: usize, skip: &str) -> Vec<u8> {
    let ensemble = members > 1;
    let mut dims = vec![("time", 2), ("level", 3), ("latitude", 2), ("longitude", 2)];
    if ensemble {
        dims.push(("number", members));
    }
    let field_dims: Vec<usize> = if ensemble {
        vec![0, 4, 1, 2, 3]
    } else {
        vec![0, 1, 2, 3]
    };
    let mut vars = vec![
        Var {
            name: "time",
            dims: vec![0],
            attrs: vec![("units", "hours since 2020-01-01 00:00:00")],
            data: vec![0.0, 6.0],
        },
        Var {
            name: "level",
            dims: vec![1],
            attrs: vec![("units", "millibars")],
            data: LEVELS_HPA.to_vec(),
        },
        Var {
            name: "latitude",
            dims: vec![2],
            attrs: vec![],
            data: LATS.to_vec(),
        },
        Var {
            name: "longitude",
            dims: vec![3],
            attrs: vec![],
            data: LONS.to_vec(),
        },
    ];
    if ensemble {
        vars.push(Var {
            name: "number",
            dims: vec![4],
            attrs: vec![],
            data: (0..members).map(|m| m as f64).collect(),
        });
    }
    for (kind, name) in [(0.0, "z"), (1.0, "t"), (2.0, "u"), (3.0, "v")] {
        if name == skip {
            continue;
        }
        let mut data = Vec::new();
        for step in 0..2 {
            for member in 0..members {
                for level in 0..3 {
                    for lat in LATS {
                        for lon in LONS {
                            data.push(field(kind, step, member, level, lat, lon));
                        }
                    }
                }
            }
        }
        vars.push(Var {
            name,
            dims: field_dims.clone(),
            attrs: vec![],
            data,
        });
    }
    classic_nc(&dims, &vars)
}

fn request(hours: f64, lat: f64, lon: f64) -> GridRequest {
    GridRequest {
        dictionary: None,
        unix_time: unix_seconds(2020, 1, 1, 0, 0, 0.0).expect("a valid date") + hours * 3600.0,
        latitude_deg: lat,
        longitude_deg: lon,
        member: None,
        earth_radius: 6_371_000.0,
        standard_gravity: G0,
    }
}

fn grid(bytes: Vec<u8>) -> WeatherGrid {
    WeatherGrid::from_bytes(bytes, "synthetic.nc").expect("synthetic file opens")
}

#[test]
fn nearest_time_step_ties_to_the_earlier_one() {
    let g = grid(synthetic(1, ""));
    let at = |h: f64| {
        g.profile(&request(h, 40.5, -9.5))
            .expect("profile")
            .temperature_k[0]
    };
    let t0 = 290.0 + 0.1 * 40.5;
    assert!((at(3.0) - t0).abs() < 1e-9, "a tie takes the earlier step");
    assert!((at(2.9) - t0).abs() < 1e-9);
    assert!((at(3.1) - (t0 + 1.0)).abs() < 1e-9);
    assert!((at(6.0) - (t0 + 1.0)).abs() < 1e-9);
}

#[test]
fn bilinear_in_latitude_and_longitude() {
    let g = grid(synthetic(1, ""));
    let (lat, lon) = (40.3, -9.2); // 350.8 in the file's 0–360 convention
    let p = g.profile(&request(0.0, lat, lon)).expect("profile");
    assert_eq!(p.pressure_pa, vec![100_000.0, 85_000.0, 70_000.0]);
    let u = 1.0 + 0.5 * lat - 0.25 * 350.8;
    assert!(
        (p.wind_u_mps[0] - u).abs() < 1e-9,
        "{} vs {u}",
        p.wind_u_mps[0]
    );
    let gph = BASE_HEIGHT[1] + 2.0 * (lat - 40.0) + 3.0 * 0.8;
    let geometric = 6_371_000.0 * gph / (6_371_000.0 - gph);
    assert!((p.height_m[1] - geometric).abs() < 1e-6);
    assert_eq!(p.surface_elevation_m, None);
}

#[test]
fn ensemble_members() {
    let g = grid(synthetic(3, ""));
    let mut r = request(0.0, 40.5, -9.5);
    let u0 = g.profile(&r).expect("member 0").wind_u_mps[2];
    r.member = Some(2);
    let u2 = g.profile(&r).expect("member 2").wind_u_mps[2];
    assert!((u2 - u0 - 2.0).abs() < 1e-9);
    r.member = Some(3);
    let e = g.profile(&r).expect_err("no member 3");
    assert!(
        matches!(
            e,
            AtmosError::NoSuchMember {
                member: 3,
                last: 2,
                ..
            }
        ),
        "{e}"
    );
    // A file without members has only member 0.
    let single = grid(synthetic(1, ""));
    assert!(single.profile(&r).is_err());
}

#[test]
fn date_outside_the_file_names_both() {
    let g = grid(synthetic(1, ""));
    let e = g
        .profile(&request(-1.0, 40.5, -9.5))
        .expect_err("before the file");
    let text = e.to_string();
    assert!(
        text.contains("2019-12-31T23:00:00Z") && text.contains("2020-01-01T00:00:00Z"),
        "{text}"
    );
    assert!(g.profile(&request(7.0, 40.5, -9.5)).is_err());
}

#[test]
fn site_outside_the_grid_names_both() {
    let g = grid(synthetic(1, ""));
    let e = g
        .profile(&request(0.0, 45.0, -9.5))
        .expect_err("north of the grid");
    assert!(
        matches!(e, AtmosError::SiteOutsideGrid { ref axis, .. } if axis == "latitude"),
        "{e}"
    );
    assert!(
        e.to_string().contains("45") && e.to_string().contains("41"),
        "{e}"
    );
    let e = g
        .profile(&request(0.0, 40.5, 20.0))
        .expect_err("east of the grid");
    assert!(
        matches!(e, AtmosError::SiteOutsideGrid { ref axis, .. } if axis == "longitude"),
        "{e}"
    );
}

#[test]
fn missing_variables_are_named() {
    let g = grid(synthetic(1, "t"));
    let mut r = request(0.0, 40.5, -9.5);
    r.dictionary = Some(GridDictionary::builtin("ECMWF_v0").expect("builtin"));
    let e = g.profile(&r).expect_err("no temperature");
    assert!(matches!(e, AtmosError::MissingVariables { .. }), "{e}");
    assert!(e.to_string().contains("t"), "{e}");
    let g = grid(synthetic(1, "z"));
    assert!(
        g.profile(&r)
            .expect_err("no geopotential")
            .to_string()
            .contains("geopotential")
    );
}

#[test]
fn requested_dictionary_falls_back_to_one_that_fits() {
    // The synthetic file has the legacy ERA5 names; asking for "ECMWF" (current names) falls
    // back to ECMWF_v0 as RocketPy does.
    let g = grid(synthetic(1, ""));
    let ecmwf = GridDictionary::builtin("ECMWF").expect("builtin");
    assert_eq!(
        g.resolve_dictionary(Some(&ecmwf)).expect("fits").name,
        "ECMWF_v0"
    );
}

#[test]
fn truncated_and_corrupt_files_are_errors() {
    let bytes = synthetic(1, "");
    for cut in [0, 3, 8, 40, bytes.len() / 2, bytes.len() - 9] {
        let truncated = bytes[..cut].to_vec();
        if let Ok(g) = WeatherGrid::from_bytes(truncated, "cut.nc") {
            assert!(
                g.profile(&request(0.0, 40.5, -9.5)).is_err(),
                "cut at {cut}"
            );
        }
    }
    let Some(validation) = karman_validation::folder() else {
        return;
    };
    for file in [
        "bella_lui/bella_lui_weather_data_ERA5.nc",
        "andromeda/euroc_2022_all_windows.nc",
    ] {
        let bytes = std::fs::read(validation.dir.join(file)).expect("ERA5 file");
        for cut in [16, 1000, bytes.len() / 3, bytes.len() - 100] {
            let mut r = request(0.0, 47.2, 9.0);
            r.unix_time = unix_seconds(2020, 2, 22, 13, 0, 0.0).expect("a valid date");
            if let Ok(g) = WeatherGrid::from_bytes(bytes[..cut].to_vec(), file) {
                assert!(g.profile(&r).is_err(), "{file} cut at {cut}");
            }
        }
        let mut flipped = bytes.clone();
        for b in flipped.iter_mut().skip(200).step_by(97) {
            *b ^= 0x5a;
        }
        if let Ok(g) = WeatherGrid::from_bytes(flipped, file) {
            let _ = g.profile(&request(0.0, 47.2, 9.0)); // any outcome but a panic
        }
    }
}

#[test]
fn real_era5_files_dates_and_sites() {
    let Some(validation) = karman_validation::folder() else {
        return;
    };
    let path = validation
        .dir
        .join("bella_lui/bella_lui_weather_data_ERA5.nc");
    let g = WeatherGrid::open(&path).expect("opens");
    assert_eq!(
        g.detect_dictionary().map(|d| d.name),
        Some("ECMWF_v0".into())
    );
    let mut r = request(0.0, 47.213476, 9.003336);
    r.unix_time = unix_seconds(2020, 2, 22, 13, 0, 0.0).expect("a valid date");
    let p = g.profile(&r).expect("profile");
    assert_eq!(p.pressure_pa.len(), 14);
    r.unix_time = unix_seconds(2021, 2, 22, 13, 0, 0.0).expect("a valid date");
    assert!(matches!(
        g.profile(&r),
        Err(AtmosError::DateOutsideFile { .. })
    ));
    let missing = WeatherGrid::open(&validation.dir.join("no/such/file.nc")).expect_err("missing");
    assert!(missing.to_string().contains("file.nc"));
}

/// A HRRR-style grid on Lambert conformal `x`/`y` (km) around Edwards AFB, y descending:
/// 2 time steps (0 h, 6 h after 2024-06-01), 4 levels (Pa), 4×4 points, fields that are not
/// bilinear in the indices.
fn lambert_grid() -> Vec<u8> {
    const XS: [f64; 4] = [-1836.0, -1833.0, -1830.0, -1827.0];
    const YS: [f64; 4] = [-144.0, -147.0, -150.0, -153.0];
    const GPH: [f64; 4] = [100.0, 1500.0, 3000.0, 5600.0];
    let dims = [("time", 2), ("isobaric", 4), ("y", 4), ("x", 4)];
    let field = |f: &dyn Fn(f64, f64, f64, f64) -> f64| -> Vec<f64> {
        let mut out = Vec::new();
        for step in 0..2 {
            for k in 0..4 {
                for iy in 0..4 {
                    for ix in 0..4 {
                        out.push(f(step as f64, k as f64, iy as f64, ix as f64));
                    }
                }
            }
        }
        out
    };
    let vars = vec![
        Var {
            name: "time",
            dims: vec![0],
            attrs: vec![("units", "hours since 2024-06-01 00:00:00")],
            data: vec![0.0, 6.0],
        },
        Var {
            name: "isobaric",
            dims: vec![1],
            attrs: vec![("units", "Pa")],
            data: vec![100_000.0, 85_000.0, 70_000.0, 50_000.0],
        },
        Var {
            name: "y",
            dims: vec![2],
            attrs: vec![("units", "km")],
            data: YS.to_vec(),
        },
        Var {
            name: "x",
            dims: vec![3],
            attrs: vec![("units", "km")],
            data: XS.to_vec(),
        },
        Var {
            name: "LambertConformal_Projection",
            dims: vec![],
            attrs: vec![("grid_mapping_name", "lambert_conformal_conic")],
            data: vec![0.0],
        },
        Var {
            name: "Temperature_isobaric",
            dims: vec![0, 1, 2, 3],
            attrs: vec![],
            data: field(&|s, k, iy, ix| 300.0 - 6.5 * k + 0.3 * ix - 0.2 * iy + 0.05 * ix * iy + s),
        },
        Var {
            name: "Geopotential_height_isobaric",
            dims: vec![0, 1, 2, 3],
            attrs: vec![],
            data: field(&|s, k, iy, ix| {
                GPH[k as usize] + 2.0 * ix + 3.0 * iy + 0.5 * ix * iy + 4.0 * s
            }),
        },
        Var {
            name: "u-component_of_wind_isobaric",
            dims: vec![0, 1, 2, 3],
            attrs: vec![],
            data: field(&|s, k, iy, ix| 2.0 + k + 0.7 * ix - 0.4 * iy * ix + s),
        },
        Var {
            name: "v-component_of_wind_isobaric",
            dims: vec![0, 1, 2, 3],
            attrs: vec![],
            data: field(&|s, k, iy, ix| -1.0 + 0.5 * k + 0.3 * iy + 0.1 * ix * ix - s),
        },
    ];
    let projection = "LambertConformal_Projection";
    classic_nc_numeric(
        &dims,
        &vars,
        &[
            (projection, "latitude_of_projection_origin", &[38.5]),
            (projection, "longitude_of_central_meridian", &[262.5]),
            (projection, "standard_parallel", &[38.5]),
            (projection, "earth_radius", &[6_371_229.0]),
        ],
    )
}

/// RocketPy 1.13 on the file of [`lambert_grid`] (written to `lambert_hrrr.nc` in the test
/// binary's scratch folder): `Environment(date=(2024, 6, 1, 4), latitude=35.35,
/// longitude=-117.81, elevation=0)`, `set_atmospheric_model(type="Forecast", file=...,
/// dictionary="HRRR")`; pressure (Pa), temperature (K), wind x and y (m/s) at these heights
/// (m ASL).
const ROCKETPY_LAMBERT: [(f64, [f64; 4]); 5] = [
    (
        50.0,
        [
            100000.0,
            301.49022879664244,
            3.413143022002549,
            -1.2067018750764835,
        ],
    ),
    (
        700.0,
        [
            93713.20712541629,
            298.7659518843228,
            3.832262546974796,
            -0.99714211259036,
        ],
    ),
    (
        2000.0,
        [
            80137.85898926477,
            292.8833010253238,
            4.737285756051564,
            -0.5446305080519759,
        ],
    ),
    (
        4000.0,
        [
            62429.541828392576,
            286.02982989087,
            5.791665930582921,
            -0.017440420786297983,
        ],
    ),
    (
        5500.0,
        [
            50906.69820155934,
            282.2849057121492,
            6.367808111924583,
            0.2706306698845331,
        ],
    ),
];

#[test]
fn lambert_conformal_grids_match_rocketpy() {
    use karman_atmos::{Atmosphere, Datum, Environment, EnvironmentConfig};
    use karman_math::PhysicalConstants;
    let bytes = lambert_grid();
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"));
    std::fs::write(dir.join("lambert_hrrr.nc"), &bytes).expect("scratch file");
    let g = grid(bytes);
    assert_eq!(
        g.detect_dictionary().map(|d| d.name),
        Some("NAM".into()),
        "the first Lambert conformal mapping (NAM, RAP and HRRR share their names)"
    );
    let c = PhysicalConstants::SI;
    let (lat, lon) = (35.35, -117.81);
    let radius = Datum::Sirgas2000.radius(lat, &c);
    let mut r = request(0.0, lat, lon);
    r.unix_time = unix_seconds(2024, 6, 1, 4, 0, 0.0).expect("a valid date");
    r.earth_radius = radius;
    r.dictionary = Some(GridDictionary::builtin("HRRR").expect("builtin"));
    let levels = g.profile(&r).expect("profile");
    let env = Environment::new(
        &EnvironmentConfig {
            latitude_deg: lat,
            longitude_deg: lon,
            atmosphere: Atmosphere::Profiles(levels.profiles("lambert_hrrr.nc")),
            ..EnvironmentConfig::default()
        },
        &c,
    )
    .expect("environment");
    for (h, [p, t, u, v]) in ROCKETPY_LAMBERT {
        let got = [
            env.pressure(h),
            env.temperature(h),
            env.wind(h)[0],
            env.wind(h)[1],
        ];
        for (x, y) in got.iter().zip([p, t, u, v]) {
            assert!(
                (x - y).abs() <= 1e-9 * y.abs().max(1.0),
                "{h} m: {got:?} vs RocketPy"
            );
        }
    }
    // A site outside the projected grid names the projected coordinate.
    r.latitude_deg = 36.0;
    let e = g.profile(&r).expect_err("north of the grid");
    assert!(e.to_string().contains("launch projected"), "{e}");
}
