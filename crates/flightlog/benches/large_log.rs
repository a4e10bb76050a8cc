//! Reading a large log: a generic CSV of `time, altitude, acceleration` rows (1 kHz, the
//! rate of a high-rate flight computer) of 10 MB and 100 MB read and normalised by
//! [`karman_flightlog::parse`] through a column mapping. Reading is linear in the file's
//! size: the throughput is per byte, so the time per byte of both sizes shows it. The target
//! is a 100 MB log in under 10 s on one core.

use std::fmt::Write as _;
use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use karman_flightlog::{ColumnMapping, ReadOptions, parse};

/// A flight sampled at 1 kHz until the text reaches `bytes`: 2 s on the pad, a 3 s boost at
/// 60 m/s², a coast to apogee, then a 20 m/s descent (repeated if the text needs more).
fn csv(bytes: usize) -> String {
    let mut text = String::with_capacity(bytes + 64);
    text.push_str("time_ms,altitude_ft,accel_g\n");
    let mut k: u64 = 0;
    while text.len() < bytes {
        let t = k as f64 * 1e-3;
        let phase = t % 200.0 - 2.0;
        let (h, a) = if phase < 0.0 {
            (0.0, 0.0)
        } else if phase < 3.0 {
            (30.0 * phase * phase, 6.1)
        } else if phase < 21.3 {
            let c = phase - 3.0;
            (270.0 + 180.0 * c - 4.903 * c * c, -1.0)
        } else {
            ((1920.0 - 20.0 * (phase - 21.3)).max(0.0), 0.0)
        };
        let _ = writeln!(text, "{},{:.2},{a:.3}", k, h / 0.3048);
        k += 1;
    }
    text
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("flightlog");
    group.sample_size(10);
    let mapping =
        ColumnMapping::parse("time=time_ms:ms,altitude=altitude_ft:ft,acceleration=accel_g:g")
            .expect("mapping");
    let options = ReadOptions {
        mapping: Some(mapping),
        ..ReadOptions::default()
    };
    for megabytes in [10, 100] {
        let text = csv(megabytes * 1_000_000);
        group.throughput(Throughput::Bytes(text.len() as u64));
        group.bench_function(format!("generic_csv_{megabytes}_MB"), |b| {
            b.iter(|| parse(black_box(text.as_bytes()), "large.csv", &options).expect("reads"));
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
