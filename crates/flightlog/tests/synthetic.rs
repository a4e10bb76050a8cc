//! Synthetic logs written by the tests: one per format, from one known flight, and every
//! bad input (empty, binary, a 10 000-column line, huge numbers, NaN, truncated rows, glitch
//! rows, a clock going back, a mapping naming a missing column, no liftoff).

use karman_flightlog::{
    ColumnMapping, EventKind, EventSource, FlightLog, FlightLogError, Format, ReadOptions,
    VelocitySource, parse,
};

const FT: f64 = 0.3048;
/// Boost acceleration of the synthetic flight, m/s² (for 2 s).
const BOOST: f64 = 60.0;
const G: f64 = 9.80665;
/// Descent rate, m/s.
const DESCENT: f64 = 10.0;

/// The synthetic flight: height (m AGL) and vertical velocity (m/s) at `t` s from liftoff.
fn flight(t: f64) -> (f64, f64) {
    let burnout = 2.0;
    let (hb, vb) = (0.5 * BOOST * burnout * burnout, BOOST * burnout);
    let apogee_t = burnout + vb / G;
    let apogee_h = hb + vb * vb / (2.0 * G);
    if t <= 0.0 {
        (0.0, 0.0)
    } else if t <= burnout {
        (0.5 * BOOST * t * t, BOOST * t)
    } else if t <= apogee_t {
        let c = t - burnout;
        (hb + vb * c - 0.5 * G * c * c, vb - G * c)
    } else {
        (
            (apogee_h - DESCENT * (t - apogee_t)).max(0.0),
            if apogee_h - DESCENT * (t - apogee_t) > 0.0 {
                -DESCENT
            } else {
                0.0
            },
        )
    }
}

fn apogee_m() -> f64 {
    let vb = BOOST * 2.0;
    0.5 * BOOST * 4.0 + vb * vb / (2.0 * G)
}

/// Times from -1 s to 100 s at `rate` Hz.
fn times(rate: f64) -> impl Iterator<Item = f64> {
    (0..)
        .map(move |i| -1.0 + f64::from(i) / rate)
        .take_while(|t| *t <= 100.0)
}

fn read(text: &str) -> Result<FlightLog, FlightLogError> {
    parse(text.as_bytes(), "synthetic", &ReadOptions::default())
}

fn read_mapped(text: &str, spec: &str) -> Result<FlightLog, FlightLogError> {
    let mapping = ColumnMapping::parse(spec).expect("mapping");
    parse(
        text.as_bytes(),
        "synthetic",
        &ReadOptions {
            mapping: Some(mapping),
            ..ReadOptions::default()
        },
    )
}

/// The flight read back: format, apogee within 1 m, liftoff within 0.15 s of the truth.
fn check(log: &FlightLog, format: Format, device_time_of_liftoff: f64) {
    assert_eq!(log.format, format);
    let apogee = log.apogee();
    assert!(
        (apogee.altitude_agl_m - apogee_m()).abs() < 1.0,
        "{format}: apogee {}",
        apogee.altitude_agl_m
    );
    assert!(
        (log.liftoff_device_time_s - device_time_of_liftoff).abs() < 0.15,
        "{format}: liftoff {}",
        log.liftoff_device_time_s
    );
    let (vmax, _) = log.max_vertical_velocity();
    assert!(
        (vmax - BOOST * 2.0).abs() < 8.0,
        "{format}: max velocity {vmax}"
    );
    assert!(
        log.event(EventKind::Landing).is_some(),
        "{format}: {:?}",
        log.events
    );
    assert!(log.samples.windows(2).all(|w| w[1].time_s > w[0].time_s));
}

#[test]
fn altus_metrum() {
    let mut s = String::from(
        "#version,serial,flight,call,time,state,state_name,acceleration,pressure,altitude,height,speed,temperature\n",
    );
    for t in times(100.0) {
        let (h, v) = flight(t);
        let (state, name) = if t < 2.0 {
            (3, "boost")
        } else if v > 0.0 {
            (5, "coast")
        } else if h > 100.0 {
            (6, "drogue")
        } else if h > 0.0 {
            (7, "main")
        } else {
            (8, "landed")
        };
        let a = if (0.0..2.0).contains(&t) { BOOST } else { 0.0 };
        s.push_str(&format!("6, 42, 1,TEST, {t:.2}, {state}, {name}, {a:.2}, 90000.00, {:.2}, {h:.2}, {v:.2}, 20.0\n", h + 1000.0));
    }
    let log = read(&s).expect("altus");
    check(&log, Format::AltusMetrum, 0.0);
    assert!(log.device.contains("42"));
    assert_eq!(log.velocity_source, VelocitySource::Device);
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
    let burnout = log.event(EventKind::Burnout).expect("burnout").time_s;
    assert!((burnout - 2.0).abs() < 0.05, "{burnout}");
    assert!(
        log.samples[0]
            .temperature_k
            .is_some_and(|k| (k - 293.15).abs() < 1e-9)
    );
}

