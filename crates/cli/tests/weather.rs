//! `karman weather fetch|show` and `--fetch` against a loopback HTTP server (std
//! `TcpListener` on 127.0.0.1) serving answers written here in each service's format — never
//! the internet: every service address points at the loopback server.

use crate::common::{failure, karman, stderr};
use karman_validation::netcdf::{Var, classic_nc};
use std::io::{BufRead, BufReader, Write};
use std::net::TcpListener;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::thread;
use std::time::Duration;

/// Serves `body` with `status` (`None`: a 200 that announces more than it sends; status 0:
/// no answer for five seconds) to `count` requests; returns the base URL.
fn serve(status: u16, body: Vec<u8>, count: usize) -> String {
    let listener = TcpListener::bind("127.0.0.1:0").expect("loopback port");
    let addr = listener.local_addr().expect("address");
    thread::spawn(move || {
        for stream in listener.incoming().take(count) {
            let Ok(mut stream) = stream else { continue };
            let mut reader = BufReader::new(stream.try_clone().expect("clone stream"));
            loop {
                let mut line = String::new();
                if reader.read_line(&mut line).unwrap_or(0) == 0 || line.trim().is_empty() {
                    break;
                }
            }
            let length = match status {
                0 => {
                    thread::sleep(Duration::from_secs(5));
                    continue;
                }
                1 => body.len() * 2 + 10,
                _ => body.len(),
            };
            let code = if status == 1 { 200 } else { status };
            let head = format!(
                "HTTP/1.1 {code} X\r\nContent-Length: {length}\r\nConnection: close\r\n\r\n"
            );
            let _ = stream.write_all(head.as_bytes());
            let _ = stream.write_all(&body);
        }
    });
    format!("http://{addr}/svc")
}

/// `karman ARGS` with every service at `base` and a one-second timeout.
fn karman_at(base: &str, args: &[&str]) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_karman"));
    for variable in [
        "KARMAN_OPEN_METEO_URL",
        "KARMAN_OPEN_METEO_ENSEMBLE_URL",
        "KARMAN_GFS_NCSS_URL",
        "KARMAN_WYOMING_URL",
    ] {
        command.env(variable, base);
    }
    command
        .env("KARMAN_WEATHER_TIMEOUT", "1")
        .args(args)
        .output()
        .expect("the karman binary runs")
}

fn ok(output: &Output) -> String {
    assert!(output.status.success(), "stderr: {}", stderr(output));
    String::from_utf8_lossy(&output.stdout).into_owned()
}

/// The launch the answers below cover: 2026-09-12 15:00 UTC at the example mission's site.
const DATE: &str = "2026-09-12T15:00:00Z";
const LAT: f64 = 40.85;
const LON: f64 = -119.12;

fn t0() -> f64 {
    karman_mission::atmos::time::unix_seconds(2026, 9, 12, 14, 0, 0.0).expect("date")
}

/// Open-Meteo levels: (hPa, °C, geopotential m, wind m/s, from deg).
const LEVELS: [(u32, f64, f64, f64, f64); 6] = [
    (1000, 24.0, 110.0, 3.0, 250.0),
    (850, 18.0, 1500.0, 6.0, 260.0),
    (700, 6.0, 3100.0, 9.0, 270.0),
    (500, -12.0, 5800.0, 14.0, 280.0),
    (300, -40.0, 9500.0, 22.0, 290.0),
    (100, -65.0, 16500.0, 12.0, 300.0),
];

/// An Open-Meteo answer for 14Z, 15Z and 16Z (the same profile each hour); `members` > 1
/// adds the ensemble's `_memberNN` arrays (wind + NN m/s).
fn open_meteo(members: usize) -> Vec<u8> {
    let t = t0();
    let mut hourly = format!("\"time\": [{t}, {}, {}]", t + 3600.0, t + 7200.0);
    for m in 0..members {
        let suffix = if m == 0 {
            String::new()
        } else {
            format!("_member{m:02}")
        };
        for (l, temp, z, s, d) in LEVELS {
            let s = s + m as f64;
            hourly.push_str(&format!(
                ", \"temperature_{l}hPa{suffix}\": [{temp}, {temp}, {temp}], \
                 \"geopotential_height_{l}hPa{suffix}\": [{z}, {z}, {z}], \
                 \"wind_speed_{l}hPa{suffix}\": [{s}, {s}, {s}], \
                 \"wind_direction_{l}hPa{suffix}\": [{d}, {d}, {d}]"
            ));
        }
    }
    format!(
        "{{\"latitude\": {LAT}, \"longitude\": {LON}, \"elevation\": 1190.0, \
         \"utc_offset_seconds\": 0, \"hourly_units\": {{\"temperature_1000hPa\": \"°C\", \
         \"wind_speed_1000hPa\": \"m/s\", \"geopotential_height_1000hPa\": \"m\"}}, \
         \"hourly\": {{{hourly}}}}}"
    )
    .into_bytes()
}

