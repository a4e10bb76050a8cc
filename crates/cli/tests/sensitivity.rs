//! `karman sensitivity`: the variance decomposition of a study's outputs against RocketPy
//! 1.13's `SensitivityModel` on the same samples, and its errors.

use crate::common::{failure, karman};
use std::path::{Path, PathBuf};

/// The Calisto validation folder (skipped with a message when absent outside CI).
fn calisto() -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/validation/calisto");
    if dir.join("mission.toml").is_file() {
        Some(dir)
    } else {
        assert!(
            std::env::var_os("CI").is_none(),
            "{} is missing",
            dir.display()
        );
        println!("skipped: {} not found", dir.display());
        None
    }
}

/// The study of the acceptance (issue 37): Calisto with its mass, inclination, wind factor
/// and drag factor varied, 2 000 samples, seed 37.
const STUDY: &str = "
[dispersion]
samples = 2000
seed = 37

[dispersion.vary]
\"rocket.mass\" = { std = 0.5 }
\"flight.inclination\" = { std = 1 }
\"environment.wind_factor\" = { normal = [1, 0.2] }
\"rocket.power_off_drag\" = { factor = { normal = [1, 0.05] } }
";

/// A scratch copy of the Calisto folder with the study's `[dispersion]` table appended.
fn calisto_study(source: &Path) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("karman-cli/sensitivity-calisto");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    for entry in std::fs::read_dir(source).expect("calisto folder") {
        let entry = entry.expect("entry");
        std::fs::copy(entry.path(), dir.join(entry.file_name())).expect("copied");
    }
    let mission = dir.join("mission.toml");
    let mut text = std::fs::read_to_string(&mission).expect("mission");
    text.push_str(STUDY);
    std::fs::write(&mission, text).expect("written");
    dir
}

/// RocketPy 1.13.0's `SensitivityModel` fitted on this study's `samples.csv`
/// (`tests/rocketpy/sensitivity.py`): for each output, the shares of `rocket.mass`,
/// `flight.inclination`, `environment.wind_factor`, `rocket.power_off_drag:factor`, the
/// linear approximation error (LAE) and the model's standard deviation.
const ROCKETPY: [(&str, [f64; 4], f64, f64); 3] = [
    (
        "apogee_agl_m",
        [
            0.815530390581306,
            0.01693742274657856,
            1.829281654690152e-08,
            0.16602082844333685,
        ],
        0.0015113399359621231,
        100.07186937921374,
    ),
    (
        "impact_x_m",
        [
            0.5063535403509378,
            0.029366352985989743,
            1.4295936908617805e-07,
            0.45678256888649355,
        ],
        0.007497394817209846,
        0.2568669987322746,
    ),
    (
        "max_mach",
        [
            0.9992203358198377,
            3.528095957236621e-05,
            2.707745579368182e-07,
            3.321175035878904e-09,
        ],
        0.0007441091248569532,
        0.023637504965220595,
    ),
];

