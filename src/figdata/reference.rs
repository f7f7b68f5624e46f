//! Continuum reference values for the cases of a discrete arch: the error of each critical
//! value against the continuum and the cost of both, for the speed-and-accuracy figure.

use crate::manifest::{AxisName, Manifest};
use crate::model::{Arch, Discretisation, Friction, WeightModel};
use crate::output::RunLayout;
use crate::scene::{self, Find, Scene, Solution};
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
        _ => &[],
    }
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
        _ => None,
    }
}

/// What makes two cases the same scene but for the voussoir count.
type SceneKey = (String, String, [u64; 3], String);

fn key_of(r: &ResultRow) -> SceneKey {
    (
        r.find.clone(),
        r.load_case.clone(),
        [
            r.k.unwrap_or(f64::NAN).to_bits(),
            r.mu.unwrap_or(f64::INFINITY).to_bits(),
            r.half_angle_deg.to_bits(),
        ],
        r.weight.clone(),
    )
}

fn continuum_scene(r: &ResultRow) -> Option<Scene> {
    let find = Find::parse(&r.find)?;
    let weight = WeightModel::parse(&r.weight)?;
    let k = r.k.unwrap_or(2.0);
    let arch = Arch::new(k, r.half_angle_deg, weight, Discretisation::Continuum).ok()?;
    let friction = r.mu.and_then(Friction::new).unwrap_or(Friction::INFINITE);
    Some(Scene::new(arch, friction, find))
}

/// The continuum value of each compared quantity for every successful discrete case of the
/// run (empty when the run has no discrete case). The continuum case of the run itself is
/// used when it has one (same find, load case, K, μ, half-angle and weight model: the
/// `continuum` entry of a `voussoirs` axis); otherwise each distinct continuum scene is
/// solved once here.
pub fn continuum_references(manifest: &Manifest, layout: &RunLayout) -> Result<Vec<ReferenceRow>> {
    let discrete = manifest.arch.voussoirs != Discretisation::Continuum
        || manifest.grid.iter().any(|a| a.name == AxisName::Voussoirs);
    // The references are the closed-form continuum of self-weight on the circular arch with
    // radial joints; other forms and live loads have none here.
    let paper = manifest.arch.form().is_circular_radial()
        && manifest.load_cases.iter().all(|l| !l.kind.is_live());
    if !discrete || !paper {
        return Ok(Vec::new());
    }
    let rows = store::read_results(&layout.results())?;
    let stored: HashMap<SceneKey, &ResultRow> = rows
        .iter()
        .filter(|r| r.voussoirs.is_none() && r.status == "ok")
        .map(|r| (key_of(r), r))
        .collect();
    let mut solved: HashMap<SceneKey, Solution> = HashMap::new();
    let mut out = Vec::new();
    for r in rows
        .iter()
        .filter(|r| r.voussoirs.is_some() && r.status == "ok")
    {
        let key = key_of(r);
        for &q in quantities_of(&r.find) {
            let (value, time) = if let Some(c) = stored.get(&key) {
                (c.value_of(q), c.solve_time_us)
            } else {
                let Some(scene) = continuum_scene(r) else {
                    continue;
                };
                let s = solved
                    .entry(key.clone())
                    .or_insert_with(|| scene::solve(&scene));
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
