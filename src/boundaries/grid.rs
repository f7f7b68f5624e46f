//! The results of a run as K × μ grids: one per load case and per value of the other axes
//! (half-angle, voussoirs, position of a point load), with the K and μ values sorted (a
//! `values:` list may be in any order).

use crate::engine::{CaseResult, Status};
use crate::model::Arch;
use crate::plan::Plan;
use crate::scene::Scene;
use std::collections::HashMap;

/// One K × μ grid of results.
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
    /// Index into the results of the case at (K index i, μ index j): `cells[j * ks.len() + i]`.
    cells: Vec<Option<usize>>,
}

impl Grid {
    /// The result index at (K index, μ index), when that case exists.
    pub fn cell(&self, i: usize, j: usize) -> Option<usize> {
        self.cells.get(j * self.ks.len() + i).copied().flatten()
    }
}

/// The result of a cell when its analysis ran.
pub(crate) fn ok_result<'a>(
    results: &'a [CaseResult],
    grid: &Grid,
    i: usize,
    j: usize,
) -> Option<&'a CaseResult> {
    let r = results.get(grid.cell(i, j)?)?;
    (r.status == Status::Ok).then_some(r)
}

/// Group key: load case, half-angle bits, discretisation and point-load position bits (as
/// an angle, as x/L).
type Key = (
    usize,
    u64,
    crate::model::Discretisation,
    Option<u64>,
    Option<u64>,
);

fn sorted_distinct(mut v: Vec<f64>) -> Vec<f64> {
    v.sort_by(f64::total_cmp);
    v.dedup_by(|a, b| a.to_bits() == b.to_bits());
    v
}

/// Splits the cases of a plan into grids, in order of first appearance. `results[n]` must be
/// the result of `plan.cases[n]`; cases without a matching result are left empty.
pub(crate) fn groups(plan: &Plan, results: &[CaseResult]) -> Vec<Grid> {
    let mut index: HashMap<Key, usize> = HashMap::new();
    let mut members: Vec<Vec<usize>> = Vec::new();
    let mut grids: Vec<Grid> = Vec::new();
    for (n, case) in plan.cases.iter().enumerate() {
        if results.get(n).map(|r| r.case_id) != Some(case.id) {
            continue;
        }
        let a = &case.scene.arch;
        // A group per position as given: an x/L position's angle moves with K.
        let at = case.scene.load.at_deg().map(f64::to_bits);
        let at_x = case.scene.load.at_x().map(f64::to_bits);
        let key = (case.load_case, a.half_angle.to_bits(), a.joints, at, at_x);
        let g = *index.entry(key).or_insert_with(|| {
            grids.push(Grid {
                load_case: case.load_case,
                arch: *a,
                scene: case.scene,
                ks: Vec::new(),
                mus: Vec::new(),
                cells: Vec::new(),
            });
            members.push(Vec::new());
            grids.len() - 1
        });
        members[g].push(n);
    }
    for (grid, cases) in grids.iter_mut().zip(&members) {
        let k_of = |n: usize| plan.cases[n].scene.arch.k;
        let mu_of = |n: usize| plan.cases[n].scene.friction.mu();
        grid.ks = sorted_distinct(cases.iter().map(|&n| k_of(n)).collect());
        grid.mus = sorted_distinct(cases.iter().map(|&n| mu_of(n)).collect());
        grid.cells = vec![None; grid.ks.len() * grid.mus.len()];
        for &n in cases {
            let i = grid.ks.binary_search_by(|x| x.total_cmp(&k_of(n)));
            let j = grid.mus.binary_search_by(|x| x.total_cmp(&mu_of(n)));
            if let (Ok(i), Ok(j)) = (i, j) {
                grid.cells[j * grid.ks.len() + i] = Some(n);
            }
        }
    }
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
pub(crate) fn regimes(grid: &Grid, results: &[CaseResult]) -> Vec<Option<crate::analysis::Regime>> {
    let (nk, nmu) = (grid.ks.len(), grid.mus.len());
    (0..nmu)
        .flat_map(|j| (0..nk).map(move |i| (i, j)))
        .map(|(i, j)| ok_result(results, grid, i, j).and_then(|r| r.solution.regime()))
        .collect()
}
