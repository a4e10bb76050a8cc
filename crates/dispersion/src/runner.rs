//! The run: every missing sample of a shard flown in parallel, rows written in index order.
//!
//! Workers of a local `rayon` pool claim runs of `CLAIM` consecutive sample positions from a
//! shared counter, draw the inputs ([`crate::sampling`]), fly the samples and send their
//! finished rows together to the calling thread, which keeps out-of-order rows in a
//! `BTreeMap` and appends every row whose predecessors are written, flushing after each
//! batch. (One message per sample cost a thread wake-up, a write and a condition-variable
//! signal per flight, about a tenth of a Monte Carlo run's time; a killed run loses at most
//! the unflushed claims, which the resume flies again.) A worker does not start a claim
//! reaching more than `WINDOW_PER_THREAD × threads` ahead of the last written row, so memory
//! stays bounded whatever the number of samples. Because each sample depends only on (seed,
//! index), `samples.csv` is byte-identical for any thread count and any interruption.

use crate::csv;
use crate::error::DispersionError;
use crate::files::{self, SAMPLES_FILE, STUDY_FILE};
use crate::progress::{Progress, ProgressMode};
use crate::sampling::draw;
use crate::study::{Record, Shard, Study};
use crate::summary::{Summary, summarize};
use std::collections::BTreeMap;
use std::fs::OpenOptions;
use std::io::{BufWriter, Write as _};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc;
use std::sync::{Condvar, Mutex, PoisonError};
use std::time::{Duration, Instant};

/// Samples a worker may start ahead of the first sample not yet written, per thread: the
/// bound on rows held in memory.
pub const WINDOW_PER_THREAD: u64 = 64;

/// Consecutive positions a worker claims, flies and sends at once.
const CLAIM: u64 = 8;

/// How often a worker waiting for the writer looks at the caller's stop flag.
const STOP_POLL: Duration = Duration::from_millis(50);

/// What one flight measured: one value per output of the study, `None` for a quantity that
/// did not occur (no impact when the flight stops at apogee).
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    values: Vec<Option<f64>>,
}

impl Outcome {
    /// The outputs' values, in the order of [`Study::outputs`].
    pub fn new(values: Vec<Option<f64>>) -> Self {
        Outcome { values }
    }

    /// The values.
    pub fn values(&self) -> &[Option<f64>] {
        &self.values
    }
}

/// Most worker threads per core a study may ask for: flights are CPU-bound, so threads beyond
/// the cores only share them (and each holds a window of rows in memory).
pub const MAX_THREADS_PER_CORE: usize = 4;

/// How to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RunOptions {
    /// Worker threads; `None` (or 0): one per core; at most [`MAX_THREADS_PER_CORE`] per core.
    pub threads: Option<usize>,
    /// The part of the study to fly ([`Shard::WHOLE`] by default).
    pub shard: Option<Shard>,
    /// Progress display.
    pub progress: ProgressMode,
}

/// What a run did.
#[derive(Debug, Clone, PartialEq)]
pub struct RunReport {
    /// The shard flown.
    pub shard: Shard,
    /// Samples in the shard.
    pub shard_samples: u64,
    /// Rows kept from an earlier, interrupted run.
    pub resumed: u64,
    /// Samples flown now.
    pub flown: u64,
    /// Failed samples in the shard (kept and new).
    pub failed: u64,
    /// Worker threads used.
    pub threads: usize,
    /// Wall time of the flights.
    pub elapsed: Duration,
    /// The summary, written for a whole study (a shard's is made by [`crate::merge`]).
    pub summary: Option<Summary>,
}

impl RunReport {
    /// Samples flown per second of wall time.
    pub fn rate(&self) -> f64 {
        self.flown as f64 / self.elapsed.as_secs_f64().max(1e-9)
    }
}

/// Runs (or resumes) `study` in `dir`: creates `study.json` and `samples.csv`, or checks
/// that they hold this very study and shard and keeps their complete rows; flies the
/// missing samples with `fly(index, sampled values)`; for a whole study writes
/// `summary.json`, `dispersion.kml` and the plots. A sample whose `fly` returns `Err` (or
/// panics) is recorded as failed with its inputs and message, and the run goes on.
pub fn run<F>(
    study: &Study,
    dir: &Path,
    options: &RunOptions,
    fly: F,
) -> Result<RunReport, DispersionError>
where
    F: Fn(u64, &[f64]) -> Result<Outcome, String> + Sync,
{
    run_until(study, dir, options, &AtomicBool::new(false), fly)
}

