//! The rows of a separable `state` grid kept compact: a case's inputs and its regime with
//! both thrust domains, 320 bytes where a full row ([`CaseResult`]) holds every column of
//! every find in over a kilobyte. A million-case map is analysed and stored from
//! these; [`StateCase::into_result`] gives the full row of the same case.

use super::{CaseResult, Status};
use crate::plan::Case;
use crate::scene::{Inputs, Solution, StateAnswer};
use rayon::prelude::*;

/// The row of one case of a separable `state` grid (the default is no case's: a placeholder
/// for a row about to be written).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct StateCase {
    /// The case id.
    pub case_id: u64,
    /// Index of the load case in the manifest.
    pub load_case: usize,
    /// The inputs the row echoes.
    pub inputs: Inputs,
    /// The answer; `None` when the analysis failed.
    pub answer: Option<StateAnswer>,
    /// The case's solve time, µs: its comparison and its share of both domain solves.
    pub solve_time_us: f64,
    /// Why the analysis failed, when it did.
    pub message: Option<String>,
}

impl StateCase {
    /// The row of a case whose analysis failed, with why.
    pub(super) fn failed(c: &Case, message: String) -> Self {
        StateCase {
            case_id: c.id,
            load_case: c.load_case,
            inputs: Inputs::of(&c.scene),
            answer: None,
            solve_time_us: 0.0,
            message: Some(message),
        }
    }

    /// Ok when the analysis ran.
    pub fn status(&self) -> Status {
        if self.answer.is_some() {
            Status::Ok
        } else {
            Status::Error
        }
    }

    /// The full row of the same case.
    pub fn into_result(self) -> CaseResult {
        let mut solution = Solution::of_inputs(self.inputs);
        if let Some(a) = &self.answer {
            a.fill(&mut solution);
        }
        solution.solve_time_us = self.solve_time_us;
        CaseResult {
            case_id: self.case_id,
            load_case: self.load_case,
            solution,
            status: self.status(),
            message: self.message,
        }
    }
}

/// The rows of a chunk of a plan: compact on the separable `state` path, full otherwise.
/// One value is kept for every chunk of a run, so that each chunk's rows are written into
/// memory already in use.
#[derive(Debug, Clone)]
pub enum Rows {
    /// Full rows.
    Cases(Vec<CaseResult>),
    /// Compact rows of a separable `state` grid.
    States(Vec<StateCase>),
}

impl Default for Rows {
    fn default() -> Self {
        Rows::Cases(Vec::new())
    }
}

impl Rows {
    /// Removes the rows, keeping the buffer.
    pub fn clear(&mut self) {
        match self {
            Rows::Cases(v) => v.clear(),
            Rows::States(v) => v.clear(),
        }
    }

    /// The buffer of full rows, empty (the one held, when it is).
    pub(super) fn take_cases(&mut self) -> Vec<CaseResult> {
        match std::mem::take(self) {
            Rows::Cases(mut v) => {
                v.clear();
                v
            }
            Rows::States(_) => Vec::new(),
        }
    }

    /// The buffer of compact rows, empty (the one held, when it is).
    pub(super) fn take_states(&mut self) -> Vec<StateCase> {
        match std::mem::take(self) {
            Rows::States(mut v) => {
                v.clear();
                v
            }
            Rows::Cases(_) => Vec::new(),
        }
    }

    /// The full rows, in order.
    pub fn into_results(self) -> Vec<CaseResult> {
        match self {
            Rows::Cases(v) => v,
            Rows::States(v) => v.into_par_iter().map(StateCase::into_result).collect(),
        }
    }
}
