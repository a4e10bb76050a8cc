//! `karman montecarlo --until`: stops at the first check at which the conditions hold and
//! writes the study of that many samples, byte for byte; errors name the condition.

use crate::common::{example, failure, karman};
use std::path::{Path, PathBuf};

fn scratch_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("karman-cli")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn montecarlo(out: &Path, extra: &[&str]) -> String {
    let example = example();
    let mut args = vec![
        "montecarlo",
        example.to_str().expect("utf-8"),
        "--seed",
        "5",
        "--quiet",
        "--out",
        out.to_str().expect("utf-8"),
    ];
    args.extend_from_slice(extra);
    let output = karman(&args);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8_lossy(&output.stdout).into_owned()
}

#[test]
fn until_stops_early_with_the_bytes_of_a_study_of_that_many_samples() {
    let stopped = scratch_dir("until-stopped");
    let text = montecarlo(
        &stopped,
        &[
            "--samples",
            "400",
            "--check-every",
            "40",
            "--until",
            "apogee_agl_m.ci95 < 30",
        ],
    );
    let line = text
        .lines()
        .find(|l| l.starts_with("--until: every condition held at "))
        .unwrap_or_else(|| panic!("{text}"));
    let n: u64 = line["--until: every condition held at ".len()..]
        .split(' ')
        .next()
        .and_then(|n| n.parse().ok())
        .expect("a sample count");
    assert!(n < 400 && n % 40 == 0, "{line}");
    let plain = scratch_dir("until-plain");
    montecarlo(&plain, &["--samples", &n.to_string()]);
    for file in [
        "study.json",
        "samples.csv",
        "summary.json",
        "dispersion.kml",
        "landing.svg",
    ] {
        let a = std::fs::read(stopped.join(file)).expect("written");
        let b = std::fs::read(plain.join(file)).expect("written");
        assert!(a == b, "{file} differs from the study of {n} samples");
    }
    // Not reached: the study runs to its cap and says so.
    let capped = scratch_dir("until-capped");
    let text = montecarlo(
        &capped,
        &[
            "--samples",
            "30",
            "--check-every",
            "20",
            "--until",
            "apogee_agl_m.ci95 < 0.001",
        ],
    );
    assert!(
        text.contains(
            "--until: the cap of 30 samples was reached before every condition held (2 checks"
        ),
        "{text}"
    );
}

#[test]
fn until_names_a_bad_condition() {
    let example = example();
    let out = scratch_dir("until-bad");
    let text = failure(&[
        "montecarlo",
        example.to_str().expect("utf-8"),
        "--until",
        "apogee_ft.ci95 < 5",
        "--out",
        out.to_str().expect("utf-8"),
    ]);
    assert!(
        text.contains("`apogee_ft` is not an output of the study"),
        "{text}"
    );
    assert!(!out.join("samples.csv").exists());
}

#[test]
fn design_sobol_writes_the_indices_of_every_output() {
    let out = scratch_dir("sobol-example");
    let text = montecarlo(&out, &["--samples", "12", "--design", "sobol"]);
    assert!(
        text.starts_with(
            "Sobol indices (Saltelli's design): 96 flights (6 inputs + 2) x 12, seed 5"
        ),
        "{text}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("sobol.json")).expect("written"))
            .expect("JSON");
    let apogee = &json["apogee_agl_m"];
    assert_eq!(apogee["evaluations"], 96);
    assert_eq!(apogee["first"].as_array().expect("first").len(), 6);
    assert_eq!(apogee["total"].as_array().expect("total").len(), 6);
    assert!(!out.join("samples.csv").exists() && !out.join("study.json").exists());
    let example = example();
    let text = failure(&[
        "montecarlo",
        example.to_str().expect("utf-8"),
        "--design",
        "sobol",
        "--until",
        "apogee_agl_m.ci95 < 5",
        "--out",
        out.to_str().expect("utf-8"),
    ]);
    assert!(
        text.contains("--design sobol takes neither --until nor --shard"),
        "{text}"
    );
}