/// [`run`] that stops early once `stop` is set (by another thread, e.g. on Ctrl-C): no
/// sample starts after that, the samples in flight finish and every row before the first
/// missing one is written, so `samples.csv` stays a valid prefix that a later run resumes;
/// the result is then [`DispersionError::Interrupted`].
pub fn run_until<F>(
    study: &Study,
    dir: &Path,
    options: &RunOptions,
    stop: &AtomicBool,
    fly: F,
) -> Result<RunReport, DispersionError>
where
    F: Fn(u64, &[f64]) -> Result<Outcome, String> + Sync,
{
    study.validate()?;
    let requested = options.threads.unwrap_or(0);
    let cores = std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get);
    if requested > MAX_THREADS_PER_CORE * cores {
        return Err(DispersionError::ThreadPool {
            threads: requested,
            message: format!(
                "at most {MAX_THREADS_PER_CORE} per core ({} on this machine's {cores} cores): \
                 more only share the same cores",
                MAX_THREADS_PER_CORE * cores
            ),
        });
    }
    let shard = options.shard.unwrap_or(Shard::WHOLE);
    let record = Record::new(study, shard);
    std::fs::create_dir_all(dir).map_err(DispersionError::io(dir))?;
    let study_path = dir.join(STUDY_FILE);
    let samples_path = dir.join(SAMPLES_FILE);
    match Record::read(&study_path)? {
        Some(existing) => {
            let fields = record.differences(&existing);
            if !fields.is_empty() {
                return Err(DispersionError::StudyMismatch {
                    dir: dir.to_owned(),
                    fields,
                });
            }
        }
        None => {
            let has_samples = std::fs::metadata(&samples_path).is_ok_and(|m| m.len() > 0);
            if has_samples {
                return Err(DispersionError::MissingStudy {
                    dir: dir.to_owned(),
                });
            }
            files::write_atomic(&study_path, record.to_json().as_bytes())?;
        }
    }

    let scan = files::scan(&samples_path, &record)?;
    let file = OpenOptions::new()
        .create(true)
        .write(true)
        .truncate(false)
        .open(&samples_path)
        .map_err(DispersionError::io(&samples_path))?;
    // Drop a partial last line (an interrupted write), then append.
    file.set_len(scan.valid_len)
        .map_err(DispersionError::io(&samples_path))?;
    let file = OpenOptions::new()
        .append(true)
        .open(&samples_path)
        .map_err(DispersionError::io(&samples_path))?;
    let mut out = BufWriter::with_capacity(1 << 16, file);
    if !scan.has_header {
        out.write_all(csv::header(&study.columns()).as_bytes())
            .and_then(|()| out.flush())
            .map_err(DispersionError::io(&samples_path))?;
    }

    let threads = options.threads.unwrap_or(0);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .thread_name(|i| format!("karman-mc-{i}"))
        .build()
        .map_err(|e| DispersionError::ThreadPool {
            threads,
            message: e.to_string(),
        })?;
    let threads = pool.current_num_threads();
    let total = shard.len(study.samples);
    let mut progress = Progress::new(options.progress, total, scan.rows);
    let started = Instant::now();
    let engine = Engine {
        study,
        shard,
        total,
        window: WINDOW_PER_THREAD * threads as u64,
        next: AtomicU64::new(scan.rows),
        abort: AtomicBool::new(false),
        stop,
        written: Mutex::new(scan.rows),
        advanced: Condvar::new(),
    };
    let (sender, receiver) = mpsc::channel::<Vec<Finished>>();
    let mut written = Ok(0);
    pool.in_place_scope(|scope| {
        for _ in 0..threads {
            let sender = sender.clone();
            let engine = &engine;
            let fly = &fly;
            scope.spawn(move |_| engine.work(fly, &sender));
        }
        drop(sender);
        written = engine.write(receiver, &mut out, &mut progress);
        if written.is_err() {
            engine.stop();
        }
    });
    progress.finish();
    let new_failures = written.map_err(DispersionError::io(&samples_path))?;
    let elapsed = started.elapsed();
    drop(out);
    let rows = *engine
        .written
        .lock()
        .unwrap_or_else(PoisonError::into_inner);
    if rows < total {
        return Err(DispersionError::Interrupted {
            dir: dir.to_owned(),
            written: rows,
            total,
        });
    }

    let summary = if shard == Shard::WHOLE {
        Some(summarize(dir)?)
    } else {
        None
    };
    Ok(RunReport {
        shard,
        shard_samples: total,
        resumed: scan.rows,
        flown: total - scan.rows,
        failed: scan.failed + new_failures,
        threads,
        elapsed,
        summary,
    })
}

