//! One writer per output directory: a second run (or a merge) on a directory that a run is
//! writing fails at once and touches nothing; the first run completes as if undisturbed.

use crate::common::{assert_same_outputs, files, fly, options, study};
use karman_dispersion::{DispersionError, Outcome, Shard, merge, run};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Waits (polling) until `ready` holds, at most a minute.
fn wait_for(ready: impl Fn() -> bool) {
    let start = Instant::now();
    while !ready() {
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "the first run never started"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
}

#[test]
fn a_second_run_on_a_directory_being_written_fails_and_touches_nothing() {
    let study = study(120);
    let tmp = tempfile::tempdir().expect("temporary directory");
    let undisturbed = tmp.path().join("undisturbed");
    run(&study, &undisturbed, &options(2, Shard::WHOLE), fly).expect("undisturbed run");

    // The first run's flights wait until the second run has been refused, so the first run
    // holds the directory the whole time.
    let dir = tmp.path().join("shared");
    let refused = AtomicBool::new(false);
    let held = |index: u64, values: &[f64]| -> Result<Outcome, String> {
        let start = Instant::now();
        while !refused.load(Ordering::Acquire) && start.elapsed() < Duration::from_secs(60) {
            std::thread::sleep(Duration::from_millis(1));
        }
        fly(index, values)
    };
    std::thread::scope(|scope| {
        let first = scope.spawn(|| run(&study, &dir, &options(2, Shard::WHOLE), held));
        wait_for(|| dir.join("samples.csv").is_file());
        let before = files(&dir);
        let second = run(&study, &dir, &options(1, Shard::WHOLE), fly);
        match &second {
            Err(DispersionError::Locked { dir: named }) => assert_eq!(named, &dir),
            other => panic!("expected the directory to be locked, got {other:?}"),
        }
        assert!(
            second
                .expect_err("locked")
                .to_string()
                .contains("another karman run"),
        );
        // A merge reading a shard that is being written is refused too, as is a merge into
        // the directory.
        let error = merge(&tmp.path().join("merged"), std::slice::from_ref(&dir))
            .expect_err("a shard being written");
        assert!(matches!(error, DispersionError::Locked { .. }), "{error}");
        let error = merge(&dir, std::slice::from_ref(&undisturbed)).expect_err("locked output");
        assert!(matches!(error, DispersionError::Locked { .. }), "{error}");
        assert_eq!(files(&dir), before, "the refused runs touched nothing");
        refused.store(true, Ordering::Release);
        let report = first
            .join()
            .expect("no panic")
            .expect("the first run completes");
        assert_eq!(report.flown, 120);
    });
    assert_same_outputs(&undisturbed, &dir);
    // The lock is released with the run: the directory can be run (resumed) again.
    run(&study, &dir, &options(1, Shard::WHOLE), fly).expect("a later run");
    assert_same_outputs(&undisturbed, &dir);
}

#[test]
fn simultaneous_atomic_writes_of_one_file_leave_one_whole_file() {
    use karman_dispersion::files::{temporary_path, write_atomic};
    let tmp = tempfile::tempdir().expect("temporary directory");
    let path = tmp.path().join("summary.json");
    assert_ne!(
        temporary_path(&path),
        temporary_path(&path),
        "one name per write"
    );
    let contents: Vec<Vec<u8>> = (0..4u8).map(|k| vec![b'a' + k; 100_000]).collect();
    std::thread::scope(|scope| {
        for content in &contents {
            let path = &path;
            scope.spawn(move || {
                for _ in 0..25 {
                    write_atomic(path, content).expect("a whole write");
                }
            });
        }
    });
    let last = std::fs::read(&path).expect("the file");
    assert!(contents.contains(&last), "a mix of writes");
    let names: Vec<_> = std::fs::read_dir(tmp.path())
        .expect("folder")
        .map(|e| e.expect("entry").file_name())
        .collect();
    assert_eq!(names, ["summary.json"], "no temporary file left");
}

#[cfg(unix)]
#[test]
fn deleting_the_lock_file_mid_run_lets_no_second_writer_in() {
    let study = study(120);
    let tmp = tempfile::tempdir().expect("temporary directory");
    let undisturbed = tmp.path().join("undisturbed");
    run(&study, &undisturbed, &options(2, Shard::WHOLE), fly).expect("undisturbed run");

    let dir = tmp.path().join("shared");
    let refused = AtomicBool::new(false);
    let held = |index: u64, values: &[f64]| -> Result<Outcome, String> {
        let start = Instant::now();
        while !refused.load(Ordering::Acquire) && start.elapsed() < Duration::from_secs(60) {
            std::thread::sleep(Duration::from_millis(1));
        }
        fly(index, values)
    };
    std::thread::scope(|scope| {
        let first = scope.spawn(|| run(&study, &dir, &options(2, Shard::WHOLE), held));
        wait_for(|| dir.join("samples.csv").is_file());
        std::fs::remove_file(dir.join("study.lock")).expect("delete the lock file");
        let before = files(&dir);
        let second = run(&study, &dir, &options(1, Shard::WHOLE), fly);
        assert!(
            matches!(&second, Err(DispersionError::Locked { .. })),
            "the directory itself stays locked: {second:?}"
        );
        let error = merge(&dir, std::slice::from_ref(&undisturbed)).expect_err("locked output");
        assert!(matches!(error, DispersionError::Locked { .. }), "{error}");
        assert_eq!(files(&dir), before, "the refused runs touched nothing");
        refused.store(true, Ordering::Release);
        // The first run, its directory still locked, puts the lock file back and completes.
        let report = first
            .join()
            .expect("no panic")
            .expect("the first run completes");
        assert_eq!(report.flown, 120);
        assert!(dir.join("study.lock").is_file(), "the lock file put back");
    });
    assert_same_outputs(&undisturbed, &dir);
    run(&study, &dir, &options(1, Shard::WHOLE), fly).expect("a later run");
    assert_same_outputs(&undisturbed, &dir);
}

#[test]
fn temporary_files_of_a_killed_run_are_removed_when_the_next_run_takes_the_lock() {
    let study = study(30);
    let tmp = tempfile::tempdir().expect("temporary directory");
    let undisturbed = tmp.path().join("undisturbed");
    run(&study, &undisturbed, &options(1, Shard::WHOLE), fly).expect("undisturbed run");
    let dir = tmp.path().join("out");
    run(&study, &dir, &options(1, Shard::WHOLE), fly).expect("run");
    let left = [".study.json.77.0.tmp", ".landing.svg.77.5.tmp"];
    for name in left {
        std::fs::write(dir.join(name), "partial").expect("write");
    }
    // Not a temporary file of the study's: kept.
    std::fs::write(dir.join(".notes.txt.77.0.tmp"), "mine").expect("write");
    run(&study, &dir, &options(1, Shard::WHOLE), fly).expect("the next run");
    for name in left {
        assert!(!dir.join(name).exists(), "{name} removed");
    }
    std::fs::remove_file(dir.join(".notes.txt.77.0.tmp")).expect("kept");
    assert_same_outputs(&undisturbed, &dir);
}
