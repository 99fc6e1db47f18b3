//! A progress bar for the harness's long work: renders, comparisons and their supersampled
//! truths, shown on stderr only once the work has taken [`SHOW_AFTER`], and only where
//! stderr is a terminal (`indicatif` draws nothing into a pipe or a file).
//!
//! The work is counted in rows: every row [`crate::rows::render_rows_into`] shades adds one
//! to [`ROWS_SHADED`], from whichever thread shades it, and a ticker thread moves the bar to
//! that count. So no renderer carries the bar through its signature, and a frame that takes
//! less than a second shows nothing.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;
use std::thread::{self, JoinHandle};
use std::time::{Duration, Instant};

/// Rows shaded by `render_rows_into` in this process.
pub static ROWS_SHADED: AtomicU64 = AtomicU64::new(0);

/// How long work runs before its bar appears.
pub const SHOW_AFTER: Duration = Duration::from_secs(1);

/// How often the bar moves.
const TICK: Duration = Duration::from_millis(100);

/// A bar over `rows` rows of work from now on; it clears itself when dropped.
pub struct Progress {
    stop: Arc<AtomicBool>,
    ticker: Option<JoinHandle<()>>,
}

impl Progress {
    /// Starts watching the next `rows` rows shaded, labelled `label`.
    pub fn start(label: &str, rows: u64) -> Progress {
        let base = ROWS_SHADED.load(Ordering::Relaxed);
        let stop = Arc::new(AtomicBool::new(false));
        let bar = ProgressBar::with_draw_target(Some(rows), ProgressDrawTarget::hidden());
        if let Ok(style) = ProgressStyle::with_template(
            "{msg} [{bar:32}] {percent:>3}% {elapsed} (about {eta} left)",
        ) {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.set_message(label.to_string());
        let stopped = Arc::clone(&stop);
        let ticker = thread::spawn(move || {
            let start = Instant::now();
            let mut shown = false;
            while !stopped.load(Ordering::Relaxed) {
                thread::park_timeout(TICK);
                if !shown && start.elapsed() >= SHOW_AFTER {
                    bar.set_draw_target(ProgressDrawTarget::stderr());
                    shown = true;
                }
                let done = ROWS_SHADED.load(Ordering::Relaxed).saturating_sub(base);
                bar.set_position(done.min(rows));
            }
            bar.finish_and_clear();
        });
        Progress {
            stop,
            ticker: Some(ticker),
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(ticker) = self.ticker.take() {
            ticker.thread().unpark();
            let _ = ticker.join();
        }
    }
}
