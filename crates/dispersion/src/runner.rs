//! The run: every missing sample of a shard flown in parallel, rows written in index order
//! (docs/physics.md §27.2).
//!
//! Workers of a local `rayon` pool claim runs of `CLAIM` consecutive sample positions from a shared
//! counter, draw the inputs ([`crate::sampling`]), fly the samples and send their finished rows
//! together to the calling thread, which keeps out-of-order rows in a `BTreeMap` and appends every
//! row whose predecessors are written, flushing after each batch (docs/performance.md, "Monte Carlo
//! runner"); a killed run loses at most the unflushed claims, which the resume flies again. A
//! worker does not start a claim reaching more than `WINDOW_PER_THREAD × threads` ahead of the last
//! written row, so memory stays bounded whatever the number of samples. Because each sample depends
//! only on (seed, index), `samples.csv` is byte-identical for any thread count and any
//! interruption.
//!
//! The run holds the directory's lock (`study.lock`) from before it reads anything until its
//! last file is written: a second run on the same directory fails at once and touches nothing.
//! A resume flies the first and the last kept rows again and requires the very same rows, so
//! that rows flown by another model are not mixed into the study.

use crate::csv::{self, Counts, Row, Status};
use crate::error::DispersionError;
use crate::files::{self, SAMPLES_FILE, STUDY_FILE};
use crate::progress::{Progress, ProgressMode};
use crate::sampling::draw;
use crate::study::{Record, Shard, Study};
use crate::summary::{Summary, summarize, summarize_rows};
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
/// did not occur (no impact when the flight stops at apogee), and how it ended.
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    values: Vec<Option<f64>>,
    status: Status,
}

impl Outcome {
    /// A completed flight: the outputs' values, in the order of [`Study::outputs`].
    pub fn new(values: Vec<Option<f64>>) -> Self {
        Outcome {
            values,
            status: Status::Completed,
        }
    }

    /// A flight that ended before the end the study asks for (its time limit reached in the
    /// air, the rail never left): `kind` is the status recorded (lowercase letters, digits and
    /// `_`, e.g. `max_time`), `message` the explanation. Its values are kept in `samples.csv`
    /// but left out of the output statistics and the ellipses.
    pub fn ended(values: Vec<Option<f64>>, kind: &str, message: String) -> Self {
        Outcome {
            values,
            status: Status::Ended {
                kind: kind.to_owned(),
                message,
            },
        }
    }

    /// The values.
    pub fn values(&self) -> &[Option<f64>] {
        &self.values
    }

    /// How the flight ended.
    pub fn status(&self) -> &Status {
        &self.status
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
    /// The shard's samples (kept and new) by how they ended.
    pub counts: Counts,
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

/// Runs (or resumes) `study` in `dir`: locks it, creates `study.json` and `samples.csv`, or
/// checks that they hold this very study and shard (data fingerprint included) and keeps
/// their complete rows, after flying the first and last of them again; flies the missing
/// samples with `fly(index, sampled values)`; for a whole study writes `summary.json`,
/// `dispersion.kml` and the plots. A sample whose `fly` returns `Err` (or panics) is recorded
/// as failed with its inputs and message, and the run goes on.
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
    let pool = thread_pool(options)?;
    let shard = options.shard.unwrap_or(Shard::WHOLE);
    let record = Record::new(study, shard);
    let key = record.fingerprint.as_str();
    std::fs::create_dir_all(dir).map_err(DispersionError::io(dir))?;
    let mut lock = files::lock(dir, true)?;
    files::remove_temporaries(dir)?;
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
            if let Some(file) = files::foreign_output(dir) {
                return Err(DispersionError::ForeignOutput {
                    dir: dir.to_owned(),
                    file,
                });
            }
            files::write_atomic(&study_path, record.to_json().as_bytes())?;
        }
    }

    let scan = match files::scan(&samples_path, &record) {
        Err(DispersionError::TamperedRow {
            file,
            line,
            index,
            stored,
            computed,
            row,
            ..
        }) => {
            let position = (index - (shard.number - 1)) / shard.count;
            let again = fly_sample(study, shard, &fly, position).line(key, study.outputs.len());
            return Err(DispersionError::TamperedRow {
                detail: changed_cells(study, &row, again.trim_end_matches('\n')),
                file,
                line,
                index,
                stored,
                computed,
                row,
            });
        }
        other => other?,
    };
    for (position, line, kept) in &scan.ends {
        let again = fly_sample(study, shard, &fly, *position).line(key, study.outputs.len());
        if again.trim_end_matches('\n') != kept.trim_end_matches('\n') {
            return Err(DispersionError::ChangedOutputs {
                file: samples_path,
                line: *line,
                index: shard.index(*position),
            });
        }
    }
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
    let mut out = FileSink {
        out: BufWriter::with_capacity(1 << 16, file),
        outputs: study.outputs.len(),
        key,
        path: &samples_path,
        lock: &mut lock,
    };
    if !scan.has_header {
        out.out
            .write_all(csv::header(&study.columns()).as_bytes())
            .and_then(|()| out.out.flush())
            .map_err(DispersionError::io(&samples_path))?;
    }
    let flown = fly_all(
        &pool,
        study,
        shard,
        options.progress,
        stop,
        scan.rows,
        &mut out,
        &fly,
    );
    drop(out);
    let mut counts = flown.written?;
    counts.merge(&scan.counts);
    let total = shard.len(study.samples);
    if flown.rows < total {
        return Err(DispersionError::Interrupted {
            dir: dir.to_owned(),
            written: flown.rows,
            total,
        });
    }

    lock.check()?;
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
        counts,
        threads: flown.threads,
        elapsed: flown.elapsed,
        summary,
    })
}

