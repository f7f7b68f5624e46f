//! The load_factor cases of results.parquet reduced while they are read, a block at a time:
//! the cases of the figure lattice (those the figures are drawn from, every case when no axis
//! is longer than the figures' resolution) and, over every case, the few the figure data and
//! the report single out: per load case and arch group (half-angle, voussoirs), the case of
//! least finite λ_max overall and per collapse mechanism, and the first case of least and the
//! last case of largest λ_max. The memory held does not grow with the cases beyond the
//! lattice, and every choice made from the cases is the one made from all of them.

use crate::store::{self, LoadFactorCase};
use anyhow::Result;
use std::collections::BTreeMap;
use std::path::Path;

/// Rows of results.parquet read at a time.
pub const READ_BLOCK_ROWS: usize = 1 << 18;

/// The mechanisms whose weakest case is kept.
const MECHANISMS: [&str; 3] = ["rotational", "mixed", "sliding"];

/// A load case and arch group: the load case, the half-angle's bits, the voussoirs, the
/// eccentricity's bits (none for a circular arch) and the joint planes.
type GroupKey = (String, u64, Option<u32>, Option<u64>, u8);

fn group_key(c: &LoadFactorCase) -> GroupKey {
    (
        c.load_case.clone(),
        c.half_angle_deg.to_bits(),
        c.voussoirs,
        c.eccentricity.map(f64::to_bits),
        c.joints as u8,
    )
}

/// The cases singled out in one load case and arch group.
#[derive(Debug, Clone, Default)]
struct Singled {
    /// Least finite λ_max (ties: the first row).
    weakest: Option<LoadFactorCase>,
    /// Least finite λ_max per mechanism of [`MECHANISMS`].
    weakest_of: [Option<LoadFactorCase>; 3],
    /// Least λ_max of the bounded cases, the first of equal ones.
    least: Option<LoadFactorCase>,
    /// Largest λ_max of the bounded cases, the last of equal ones.
    largest: Option<LoadFactorCase>,
}

/// Whether `c` is weaker than `than`: smaller finite λ_max, or the same and an earlier row.
fn weaker(c: &LoadFactorCase, than: Option<&LoadFactorCase>) -> bool {
    let Some(t) = than else { return true };
    let (x, y) = (c.load_factor.unwrap_or(0.0), t.load_factor.unwrap_or(0.0));
    x.total_cmp(&y).then(c.row.cmp(&t.row)).is_lt()
}

impl Singled {
    fn add(&mut self, c: &LoadFactorCase) {
        if c.load_factor.is_some_and(f64::is_finite) {
            if weaker(c, self.weakest.as_ref()) {
                self.weakest = Some(c.clone());
            }
            if let Some(i) = MECHANISMS
                .iter()
                .position(|m| c.mechanism.as_deref() == Some(*m))
                && weaker(c, self.weakest_of[i].as_ref())
            {
                self.weakest_of[i] = Some(c.clone());
            }
        }
        // Rows come in order: the first least and the last largest, as `min_by` and
        // `max_by` choose among all cases.
        let Some(v) = c.load_factor else { return };
        let lf = |o: &Option<LoadFactorCase>| o.as_ref().and_then(|c| c.load_factor);
        if lf(&self.least).is_none_or(|l| v.total_cmp(&l).is_lt()) {
            self.least = Some(c.clone());
        }
        if lf(&self.largest).is_none_or(|l| v.total_cmp(&l).is_ge()) {
            self.largest = Some(c.clone());
        }
    }

    fn cases(&self) -> impl Iterator<Item = &LoadFactorCase> {
        [&self.weakest, &self.least, &self.largest]
            .into_iter()
            .chain(&self.weakest_of)
            .flatten()
    }
}

/// The load_factor cases of a run, reduced as they are read.
#[derive(Debug, Clone, Default)]
pub struct LoadFactorCases {
    /// The cases the figures are drawn from (of the figure lattice), in row order.
    pub kept: Vec<LoadFactorCase>,
    singled: BTreeMap<GroupKey, Singled>,
}

impl LoadFactorCases {
    /// Reads the load_factor cases of results.parquet a block at a time, keeping those
    /// `keeps` (by case id, the row of a run's results.parquet) and singling out the others.
    pub fn read(path: &Path, keeps: impl Fn(u64) -> bool) -> Result<Self> {
        let mut out = LoadFactorCases::default();
        store::read_load_factor_cases_in_blocks(path, READ_BLOCK_ROWS, |block| {
            for c in &block {
                out.singled.entry(group_key(c)).or_default().add(c);
            }
            out.kept
                .extend(block.into_iter().filter(|c| keeps(c.row as u64)));
            Ok(())
        })?;
        Ok(out)
    }

    /// The cases singled out over every case, in row order, each once: every choice of the
    /// weakest, least or largest λ_max of a load case or arch group among all the cases is
    /// among them.
    pub fn singled(&self) -> Vec<LoadFactorCase> {
        let mut v: Vec<LoadFactorCase> = self
            .singled
            .values()
            .flat_map(Singled::cases)
            .cloned()
            .collect();
        v.sort_by_key(|c| c.row);
        v.dedup_by_key(|c| c.row);
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn case(row: usize, group: Option<u32>, lambda: Option<f64>, mech: &str) -> LoadFactorCase {
        LoadFactorCase {
            row,
            load_case: "h".into(),
            k: 1.2,
            mu: 0.5,
            half_angle_deg: 90.0,
            voussoirs: group,
            eccentricity: None,
            joints: crate::model::JointOrientation::Radial,
            at_deg: None,
            at_x: None,
            load_factor: lambda,
            mechanism: Some(mech.into()),
            collapse_below: None,
            sliding_at_load: 0,
        }
    }

    #[test]
    fn the_weakest_least_and_largest_cases_are_those_of_all_cases() {
        let cases = vec![
            case(0, None, Some(0.30), "mixed"),
            case(1, None, Some(0.20), "rotational"),
            case(2, None, None, "rotational"),
            case(3, None, Some(0.20), "rotational"),
            case(4, None, Some(0.50), "sliding"),
            case(5, None, Some(0.50), "mixed"),
            case(6, None, Some(0.25), "mixed"),
            case(7, Some(8), Some(0.10), "sliding"),
        ];
        let mut s = BTreeMap::<GroupKey, Singled>::new();
        for c in &cases {
            s.entry(group_key(c)).or_default().add(c);
        }
        let r = LoadFactorCases {
            kept: Vec::new(),
            singled: s,
        };
        let rows: Vec<usize> = r.singled().iter().map(|c| c.row).collect();
        // Continuum: weakest 1 (the first of 0.20), rotational 1, mixed 6, sliding 4, least
        // 1, largest 5 (the last of 0.50); eight voussoirs: 7.
        assert_eq!(rows, vec![1, 4, 5, 6, 7]);
    }
}
