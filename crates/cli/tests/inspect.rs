//! `karman inspect`: the environment, motor and rocket objects shaped like the validation
//! references, readable tables (snapshotted), plots and the rocket drawing.

use crate::common::{example, karman, stderr, validation_flights};
use std::path::Path;

fn keys(v: &serde_json::Value) -> Vec<String> {
    let mut k: Vec<String> = v.as_object().expect("object").keys().cloned().collect();
    k.sort_unstable();
    k
}

#[test]
fn validate_json_objects_have_the_reference_shape() {
    let Some(flights) = validation_flights() else {
        return;
    };
    let mut count = 0;
    for flight in flights {
        let mission = flight.mission();
        let output = karman(&["inspect", mission.to_str().expect("UTF-8"), "--json"]);
        assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
        let ours: serde_json::Value = serde_json::from_slice(&output.stdout).expect("JSON");
        let reference: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(flight.reference()).expect("reference"))
                .expect("reference JSON");
        for object in ["environment", "motor", "rocket"] {
            assert_eq!(keys(&ours[object]), keys(&reference[object]), "{object}");
        }
        let surfaces = |v: &serde_json::Value| -> Vec<String> {
            v["rocket"]["surfaces"]
                .as_array()
                .expect("surfaces")
                .iter()
                .map(|s| s["name"].as_str().expect("name").to_owned())
                .collect()
        };
        assert_eq!(surfaces(&ours), surfaces(&reference), "{}", flight.name);
        // Default motor times are the reference's times, to the last bit.
        assert_eq!(
            ours["motor"]["times_s"], reference["motor"]["times_s"],
            "{}",
            flight.name
        );
        count += 1;
    }
    assert!(count >= 8, "found {count} flights");
}

#[test]
fn heights_and_times_are_honoured() {
    let output = karman(&[
        "inspect",
        example().to_str().expect("UTF-8"),
        "--json",
        "--heights",
        "1200,1500,2500",
        "--times",
        "0,1",
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let v: serde_json::Value = serde_json::from_slice(&output.stdout).expect("JSON");
    assert_eq!(
        v["environment"]["heights_asl_m"],
        serde_json::json!([1200.0, 1500.0, 2500.0])
    );
    assert_eq!(
        v["environment"]["pressure_pa"].as_array().map(Vec::len),
        Some(3)
    );
    assert_eq!(v["motor"]["times_s"], serde_json::json!([0.0, 1.0]));
}

#[test]
fn readable_tables() {
    let output = karman(&["inspect", example().to_str().expect("UTF-8")]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    insta::assert_snapshot!(String::from_utf8_lossy(&output.stdout));
}

#[test]
fn plots_and_drawing_are_svg() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("karman-cli/inspect-plots");
    let _ = std::fs::remove_dir_all(&dir);
    let drawing = dir.join("rocket.svg");
    let output = karman(&[
        "inspect",
        example().to_str().expect("UTF-8"),
        "--plot",
        dir.to_str().expect("UTF-8"),
        "--draw",
        drawing.to_str().expect("UTF-8"),
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    for name in [
        "pressure",
        "temperature",
        "density",
        "speed_of_sound",
        "wind",
        "thrust",
        "motor_mass",
        "motor_inertia",
        "rocket",
    ] {
        let svg = std::fs::read_to_string(dir.join(format!("{name}.svg"))).expect("svg file");
        assert!(svg.contains("<svg"), "{name}.svg");
    }
    let svg = std::fs::read_to_string(&drawing).expect("drawing");
    assert!(
        svg.contains("CP") && svg.contains("CG"),
        "drawing lacks CG/CP marks"
    );
}

#[test]
fn bad_heights_are_a_usage_error_not_a_panic() {
    let output = karman(&[
        "inspect",
        example().to_str().expect("UTF-8"),
        "--heights",
        "1,x",
    ]);
    let text = stderr(&output);
    assert!(!text.contains("panicked at"), "{text}");
    assert_eq!(output.status.code(), Some(2), "{text}");
    assert!(text.contains("x"), "{text}");
}

#[test]
fn extra_motors_are_listed_each_as_it_would_be_alone() {
    let airstart = example().with_file_name("airstart.toml");
    let output = karman(&["inspect", airstart.to_str().expect("UTF-8"), "--json"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let v: serde_json::Value = serde_json::from_slice(&output.stdout).expect("JSON");
    let extra = &v["extra_motors"][0];
    assert_eq!(extra["name"], "outboard");
    assert_eq!(extra["ignition_delay_s"], 3.0);
    assert_eq!(extra["cluster_count"], 2);
    // The fixture's inline curve [[0, 0], [0.05, 320], [0.3, 290], [1.4, 230], [1.6, 0]]:
    // 8 + 76.25 + 286 + 23 N·s by the trapezoidal rule.
    let impulse = extra["motor"]["total_impulse_ns"]
        .as_f64()
        .expect("impulse");
    assert!((impulse - 393.25).abs() < 1e-9, "{impulse}");
    assert_eq!(extra["motor"]["burn_out_s"], 1.6);
    // `[motor]` stays the K motor alone; the rocket's masses hold every motor.
    assert!(v["motor"]["total_impulse_ns"].as_f64().expect("K") > 1900.0);
    let text = karman(&["inspect", airstart.to_str().expect("UTF-8")]);
    assert!(
        String::from_utf8_lossy(&text.stdout)
            .contains("Extra motor 'outboard' ([[extra_motors]] 0"),
        "{}",
        String::from_utf8_lossy(&text.stdout)
    );
    // The thrust and mass charts show every motor beside [motor].
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("karman-cli/inspect-airstart");
    let _ = std::fs::remove_dir_all(&dir);
    let output = karman(&[
        "inspect",
        airstart.to_str().expect("UTF-8"),
        "--plot",
        dir.to_str().expect("UTF-8"),
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    for chart in ["thrust", "motor_mass"] {
        let svg = std::fs::read_to_string(dir.join(format!("{chart}.svg"))).expect("svg file");
        assert!(
            svg.contains("[motor]") && svg.contains("every motor"),
            "{chart}.svg"
        );
    }
}
