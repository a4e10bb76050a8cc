//! One full environment evaluation at a height (pressure, density, temperature, speed of
//! sound, viscosity, wind, gravity) — what the equations of motion ask per step. Target
//! ≤ 50 ns. `sample` evaluates the same quantities in one call. Two environments: the ISA (pointwise density) and a tabulated 37-level profile
//! (node-wise tables, the ERA5 case).

use criterion::{Criterion, criterion_group, criterion_main};
use karman_atmos::{Atmosphere, Curve, Environment, EnvironmentConfig, Profiles};
use karman_math::PhysicalConstants;
use std::hint::black_box;

fn evaluate(env: &Environment, z: f64) -> f64 {
    let [u, v] = env.wind(z);
    env.pressure(z)
        + env.density(z)
        + env.temperature(z)
        + env.speed_of_sound(z)
        + env.dynamic_viscosity(z)
        + u
        + v
        + env.gravity(z)
}

fn bench(c: &mut Criterion) {
    let constants = PhysicalConstants::SI;
    let isa = EnvironmentConfig {
        earth_model: None,
        latitude_deg: 32.990254,
        elevation: 1400.0,
        ..EnvironmentConfig::default()
    };
    let isa = Environment::new(&isa, &constants).expect("ISA environment");
    let heights: Vec<f64> = (0..37).map(|k| 100.0 + 900.0 * f64::from(k)).collect();
    let col = |f: &dyn Fn(f64) -> f64| heights.iter().map(|&h| [h, f(h)]).collect::<Vec<_>>();
    let profiles = Profiles {
        source_name: "bench".into(),
        pressure: Some(Curve::Points(col(&|h| 101_325.0 * (-h / 8000.0).exp()))),
        temperature: Some(Curve::Points(col(&|h| 288.0 - 0.0065 * h.min(11_000.0)))),
        wind_u: Curve::Points(col(&|h| 5.0 + h / 1000.0)),
        wind_v: Curve::Points(col(&|h| -2.0 - h / 2000.0)),
        barometric_points: None,
    };
    let table = EnvironmentConfig {
        earth_model: None,
        atmosphere: Atmosphere::Profiles(profiles),
        ..EnvironmentConfig::default()
    };
    let table = Environment::new(&table, &constants).expect("tabulated environment");
    let mut z = 1400.0;
    c.bench_function("environment_full_evaluation_isa", |b| {
        b.iter(|| {
            z = if z > 4000.0 { 1400.0 } else { z + 13.7 };
            black_box(evaluate(black_box(&isa), black_box(z)))
        });
    });
    c.bench_function("environment_sample_isa", |b| {
        b.iter(|| {
            z = if z > 4000.0 { 1400.0 } else { z + 13.7 };
            black_box(black_box(&isa).sample(black_box(z)))
        });
    });
    c.bench_function("environment_full_evaluation_profile", |b| {
        b.iter(|| {
            z = if z > 4000.0 { 1400.0 } else { z + 13.7 };
            black_box(evaluate(black_box(&table), black_box(z)))
        });
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
