//! Real flight logs: the detected format and the apogee against the device's (or the
//! flight's official) figure, as the `SOURCE.md` beside each log states it.
//!
//! Logs in the repository (`fixtures/flightlogs`, `fixtures/validation`) are always read.
//! The shared collection `../shared/flightlogs` (beside the workspace root) also holds
//! test-only logs that must never be copied into the repository; without it these tests
//! print a message and pass, unless `CI` is set, when they fail.

use karman_flightlog::{
    ColumnMapping, EventKind, EventSource, FlightLog, FlightLogError, Format, ReadOptions, read,
    read_with,
};
use std::path::{Path, PathBuf};

/// Metres per foot (exact).
const FT: f64 = 0.3048;

/// Prometheus 2022: "Official Recorded Apogee: 3898.37 m" (RocketPy notebook
/// `docs/examples/prometheus_2022_flight_sim.ipynb`, quoted in the folder's SOURCE.md; it is
/// the TeleMega's maximum `height`).
const PROMETHEUS_OFFICIAL_APOGEE_M: f64 = 3898.37;
/// NDRT 2020 Raven: "measured altitude 4,320 ft" (RocketPy notebook
/// `ndrt_2020_flight_sim.ipynb`, SOURCE.md).
const NDRT_MEASURED_APOGEE_FT: f64 = 4320.0;
/// Juno III RRC3: "Apogee registered at Flight Card: `3213 m`" (upstream README.txt).
const JUNO3_FLIGHT_CARD_APOGEE_M: f64 = 3213.0;
/// EREBUS-11 Eggtimer: the device's `Apogee` event column holds 10,434 ft (SOURCE.md).
const EREBUS_DEVICE_APOGEE_FT: f64 = 10_434.0;
/// Hedy CATS Vega: the device's own `flightInfo.csv` estimate, max height 5,230.4 m
/// (SOURCE.md; that file is not copied).
const HEDY_DEVICE_APOGEE_M: f64 = 5230.4;
/// Blue Raven SN0829: the app's summary file, "Max Altitude,4034.98 feet".
const BLUERAVEN_SUMMARY_APOGEE_FT: f64 = 4034.98;
/// Intrepid III pf2: the header line "Apogee: 15373' AGL".
const PF2_HEADER_APOGEE_FT: f64 = 15_373.0;
/// Stargazer 1.2 booster StratoLogger text: no header figure; SOURCE.md measured the
/// altitude column's maximum, 1,530 ft at 9.80 s.
const SG12_MAX_ALTITUDE_FT: f64 = 1530.0;
/// NCSU Jackpot 1 FIRM: `metadata.json` "apogee_meters": 762.28.
const JACKPOT_METADATA_APOGEE_M: f64 = 762.28;

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The shared collection, or `None` (with a message) when absent outside CI.
fn shared() -> Option<PathBuf> {
    let dir = workspace().join("../shared/flightlogs");
    if dir.join("README.md").is_file() {
        return Some(dir);
    }
    let ci = std::env::var("CI").is_ok_and(|v| !matches!(v.trim(), "" | "0" | "false"));
    assert!(
        !ci,
        "{} is absent and CI is set: the real-log tests must run",
        dir.display()
    );
    println!("skipped: {} is absent", dir.display());
    None
}

/// Asserts `value` within 0.5 % or 1 m of `expected`.
fn close(log: &FlightLog, expected: f64, what: &str) {
    let apogee = log.apogee().altitude_agl_m;
    let tolerance = (0.005 * expected).max(1.0);
    assert!(
        (apogee - expected).abs() <= tolerance,
        "{what}: apogee {apogee:.2} m, expected {expected:.2} m ± {tolerance:.2}"
    );
}

fn mapped(spec: &str) -> ReadOptions {
    ReadOptions {
        mapping: Some(ColumnMapping::parse(spec).expect("mapping")),
        ..ReadOptions::default()
    }
}

