//! A cheap synthetic experiment standing in for a flight: a few varied inputs of every kind
//! and outputs shaped like a flight summary, with some failures and missing values.

use karman_dispersion::{
    Distribution, Outcome, Points, ProgressMode, RunOptions, Shard, Site, Study, Target, Variation,
    VariedInput,
};
use std::path::Path;

/// The synthetic study: `samples` samples with seed 2024.
pub fn study(samples: u64) -> Study {
    let inputs = vec![
        VariedInput::new("rocket.mass", Target::Number(14.426), Variation::Std(0.5)),
        VariedInput::new(
            "rocket.power_off_drag",
            Target::Curve,
            Variation::Factor(Distribution::Normal {
                mean: 1.0,
                std: 0.05,
            }),
        ),
        VariedInput::new(
            "flight.heading",
            Target::Number(0.0),
            Variation::Value(Distribution::Uniform {
                low: -10.0,
                high: 10.0,
            }),
        ),
        VariedInput::new(
            "flight.inclination",
            Target::Number(85.0),
            Variation::Value(Distribution::Triangular {
                low: 83.0,
                mode: 85.0,
                high: 86.0,
            }),
        ),
        VariedInput::new(
            "environment.wind_factor",
            Target::Number(1.0),
            Variation::Value(Distribution::Lognormal {
                mu: 0.0,
                sigma: 0.2,
            }),
        ),
        VariedInput::new(
            "environment.atmosphere.member",
            Target::Integer(0),
            Variation::Value(Distribution::Choice(vec![0.0, 1.0, 2.0, 3.0])),
        ),
        VariedInput::new(
            "motor.nozzle_position",
            Target::Number(0.0),
            Variation::Offset(Distribution::Normal {
                mean: 0.0,
                std: 0.01,
            }),
        ),
    ];
    let outputs = [
        "apogee_agl_m",
        "apogee_x_m",
        "apogee_y_m",
        "impact_x_m",
        "impact_y_m",
        "impact_velocity_mps",
    ]
    .map(str::to_owned)
    .to_vec();
    let mut study = Study::new(2024, samples, inputs, outputs);
    study.points = Points {
        apogee: Some(["apogee_x_m".to_owned(), "apogee_y_m".to_owned()]),
        landing: Some(["impact_x_m".to_owned(), "impact_y_m".to_owned()]),
        histogram: Some("apogee_agl_m".to_owned()),
        ..Points::default()
    };
    study.site = Some(Site {
        latitude_deg: 32.990254,
        longitude_deg: -106.974998,
        earth_radius: 6.3781e6,
    });
    study.context = "synthetic test experiment".to_owned();
    study
}

/// The synthetic "flight": deterministic in its inputs; samples with a large drag factor
/// fail, a few have no impact, and samples with index % 29 == 3 end early (`max_time`).
pub fn fly(index: u64, values: &[f64]) -> Result<Outcome, String> {
    let [
        mass,
        drag,
        heading_deg,
        inclination_deg,
        wind,
        member,
        nozzle,
    ] = values
    else {
        return Err(format!("expected 7 values, got {}", values.len()));
    };
    if *drag > 1.1 {
        return Err(format!(
            "sample {index}: drag factor {drag} makes the flight \"unstable\", stop"
        ));
    }
    let apogee = 3300.0 * (14.426 / mass).powf(0.7) / drag + 10.0 * member + 100.0 * nozzle;
    let drift = 50.0 * wind + (90.0 - inclination_deg) * 40.0;
    let (sin_h, cos_h) = heading_deg.to_radians().sin_cos();
    let apogee_x = drift * sin_h;
    let apogee_y = drift * cos_h;
    if index % 29 == 3 {
        let message = format!("sample {index} reached max_time before landing");
        return Ok(Outcome::ended(
            vec![
                Some(apogee),
                Some(apogee_x),
                Some(apogee_y),
                None,
                None,
                None,
            ],
            "max_time",
            message,
        ));
    }
    let impact = if index % 17 == 5 {
        None
    } else {
        Some([
            apogee_x + 300.0 * wind,
            apogee_y - 150.0 * wind + 0.01 * apogee,
        ])
    };
    Ok(Outcome::new(vec![
        Some(apogee),
        Some(apogee_x),
        Some(apogee_y),
        impact.map(|p| p[0]),
        impact.map(|p| p[1]),
        impact.map(|_| 5.0 + wind),
    ]))
}

/// Options: `threads` workers, `shard`, no progress output.
pub fn options(threads: usize, shard: Shard) -> RunOptions {
    RunOptions {
        threads: Some(threads),
        shard: Some(shard),
        progress: ProgressMode::Hidden,
    }
}

/// The files of an output directory, by name, sorted.
pub fn files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .expect("output directory")
        .map(|entry| {
            let entry = entry.expect("directory entry");
            let name = entry.file_name().to_string_lossy().into_owned();
            (name, std::fs::read(entry.path()).expect("readable file"))
        })
        .collect();
    files.sort();
    files
}

/// Asserts two output directories hold the same files with the same bytes.
pub fn assert_same_outputs(a: &Path, b: &Path) {
    let (fa, fb) = (files(a), files(b));
    let names = |f: &[(String, Vec<u8>)]| f.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>();
    assert_eq!(names(&fa), names(&fb));
    for ((name, x), (_, y)) in fa.iter().zip(&fb) {
        assert!(
            x == y,
            "{name} differs between {} and {}",
            a.display(),
            b.display()
        );
    }
}
