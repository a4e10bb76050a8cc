//! Resuming an interrupted study in its directory.

use crate::common::{assert_same_outputs, fly, options, study};
use karman_dispersion::{DispersionError, Shard, run};

#[test]
fn resume_after_a_partial_line_gives_identical_bytes() {
    let study = study(300);
    let tmp = tempfile::tempdir().expect("temporary directory");
    let full = tmp.path().join("full");
    run(&study, &full, &options(2, Shard::WHOLE), fly).expect("uninterrupted run");

    // An interrupted run: study.json and samples.csv cut in the middle of row 123.
    let cut = tmp.path().join("cut");
    std::fs::create_dir(&cut).expect("directory");
    std::fs::copy(full.join("study.json"), cut.join("study.json")).expect("copy");
    let csv = std::fs::read(full.join("samples.csv")).expect("samples.csv");
    let row_starts: Vec<usize> = csv
        .iter()
        .enumerate()
        .filter(|(_, b)| **b == b'\n')
        .map(|(i, _)| i + 1)
        .collect();
    // Line 124 of the file is row 123; cut 7 bytes into it.
    let at = row_starts[123] + 7;
    assert_ne!(csv[at - 1], b'\n');
    std::fs::write(cut.join("samples.csv"), &csv[..at]).expect("write");

    let report = run(&study, &cut, &options(3, Shard::WHOLE), fly).expect("resumed run");
    assert_eq!((report.resumed, report.flown), (123, 177));
    assert_same_outputs(&full, &cut);

    // Running a finished study again flies nothing and changes nothing.
    let again = run(&study, &cut, &options(1, Shard::WHOLE), fly).expect("rerun");
    assert_eq!((again.resumed, again.flown), (300, 0));
    assert_same_outputs(&full, &cut);
}

#[test]
fn resume_with_only_a_partial_header() {
    let study = study(20);
    let tmp = tempfile::tempdir().expect("temporary directory");
    let full = tmp.path().join("full");
    run(&study, &full, &options(1, Shard::WHOLE), fly).expect("run");
    let cut = tmp.path().join("cut");
    std::fs::create_dir(&cut).expect("directory");
    std::fs::copy(full.join("study.json"), cut.join("study.json")).expect("copy");
    let csv = std::fs::read(full.join("samples.csv")).expect("samples.csv");
    std::fs::write(cut.join("samples.csv"), &csv[..10]).expect("write");
    run(&study, &cut, &options(1, Shard::WHOLE), fly).expect("resumed run");
    assert_same_outputs(&full, &cut);
}

#[test]
fn a_different_study_is_refused() {
    let study = study(30);
    let tmp = tempfile::tempdir().expect("temporary directory");
    let dir = tmp.path().join("out");
    run(&study, &dir, &options(1, Shard::WHOLE), fly).expect("run");
    let mut other = study.clone();
    other.samples = 31;
    other.seed = 7;
    match run(&other, &dir, &options(1, Shard::WHOLE), fly) {
        Err(DispersionError::StudyMismatch { fields, .. }) => {
            assert_eq!(fields, ["seed", "samples"]);
        }
        other => panic!("expected a mismatch, got {other:?}"),
    }
    let shard = Shard::new(1, 2).expect("valid");
    let error = run(&study, &dir, &options(1, shard), fly).expect_err("another shard");
    assert!(error.to_string().contains("shard"), "{error}");
}

#[test]
fn a_corrupt_complete_row_is_an_error_naming_the_line() {
    let study = study(30);
    let tmp = tempfile::tempdir().expect("temporary directory");
    let dir = tmp.path().join("out");
    run(&study, &dir, &options(1, Shard::WHOLE), fly).expect("run");
    let path = dir.join("samples.csv");
    let text = std::fs::read_to_string(&path).expect("samples.csv");
    let mut lines: Vec<&str> = text.lines().collect();
    lines.truncate(10);
    lines[5] = "4,ok,,1,2,3";
    std::fs::write(&path, lines.join("\n") + "\n").expect("write");
    let error = run(&study, &dir, &options(1, Shard::WHOLE), fly).expect_err("corrupt row");
    match error {
        DispersionError::CorruptSamples { line, .. } => assert_eq!(line, 6),
        other => panic!("expected a corrupt row, got {other}"),
    }
    // Rows whose inputs are not the study's draws (edited by hand) are refused too.
    let mut rows: Vec<String> = text.lines().map(str::to_owned).collect();
    let ok = rows
        .iter()
        .position(|r| r.contains(",ok,"))
        .expect("a successful sample");
    let mut fields: Vec<String> = rows[ok].split(',').map(str::to_owned).collect();
    fields[3] = "99.0".to_owned();
    rows[ok] = fields.join(",");
    std::fs::write(&path, rows.join("\n") + "\n").expect("write");
    let error = run(&study, &dir, &options(1, Shard::WHOLE), fly).expect_err("edited inputs");
    assert!(error.to_string().contains("draws"), "{error}");
}