#[test]
fn vendored_logs_read_in_every_run() {
    let root = workspace().join("fixtures");
    let egg = read(root.join("flightlogs/eggtimer/rocketpy-erebus11-2022/flight_data.csv"))
        .expect("eggtimer");
    assert_eq!(egg.format, Format::Eggtimer);
    close(&egg, EREBUS_DEVICE_APOGEE_FT * FT, "eggtimer");
    let reported = egg.reported.apogee_agl_m.expect("Apogee column");
    assert!((reported - EREBUS_DEVICE_APOGEE_FT * FT).abs() < 1e-6);
    assert!(egg.event(EventKind::Drogue).is_some() && egg.event(EventKind::Main).is_some());

    let raven =
        read(root.join(
            "flightlogs/featherweight-raven-fip/rocketpy-ndrt-2020/ndrt_2020_flight_data.csv",
        ))
        .expect("raven");
    assert_eq!(raven.format, Format::RavenFip);
    close(&raven, NDRT_MEASURED_APOGEE_FT * FT, "raven");
    // The 400 Hz acceleration channel lands on the 20 Hz altitude samples during boost only.
    let with_accel = raven
        .samples
        .iter()
        .filter(|s| s.acceleration_mps2.is_some())
        .count();
    assert!(
        with_accel > 50 && with_accel < raven.samples.len() / 2,
        "{with_accel}"
    );

    let rrc3 = read(root.join("validation/juno3/cots_altimeter.csv")).expect("rrc3");
    assert_eq!(rrc3.format, Format::Rrc3);
    close(&rrc3, JUNO3_FLIGHT_CARD_APOGEE_M, "rrc3");
    // The two glitch rows at the Drogue event (10,700.59 m, then -2,490.54 m) are dropped and
    // reported; the log ends before landing.
    assert!(
        rrc3.warnings.iter().any(|w| w.contains("2 glitch row(s)")),
        "{:?}",
        rrc3.warnings
    );
    assert!(rrc3.warnings.iter().any(|w| w.contains("before landing")));
    assert_eq!(
        rrc3.event(EventKind::Drogue).map(|e| e.source),
        Some(EventSource::Device)
    );

    let metrum = read(
        root.join("validation/prometheus_2022/2022-06-24-serial-5115-flight-0001-TeleMetrum.csv"),
    )
    .expect("telemetrum");
    assert_eq!(metrum.format, Format::AltusMetrum);
    assert!(metrum.device.contains("5115"));
    close(&metrum, PROMETHEUS_OFFICIAL_APOGEE_M, "telemetrum");

    let cats = read(root.join("validation/hedy/filteredDataInfo.csv")).expect("cats filtered");
    assert_eq!(cats.format, Format::CatsVega);
    close(&cats, HEDY_DEVICE_APOGEE_M, "cats filtered");
}

