//! The Calisto validation mission (`../shared/validation/calisto`, or
//! `$KARMAN_VALIDATION_DATA/calisto`) flown to the ground, parachute noise zeroed: the models
//! are built once, the timing covers `karman_dynamics::simulate` only. Prints the step and
//! right-hand-side counts once so that ns per evaluation can be read off the median.

use std::path::PathBuf;

use criterion::{Criterion, criterion_group, criterion_main};
use karman_mission::build::environment::build_environment;
use karman_mission::build::flight::flight_settings;
use karman_mission::build::motor::build_motor;
use karman_mission::build::rocket::build_rocket;

fn calisto() -> Option<PathBuf> {
    let dir = std::env::var_os("KARMAN_VALIDATION_DATA").map_or_else(
        || PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/validation"),
        PathBuf::from,
    );
    let path = dir.join("calisto/mission.toml");
    path.is_file().then_some(path)
}

fn flight(c: &mut Criterion) {
    let Some(path) = calisto() else {
        eprintln!("calisto mission not found: flight bench skipped");
        return;
    };
    let nominal = karman_mission::load(&path, &[]).expect("calisto loads");
    let quiet = nominal.parachute_noise_off().expect("noise overrides");
    let mission = karman_mission::load(&path, &quiet).expect("calisto loads");
    let environment = build_environment(&mission).expect("environment");
    let motor = build_motor(&mission).expect("motor");
    let rocket = build_rocket(&mission, &motor).expect("rocket");
    let settings = flight_settings(&mission, 0);
    let once = karman_mission::dynamics::simulate(&environment, &rocket, &settings).expect("flies");
    eprintln!(
        "calisto: {} steps ({} rejected), {} right-hand-side evaluations",
        once.stats.steps, once.stats.rejected_steps, once.stats.evaluations
    );
    c.bench_function("calisto_flight_to_ground", |b| {
        b.iter(|| {
            karman_mission::dynamics::simulate(&environment, &rocket, &settings).expect("flies")
        });
    });
}

criterion_group!(benches, flight);
criterion_main!(benches);
