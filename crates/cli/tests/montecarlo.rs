//! `karman montecarlo` and `karman merge`: a small study of the example mission, its files,
//! shards merged into the single run's bytes, resume, and clear errors (never a panic).

use crate::common::{example, failure, karman, scratch, stderr};
use std::path::{Path, PathBuf};

/// A fresh output directory under this test binary's scratch folder.
fn fresh(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("karman-cli")
        .join("montecarlo")
        .join(name);
    if dir.exists() {
        std::fs::remove_dir_all(&dir).expect("remove an old scratch directory");
    }
    dir
}

/// `karman montecarlo MISSION --samples 12 --quiet --out OUT EXTRA...`.
fn montecarlo_of(mission: &Path, out: &Path, extra: &[&str]) -> std::process::Output {
    let mission = mission.display().to_string();
    let out = out.display().to_string();
    let mut args = vec![
        "montecarlo",
        &mission,
        "--samples",
        "12",
        "--quiet",
        "--out",
        &out,
    ];
    args.extend_from_slice(extra);
    karman(&args)
}

/// [`montecarlo_of`] the example mission.
fn montecarlo(out: &Path, extra: &[&str]) -> std::process::Output {
    montecarlo_of(&example(), out, extra)
}

fn assert_same_files(a: &Path, b: &Path) {
    let mut names: Vec<_> = std::fs::read_dir(a)
        .expect("directory")
        .map(|e| e.expect("entry").file_name())
        .collect();
    names.sort();
    assert_eq!(names.len(), 7, "{names:?}");
    for name in names {
        let x = std::fs::read(a.join(&name)).expect("file");
        let y = std::fs::read(b.join(&name)).unwrap_or_default();
        assert!(x == y, "{} differs", name.to_string_lossy());
    }
}