#[test]
fn shared_logs_match_their_devices_figures() {
    let Some(dir) = shared() else { return };
    let metrum = read(dir.join(
        "altusmetrum-csv/rocketpy-prometheus-2022/2022-06-24-serial-5115-flight-0001-TeleMetrum.csv",
    ))
    .expect("telemetrum");
    let mega = read(dir.join(
        "altusmetrum-csv/rocketpy-prometheus-2022/2022-06-24-serial-6583-flight-0003-TeleMega.csv",
    ))
    .expect("telemega");
    assert_eq!(mega.format, Format::AltusMetrum);
    close(&mega, PROMETHEUS_OFFICIAL_APOGEE_M, "telemega");
    close(&metrum, PROMETHEUS_OFFICIAL_APOGEE_M, "telemetrum");
    // Two boards of one flight agree within 1 %.
    let (a, b) = (metrum.apogee().altitude_agl_m, mega.apogee().altitude_agl_m);
    assert!((a - b).abs() <= 0.01 * a.max(b), "{a} vs {b}");
    // Their state changes are device events.
    for log in [&metrum, &mega] {
        for kind in [
            EventKind::Burnout,
            EventKind::Drogue,
            EventKind::Main,
            EventKind::Landing,
        ] {
            assert_eq!(
                log.event(kind).map(|e| e.source),
                Some(EventSource::Device),
                "{kind:?}"
            );
        }
    }

    let raven =
        read(dir.join("featherweight-raven-fip/rocketpy-ndrt-2020/ndrt_2020_flight_data.csv"))
            .expect("raven");
    assert_eq!(raven.format, Format::RavenFip);
    close(&raven, NDRT_MEASURED_APOGEE_FT * FT, "raven");

    let rrc3 =
        read(dir.join("missileworks-rrc3/rocketpy-juno3-2023/cots_altimeter.csv")).expect("rrc3");
    assert_eq!(rrc3.format, Format::Rrc3);
    close(&rrc3, JUNO3_FLIGHT_CARD_APOGEE_M, "rrc3");

    let baro = read(dir.join("cats-vega/rocketpy-hedy-2025/baro.csv")).expect("cats baro");
    assert_eq!(baro.format, Format::CatsVega);
    close(
        &baro,
        HEDY_DEVICE_APOGEE_M,
        "cats baro (ISA pressure altitude)",
    );
    for name in ["imu.csv", "gnssInfo.csv"] {
        let e = read(dir.join("cats-vega/rocketpy-hedy-2025").join(name)).expect_err(name);
        assert!(
            matches!(
                e,
                FlightLogError::NoAltitude {
                    format: "cats-vega",
                    ..
                }
            ),
            "{e}"
        );
    }

    let egg = read(dir.join("eggtimer/rocketpy-erebus11-2022/flight_data.csv")).expect("egg");
    assert_eq!(egg.format, Format::Eggtimer);
    close(&egg, EREBUS_DEVICE_APOGEE_FT * FT, "eggtimer");

    let blue =
        read(dir.join("featherweight-blueraven-app/debrief-trf-kjh-sn0829/blueraven-app-lr.csv"))
            .expect("blue raven");
    assert_eq!(blue.format, Format::BlueRaven);
    close(&blue, BLUERAVEN_SUMMARY_APOGEE_FT * FT, "blue raven");
    // The summary file is no log.
    let e = read(
        dir.join("featherweight-blueraven-app/debrief-trf-kjh-sn0829/blueraven-app.summary.csv"),
    )
    .expect_err("summary");
    assert!(matches!(e, FlightLogError::UnknownFormat { .. }), "{e}");

    let pf2 =
        read(dir.join("perfectflite-pf2/issuiuc-intrepid3-tf2-al0/AL0_march_launch_data.pf2"))
            .expect("pf2");
    assert_eq!(pf2.format, Format::PerfectFlitePf2);
    assert!(pf2.device.contains("5753"), "{}", pf2.device);
    let header = pf2.reported.apogee_agl_m.expect("header apogee");
    assert!((header - PF2_HEADER_APOGEE_FT * FT).abs() < 1e-6);
    assert!((pf2.reported.ground_elevation_m.expect("ground") - 225.0 * FT).abs() < 1e-6);
    close(&pf2, PF2_HEADER_APOGEE_FT * FT, "pf2");
    // The strongly negative first samples are kept and reported.
    assert!(
        pf2.warnings.iter().any(|w| w.contains("below -10 m")),
        "{:?}",
        pf2.warnings
    );
    assert_eq!(
        pf2.event(EventKind::Drogue).map(|e| e.source),
        Some(EventSource::Device)
    );

    let txt = read(dir.join(
        "perfectflite-stratologger-txt/issuiuc-sg1.2-booster/SG1.2-Booster-November-StratoLogger1.txt",
    ))
    .expect("stratologger");
    assert_eq!(txt.format, Format::StratoLoggerText);
    close(&txt, SG12_MAX_ALTITUDE_FT * FT, "stratologger txt");
    assert!(
        txt.samples[0]
            .temperature_k
            .is_some_and(|k| (k - 288.03).abs() < 0.1)
    );

    // Not a format of this crate: a clear error, or a generic mapping.
    let aim = read(dir.join("entacore-aim/debrief-hmc-dofpro/aim-xtra.csv")).expect_err("aim");
    assert!(
        matches!(aim, FlightLogError::UnknownFormat { line: 1, .. }),
        "{aim}"
    );
    let firm_path = dir.join("team-fc-firm/ncsu-jackpot-1/jackpot_launch_1.csv");
    assert!(matches!(
        read(&firm_path),
        Err(FlightLogError::UnknownFormat { .. })
    ));
    let firm = read_with(
        &firm_path,
        &mapped("time=timestamp_seconds,altitude=est_position_z_meters,pressure=pressure_pascals"),
    )
    .expect("firm");
    assert_eq!(firm.format, Format::Generic);
    close(&firm, JACKPOT_METADATA_APOGEE_M, "firm");

    // A GNSS log whose clock goes back at the start: dropped rows are reported.
    let gnss = read_with(
        dir.join("missileworks-rrc3/rocketpy-juno3-2023/cots_GNSS.csv"),
        &mapped("time=time,altitude_msl=ALT:ft,latitude=LAT,longitude=LON,gnss_altitude=ALT:ft"),
    )
    .expect("gnss");
    assert!(
        gnss.warnings.iter().any(|w| w.contains("clock going back")),
        "{:?}",
        gnss.warnings
    );
    assert!(gnss.samples.iter().all(|s| s.gnss.is_some()));
    assert!(gnss.samples.windows(2).all(|w| w[1].time_s > w[0].time_s));
}
