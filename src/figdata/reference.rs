//! Continuum reference values for the cases of a discrete arch: the error of each critical
//! value against the continuum and the cost of both, for the speed-and-accuracy figure.

use crate::manifest::{AxisName, Manifest};
use crate::model::Discretisation;
use crate::output::RunLayout;
use crate::scene::{self, Scene, Solution};
use crate::store::{self, ReferenceRow, ResultRow};
use anyhow::Result;
use std::collections::HashMap;

/// The results columns compared with the continuum for each find.
pub fn quantities_of(find: &str) -> &'static [&'static str] {
    match find {
        "thickness" => &["k_crit"],
        "friction" => &["mu_crit"],
        "thrust" => &["thrust_min"],
        "state" => &["thrust_r_min"],
        "thresholds" => &[
            "k_c_rotational",
            "mu_rotational_mixed",
            "mu_min",
            "k_mixed_sliding",
        ],
        "load_factor" => &["load_factor"],
        _ => &[],
    }
}

/// The find whose results column `quantity` is (the inverse of [`quantities_of`]).
pub fn find_of_quantity(quantity: &str) -> Option<&'static str> {
    crate::scene::Find::ALL
        .iter()
        .map(|f| f.as_str())
        .find(|f| quantities_of(f).contains(&quantity))
}

fn value_of(s: &Solution, quantity: &str) -> Option<f64> {
    match quantity {
        "k_crit" => s.k_crit,
        "mu_crit" => s.mu_crit,
        "thrust_min" => s.thrust_min,
        "thrust_r_min" => s.thrust_r_min,
        "k_c_rotational" => s.k_c_rotational,
        "mu_rotational_mixed" => s.mu_rotational_mixed,
        "mu_min" => s.mu_min,
        "k_mixed_sliding" => s.k_mixed_sliding,
        "load_factor" => s.load_factor,
        _ => None,
    }
}

/// What makes two cases the same scene but for the voussoir count: the load case and the
/// bits of K, μ, α, the position of a point load and λ.
type SceneKey = (usize, [u64; 5]);

fn key_of(load_case: usize, s: &Scene) -> SceneKey {
    (
        load_case,
        [
            s.arch.k.to_bits(),
            s.friction.mu().to_bits(),
            s.arch.half_angle.to_bits(),
            s.load.at_deg().unwrap_or(f64::NAN).to_bits(),
            s.lambda.to_bits(),
        ],
    )
}

/// Rows of results.parquet compared at a time, and the most continuum rows read for them at
/// once (their counterparts lie in a window of about this many rows).
const BLOCK_ROWS: usize = 1 << 16;

/// Continuum scenes solved here kept for the cases after them (cleared when full: solved
/// again if met later, to the same values).
const SOLVED_CACHE: usize = 1 << 16;

/// Where the continuum case of a discrete case lies in the plan: per load case, its first
/// case id, its number of cases, and the stride and number of positions of its voussoir axis
/// with the position of the continuum (None when it has no continuum entry).
struct Counterparts {
    load_cases: Vec<(u64, u64, Option<VoussoirAxis>)>,
}

/// A load case's voussoir axis in the plan: its stride, its number of positions and the
/// position of its continuum entry.
type VoussoirAxis = (u64, u64, u64);

impl Counterparts {
    fn of(m: &Manifest) -> Self {
        let mut first = 0u64;
        let mut load_cases = Vec::new();
        for lc in &m.load_cases {
            let dims = crate::plan::load_case_dims(m, lc);
            let count: u64 = dims.iter().product();
            let axis = m.grid.iter().enumerate().find_map(|(d, a)| {
                let c = a.values.iter().position(|v| v.is_infinite())?;
                (a.name == AxisName::Voussoirs && lc.spans(a.name))
                    .then(|| (dims[d + 1..].iter().product(), dims[d], c as u64))
            });
            load_cases.push((first, count, axis));
            first += count;
        }
        Counterparts { load_cases }
    }

    /// The id of the continuum case of case `id`: the same case but for its voussoirs.
    fn of_case(&self, id: u64) -> Option<u64> {
        let &(first, _, axis) = self
            .load_cases
            .iter()
            .find(|(first, count, _)| id >= *first && id - first < *count)?;
        let (stride, n, c) = axis?;
        let at = (id - first) / stride % n;
        Some(id - at * stride + c * stride)
    }
}

/// The continuum rows of results.parquet among `ids` (sorted), read a window at a time.
fn continuum_rows(path: &std::path::Path, ids: &[u64]) -> Result<HashMap<u64, ResultRow>> {
    let mut out = HashMap::new();
    let mut rest = ids;
    while let Some(&start) = rest.first() {
        let n = rest.partition_point(|&i| i < start + BLOCK_ROWS as u64);
        let span = rest[n - 1] - start + 1;
        let offset = usize::try_from(start)?;
        for r in store::read_results_rows(path, (offset, usize::try_from(span)?))? {
            if rest[..n].binary_search(&r.case_id).is_ok() {
                out.insert(r.case_id, r);
            }
        }
        rest = &rest[n..];
    }
    Ok(out)
}