#[test]
fn a_study_and_its_shards_give_the_same_files() {
    let single = fresh("single");
    let output = montecarlo(&single, &["--threads", "2"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("apogee_agl_m"), "{stdout}");
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(single.join("summary.json")).expect("summary.json"))
            .expect("JSON");
    assert_eq!(summary["samples"], 12);
    assert_eq!(summary["seed"], 7, "the example mission's seed");
    let csv = std::fs::read_to_string(single.join("samples.csv")).expect("samples.csv");
    assert_eq!(csv.lines().count(), 13);
    assert!(csv.starts_with("index,status,error,rocket.mass,motor.total_impulse,"));

    let mut shards = Vec::new();
    for k in ["2/3", "1/3", "3/3"] {
        let dir = fresh(&format!("shard{}", &k[..1]));
        let output = montecarlo(&dir, &["--threads", "1", "--shard", k]);
        assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
        shards.push(dir.display().to_string());
    }
    let merged = fresh("merged");
    let merged_arg = merged.display().to_string();
    let mut args = vec!["merge", merged_arg.as_str()];
    args.extend(shards.iter().map(String::as_str));
    let output = karman(&args);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert_same_files(&single, &merged);

    // A partial last line (an interrupted run) is dropped and the study finished.
    let path = single.join("samples.csv");
    std::fs::write(&path, &csv.as_bytes()[..csv.len() / 2]).expect("cut samples.csv");
    let output = montecarlo(&single, &[]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert_same_files(&single, &merged);
}

#[test]
fn a_different_study_or_missing_shard_fails_cleanly() {
    let dir = fresh("refused");
    let output = montecarlo(&dir, &["--seed", "1"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let text = failure(&[
        "montecarlo",
        &example().display().to_string(),
        "--samples",
        "12",
        "--seed",
        "2",
        "--quiet",
        "--out",
        &dir.display().to_string(),
    ]);
    assert!(
        text.contains("different study") && text.contains("seed"),
        "{text}"
    );

    let shard = fresh("lonely");
    let output = montecarlo(&shard, &["--shard", "1/2"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let merged = fresh("lonely-merged").display().to_string();
    let text = failure(&["merge", &merged, &shard.display().to_string()]);
    assert!(text.contains("shard 2/2 is missing"), "{text}");

    let output = montecarlo(&fresh("bad-shard"), &["--shard", "3/2"]);
    assert_eq!(output.status.code(), Some(2), "a usage error");
    assert!(!stderr(&output).contains("panicked"));
}

#[test]
fn arrays_varied_by_component_and_whole_give_the_same_bytes_on_any_thread_count() {
    // The inertia scaled as a whole and one component drawn on its own, both set with --set.
    let set = [
        "--set",
        "dispersion.vary.\"rocket.inertia\"={ factor = { normal = [1.0, 0.05] } }",
        "--set",
        "dispersion.vary.\"rocket.inertia.2\"={ std = 0.0002 }",
        "--set",
        "dispersion.vary.\"rocket.mass\".std=0.2",
    ];
    let mut files = Vec::new();
    for threads in ["1", "2", "3"] {
        let out = fresh(&format!("arrays-{threads}"));
        let mut extra = vec!["--threads", threads];
        extra.extend_from_slice(&set);
        let output = montecarlo(&out, &extra);
        assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
        files.push(std::fs::read(out.join("samples.csv")).expect("samples.csv"));
    }
    assert!(files.iter().all(|f| *f == files[0]), "samples.csv differs");
    let csv = String::from_utf8(files.swap_remove(0)).expect("UTF-8");
    let header: Vec<&str> = csv.lines().next().expect("header").split(',').collect();
    let column = |name: &str| {
        header
            .iter()
            .position(|c| *c == name)
            .unwrap_or_else(|| panic!("{name} not in {header:?}"))
    };
    let (factor, i33, mass) = (
        column("rocket.inertia:factor"),
        column("rocket.inertia.2"),
        column("rocket.mass"),
    );
    let values = |index: usize| -> Vec<f64> {
        csv.lines()
            .skip(1)
            .map(|row| {
                row.split(',')
                    .nth(index)
                    .expect("cell")
                    .parse()
                    .expect("number")
            })
            .collect()
    };
    let spread = |v: &[f64]| {
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / v.len() as f64).sqrt()
    };
    // Every draw differs, around the nominal values (factor 1, I33 0.0021 kg·m², the mass's
    // standard deviation now 0.2 kg instead of the file's 0.05).
    let (f, i, m) = (values(factor), values(i33), values(mass));
    assert!(
        f.iter().all(|x| (x - 1.0).abs() < 0.25) && spread(&f) > 0.01,
        "{f:?}"
    );
    assert!(
        i.iter().all(|x| (x - 0.0021).abs() < 0.001) && spread(&i) > 0.0,
        "{i:?}"
    );
    assert!(spread(&m) > 0.08, "{m:?}");
}

/// A copy of the example mission and its data files in a fresh folder `name`, to edit.
fn example_copy(name: &str) -> PathBuf {
    let dir = fresh(name);
    std::fs::create_dir_all(&dir).expect("folder");
    let source = example();
    let fixtures = source.parent().expect("fixtures folder");
    for file in [
        "example.toml",
        "example_K1960.eng",
        "power_off_drag.csv",
        "power_on_drag.csv",
    ] {
        std::fs::copy(fixtures.join(file), dir.join(file)).expect("copy");
    }
    dir
}

#[test]
fn a_drag_file_edited_before_the_resume_is_named_and_refused() {
    let mission = example_copy("edited-drag-mission");
    let out = fresh("edited-drag-out");
    let output = montecarlo_of(&mission.join("example.toml"), &out, &[]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let study: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("study.json")).expect("study.json"))
            .expect("JSON");
    let roles: Vec<&str> = study["data"]
        .as_array()
        .expect("data files")
        .iter()
        .map(|f| f["role"].as_str().expect("role"))
        .collect();
    assert_eq!(
        roles,
        [
            "mission",
            "motor.thrust",
            "rocket.power_off_drag",
            "rocket.power_on_drag"
        ]
    );
    // Killed half-way: a cut samples.csv. Then the drag curve is edited.
    let csv = std::fs::read(out.join("samples.csv")).expect("samples.csv");
    std::fs::write(out.join("samples.csv"), &csv[..csv.len() / 2]).expect("cut");
    let drag = mission.join("power_off_drag.csv");
    let text = std::fs::read_to_string(&drag).expect("drag curve");
    std::fs::write(&drag, text.replacen("0.52", "0.53", 1)).expect("edited drag curve");
    let before = std::fs::read(out.join("samples.csv")).expect("samples.csv");
    let output = montecarlo_of(&mission.join("example.toml"), &out, &[]);
    let text = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{text}");
    assert!(
        text.contains("power_off_drag.csv") && text.contains("different study"),
        "{text}"
    );
    assert!(
        !text.contains("power_on_drag.csv"),
        "only the edited file: {text}"
    );
    assert_eq!(
        std::fs::read(out.join("samples.csv")).expect("samples.csv"),
        before,
        "the refused resume wrote nothing"
    );
}

#[test]
fn shards_flown_on_different_weather_files_are_not_merged() {
    // A custom atmosphere with its wind profile in a file; the second shard's file differs.
    let wind = |dir: &Path, speed: &str| {
        std::fs::write(
            dir.join("wind_u.csv"),
            format!("height_m,wind_mps\n0,{speed}\n5000,{speed}\n"),
        )
        .expect("wind file");
    };
    let weather = [
        "--set",
        "environment.atmosphere.model=\"custom\"",
        "--set",
        "environment.atmosphere.wind_u=\"wind_u.csv\"",
    ];
    let (a, b) = (example_copy("weather-a"), example_copy("weather-b"));
    wind(&a, "3");
    wind(&b, "4");
    let (shard1, shard2) = (fresh("weather-shard1"), fresh("weather-shard2"));
    let output = montecarlo_of(
        &a.join("example.toml"),
        &shard1,
        &[&weather[..], &["--shard", "1/2"]].concat(),
    );
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let output = montecarlo_of(
        &b.join("example.toml"),
        &shard2,
        &[&weather[..], &["--shard", "2/2"]].concat(),
    );
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let merged = fresh("weather-merged");
    let text = failure(&[
        "merge",
        &merged.display().to_string(),
        &shard1.display().to_string(),
        &shard2.display().to_string(),
    ]);
    assert!(
        text.contains("wind_u.csv") && text.contains("environment.atmosphere.wind_u"),
        "{text}"
    );
    assert!(!merged.join("samples.csv").exists(), "nothing merged");
    // The same weather in both shards merges.
    wind(&b, "3");
    let output = montecarlo_of(
        &b.join("example.toml"),
        &fresh("weather-shard2"),
        &[&weather[..], &["--shard", "2/2"]].concat(),
    );
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let output = karman(&[
        "merge",
        &merged.display().to_string(),
        &shard1.display().to_string(),
        &shard2.display().to_string(),
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
}

#[test]
fn samples_that_reach_max_time_are_marked_counted_and_fail_the_study() {
    let out = fresh("max-time");
    let output = montecarlo(&out, &["--set", "flight.max_time=5"]);
    let text = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "no sample landed: {text}");
    assert!(!text.contains("panicked"), "{text}");
    assert!(text.contains("no sample of shard 1/1 completed"), "{text}");
    // The error itself says why, from the first sample.
    assert!(
        text.contains("sample 0 max_time: the flight reached max_time (5 s)"),
        "{text}"
    );
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        stdout.contains("0 completed, 12 ended early (max_time 12), 0 failed"),
        "{stdout}"
    );
    let csv = std::fs::read_to_string(out.join("samples.csv")).expect("samples.csv");
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    assert_eq!(rows.len(), 12);
    assert!(
        rows.iter()
            .all(|r| r.contains(",max_time,the flight reached max_time (5 s) before landing")),
        "{csv}"
    );
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("summary.json")).expect("summary.json"))
            .expect("JSON");
    assert_eq!(summary["completed"], 0);
    assert_eq!(summary["ended_early"], 12);
    assert_eq!(summary["ended_early_by_status"]["max_time"], 12);
    assert_eq!(summary["failed"], 0);
    assert_eq!(summary["failures"][0]["status"], "max_time");
    // The statistics and ellipses use completed flights only: none here.
    let apogee = summary["outputs"]
        .as_array()
        .expect("outputs")
        .iter()
        .find(|c| c["name"] == "apogee_agl_m")
        .expect("apogee column");
    assert!(apogee.get("mean").is_none(), "{apogee}");
    assert_eq!(summary["ellipses"].as_array().map(Vec::len), Some(0));

    // `simulate` counts the same flight as a failure, with the same message.
    let example = example().display().to_string();
    let text = failure(&["simulate", &example, "--set", "flight.max_time=5"]);
    assert!(
        text.contains("the flight reached max_time (5 s) before landing"),
        "{text}"
    );
    // With the mission's own max_time every sample lands: exit 0.
    let output = montecarlo(&fresh("max-time-ok"), &[]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        stdout.contains("12 completed, 0 ended early, 0 failed"),
        "{stdout}"
    );
}

#[test]
fn a_study_of_dispersed_sensor_noise_is_the_same_on_one_and_two_threads() {
    // The main parachute fires when the noisy barometer and accelerometer say so; their noise
    // keys are the study's inputs (`rocket.sensors.<i>.<key>`).
    let mission = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../mission/tests/fixtures/sensors/calisto_sensor_study.toml");
    let (one, two) = (fresh("sensors-one"), fresh("sensors-two"));
    for (dir, threads) in [(&one, "1"), (&two, "2")] {
        let output = montecarlo_of(&mission, dir, &["--threads", threads]);
        assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    }
    assert_same_files(&one, &two);
    // The draws reach the trigger: the samples' apogees differ.
    let csv = std::fs::read_to_string(one.join("samples.csv")).expect("samples.csv");
    let header: Vec<&str> = csv.lines().next().expect("header").split(',').collect();
    assert!(
        header.contains(&"rocket.sensors.1.noise_density.2"),
        "{header:?}"
    );
    let column = header
        .iter()
        .position(|h| *h == "apogee_agl_m")
        .expect("apogee");
    let mut apogees: Vec<&str> = csv
        .lines()
        .skip(1)
        .map(|row| row.split(',').nth(column).expect("apogee"))
        .collect();
    apogees.sort_unstable();
    apogees.dedup();
    assert_eq!(apogees.len(), 12, "{csv}");
}

#[test]
fn a_3dof_study_is_the_same_on_one_and_two_threads() {
    let three_dof = [
        "--set",
        "flight.simulation_mode=\"3 DOF\"",
        "--set",
        "flight.weathercock_coeff=0.3",
    ];
    let (one, two, six) = (fresh("3dof-one"), fresh("3dof-two"), fresh("3dof-six"));
    for (dir, threads) in [(&one, "1"), (&two, "2")] {
        let mut args = three_dof.to_vec();
        args.extend(["--threads", threads]);
        let output = montecarlo(dir, &args);
        assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    }
    assert_same_files(&one, &two);
    // The same samples in 6 DOF fly other trajectories.
    let output = montecarlo(&six, &["--threads", "2"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let samples = |dir: &Path| std::fs::read(dir.join("samples.csv")).expect("samples.csv");
    assert!(
        samples(&one) != samples(&six),
        "the 3-DOF study flew in 6 DOF"
    );
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(one.join("summary.json")).expect("summary.json"))
            .expect("JSON");
    assert_eq!(summary["completed"], 12, "{summary}");
}

/// The two-stage example mission (with its `[dispersion]` study).
fn two_stage() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/two_stage.toml")
}

#[test]
fn a_two_stage_study_has_each_body_and_the_same_bytes_on_any_split() {
    let single = fresh("staged-single");
    let output = montecarlo_of(&two_stage(), &single, &["--threads", "2"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("booster.impact_x_m"), "{stdout}");
    assert!(stdout.contains("sustainer landing ellipse"), "{stdout}");
    assert!(stdout.contains("booster landing ellipse"), "{stdout}");
    let csv = std::fs::read_to_string(single.join("samples.csv")).expect("samples.csv");
    let header: Vec<&str> = csv.lines().next().expect("header").split(',').collect();
    // The top stage's columns as in a single-stage study, then the booster's.
    let at = |name: &str| header.iter().position(|c| *c == name);
    assert!(at("stages.0.separation").is_some(), "{header:?}");
    let top = at("impact_velocity_mps").expect("top stage column");
    assert_eq!(header[top + 1], "booster.separation_time_s");
    // The booster's outputs last, before the row's digest.
    assert_eq!(
        header[header.len() - 2..],
        ["booster.impact_velocity_mps", "digest"]
    );
    // Every sample flew both bodies: the booster lands short of the sustainer.
    let (sx, bx) = (
        at("impact_x_m").expect("x"),
        at("booster.impact_x_m").expect("x"),
    );
    for row in csv.lines().skip(1) {
        let fields: Vec<&str> = row.split(',').collect();
        assert_eq!(fields[1], "ok", "{row}");
        let x = |i: usize| fields[i].parse::<f64>().expect("number");
        assert!(x(bx).abs() < x(sx).abs(), "{row}");
    }
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(single.join("summary.json")).expect("summary.json"))
            .expect("JSON");
    let ellipses = summary["ellipses"].as_array().expect("ellipses");
    let named: Vec<(&str, &str)> = ellipses
        .iter()
        .map(|e| {
            (
                e["body"].as_str().unwrap_or_default(),
                e["name"].as_str().unwrap_or_default(),
            )
        })
        .collect();
    assert_eq!(
        named,
        [
            ("sustainer", "apogee"),
            ("sustainer", "landing"),
            ("booster", "apogee"),
            ("booster", "landing")
        ]
    );
    let kml = std::fs::read_to_string(single.join("dispersion.kml")).expect("KML");
    assert!(kml.contains("<Folder><name>sustainer</name>"));
    assert!(kml.contains("<Folder><name>booster</name>"));
    let svg = std::fs::read_to_string(single.join("landing.svg")).expect("plot");
    assert!(svg.contains("booster: landing points"));

    // One thread, shards merged, and a resume after a cut give the same files.
    let one = fresh("staged-one-thread");
    let output = montecarlo_of(&two_stage(), &one, &["--threads", "1"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert_same_files(&single, &one);
    let mut shards = Vec::new();
    for k in ["2/2", "1/2"] {
        let dir = fresh(&format!("staged-shard{}", &k[..1]));
        let output = montecarlo_of(&two_stage(), &dir, &["--threads", "1", "--shard", k]);
        assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
        shards.push(dir.display().to_string());
    }
    let merged = fresh("staged-merged");
    let merged_arg = merged.display().to_string();
    let mut args = vec!["merge", merged_arg.as_str()];
    args.extend(shards.iter().map(String::as_str));
    let output = karman(&args);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert_same_files(&single, &merged);
    let path = single.join("samples.csv");
    std::fs::write(&path, &csv.as_bytes()[..csv.len() / 2]).expect("cut samples.csv");
    let output = montecarlo_of(&two_stage(), &single, &[]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert_same_files(&single, &merged);
}

#[test]
fn a_bad_stage_path_is_located() {
    let fixtures = two_stage().with_file_name("");
    let mut text = std::fs::read_to_string(two_stage()).expect("fixture");
    for file in [
        "example_K1960.eng",
        "power_off_drag.csv",
        "power_on_drag.csv",
    ] {
        let absolute = fixtures.join(file).display().to_string();
        text = text.replace(&format!("\"{file}\""), &format!("'{absolute}'"));
    }
    let text = text.replace("\"stages.0.ignition_delay\"", "\"stages.0.ignition_dlay\"");
    let line = 1 + text
        .lines()
        .position(|l| l.contains("ignition_dlay"))
        .expect("the entry");
    let mission = scratch("two_stage_bad_path.toml", text.as_bytes());
    let message = failure(&["check", &mission.display().to_string()]);
    assert!(
        message.contains(&format!("two_stage_bad_path.toml:{line}:")),
        "{message}"
    );
    assert!(message.contains("stages.0.ignition_dlay"), "{message}");
    assert!(
        message.contains("ignition_delay"),
        "the keys there: {message}"
    );
}

#[test]
fn an_input_left_at_an_infinite_default_can_be_drawn_and_the_study_resumed() {
    // `flight.max_time_step` defaults to infinity: study.json once recorded its nominal value
    // as `null`, which made the study unreadable after every sample had flown.
    let out = fresh("infinite-default");
    let vary = r#"dispersion.vary."flight.max_time_step"={ uniform = [0.05, 0.2] }"#;
    let output = montecarlo(&out, &["--set", vary]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let study = std::fs::read_to_string(out.join("study.json")).expect("study.json");
    assert!(study.contains(r#""number": "inf""#), "{study}");
    assert!(!study.contains("null"), "{study}");
    let whole = std::fs::read(out.join("samples.csv")).expect("samples.csv");
    // Killed half-way, then resumed: the same bytes.
    std::fs::write(out.join("samples.csv"), &whole[..whole.len() / 2]).expect("cut");
    let output = montecarlo(&out, &["--set", vary]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert_eq!(
        std::fs::read(out.join("samples.csv")).expect("samples.csv"),
        whole
    );
    // A normal around (or a factor of) infinity is no distribution: refused before flying.
    for variation in ["{ std = 0.01 }", "{ factor = { normal = [1, 0.1] } }"] {
        let out = fresh("infinite-default-std");
        let vary = format!(r#"dispersion.vary."flight.max_time_step"={variation}"#);
        let output = montecarlo(&out, &["--set", &vary]);
        let text = stderr(&output);
        assert_eq!(output.status.code(), Some(1), "{text}");
        assert!(
            text.contains("flight.max_time_step") && text.contains("finite nominal value"),
            "{text}"
        );
        assert!(!out.join("samples.csv").exists());
    }
}

/// Doubles the first completed row's `apogee_agl_m` in `samples.csv`: its line number and
/// sample index.
fn double_an_apogee(samples: &Path) -> (usize, String) {
    let text = std::fs::read_to_string(samples).expect("samples.csv");
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    let column = lines[0]
        .split(',')
        .position(|c| c == "apogee_agl_m")
        .expect("apogee column");
    let number = (1..lines.len())
        .find(|&n| lines[n].contains(",ok,") && !lines[n].contains('"'))
        .expect("a completed row");
    let mut cells: Vec<String> = lines[number].split(',').map(str::to_owned).collect();
    let apogee: f64 = cells[column].parse().expect("a number");
    cells[column] = format!("{:?}", 2.0 * apogee);
    let index = cells[0].clone();
    lines[number] = cells.join(",");
    std::fs::write(samples, lines.join("\n") + "\n").expect("write");
    (number + 1, index)
}

#[test]
fn a_doubled_apogee_is_refused_on_resume_and_merge_naming_the_row() {
    let dir = fresh("tampered");
    let output = montecarlo(&dir, &["--threads", "2"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let csv = std::fs::read_to_string(dir.join("samples.csv")).expect("samples.csv");
    assert!(csv.lines().next().expect("header").ends_with(",digest"));
    let (line, index) = double_an_apogee(&dir.join("samples.csv"));
    let before = std::fs::read(dir.join("samples.csv")).expect("samples.csv");
    let out = dir.display().to_string();
    let text = failure(&[
        "montecarlo",
        &example().display().to_string(),
        "--samples",
        "12",
        "--quiet",
        "--out",
        &out,
    ]);
    assert!(text.contains("samples.csv"), "{text}");
    assert!(text.contains(&format!("line {line}")), "{text}");
    assert!(
        text.contains(&format!("sample {index} was altered")),
        "{text}"
    );
    assert!(text.contains("differs in: apogee_agl_m"), "{text}");
    assert_eq!(text.trim().lines().count(), 1, "one line: {text}");
    assert_eq!(
        std::fs::read(dir.join("samples.csv")).expect("samples.csv"),
        before,
        "the study is left as it was"
    );

    // Shards: one tampered shard is refused by merge, naming its file and row.
    let shards: Vec<PathBuf> = (1..=2)
        .map(|k| {
            let shard = fresh(&format!("tampered-shard-{k}"));
            let output = montecarlo(&shard, &["--shard", &format!("{k}/2")]);
            assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
            shard
        })
        .collect();
    let (line, index) = double_an_apogee(&shards[1].join("samples.csv"));
    let merged = fresh("tampered-merged");
    let mut args = vec!["merge".to_owned(), merged.display().to_string()];
    args.extend(shards.iter().map(|s| s.display().to_string()));
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let text = failure(&args);
    assert!(
        text.contains(&shards[1].join("samples.csv").display().to_string()),
        "{text}"
    );
    assert!(text.contains(&format!("line {line}")), "{text}");
    assert!(
        text.contains(&format!("sample {index} was altered")),
        "{text}"
    );
}

#[test]
fn a_folder_of_the_previous_format_version_is_refused_by_name() {
    let dir = fresh("old-version");
    let output = montecarlo(&dir, &[]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let path = dir.join("study.json");
    let text = std::fs::read_to_string(&path).expect("study.json");
    std::fs::write(&path, text.replace("\"version\": 3", "\"version\": 2")).expect("write");
    let out = dir.display().to_string();
    let text = failure(&[
        "montecarlo",
        &example().display().to_string(),
        "--samples",
        "12",
        "--quiet",
        "--out",
        &out,
    ]);
    assert!(text.contains("study.json"), "{text}");
    assert!(text.contains("version 2"), "{text}");
    assert!(text.contains("an earlier karman"), "{text}");
}

#[test]
fn temporary_files_of_a_killed_run_are_removed_by_the_next_run() {
    let dir = fresh("leftovers");
    let output = montecarlo(&dir, &[]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let reference = fresh("leftovers-reference");
    let output = montecarlo(&reference, &[]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    // What a run killed while writing its files leaves, and a file of the user's.
    let left = [".summary.json.999999.0.tmp", ".samples.csv.999999.3.tmp"];
    for name in left {
        std::fs::write(dir.join(name), "partial").expect("write");
    }
    std::fs::write(dir.join("notes.tmp"), "mine").expect("write");
    let output = montecarlo(&dir, &[]);
    let text = stderr(&output);
    assert_eq!(output.status.code(), Some(0), "{text}");
    for name in left {
        assert!(!dir.join(name).exists(), "{name} removed");
        assert!(
            text.contains(&format!("removed {}", dir.join(name).display())),
            "{text}"
        );
    }
    std::fs::remove_file(dir.join("notes.tmp")).expect("the user's file is kept");
    assert_same_files(&reference, &dir);
}

#[cfg(unix)]
#[test]
fn deleting_study_lock_mid_run_lets_no_second_run_in() {
    let dir = fresh("lock-deleted");
    let out = dir.display().to_string();
    let mission = example().display().to_string();
    // A study long enough to be caught running (killed once the second run was refused).
    let args = [
        "montecarlo",
        mission.as_str(),
        "--samples",
        "1000000",
        "--threads",
        "1",
        "--quiet",
        "--out",
        out.as_str(),
    ];
    let mut first = std::process::Command::new(env!("CARGO_BIN_EXE_karman"))
        .args(args)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("the karman binary runs");
    let start = std::time::Instant::now();
    let samples = dir.join("samples.csv");
    while std::fs::read_to_string(&samples).map_or(0, |t| t.lines().count()) < 3 {
        if start.elapsed() > std::time::Duration::from_secs(60) {
            let _ = first.kill();
            panic!("the first run never wrote a row");
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    std::fs::remove_file(dir.join("study.lock")).expect("delete study.lock");
    let second = karman(&args);
    let text = stderr(&second);
    // The first run, its directory still locked, puts the lock file back at its next batch
    // and goes on.
    let start = std::time::Instant::now();
    while !dir.join("study.lock").is_file() && start.elapsed().as_secs() < 60 {
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let put_back = dir.join("study.lock").is_file();
    let still_running = first.try_wait().expect("the first run").is_none();
    let _ = first.kill();
    let _ = first.wait();
    assert_eq!(second.status.code(), Some(1), "{text}");
    assert!(
        text.contains("being written by another karman run"),
        "{text}"
    );
    assert!(still_running, "the first run went on");
    assert!(put_back, "the lock file put back");
    let _ = std::fs::remove_dir_all(&dir);
}
