//! Progress of a run on standard error: a bar per stage on a terminal; off a terminal (a batch
//! log) one plain line when a stage begins, a line every few seconds on a long stage, and one
//! when it ends.

use crate::progress::{Progress, Stage};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// How often a long stage writes a line to a log, at most.
const LOG_EVERY: Duration = Duration::from_secs(5);

/// Progress shown on standard error.
pub struct Shown {
    terminal: bool,
    bar: Mutex<Option<ProgressBar>>,
    stage: Mutex<Option<Running>>,
    done: AtomicU64,
}

/// The stage under way, for log lines.
struct Running {
    stage: Stage,
    total: Option<u64>,
    started: Instant,
    last_line: Instant,
}

impl Shown {
    /// Progress on standard error: bars on a terminal, lines in a log.
    pub fn on_stderr() -> Self {
        Shown {
            terminal: std::io::stderr().is_terminal(),
            bar: Mutex::new(None),
            stage: Mutex::new(None),
            done: AtomicU64::new(0),
        }
    }

    fn bar(stage: Stage, total: Option<u64>) -> ProgressBar {
        let (bar, template) = match total {
            Some(n) => (
                ProgressBar::new(n),
                format!(
                    "{{spinner}} {} [{{bar:40}}] {{pos}}/{{len}} {} ({{per_sec}}, {{eta}} left)",
                    stage.as_str(),
                    stage.unit()
                ),
            ),
            None if stage.unit() != "steps" => (
                ProgressBar::new_spinner(),
                format!(
                    "{{spinner}} {} {{pos}} {} ({{per_sec}}, {{elapsed}})",
                    stage.as_str(),
                    stage.unit()
                ),
            ),
            None => (
                ProgressBar::new_spinner(),
                format!("{{spinner}} {} ({{elapsed}})", stage.as_str()),
            ),
        };
        bar.set_draw_target(ProgressDrawTarget::stderr());
        if let Ok(style) = ProgressStyle::with_template(&template) {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.enable_steady_tick(Duration::from_millis(200));
        bar
    }

    /// One log line about the stage under way.
    fn log_line(r: &Running, done: u64, last: bool) {
        let secs = r.started.elapsed().as_secs_f64();
        let what = if last { "done" } else { "running" };
        let rate = if secs > 0.0 { done as f64 / secs } else { 0.0 };
        let (stage, unit) = (r.stage.as_str(), r.stage.unit());
        match r.total {
            Some(total) => {
                eprintln!(
                    "{stage}: {what}, {done}/{total} {unit} in {secs:.1} s ({rate:.0} {unit}/s)"
                );
            }
            // A stage of unknown length that counts: how many so far, and how fast.
            None if done > 0 => {
                eprintln!("{stage}: {what}, {done} {unit} in {secs:.1} s ({rate:.0} {unit}/s)");
            }
            None => eprintln!("{stage}: {what} in {secs:.1} s"),
        }
    }
}

impl Progress for Shown {
    fn begin(&self, stage: Stage, total: Option<u64>) {
        self.done.store(0, Ordering::Relaxed);
        let now = Instant::now();
        if self.terminal {
            if let Ok(mut b) = self.bar.lock() {
                *b = Some(Self::bar(stage, total));
            }
        } else {
            match total {
                Some(n) => eprintln!("{}: {n} {}", stage.as_str(), stage.unit()),
                None => eprintln!("{}", stage.as_str()),
            }
        }
        if let Ok(mut s) = self.stage.lock() {
            *s = Some(Running {
                stage,
                total,
                started: now,
                last_line: now,
            });
        }
    }

    fn advance(&self, n: u64) {
        let done = self.done.fetch_add(n, Ordering::Relaxed) + n;
        if self.terminal {
            if let Ok(b) = self.bar.lock()
                && let Some(bar) = b.as_ref()
            {
                bar.inc(n);
            }
            return;
        }
        // A log line at most every LOG_EVERY; the lock is only tried, never waited for.
        if let Ok(mut s) = self.stage.try_lock()
            && let Some(r) = s.as_mut()
            && r.last_line.elapsed() >= LOG_EVERY
        {
            r.last_line = Instant::now();
            Self::log_line(r, done, false);
        }
    }

    fn end(&self, _stage: Stage) {
        if let Ok(mut b) = self.bar.lock()
            && let Some(bar) = b.take()
        {
            bar.finish_and_clear();
        }
        if let Ok(mut s) = self.stage.lock()
            && let Some(r) = s.take()
            && !self.terminal
        {
            Self::log_line(&r, self.done.load(Ordering::Relaxed), true);
        }
    }
}
