//! The thrust files of the validation missions load, and a malformed or missing file is
//! reported with its name.

use karman_propulsion::{PropulsionError, ThrustData, ThrustFormat};

#[test]
fn validation_thrust_files_load() {
    let Some(folder) = karman_validation::folder() else {
        return;
    };
    let mut loaded = 0;
    for flight in folder.flown() {
        for file in std::fs::read_dir(&flight.dir)
            .into_iter()
            .flatten()
            .flatten()
        {
            let path = file.path();
            let name = path
                .file_name()
                .and_then(|n| n.to_str())
                .unwrap_or_default()
                .to_owned();
            let is_thrust = name.ends_with(".eng") || name.contains("thrust");
            if !is_thrust {
                continue;
            }
            let data = ThrustData::load(&path).unwrap_or_else(|e| panic!("{e}"));
            if data.format == ThrustFormat::Eng {
                // RocketPy prepends (0, 0) to RASP data (docs/physics.md §6.1); a file that states
                // its own t = 0 sample keeps it (Halcyon's, which its mission therefore states
                // as a table: see fixtures/validation/halcyon/mission.toml).
                let text = std::fs::read_to_string(&path).expect("readable");
                let first: Vec<f64> = text
                    .lines()
                    .map(str::trim)
                    .find(|l| l.starts_with(|c: char| c.is_ascii_digit()))
                    .map(|l| {
                        l.split_whitespace()
                            .filter_map(|v| v.parse().ok())
                            .collect()
                    })
                    .unwrap_or_default();
                let origin = match first.as_slice() {
                    [t, thrust] if t.abs() < 1e-300 => *thrust,
                    _ => 0.0,
                };
                assert!(
                    data.times[0].abs() < 1e-300 && (data.thrusts[0] - origin).abs() < 1e-300,
                    "{name}"
                );
                assert!(
                    data.header.as_ref().and_then(|h| h.dry_mass()).is_some(),
                    "{name}"
                );
            }
            loaded += 1;
        }
    }
    // 6 .eng files and 5 CSV curves (andromeda, juno3, valetudo, hedy, camoes).
    assert_eq!(loaded, 11);
}

#[test]
fn bad_files_name_file_and_line() {
    let dir = std::env::temp_dir().join(format!("karman-propulsion-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let eng = dir.join("bad.eng");
    std::fs::write(&eng, "; c\nM1 75 757 0 3 5 CTI\n0.1 100\n0.2 1O0\n").expect("write");
    let e = ThrustData::load(&eng).unwrap_err();
    assert!(
        matches!(&e, PropulsionError::Malformed { line: 4, text, .. } if text == "1O0"),
        "{e}"
    );
    assert!(e.to_string().contains("bad.eng:4"), "{e}");
    let csv = dir.join("bad.csv");
    std::fs::write(&csv, "t,f\n0,1\n1,x\n").expect("write");
    let e = ThrustData::load(&csv).unwrap_err();
    assert!(e.to_string().contains("bad.csv:3"), "{e}");
    let rse = dir.join("bad.rse");
    std::fs::write(
        &rse,
        "<engine code=\"x\">\n<data>\n<eng-data t=\"1\" f=\"-3\"/>\n</data></engine>\n",
    )
    .expect("write");
    let e = ThrustData::load(&rse).unwrap_err();
    assert!(
        matches!(e, PropulsionError::NegativeThrust { line: 3, .. }),
        "{e}"
    );
    // Not well-formed XML (never closed): an XML error naming the file.
    std::fs::write(
        &rse,
        "<engine code=\"x\">\n<data>\n<eng-data t=\"1\" f=\"3\"/>\n",
    )
    .expect("write");
    let e = ThrustData::load(&rse).unwrap_err();
    assert!(matches!(e, PropulsionError::Xml { .. }), "{e}");
    assert!(e.to_string().contains("bad.rse:"), "{e}");
    let missing = dir.join("missing.eng");
    let e = ThrustData::load(&missing).unwrap_err();
    assert!(
        matches!(&e, PropulsionError::Io { source_name, .. } if source_name.contains("missing.eng")),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).expect("cleanup");
}