/// A flown sample's row.
struct Finished {
    position: u64,
    line: String,
    failed: bool,
}

/// State shared by the workers and the writer.
struct Engine<'a> {
    study: &'a Study,
    shard: Shard,
    total: u64,
    window: u64,
    next: AtomicU64,
    abort: AtomicBool,
    /// Set by the caller to stop the run early.
    stop: &'a AtomicBool,
    /// Positions below this are written.
    written: Mutex<u64>,
    advanced: Condvar,
}

impl Engine<'_> {
    /// A worker: claims runs of positions until none is left or the run stops.
    fn work<F>(&self, fly: &F, sender: &mpsc::Sender<Vec<Finished>>)
    where
        F: Fn(u64, &[f64]) -> Result<Outcome, String> + Sync,
    {
        loop {
            let first = self.next.fetch_add(CLAIM, Ordering::Relaxed);
            if first >= self.total || self.stopped() {
                return;
            }
            let end = (first + CLAIM).min(self.total);
            {
                let mut written = self.written.lock().unwrap_or_else(PoisonError::into_inner);
                // `stop` is set without a notification: wake up now and then to see it.
                while end > *written + self.window && !self.stopped() {
                    written = self
                        .advanced
                        .wait_timeout(written, STOP_POLL)
                        .unwrap_or_else(PoisonError::into_inner)
                        .0;
                }
            }
            let mut rows = Vec::with_capacity((end - first) as usize);
            for position in first..end {
                if self.stopped() {
                    // Send the rows already flown: they may extend the written prefix.
                    let _ = sender.send(rows);
                    return;
                }
                rows.push(self.fly_one(fly, position));
            }
            if sender.send(rows).is_err() {
                return;
            }
        }
    }

    /// Flies the sample at `position` and formats its row.
    fn fly_one<F>(&self, fly: &F, position: u64) -> Finished
    where
        F: Fn(u64, &[f64]) -> Result<Outcome, String> + Sync,
    {
        let index = self.shard.index(position);
        let inputs = draw(self.study.seed, index, &self.study.inputs);
        let outputs = self.study.outputs.len();
        let result = match catch_unwind(AssertUnwindSafe(|| fly(index, &inputs))) {
            Ok(Ok(outcome)) if outcome.values.len() == outputs => Ok(outcome.values),
            Ok(Ok(outcome)) => Err(format!(
                "the flight returned {} values for {outputs} outputs",
                outcome.values.len()
            )),
            Ok(Err(message)) => Err(message),
            Err(payload) => Err(format!("panicked: {}", panic_message(payload.as_ref()))),
        };
        let line = match &result {
            Ok(values) => csv::row(index, &inputs, Ok(values), outputs),
            Err(message) => csv::row(index, &inputs, Err(message), outputs),
        };
        Finished {
            position,
            line,
            failed: result.is_err(),
        }
    }

    /// The writer: appends rows in position order; returns the number of failed samples.
    fn write(
        &self,
        receiver: mpsc::Receiver<Vec<Finished>>,
        out: &mut impl std::io::Write,
        progress: &mut Progress,
    ) -> std::io::Result<u64> {
        let mut pending = BTreeMap::new();
        let mut next = *self.written.lock().unwrap_or_else(PoisonError::into_inner);
        let mut failed = 0;
        for batch in receiver {
            pending.extend(batch.into_iter().map(|row| (row.position, row)));
            let first = next;
            while let Some(row) = pending.remove(&next) {
                out.write_all(row.line.as_bytes())?;
                failed += u64::from(row.failed);
                next += 1;
            }
            if next > first {
                out.flush()?;
                *self.written.lock().unwrap_or_else(PoisonError::into_inner) = next;
                self.advanced.notify_all();
                progress.advance(next - first);
            }
        }
        Ok(failed)
    }

    /// Whether workers must stop claiming and flying samples.
    fn stopped(&self) -> bool {
        self.abort.load(Ordering::Relaxed) || self.stop.load(Ordering::Relaxed)
    }

    /// Stops the workers (after a write error).
    fn stop(&self) {
        self.abort.store(true, Ordering::Relaxed);
        let _guard = self.written.lock().unwrap_or_else(PoisonError::into_inner);
        self.advanced.notify_all();
    }
}

/// The text of a panic's payload.
fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(text) = payload.downcast_ref::<&str>() {
        (*text).to_owned()
    } else if let Some(text) = payload.downcast_ref::<String>() {
        text.clone()
    } else {
        "(no message)".to_owned()
    }
}
