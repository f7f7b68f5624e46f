//! results.parquet reduced to what the report shows: every row is read once, a block at a
//! time, into the totals the tables give over all cases (cases per regime or outcome, solve
//! times, the largest K) and the rows of the figure lattice, those the figures and the other
//! tables are drawn from. A K or μ axis longer than [`FIGURE_AXIS_POINTS`] keeps every s-th
//! value (and its last), so a map of 4001² cases is drawn from 1001² of them: more cells than
//! the pixels of the widest figure, and a run's memory that does not grow with its cases.

use crate::manifest::{AxisName, Manifest};
use crate::store::ResultRow;
use rustc_hash::FxHashMap;
use std::collections::BTreeMap;
use std::sync::Arc;

/// Most values of a K or μ axis the figures are drawn from: a longer axis keeps every s-th
/// value, s = ⌈(n − 1)/(FIGURE_AXIS_POINTS − 1)⌉, and its last.
pub const FIGURE_AXIS_POINTS: u64 = 1001;

/// Rows of results.parquet read at a time.
pub const READ_BLOCK_ROWS: usize = 1 << 18;

/// One load case in the lattice: its first case id, its number of cases and, per grid axis,
/// the number of positions and the step kept.
type LoadCaseLattice = (u64, u64, Vec<(u64, u64)>);

/// The cases of a plan the figures are drawn from, decided from a case id alone.
#[derive(Debug, Clone, Default)]
pub struct FigureLattice {
    /// Per load case, in plan order.
    load_cases: Vec<LoadCaseLattice>,
    /// No case is drawn as a grid point: the cases of a sampling study are samples, drawn
    /// from samples.parquet and estimates.parquet.
    none: bool,
}

impl FigureLattice {
    /// The lattice of a manifest's plan.
    pub fn of(m: &Manifest) -> Self {
        if m.sampling.is_some() {
            return FigureLattice {
                load_cases: Vec::new(),
                none: true,
            };
        }
        let mut first = 0u64;
        let mut load_cases = Vec::new();
        for lc in &m.load_cases {
            let axes: Vec<(u64, u64)> = m
                .grid
                .iter()
                .map(|a| {
                    let n = if lc.spans(a.name) {
                        a.values.len() as u64
                    } else {
                        1
                    };
                    let reduced = matches!(a.name, AxisName::K | AxisName::TOverR | AxisName::Mu)
                        && n > FIGURE_AXIS_POINTS;
                    let step = if reduced {
                        (n - 1).div_ceil(FIGURE_AXIS_POINTS - 1)
                    } else {
                        1
                    };
                    (n, step)
                })
                .collect();
            let count: u64 = axes.iter().map(|&(n, _)| n).product();
            load_cases.push((first, count, axes));
            first += count;
        }
        FigureLattice {
            load_cases,
            none: false,
        }
    }

    /// True when every case is kept ([`keeps`](Self::keeps) is true of every id): no axis is
    /// reduced and the cases are grid points.
    pub fn keeps_every(&self) -> bool {
        !self.none && !self.reduces()
    }

    /// True when some axis is reduced.
    pub fn reduces(&self) -> bool {
        self.load_cases
            .iter()
            .any(|(_, _, axes)| axes.iter().any(|&(_, s)| s > 1))
    }

    /// The number of cases the figures show, of the plan's (a bound on the rows kept of a
    /// run's results, which hold no other cases).
    pub fn kept(&self) -> usize {
        if self.none {
            return 0;
        }
        let kept: u64 = (self.load_cases.iter())
            .map(|(_, _, axes)| {
                (axes.iter())
                    .map(|&(n, step)| match n {
                        0 => 0,
                        // Every step-th position, and the last.
                        _ => (n - 1) / step + 1 + u64::from((n - 1) % step != 0),
                    })
                    .product::<u64>()
            })
            .sum();
        usize::try_from(kept).unwrap_or(usize::MAX)
    }

    /// Whether the figures show case `id` (every case when nothing is reduced).
    pub fn keeps(&self, id: u64) -> bool {
        if self.none {
            return false;
        }
        let Some((first, _, axes)) = self
            .load_cases
            .iter()
            .find(|(first, count, _)| id >= *first && id - first < *count)
        else {
            return true;
        };
        // The odometer position of the case, last axis fastest.
        let mut rest = id - first;
        for &(n, step) in axes.iter().rev() {
            let i = rest % n;
            rest /= n;
            if step > 1 && !i.is_multiple_of(step) && i != n - 1 {
                return false;
            }
        }
        true
    }
}

/// The voussoir count and find that group solve times.
type TimeKey<'a> = (Option<u32>, &'a str);

/// What the report gives over every row of results.parquet.
#[derive(Debug, Clone, Default)]
pub struct ResultTotals {
    /// Rows read.
    pub rows: u64,
    /// Cases per regime or outcome (`regime stable`, `never stands`, `failed`, …).
    pub by_outcome: BTreeMap<String, usize>,
    /// Solve times of the cases that succeeded, per voussoir count and find, increasing once
    /// [`ResultTotals::finish`] has run.
    pub solve_times: BTreeMap<(Option<u32>, Arc<str>), Vec<f64>>,
    /// The largest finite K per load case.
    pub k_max: BTreeMap<String, f64>,
}

