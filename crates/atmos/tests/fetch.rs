//! The `fetch` feature against a loopback HTTP server (std `TcpListener` on 127.0.0.1 in a
//! thread) serving small responses authored here — never the internet.

use crate::common::{Var, classic_nc};
use karman_atmos::AtmosError;
use karman_atmos::fetch::{Endpoints, Fetcher, Request, Service};
use karman_atmos::time::unix_seconds;
use std::io::{BufRead, BufReader, Write};
use std::net::TcpListener;
use std::sync::mpsc;
use std::thread;
use std::time::Duration;

/// How the loopback server answers.
#[derive(Clone, Copy)]
enum Mode {
    /// The whole body with this status.
    Status(u16),
    /// Status 200 announcing more bytes than it sends, then closing.
    Truncated,
    /// No answer for five seconds.
    Silent,
}

/// Serves `body` as `mode` says to `count` requests; returns the base URL and a channel of
/// the request lines received.
fn serve_as(mode: Mode, body: Vec<u8>, count: usize) -> (String, mpsc::Receiver<String>) {
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
            let (status, length) = match mode {
                Mode::Status(s) => (s, body.len()),
                Mode::Truncated => (200, body.len() * 2 + 10),
                Mode::Silent => {
                    thread::sleep(Duration::from_secs(5));
                    continue;
                }
            };
            let head = format!(
                "HTTP/1.1 {status} X\r\nContent-Length: {length}\r\nConnection: close\r\n\r\n"
            );
            let _ = stream.write_all(head.as_bytes());
            let _ = stream.write_all(&body);
        }
    });
    (format!("http://{addr}/svc"), rx)
}

fn serve(status: u16, body: Vec<u8>, count: usize) -> (String, mpsc::Receiver<String>) {
    serve_as(Mode::Status(status), body, count)
}

fn fetcher(base: &str) -> Fetcher {
    Fetcher::new(
        Endpoints {
            wyoming: base.into(),
            gfs_ncss: base.into(),
            open_meteo: base.into(),
            open_meteo_ensemble: format!("{base}/ensemble"),
        },
        Duration::from_secs(1),
    )
    .expect("client")
}

