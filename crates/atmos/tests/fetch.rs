//! The `fetch` feature against a loopback HTTP server (std `TcpListener` on 127.0.0.1 in a
//! thread) serving small responses authored here — never the internet.

use crate::common::{Var, classic_nc};
use karman_atmos::fetch::{Endpoints, Fetcher};
use karman_atmos::time::unix_seconds;
use karman_atmos::{AtmosError, GridRequest};
use std::io::{BufRead, BufReader, Write};
use std::net::TcpListener;
use std::sync::mpsc;
use std::thread;

/// Serves `body` with `status` to `count` requests; returns the base URL and a channel of the
/// request lines received.
fn serve(status: u16, body: Vec<u8>, count: usize) -> (String, mpsc::Receiver<String>) {
    let listener = TcpListener::bind("127.0.0.1:0").expect("loopback port");
    let addr = listener.local_addr().expect("address");
    let (tx, rx) = mpsc::channel();
    thread::spawn(move || {
        for stream in listener.incoming().take(count) {
            let Ok(mut stream) = stream else { continue };
            let mut reader = BufReader::new(stream.try_clone().expect("clone stream"));
            let mut request_line = String::new();
            let _ = reader.read_line(&mut request_line);
            loop {
                let mut header = String::new();
                if reader.read_line(&mut header).unwrap_or(0) == 0 || header.trim().is_empty() {
                    break;
                }
            }
            let _ = tx.send(request_line.trim().to_string());
            let head = format!(
                "HTTP/1.1 {status} X\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
                body.len()
            );
            let _ = stream.write_all(head.as_bytes());
            let _ = stream.write_all(&body);
        }
    });
    (format!("http://{addr}/svc"), rx)
}

fn fetcher(base: &str) -> Fetcher {
    Fetcher::new(Endpoints {
        wyoming: base.into(),
        gfs_ncss: base.into(),
        open_meteo: base.into(),
    })
    .expect("client")
}

const WYOMING_PAGE: &str = "<html><body><h2>02963 Jokioinen Observations</h2>\n<pre>\n\
-----------------------------------------------------------------------------\n\
   PRES   HGHT   TEMP   DWPT   RELH   MIXR   DRCT   SKNT   THTA   THTE   THTV\n\
    hPa     m      C      C      %    g/kg    deg   knot     K      K      K\n\
-----------------------------------------------------------------------------\n\
  992.0    103    1.6    0.8     94   4.11    240      5  275.4  286.7  276.1\n\
  850.0   1325   -6.5  -10.0     76   2.11    280      3  279.3  285.5  279.7\n\
</pre><h3>Station information and sounding indices</h3><pre>\n\
                         Station elevation: 103.0\n</pre></body></html>\n";

#[test]
fn wyoming_by_station_and_date() {
    let (base, requests) = serve(200, WYOMING_PAGE.as_bytes().to_vec(), 1);
    let s = fetcher(&base)
        .wyoming_sounding(
            "02963",
            unix_seconds(2006, 4, 10, 12, 0, 0.0).expect("a valid date"),
        )
        .expect("sounding");
    assert_eq!(s.levels.len(), 2);
    assert_eq!(s.station_elevation_m, Some(103.0));
    let line = requests.recv().expect("one request");
    assert!(
        line.contains("id=02963") && line.contains("2006-04-10"),
        "{line}"
    );
}

#[test]
fn http_errors_are_reported() {
    let (base, _requests) = serve(404, b"not found".to_vec(), 1);
    let e = fetcher(&base)
        .wyoming_sounding(
            "00000",
            unix_seconds(2006, 4, 10, 12, 0, 0.0).expect("a valid date"),
        )
        .expect_err("404");
    assert!(matches!(e, AtmosError::Download { .. }), "{e}");
}