impl ResultTotals {
    /// Adds a block of rows.
    pub fn add(&mut self, rows: &[ResultRow]) {
        // Counted under borrowed keys first: a block holds few distinct outcomes, finds and
        // load cases, and a million rows should not make a million strings.
        let mut outcomes: FxHashMap<(bool, Option<&str>, Option<&str>), usize> =
            FxHashMap::default();
        let mut k_max: FxHashMap<&str, f64> = FxHashMap::default();
        let mut times: Vec<(TimeKey<'_>, Vec<f64>)> = Vec::new();
        for r in rows {
            let ok = &*r.status == "ok";
            *outcomes
                .entry((ok, r.regime.as_deref(), r.outcome.as_deref()))
                .or_default() += 1;
            if ok {
                let key = (r.voussoirs, &*r.find);
                let at = match times.iter().rposition(|(k, _)| *k == key) {
                    Some(at) => at,
                    None => {
                        times.push((key, Vec::new()));
                        times.len() - 1
                    }
                };
                times[at].1.push(r.solve_time_us);
            }
            if let Some(k) = r.k.filter(|k| k.is_finite()) {
                let m = k_max.entry(&r.load_case).or_insert(k);
                *m = m.max(k);
            }
        }
        let mut block = ResultTotals {
            rows: rows.len() as u64,
            ..ResultTotals::default()
        };
        for ((ok, regime, outcome), n) in outcomes {
            let key = if !ok {
                "failed".to_string()
            } else if let Some(g) = regime {
                format!("regime {g}")
            } else if let Some(o) = outcome {
                o.replace('_', " ")
            } else {
                "ok".to_string()
            };
            *block.by_outcome.entry(key).or_default() += n;
        }
        block.solve_times = (times.into_iter())
            .map(|((v, find), t)| ((v, Arc::from(find)), t))
            .collect();
        block.k_max = (k_max.into_iter())
            .map(|(lc, k)| (lc.to_string(), k))
            .collect();
        self.merge(block);
    }
}

impl ResultTotals {
    /// Adds the totals of other rows.
    pub fn merge(&mut self, other: ResultTotals) {
        self.rows += other.rows;
        for (key, n) in other.by_outcome {
            *self.by_outcome.entry(key).or_default() += n;
        }
        for (key, t) in other.solve_times {
            self.solve_times.entry(key).or_default().extend(t);
        }
        for (lc, k) in other.k_max {
            let m = self.k_max.entry(lc).or_insert(k);
            *m = m.max(k);
        }
    }

    /// Sorts the solve times, once every block is added (a million of them on every core).
    pub fn finish(&mut self) {
        use rayon::prelude::*;
        for t in self.solve_times.values_mut() {
            t.par_sort_unstable_by(f64::total_cmp);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    fn manifest(steps: u64) -> Manifest {
        crate::manifest::parse(
            &format!(
                "name: a\ngrid:\n  k: {{from: 1.05, to: 1.5, steps: {steps}}}\n  mu: {{from: 0.2, to: 0.8, steps: {steps}}}\n"
            ),
            Path::new("a.yaml"),
        )
        .unwrap()
    }

    #[test]
    fn a_map_of_4001_squared_cases_is_drawn_from_1001_squared() {
        let l = FigureLattice::of(&manifest(4001));
        assert!(l.reduces() && !l.keeps_every());
        let kept: Vec<u64> = (0..4001u64 * 4001).filter(|&id| l.keeps(id)).collect();
        assert_eq!(kept.len(), 1001 * 1001);
        // Every 4th μ of every 4th K, the last of each axis among them.
        assert_eq!(&kept[..3], &[0, 4, 8]);
        assert_eq!(kept[1000], 4000);
        assert_eq!(kept[1001], 4 * 4001);
        assert_eq!(*kept.last().unwrap(), 4001 * 4001 - 1);
    }

    #[test]
    fn a_map_within_the_figure_resolution_keeps_every_case() {
        let l = FigureLattice::of(&manifest(1001));
        assert!(!l.reduces() && l.keeps_every());
        assert!((0..1001u64 * 1001).all(|id| l.keeps(id)));
        // 2001 values keep every other one: 1001 of them.
        let l = FigureLattice::of(&manifest(2001));
        let kept = (0..2001u64 * 2001).filter(|&id| l.keeps(id)).count();
        assert_eq!(kept, 1001 * 1001);
    }

    #[test]
    fn the_count_of_kept_cases_is_that_of_the_cases_kept() {
        // 1500 values keep every second one (750) and the last, an odd one out.
        for steps in [7, 1001, 1500, 2001] {
            let l = FigureLattice::of(&manifest(steps));
            let kept = (0..steps * steps).filter(|&id| l.keeps(id)).count();
            assert_eq!(l.kept(), kept, "{steps} values an axis");
        }
        assert_eq!(FigureLattice::of(&manifest(1500)).kept(), 751 * 751);
    }
}
