//! Evaluation cost of the hot-path functions: a 200-point linear and spline [`Table1`] at
//! pseudo-random points (evenly spaced and clustered abscissae), the same with a [`Cursor`] along a sorted
//! sweep, and a [`Function`] that is the product of two tables.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use karman_math::{Cursor, Extrapolation, Function, Interpolation, Table1};

/// 1024 pseudo-random abscissae in [−1, 11] from a fixed linear congruential generator
/// (Knuth's MMIX constants), so every run measures the same queries.
fn queries() -> Vec<f64> {
    let mut state: u64 = 0x2545_f491_4f6c_dd1d;
    (0..1024)
        .map(|_| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            -1.0 + 12.0 * (state >> 11) as f64 / (1u64 << 53) as f64
        })
        .collect()
}

fn table(interp: Interpolation) -> Table1 {
    Table1::sample(
        |x| (x * 0.7).sin() + 0.1 * x,
        0.0,
        10.0,
        200,
        interp,
        Extrapolation::Constant,
    )
    .expect("finite samples")
}

fn bench(c: &mut Criterion) {
    let xs = queries();
    let linear = table(Interpolation::Linear);
    let spline = table(Interpolation::Spline);
    // Abscissae crowded towards 0 (x = 10·(k/199)³), as a drag curve dense at low Mach.
    let clustered_xs: Vec<f64> = (0..200)
        .map(|k| 10.0 * (f64::from(k) / 199.0).powi(3))
        .collect();
    let clustered_ys: Vec<f64> = clustered_xs.iter().map(|x| (x * 0.7).sin()).collect();
    let clustered = Table1::linear(clustered_xs, clustered_ys).expect("increasing samples");
    let product = Function::table(linear.clone()) * Function::table(spline.clone());
    let mut k = 0;
    let mut next = move || {
        k = (k + 1) & 1023;
        xs[k]
    };
    c.bench_function("linear_200_random", |b| {
        b.iter(|| linear.eval(black_box(next())))
    });
    c.bench_function("linear_200_clustered_random", |b| {
        b.iter(|| clustered.eval(black_box(next())))
    });
    c.bench_function("spline_200_random", |b| {
        b.iter(|| spline.eval(black_box(next())))
    });
    c.bench_function("function_product_of_two_tables", |b| {
        b.iter(|| product.eval(black_box(next())))
    });
    let mut cursor = Cursor::default();
    let mut t = 0.0;
    c.bench_function("linear_200_cursor_sweep", |b| {
        b.iter(|| {
            t = if t > 10.0 { 0.0 } else { t + 0.003 };
            linear.eval_with(black_box(t), &mut cursor)
        })
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
