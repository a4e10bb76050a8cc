//! `karman sweep`: every variant flown as `simulate --set` would fly it, the table, the CSV
//! of summaries, one overlaid SVG per series, and located errors.

use crate::common::{example, failure, karman, stderr};

#[test]
fn each_variant_flies_as_simulate_with_the_override() {
    let out = tempfile::tempdir().expect("temporary directory");
    let mission = example().display().to_string();
    let dir = out.path().display().to_string();
    let output = karman(&[
        "sweep",
        &mission,
        "--vary",
        "rocket.surfaces.fins.position=1.3,1.42",
        "--series",
        "altitude_agl",
        "--series",
        "attitude_angle",
        "--out",
        &dir,
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let table = String::from_utf8_lossy(&output.stdout);
    assert!(table.contains("apogee AGL (m)"), "{table}");
    assert_eq!(
        table.lines().filter(|l| l.starts_with("1.")).count(),
        2,
        "{table}"
    );

    let csv = std::fs::read_to_string(out.path().join("summary.csv")).expect("summary.csv");
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(rows.len(), 3, "{csv}");
    let header: Vec<&str> = rows[0].split(',').collect();
    assert_eq!(header[0], "rocket.surfaces.fins.position");
    let apogee = header
        .iter()
        .position(|h| *h == "apogee_agl_m")
        .expect("apogee column");
    for (row, value) in rows[1..].iter().zip(["1.3", "1.42"]) {
        let fields: Vec<&str> = row.split(',').collect();
        assert_eq!(fields[0], value);
        let set = format!("rocket.surfaces.fins.position={value}");
        let single = karman(&["simulate", &mission, "--json", "--set", &set]);
        assert_eq!(single.status.code(), Some(0), "{}", stderr(&single));
        let summary: serde_json::Value = serde_json::from_slice(&single.stdout).expect("JSON");
        let expected = summary["apogee_agl_m"].as_f64().expect("apogee");
        let got: f64 = fields[apogee].parse().expect("a number");
        assert!(got.to_bits() == expected.to_bits(), "{got} vs {expected}");
    }
    for name in ["altitude_agl.svg", "attitude_angle.svg"] {
        let svg = std::fs::read_to_string(out.path().join(name)).expect(name);
        assert!(
            svg.contains("rocket.surfaces.fins.position=1.3"),
            "{name} has no legend"
        );
        assert!(svg.contains("rocket.surfaces.fins.position=1.42"), "{name}");
    }
}

#[test]
fn bad_sweeps_are_clear_errors() {
    let mission = example().display().to_string();
    let text = failure(&["sweep", &mission, "--vary", "rocket.surfaces.fins.position"]);
    assert!(text.contains("expected PATH=V1,V2,..."), "{text}");
    let text = failure(&["sweep", &mission, "--vary", "flight.inclinatio=80,85"]);
    assert!(text.contains("inclinatio"), "{text}");
    let text = failure(&[
        "sweep",
        &mission,
        "--vary",
        "flight.inclination=80",
        "--series",
        "height",
    ]);
    assert!(text.contains("--series `height`: no such series"), "{text}");
    // A value that is not TOML, or out of range, is named as the `--vary` value it is.
    for (vary, shown) in [
        ("rocket.mass=2.6,a", "--vary rocket.mass: the value `a`"),
        ("rocket.mass=[1,2", "--vary rocket.mass: the value `[1,2`"),
        ("rocket.mass=2.6,nan", "--vary rocket.mass: the value `nan`"),
        ("rocket.mass=-1,2.6", "--vary rocket.mass: the value `-1`"),
    ] {
        let text = failure(&["sweep", &mission, "--vary", vary]);
        assert!(text.contains(shown), "{vary}: {text}");
    }
}

#[test]
fn a_two_stage_sweep_has_each_body() {
    let out = tempfile::tempdir().expect("temporary directory");
    let fixture = example().with_file_name("two_stage.toml");
    let mission = fixture.display().to_string();
    let dir = out.path().display().to_string();
    let output = karman(&[
        "sweep",
        &mission,
        "--vary",
        "stages.0.separation=\"burnout + 0.2\",\"burnout + 1.2\"",
        "--out",
        &dir,
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let csv = std::fs::read_to_string(out.path().join("summary.csv")).expect("summary.csv");
    let rows: Vec<Vec<&str>> = csv.lines().map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 3, "{csv}");
    let at = |name: &str| {
        rows[0]
            .iter()
            .position(|h| *h == name)
            .unwrap_or_else(|| panic!("{name} in {:?}", rows[0]))
    };
    let number = |row: usize, name: &str| rows[row][at(name)].parse::<f64>().expect("number");
    // The same columns as a Monte Carlo study's; one second later, and both bodies land.
    let separation =
        number(2, "booster.separation_time_s") - number(1, "booster.separation_time_s");
    assert!((separation - 1.0).abs() < 0.02, "{separation}");
    for row in [1, 2] {
        assert!(number(row, "impact_time_s") > number(row, "booster.impact_time_s"));
    }
    // The simulate of the same variant gives the same booster landing.
    let output = karman(&[
        "simulate",
        &mission,
        "--json",
        "--set",
        "stages.0.separation=\"burnout + 1.2\"",
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).expect("JSON");
    let booster = json["bodies"]
        .as_array()
        .and_then(|b| b.iter().find(|b| b["name"] == "booster"))
        .expect("booster");
    let x = booster["summary"]["impact_x_m"].as_f64().expect("x");
    assert_eq!(x.to_bits(), number(2, "booster.impact_x_m").to_bits());
    let svg = std::fs::read_to_string(out.path().join("altitude_agl.svg")).expect("chart");
    assert!(svg.contains("(booster)") && svg.contains("(sustainer)"));
    // A variant whose booster is not flown alone (no mass) changes the columns: refused.
    let text = failure(&[
        "sweep",
        &mission,
        "--vary",
        "stages.0.rocket.mass=1.1,0",
        "--out",
        &dir,
    ]);
    assert!(text.contains("stages.0.rocket.mass=0"), "{text}");
    assert!(text.contains("columns"), "{text}");
}

/// The number of points of each curve of an SVG chart: its 2-pixel `<polyline>`s (the grid
/// and axes are thinner) of more than the legend's two points.
fn curve_points(svg: &str) -> Vec<usize> {
    svg.split("<polyline")
        .skip(1)
        .filter(|p| {
            p.split('>')
                .next()
                .is_some_and(|tag| tag.contains("stroke-width=\"2\""))
        })
        .filter_map(|p| {
            let start = p.find("points=\"")? + 8;
            let end = p[start..].find('"')?;
            Some(p[start..start + end].split_whitespace().count())
        })
        .filter(|&n| n > 2)
        .collect()
}

#[test]
fn a_window_limits_the_charts_to_its_times() {
    let mission = example().display().to_string();
    let sweep = |extra: &[&str]| {
        let out = tempfile::tempdir().expect("temporary directory");
        let dir = out.path().display().to_string();
        let mut args = vec![
            "sweep",
            &mission,
            "--vary",
            "rocket.mass=2.5,2.7",
            "--out",
            &dir,
        ];
        args.extend_from_slice(extra);
        let output = karman(&args);
        assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
        std::fs::read_to_string(out.path().join("altitude_agl.svg")).expect("chart")
    };
    let whole = curve_points(&sweep(&[]));
    let boost = curve_points(&sweep(&["--window", "0:3"]));
    assert_eq!(whole.len(), boost.len());
    assert!(!boost.is_empty());
    for (w, b) in whole.iter().zip(&boost) {
        assert!(*b > 1 && b < w, "window 0:3 kept {b} of {w} points");
    }
    // A bad window is a usage error naming the flag and the value.
    let output = karman(&[
        "sweep",
        &mission,
        "--vary",
        "rocket.mass=2.5",
        "--window",
        "5:2",
    ]);
    assert_eq!(output.status.code(), Some(2));
    let text = stderr(&output);
    assert!(
        text.contains("--window") && text.contains("ends before it starts"),
        "{text}"
    );
}