/// The continuum value of each compared quantity for every successful discrete case of the
/// run (empty when the run has no discrete case). The continuum case of the run itself is
/// used when it has one (the `continuum` entry of a `voussoirs` axis: same load case, K, μ,
/// half-angle, load position and λ); otherwise each distinct continuum scene is solved once
/// here, by the same route as the run's own cases. results.parquet is read a block at a
/// time, with the continuum rows of the block's cases, and only the block's cases are
/// expanded: the memory held besides the rows returned does not grow with the cases.
pub fn continuum_references(manifest: &Manifest, layout: &RunLayout) -> Result<Vec<ReferenceRow>> {
    // A study without voussoirs has nothing to compare.
    let discrete = manifest.arch.voussoirs != Discretisation::Continuum
        || manifest
            .grid
            .iter()
            .any(|a| a.name == AxisName::Voussoirs && a.values.iter().any(|v| v.is_finite()));
    if !discrete {
        return Ok(Vec::new());
    }
    let path = layout.results();
    let counterparts = Counterparts::of(manifest);
    let mut solved: HashMap<SceneKey, Solution> = HashMap::new();
    let mut out = Vec::new();
    store::read_results_in_blocks(&path, BLOCK_ROWS, |offset, rows| {
        let first = offset as u64;
        let plan = crate::plan::build_slice(manifest.clone(), first..first + rows.len() as u64);
        let case_of = |r: &ResultRow| {
            r.case_id
                .checked_sub(first)
                .and_then(|i| usize::try_from(i).ok())
                .and_then(|i| plan.cases.get(i))
                .filter(|c| c.id == r.case_id)
        };
        let discrete: Vec<&ResultRow> = rows
            .iter()
            .filter(|r| r.voussoirs.is_some() && &*r.status == "ok")
            .collect();
        let mut wanted: Vec<u64> = discrete
            .iter()
            .filter_map(|r| counterparts.of_case(r.case_id))
            .collect();
        wanted.sort_unstable();
        wanted.dedup();
        let stored = continuum_rows(&path, &wanted)?;
        for r in discrete {
            let Some(case) = case_of(r) else {
                continue;
            };
            let own = counterparts
                .of_case(r.case_id)
                .and_then(|id| stored.get(&id))
                .filter(|c| c.voussoirs.is_none() && &*c.status == "ok");
            let key = key_of(case.load_case, &case.scene);
            if own.is_none() && !solved.contains_key(&key) && solved.len() >= SOLVED_CACHE {
                solved.clear();
            }
            for &q in quantities_of(&r.find) {
                let (value, time) = if let Some(c) = own {
                    (c.value_of(q), c.solve_time_us)
                } else {
                    let mut scene = case.scene;
                    scene.arch.joints = Discretisation::Continuum;
                    let s = solved.entry(key).or_insert_with(|| scene::solve(&scene));
                    (value_of(s, q), s.solve_time_us)
                };
                out.push(ReferenceRow {
                    case_id: r.case_id,
                    quantity: q.to_string(),
                    continuum_value: value,
                    continuum_solve_time_us: time,
                });
            }
        }
        Ok(())
    })?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    /// The counterpart found from a case id is the continuum case of the same scene, found
    /// by its key over the whole plan, whatever the order of the axes.
    #[test]
    fn the_continuum_case_of_a_discrete_case_is_found_from_its_id() {
        for text in [
            "name: a\ngrid:\n  voussoirs: {values: [6, continuum, 12]}\n  k: {values: [1.1, 1.2]}\n  mu: {values: [0.3, 0.6, inf]}\n",
            "name: b\nfind: load_factor\nload_cases:\n  - {name: h, kind: horizontal}\n  - {name: p, kind: point, at_deg: 30}\ngrid:\n  k: {values: [1.1, 1.2, 1.3]}\n  voussoirs: {values: [8, 16, continuum]}\n  mu: {values: [0.4, 0.7]}\n",
            "name: c\nfind: thickness\ngrid:\n  mu: {values: [0.3, 0.6]}\n  voussoirs: {values: [continuum, 6]}\n",
        ] {
            let m = crate::manifest::parse(text, Path::new("s.yaml")).unwrap();
            let plan = crate::plan::build(m.clone()).unwrap();
            let counterparts = Counterparts::of(&m);
            let continuum =
                |c: &crate::plan::Case| c.scene.arch.joints == Discretisation::Continuum;
            let mut found = 0;
            for c in plan.cases.iter().filter(|c| !continuum(c)) {
                let key = key_of(c.load_case, &c.scene);
                let by_key: Vec<u64> = (plan.cases.iter())
                    .filter(|o| continuum(o) && key_of(o.load_case, &o.scene) == key)
                    .map(|o| o.id)
                    .collect();
                assert_eq!(by_key.len(), 1, "{text}");
                assert_eq!(
                    counterparts.of_case(c.id),
                    Some(by_key[0]),
                    "{text}: case {}",
                    c.id
                );
                found += 1;
            }
            assert!(found >= 2, "{text}");
        }
        // No continuum entry: nothing to find.
        let m = crate::manifest::parse(
            "name: d\ngrid:\n  voussoirs: {values: [6, 8]}\n  k: {values: [1.2]}\n  mu: {values: [0.5]}\n",
            Path::new("s.yaml"),
        )
        .unwrap();
        assert_eq!(Counterparts::of(&m).of_case(0), None);
    }
}
