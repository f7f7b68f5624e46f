//! The plan: the cartesian product of the grid axes and the load cases, in a stable order
//! with stable case ids (load case outermost, then the axes in manifest plan order, μ
//! innermost). A load case spans the axes its find uses: a `thresholds` load case in a study
//! whose other load cases have k and mu axes has one case per value of the other axes.

use crate::manifest::{AxisName, LoadCase, Manifest, ParamName};
use crate::model::{Arch, Discretisation, Friction, Load, Shape, k_from_t_over_r};
use crate::sampling::Design;
use crate::scene::{Find, Scene};

/// The index of `x` among the increasing values `v` of a grid axis, within a relative
/// tolerance of 1e-9 (a value read back from a file or computed from the axis).
pub fn axis_index(v: &[f64], x: f64) -> Option<usize> {
    let i = v.partition_point(|&g| g < x);
    let tol = 1e-9 * (1.0 + x.abs());
    [i.checked_sub(1), Some(i)]
        .into_iter()
        .flatten()
        .filter(|&i| i < v.len())
        .find(|&i| (v[i] - x).abs() <= tol)
}

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
    "the study asks for {requested} cases, more than the {MAX_CASES} one run holds in memory: run it in shards, `archstudy run STUDY --shard I/N` with N ≥ {}, then `archstudy merge`, or reduce the steps of the grid axes (or the samples of a study of uncertain parameters)",
    requested.div_ceil(u128::from(MAX_CASES))
)]
pub struct PlanTooLarge {
    /// Number of cases asked for.
    pub requested: u128,
}

/// Number of cases a manifest asks for: the grid points of each load case, times the sample
/// rows of a sampling study.
pub fn case_count(m: &Manifest) -> u128 {
    let rows = m
        .sampling
        .as_ref()
        .map_or(1, |s| u128::from(s.rows()) * u128::from(s.axis_points()));
    m.load_cases
        .iter()
        .map(|lc| {
            m.grid
                .iter()
                .filter(|a| lc.spans(a.name))
                .map(|a| a.values.len() as u128)
                .product::<u128>()
                * rows
        })
        .sum()
}

/// The number of positions of each grid axis for the cases of `load_case`, in grid order
/// (the case ids run through them as an odometer, last axis fastest): an axis the load case
/// does not span has a single position (never read: the scene finds that parameter itself).
/// A sampling study has one more position, innermost: the sample row.
pub fn load_case_dims(manifest: &Manifest, load_case: &LoadCase) -> Vec<u64> {
    manifest
        .grid
        .iter()
        .map(|a| {
            if load_case.spans(a.name) {
                a.values.len() as u64
            } else {
                1
            }
        })
        .chain(manifest.sampling.iter().flat_map(|s| {
            (s.axes.iter().map(|a| a.values.len() as u64)).chain(std::iter::once(s.rows()))
        }))
        .collect()
}

/// Expands a manifest into its cases.
pub fn build(manifest: Manifest) -> Result<Plan, PlanTooLarge> {
    let requested = case_count(&manifest);
    if requested > u128::from(MAX_CASES) {
        return Err(PlanTooLarge { requested });
    }
    Ok(build_slice(manifest, 0..requested as u64))
}

