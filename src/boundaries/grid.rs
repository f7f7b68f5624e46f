//! The answers of a run as K × μ grids: one per load case and per value of the other axes
//! (half-angle, eccentricity, joints, voussoirs, position of a point load), with the K and μ values sorted (a
//! `values:` list may be in any order). A grid holds one byte per case, the case's
//! [cell code](super::cells), read from the plan chunk by chunk: neither the whole plan nor
//! the engine's rows are held.

use super::cells::{self, NO_CELL};
use crate::manifest::Manifest;
use crate::model::Arch;
use crate::plan;
use crate::scene::Scene;
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

/// One K × μ grid of answers.
#[derive(Debug, Clone)]
pub(crate) struct Grid {
    /// Index of the load case in the manifest.
    pub load_case: usize,
    /// The arch of the first case of the group (its K is one of the grid's).
    pub arch: Arch,
    /// The scene of the first case of the group (form, load, λ, find; its K and μ are two of
    /// the grid's).
    pub scene: Scene,
    /// Distinct K values, increasing.
    pub ks: Vec<f64>,
    /// Distinct μ values, increasing (may end with +∞).
    pub mus: Vec<f64>,
    /// The cell code of the case at (K index i, μ index j): `codes[j * ks.len() + i]`.
    codes: Vec<u8>,
}

impl Grid {
    /// The cell code at (K index, μ index), [`NO_CELL`] when that case is missing or failed.
    pub fn code(&self, i: usize, j: usize) -> u8 {
        self.codes
            .get(j * self.ks.len() + i)
            .copied()
            .unwrap_or(NO_CELL)
    }

    /// The compared answer at (K index, μ index), when the case ran.
    pub fn cell(&self, i: usize, j: usize) -> Option<cells::Cell> {
        cells::decode(self.code(i, j))
    }
}

/// Group key: load case, half-angle bits, discretisation, point-load position bits (as an
/// angle, as x/L) and form ([`crate::model::ArchForm::key`]).
type Key = (
    usize,
    u64,
    crate::model::Discretisation,
    Option<u64>,
    Option<u64>,
    (bool, u64, crate::model::JointOrientation, bool),
);

/// The group of a case: one for each load case and each value of the axes that
/// [`crate::manifest::AxisName::splits_groups`] (the arch and the load's position).
fn key_of(case: &plan::Case) -> Key {
    let a = &case.scene.arch;
    // A group per position as given: an x/L position's angle moves with K.
    let at = case.scene.load.at_deg().map(f64::to_bits);
    let at_x = case.scene.load.at_x().map(f64::to_bits);
    (
        case.load_case,
        a.half_angle.to_bits(),
        a.joints,
        at,
        at_x,
        case.scene.form.key(),
    )
}

fn sorted_distinct(set: &HashSet<u64>) -> Vec<f64> {
    let mut v: Vec<f64> = set.iter().map(|&b| f64::from_bits(b)).collect();
    v.sort_by(f64::total_cmp);
    v
}

/// Cases of the plan expanded at a time while the grids are built.
const PLAN_CHUNK: u64 = 1 << 16;

/// Calls `each` on every case of a manifest's plan, in id order, expanding a chunk at a time.
fn for_each_case(m: &Manifest, mut each: impl FnMut(&plan::Case)) {
    let total = u64::try_from(plan::case_count(m)).unwrap_or(u64::MAX);
    let mut start = 0;
    while start < total {
        let end = (start + PLAN_CHUNK).min(total);
        for case in &plan::build_slice(m.clone(), start..end).cases {
            each(case);
        }
        start = end;
    }
}

/// Splits the cases of a manifest's plan into grids, in order of first appearance;
/// `codes[n]` is the cell code of case n ([`NO_CELL`] past the end of `codes`).
pub(crate) fn groups(m: &Manifest, codes: &[u8]) -> Vec<Grid> {
    let mut index: HashMap<Key, usize> = HashMap::default();
    let mut grids: Vec<Grid> = Vec::new();
    let mut values: Vec<(HashSet<u64>, HashSet<u64>)> = Vec::new();
    let mut last: Option<(Key, usize)> = None;
    let mut group_of = |case: &plan::Case, grids: &mut Vec<Grid>| -> usize {
        let key = key_of(case);
        if let Some((k, g)) = last
            && k == key
        {
            return g;
        }
        let g = *index.entry(key).or_insert_with(|| {
            grids.push(Grid {
                load_case: case.load_case,
                arch: case.scene.arch,
                scene: case.scene,
                ks: Vec::new(),
                mus: Vec::new(),
                codes: Vec::new(),
            });
            grids.len() - 1
        });
        last = Some((key, g));
        g
    };
    // The value of an axis often repeats from one case to the next: a repeat is not hashed.
    let mut previous: Option<(usize, u64, u64)> = None;
    for_each_case(m, |case| {
        let g = group_of(case, &mut grids);
        if values.len() <= g {
            values.resize_with(g + 1, Default::default);
        }
        let (k, mu) = (
            case.scene.arch.k.to_bits(),
            case.scene.friction.mu().to_bits(),
        );
        let before = previous.replace((g, k, mu));
        if before.is_none_or(|(bg, bk, _)| (bg, bk) != (g, k)) {
            values[g].0.insert(k);
        }
        if before.is_none_or(|(bg, _, bm)| (bg, bm) != (g, mu)) {
            values[g].1.insert(mu);
        }
    });
    for (grid, (ks, mus)) in grids.iter_mut().zip(&values) {
        grid.ks = sorted_distinct(ks);
        grid.mus = sorted_distinct(mus);
        grid.codes = vec![NO_CELL; grid.ks.len() * grid.mus.len()];
    }
    for_each_case(m, |case| {
        let g = group_of(case, &mut grids);
        let grid = &mut grids[g];
        let (k, mu) = (case.scene.arch.k, case.scene.friction.mu());
        let i = grid.ks.binary_search_by(|x| x.total_cmp(&k));
        let j = grid.mus.binary_search_by(|x| x.total_cmp(&mu));
        let code = usize::try_from(case.id)
            .ok()
            .and_then(|n| codes.get(n))
            .copied()
            .unwrap_or(NO_CELL);
        if let (Ok(i), Ok(j)) = (i, j) {
            let nk = grid.ks.len();
            grid.codes[j * nk + i] = code;
        }
    });
    grids
}

/// The boundary points of every μ row and then every K column of a grid, each line refined
/// in parallel; `row(j)` and `column(i)` give the points of one line.
pub(crate) fn every_line<R, C>(grid: &Grid, row: R, column: C) -> Vec<super::BoundaryPoint>
where
    R: Fn(usize) -> Vec<super::BoundaryPoint> + Sync + Send,
    C: Fn(usize) -> Vec<super::BoundaryPoint> + Sync + Send,
{
    use rayon::prelude::*;
    let rows: Vec<Vec<super::BoundaryPoint>> =
        (0..grid.mus.len()).into_par_iter().map(row).collect();
    let cols: Vec<Vec<super::BoundaryPoint>> =
        (0..grid.ks.len()).into_par_iter().map(column).collect();
    rows.into_iter().chain(cols).flatten().collect()
}

/// The regime of every cell, μ row by μ row (`None` where the case failed or is missing).
pub(crate) fn regimes(grid: &Grid) -> Vec<Option<crate::analysis::Regime>> {
    grid.codes.iter().map(|&c| cells::regime(c)).collect()
}
