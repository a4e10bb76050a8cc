//! Reading a large log: a generic CSV of `time, altitude, acceleration` rows (1 kHz, the
//! rate of a high-rate flight computer) of 10 MB and 100 MB read and normalised by
//! [`karman_flightlog::parse`] through a column mapping. Reading is linear in the file's
//! size: the throughput is per byte, so the time per byte of both sizes shows it. The target
//! is a 100 MB log in under 10 s on one core. Its memory is tested, not timed: `tests/memory.rs`
//! counts the bytes reading allocates.

#[path = "../tests/support/large_csv.rs"]
mod large_csv;

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use karman_flightlog::{ColumnMapping, ReadOptions, parse};

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("flightlog");
    group.sample_size(10);
    let mapping = ColumnMapping::parse(large_csv::MAPPING).expect("mapping");
    let options = ReadOptions {
        mapping: Some(mapping),
        ..ReadOptions::default()
    };
    for megabytes in [10, 100] {
        let text = large_csv::csv(megabytes * 1_000_000);
        group.throughput(Throughput::Bytes(text.len() as u64));
        group.bench_function(format!("generic_csv_{megabytes}_MB"), |b| {
            b.iter(|| parse(black_box(text.as_bytes()), "large.csv", &options).expect("reads"));
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