/// The cases of a plan whose ids lie in `ids` (clamped to the plan), in id order, without
/// expanding the others: each load case's first case in the slice is found from its id by
/// mixed-radix decomposition, so a slice of a plan of 10⁸ cases costs only its own cases.
/// The case ids are those of the whole plan.
pub fn build_slice(manifest: Manifest, ids: std::ops::Range<u64>) -> Plan {
    let total = u64::try_from(case_count(&manifest)).unwrap_or(u64::MAX);
    let (start, end) = (ids.start.min(total), ids.end.min(total));
    let mut cases = Vec::with_capacity(usize::try_from(end.saturating_sub(start)).unwrap_or(0));
    let mut first = 0u64;
    // The sample rows are drawn from one design, built once for the slice; the sampling at
    // the current position of the distribution axes is rebuilt only when it moves.
    let design = manifest.sampling.as_ref().map(|s| s.design());
    let mut at: Option<(Vec<usize>, crate::manifest::Sampling)> = None;
    for (lc, load_case) in manifest.load_cases.iter().enumerate() {
        let dims = load_case_dims(&manifest, load_case);
        let per_lc: u64 = dims.iter().product();
        let (lo, hi) = (start.max(first), end.min(first + per_lc));
        if lo < hi {
            // The odometer position of case `lo`, last axis fastest.
            let mut rest = lo - first;
            let mut idx = vec![0usize; dims.len()];
            for d in (0..dims.len()).rev() {
                idx[d] = (rest % dims[d]) as usize;
                rest /= dims[d];
            }
            for id in lo..hi {
                let sampled = match (&manifest.sampling, &design) {
                    (Some(s), Some(d)) => {
                        let g = manifest.grid.len();
                        let pos = &idx[g..g + s.axes.len()];
                        if at.as_ref().is_none_or(|(p, _)| p != pos) {
                            at = Some((pos.to_vec(), s.at(pos)));
                        }
                        at.as_ref().map(|(_, s)| (s, d))
                    }
                    _ => None,
                };
                cases.push(Case {
                    id,
                    load_case: lc,
                    scene: scene_at(&manifest, lc, &idx, sampled),
                });
                // Odometer increment, last axis fastest.
                for d in (0..dims.len()).rev() {
                    idx[d] += 1;
                    if (idx[d] as u64) < dims[d] {
                        break;
                    }
                    idx[d] = 0;
                }
            }
        }
        first += per_lc;
    }
    Plan { manifest, cases }
}

/// The ids of shard `index` (1-based) of `count` of a plan of `total` cases: contiguous
/// slices in plan order whose sizes differ by at most one case (empty when `count > total`).
pub fn shard_ids(total: u64, index: u64, count: u64) -> std::ops::Range<u64> {
    let count = u128::from(count.max(1));
    let at = |i: u64| (u128::from(total) * u128::from(i) / count) as u64;
    at(index.saturating_sub(1))..at(index)
}

fn scene_at(
    m: &Manifest,
    lc: usize,
    idx: &[usize],
    sampled: Option<(&crate::manifest::Sampling, &Design)>,
) -> Scene {
    let mut half = m.arch.half_angle_deg;
    let mut at_deg = None;
    let mut at_x = None;
    let mut joints = m.arch.voussoirs;
    let mut form = m.arch.form();
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
            AxisName::Eccentricity => form.shape = Shape::Pointed { eccentricity: v },
            AxisName::Joints => form.joints = crate::manifest::joints_of_axis_value(v),
            AxisName::Voussoirs => joints = discretisation(v),
            AxisName::AtDeg => at_deg = Some(v),
            AxisName::AtX => at_x = Some(v),
        }
    }
    // Every value was validated with the manifest, so the constructors cannot fail.
    let scene = Scene {
        arch: Arch::from_valid(k, half, m.arch.weight, joints),
        friction: Friction::new(mu).unwrap_or(Friction::INFINITE),
        find: case.map_or(m.find, |c| c.find),
        form,
        load: case.map_or(Load::SelfWeight, |c| c.load(at_deg, at_x)),
        lambda: case.and_then(|c| c.lambda).unwrap_or(0.0),
    };
    match sampled {
        Some((s, design)) => {
            let row = idx.last().map_or(0, |&r| r as u64);
            with_sample(scene, s, &s.values(design, row))
        }
        None => scene,
    }
}

/// `scene` at the values of one sample of `s` (in `s.params` order): the scene of a case of a
/// sampling study, and of the replicates its convergence study draws. A sample at the closed
/// end of a continuous support of K rounds onto it, and is moved off (K = 1 is no arch).
pub fn with_sample(mut scene: Scene, s: &crate::manifest::Sampling, values: &[f64]) -> Scene {
    let a = scene.arch;
    let (mut k, mut half, mut joints) = (a.k, a.half_angle_deg(), a.joints);
    for (p, &v) in s.params.iter().zip(values) {
        match p.name {
            ParamName::K => k = v,
            ParamName::TOverR => k = k_from_t_over_r(v),
            ParamName::Mu => scene.friction = Friction::new(v).unwrap_or(Friction::INFINITE),
            ParamName::HalfAngleDeg => half = v,
            ParamName::Eccentricity => scene.form.shape = Shape::Pointed { eccentricity: v },
            ParamName::Voussoirs => joints = discretisation(v),
            ParamName::AtDeg => {
                let width = scene.load.width().unwrap_or(0.0);
                scene.load = Load::Point { at_deg: v, width };
            }
            ParamName::AtX => {
                let width = scene.load.width().unwrap_or(0.0);
                scene.load = Load::PointX { at_x: v, width };
            }
            ParamName::Lambda => scene.lambda = v,
        }
    }
    scene.arch = Arch::from_valid(k.max(1f64.next_up()), half, a.weight, joints);
    scene
}

