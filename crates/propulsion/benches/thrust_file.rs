//! Loading a dense thrust curve: 10^6 `time, thrust` rows of CSV text parsed into
//! `ThrustData` and processed into a linear [`ThrustCurve`] (burn window, impulse), the
//! work `karman check` and `simulate` do for a static-fire file sampled at 1 MHz. The target
//! is under a second; the throughput is per row, so the time per element shows that the
//! work is linear in the number of rows.

use std::fmt::Write as _;
use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use karman_propulsion::{ThrustCurve, ThrustOptions, ThrustSource};

/// Rows of the benchmark's thrust file.
const ROWS: usize = 1_000_000;

/// A 3 s burn sampled at `rows` evenly spaced times: a smooth curve with a ripple.
fn csv(rows: usize) -> String {
    let mut text = String::with_capacity(rows * 28);
    text.push_str("time (s),thrust (N)\n");
    for k in 0..rows {
        let t = 3.0 * k as f64 / (rows - 1) as f64;
        let thrust = 1500.0 * (std::f64::consts::PI * t / 3.0).sin() + 10.0 + (40.0 * t).sin();
        let _ = writeln!(text, "{t:.9},{thrust:.6}");
    }
    text
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("thrust_file");
    group.sample_size(10);
    for rows in [ROWS / 10, ROWS] {
        let text = csv(rows);
        group.throughput(Throughput::Elements(rows as u64));
        group.bench_function(format!("csv_{rows}_rows"), |b| {
            b.iter(|| {
                let data = karman_propulsion::csv::parse(black_box(&text), "dense.csv")
                    .expect("valid rows");
                let source = ThrustSource::Data(Box::new(data));
                ThrustCurve::new(&source, &ThrustOptions::default()).expect("a curve")
            });
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