#[test]
fn raven_fip_per_channel_times() {
    let mut s = String::from(
        "Time-Axial Accel (Gs), Axial Accel (Gs), bILBA, Time (s), Altitude (Ft-AGL), bILBA\n",
    );
    let alt: Vec<f64> = times(20.0).collect();
    let acc: Vec<f64> = (0..2400).map(|i| -1.0 + f64::from(i) / 400.0).collect();
    for i in 0..alt.len().max(acc.len()) {
        let a = acc.get(i).map_or(",,".to_owned(), |&t| {
            let g = if (0.0..2.0).contains(&t) {
                BOOST / G + 1.0
            } else {
                1.0
            };
            format!("{t},{g:.3},b0000")
        });
        let h = alt.get(i).map_or(",,".to_owned(), |&t| {
            format!("{t},{:.3},b0000", flight(t).0 / FT)
        });
        s.push_str(&format!("{a},{h}\n"));
    }
    let log = read(&s).expect("raven");
    check(&log, Format::RavenFip, 0.0);
    assert_eq!(log.velocity_source, VelocitySource::Derivative);
    let boosting = log
        .samples
        .iter()
        .find(|x| (x.time_s - 1.0).abs() < 0.03)
        .expect("t = 1 s");
    let a = boosting.acceleration_mps2.expect("accel channel at 1 s");
    assert!((a - (BOOST + G)).abs() < 0.1, "{a}");
}

#[test]
fn blue_raven() {
    let mut s = String::from(
        "Year,Month,Day,Time,Flight_Time_(s),Sync,Temperature_(F),Baro_Press_(atm),Baro_Altitude_ASL_(feet),Baro_Altitude_AGL_(feet),Velocity_Up,\n",
    );
    for t in times(25.0) {
        let (h, v) = flight(t);
        s.push_str(&format!(
            "2024,5,11,14:09:44.602,{t:.2},0,68.0,0.99,{:.1},{:.1},{:.2},0,0\n",
            (h + 100.0) / FT,
            h / FT,
            v / FT
        ));
    }
    let log = read(&s).expect("blue raven");
    check(&log, Format::BlueRaven, 0.0);
    assert!(
        log.samples[0]
            .temperature_k
            .is_some_and(|k| (k - 293.15).abs() < 1e-9)
    );
    assert!(
        log.samples[0]
            .pressure_pa
            .is_some_and(|p| (p - 0.99 * 101_325.0).abs() < 1e-6)
    );
}

#[test]
fn perfectflite_pf2_header_block() {
    let mut s = String::from(
        "PerfectFlite SLCF\nFirmware: 1.0\nSerial Number: 77\nApogee: 2804' AGL\nGround Elevation: 100' MSL\nDrogue At: 14.30 Seconds\nMain At: 90.00 Seconds\nComments: \n\nData: (Time, Altitude, Velocity, Temperature (F), Voltage)\n",
    );
    for t in times(20.0).filter(|t| *t >= 0.0) {
        let (h, v) = flight(t);
        s.push_str(&format!(
            "{t:.2}, {:.0}, {:.0}, 75.00, 8.10\n",
            h / FT,
            v / FT
        ));
    }
    let log = read(&s).expect("pf2");
    check(&log, Format::PerfectFlitePf2, 0.0);
    assert_eq!(log.device, "PerfectFlite SLCF serial 77");
    assert!((log.reported.apogee_agl_m.expect("apogee") - 2804.0 * FT).abs() < 1e-9);
    assert!((log.reported.ground_elevation_m.expect("ground") - 100.0 * FT).abs() < 1e-9);
    let drogue = log.event(EventKind::Drogue).expect("drogue");
    assert_eq!(drogue.source, EventSource::Device);
    assert!((drogue.time_s - (14.30 - log.liftoff_device_time_s)).abs() < 1e-9);
}