/// A THREDDS NCSS GFS subset around the site at 15Z: `time1`, `isobaric` in Pa, 2×2 points.
fn gfs() -> Vec<u8> {
    let dims = [("time1", 1), ("isobaric", 3), ("lat", 2), ("lon", 2)];
    let field =
        |values: [f64; 3]| -> Vec<f64> { values.iter().flat_map(|&v| [v, v, v, v]).collect() };
    let vars = vec![
        Var {
            name: "time1",
            dims: vec![0],
            attrs: vec![("units", "Hour since 2026-09-12T12:00:00Z")],
            data: vec![3.0],
        },
        Var {
            name: "isobaric",
            dims: vec![1],
            attrs: vec![("units", "Pa")],
            data: vec![100_000.0, 85_000.0, 50_000.0],
        },
        Var {
            name: "lat",
            dims: vec![2],
            attrs: vec![],
            data: vec![LAT + 0.5, LAT - 0.5],
        },
        Var {
            name: "lon",
            dims: vec![3],
            attrs: vec![],
            data: vec![360.0 + LON - 0.5, 360.0 + LON + 0.5],
        },
        Var {
            name: "Temperature_isobaric",
            dims: vec![0, 1, 2, 3],
            attrs: vec![],
            data: field([297.0, 291.0, 261.0]),
        },
        Var {
            name: "Geopotential_height_isobaric",
            dims: vec![0, 1, 2, 3],
            attrs: vec![],
            data: field([110.0, 1500.0, 5800.0]),
        },
        Var {
            name: "u-component_of_wind_isobaric",
            dims: vec![0, 1, 2, 3],
            attrs: vec![],
            data: field([2.0, 5.0, 12.0]),
        },
        Var {
            name: "v-component_of_wind_isobaric",
            dims: vec![0, 1, 2, 3],
            attrs: vec![],
            data: field([1.0, -1.0, 3.0]),
        },
    ];
    classic_nc(&dims, &vars)
}

/// A Wyoming TEXT:LIST page (winds in knots).
const WYOMING: &str = "<html><body><h2>72489 REV Reno Observations at 12Z 12 Sep 2026</h2>\n\
<pre>\n\
-----------------------------------------------------------------------------\n\
   PRES   HGHT   TEMP   DWPT   RELH   MIXR   DRCT   SKNT   THTA   THTE   THTV\n\
    hPa     m      C      C      %    g/kg    deg   knot     K      K      K\n\
-----------------------------------------------------------------------------\n\
  870.0   1516   22.0    1.0     25   4.70    240      6  307.3  321.9  308.2\n\
  850.0   1700   20.0    0.0     26   4.55    250     10  307.1  321.2  308.0\n\
  700.0   3180    8.0  -10.0     27   2.55    260     20  310.0  318.3  310.5\n\
  500.0   5880  -10.0  -30.0     18   0.48    270     35  320.0  321.8  320.1\n\
  300.0   9600  -38.0  -50.0     27   0.08    280     50  334.0  334.3  334.0\n\
</pre><h3>Station information and sounding indices</h3><pre>\n\
                         Station elevation: 1516.0\n</pre></body></html>\n";

/// A scratch copy of the example mission (its data files beside it) with this
/// `[environment.atmosphere]` body; returns the mission path.
fn mission(folder: &str, atmosphere: &str) -> PathBuf {
    let fixtures = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures");
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("karman-cli/weather")
        .join(folder);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    for file in [
        "example_K1960.eng",
        "power_off_drag.csv",
        "power_on_drag.csv",
    ] {
        std::fs::copy(fixtures.join(file), dir.join(file)).expect("data file");
    }
    let text = std::fs::read_to_string(fixtures.join("example.toml")).expect("example");
    let text = text.replace(
        "[environment.atmosphere]\nmodel = \"standard\"",
        &format!("[environment.atmosphere]\n{atmosphere}"),
    );
    assert!(
        text.contains(atmosphere),
        "the example's atmosphere was replaced"
    );
    let path = dir.join("mission.toml");
    std::fs::write(&path, text).expect("mission");
    path
}

fn scratch_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("karman-cli/weather")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

fn text(path: &Path) -> &str {
    path.to_str().expect("UTF-8 path")
}