#[test]
fn a_stopped_run_leaves_a_prefix_that_resumes_to_identical_bytes() {
    use karman_dispersion::run_until;
    use std::sync::atomic::{AtomicBool, Ordering};

    let study = study(400);
    let tmp = tempfile::tempdir().expect("temporary directory");
    let full = tmp.path().join("full");
    run(&study, &full, &options(2, Shard::WHOLE), fly).expect("uninterrupted run");

    // Stop from inside the flights once sample 100 is reached, as a Ctrl-C handler would.
    let stopped = tmp.path().join("stopped");
    let stop = AtomicBool::new(false);
    let result = run_until(
        &study,
        &stopped,
        &options(2, Shard::WHOLE),
        &stop,
        |i, v| {
            if i >= 100 {
                stop.store(true, Ordering::Relaxed);
            }
            fly(i, v)
        },
    );
    let Err(DispersionError::Interrupted { written, total, .. }) = result else {
        panic!("expected an interruption, got {result:?}");
    };
    assert_eq!(total, 400);
    // Samples in flight on other workers stop too, so the prefix may end before sample 100.
    assert!(written < 400, "{written} rows written");
    assert!(!stopped.join("summary.json").exists());

    let report = run(&study, &stopped, &options(3, Shard::WHOLE), fly).expect("resumed run");
    assert_eq!((report.resumed, report.flown), (written, 400 - written));
    assert_same_outputs(&full, &stopped);
}

#[test]
fn a_resume_with_other_data_or_another_model_is_refused() {
    use karman_dispersion::DataFile;
    let mut study = study(40);
    study.data = vec![DataFile {
        role: "rocket.power_off_drag".to_owned(),
        path: "powerOffDragCurve.csv".to_owned(),
        sha256: "aa".to_owned(),
    }];
    let tmp = tempfile::tempdir().expect("temporary directory");
    let dir = tmp.path().join("out");
    run(&study, &dir, &options(1, Shard::WHOLE), fly).expect("run");
    let path = dir.join("samples.csv");
    let csv = std::fs::read(&path).expect("samples.csv");
    std::fs::write(&path, &csv[..csv.len() / 2]).expect("an interrupted run");

    // The drag file edited since: refused, naming the file.
    let mut edited = study.clone();
    edited.data[0].sha256 = "ab".to_owned();
    let error = run(&edited, &dir, &options(1, Shard::WHOLE), fly).expect_err("other data");
    let text = error.to_string();
    assert!(
        text.contains("powerOffDragCurve.csv") && text.contains("rocket.power_off_drag"),
        "{text}"
    );

    // The same study flown by a model that gives other outputs: the kept rows flown again
    // differ, and the resume is refused before anything is written.
    let other_model = |index: u64, values: &[f64]| {
        fly(index, values).map(|o| {
            let values = o.values().iter().map(|v| v.map(|x| x + 1e-9)).collect();
            karman_dispersion::Outcome::new(values)
        })
    };
    let before = std::fs::read(&path).expect("samples.csv");
    let error = run(&study, &dir, &options(1, Shard::WHOLE), other_model).expect_err("changed");
    assert!(
        matches!(
            error,
            DispersionError::ChangedOutputs {
                line: 2,
                index: 0,
                ..
            }
        ),
        "{error}"
    );
    assert_eq!(std::fs::read(&path).expect("samples.csv"), before);
    // The right model resumes.
    run(&study, &dir, &options(1, Shard::WHOLE), fly).expect("resumed");
}