#[test]
fn stratologger_text() {
    let mut s = String::from("Time\tAltitude\tTemp.\tVoltage\n");
    for t in times(20.0).filter(|t| *t >= 0.0) {
        s.push_str(&format!("{t:.2}\t{:.0}\t58.7F\t9.6\n", flight(t).0 / FT));
    }
    let log = read(&s).expect("stratologger");
    check(&log, Format::StratoLoggerText, 0.0);
    let k = log.samples[0].temperature_k.expect("temperature");
    assert!((k - ((58.7 - 32.0) * 5.0 / 9.0 + 273.15)).abs() < 1e-9);
}

fn rrc3_text(rows: impl Iterator<Item = f64>) -> String {
    let mut s = String::from("time,altitude,pressure,velocity,temperature,events,voltages\n");
    for t in rows {
        let (h, v) = flight(t);
        let event = if (t - 14.25).abs() < 0.01 {
            "Drogue"
        } else {
            "-"
        };
        s.push_str(&format!("{t:.2},{h:.3},900.0,{v:.3},25.0, {event},3.8\n"));
    }
    s
}

#[test]
fn rrc3_and_its_drogue_event() {
    let log = read(&rrc3_text(times(20.0).filter(|t| *t >= 0.0))).expect("rrc3");
    check(&log, Format::Rrc3, 0.0);
    assert!(
        log.samples[0]
            .pressure_pa
            .is_some_and(|p| (p - 90_000.0).abs() < 1e-9)
    );
    assert_eq!(
        log.event(EventKind::Drogue).map(|e| e.source),
        Some(EventSource::Device)
    );
}

#[test]
fn eggtimer_ms_and_event_columns() {
    let mut s = String::from("T,Alt,Veloc,FAlt,FVeloc,LDA,LowV,Apogee,N-O,Drogue,Main\n");
    let apogee_ft = (apogee_m() / FT).round();
    for t in times(20.0).filter(|t| *t >= 0.0) {
        let (h, v) = flight(t);
        let after = |at: f64, value: f64| if t >= at { value } else { 0.0 };
        s.push_str(&format!(
            "{:.0},{:.0},{:.0},{:.0},{:.0},{},0,{},0,{},{}\n",
            t * 1000.0,
            h / FT,
            v / FT,
            h / FT,
            v / FT,
            after(0.5, 25.0),
            after(14.3, apogee_ft),
            after(14.3, apogee_ft),
            after(80.0, 300.0)
        ));
    }
    let log = read(&s).expect("eggtimer");
    check(&log, Format::Eggtimer, 0.0);
    assert!((log.reported.apogee_agl_m.expect("Apogee column") - apogee_ft * FT).abs() < 1e-9);
    let main = log.event(EventKind::Main).expect("main");
    assert!((main.time_s - (80.0 - log.liftoff_device_time_s)).abs() < 0.06);
}

#[test]
fn cats_vega_barometer_as_pressure_altitude() {
    // The ISA troposphere's pressure at the height (the reader's own inverse).
    let p = |h: f64| 101_325.0 * (1.0 - 0.0065 * h / 288.15).powf(G / (287.052_87 * 0.0065));
    let mut s = String::from("ts,id,T,P\n");
    for t in times(100.0) {
        s.push_str(&format!("{t:.3},BARO0,20.0,{:.2}\n", p(flight(t).0)));
        s.push_str(&format!("{t:.3},BARO1,20.0,{:.2}\n", p(flight(t).0) + 50.0));
    }
    let log = read(&s).expect("cats");
    check(&log, Format::CatsVega, 0.0);
    assert!(
        log.warnings.iter().any(|w| w.contains("other than BARO0")),
        "{:?}",
        log.warnings
    );
    let imu = read("ts,id,Ax,Ay,Az,Gx,Gy,Gz\n0.0,IMU0,0,-9.8,0,0,0,0\n").expect_err("imu");
    assert!(matches!(imu, FlightLogError::NoAltitude { .. }), "{imu}");
}

#[test]
fn generic_mapping_with_units() {
    let mut s = String::from("when_ms;alt_ft;vz;temp_f\n");
    for t in times(10.0) {
        let (h, v) = flight(t);
        s.push_str(&format!(
            "{:.0};{:.3};{:.3};50\n",
            t * 1000.0,
            h / FT,
            v / FT
        ));
    }
    let log = read_mapped(
        &s,
        "time=when_ms:ms, altitude=alt_ft:ft, velocity=vz:ft/s, temperature=temp_f:F",
    )
    .expect("generic");
    check(&log, Format::Generic, 0.0);
    assert_eq!(log.velocity_source, VelocitySource::Device);
    assert!(
        log.samples[0]
            .temperature_k
            .is_some_and(|k| (k - 283.15).abs() < 1e-9)
    );
    // Without the mapping: unknown, with a clear error on line 1.
    let e = read(&s).expect_err("unknown");
    assert!(
        matches!(e, FlightLogError::UnknownFormat { line: 1, .. }),
        "{e}"
    );
    assert!(e.to_string().contains("mapping"));
}

