//! The page's import of an OpenRocket design is `karman import`'s, its motor files given as
//! bytes; and a missing motor is an error naming it, not a panic.

use karman_web::{Files, fly, import_ork};
use std::path::Path;

const DESIGN: &str = "../../fixtures/openrocket/a_simple_model_rocket";
const MOTORS: [&str; 3] = ["Estes_A8.eng", "Estes_B4.eng", "Estes_C6.eng"];

#[test]
fn an_ork_imports_as_the_command_line_imports_it_and_flies() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join(DESIGN);
    let native = karman_openrocket::import(
        &dir.join("design.ork"),
        &karman_openrocket::ImportOptions {
            simulation: None,
            motors: Vec::new(),
            output_dir: Some(dir.clone()),
        },
    )
    .expect("native import");
    let mut files = Files::new();
    for motor in MOTORS {
        files
            .add(motor, std::fs::read(dir.join(motor)).expect("motor"))
            .expect("added");
    }
    let bytes = std::fs::read(dir.join("design.ork")).expect("design");
    let page: serde_json::Value =
        serde_json::from_str(&import_ork("design.ork", &bytes, &files).expect("page import"))
            .expect("JSON");
    let mission = page["mission"].as_str().expect("mission text");
    // The command line's comment names the motor file by the path it found it at.
    let named = MOTORS.iter().fold(native.mission.clone(), |text, motor| {
        text.replace(&dir.join(motor).display().to_string(), motor)
    });
    assert_eq!(mission, named);
    assert!(mission.contains("Estes_"), "a thrust file is named");
    let flown: serde_json::Value =
        serde_json::from_str(&fly("design.toml", mission, &files).expect("flies")).expect("JSON");
    assert!(
        flown["json"]
            .as_str()
            .is_some_and(|j| j.contains("apogee_agl_m"))
    );
}

#[test]
fn a_design_without_its_motor_file_is_an_error_naming_the_motor() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join(DESIGN);
    let bytes = std::fs::read(dir.join("design.ork")).expect("design");
    let error = import_ork("design.ork", &bytes, &Files::new()).expect_err("no motor");
    let failure: serde_json::Value = serde_json::from_str(&error).expect("JSON");
    let message = failure["message"].as_str().expect("message");
    assert!(message.starts_with("design.ork"), "{message}");
    assert!(message.to_lowercase().contains("motor"), "{message}");
    let garbage =
        import_ork("junk.ork", b"\x00\x01 not a design", &Files::new()).expect_err("junk");
    assert!(garbage.contains("junk.ork"), "{garbage}");
}
