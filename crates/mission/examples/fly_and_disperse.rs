//! Loads a mission file, flies it once, and runs a small Monte Carlo study of it in memory:
//! what a program built on the library does where the CLI runs `karman simulate` and
//! `karman montecarlo`.
//!
//! The mission is the project's example (`fixtures/example.toml`: a 1.3 m rocket on a
//! K1960); its `[dispersion]` varies the rocket's mass, the motor's impulse, the drag, the
//! main parachute and the launch angles. Run with
//! `cargo run --release -p karman-mission --example fly_and_disperse [MISSION] [SAMPLES]`.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use karman_mission::assemble::flight::PreparedFlight;
use karman_mission::dispersion::{MemoryRun, ProgressMode, RunOptions, run_in_memory};
use karman_mission::load;
use karman_mission::montecarlo::{MonteCarlo, StudyOverrides};

/// The example mission of the repository.
pub fn example_mission() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/example.toml")
}

/// What the example found: the nominal flight's apogee above ground (m) and its time (s),
/// and the study run in memory.
pub struct Findings {
    /// Apogee of the nominal flight above the ground, m.
    pub apogee_agl_m: f64,
    /// Its time from ignition, s.
    pub apogee_time_s: f64,
    /// The study's rows and report (its summary: the statistics of every output).
    pub study: MemoryRun,
}

/// Flies `mission` once (seed 0) and a study of `samples` samples of its `[dispersion]`
/// on `threads` worker threads.
///
/// # Errors
/// The mission's errors (the file, a key, a model that cannot be built, a study that is not
/// valid) and the runner's.
pub fn run(
    mission: &Path,
    samples: u64,
    threads: usize,
) -> Result<Findings, Box<dyn std::error::Error>> {
    // `load` reads and validates the file (and applies `--set`-style overrides, none here).
    let mission = load(mission, &[])?;
    // The models are built and checked once; a prepared flight flies any number of seeds.
    let prepared = PreparedFlight::new(&mission)?;
    let summary = prepared.fly(&mission, 0)?.summary();
    // The study: the mission's `[dispersion]`, its sample count replaced.
    let study = MonteCarlo::new(
        &mission,
        StudyOverrides {
            samples: Some(samples),
            seed: None,
        },
    )?;
    let options = RunOptions {
        threads: Some(threads),
        shard: None,
        progress: ProgressMode::Hidden,
    };
    // Nothing stops this study early; a program would set the flag from a signal handler.
    let stop = AtomicBool::new(false);
    let study = run_in_memory(study.study(), &options, &stop, |index, values| {
        study.fly(index, values)
    })?;
    Ok(Findings {
        apogee_agl_m: summary.apogee_agl_m.unwrap_or(f64::NAN),
        apogee_time_s: summary.apogee_time_s.unwrap_or(f64::NAN),
        study,
    })
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let mission = args.next().map_or_else(example_mission, PathBuf::from);
    let samples = args.next().map_or(Ok(100), |s| s.parse())?;
    let findings = run(&mission, samples, 2)?;
    println!(
        "nominal apogee {:.1} m AGL at {:.2} s",
        findings.apogee_agl_m, findings.apogee_time_s
    );
    let summary = findings.study.report.summary.as_ref();
    for column in summary.map(|s| s.outputs.as_slice()).unwrap_or_default() {
        if let Some(s) = &column.statistics {
            println!(
                "{:<24} mean {:>10.3}  std {:>9.3}  95 % in [{:.3}, {:.3}]",
                column.name, s.mean, s.std, s.p2_5, s.p97_5
            );
        }
    }
    Ok(())
}