#[test]
fn mapping_errors() {
    for (spec, needle) in [
        ("altitude=h", "no 'time'"),
        ("time=t", "no 'altitude'"),
        ("time=t,height=h", "unknown key"),
        ("time=t,altitude=h:furlong", "unknown unit"),
        ("time=t:ft,altitude=h", "is a time"),
        ("time=t,time=u,altitude=h", "twice"),
        ("time,altitude=h", "not key=column"),
    ] {
        let e = ColumnMapping::parse(spec).expect_err(spec);
        assert!(e.to_string().contains(needle), "{spec}: {e}");
    }
    let e = read_mapped("t,h\n0,0\n", "time=t,altitude=alt").expect_err("missing column");
    assert_eq!(
        e,
        FlightLogError::MissingColumn {
            file: "synthetic".into(),
            line: 1,
            column: "alt".into()
        }
    );
}

#[test]
fn empty_and_binary_files() {
    for text in ["", "   \n\r\n\t"] {
        assert!(matches!(read(text), Err(FlightLogError::Empty { .. })));
    }
    let mut bytes = b"time,altitude\n0,0\n".to_vec();
    bytes.extend([0u8, 1, 2, 255, 254, 0, 7]);
    let e = parse(&bytes, "garbage.bin", &ReadOptions::default()).expect_err("binary");
    assert!(matches!(e, FlightLogError::Binary { line: 3, .. }), "{e}");
    assert!(e.to_string().starts_with("garbage.bin:3:"));
}

#[test]
fn ten_thousand_columns() {
    let header: Vec<String> = (0..10_000).map(|i| format!("c{i}")).collect();
    let mut s = header.join(",");
    s.push('\n');
    let row: Vec<String> = (0..10_000).map(|i| i.to_string()).collect();
    s.push_str(&row.join(","));
    s.push('\n');
    let e = read(&s).expect_err("unknown");
    match e {
        FlightLogError::UnknownFormat { header, .. } => assert_eq!(header.chars().count(), 120),
        other => panic!("{other}"),
    }
    let e = read_mapped(&s, "time=c0,altitude=c9999").expect_err("one sample");
    assert!(matches!(e, FlightLogError::NoLiftoff { .. }), "{e}");
}

#[test]
fn huge_numbers_and_nan_are_skipped_and_reported() {
    let mut s = rrc3_text(times(20.0).filter(|t| *t >= 0.0));
    s = s.replacen("0.50,", "0.50x,", 1);
    let lines: Vec<&str> = s.lines().collect();
    let mut text = String::new();
    for (i, l) in lines.iter().enumerate() {
        // Between the rows of 5.00 s and 5.05 s.
        if i == 102 {
            text.push_str("5.01,1e308,900,0,25, -,3.8\n");
            text.push_str("5.02,1e999,900,0,25, -,3.8\n");
            text.push_str("5.03,NaN,900,0,25, -,3.8\n");
            text.push_str("5.04,700.0,900,NaN,25, -,3.8\n");
        }
        text.push_str(l);
        text.push('\n');
    }
    let log = read(&text).expect("rrc3 with bad values");
    check(&log, Format::Rrc3, 0.0);
    assert!(
        log.warnings.iter().any(|w| w.contains("4 row(s) skipped")),
        "{:?}",
        log.warnings
    );
    assert!(
        log.warnings
            .iter()
            .any(|w| w.contains("1 velocity value(s)")),
        "{:?}",
        log.warnings
    );
    // The row at 5.04 s is 400 m off the flight: a glitch row.
    assert!(
        log.warnings.iter().any(|w| w.contains("glitch")),
        "{:?}",
        log.warnings
    );
}

