//! Memory stays bounded: while one slow sample holds up the writing, the other workers start
//! at most `WINDOW_PER_THREAD × threads` samples past it.

use crate::common::{fly, options, study};
use karman_dispersion::{Outcome, Shard, WINDOW_PER_THREAD, run};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::Duration;

#[test]
fn workers_wait_for_a_slow_sample() {
    let first_done = AtomicBool::new(false);
    let furthest = AtomicU64::new(0);
    let slow_first = |index: u64, values: &[f64]| -> Result<Outcome, String> {
        if index == 0 {
            std::thread::sleep(Duration::from_millis(400));
            first_done.store(true, Ordering::SeqCst);
        } else if !first_done.load(Ordering::SeqCst) {
            furthest.fetch_max(index, Ordering::SeqCst);
        }
        fly(index, values)
    };
    let threads = 2;
    let tmp = tempfile::tempdir().expect("temporary directory");
    run(
        &study(5000),
        tmp.path(),
        &options(threads, Shard::WHOLE),
        slow_first,
    )
    .expect("run");
    let furthest = furthest.load(Ordering::SeqCst);
    let window = WINDOW_PER_THREAD * threads as u64;
    // Positions 1..window may start while sample 0 is in flight, and no further.
    assert!(
        furthest < window,
        "a worker started sample {furthest} (window {window})"
    );
    assert!(
        furthest >= window / 2,
        "the other worker did not run ahead ({furthest})"
    );
}
