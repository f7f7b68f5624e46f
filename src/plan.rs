//! The plan: the cartesian product of the grid axes and the load cases, in a stable order
//! with stable case ids (load case outermost, then the axes in manifest plan order, μ
//! innermost). A load case spans the axes its find uses: a `thresholds` load case in a study
//! whose other load cases have k and mu axes has one case per value of the other axes.

use crate::manifest::{AxisName, LoadCase, Manifest};
use crate::model::{Arch, Discretisation, Friction, Load, k_from_t_over_r};
use crate::scene::{Find, Scene};

/// Largest number of cases a study may ask for.
pub const MAX_CASES: u64 = 20_000_000;

/// One case of a study.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// Position in the plan (stable: the same manifest gives the same ids).
    pub id: u64,
    /// Index of the load case in the manifest.
    pub load_case: usize,
    /// The scene.
    pub scene: Scene,
}

/// The validated plan of a study.
#[derive(Debug, Clone)]
pub struct Plan {
    /// The manifest it comes from.
    pub manifest: Manifest,
    /// The cases, in id order.
    pub cases: Vec<Case>,
}

/// A plan too large to run.
#[derive(Debug, thiserror::Error)]
#[error(
    "the study asks for {requested} cases, more than the {MAX_CASES} allowed: reduce the steps of the grid axes"
)]
pub struct PlanTooLarge {
    /// Number of cases asked for.
    pub requested: u128,
}

/// Number of cases a manifest asks for.
pub fn case_count(m: &Manifest) -> u128 {
    m.load_cases
        .iter()
        .map(|lc| {
            m.grid
                .iter()
                .filter(|a| lc.spans(a.name))
                .map(|a| a.values.len() as u128)
                .product::<u128>()
        })
        .sum()
}

/// Expands a manifest into its cases.
pub fn build(manifest: Manifest) -> Result<Plan, PlanTooLarge> {
    let requested = case_count(&manifest);
    if requested > u128::from(MAX_CASES) {
        return Err(PlanTooLarge { requested });
    }
    let mut cases = Vec::with_capacity(requested as usize);
    let mut id = 0u64;
    for (lc, load_case) in manifest.load_cases.iter().enumerate() {
        // An axis this load case does not span has a single position (never read: the
        // scene finds that parameter itself).
        let dims: Vec<usize> = manifest
            .grid
            .iter()
            .map(|a| {
                if load_case.spans(a.name) {
                    a.values.len()
                } else {
                    1
                }
            })
            .collect();
        let per_lc: usize = dims.iter().product();
        let mut idx = vec![0usize; dims.len()];
        for _ in 0..per_lc {
            let scene = scene_at(&manifest, lc, &idx);
            cases.push(Case {
                id,
                load_case: lc,
                scene,
            });
            id += 1;
            // Odometer increment, last axis fastest.
            for d in (0..dims.len()).rev() {
                idx[d] += 1;
                if idx[d] < dims[d] {
                    break;
                }
                idx[d] = 0;
            }
        }
    }
    Ok(Plan { manifest, cases })
}

fn scene_at(m: &Manifest, lc: usize, idx: &[usize]) -> Scene {
    let mut half = m.arch.half_angle_deg;
    let mut at_deg = None;
    let mut joints = m.arch.voussoirs;
    // K for finds that do not use it: a placeholder the analysis ignores.
    let mut k = 2.0;
    let mut mu = f64::INFINITY;
    let case = m.load_cases.get(lc);
    for (axis, &i) in m.grid.iter().zip(idx) {
        if case.is_some_and(|c| !c.spans(axis.name)) {
            continue;
        }
        let v = axis.values[i];
        match axis.name {
            AxisName::K => k = v,
            AxisName::TOverR => k = k_from_t_over_r(v),
            AxisName::Mu => mu = v,
            AxisName::HalfAngleDeg => half = v,
            AxisName::Voussoirs => {
                joints = if v.is_infinite() {
                    Discretisation::Continuum
                } else {
                    Discretisation::Voussoirs(v as u32)
                }
            }
            AxisName::AtDeg => at_deg = Some(v),
        }
    }
    // Every value was validated with the manifest, so the constructors cannot fail.
    let arch = Arch {
        k,
        half_angle: half.to_radians(),
        weight: m.arch.weight,
        joints,
    };
    let friction = Friction::new(mu).unwrap_or(Friction::INFINITE);
    Scene {
        arch,
        friction,
        find: case.map_or(m.find, |c| c.find),
        form: m.arch.form(),
        load: case.map_or(Load::SelfWeight, |c| c.load(at_deg)),
        lambda: case.and_then(|c| c.lambda).unwrap_or(0.0),
    }
}

