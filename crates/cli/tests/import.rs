//! `karman import` of a multi-stage OpenRocket design: the written mission reads as a
//! commented `[[stages]]` mission, `karman check` accepts it and `karman simulate` flies both
//! bodies.

use std::path::{Path, PathBuf};

use crate::common::{karman, stderr};

fn design(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/openrocket")
        .join(name)
        .join("design.ork")
}

/// The mission text with the thrust-curve paths (relative to wherever the scratch folder
/// lies) replaced by their file names.
fn without_paths(text: &str) -> String {
    text.lines()
        .map(|line| {
            if let Some(path) = line
                .strip_prefix("thrust = \"")
                .and_then(|p| p.strip_suffix('"'))
            {
                let name = Path::new(path)
                    .file_name()
                    .expect("a file")
                    .to_string_lossy();
                format!("thrust = \"<fixtures>/{name}\"")
            } else if line.starts_with("# AeroTech ") && line.contains(" from ") {
                let (head, tail) = line.split_once(" from ").expect("from");
                let (path, rest) = tail.split_once(": ").expect("path");
                let name = Path::new(path)
                    .file_name()
                    .expect("a file")
                    .to_string_lossy();
                format!("{head} from <fixtures>/{name}: {rest}")
            } else {
                line.to_owned()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn a_two_stage_design_imports_checks_and_flies() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("karman-cli/import");
    std::fs::create_dir_all(&dir).expect("scratch folder");
    let mission = dir.join("two_stage.toml");
    let ork = design("two_stage_high_power_rocket");
    let output = karman(&[
        "import",
        ork.to_str().expect("utf-8"),
        "--simulation",
        "Simulation 2",
        "-o",
        mission.to_str().expect("utf-8"),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = std::fs::read_to_string(&mission).expect("written");
    insta::assert_snapshot!("two_stage_import", without_paths(&text));

    let mission = mission.to_str().expect("utf-8");
    let output = karman(&["check", mission]);
    assert!(output.status.success(), "{}", stderr(&output));
    let output = karman(&["simulate", mission, "--json"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).expect("json");
    let bodies = json["bodies"].as_array().expect("bodies");
    assert_eq!(bodies.len(), 2);
    assert_eq!(bodies[0]["name"], "sustainer");
    assert_eq!(bodies[1]["name"], "Booster");
    let separation = json["separations"][0]["time_s"].as_f64().expect("time");
    // OpenRocket separates the booster at its burn-out, 1.515 s.
    assert!((separation - 1.515).abs() < 0.03, "{separation}");
}
