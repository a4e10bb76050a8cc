//! A study killed with SIGKILL in the middle of its run resumes to the bytes of an
//! uninterrupted run. The test runs itself as the child process: with
//! `KARMAN_DISPERSION_KILL_CHILD` set it is the slow study that gets killed.

use crate::common::{assert_same_outputs, fly, options, study};
use karman_dispersion::{Outcome, Shard, run};
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const CHILD: &str = "KARMAN_DISPERSION_KILL_CHILD";
const SAMPLES: u64 = 400;

/// The child's flight: the synthetic one, slowed down so the parent can kill it mid-run.
fn slow_fly(index: u64, values: &[f64]) -> Result<Outcome, String> {
    std::thread::sleep(Duration::from_millis(10));
    fly(index, values)
}

fn rows(path: &std::path::Path) -> usize {
    std::fs::read(path).map_or(0, |b| b.iter().filter(|c| **c == b'\n').count())
}

#[test]
fn resume_after_sigkill() {
    if let Some(dir) = std::env::var_os(CHILD) {
        // The child: fly until killed.
        let _ = run(
            &study(SAMPLES),
            &PathBuf::from(dir),
            &options(2, Shard::WHOLE),
            slow_fly,
        );
        return;
    }
    let tmp = tempfile::tempdir().expect("temporary directory");
    let killed = tmp.path().join("killed");
    let exe = std::env::current_exe().expect("the test binary");
    let mut child = Command::new(exe)
        .args([
            "--exact",
            "sigkill::resume_after_sigkill",
            "--nocapture",
            "--test-threads=1",
        ])
        .env(CHILD, &killed)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("spawn the child");
    let samples = killed.join("samples.csv");
    let started = Instant::now();
    while rows(&samples) < 60 {
        assert!(
            started.elapsed() < Duration::from_secs(120),
            "the child wrote no rows"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().expect("SIGKILL the child");
    child.wait().expect("reap the child");
    let written = rows(&samples);
    assert!(
        (60..=SAMPLES as usize).contains(&written),
        "killed mid-run: {written} lines of {} (header included)",
        SAMPLES + 1
    );

    let report = run(&study(SAMPLES), &killed, &options(2, Shard::WHOLE), fly).expect("resume");
    assert!(report.resumed >= 59 && report.flown > 0, "{report:?}");
    let full = tmp.path().join("full");
    run(&study(SAMPLES), &full, &options(1, Shard::WHOLE), fly).expect("uninterrupted run");
    assert_same_outputs(&full, &killed);
}