/// The discretisation of a voussoir count (+inf: the continuum).
fn discretisation(v: f64) -> Discretisation {
    if v.is_infinite() {
        Discretisation::Continuum
    } else {
        Discretisation::Voussoirs(v as u32)
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
            && !self.manifest.forms_vary()
            && self
                .manifest
                .load_cases
                .iter()
                .all(|l| l.find == Find::State && !l.kind.is_live())
    }

    /// A readable description of the plan for `archstudy check` ([`describe`]).
    pub fn describe(&self) -> String {
        describe(&self.manifest)
    }
}

/// The arch line of [`describe`]: an arch parameter that is a grid axis is described with
/// the axes, not as one value.
fn describe_arch(m: &Manifest) -> String {
    let is_axis = |n: AxisName| m.grid.iter().any(|a| a.name == n);
    let shape = match m.arch.eccentricity {
        _ if is_axis(AxisName::Eccentricity) => format!("{} (e: grid axis)", m.arch.shape),
        Some(e) => format!("{} (e = {e})", m.arch.shape),
        None => m.arch.shape.to_string(),
    };
    let joints = if is_axis(AxisName::Joints) {
        "joints: grid axis".to_string()
    } else {
        format!("{} joints", m.arch.joints)
    };
    let alpha = if is_axis(AxisName::HalfAngleDeg) {
        "α: grid axis".to_string()
    } else {
        format!("α = {}°", m.arch.half_angle_deg)
    };
    let voussoirs = if is_axis(AxisName::Voussoirs) {
        "voussoirs: grid axis".to_string()
    } else {
        m.arch.voussoirs.to_string()
    };
    let keystone = if m.arch.keystone { ", keystone" } else { "" };
    format!(
        "arch: {} {alpha}, {joints}{keystone}, {} weight, {voussoirs}\n",
        shape, m.arch.weight
    )
}