impl Plan {
    /// The load case of a case.
    pub fn load_case(&self, c: &Case) -> &LoadCase {
        &self.manifest.load_cases[c.load_case]
    }

    /// True when every case is a symmetric self-weight `state` query on a circular arch with
    /// radial joints, so the grid can use the separable structure (H^r depends on K only,
    /// H^s on μ only). Live loads and other forms go case by case through the general
    /// formulation.
    pub fn is_separable_state_grid(&self) -> bool {
        self.manifest.arch.form().is_circular_radial()
            && self
                .manifest
                .load_cases
                .iter()
                .all(|l| l.find == Find::State && !l.kind.is_live())
    }

    /// A readable description of the plan for `archstudy check`.
    pub fn describe(&self) -> String {
        let m = &self.manifest;
        let mut s = format!("study `{}`: find {}\n", m.name, m.find);
        let shape = match m.arch.eccentricity {
            Some(e) => format!("{} (e = {e})", m.arch.shape),
            None => m.arch.shape.to_string(),
        };
        s.push_str(&format!(
            "arch: {} α = {}°, {} joints, {} weight, {}\n",
            shape, m.arch.half_angle_deg, m.arch.joints, m.arch.weight, m.arch.voussoirs
        ));
        for a in &m.grid {
            let first = a.values.first().copied().unwrap_or(f64::NAN);
            let last = a.values.last().copied().unwrap_or(f64::NAN);
            s.push_str(&format!(
                "axis {}: {} values from {} to {}\n",
                a.name.as_str(),
                a.values.len(),
                first,
                last
            ));
        }
        let names: Vec<String> = m
            .load_cases
            .iter()
            .map(|l| {
                let mut d = format!("{} ({}", l.name, l.kind.as_str());
                if let Some(a) = l.at_deg {
                    d.push_str(&format!(" at {a}°"));
                }
                if let Some(x) = l.lambda {
                    d.push_str(&format!(", λ = {x}"));
                }
                if l.find != m.find {
                    d.push_str(&format!(", find {}", l.find));
                }
                d.push(')');
                d
            })
            .collect();
        s.push_str(&format!("load cases: {}\n", names.join(", ")));
        s.push_str(&format!("cases: {}\n", self.cases.len()));
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    #[test]
    fn load_cases_span_the_axes_of_their_own_find() {
        let m = crate::manifest::parse(
            "name: a
grid:
  voussoirs: {values: [8, 64, continuum]}
  t_over_r: {values: [0.15, 0.2]}
  mu: {values: [0.4]}
load_cases:
  - {name: gravity, kind: self_weight}
  - {name: wind, kind: horizontal, find: load_factor}
find: thresholds
",
            Path::new("a.yaml"),
        )
        .unwrap();
        assert_eq!(case_count(&m), 3 + 3 * 2);
        let plan = build(m).unwrap();
        let ids: Vec<u64> = plan.cases.iter().map(|c| c.id).collect();
        assert_eq!(ids, (0..9).collect::<Vec<_>>());
        let (gravity, wind) = plan.cases.split_at(3);
        assert!(
            gravity
                .iter()
                .all(|c| c.load_case == 0 && c.scene.find == Find::Thresholds)
        );
        assert_eq!(
            gravity
                .iter()
                .map(|c| c.scene.arch.joints)
                .collect::<Vec<_>>(),
            [
                Discretisation::Voussoirs(8),
                Discretisation::Voussoirs(64),
                Discretisation::Continuum
            ]
        );
        assert!(
            wind.iter()
                .all(|c| c.load_case == 1 && c.scene.find == Find::LoadFactor)
        );
        // K varies inside the voussoir count, μ innermost.
        let k = |t| k_from_t_over_r(t);
        let got: Vec<(Discretisation, f64, f64)> = wind
            .iter()
            .map(|c| (c.scene.arch.joints, c.scene.arch.k, c.scene.friction.mu()))
            .collect();
        assert_eq!(got[0], (Discretisation::Voussoirs(8), k(0.15), 0.4));
        assert_eq!(got[1], (Discretisation::Voussoirs(8), k(0.2), 0.4));
        assert_eq!(got[5], (Discretisation::Continuum, k(0.2), 0.4));
        assert!(!plan.is_separable_state_grid());
        assert!(
            plan.describe()
                .contains("wind (horizontal, find load_factor)")
        );
    }
}