/// A study run in memory ([`run_in_memory`]): every sample's row, in index order, and what
/// the run did (with the summary).
#[derive(Debug, Clone, PartialEq)]
pub struct MemoryRun {
    /// The rows, as `samples.csv` would hold them ([`Row::of`]).
    pub rows: Vec<Row>,
    /// What the run did; its summary is the one `summary.json` would hold.
    pub report: RunReport,
}

/// [`run_until`] without an output directory: flies every sample of the whole `study`
/// (`options.shard` must be absent or the whole study) and keeps the rows in memory; the
/// rows and the summary are those a run into a directory writes, byte for byte once
/// written. Stopped by `stop`, it returns [`DispersionError::Stopped`] (nothing to resume).
pub fn run_in_memory<F>(
    study: &Study,
    options: &RunOptions,
    stop: &AtomicBool,
    fly: F,
) -> Result<MemoryRun, DispersionError>
where
    F: Fn(u64, &[f64]) -> Result<Outcome, String> + Sync,
{
    study.validate()?;
    if options.shard.is_some_and(|shard| shard != Shard::WHOLE) {
        return Err(DispersionError::InvalidStudy {
            reason: "a study in memory is the whole study; shards are written to a directory"
                .to_owned(),
        });
    }
    let pool = thread_pool(options)?;
    let total = study.samples;
    let mut sink = MemorySink {
        rows: Vec::with_capacity(usize::try_from(total).unwrap_or(0)),
        outputs: study.outputs.len(),
    };
    let flown = fly_all(
        &pool,
        study,
        Shard::WHOLE,
        options.progress,
        stop,
        0,
        &mut sink,
        &fly,
    );
    let Ok(counts) = flown.written;
    if flown.rows < total {
        return Err(DispersionError::Stopped {
            written: flown.rows,
            total,
        });
    }
    let summary = summarize_rows(study, &sink.rows);
    Ok(MemoryRun {
        rows: sink.rows,
        report: RunReport {
            shard: Shard::WHOLE,
            shard_samples: total,
            resumed: 0,
            flown: total,
            counts,
            threads: flown.threads,
            elapsed: flown.elapsed,
            summary: Some(summary),
        },
    })
}

/// The header line of `samples.csv` of `study`, newline included.
pub fn samples_header(study: &Study) -> String {
    csv::header(&study.columns())
}

/// The lines of `samples.csv` of the samples `indices` of `study` (an index at or beyond
/// `study.samples` has none), flown one after another on the calling thread: no pool, no
/// clock, no file, for a program without threads (the browser page, each of whose workers
/// flies a slice). They are the lines [`run`] writes for those samples, byte for byte, so the
/// slices joined in index order after [`samples_header`] make a whole run's `samples.csv`.
///
/// # Errors
/// [`DispersionError`] of a study that does not [validate](Study::validate).
pub fn sample_lines<F>(
    study: &Study,
    indices: std::ops::Range<u64>,
    fly: F,
) -> Result<String, DispersionError>
where
    F: Fn(u64, &[f64]) -> Result<Outcome, String> + Sync,
{
    study.validate()?;
    let key = Record::new(study, Shard::WHOLE).fingerprint;
    let outputs = study.outputs.len();
    let mut text = String::new();
    for index in indices.start..indices.end.min(study.samples) {
        text.push_str(&fly_sample(study, Shard::WHOLE, &fly, index).line(&key, outputs));
    }
    Ok(text)
}

