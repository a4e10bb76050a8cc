//! `karman import` of a multi-stage OpenRocket design: the written mission reads as a
//! commented `[[stages]]` mission, `karman check` accepts it and `karman simulate` flies both
//! bodies; of a design with a pair of canards: `karman inspect` gives OpenRocket's CP and
//! margin at rail exit.

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

#[test]
fn inspect_reports_openrocket_stability_at_rail_exit() {
    // `simulation_scripting`'s two canards sit at 90° and 270°: OpenRocket rolls the rocket
    // so that the wind comes normal to them (its least stable roll angle, 0°), and its CP
    // at rod exit (1.760 m, margin 0.876 cal at α 7.7°) counts them at twice the average.
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("karman-cli/import");
    std::fs::create_dir_all(&dir).expect("scratch folder");
    let mission = dir.join("simulation_scripting.toml");
    let ork = design("simulation_scripting");
    let output = karman(&[
        "import",
        ork.to_str().expect("utf-8"),
        "--simulation",
        "No controlling",
        "-o",
        mission.to_str().expect("utf-8"),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let output = karman(&["inspect", mission.to_str().expect("utf-8"), "--json"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).expect("json");
    let stability = &json["stability_at_rail_exit"];
    let get = |key: &str| stability[key].as_f64().expect(key);
    assert!(get("roll_rad").abs() < 1e-12, "{stability}");
    // Within 1 % of the body length (2.705 m) and 0.1 cal, the comparison's tolerances.
    assert!((get("cp_m") - 1.760).abs() < 0.01 * 2.705, "{stability}");
    assert!((get("margin_cal") - 0.876).abs() < 0.1, "{stability}");
    assert!(get("alpha_rad").to_degrees() > 5.0, "{stability}");
    let output = karman(&["inspect", mission.to_str().expect("utf-8")]);
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(text.contains("At rail exit: CP 1.76"), "{text}");
}

/// `import X.ork -o X.ork` is refused and leaves the design as it was; a `--motor` path that
/// does not exist is an error naming it.
#[test]
fn import_refuses_to_overwrite_the_design_and_a_missing_motor_path() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("karman-cli/import-refusals");
    std::fs::create_dir_all(&dir).expect("scratch folder");
    let copy = dir.join("design.ork");
    std::fs::copy(design("a_simple_model_rocket"), &copy).expect("copy");
    let before = std::fs::read(&copy).expect("read");
    let path = copy.to_str().expect("utf-8");
    let output = karman(&["import", path, "-o", path]);
    assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
    assert!(
        stderr(&output).contains("that is the design being imported"),
        "{}",
        stderr(&output)
    );
    assert_eq!(
        std::fs::read(&copy).expect("read"),
        before,
        "the design is untouched"
    );
    let mission = dir.join("m.toml");
    let output = karman(&[
        "import",
        path,
        "--motor",
        "/no/such/motors",
        "-o",
        mission.to_str().expect("utf-8"),
    ]);
    assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
    assert!(
        stderr(&output).contains("--motor /no/such/motors: no such file or folder"),
        "{}",
        stderr(&output)
    );
    assert!(!mission.exists());
}
