//! `karman montecarlo` and `karman merge`: a small study of the example mission, its files,
//! shards merged into the single run's bytes, resume, and clear errors (never a panic).

use crate::common::{example, failure, karman, stderr};
use std::path::{Path, PathBuf};

/// A fresh output directory under this test binary's scratch folder.
fn fresh(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("karman-cli")
        .join("montecarlo")
        .join(name);
    if dir.exists() {
        std::fs::remove_dir_all(&dir).expect("remove an old scratch directory");
    }
    dir
}

fn montecarlo(out: &Path, extra: &[&str]) -> std::process::Output {
    let mission = example().display().to_string();
    let out = out.display().to_string();
    let mut args = vec![
        "montecarlo",
        &mission,
        "--samples",
        "12",
        "--quiet",
        "--out",
        &out,
    ];
    args.extend_from_slice(extra);
    karman(&args)
}

fn assert_same_files(a: &Path, b: &Path) {
    let mut names: Vec<_> = std::fs::read_dir(a)
        .expect("directory")
        .map(|e| e.expect("entry").file_name())
        .collect();
    names.sort();
    assert_eq!(names.len(), 6, "{names:?}");
    for name in names {
        let x = std::fs::read(a.join(&name)).expect("file");
        let y = std::fs::read(b.join(&name)).unwrap_or_default();
        assert!(x == y, "{} differs", name.to_string_lossy());
    }
}

#[test]
fn a_study_and_its_shards_give_the_same_files() {
    let single = fresh("single");
    let output = montecarlo(&single, &["--threads", "2"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("apogee_agl_m"), "{stdout}");
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(single.join("summary.json")).expect("summary.json"))
            .expect("JSON");
    assert_eq!(summary["samples"], 12);
    assert_eq!(summary["seed"], 7, "the example mission's seed");
    let csv = std::fs::read_to_string(single.join("samples.csv")).expect("samples.csv");
    assert_eq!(csv.lines().count(), 13);
    assert!(csv.starts_with("index,status,error,rocket.mass,motor.total_impulse,"));

    let mut shards = Vec::new();
    for k in ["2/3", "1/3", "3/3"] {
        let dir = fresh(&format!("shard{}", &k[..1]));
        let output = montecarlo(&dir, &["--threads", "1", "--shard", k]);
        assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
        shards.push(dir.display().to_string());
    }
    let merged = fresh("merged");
    let merged_arg = merged.display().to_string();
    let mut args = vec!["merge", merged_arg.as_str()];
    args.extend(shards.iter().map(String::as_str));
    let output = karman(&args);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert_same_files(&single, &merged);

    // A partial last line (an interrupted run) is dropped and the study finished.
    let path = single.join("samples.csv");
    std::fs::write(&path, &csv.as_bytes()[..csv.len() / 2]).expect("cut samples.csv");
    let output = montecarlo(&single, &[]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert_same_files(&single, &merged);
}

#[test]
fn a_different_study_or_missing_shard_fails_cleanly() {
    let dir = fresh("refused");
    let output = montecarlo(&dir, &["--seed", "1"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let text = failure(&[
        "montecarlo",
        &example().display().to_string(),
        "--samples",
        "12",
        "--seed",
        "2",
        "--quiet",
        "--out",
        &dir.display().to_string(),
    ]);
    assert!(
        text.contains("different study") && text.contains("seed"),
        "{text}"
    );

    let shard = fresh("lonely");
    let output = montecarlo(&shard, &["--shard", "1/2"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let merged = fresh("lonely-merged").display().to_string();
    let text = failure(&["merge", &merged, &shard.display().to_string()]);
    assert!(text.contains("shard 2/2 is missing"), "{text}");

    let output = montecarlo(&fresh("bad-shard"), &["--shard", "3/2"]);
    assert_eq!(output.status.code(), Some(2), "a usage error");
    assert!(!stderr(&output).contains("panicked"));
}