/// `weather fetch` of one source, then `weather show`, then a mission flying on the file.
fn end_to_end(source: &str, body: Vec<u8>, file: &str, extra: &[&str], atmosphere: &str) {
    let base = serve(200, body.clone(), 1);
    let dir = scratch_dir(&format!("fetch-{source}"));
    let out = dir.join(file);
    let (lat, lon) = (LAT.to_string(), LON.to_string());
    let mut args = vec![
        "weather", "fetch", "--source", source, "--lat", &lat, "--lon", &lon, "--date", DATE, "-o",
    ];
    args.push(text(&out));
    args.extend_from_slice(extra);
    let printed = ok(&karman_at(&base, &args));
    assert!(printed.contains("request: http://127.0.0.1"), "{printed}");
    assert_eq!(std::fs::read(&out).expect("file written"), body, "as sent");
    let provenance =
        std::fs::read_to_string(dir.join(format!("{file}.provenance.json"))).expect("provenance");
    assert!(
        provenance.contains(&format!("\"service\": \"{source}\""))
            && provenance.contains("\"downloaded\"")
            && provenance.contains("127.0.0.1"),
        "{provenance}"
    );
    let shown = ok(&karman(&[
        "weather",
        "show",
        text(&out),
        "--lat",
        &lat,
        "--lon",
        &lon,
        "--date",
        DATE,
    ]));
    assert!(
        shown.contains("height m") && shown.contains("p hPa"),
        "{shown}"
    );
    let plots = dir.join("plots");
    ok(&karman(&[
        "weather",
        "show",
        text(&out),
        "--lat",
        &lat,
        "--lon",
        &lon,
        "--date",
        DATE,
        "--plot",
        text(&plots),
    ]));
    for chart in ["temperature", "pressure", "wind_speed", "wind_direction"] {
        assert!(plots.join(format!("{chart}.svg")).is_file(), "{chart}");
    }
    let atmosphere = atmosphere.replace("FILE", text(&out));
    let m = mission(&format!("fly-{source}"), &atmosphere);
    let summary = ok(&karman(&["simulate", text(&m), "--json"]));
    assert!(summary.contains("apogee_agl_m"), "{summary}");
}

#[test]
fn open_meteo_end_to_end() {
    end_to_end(
        "open-meteo",
        open_meteo(1),
        "launch.json",
        &[],
        "model = \"open_meteo\"\nfile = \"FILE\"",
    );
}

#[test]
fn gfs_end_to_end() {
    end_to_end(
        "gfs",
        gfs(),
        "gfs.nc",
        &[],
        "model = \"forecast\"\nfile = \"FILE\"",
    );
}

#[test]
fn wyoming_end_to_end() {
    end_to_end(
        "wyoming",
        WYOMING.as_bytes().to_vec(),
        "reno.txt",
        &["--station", "72489"],
        "model = \"sounding\"\nformat = \"wyoming\"\nfile = \"FILE\"",
    );
}

#[test]
fn service_failures_are_clear_errors() {
    let dir = scratch_dir("failures");
    let out = dir.join("x.json");
    let (lat, lon) = (LAT.to_string(), LON.to_string());
    let args = [
        "weather",
        "fetch",
        "--source",
        "open-meteo",
        "--lat",
        &lat,
        "--lon",
        &lon,
        "--date",
        DATE,
        "-o",
        text(&out),
    ];
    let mut half = open_meteo(1);
    half.truncate(half.len() / 2);
    for (status, body, needle) in [
        (404, b"Not Found".to_vec(), "HTTP 404"),
        (
            500,
            b"{\"error\": true, \"reason\": \"Internal error\"}".to_vec(),
            "Internal error",
        ),
        (
            400,
            b"{\"error\": true, \"reason\": \"Parameter 'start_date' is out of allowed range\"}"
                .to_vec(),
            "out of allowed range",
        ),
        (0, Vec::new(), "timeout"),
        (1, open_meteo(1), "cut short"),
        (200, half, "format"),
        (200, b"<html>maintenance</html>".to_vec(), "format"),
    ] {
        let base = serve(status, body, 1);
        let output = karman_at(&base, &args);
        let message = stderr(&output);
        assert!(!message.contains("panicked at"), "{message}");
        assert_eq!(output.status.code(), Some(1), "{message}");
        assert!(
            message.contains("Open-Meteo") && message.contains(&base) && message.contains(needle),
            "{status}: {message}"
        );
        assert!(!out.exists(), "nothing written on a failure");
    }
    // A site the answer does not cover.
    let base = serve(200, gfs(), 1);
    let output = karman_at(
        &base,
        &[
            "weather",
            "fetch",
            "--source",
            "gfs",
            "--lat",
            "10",
            "--lon",
            &lon,
            "--date",
            DATE,
            "-o",
            text(&dir.join("x.nc")),
        ],
    );
    assert!(
        stderr(&output).contains("does not cover the launch"),
        "{}",
        stderr(&output)
    );
    // The station goes with Wyoming: each misuse says which way round.
    let wyoming = [
        "weather", "fetch", "--source", "wyoming", "--lat", &lat, "--lon", &lon,
    ];
    let message = failure(&[&wyoming[..], &["--date", DATE, "-o", text(&out)]].concat());
    assert!(
        message.contains("--source wyoming needs --station ID"),
        "{message}"
    );
    let message = failure(&[&args[..], &["--station", "02963"]].concat());
    assert!(
        message.contains("--station 02963 is for --source wyoming only"),
        "{message}"
    );
    // Missions read offline: a missing file is a plain error that suggests nothing remote.
    let m = mission(
        "offline",
        "model = \"open_meteo\"\nfile = \"absent.json\"\nsource = \"open-meteo\"",
    );
    let message = failure(&["simulate", text(&m)]);
    assert!(message.contains("absent.json"), "{message}");
}

