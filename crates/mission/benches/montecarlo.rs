//! Monte Carlo throughput (issue 7): the Calisto validation mission (`fixtures/validation/
//! calisto`, or `$KARMAN_VALIDATION_DATA/calisto`) with a 10-parameter dispersion — rocket
//! mass, grain density, total impulse, burn time, both drag curves (factors), inclination,
//! heading and both parachutes' `cd_s` — parachute trigger noise kept, as `karman
//! montecarlo` flies it.
//!
//! - `calisto_montecarlo_sample`: one sample (inputs applied, models rebuilt, flown,
//!   summarised) on one thread, over a fixed set of 64 samples;
//! - `calisto_montecarlo_run_2_threads`: the whole runner (`karman_dispersion::run`: two
//!   worker threads, samples.csv written in index order, summary, ellipses, KML and plots)
//!   for 2,000 samples; criterion's throughput line gives flights per second.

mod common;

use common::calisto;
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use karman_mission::dispersion::{self, ProgressMode, RunOptions};
use karman_mission::montecarlo::{MonteCarlo, StudyOverrides};

/// The dispersion of the benchmark (10 varied inputs).
const DISPERSION: &str = r#"
[dispersion]
samples = 2000
seed = 42

[dispersion.vary]
"rocket.mass" = { std = 0.5 }
"motor.grain_density" = { std = 30 }
"motor.total_impulse" = { std = 50 }
"motor.burn_time" = { std = 0.05 }
"rocket.power_off_drag" = { factor = { normal = [1.0, 0.05] } }
"rocket.power_on_drag" = { factor = { normal = [1.0, 0.05] } }
"flight.inclination" = { std = 1 }
"flight.heading" = { std = 2 }
"rocket.parachutes.main.cd_s" = { std = 0.5 }
"rocket.parachutes.drogue.cd_s" = { std = 0.1 }
"#;

fn montecarlo(c: &mut Criterion) {
    let Some(path) = calisto() else {
        eprintln!("calisto mission not found: Monte Carlo bench skipped");
        return;
    };
    let text = std::fs::read_to_string(&path).expect("calisto mission");
    // RocketPy 1.13's form of the equations, the one timed before the `equations` key
    // existed (comparable figures across versions).
    let rocketpy = karman_mission::Override::new("flight.equations", "\"rocketpy_1_13\"")
        .expect("override parses");
    let mission =
        karman_mission::parse(&format!("{text}\n{DISPERSION}"), &path, &[rocketpy]).expect("loads");
    let mc = MonteCarlo::new(&mission, StudyOverrides::default()).expect("study");
    let study = mc.study();
    let batch: Vec<(u64, Vec<f64>)> = (0..64)
        .map(|i| (i, dispersion::sampling::draw(study.seed, i, &study.inputs)))
        .collect();
    let mut group = c.benchmark_group("calisto_montecarlo");
    group.throughput(Throughput::Elements(batch.len() as u64));
    group.bench_function("sample", |b| {
        b.iter(|| {
            for (index, values) in &batch {
                mc.fly(*index, values).expect("flies");
            }
        });
    });
    let out = std::env::temp_dir().join(format!("karman-bench-montecarlo-{}", std::process::id()));
    let options = RunOptions {
        threads: Some(2),
        shard: None,
        progress: ProgressMode::Hidden,
    };
    group.throughput(Throughput::Elements(study.samples));
    group.sample_size(10);
    group.bench_function("run_2_threads", |b| {
        b.iter(|| {
            // A fresh directory each time: an existing one would be resumed, not flown.
            let _ = std::fs::remove_dir_all(&out);
            dispersion::run(study, &out, &options, |index, values| mc.fly(index, values))
                .expect("runs")
        });
    });
    group.finish();
    let _ = std::fs::remove_dir_all(&out);
}

criterion_group!(benches, montecarlo);
criterion_main!(benches);