#[test]
fn validate_sensitivity_equals_rocketpy_on_the_same_samples() {
    let Some(source) = calisto() else { return };
    let dir = calisto_study(&source);
    let out = dir.join("mc");
    let mission = dir.join("mission.toml");
    let run = karman(&[
        "montecarlo",
        mission.to_str().expect("utf-8"),
        "--threads",
        "2",
        "--quiet",
        "--out",
        out.to_str().expect("utf-8"),
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let mut args = vec!["sensitivity", out.to_str().expect("utf-8"), "--json"];
    for (name, ..) in ROCKETPY {
        args.extend(["--output", name]);
    }
    let svg = dir.join("charts");
    args.extend(["--svg", svg.to_str().expect("utf-8")]);
    let output = karman(&args);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).expect("JSON");
    let outputs = json["outputs"].as_array().expect("outputs");
    assert_eq!(outputs.len(), ROCKETPY.len());
    for (decomposition, (name, shares, lae, std)) in outputs.iter().zip(ROCKETPY) {
        assert_eq!(decomposition["output"], name);
        assert_eq!(decomposition["samples"], 2000);
        let inputs = decomposition["inputs"].as_array().expect("inputs");
        let got: Vec<f64> = inputs
            .iter()
            .map(|i| i["share"].as_f64().expect("share"))
            .collect();
        let unexplained = decomposition["unexplained"].as_f64().expect("unexplained");
        for (g, r) in got.iter().zip(shares) {
            assert!((g - r).abs() < 1e-6, "{name}: share {g} vs RocketPy {r}");
        }
        assert!(
            (unexplained - lae).abs() < 1e-6,
            "{name}: {unexplained} vs {lae}"
        );
        let sd = decomposition["std"].as_f64().expect("std");
        assert!((sd / std - 1.0).abs() < 1e-6, "{name}: std {sd} vs {std}");
        // The shares and the unexplained part make up the whole variance.
        assert!((got.iter().sum::<f64>() + unexplained - 1.0).abs() < 1e-12);
        let chart = svg.join(format!("sensitivity_{name}.svg"));
        let text = std::fs::read_to_string(&chart).expect("chart written");
        assert!(
            text.contains("rocket.mass") && text.contains("unexplained"),
            "{}",
            chart.display()
        );
    }
    check_tolerance(&out);
}

/// `karman tolerance` on the same study: Wilks' 99 %/95 % bounds of the apogee are its 13th
/// largest and 13th smallest values (`P(B ≤ 1987) = 0.961692322388526 ≥ 0.95 >
/// P(B ≤ 1986) = 0.9348222763313376` for `B ~ Binomial(2000, 0.99)`, SciPy's `binom.cdf`).
fn check_tolerance(out: &Path) {
    let output = karman(&[
        "tolerance",
        out.to_str().expect("utf-8"),
        "--output",
        "apogee_agl_m",
        "--json",
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).expect("JSON");
    let bounds = &json[0];
    assert_eq!(bounds["rank"], 13);
    let confidence = bounds["achieved_confidence"].as_f64().expect("confidence");
    assert!(
        (confidence - 0.961692322388526).abs() < 1e-12,
        "{confidence}"
    );
    let text = std::fs::read_to_string(out.join("samples.csv")).expect("samples");
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().expect("header").split(',').collect();
    let column = header
        .iter()
        .position(|c| *c == "apogee_agl_m")
        .expect("column");
    let mut apogees: Vec<f64> = lines
        .map(|l| {
            l.split(',')
                .nth(column)
                .expect("cell")
                .parse()
                .expect("number")
        })
        .collect();
    apogees.sort_by(f64::total_cmp);
    let upper = bounds["upper"].as_f64().expect("upper");
    let lower = bounds["lower"].as_f64().expect("lower");
    assert_eq!(upper.to_bits(), apogees[2000 - 13].to_bits());
    assert_eq!(lower.to_bits(), apogees[12].to_bits());
}

#[test]
fn bad_sensitivity_requests_are_errors() {
    // Not a study's folder.
    let empty = Path::new(env!("CARGO_TARGET_TMPDIR")).join("karman-cli/sensitivity-empty");
    std::fs::create_dir_all(&empty).expect("folder");
    let text = failure(&["sensitivity", empty.to_str().expect("utf-8")]);
    assert!(text.contains("study.json"), "{text}");
    // An output the study does not have.
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("karman-cli/sensitivity-example");
    let _ = std::fs::remove_dir_all(&out);
    let example = crate::common::example();
    let run = karman(&[
        "montecarlo",
        example.to_str().expect("utf-8"),
        "--samples",
        "12",
        "--quiet",
        "--out",
        out.to_str().expect("utf-8"),
    ]);
    assert!(run.status.success());
    let text = failure(&[
        "sensitivity",
        out.to_str().expect("utf-8"),
        "--output",
        "apogee_feet",
    ]);
    assert!(
        text.contains("`apogee_feet` is not an output") && text.contains("apogee_agl_m"),
        "{text}"
    );
    // Too few samples for six inputs and an intercept is said, not a panic.
    let few = Path::new(env!("CARGO_TARGET_TMPDIR")).join("karman-cli/sensitivity-few");
    let _ = std::fs::remove_dir_all(&few);
    let run = karman(&[
        "montecarlo",
        example.to_str().expect("utf-8"),
        "--samples",
        "5",
        "--quiet",
        "--out",
        few.to_str().expect("utf-8"),
    ]);
    assert!(run.status.success());
    let text = failure(&[
        "sensitivity",
        few.to_str().expect("utf-8"),
        "--output",
        "apogee_agl_m",
    ]);
    assert!(
        text.contains("5 completed samples") && text.contains("needs at least 8"),
        "{text}"
    );
    // Wilks' bounds need more samples than 12: said, with the number needed.
    let output = karman(&[
        "tolerance",
        out.to_str().expect("utf-8"),
        "--output",
        "apogee_agl_m",
    ]);
    assert!(output.status.success());
    let table = String::from_utf8_lossy(&output.stdout);
    assert!(
        table.contains("needs at least 299 completed samples"),
        "{table}"
    );
    let text = failure(&[
        "tolerance",
        out.to_str().expect("utf-8"),
        "--coverage",
        "99",
    ]);
    assert!(
        text.contains("strictly between 0 and 1") && text.contains("got 99"),
        "{text}"
    );
    // 12 completed samples suffice, so the table prints.
    let output = karman(&[
        "sensitivity",
        out.to_str().expect("utf-8"),
        "--output",
        "apogee_agl_m",
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let table = String::from_utf8_lossy(&output.stdout);
    assert!(
        table.starts_with("apogee_agl_m: mean ") && table.contains("unexplained"),
        "{table}"
    );
}