#[test]
fn simulate_and_montecarlo_fetch_into_the_mission_folder() {
    let m = mission(
        "fetch-flag",
        "model = \"open_meteo\"\nfile = \"weather/launch.json\"\nsource = \"open-meteo\"\n\
         member = 2",
    );
    let base = serve(200, open_meteo(4), 2);
    let summary = ok(&karman_at(
        &base,
        &["simulate", text(&m), "--fetch", "--json"],
    ));
    assert!(summary.contains("apogee_agl_m"), "{summary}");
    let file = m.with_file_name("weather/launch.json");
    assert_eq!(std::fs::read(&file).expect("downloaded"), open_meteo(4));
    assert!(
        m.with_file_name("weather/launch.json.provenance.json")
            .is_file()
    );
    // Member 3 is the last one; member 4 does not exist.
    let message = failure(&[
        "simulate",
        text(&m),
        "--set",
        "environment.atmosphere.member=4",
    ]);
    assert!(message.contains("member 4"), "{message}");
    // The Monte Carlo study fingerprints the downloaded file.
    let out = m.with_file_name("study");
    ok(&karman_at(
        &base,
        &[
            "montecarlo",
            text(&m),
            "--fetch",
            "--samples",
            "2",
            "--quiet",
            "--out",
            text(&out),
        ],
    ));
    let study = std::fs::read_to_string(out.join("study.json")).expect("study.json");
    assert!(study.contains("launch.json"), "{study}");
}

/// The atmosphere of `mission` at `heights` (`inspect --json`).
fn atmosphere_at(mission: &Path, heights: &str) -> serde_json::Value {
    let printed = ok(&karman(&[
        "inspect",
        text(mission),
        "--json",
        "--heights",
        heights,
    ]));
    let json: serde_json::Value = serde_json::from_str(&printed).expect("JSON");
    json["environment"].clone()
}

#[test]
fn a_saved_open_meteo_file_is_the_custom_profile_of_its_numbers() {
    let dir = scratch_dir("same-atmosphere");
    let file = dir.join("launch.json");
    std::fs::write(&file, open_meteo(1)).expect("file");
    let forecast = mission(
        "same-forecast",
        &format!("model = \"open_meteo\"\nfile = \"{}\"", text(&file)),
    );
    // The same numbers by hand: geometric heights R·H/(R − H) with the datum's radius at the
    // site, kelvin, and the wind towards where it blows.
    let radius = karman_mission::atmos::Datum::Sirgas2000
        .radius(LAT, &karman_mission::math::PhysicalConstants::SI);
    let points = |f: &dyn Fn(f64, f64, f64, f64) -> f64| {
        let rows: Vec<String> = LEVELS
            .iter()
            .map(|&(p, t, z, s, d)| {
                let h = radius * z / (radius - z);
                format!("[{h:?}, {:?}]", f(f64::from(p), t, s, d))
            })
            .collect();
        format!("[{}]", rows.join(", "))
    };
    let custom = format!(
        "model = \"custom\"\npressure = {}\ntemperature = {}\nwind_u = {}\nwind_v = {}",
        points(&|p, _, _, _| p * 100.0),
        points(&|_, t, _, _| t + 273.15),
        points(&|_, _, s, d| -s * d.to_radians().sin()),
        points(&|_, _, s, d| -s * d.to_radians().cos()),
    );
    let custom = mission("same-custom", &custom);
    let heights = "1190,2000,4321,7777,12000";
    let a = atmosphere_at(&forecast, heights);
    let b = atmosphere_at(&custom, heights);
    for key in [
        "pressure_pa",
        "temperature_k",
        "density_kgpm3",
        "wind_u_mps",
        "wind_v_mps",
        "speed_of_sound_mps",
    ] {
        let (x, y) = (&a[key], &b[key]);
        let (Some(x), Some(y)) = (x.as_array(), y.as_array()) else {
            panic!("{key}: {a} / {b}");
        };
        assert_eq!(x.len(), 5, "{key}");
        for (u, v) in x.iter().zip(y) {
            let (u, v) = (u.as_f64().expect("number"), v.as_f64().expect("number"));
            assert!(
                (u - v).abs() <= 1e-9 * u.abs().max(1.0),
                "{key}: {u} vs {v}"
            );
        }
    }
    let fly = |m: &Path| {
        let printed = ok(&karman(&["simulate", text(m), "--json"]));
        let mut json: serde_json::Value = serde_json::from_str(&printed).expect("JSON");
        json.as_object_mut().map(|o| o.remove("warnings"));
        json["apogee_agl_m"].as_f64().expect("apogee")
    };
    let (x, y) = (fly(&forecast), fly(&custom));
    assert!((x - y).abs() <= 1e-9 * x, "apogee {x} vs {y}");
}

