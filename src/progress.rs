//! Progress of a run, as events: the stages report what they do, and whoever drives the run
//! (the command line, a test, another program) decides how to show it. Nothing here prints.

/// The stages of a run that report progress.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    /// Analysing every case of the plan and appending its rows to results.parquet.
    Analyse,
    /// Locating regime boundaries and bifurcations.
    Boundaries,
    /// Computing and storing the figure data.
    FigureData,
    /// Drawing the figures.
    Figures,
    /// Writing report.html and report.md.
    Reports,
}

impl Stage {
    /// A short name of the stage for progress lines, e.g. `analysing`.
    pub fn as_str(self) -> &'static str {
        match self {
            Stage::Analyse => "analysing",
            Stage::Boundaries => "locating boundaries",
            Stage::FigureData => "figure data",
            Stage::Figures => "drawing figures",
            Stage::Reports => "writing reports",
        }
    }

    /// What the stage counts (`cases`, refinement `analyses`, `figures`), when it counts
    /// anything.
    pub fn unit(self) -> &'static str {
        match self {
            Stage::Analyse => "cases",
            Stage::Boundaries => "analyses",
            Stage::Figures => "figures",
            _ => "steps",
        }
    }
}

/// Receives the progress of a run; called from worker threads.
pub trait Progress: Send + Sync {
    /// A stage begins; `total` is the number of units it will count, when known.
    fn begin(&self, stage: Stage, total: Option<u64>);
    /// `n` more units of the current stage are done.
    fn advance(&self, n: u64);
    /// The current stage has ended.
    fn end(&self, stage: Stage);
    /// True when whoever drives the run asks it to stop (a Python caller's Ctrl-C): the
    /// engine skips the cases it has not begun and the run returns [`Stopped`] at its next
    /// check, its staging directory removed. Never true by default.
    fn stopped(&self) -> bool {
        false
    }
}

/// A run or a batch of scenes stopped at its caller's request ([`Progress::stopped`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("stopped at the caller's request before it finished")]
pub struct Stopped;

/// Progress that goes nowhere.
#[derive(Debug, Clone, Copy, Default)]
pub struct Silent;

impl Progress for Silent {
    fn begin(&self, _stage: Stage, _total: Option<u64>) {}
    fn advance(&self, _n: u64) {}
    fn end(&self, _stage: Stage) {}
}

/// Progress whose caller asks to stop from the start (tests of stopped runs).
#[cfg(test)]
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct StopNow;

#[cfg(test)]
impl Progress for StopNow {
    fn begin(&self, _stage: Stage, _total: Option<u64>) {}
    fn advance(&self, _n: u64) {}
    fn end(&self, _stage: Stage) {}
    fn stopped(&self) -> bool {
        true
    }
}
