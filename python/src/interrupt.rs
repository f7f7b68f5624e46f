//! Long work off the interpreter's thread: the work runs on its own thread while the
//! interpreter's thread waits without the GIL and checks for signals every
//! [`POLL`]; a Ctrl-C asks the work to stop ([`Progress::stopped`]), waits for it to return
//! (its staging directory removed) and raises `KeyboardInterrupt`.

use archstudy::progress::{Progress, Stage};
use pyo3::prelude::*;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::Duration;

/// How often the waiting thread checks for Ctrl-C.
const POLL: Duration = Duration::from_millis(50);

/// Progress that asks the work to stop once the flag is set, and prints stage lines to
/// standard error unless quiet.
pub(crate) struct Stoppable {
    stop: AtomicBool,
    quiet: bool,
}

impl Progress for Stoppable {
    fn begin(&self, stage: Stage, total: Option<u64>) {
        if !self.quiet {
            match total {
                Some(n) => eprintln!("archstudy: {} ({n} {})", stage.as_str(), stage.unit()),
                None => eprintln!("archstudy: {}", stage.as_str()),
            }
        }
    }
    fn advance(&self, _n: u64) {}
    fn end(&self, _stage: Stage) {}
    fn stopped(&self) -> bool {
        self.stop.load(Ordering::Relaxed)
    }
}

/// Runs `work` on its own thread with a [`Stoppable`] progress; Ctrl-C stops it and raises
/// `KeyboardInterrupt`. A panic of the work becomes a `RuntimeError`.
pub(crate) fn run_stoppable<T: Send + 'static>(
    py: Python<'_>,
    quiet: bool,
    work: impl FnOnce(Arc<Stoppable>) -> T + Send + 'static,
) -> PyResult<T> {
    let progress = Arc::new(Stoppable {
        stop: AtomicBool::new(false),
        quiet,
    });
    let (tx, rx) = mpsc::channel();
    let p = progress.clone();
    let handle = std::thread::Builder::new()
        .name("archstudy".into())
        .spawn(move || {
            let out = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| work(p)));
            let _ = tx.send(());
            out
        })
        .map_err(crate::runtime_error)?;
    let mut interrupted = None;
    let mut rx = rx;
    loop {
        // The receiver goes into the GIL-free wait and back (it is Send, not Sync).
        let (back, done) = py.detach(move || {
            let done = rx.recv_timeout(POLL);
            (rx, done)
        });
        rx = back;
        if !matches!(done, Err(mpsc::RecvTimeoutError::Timeout)) {
            break;
        }
        if interrupted.is_none()
            && let Err(e) = py.check_signals()
        {
            progress.stop.store(true, Ordering::Relaxed);
            interrupted = Some(e);
        }
    }
    let out = py.detach(|| handle.join());
    if let Some(e) = interrupted {
        return Err(e);
    }
    match out {
        Ok(Ok(v)) => Ok(v),
        Ok(Err(p)) | Err(p) => Err(crate::runtime_error(panic_text(p.as_ref()))),
    }
}

fn panic_text(p: &(dyn std::any::Any + Send)) -> String {
    let what = p
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| p.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown".into());
    format!("the analysis failed unexpectedly (a panic in archstudy): {what}")
}
