//! The plan: the cartesian product of the grid axes and the load cases, in a stable order
//! with stable case ids (load case outermost, then the axes in manifest plan order, μ
//! innermost).

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
    m.grid
        .iter()
        .map(|a| a.values.len() as u128)
        .product::<u128>()
        * m.load_cases.len() as u128
}

/// Expands a manifest into its cases.
pub fn build(manifest: Manifest) -> Result<Plan, PlanTooLarge> {
    let requested = case_count(&manifest);
    if requested > u128::from(MAX_CASES) {
        return Err(PlanTooLarge { requested });
    }
    let mut cases = Vec::with_capacity(requested as usize);
    let dims: Vec<usize> = manifest.grid.iter().map(|a| a.values.len()).collect();
    let per_lc: usize = dims.iter().product();
    let mut id = 0u64;
    for (lc, _) in manifest.load_cases.iter().enumerate() {
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
    for (axis, &i) in m.grid.iter().zip(idx) {
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
    let case = m.load_cases.get(lc);
    Scene {
        arch,
        friction,
        find: m.find,
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
        self.manifest.find == Find::State
            && self.manifest.arch.form().is_circular_radial()
            && self.manifest.load_cases.iter().all(|l| !l.kind.is_live())
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
                d.push(')');
                d
            })
            .collect();
        s.push_str(&format!("load cases: {}\n", names.join(", ")));
        s.push_str(&format!("cases: {}\n", self.cases.len()));
        s
    }
}
