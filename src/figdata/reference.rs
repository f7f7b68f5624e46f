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

/// The continuum value of each compared quantity for every successful discrete case of the
/// run (empty when the run has no discrete case). The continuum case of the run itself is
/// used when it has one (the `continuum` entry of a `voussoirs` axis: same load case, K, μ,
/// half-angle, load position and λ); otherwise each distinct continuum scene is solved once
/// here, by the same route as the run's own cases.
pub fn continuum_references(manifest: &Manifest, layout: &RunLayout) -> Result<Vec<ReferenceRow>> {
    // A study without voussoirs has nothing to compare; only then is its plan expanded.
    let discrete = manifest.arch.voussoirs != Discretisation::Continuum
        || manifest
            .grid
            .iter()
            .any(|a| a.name == AxisName::Voussoirs && a.values.iter().any(|v| v.is_finite()));
    if !discrete {
        return Ok(Vec::new());
    }
    let total = u64::try_from(crate::plan::case_count(manifest)).unwrap_or(u64::MAX);
    let plan = crate::plan::build_slice(manifest.clone(), 0..total);
    let rows = store::read_results(&layout.results())?;
    let case_of = |r: &ResultRow| {
        usize::try_from(r.case_id)
            .ok()
            .and_then(|i| plan.cases.get(i))
            .filter(|c| c.id == r.case_id)
    };
    let stored: HashMap<SceneKey, &ResultRow> = rows
        .iter()
        .filter(|r| r.voussoirs.is_none() && &*r.status == "ok")
        .filter_map(|r| {
            let c = case_of(r)?;
            Some((key_of(c.load_case, &c.scene), r))
        })
        .collect();
    let mut solved: HashMap<SceneKey, Solution> = HashMap::new();
    let mut out = Vec::new();
    for r in rows
        .iter()
        .filter(|r| r.voussoirs.is_some() && &*r.status == "ok")
    {
        let Some(case) = case_of(r) else {
            continue;
        };
        let key = key_of(case.load_case, &case.scene);
        for &q in quantities_of(&r.find) {
            let (value, time) = if let Some(c) = stored.get(&key) {
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
    Ok(out)
}
