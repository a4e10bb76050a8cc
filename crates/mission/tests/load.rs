//! Loading the validation missions.

use crate::common::validation_missions;
use karman_mission::load;

#[test]
fn validate_missions_load() {
    let Some(missions) = validation_missions() else {
        println!("skipped: validation data folder not found");
        return;
    };
    assert!(
        missions.len() >= 8,
        "expected the 8 validation missions, found {}",
        missions.len()
    );
    for path in &missions {
        if let Err(error) = load(path, &[]) {
            panic!("{error}");
        }
    }
}
