//! The data fingerprint of a Monte Carlo study: every file a mission names is hashed, and a
//! changed file changes exactly its entry.

use crate::common::validation_missions;
use karman_mission::montecarlo::{MonteCarlo, StudyOverrides, data_fingerprint};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// Every string of a TOML value that names a file beside the mission.
fn named_files(value: &toml::Value, dir: &Path, out: &mut BTreeSet<PathBuf>) {
    match value {
        toml::Value::String(s) if dir.join(s).is_file() => {
            out.insert(PathBuf::from(s));
        }
        toml::Value::Array(items) => items.iter().for_each(|v| named_files(v, dir, out)),
        toml::Value::Table(table) => table.values().for_each(|v| named_files(v, dir, out)),
        _ => {}
    }
}

#[test]
fn validate_every_file_a_mission_names_is_in_its_fingerprint() {
    let Some(missions) = validation_missions() else {
        return;
    };
    for path in missions {
        let mission = karman_mission::load(&path, &[]).expect("mission loads");
        let dir = path.parent().expect("folder");
        let text = std::fs::read_to_string(&path).expect("mission text");
        let mut named = BTreeSet::new();
        let table: toml::Table = text.parse().expect("TOML");
        named_files(&toml::Value::Table(table), dir, &mut named);
        let data = data_fingerprint(&mission).expect("fingerprint");
        let hashed: BTreeSet<PathBuf> = data
            .iter()
            .skip(1)
            .map(|f| PathBuf::from(&f.path))
            .collect();
        assert_eq!(hashed, named, "{}", path.display());
        assert_eq!(data[0].role, "mission");
        assert!(data.iter().all(|f| f.sha256.len() == 64));
    }
}

#[test]
fn validate_a_changed_drag_file_changes_its_entry_only() {
    let Some(dir) = crate::common::validation_dir() else {
        return;
    };
    let copy = Path::new(env!("CARGO_TARGET_TMPDIR")).join("fingerprint-calisto");
    let _ = std::fs::remove_dir_all(&copy);
    std::fs::create_dir_all(&copy).expect("folder");
    for entry in std::fs::read_dir(dir.join("calisto")).expect("calisto") {
        let entry = entry.expect("entry");
        std::fs::copy(entry.path(), copy.join(entry.file_name())).expect("copy");
    }
    let path = copy.join("mission.toml");
    let study = |samples| {
        let mission = karman_mission::load(&path, &[]).expect("mission loads");
        let overrides = StudyOverrides {
            samples: Some(samples),
            seed: None,
        };
        MonteCarlo::new(&mission, overrides)
            .expect("study")
            .study()
            .data
            .clone()
    };
    let before = study(10);
    assert_eq!(study(10), before, "the same files hash the same");
    let drag = copy.join("powerOffDragCurve.csv");
    let mut bytes = std::fs::read(&drag).expect("drag");
    bytes.extend_from_slice(b"\n");
    std::fs::write(&drag, bytes).expect("edited");
    let after = study(10);
    let changed: Vec<&str> = before
        .iter()
        .zip(&after)
        .filter(|(a, b)| a != b)
        .map(|(a, _)| a.role.as_str())
        .collect();
    assert_eq!(changed, ["rocket.power_off_drag"]);
}
