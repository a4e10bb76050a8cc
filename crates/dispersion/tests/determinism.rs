//! Byte-identical outputs for any thread count and any shard split.

use crate::common::{assert_same_outputs, files, fly, options, study};
use karman_dispersion::{DispersionError, Shard, merge, run};

#[test]
fn threads_do_not_change_the_outputs() {
    let study = study(600);
    let tmp = tempfile::tempdir().expect("temporary directory");
    let one = tmp.path().join("one");
    let two = tmp.path().join("two");
    let report = run(&study, &one, &options(1, Shard::WHOLE), fly).expect("run, 1 thread");
    assert_eq!((report.flown, report.resumed, report.threads), (600, 0, 1));
    let report2 = run(&study, &two, &options(2, Shard::WHOLE), fly).expect("run, 2 threads");
    assert_eq!(report2.threads, 2);
    assert_same_outputs(&one, &two);

    let names: Vec<String> = files(&one).into_iter().map(|(n, _)| n).collect();
    assert_eq!(
        names,
        [
            "apogee_histogram.svg",
            "dispersion.kml",
            "landing.svg",
            "samples.csv",
            "study.json",
            "study.lock",
            "summary.json"
        ]
    );
    // The synthetic flight fails when the drag factor N(1, 0.05) exceeds 1.1 (2.3 % of the
    // samples) and has no impact for index % 17 == 5.
    let summary = report.summary.expect("a whole study is summarized");
    let counts = &summary.counts;
    assert_eq!(counts.total(), 600);
    assert_eq!(&report.counts, counts);
    assert!((3..=30).contains(&counts.failed), "{counts}");
    // index % 29 == 3 ends early, unless the drag draw makes it fail first.
    let early = (0..600u64).filter(|i| i % 29 == 3).count() as u64;
    assert!(
        counts.ended_early <= early && counts.ended_early + counts.failed >= early,
        "{counts}"
    );
    assert_eq!(
        counts.ended_early_by_status.get("max_time"),
        Some(&counts.ended_early)
    );
    assert_eq!(
        summary.failures.len() as u64,
        (counts.failed + counts.ended_early).min(100)
    );
    // The output statistics count completed flights only: the impact column has exactly the
    // completed rows with an impact.
    let csv = std::fs::read_to_string(one.join("samples.csv")).expect("samples.csv");
    let rows: Vec<karman_dispersion::Row> = csv
        .lines()
        .skip(1)
        .map(|line| karman_dispersion::parse_row(line, 7, 6).expect("a row"))
        .collect();
    let expected = rows
        .iter()
        .filter(|r| r.status.is_completed() && r.outputs[3].is_some())
        .count() as u64;
    let impact = summary
        .outputs
        .iter()
        .find(|c| c.name == "impact_x_m")
        .expect("column");
    assert_eq!(impact.statistics.expect("statistics").count, expected);
    let apogee = summary
        .outputs
        .iter()
        .find(|c| c.name == "apogee_agl_m")
        .expect("column");
    assert_eq!(
        apogee.statistics.expect("statistics").count,
        counts.completed,
        "an early ending's apogee is kept in samples.csv, not in the statistics"
    );
    assert!(
        rows.iter()
            .any(|r| r.outputs[0].is_some() && !r.status.is_completed())
    );
    assert_eq!(csv.lines().count(), 601);
    assert!(csv.starts_with(
        "index,status,error,rocket.mass,rocket.power_off_drag:factor,flight.heading,"
    ));
}

