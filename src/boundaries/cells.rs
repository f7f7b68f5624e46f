//! The one byte of a case that locating boundaries reads from the engine's rows: its regime
//! (a `state` case) or its outcome with the collapse mechanism kind (the other finds), or
//! nothing (a failed case). A grid of 16 million cases is 16 MB of codes; the rows
//! themselves go to results.parquet chunk by chunk and are never all held.

use crate::analysis::{MechanismKind, Regime};
use crate::engine::{CaseResult, StateCase, Status};
use crate::scene::{Find, Outcome};

/// The code of a failed case, or of a case with nothing to compare.
pub const NO_CELL: u8 = 0;

const REGIME: u8 = 1;
const FOUND: u8 = 16;
const OTHER: u8 = 32;

const KINDS: [MechanismKind; 3] = [
    MechanismKind::Rotational,
    MechanismKind::Mixed,
    MechanismKind::Sliding,
];

/// What an edge's ends are compared by.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Cell {
    /// The regime (state finds).
    Regime(Regime),
    /// A limit state with its mechanism kind (other finds).
    Found(Option<MechanismKind>),
    /// Any other outcome (unbounded, never or always stands, …).
    Other(Outcome),
}

fn index<T: PartialEq>(all: &[T], v: &T) -> u8 {
    all.iter().position(|x| x == v).map_or(0, |i| i as u8)
}

/// The code of one engine row (see the module documentation).
pub fn cell_code(r: &CaseResult) -> u8 {
    if r.status != Status::Ok {
        return NO_CELL;
    }
    let s = &r.solution;
    if s.find == Find::State {
        return s.regime().map_or(NO_CELL, regime_code);
    }
    match s.outcome {
        None => NO_CELL,
        Some(Outcome::Found) => FOUND + s.mechanism.map_or(0, |m| 1 + index(&KINDS, &m)),
        Some(o) => OTHER + index(&Outcome::ALL, &o),
    }
}

/// The code of a `state` case of this regime.
fn regime_code(g: Regime) -> u8 {
    REGIME + index(&Regime::ALL, &g)
}

/// The code of one compact row of a separable `state` grid: that of its full row.
pub fn state_cell_code(r: &StateCase) -> u8 {
    r.answer.map_or(NO_CELL, |a| regime_code(a.regime))
}

/// The cell a code stands for (`None` for [`NO_CELL`]).
pub(crate) fn decode(code: u8) -> Option<Cell> {
    match code {
        OTHER.. => Outcome::ALL
            .get(usize::from(code - OTHER))
            .map(|&o| Cell::Other(o)),
        FOUND.. => match code - FOUND {
            0 => Some(Cell::Found(None)),
            n => KINDS.get(usize::from(n - 1)).map(|&m| Cell::Found(Some(m))),
        },
        REGIME.. => Regime::ALL
            .get(usize::from(code - REGIME))
            .map(|&g| Cell::Regime(g)),
        _ => None,
    }
}

/// The regime of a code, when it is a state case's.
pub(crate) fn regime(code: u8) -> Option<Regime> {
    match decode(code)? {
        Cell::Regime(g) => Some(g),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A compact row of a separable `state` grid has the code of its full row, whether its
    /// analysis ran or failed.
    #[test]
    fn a_compact_state_row_has_the_code_of_its_full_row() {
        let m = crate::manifest::parse(
            "name: a\ngrid:\n  k: {from: 1.05, to: 1.4, steps: 15}\n  mu: {values: [0.2, 0.3, 0.4, 0.6, inf]}\n",
            std::path::Path::new("a.yaml"),
        )
        .unwrap();
        let plan = crate::plan::build(m).unwrap();
        let mut rows = crate::engine::Rows::default();
        crate::engine::analyse_rows(&plan, &crate::progress::Silent, &mut rows);
        let crate::engine::Rows::States(states) = &rows else {
            panic!("a separable grid gives compact rows");
        };
        let mut codes: Vec<u8> = states.iter().map(state_cell_code).collect();
        let failed = StateCase {
            message: Some("stopped".into()),
            answer: None,
            ..states[0].clone()
        };
        codes.push(state_cell_code(&failed));
        let mut full = rows.into_results();
        full.push(failed.into_result());
        assert_eq!(codes, full.iter().map(cell_code).collect::<Vec<_>>());
        // Several regimes are met, and the failed row has no cell.
        let mut distinct = codes.clone();
        distinct.sort_unstable();
        distinct.dedup();
        assert!(distinct.len() >= 4, "{distinct:?}");
        assert_eq!(codes.last(), Some(&NO_CELL));
    }

    #[test]
    fn every_cell_reads_back_from_its_code() {
        let mut cells: Vec<Cell> = Regime::ALL.iter().map(|&g| Cell::Regime(g)).collect();
        cells.push(Cell::Found(None));
        cells.extend(KINDS.iter().map(|&m| Cell::Found(Some(m))));
        cells.extend(Outcome::ALL.iter().map(|&o| Cell::Other(o)));
        let encode = |c: Cell| match c {
            Cell::Regime(g) => REGIME + index(&Regime::ALL, &g),
            Cell::Found(m) => FOUND + m.map_or(0, |m| 1 + index(&KINDS, &m)),
            Cell::Other(o) => OTHER + index(&Outcome::ALL, &o),
        };
        let codes: Vec<u8> = cells.iter().map(|&c| encode(c)).collect();
        let mut distinct = codes.clone();
        distinct.sort_unstable();
        distinct.dedup();
        assert_eq!(distinct.len(), cells.len());
        assert!(!codes.contains(&NO_CELL));
        for (c, code) in cells.iter().zip(codes) {
            assert_eq!(decode(code), Some(*c));
        }
        assert_eq!(decode(NO_CELL), None);
        assert_eq!(regime(REGIME + 2), Some(Regime::ALL[2]));
    }
}
