//! Continuum reference values for the cases of a discrete arch: the error of each critical
//! value against the continuum and the cost of both, for the speed-and-accuracy figure.

use crate::manifest::{AxisName, Manifest};
use crate::model::{Arch, Discretisation, Friction, WeightModel};
use crate::output::RunLayout;
use crate::scene::{self, Find, Scene, Solution};
use crate::store::{self, ReferenceRow, ResultRow};
use anyhow::Result;
use std::collections::HashMap;

/// The results column compared with the continuum for each find.
pub fn quantity_of(find: &str) -> Option<&'static str> {
    match find {
        "thickness" => Some("k_crit"),
        "friction" => Some("mu_crit"),
        "thrust" => Some("thrust_min"),
        "state" => Some("thrust_r_min"),
        _ => None,
    }
}

fn value_of(s: &Solution, quantity: &str) -> Option<f64> {
    match quantity {
        "k_crit" => s.k_crit,
        "mu_crit" => s.mu_crit,
        "thrust_min" => s.thrust_min,
        "thrust_r_min" => s.thrust_r_min,
        _ => None,
    }
}

fn continuum_scene(r: &ResultRow) -> Option<Scene> {
    let find = Find::parse(&r.find)?;
    let weight = WeightModel::parse(&r.weight)?;
    let k = r.k.unwrap_or(2.0);
    let arch = Arch::new(k, r.half_angle_deg, weight, Discretisation::Continuum).ok()?;
    let friction = r.mu.and_then(Friction::new).unwrap_or(Friction::INFINITE);
    Some(Scene::new(arch, friction, find))
}

/// The continuum value of the compared quantity for every successful discrete case of the
/// run (empty when the run has no discrete case). Each distinct continuum scene is solved
/// once.
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
    let mut cache: HashMap<[u64; 4], (Option<f64>, f64)> = HashMap::new();
    let mut out = Vec::new();
    for r in rows
        .iter()
        .filter(|r| r.voussoirs.is_some() && r.status == "ok")
    {
        let (Some(q), Some(scene)) = (quantity_of(&r.find), continuum_scene(r)) else {
            continue;
        };
        let key = [
            scene.arch.k.to_bits(),
            scene.friction.mu().to_bits(),
            scene.arch.half_angle.to_bits(),
            u64::from(scene.arch.weight == WeightModel::Centreline),
        ];
        let (value, time) = *cache.entry(key).or_insert_with(|| {
            let s = scene::solve(&scene);
            (value_of(&s, q), s.solve_time_us)
        });
        out.push(ReferenceRow {
            case_id: r.case_id,
            quantity: q.to_string(),
            continuum_value: value,
            continuum_solve_time_us: time,
        });
    }
    Ok(out)
}
