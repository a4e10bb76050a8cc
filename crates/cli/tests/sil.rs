//! `karman sil`: the C flight computer of `fixtures/airbrakes/sil_apogee.c`, compiled with the
//! system C compiler, flies Calisto's air brakes as its Rhai twin does, bit for bit; a program
//! that answers garbage, exits, stops answering or does not exist ends the flight with a
//! clear error, never a hang.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use crate::common::{failure, karman};

fn airbrakes(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/airbrakes")
        .join(file)
}

fn mission() -> String {
    airbrakes("calisto_apogee.toml").display().to_string()
}

/// A scratch folder of this test's own.
fn folder(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("karman-sil")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

#[test]
fn the_c_flight_computer_flies_its_rhai_twin_s_flight_bit_for_bit() {
    let dir = folder("c");
    let program = dir.join("sil_apogee");
    let compiled = std::process::Command::new("cc")
        .args(["-O2", "-ffp-contract=off", "-o"])
        .arg(&program)
        .arg(airbrakes("sil_apogee.c"))
        .arg("-lm")
        .output()
        .expect("the system C compiler (cc) runs");
    assert!(
        compiled.status.success(),
        "cc: {}",
        String::from_utf8_lossy(&compiled.stderr)
    );
    let (c_out, rhai_out) = (dir.join("c"), dir.join("rhai"));
    let program = program.display().to_string();
    let sil = karman(&[
        "sil",
        &mission(),
        "--out",
        &c_out.display().to_string(),
        "--exec",
        &program,
    ]);
    assert!(
        sil.status.success(),
        "{}",
        String::from_utf8_lossy(&sil.stderr)
    );
    let script = format!(
        "rocket.air_brakes.controller='{}'",
        airbrakes("sil_apogee.rhai").display()
    );
    let rhai = karman(&[
        "simulate",
        &mission(),
        "--set",
        &script,
        "--out",
        &rhai_out.display().to_string(),
    ]);
    assert!(
        rhai.status.success(),
        "{}",
        String::from_utf8_lossy(&rhai.stderr)
    );
    for file in ["trajectory.csv", "summary.json"] {
        let a = std::fs::read(c_out.join(file)).expect("the C flight's file");
        let b = std::fs::read(rhai_out.join(file)).expect("the Rhai flight's file");
        assert!(
            a == b,
            "{file} differs between the C program and its Rhai twin"
        );
    }
    // The program did steer: the brakes-shut flight climbs 3305 m.
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(c_out.join("summary.json")).expect("summary"))
            .expect("json");
    let apogee = summary["apogee_agl_m"].as_f64().expect("apogee");
    assert!((apogee - 3067.56).abs() < 0.01, "{apogee}");
}

/// Runs `karman sil` with `sh -c SCRIPT` as the program; returns its error (exit 1, no panic)
/// and how long it took.
fn refused(script: &str, extra: &[&str]) -> (String, Duration) {
    let started = Instant::now();
    let mut args = vec!["sil", "--timeout", "1"];
    let mission = mission();
    args.push(&mission);
    args.extend_from_slice(extra);
    args.extend_from_slice(&["--exec", "sh", "-c", script]);
    let error = failure(&args);
    (error, started.elapsed())
}

#[test]
fn a_program_that_misbehaves_ends_the_flight_with_a_clear_error() {
    for (script, expected) in [
        (
            "read h; read s; echo hello",
            "the call at t = 0 s: the program answered `hello`; expected `level VALUE`",
        ),
        (
            "read h; while read s; do echo 'level nan'; done",
            "the call at t = 0 s: the program answered `level nan`",
        ),
        (
            "read h; while read s; do echo 'level 0.5 extra'; done",
            "the program answered `level 0.5 extra`",
        ),
        (
            "read h; exit 3",
            "the call at t = 0 s: the program exited before answering",
        ),
        (
            "read h; sleep 30",
            "the call at t = 0 s: the program did not answer within 1 s (--timeout)",
        ),
        (
            "read h; head -c 10000 /dev/zero | tr '\\0' x; echo",
            "longer than 4096 bytes",
        ),
    ] {
        let (error, took) = refused(script, &[]);
        assert!(error.contains(expected), "`{script}`: {error}");
        assert!(
            error.contains("rocket.air_brakes.controller"),
            "`{script}`: {error}"
        );
        assert!(took < Duration::from_secs(10), "`{script}` took {took:?}");
    }
    // A later call: the first 100 calls are answered. The 101st is at 1.01 s: 0.36 s, where
    // the rail phase ends, is no call (the Rhai controller's record has none there either).
    let (error, _) = refused(
        "read h; n=0; while read s; do n=$((n+1)); if [ $n -gt 100 ]; then echo oops; else echo keep; fi; done",
        &[],
    );
    assert!(
        error.contains("the call at t = 1.01 s: the program answered `oops`"),
        "{error}"
    );
}

#[test]
fn sil_refuses_what_it_cannot_fly() {
    let error = failure(&["sil", &mission(), "--exec", "/nonexistent/flight-computer"]);
    assert!(
        error.contains("cannot run `/nonexistent/flight-computer`"),
        "{error}"
    );
    let example = crate::common::example().display().to_string();
    let error = failure(&["sil", &example, "--exec", "true"]);
    assert!(error.contains("has no [rocket.air_brakes]"), "{error}");
    let error = failure(&["sil", &mission(), "--timeout", "0", "--exec", "true"]);
    assert!(
        error.contains("--timeout 0: must be a number of seconds"),
        "{error}"
    );
}