/// The worker pool of `options.threads` (0 or absent: one thread per core), refused beyond
/// [`MAX_THREADS_PER_CORE`] per core.
pub(crate) fn thread_pool(options: &RunOptions) -> Result<rayon::ThreadPool, DispersionError> {
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
    rayon::ThreadPoolBuilder::new()
        .num_threads(requested)
        .thread_name(|i| format!("karman-mc-{i}"))
        .build()
        .map_err(|e| DispersionError::ThreadPool {
            threads: requested,
            message: e.to_string(),
        })
}

/// Where the writer puts the rows, in position order.
trait Sink {
    /// The sink's error (none for memory).
    type Error;
    /// Takes the next row.
    fn push(&mut self, row: Finished) -> Result<(), Self::Error>;
    /// Makes the rows taken so far durable (after each batch).
    fn flush(&mut self) -> Result<(), Self::Error>;
}

/// Rows appended to `samples.csv` (`path`), each with its digest keyed by `key`; before each
/// batch is flushed, the directory's lock is checked ([`files::DirLock::check`]).
struct FileSink<'a, W: std::io::Write> {
    out: W,
    outputs: usize,
    key: &'a str,
    path: &'a Path,
    lock: &'a mut files::DirLock,
}

impl<W: std::io::Write> Sink for FileSink<'_, W> {
    type Error = DispersionError;

    fn push(&mut self, row: Finished) -> Result<(), DispersionError> {
        self.out
            .write_all(row.line(self.key, self.outputs).as_bytes())
            .map_err(DispersionError::io(self.path))
    }

    fn flush(&mut self) -> Result<(), DispersionError> {
        self.lock.check()?;
        self.out.flush().map_err(DispersionError::io(self.path))
    }
}

/// Rows kept in memory.
struct MemorySink {
    rows: Vec<Row>,
    outputs: usize,
}

impl Sink for MemorySink {
    type Error = std::convert::Infallible;

    fn push(&mut self, row: Finished) -> Result<(), Self::Error> {
        self.rows.push(row.into_row(self.outputs));
        Ok(())
    }

    fn flush(&mut self) -> Result<(), Self::Error> {
        Ok(())
    }
}

/// What [`fly_all`] did.
struct Flown<E> {
    /// The counts of the rows written now, or the sink's error.
    written: Result<Counts, E>,
    /// Positions below this are written (kept and new).
    rows: u64,
    threads: usize,
    elapsed: Duration,
}

/// Flies the positions of `shard` from `first` on in `pool` and hands their rows to `sink`
/// in position order, until all are written, `stop` is set or the sink fails.
#[allow(clippy::too_many_arguments)]
fn fly_all<F, S>(
    pool: &rayon::ThreadPool,
    study: &Study,
    shard: Shard,
    progress: ProgressMode,
    stop: &AtomicBool,
    first: u64,
    sink: &mut S,
    fly: &F,
) -> Flown<S::Error>
where
    F: Fn(u64, &[f64]) -> Result<Outcome, String> + Sync,
    S: Sink,
{
    let threads = pool.current_num_threads();
    let total = shard.len(study.samples);
    let mut progress = Progress::new(progress, total, first);
    let started = Instant::now();
    let engine = Engine {
        study,
        shard,
        total,
        window: WINDOW_PER_THREAD * threads as u64,
        next: AtomicU64::new(first),
        abort: AtomicBool::new(false),
        stop,
        written: Mutex::new(first),
        advanced: Condvar::new(),
    };
    let (sender, receiver) = mpsc::channel::<Vec<Finished>>();
    let mut written = None;
    pool.in_place_scope(|scope| {
        for _ in 0..threads {
            let sender = sender.clone();
            let engine = &engine;
            scope.spawn(move |_| engine.work(fly, &sender));
        }
        drop(sender);
        let result = engine.write(receiver, sink, &mut progress);
        if result.is_err() {
            engine.stop();
        }
        written = Some(result);
    });
    progress.finish();
    let rows = *engine
        .written
        .lock()
        .unwrap_or_else(PoisonError::into_inner);
    Flown {
        written: written.unwrap_or_else(|| Ok(Counts::default())),
        rows,
        threads,
        elapsed: started.elapsed(),
    }
}

/// A flown sample's row.
struct Finished {
    position: u64,
    index: u64,
    inputs: Vec<f64>,
    status: Status,
    values: Vec<Option<f64>>,
}

impl Finished {
    /// Its line of `samples.csv` in a study of `outputs` outputs and fingerprint `key`.
    fn line(&self, key: &str, outputs: usize) -> String {
        csv::row(
            key,
            self.index,
            &self.inputs,
            &self.status,
            &self.values,
            outputs,
        )
    }

