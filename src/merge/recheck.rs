//! Rows of a shard analysed again by the merging build: a shard's table and the hash its own
//! run.json records are claims of the shard, so a table edited with its hash recomputed (a
//! regime flipped, every thrust scaled) would otherwise pass every check of the plan. The
//! rows are drawn at random in each merge (no one can tell in advance which rows a merge
//! reads), analysed as a plan of their own and compared with the shard's, value by value,
//! at `verify`'s tolerance ([`compare`]). `verify` on the merged run re-analyses every row.

use crate::engine::{self, CaseResult};
use crate::plan::Plan;
use crate::progress::Silent;
use crate::store;
use crate::store::compare::{self, ColumnVerdict, compare_tables};
use anyhow::Result;
use std::collections::BTreeSet;
use std::hash::{BuildHasher, Hasher};

/// Rows of each shard a merge analyses again unless told otherwise (`--recheck`).
pub const DEFAULT_RECHECK_ROWS: u64 = 64;

/// How many rows of each shard a merge analyses again.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Recheck {
    /// This many rows of each shard, drawn at random (all of a shard that has fewer); 0 takes
    /// the shards' values on trust, after the checks against the plan.
    Rows(u64),
    /// Every row: the merge costs what the shards' analyses cost.
    All,
}

impl Default for Recheck {
    fn default() -> Self {
        Recheck::Rows(DEFAULT_RECHECK_ROWS)
    }
}

impl Recheck {
    /// `N` or `all`, as `--recheck` takes it.
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "all" => Some(Recheck::All),
            _ => s.parse().ok().map(Recheck::Rows),
        }
    }

    /// The offsets, within a shard of `n` rows, of the rows to analyse again, in order.
    pub fn offsets(self, n: u64) -> BTreeSet<u64> {
        let want = match self {
            Recheck::All => n,
            Recheck::Rows(k) => k.min(n),
        };
        if want == n {
            return (0..n).collect();
        }
        // A fresh random seed for every merge (the standard library seeds each RandomState
        // from the operating system), spread by splitmix64.
        let mut state = std::collections::hash_map::RandomState::new()
            .build_hasher()
            .finish();
        let mut next = move || {
            state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^ (z >> 31)
        };
        let mut picked = BTreeSet::new();
        while (picked.len() as u64) < want {
            picked.insert(next() % n);
        }
        picked
    }
}

/// The first disagreement between a shard's rows and the same cases analysed again.
#[derive(Debug, Clone, PartialEq)]
pub struct Disagreement {
    /// The case id.
    pub case_id: u64,
    /// The column that differs.
    pub column: String,
    /// The shard's value.
    pub stored: String,
    /// The value analysed again.
    pub recomputed: String,
}

/// Analyses the cases `picks` (indices into `slice.cases` and `rows`) again and compares them
/// with the shard's rows: the first disagreement, if any.
pub fn recheck(slice: &Plan, rows: &[CaseResult], picks: &[usize]) -> Result<Option<Disagreement>> {
    if picks.is_empty() {
        return Ok(None);
    }
    let sub = Plan {
        manifest: slice.manifest.clone(),
        cases: picks.iter().map(|&i| slice.cases[i].clone()).collect(),
    };
    let stored: Vec<CaseResult> = picks.iter().map(|&i| rows[i].clone()).collect();
    let again = engine::analyse(&sub, &Silent);
    let table = |r: &[CaseResult]| -> Result<store::Table> {
        store::table_from_frame(&store::results_frame(&sub, r)?)
    };
    let c = compare_tables(
        &table(&stored)?,
        &table(&again)?,
        compare::DEFAULT_TOLERANCE,
    );
    for col in &c.columns {
        if let ColumnVerdict::Different { first, .. } = &col.verdict
            && let Some(d) = first.first()
        {
            return Ok(Some(Disagreement {
                case_id: sub.cases[d.row].id,
                column: col.name.clone(),
                stored: d.stored.clone(),
                recomputed: d.recomputed.clone(),
            }));
        }
        if !col.verdict.agrees() {
            return Ok(Some(Disagreement {
                case_id: sub.cases[0].id,
                column: col.name.clone(),
                stored: format!("{:?}", col.verdict),
                recomputed: String::new(),
            }));
        }
    }
    Ok(None)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offsets_are_distinct_in_range_and_all_of_a_short_shard() {
        let o = Recheck::Rows(64).offsets(1000);
        assert_eq!(o.len(), 64);
        assert!(o.iter().all(|&i| i < 1000));
        assert_eq!(Recheck::Rows(64).offsets(10), (0..10).collect());
        assert_eq!(Recheck::All.offsets(5), (0..5).collect());
        assert!(Recheck::Rows(0).offsets(5).is_empty());
        // Two merges draw other rows (the chance of the same 64 of 10⁶ is nil).
        assert_ne!(
            Recheck::Rows(64).offsets(1_000_000),
            Recheck::Rows(64).offsets(1_000_000)
        );
    }

    #[test]
    fn recheck_parses_a_count_or_all() {
        assert_eq!(Recheck::parse("all"), Some(Recheck::All));
        assert_eq!(Recheck::parse("0"), Some(Recheck::Rows(0)));
        assert_eq!(Recheck::parse("128"), Some(Recheck::Rows(128)));
        assert_eq!(Recheck::parse("-1"), None);
        assert_eq!(Recheck::parse("some"), None);
    }
}
