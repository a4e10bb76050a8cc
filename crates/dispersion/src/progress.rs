//! Progress of a run on standard error: an `indicatif` bar on a terminal (done/total, rate,
//! ETA), plain periodic lines otherwise (logs of batch jobs), or nothing.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal as _;
use std::time::{Duration, Instant};

/// How a run reports progress.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ProgressMode {
    /// A bar when standard error is a terminal, else a line every 10 s.
    #[default]
    Auto,
    /// Nothing.
    Hidden,
}

/// Interval of the plain progress lines.
const LINE_INTERVAL: Duration = Duration::from_secs(10);

pub(crate) enum Progress {
    Bar(ProgressBar),
    Lines {
        total: u64,
        start_done: u64,
        done: u64,
        started: Instant,
        last: Instant,
    },
    Hidden,
}

impl Progress {
    /// Progress of `total` samples of which `done` are already there.
    pub fn new(mode: ProgressMode, total: u64, done: u64) -> Self {
        let now = Instant::now();
        match mode {
            ProgressMode::Hidden => Progress::Hidden,
            ProgressMode::Auto if std::io::stderr().is_terminal() => {
                let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
                let style = ProgressStyle::with_template(
                    "{bar:40} {pos}/{len} samples  {per_sec}  ETA {eta}  [{elapsed}]",
                )
                .unwrap_or_else(|_| ProgressStyle::default_bar());
                bar.set_style(style);
                bar.set_position(done);
                bar.reset_eta();
                Progress::Bar(bar)
            }
            ProgressMode::Auto => Progress::Lines {
                total,
                start_done: done,
                done,
                started: now,
                last: now,
            },
        }
    }

    /// `n` more samples are written.
    pub fn advance(&mut self, n: u64) {
        match self {
            Progress::Bar(bar) => bar.inc(n),
            Progress::Lines {
                total,
                start_done,
                done,
                started,
                last,
            } => {
                *done += n;
                if last.elapsed() >= LINE_INTERVAL || *done == *total {
                    *last = Instant::now();
                    let seconds = started.elapsed().as_secs_f64();
                    let rate = (*done - *start_done) as f64 / seconds.max(1e-9);
                    let eta = (*total - *done) as f64 / rate.max(1e-9);
                    eprintln!(
                        "montecarlo: {done}/{total} samples ({:.1} %), {rate:.1} samples/s, ETA {eta:.0} s",
                        100.0 * *done as f64 / (*total).max(1) as f64
                    );
                }
            }
            Progress::Hidden => {}
        }
    }

    /// The run is over.
    pub fn finish(&self) {
        if let Progress::Bar(bar) = self {
            bar.finish();
        }
    }
}