#[test]
fn open_meteo_levels() {
    let t0 = unix_seconds(2024, 6, 1, 0, 0, 0.0).expect("a valid date");
    let mut hourly = format!("\"time\": [{}, {}]", t0, t0 + 3600.0);
    // Two levels with data at the second hour; every other level null.
    for (l, t, z, s, d) in [
        (1000, 20.0, 110.0, 5.0, 270.0),
        (850, 10.0, 1500.0, 10.0, 180.0),
    ] {
        hourly.push_str(&format!(
            ", \"temperature_{l}hPa\": [0, {t}], \"geopotential_height_{l}hPa\": [0, {z}], \
             \"wind_speed_{l}hPa\": [0, {s}], \"wind_direction_{l}hPa\": [0, {d}]"
        ));
    }
    hourly.push_str(", \"temperature_700hPa\": [null, null]");
    let body = format!("{{\"elevation\": 50.0, \"hourly\": {{{hourly}}}}}");
    let (base, requests) = serve(200, body.into_bytes(), 2);
    let f = fetcher(&base);
    let p = f
        .open_meteo_profile(40.0, -8.0, t0 + 2000.0, 6.371e6)
        .expect("profile");
    assert_eq!(p.pressure_pa, vec![100_000.0, 85_000.0]);
    assert!((p.temperature_k[0] - 293.15).abs() < 1e-9);
    assert!(
        (p.wind_u_mps[0] - 5.0).abs() < 1e-9,
        "wind from the west blows east"
    );
    assert!(
        (p.wind_v_mps[1] - 10.0).abs() < 1e-9,
        "wind from the south blows north"
    );
    assert_eq!(p.surface_elevation_m, Some(50.0));
    let line = requests.recv().expect("request");
    assert!(line.contains("start_date=2024-06-01"), "{line}");
    let e = f
        .open_meteo_profile(40.0, -8.0, t0 + 90_000.0, 6.371e6)
        .expect_err("outside");
    assert!(matches!(e, AtmosError::DateOutsideFile { .. }), "{e}");
}

#[test]
fn gfs_through_ncss() {
    // A THREDDS-style subset: dimensions time1 and isobaric (Pa), 2×2 points, one time.
    let dims = [("time1", 1), ("isobaric", 2), ("lat", 2), ("lon", 2)];
    let field = |base: f64| -> Vec<f64> {
        (0..2)
            .flat_map(|k| (0..4).map(move |c| base + 10.0 * k as f64 + c as f64))
            .collect()
    };
    let vars = vec![
        Var {
            name: "time1",
            dims: vec![0],
            attrs: vec![("units", "Hour since 2024-06-01T00:00:00Z")],
            data: vec![12.0],
        },
        Var {
            name: "isobaric",
            dims: vec![1],
            attrs: vec![("units", "Pa")],
            data: vec![100_000.0, 85_000.0],
        },
        Var {
            name: "lat",
            dims: vec![2],
            attrs: vec![],
            data: vec![40.5, 39.5],
        },
        Var {
            name: "lon",
            dims: vec![3],
            attrs: vec![],
            data: vec![351.5, 352.5],
        },
        Var {
            name: "Temperature_isobaric",
            dims: vec![0, 1, 2, 3],
            attrs: vec![],
            data: field(280.0),
        },
        Var {
            name: "Geopotential_height_isobaric",
            dims: vec![0, 1, 2, 3],
            attrs: vec![],
            data: field(100.0),
        },
        Var {
            name: "u-component_of_wind_isobaric",
            dims: vec![0, 1, 2, 3],
            attrs: vec![],
            data: field(1.0),
        },
        Var {
            name: "v-component_of_wind_isobaric",
            dims: vec![0, 1, 2, 3],
            attrs: vec![],
            data: field(-1.0),
        },
    ];
    let (base, requests) = serve(200, classic_nc(&dims, &vars), 1);
    let request = GridRequest {
        dictionary: None,
        unix_time: unix_seconds(2024, 6, 1, 12, 0, 0.0).expect("a valid date"),
        latitude_deg: 40.0,
        longitude_deg: -8.0,
        member: None,
        earth_radius: 6.371e6,
        standard_gravity: 9.80665,
    };
    let p = fetcher(&base).gfs_profile(&request).expect("profile");
    assert_eq!(p.pressure_pa, vec![100_000.0, 85_000.0]);
    // The centre of the 2×2 cell is the mean of its corners: base + 1.5 (+10 per level).
    assert!(
        (p.temperature_k[1] - 291.5).abs() < 1e-9,
        "{}",
        p.temperature_k[1]
    );
    let line = requests.recv().expect("request");
    assert!(
        line.contains("accept=netcdf3") && line.contains("Temperature_isobaric"),
        "{line}"
    );
}
