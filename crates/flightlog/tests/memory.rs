//! The reader's memory: reading a large log holds the text, the normalised record and a
//! small working set per row, nothing proportional to the text beside them (no table of
//! parsed rows, no second copy of the samples).
//!
//! Measured with a counting global allocator (this test binary's only test, so nothing else
//! allocates meanwhile): the peak of live heap bytes during `parse`, above what was live
//! before it, must stay within the record's own size plus [`WORKING_BYTES_PER_ROW`].
//!
//! The counting allocator is the one `unsafe` of the file: a `GlobalAlloc` can only be
//! written as unsafe code, and it forwards every call unchanged to the system allocator.
#![allow(unsafe_code)]

#[path = "support/large_csv.rs"]
mod large_csv;

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use karman_flightlog::{ColumnMapping, ReadOptions, Sample, parse};

/// Live and peak heap bytes of the whole process.
struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

// SAFETY: every call forwards to the system allocator with the same layout; the counters
// only observe the sizes.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let live = LIVE.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            PEAK.fetch_max(live, Ordering::Relaxed);
        }
        p
    }
    unsafe fn dealloc(&self, p: *mut u8, layout: Layout) {
        unsafe { System.dealloc(p, layout) };
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
    }
    unsafe fn realloc(&self, p: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let q = unsafe { System.realloc(p, layout, new_size) };
        if !q.is_null() {
            if new_size >= layout.size() {
                let grow = new_size - layout.size();
                let live = LIVE.fetch_add(grow, Ordering::Relaxed) + grow;
                PEAK.fetch_max(live, Ordering::Relaxed);
            } else {
                LIVE.fetch_sub(layout.size() - new_size, Ordering::Relaxed);
            }
        }
        q
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// What reading may hold per row beside the record, bytes: the time and height columns and
/// the smoothing derivative (8 bytes each) and each row's line number.
const WORKING_BYTES_PER_ROW: usize = 40;

#[test]
fn a_large_log_reads_in_memory_bounded_by_its_record() {
    let text = large_csv::csv(4_000_000);
    let rows = text.lines().count() - 1;
    let options = ReadOptions {
        mapping: Some(ColumnMapping::parse(large_csv::MAPPING).expect("mapping")),
        ..ReadOptions::default()
    };
    let before = LIVE.load(Ordering::Relaxed);
    PEAK.store(before, Ordering::Relaxed);
    let log = parse(text.as_bytes(), "large.csv", &options).expect("reads");
    let peak = PEAK.load(Ordering::Relaxed) - before;
    let record = log.samples.capacity() * size_of::<Sample>();
    let bound = record + WORKING_BYTES_PER_ROW * rows + 1_000_000;
    eprintln!(
        "{rows} rows, text {} B: peak {peak} B above the text ({:.1} B/row), record {record} B, \
         bound {bound} B",
        text.len(),
        peak as f64 / rows as f64
    );
    assert_eq!(log.samples.len(), rows, "every row is a sample");
    assert!(
        peak <= bound,
        "reading peaked at {peak} B, above the record ({record} B) and \
         {WORKING_BYTES_PER_ROW} B for each of {rows} rows"
    );
}