/// A readable description of a manifest's plan for `archstudy check`, without expanding it:
/// the number of cases is [`case_count`], so a plan of 10⁸ cases costs what a plan of ten
/// does.
pub fn describe(m: &Manifest) -> String {
    let find = m
        .sampling
        .as_ref()
        .map_or(m.find.to_string(), |s| s.question.to_string());
    let mut s = format!("study `{}`: find {find}\n", m.name);
    s.push_str(&describe_arch(m));
    for a in &m.grid {
        let first = a.values.first().copied().unwrap_or(f64::NAN);
        let last = a.values.last().copied().unwrap_or(f64::NAN);
        let show = |v: f64| {
            if a.name == AxisName::Voussoirs && v.is_infinite() {
                "continuum".to_string()
            } else if a.name == AxisName::Joints {
                crate::manifest::joints_of_axis_value(v)
                    .as_str()
                    .to_string()
            } else {
                v.to_string()
            }
        };
        s.push_str(&format!(
            "axis {}: {} values from {} to {}\n",
            a.name.as_str(),
            a.values.len(),
            show(first),
            show(last)
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
            if let Some(x) = l.at_x {
                d.push_str(&format!(" at x/L = {x}"));
            }
            if let Some(x) = l.lambda {
                d.push_str(&format!(", λ = {x}"));
            }
            if l.find != m.find && m.sampling.is_none() {
                d.push_str(&format!(", find {}", l.find));
            }
            d.push(')');
            d
        })
        .collect();
    s.push_str(&format!("load cases: {}\n", names.join(", ")));
    if let Some(u) = &m.sampling {
        for p in &u.params {
            s.push_str(&format!(
                "uncertain {}: {}\n",
                p.name.as_str(),
                p.distribution.describe()
            ));
        }
        for a in &u.axes {
            let (first, last) = (a.values[0], a.values[a.values.len() - 1]);
            s.push_str(&format!(
                "axis {}: {} values from {first} to {last} (each grid point its own distribution)\n",
                u.axis_name(a),
                a.values.len()
            ));
        }
        if let Some(c) = u.correlation {
            s.push_str(&format!(
                "correlation of {} and {}: {}\n",
                u.params[c.first].name.as_str(),
                u.params[c.second].name.as_str(),
                c.value
            ));
        }
        s.push_str(&format!(
            "samples: {} by {} (seed {}), {} analyses per grid point\n",
            u.n,
            u.method.as_str(),
            u.seed,
            u.rows()
        ));
    }
    s.push_str(&format!("cases: {}\n", case_count(m)));
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    #[test]
    fn arch_axes_are_described_as_axes() {
        let m = crate::manifest::parse(
            "name: ax\ngrid:\n  half_angle_deg: {values: [60, 90]}\n  voussoirs: {values: [8, continuum]}\n  k: {values: [1.2]}\n  mu: {values: [0.4]}\n",
            Path::new("ax.yaml"),
        )
        .unwrap();
        let text = build(m).unwrap().describe();
        assert!(text.contains("α: grid axis"), "{text}");
        assert!(text.contains("voussoirs: grid axis"), "{text}");
        assert!(!text.contains("α = 90°"), "{text}");
        assert!(
            text.contains("axis voussoirs: 2 values from 8 to continuum"),
            "{text}"
        );
        assert!(text.contains("cases: 4"), "{text}");
    }

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

    fn manifest(text: &str) -> Manifest {
        crate::manifest::parse(text, Path::new("a.yaml")).unwrap()
    }

    #[test]
    fn a_slice_holds_the_cases_of_the_whole_plan_with_their_ids() {
        let m = manifest(
            "name: a
grid:
  voussoirs: {values: [8, continuum]}
  k: {values: [1.1, 1.2, 1.3]}
  mu: {values: [0.4, 0.5]}
load_cases:
  - {name: gravity, kind: self_weight}
  - {name: wind, kind: horizontal, find: load_factor}
",
        );
        let whole = build(m.clone()).unwrap();
        assert_eq!(whole.cases.len(), 24);
        for (a, b) in [
            (0, 24),
            (0, 0),
            (5, 17),
            (11, 13),
            (12, 24),
            (23, 99),
            (30, 40),
        ] {
            let slice = build_slice(m.clone(), a..b);
            let want: Vec<&Case> = whole
                .cases
                .iter()
                .filter(|c| c.id >= a && c.id < b)
                .collect();
            assert_eq!(slice.cases.iter().collect::<Vec<_>>(), want, "{a}..{b}");
        }
    }

    #[test]
    fn shards_cover_the_plan_once_in_order_with_sizes_within_one() {
        for (total, count) in [(10, 3), (7, 7), (3, 5), (0, 2), (271_051, 16)] {
            let ranges: Vec<_> = (1..=count).map(|i| shard_ids(total, i, count)).collect();
            assert_eq!(ranges[0].start, 0);
            assert_eq!(ranges[ranges.len() - 1].end, total);
            for w in ranges.windows(2) {
                assert_eq!(w[0].end, w[1].start);
            }
            let sizes: Vec<u64> = ranges.iter().map(|r| r.end - r.start).collect();
            let (lo, hi) = (sizes.iter().min().unwrap(), sizes.iter().max().unwrap());
            assert!(hi - lo <= 1, "{total}/{count}: {sizes:?}");
        }
        assert_eq!(shard_ids(3, 5, 5), 2..3);
        assert_eq!(shard_ids(3, 1, 5), 0..0);
    }

    #[test]
    fn a_shard_of_a_plan_of_a_hundred_million_cases_expands_only_its_own_cases() {
        let m = manifest(
            "name: big\ngrid:\n  k: {from: 1.05, to: 1.5, steps: 10000}\n  mu: {from: 0.2, to: 0.8, steps: 10000}\n",
        );
        assert_eq!(case_count(&m), 100_000_000);
        assert!(build(m.clone()).is_err());
        let ids = shard_ids(100_000_000, 1000, 1000);
        let slice = build_slice(m, ids.clone());
        assert_eq!(slice.cases.len(), 100_000);
        assert_eq!(slice.cases[0].id, ids.start);
        let last = slice.cases.last().unwrap();
        assert_eq!(
            (last.id, last.scene.arch.k, last.scene.friction.mu()),
            (99_999_999, 1.5, 0.8)
        );
    }
}