fn request(service: Service, unix_time: f64) -> Request {
    Request {
        service,
        latitude_deg: 40.0,
        longitude_deg: -8.0,
        unix_time,
        station: Some("02963".into()),
        ensemble: false,
        earth_radius: 6.371e6,
        standard_gravity: 9.80665,
    }
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

/// A THREDDS-style GFS subset: dimensions `time1` and `isobaric` (Pa), 2×2 points, one
/// time (2024-06-01 12Z).
fn gfs_subset() -> Vec<u8> {
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
    classic_nc(&dims, &vars)
}

/// An Open-Meteo answer for 2024-06-01 00Z and 01Z: two levels with data at the second hour,
/// every other level null; `members` > 1 adds `_memberNN` arrays (wind + NN m/s).
fn open_meteo_body(members: usize) -> String {
    let t0 = unix_seconds(2024, 6, 1, 0, 0, 0.0).expect("a valid date");
    let mut hourly = format!("\"time\": [{}, {}]", t0, t0 + 3600.0);
    for m in 0..members {
        let suffix = if m == 0 {
            String::new()
        } else {
            format!("_member{m:02}")
        };
        for (l, t, z, s, d) in [
            (1000, 20.0, 110.0, 5.0, 270.0),
            (850, 10.0, 1500.0, 10.0, 180.0),
        ] {
            let s = s + m as f64;
            hourly.push_str(&format!(
                ", \"temperature_{l}hPa{suffix}\": [0, {t}], \
                 \"geopotential_height_{l}hPa{suffix}\": [0, {z}], \
                 \"wind_speed_{l}hPa{suffix}\": [0, {s}], \"wind_direction_{l}hPa{suffix}\": [0, {d}]"
            ));
        }
    }
    hourly.push_str(", \"temperature_700hPa\": [null, null]");
    format!(
        "{{\"elevation\": 50.0, \"hourly_units\": {{\"wind_speed_1000hPa\": \"m/s\"}}, \
         \"hourly\": {{{hourly}}}}}"
    )
}

fn june_first(hour: u32, minute: u32) -> f64 {
    unix_seconds(2024, 6, 1, hour, minute, 0.0).expect("a valid date")
}

#[test]
fn wyoming_by_station_and_date() {
    let (base, requests) = serve(200, WYOMING_PAGE.as_bytes().to_vec(), 1);
    let t = unix_seconds(2006, 4, 10, 12, 0, 0.0).expect("a valid date");
    let d = fetcher(&base)
        .fetch(&request(Service::Wyoming, t))
        .expect("sounding");
    assert_eq!(d.bytes, WYOMING_PAGE.as_bytes(), "the page is kept as sent");
    assert_eq!(d.profile.pressure_pa.len(), 2);
    assert_eq!(d.profile.surface_elevation_m, Some(103.0));
    let line = requests.recv().expect("one request");
    assert!(
        line.contains("id=02963") && line.contains("2006-04-10"),
        "{line}"
    );
    assert!(d.request.contains("id=02963"), "{}", d.request);
    let provenance = d.provenance(&request(Service::Wyoming, t));
    assert!(
        provenance.contains("\"service\": \"wyoming\"") && provenance.contains("id=02963"),
        "{provenance}"
    );
}

#[test]
fn open_meteo_forecast_and_ensemble() {
    let (base, requests) = serve(200, open_meteo_body(1).into_bytes(), 1);
    let d = fetcher(&base)
        .fetch(&request(Service::OpenMeteo, june_first(0, 33)))
        .expect("forecast");
    let p = &d.profile;
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
    assert_eq!(d.members, 1);
    let line = requests.recv().expect("request");
    assert!(
        line.contains("start_date=2024-06-01")
            && line.contains("end_date=2024-06-02")
            && line.contains("wind_speed_unit=ms"),
        "{line}"
    );

    let (base, requests) = serve(200, open_meteo_body(3).into_bytes(), 1);
    let mut r = request(Service::OpenMeteo, june_first(0, 33));
    r.ensemble = true;
    let d = fetcher(&base).fetch(&r).expect("ensemble");
    assert_eq!(d.members, 3);
    let line = requests.recv().expect("request");
    assert!(line.contains("/svc/ensemble?"), "{line}");
}

#[test]
fn gfs_through_ncss() {
    let (base, requests) = serve(200, gfs_subset(), 1);
    let d = fetcher(&base)
        .fetch(&request(Service::Gfs, june_first(12, 0)))
        .expect("profile");
    let p = &d.profile;
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
    // The saved subset reads offline with the GFS mapping (its `time1` coordinate adopted).
    let grid = karman_atmos::WeatherGrid::from_bytes(d.bytes, "gfs.nc").expect("opens");
    assert_eq!(
        grid.detect_dictionary().map(|g| g.time),
        Some("time1".into())
    );
}

/// The body each service sends for a good request.
fn good_body(service: Service) -> Vec<u8> {
    match service {
        Service::OpenMeteo => open_meteo_body(1).into_bytes(),
        Service::Gfs => gfs_subset(),
        Service::Wyoming => WYOMING_PAGE.as_bytes().to_vec(),
    }
}

fn launch(service: Service) -> f64 {
    match service {
        Service::Wyoming => unix_seconds(2006, 4, 10, 12, 0, 0.0).expect("a valid date"),
        Service::Gfs => june_first(12, 0),
        Service::OpenMeteo => june_first(0, 30),
    }
}

/// Fetches from a server answering as `mode` with `body`; returns the error's text.
fn failure(service: Service, mode: Mode, body: Vec<u8>) -> String {
    let (base, _requests) = serve_as(mode, body, 1);
    let e = fetcher(&base)
        .fetch(&request(service, launch(service)))
        .expect_err("fails");
    assert!(matches!(e, AtmosError::Download { .. }), "{e}");
    let text = e.to_string();
    assert!(
        text.contains(service.title()) && text.contains(&base),
        "names service and request: {text}"
    );
    text
}

/// Offline (nothing listens at the address): one line, the cause first, the address once.
#[test]
fn an_unreachable_service_is_one_line_with_the_cause_first() {
    let listener = std::net::TcpListener::bind("127.0.0.1:0").expect("a free port");
    let base = format!("http://{}", listener.local_addr().expect("address"));
    drop(listener);
    let e = fetcher(&base)
        .fetch(&request(Service::OpenMeteo, launch(Service::OpenMeteo)))
        .expect_err("nothing listens");
    let text = e.to_string();
    assert!(!text.contains('\n'), "{text}");
    assert_eq!(text.matches(&base).count(), 1, "{text}");
    let cause = text.find("cannot connect").expect("the cause is named");
    assert!(cause < text.find(&base).expect("the request"), "{text}");
    assert!(
        text.chars().count() < 600,
        "{} characters: {text}",
        text.len()
    );
}

#[test]
fn failures_name_the_service_and_the_request() {
    for (service, _) in Service::ALL.map(|(n, s)| (s, n)) {
        let text = failure(service, Mode::Status(404), b"no such page".to_vec());
        assert!(
            text.contains("HTTP 404") && text.contains("no such page"),
            "{text}"
        );
        let text = failure(
            service,
            Mode::Status(500),
            b"{\"error\": true, \"reason\": \"overloaded\"}".to_vec(),
        );
        assert!(
            text.contains("HTTP 500") && text.contains("overloaded"),
            "{text}"
        );
        let text = failure(service, Mode::Silent, Vec::new());
        assert!(text.contains("timeout"), "{text}");
        let text = failure(service, Mode::Truncated, good_body(service));
        assert!(text.contains("cut short"), "{text}");
        let mut cut = good_body(service);
        cut.truncate(cut.len() / 2);
        let text = failure(service, Mode::Status(200), cut);
        assert!(text.contains("format"), "{text}");
        let text = failure(
            service,
            Mode::Status(200),
            b"<html>maintenance</html>".to_vec(),
        );
        assert!(text.contains("format"), "{text}");
    }
}

#[test]
fn a_launch_outside_the_answer_is_a_coverage_error() {
    let (base, _requests) = serve(200, open_meteo_body(1).into_bytes(), 1);
    let e = fetcher(&base)
        .fetch(&request(Service::OpenMeteo, june_first(5, 0)))
        .expect_err("after the last hour");
    assert!(e.to_string().contains("does not cover the launch"), "{e}");
    let (base, _requests) = serve(200, gfs_subset(), 1);
    let mut r = request(Service::Gfs, june_first(12, 0));
    r.latitude_deg = 45.0;
    let e = fetcher(&base).fetch(&r).expect_err("north of the box");
    assert!(e.to_string().contains("does not cover the launch"), "{e}");
    let mut r = request(Service::Wyoming, june_first(12, 0));
    r.station = None;
    let e = fetcher("http://127.0.0.1:9/none")
        .fetch(&r)
        .expect_err("no station");
    assert!(e.to_string().contains("station"), "{e}");
}
