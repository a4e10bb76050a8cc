//! Studies are never silently altered: every row of `samples.csv` carries a digest of its
//! cells keyed by the study, which resume, merge and the summary check.

use crate::common::{assert_same_outputs, files, fly, options, study};
use karman_dispersion::{DispersionError, Shard, merge, run, summarize};
use std::path::Path;

/// Doubles the `apogee_agl_m` cell of the `nth` completed row; its line number (1-based)
/// and sample index.
fn double_an_apogee(path: &Path, nth: usize) -> (u64, u64) {
    let text = std::fs::read_to_string(path).expect("samples.csv");
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    let column = lines[0]
        .split(',')
        .position(|c| c == "apogee_agl_m")
        .expect("apogee column");
    let (number, _) = lines
        .iter()
        .enumerate()
        .filter(|(_, l)| l.contains(",ok,"))
        .nth(nth)
        .expect("a completed row");
    let mut cells: Vec<String> = lines[number].split(',').map(str::to_owned).collect();
    let apogee: f64 = cells[column].parse().expect("a number");
    cells[column] = format!("{:?}", 2.0 * apogee);
    let index = cells[0].parse().expect("index");
    lines[number] = cells.join(",");
    std::fs::write(path, lines.join("\n") + "\n").expect("write");
    (number as u64 + 1, index)
}

#[test]
fn an_edited_output_cell_is_an_error_on_resume_and_nothing_is_changed() {
    let study = study(40);
    let tmp = tempfile::tempdir().expect("temporary directory");
    let dir = tmp.path().join("out");
    run(&study, &dir, &options(2, Shard::WHOLE), fly).expect("run");
    let samples = dir.join("samples.csv");
    let (line, index) = double_an_apogee(&samples, 5);
    let before = files(&dir);
    let error = run(&study, &dir, &options(2, Shard::WHOLE), fly).expect_err("tampered row");
    let text = error.to_string();
    match &error {
        DispersionError::TamperedRow {
            file,
            line: named,
            index: sample,
            ..
        } => {
            assert_eq!(file, &samples);
            assert_eq!((*named, *sample), (line, index));
        }
        other => panic!("expected a tampered row, got {other}"),
    }
    assert!(text.contains("samples.csv"), "{text}");
    assert!(text.contains(&format!("line {line}")), "{text}");
    assert!(text.contains(&format!("sample {index}")), "{text}");
    assert!(text.contains("differs in: apogee_agl_m (kept"), "{text}");
    assert_eq!(files(&dir), before, "the study is left as it was");
    // The summary of the folder refuses it too.
    let error = summarize(&dir).expect_err("tampered row");
    assert!(
        matches!(error, DispersionError::TamperedRow { .. }),
        "{error}"
    );
}

#[test]
fn an_edited_digest_or_a_row_of_another_study_is_detected() {
    let study = study(20);
    let tmp = tempfile::tempdir().expect("temporary directory");
    let dir = tmp.path().join("out");
    run(&study, &dir, &options(1, Shard::WHOLE), fly).expect("run");
    let samples = dir.join("samples.csv");
    let text = std::fs::read_to_string(&samples).expect("samples.csv");
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    let last = lines[3].pop().expect("a digest digit");
    lines[3].push(if last == '0' { '1' } else { '0' });
    std::fs::write(&samples, lines.join("\n") + "\n").expect("write");
    let error = run(&study, &dir, &options(1, Shard::WHOLE), fly).expect_err("edited digest");
    assert!(
        error.to_string().contains("its digest was edited"),
        "{error}"
    );

    // A row (its digest included) of a study of another context: another fingerprint.
    let mut other = study.clone();
    other.context = "another study".to_owned();
    let elsewhere = tmp.path().join("elsewhere");
    run(&other, &elsewhere, &options(1, Shard::WHOLE), fly).expect("run");
    let foreign = std::fs::read_to_string(elsewhere.join("samples.csv")).expect("samples.csv");
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    lines[3] = foreign.lines().nth(3).expect("row").to_owned();
    std::fs::write(&samples, lines.join("\n") + "\n").expect("write");
    let error = run(&study, &dir, &options(1, Shard::WHOLE), fly).expect_err("foreign row");
    assert!(
        matches!(error, DispersionError::TamperedRow { line: 4, .. }),
        "{error}"
    );
}

#[test]
fn merge_checks_the_digests_of_the_shards() {
    let study = study(30);
    let tmp = tempfile::tempdir().expect("temporary directory");
    let whole = tmp.path().join("whole");
    run(&study, &whole, &options(2, Shard::WHOLE), fly).expect("run");
    let dirs: Vec<_> = (1..=2)
        .map(|k| {
            let dir = tmp.path().join(format!("shard{k}"));
            run(
                &study,
                &dir,
                &options(1, Shard::new(k, 2).expect("shard")),
                fly,
            )
            .expect("shard");
            dir
        })
        .collect();
    let merged = tmp.path().join("merged");
    merge(&merged, &dirs).expect("merge");
    assert_same_outputs(&whole, &merged);

    let (line, index) = double_an_apogee(&dirs[1].join("samples.csv"), 2);
    let again = tmp.path().join("again");
    let error = merge(&again, &dirs).expect_err("tampered shard");
    match &error {
        DispersionError::TamperedRow {
            file,
            line: named,
            index: sample,
            ..
        } => {
            assert_eq!(file, &dirs[1].join("samples.csv"));
            assert_eq!((*named, *sample), (line, index));
        }
        other => panic!("expected a tampered row, got {other}"),
    }
    assert!(!again.join("samples.csv").exists(), "nothing merged");
}

#[test]
fn a_folder_of_an_earlier_format_version_is_refused_by_name() {
    let study = study(10);
    let tmp = tempfile::tempdir().expect("temporary directory");
    let dir = tmp.path().join("out");
    run(&study, &dir, &options(1, Shard::WHOLE), fly).expect("run");
    let path = dir.join("study.json");
    let text = std::fs::read_to_string(&path).expect("study.json");
    std::fs::write(&path, text.replace("\"version\": 3", "\"version\": 2")).expect("write");
    let before = files(&dir);
    for error in [
        run(&study, &dir, &options(1, Shard::WHOLE), fly).expect_err("old version"),
        merge(&tmp.path().join("merged"), std::slice::from_ref(&dir)).expect_err("old version"),
    ] {
        assert!(
            matches!(error, DispersionError::OtherVersion { version: 2, .. }),
            "{error}"
        );
        let text = error.to_string();
        assert!(text.contains("study.json"), "{text}");
        assert!(text.contains("an earlier karman"), "{text}");
    }
    assert_eq!(files(&dir), before);
}
