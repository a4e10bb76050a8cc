//! `--until`: a study stopped when its conditions hold is the study of that many samples,
//! byte for byte, and its rows are the first rows of a longer study with the same seed.

use crate::common::{assert_same_outputs, fly, options, study};
use karman_dispersion::convergence::{Condition, Until, run_converging};
use karman_dispersion::{Shard, run};
use tempfile::tempdir;

fn until(texts: &[&str], every: u64, cap: u64) -> Until {
    let study = study(cap);
    Until {
        conditions: texts
            .iter()
            .map(|t| Condition::parse(t, &study).expect("a valid condition"))
            .collect(),
        every,
    }
}

/// The rows of `samples.csv` without their digest (keyed by the study, whose sample count
/// differs between a stopped study and a longer one).
fn cells(dir: &std::path::Path) -> Vec<String> {
    std::fs::read_to_string(dir.join("samples.csv"))
        .expect("samples.csv")
        .lines()
        .map(|l| l.rsplit_once(',').map_or(l, |(cells, _)| cells).to_owned())
        .collect()
}

#[test]
fn a_study_that_converges_stops_early_and_is_the_study_of_that_many_samples() {
    let cap = 2000;
    let rule = until(
        &["apogee_agl_m.ci95 < 40", "landing.semi_major.ci95 < 400"],
        20,
        cap,
    );
    let stopped = tempdir().expect("temp dir");
    let (report, converged) = run_converging(
        &study(cap),
        stopped.path(),
        &options(2, Shard::WHOLE),
        &rule,
        fly,
    )
    .expect("run");
    assert!(converged.met, "{converged:?}");
    assert!(
        converged.samples < cap && converged.samples % 20 == 0,
        "{converged:?}"
    );
    assert_eq!(converged.checks, converged.samples / 20);
    assert_eq!(report.shard_samples, converged.samples);
    // Each half-width is below its bound at the stop, and the check before did not hold.
    for (c, w) in rule.conditions.iter().zip(&converged.widths) {
        assert!(w.is_some_and(|w| w < c.threshold), "{c:?}: {w:?}");
    }
    let n = converged.samples;
    let fewer = tempdir().expect("temp dir");
    let (_, earlier) = run_converging(
        &study(n - 20),
        fewer.path(),
        &options(1, Shard::WHOLE),
        &rule,
        fly,
    )
    .expect("run");
    assert!(!earlier.met, "{earlier:?}");
    // Byte for byte the study of n samples, whatever the thread count.
    let plain = tempdir().expect("temp dir");
    run(&study(n), plain.path(), &options(1, Shard::WHOLE), fly).expect("run");
    assert_same_outputs(stopped.path(), plain.path());
    // Its rows are the first n rows of the capped study (all but the digest, keyed by the
    // study's sample count).
    let longer = tempdir().expect("temp dir");
    run(&study(cap), longer.path(), &options(2, Shard::WHOLE), fly).expect("run");
    let (short, long) = (cells(stopped.path()), cells(longer.path()));
    assert_eq!(short.len() as u64, n + 1);
    assert_eq!(short[..], long[..short.len()]);
}

#[test]
fn a_study_that_does_not_converge_runs_to_the_cap() {
    let cap = 70;
    let rule = until(&["apogee_agl_m.ci95 < 1"], 25, cap);
    let dir = tempdir().expect("temp dir");
    let (_, converged) = run_converging(
        &study(cap),
        dir.path(),
        &options(2, Shard::WHOLE),
        &rule,
        fly,
    )
    .expect("run");
    assert!(!converged.met);
    assert_eq!((converged.samples, converged.checks), (70, 3));
    let plain = tempdir().expect("temp dir");
    run(&study(cap), plain.path(), &options(2, Shard::WHOLE), fly).expect("run");
    assert_same_outputs(dir.path(), plain.path());
}

#[test]
fn bad_conditions_are_errors_naming_them() {
    let s = study(10);
    for (text, expected) in [
        ("apogee_feet.ci95 < 5", "`apogee_feet` is not an output"),
        ("apogee_agl_m.std < 5", "the statistic is `ci95`"),
        ("apogee_agl_m.ci95 > 5", "expected QUANTITY.ci95 < VALUE"),
        ("apogee_agl_m.ci95 < five", "\"five\" is not a number"),
        ("apogee_agl_m.ci95 < -1", "positive number, got -1"),
        ("apogee_agl_m.ci95 < inf", "positive number, got inf"),
    ] {
        let error = Condition::parse(text, &s).expect_err(text).to_string();
        assert!(
            error.contains(expected) && error.contains(text),
            "{text}: {error}"
        );
    }
    let dir = tempdir().expect("temp dir");
    let rule = Until {
        conditions: vec![],
        every: 0,
    };
    assert!(run_converging(&s, dir.path(), &options(1, Shard::WHOLE), &rule, fly).is_err());
    let rule = until(&["apogee_agl_m.ci95 < 1"], 5, 10);
    let error = run_converging(
        &s,
        dir.path(),
        &options(1, Shard::new(1, 2).expect("shard")),
        &rule,
        fly,
    )
    .expect_err("a shard");
    assert!(error.to_string().contains("--shard"), "{error}");
}