#[test]
fn weather_heights_that_fold_back_are_a_warning() {
    let good = String::from_utf8(open_meteo(1)).expect("text");
    // 700 hPa placed below 850 hPa.
    let folded = good.replace("[3100, 3100, 3100]", "[1400, 1400, 1400]");
    assert_ne!(good, folded);
    let dir = scratch_dir("folded");
    let file = dir.join("folded.json");
    std::fs::write(&file, folded).expect("file");
    let m = mission(
        "folded-mission",
        &format!("model = \"open_meteo\"\nfile = \"{}\"", text(&file)),
    );
    for args in [vec!["check"], vec!["simulate", "--json"]] {
        let command = args[0];
        let mut args = args.clone();
        args.insert(1, text(&m));
        let output = karman(&args);
        let message = format!(
            "{}{}",
            String::from_utf8_lossy(&output.stdout),
            stderr(&output)
        );
        assert!(
            message.contains(
                "`environment.atmosphere.file`: the heights are not monotonic through the \
                 levels: 850.0 hPa at 1500 m, then 700.0 hPa at 1400 m"
            ),
            "{command}: {message}"
        );
    }
}

/// An Open-Meteo file with one usable pressure level (every height the same pressure and
/// temperature) fails `check` as it fails the flight, naming the file and the level; with two
/// levels it checks and flies.
#[test]
fn a_single_level_open_meteo_file_fails_check() {
    for (name, kept, refused) in [
        ("one-level", &["850hPa"][..], true),
        ("two-levels", &["850hPa", "700hPa"][..], false),
    ] {
        let mut json: serde_json::Value =
            serde_json::from_slice(&open_meteo(1)).expect("the answer is JSON");
        let hourly = json["hourly"].as_object_mut().expect("hourly");
        hourly.retain(|key, _| key == "time" || kept.iter().any(|l| key.ends_with(l)));
        let m = mission(name, "model = \"open_meteo\"\nfile = \"levels.json\"");
        let file = m.with_file_name("levels.json");
        std::fs::write(&file, json.to_string()).expect("weather file");
        let check = karman(&["check", text(&m)]);
        let fly = karman(&["simulate", text(&m)]);
        if refused {
            let message = stderr(&check);
            assert_eq!(check.status.code(), Some(1), "{message}");
            assert!(
                message.contains("levels.json")
                    && message.contains("`environment.atmosphere")
                    && message.contains("only the 850 hPa level"),
                "{message}"
            );
            assert_eq!(fly.status.code(), Some(1));
            assert_eq!(stderr(&fly), message, "check and the flight fail alike");
        } else {
            ok(&check);
            ok(&fly);
        }
    }
}

/// A write error on stdout is an error (exit 1), never exit 0 or a panic: `--help`,
/// `--version` and a command's report into a full device.
#[cfg(target_os = "linux")]
#[test]
fn writing_into_a_full_device_fails() {
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/example.toml");
    for args in [
        vec!["--help"],
        vec!["--version"],
        vec!["check", text(&example)],
    ] {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .expect("/dev/full");
        let output = Command::new(env!("CARGO_BIN_EXE_karman"))
            .args(&args)
            .stdout(full)
            .output()
            .expect("runs");
        let message = stderr(&output);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {message}");
        assert!(!message.contains("panicked"), "{message}");
    }
}