#[test]
fn three_shards_merge_into_a_single_run() {
    let study = study(400);
    let tmp = tempfile::tempdir().expect("temporary directory");
    let single = tmp.path().join("single");
    run(&study, &single, &options(2, Shard::WHOLE), fly).expect("single run");
    let mut dirs = Vec::new();
    // Shards flown in a scrambled order with different thread counts.
    for (number, threads) in [(2, 1), (3, 2), (1, 3)] {
        let dir = tmp.path().join(format!("shard{number}"));
        let shard = Shard::new(number, 3).expect("valid shard");
        let report = run(&study, &dir, &options(threads, shard), fly).expect("shard run");
        assert!(report.summary.is_none(), "a shard is not summarized");
        assert_eq!(report.shard_samples, shard.len(400));
        dirs.push(dir);
    }
    let merged = tmp.path().join("merged");
    merge(&merged, &dirs).expect("merge");
    assert_same_outputs(&single, &merged);

    // Incomplete sets of shards are refused.
    let error = merge(&tmp.path().join("partial"), &dirs[..2]).expect_err("a shard is missing");
    assert!(
        error.to_string().contains("shard 1/3 is missing"),
        "{error}"
    );
    let twice = [dirs[0].clone(), dirs[0].clone(), dirs[1].clone()];
    let error = merge(&tmp.path().join("twice"), &twice).expect_err("a shard twice");
    assert!(matches!(error, DispersionError::Merge { .. }), "{error}");
    let mut other = study.clone();
    other.seed += 1;
    let foreign = tmp.path().join("foreign");
    run(
        &other,
        &foreign,
        &options(1, Shard::new(1, 3).expect("valid")),
        fly,
    )
    .expect("run");
    let mixed = [foreign, dirs[0].clone(), dirs[1].clone()];
    let error = merge(&tmp.path().join("mixed"), &mixed).expect_err("different studies");
    assert!(error.to_string().contains("seed"), "{error}");

    // A shard folder that does not exist, or is a file, is said to be so (not a missing
    // study.json), and nothing is created for it.
    let typo = tmp.path().join("shard-typo");
    let error = merge(&tmp.path().join("typo"), &[typo.clone(), dirs[1].clone()])
        .expect_err("no such folder");
    let text = error.to_string();
    assert!(
        text.contains("shard-typo") && text.contains("the folder does not exist"),
        "{text}"
    );
    assert!(!typo.exists());
    let file = dirs[0].join("samples.csv");
    let error = merge(&tmp.path().join("file"), &[file]).expect_err("a file");
    assert!(error.to_string().contains("not a folder"), "{error}");
}

#[test]
fn a_study_in_memory_is_the_study_written_to_a_directory() {
    use karman_dispersion::{parse_row, run_in_memory};
    use std::sync::atomic::{AtomicBool, Ordering};

    let study = study(300);
    let tmp = tempfile::tempdir().expect("temporary directory");
    let dir = tmp.path().join("study");
    run(&study, &dir, &options(2, Shard::WHOLE), fly).expect("run into a directory");
    let csv = std::fs::read_to_string(dir.join("samples.csv")).expect("samples.csv");
    let written: Vec<_> = csv
        .lines()
        .skip(1)
        .map(|line| parse_row(line, 7, 6).expect("a row"))
        .collect();
    let summary_json = std::fs::read_to_string(dir.join("summary.json")).expect("summary");
    let never = AtomicBool::new(false);
    for threads in [1, 2] {
        let memory =
            run_in_memory(&study, &options(threads, Shard::WHOLE), &never, fly).expect("memory");
        // Debug text compares every number exactly (NaN included).
        assert_eq!(format!("{:?}", memory.rows), format!("{written:?}"));
        let summary = memory.report.summary.expect("a summary");
        let mut json = serde_json::to_string_pretty(&summary).expect("json");
        json.push('\n');
        assert_eq!(json, summary_json, "{threads} threads");
        assert_eq!(memory.report.counts, summary.counts);
        assert_eq!((memory.report.flown, memory.report.threads), (300, threads));
    }

    let stop = AtomicBool::new(false);
    let result = run_in_memory(&study, &options(2, Shard::WHOLE), &stop, |i, v| {
        if i >= 50 {
            stop.store(true, Ordering::Relaxed);
        }
        fly(i, v)
    });
    let Err(DispersionError::Stopped { written, total }) = result else {
        panic!("expected a stop, got {result:?}");
    };
    assert!(written < 300 && total == 300, "{written} of {total}");
    let shard = Shard::new(1, 2).expect("shard");
    let error = run_in_memory(&study, &options(1, shard), &never, fly).expect_err("a shard");
    assert!(error.to_string().contains("whole study"), "{error}");
}

#[test]
fn slices_flown_apart_join_into_the_samples_file_of_a_run() {
    let study = study(150);
    let tmp = tempfile::tempdir().expect("temporary directory");
    run(&study, tmp.path(), &options(2, Shard::WHOLE), fly).expect("run");
    let written = std::fs::read_to_string(tmp.path().join("samples.csv")).expect("samples.csv");
    // Uneven slices, the last one reaching past the end of the study.
    let mut joined = karman_dispersion::samples_header(&study);
    for (first, end) in [(0, 7), (7, 64), (64, 200)] {
        joined.push_str(&karman_dispersion::sample_lines(&study, first..end, fly).expect("slice"));
    }
    assert_eq!(joined, written);
    assert_eq!(
        karman_dispersion::sample_lines(&study, 150..160, fly).expect("past the end"),
        ""
    );
}