    /// Its row as read back from that line.
    fn into_row(self, outputs: usize) -> Row {
        Row::of(self.index, self.inputs, self.status, self.values, outputs)
    }
}

/// The cells in which the kept row `kept` differs from the row `again` flown again (both
/// without their newline), for [`DispersionError::TamperedRow`]: `; flown again, it differs
/// in: apogee_m (kept 2468.2, flown again 1234.1)`.
fn changed_cells(study: &Study, kept: &str, again: &str) -> String {
    let (Ok(kept), Ok(again)) = (csv::split(kept), csv::split(again)) else {
        return String::new();
    };
    let columns = study.columns();
    let cells = columns.len() - 1;
    let changed: Vec<String> = columns
        .iter()
        .zip(kept.iter().zip(&again))
        .take(cells)
        .filter(|(_, (a, b))| a != b)
        .map(|(name, (a, b))| format!("{name} (kept {a:?}, flown again {b:?})"))
        .collect();
    if changed.is_empty() {
        "; flown again, its cells are the same: its digest was edited".to_owned()
    } else {
        format!("; flown again, it differs in: {}", changed.join(", "))
    }
}

/// The rows of samples `range` of the whole `study`, flown on `pool` (as a run flies them:
/// a panic or an error is a failed sample), in index order.
pub(crate) fn fly_rows<F>(
    pool: &rayon::ThreadPool,
    study: &Study,
    range: std::ops::Range<u64>,
    fly: &F,
) -> Vec<Row>
where
    F: Fn(u64, &[f64]) -> Result<Outcome, String> + Sync,
{
    use rayon::prelude::*;
    let outputs = study.outputs.len();
    pool.install(|| {
        range
            .into_par_iter()
            .map(|position| {
                let f = fly_sample(study, Shard::WHOLE, fly, position);
                Row::of(f.index, f.inputs, f.status, f.values, outputs)
            })
            .collect()
    })
}

/// Flies the sample at `position` of `shard` and formats its row.
fn fly_sample<F>(study: &Study, shard: Shard, fly: &F, position: u64) -> Finished
where
    F: Fn(u64, &[f64]) -> Result<Outcome, String> + Sync,
{
    let index = shard.index(position);
    let inputs = draw(study.seed, index, &study.inputs);
    let outputs = study.outputs.len();
    let outcome = match catch_unwind(AssertUnwindSafe(|| fly(index, &inputs))) {
        Ok(Ok(outcome)) if outcome.values.len() != outputs => Err(format!(
            "the flight returned {} values for {outputs} outputs",
            outcome.values.len()
        )),
        Ok(Ok(Outcome {
            status: Status::Ended { kind, .. },
            ..
        })) if !csv::is_ending_kind(&kind) => {
            Err(format!("the flight ended with the invalid status {kind:?}"))
        }
        Ok(Ok(Outcome {
            status: Status::Failed(message),
            ..
        })) => Err(message),
        Ok(Ok(outcome)) => Ok(outcome),
        Ok(Err(message)) => Err(message),
        Err(payload) => Err(format!("panicked: {}", panic_message(payload.as_ref()))),
    };
    let (status, values) = match outcome {
        Ok(outcome) => (outcome.status, outcome.values),
        Err(message) => (Status::Failed(message), Vec::new()),
    };
    Finished {
        position,
        index,
        inputs,
        status,
        values,
    }
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
                rows.push(fly_sample(self.study, self.shard, fly, position));
            }
            if sender.send(rows).is_err() {
                return;
            }
        }
    }

    /// The writer: hands rows to `sink` in position order; returns the written rows' counts.
    fn write<S: Sink>(
        &self,
        receiver: mpsc::Receiver<Vec<Finished>>,
        sink: &mut S,
        progress: &mut Progress,
    ) -> Result<Counts, S::Error> {
        let mut pending = BTreeMap::new();
        let mut next = *self.written.lock().unwrap_or_else(PoisonError::into_inner);
        let mut counts = Counts::default();
        for batch in receiver {
            pending.extend(batch.into_iter().map(|row| (row.position, row)));
            let first = next;
            while let Some(row) = pending.remove(&next) {
                counts.add(&row.status);
                sink.push(row)?;
                next += 1;
            }
            if next > first {
                sink.flush()?;
                *self.written.lock().unwrap_or_else(PoisonError::into_inner) = next;
                self.advanced.notify_all();
                progress.advance(next - first);
            }
        }
        Ok(counts)
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