#[test]
fn truncated_rows() {
    let s = rrc3_text(times(20.0).filter(|t| *t >= 0.0));
    // The last row cut off while being written: skipped with a warning.
    let cut = &s[..s.len() - 20];
    let log = read(cut).expect("truncated final row");
    assert!(
        log.warnings
            .iter()
            .any(|w| w.contains("truncated final row")),
        "{:?}",
        log.warnings
    );
    // A short row in the middle: an error naming its line.
    let mut lines: Vec<&str> = s.lines().collect();
    lines[50] = "2.45,100";
    let e = read(&lines.join("\n")).expect_err("truncated row");
    assert!(
        matches!(
            e,
            FlightLogError::TruncatedRow {
                line: 51,
                found: 2,
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().starts_with("synthetic:51: truncated row"));
}

#[test]
fn glitch_rows_clock_and_negative_start() {
    let mut s = String::from("t,h\n");
    let mut lines = 0;
    for t in times(20.0) {
        let (h, _) = flight(t);
        // Negative start-up altitudes, a glitch pair at apogee, the clock going back once.
        let h = if t < -0.5 { -30.0 } else { h };
        s.push_str(&format!("{t:.2},{h:.3}\n"));
        lines += 1;
        if lines == 300 {
            s.push_str(&format!("{t:.2},{:.3}\n", 10_000.0));
            s.push_str(&format!("{:.2},{:.3}\n", t + 0.01, 10_000.0));
            s.push_str(&format!("{:.2},{:.3}\n", t + 0.02, -2_000.0));
            s.push_str(&format!("{:.2},{:.3}\n", t - 3.0, 5.0));
        }
    }
    let log = read_mapped(&s, "time=t,altitude=h").expect("generic");
    check(&log, Format::Generic, 0.0);
    let w = log.warnings.join("\n");
    assert!(w.contains("2 glitch row(s)"), "{w}");
    assert!(w.contains("1 row(s) repeat the time"), "{w}");
    assert!(w.contains("1 row(s) with a clock going back"), "{w}");
    assert!(w.contains("below -10 m AGL"), "{w}");
}

#[test]
fn no_liftoff() {
    let mut s = String::from("t,h\n");
    for i in 0..200 {
        s.push_str(&format!(
            "{},{}\n",
            f64::from(i) * 0.05,
            f64::from(i % 7) - 3.0
        ));
    }
    let e = read_mapped(&s, "time=t,altitude=h").expect_err("flat");
    assert!(matches!(e, FlightLogError::NoLiftoff { .. }), "{e}");
}

#[test]
fn format_names_round_trip() {
    for f in Format::ALL {
        assert_eq!(f.name().parse::<Format>().expect("name"), f);
    }
    assert!(matches!(
        "telemetrum".parse::<Format>(),
        Err(FlightLogError::UnknownFormatName { .. })
    ));
    let e = parse(
        b"a,b\n1,2\n",
        "x",
        &ReadOptions {
            format: Some(Format::Generic),
            mapping: None,
        },
    )
    .expect_err("generic without mapping");
    assert!(e.to_string().contains("needs a column mapping"));
}

/// Random garbage built from pieces of real headers and numbers: never a panic.
#[test]
fn hostile_inputs_never_panic() {
    let pieces = [
        "#version,time,height,speed\n",
        "PerfectFlite\n",
        "Data: (Time, Altitude)\n",
        "ts,id,T,P\n",
        "T,Alt,Veloc,FAlt,FVeloc\n",
        "Time\tAltitude\tTemp.\n",
        "time,altitude,pressure,velocity,temperature,events\n",
        "Time-Axial Accel (Gs),a,Time (s),Altitude (Ft-AGL)\n",
        "1e308,",
        "-1e308,",
        "NaN,",
        "inf,",
        "0,",
        "\"",
        ",,,,\n",
        "\n",
        "\t",
        "12.5",
        "-0",
        "\u{feff}",
        "é",
        ":",
        "1,2,3\n",
        "99999999999999999999999,",
    ];
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    for _ in 0..400 {
        let mut text = String::new();
        let n = 1 + (state % 60) as usize;
        for _ in 0..n {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            text.push_str(pieces[(state % pieces.len() as u64) as usize]);
        }
        let _ = parse(text.as_bytes(), "fuzz", &ReadOptions::default());
        let mapping = ColumnMapping::parse("time=time,altitude=height").expect("mapping");
        let _ = parse(
            text.as_bytes(),
            "fuzz",
            &ReadOptions {
                mapping: Some(mapping),
                ..ReadOptions::default()
            },
        );
        for f in Format::ALL {
            let _ = parse(
                text.as_bytes(),
                "fuzz",
                &ReadOptions {
                    format: Some(f),
                    mapping: None,
                },
            );
        }
    }
}
