//! The Calisto validation mission (`fixtures/validation/calisto`, or
//! `$KARMAN_VALIDATION_DATA/calisto`) flown to the ground, once with the parachute noise zeroed
//! (`calisto_flight/to_ground`) and once with the mission's trigger noise kept and a fixed
//! noise seed (`calisto_flight/noisy`, the flight a Monte Carlo run repeats); the noise-free
//! flight in RocketPy's 3-DOF point-mass mode (`calisto_flight/to_ground_3dof`,
//! `simulation_mode = "3 DOF"`, timed against `to_ground`); and the liquid
//! (`hedy_flight/to_ground`) and hybrid (`halcyon_flight/to_ground`) validation flights, noise
//! zeroed, whose ns per evaluation set against Calisto's measure what the tank-derived mass
//! tables cost (issue 24: at most 1.5 times a solid flight); and Calisto with air brakes driven
//! by a closed-loop controller at 100 Hz (`calisto_flight/air_brakes_100hz`, the mission
//! `fixtures/airbrakes/calisto_apogee.toml`: a proportional controller on the predicted
//! apogee, flown to the ground), set against `calisto_flight/to_ground` for what a controller
//! costs (issue 22: at most twice the flight without it). The models are built once (the
//! script compiled once), the timing covers the flight only: `karman_dynamics::simulate`, and
//! for the controlled flight the controller made from the compiled script and flown with it.
//! The throughput is declared in right-hand-side evaluations, so that `cargo xtask bench`
//! prints the ns per evaluation beside the median; the step counts are printed once.

use std::path::Path;

mod common;

use common::{calisto, validation_mission};
use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion, Throughput, criterion_group, criterion_main};
use karman_mission::Override;
use karman_mission::assemble::environment::build_environment;
use karman_mission::assemble::motor::build_motor;
use karman_mission::assemble::preflight::flight_settings;
use karman_mission::assemble::rocket::build_rocket;
use karman_mission::assemble::scripts::{ControllerEnvironment, compile_controller};
use std::sync::Arc;

/// Noise seed of the noisy flight (any fixed value: the bench must time the same flight).
const NOISE_SEED: u64 = 20_240_611;

/// Builds the mission with `overrides`, flies it once to print its counters, then times it.
fn bench_one(
    group: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    path: &Path,
    overrides: &[Override],
    seed: u64,
) {
    let mission = karman_mission::load(path, overrides).expect("mission loads");
    let environment = build_environment(&mission).expect("environment");
    let motor = build_motor(&mission).expect("motor");
    let rocket = build_rocket(&mission, &motor).expect("rocket");
    let mut settings = flight_settings(&mission, seed);
    // RocketPy 1.13's form of the equations, the one timed before the `equations` key
    // existed (comparable figures across versions).
    settings.equations = karman_mission::dynamics::EquationsForm::RocketPy113;
    let once = karman_mission::dynamics::simulate(&environment, &rocket, &settings).expect("flies");
    eprintln!(
        "{name}: {} steps ({} rejected), {} right-hand-side evaluations, parachutes {:?}",
        once.stats.steps,
        once.stats.rejected_steps,
        once.stats.evaluations,
        once.parachute_events
            .iter()
            .map(|e| (e.name.as_str(), e.trigger_time))
            .collect::<Vec<_>>()
    );
    group.throughput(Throughput::Elements(once.stats.evaluations as u64));
    group.bench_function(name, |b| {
        b.iter(|| {
            karman_mission::dynamics::simulate(&environment, &rocket, &settings).expect("flies")
        });
    });
}

/// The Calisto flight with a closed-loop air-brake controller at 100 Hz
/// (`fixtures/airbrakes/calisto_apogee.toml`), flown once to print its counters, then timed.
fn bench_controlled(group: &mut BenchmarkGroup<'_, WallTime>) {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/airbrakes/calisto_apogee.toml");
    let mission = karman_mission::load(&path, &[]).expect("mission loads");
    let environment = Arc::new(build_environment(&mission).expect("environment"));
    let motor = build_motor(&mission).expect("motor");
    let rocket = build_rocket(&mission, &motor).expect("rocket");
    let mut settings = flight_settings(&mission, 0);
    settings.equations = karman_mission::dynamics::EquationsForm::RocketPy113;
    let script = compile_controller(&mission).expect("script compiles");
    let fly = || {
        karman_mission::assemble::flight::fly(
            &mission,
            &*environment,
            &rocket,
            &settings,
            script.as_ref(),
            || {
                Arc::new(ControllerEnvironment::new(
                    Arc::clone(&environment),
                    1.0,
                    0.0,
                ))
            },
        )
        .expect("flies")
    };
    let (once, record) = fly();
    eprintln!(
        "air_brakes_100hz: {} steps ({} rejected), {} right-hand-side evaluations, {} controller \
         calls, apogee at {:.3} s",
        once.stats.steps,
        once.stats.rejected_steps,
        once.stats.evaluations,
        record.map_or(0, |r| r.levels.len()),
        once.points
            .iter()
            .max_by(|a, b| a.state[2].total_cmp(&b.state[2]))
            .map_or(f64::NAN, |p| p.t),
    );
    group.throughput(Throughput::Elements(once.stats.evaluations as u64));
    group.bench_function("air_brakes_100hz", |b| b.iter(fly));
}

fn flight(c: &mut Criterion) {
    let Some(path) = calisto() else {
        eprintln!("calisto mission not found: flight bench skipped");
        return;
    };
    let nominal = karman_mission::load(&path, &[]).expect("calisto loads");
    let quiet = nominal.parachute_noise_off().expect("noise overrides");
    let mut group = c.benchmark_group("calisto_flight");
    bench_one(&mut group, "to_ground", &path, &quiet, 0);
    bench_one(&mut group, "noisy", &path, &[], NOISE_SEED);
    let mut point_mass = quiet.clone();
    point_mass.push(Override::new("flight.simulation_mode", "\"3 DOF\"").expect("override"));
    bench_one(&mut group, "to_ground_3dof", &path, &point_mass, 0);
    bench_controlled(&mut group);
    group.finish();
    for flight in ["hedy", "halcyon"] {
        let Some(path) = validation_mission(flight) else {
            eprintln!("{flight} mission not found: its flight bench skipped");
            continue;
        };
        let nominal = karman_mission::load(&path, &[]).expect("mission loads");
        let quiet = nominal.parachute_noise_off().expect("noise overrides");
        let mut group = c.benchmark_group(format!("{flight}_flight"));
        bench_one(&mut group, "to_ground", &path, &quiet, 0);
        group.finish();
    }
}

criterion_group!(benches, flight);
criterion_main!(benches);
