//! The collapse curve drawn under the samples of a sampling study: the collapse thickness
//! K_c(μ) of the study's arch across the range of the sampled μ, one series per collapse
//! mechanism, so that the samples are seen against the regions they fall in.

use super::samples_figure;
use crate::manifest::{Manifest, ParamName, Sampling};
use crate::model::Friction;
use crate::plan;
use crate::sampling::Distribution;
use crate::scene::{self, Find, Outcome};
use crate::store::CurvePoint;
use rayon::prelude::*;

/// Points of each collapse curve.
const CURVE_POINTS: usize = 121;

/// The μ range a distribution's samples cover: its support, or its 0.05 % and 99.95 %
/// quantiles where the support is unbounded.
fn mu_range(d: &Distribution) -> (f64, f64) {
    let (lo, hi) = d.support();
    let lo = if lo.is_finite() { lo } else { d.quantile(5e-4) };
    let hi = if hi.is_finite() {
        hi
    } else {
        d.quantile(1.0 - 5e-4)
    };
    (lo.max(1e-6), hi.max(lo.max(1e-6) * 1.01))
}

/// The series holding μ_min, below which no thickness stands (its x; y is NaN).
pub const MU_MIN_SERIES: &str = "mu_min";

/// Steps of the bisection for μ_min between two curve points.
const MU_MIN_STEPS: usize = 30;

/// μ_min, where the curve starts after points at which no thickness stands: bisected between
/// the last such point and the first found.
fn sliding_threshold(
    scene: &crate::scene::Scene,
    found: &[(f64, Option<(f64, &'static str)>)],
) -> Option<f64> {
    let first = found.iter().position(|f| f.1.is_some())?;
    let (mut lo, mut hi) = (found.get(first.checked_sub(1)?)?.0, found[first].0);
    let stands_somewhere = |mu: f64| {
        let t = crate::scene::Scene {
            friction: Friction::new(mu).unwrap_or(Friction::INFINITE),
            find: Find::Thickness,
            ..*scene
        };
        scene::solve_static(&t).outcome == Some(Outcome::Found)
    };
    for _ in 0..MU_MIN_STEPS {
        let mid = 0.5 * (lo + hi);
        if stands_somewhere(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Some(hi)
}

/// The series name of the part of a collapse curve where the mechanism is `m`.
pub fn collapse_series(m: &str) -> String {
    format!("k_crit:{m}")
}

/// The collapse curves of every load case whose samples spread over both K and μ (and
/// nothing else, so that one curve describes every sample).
pub fn curves(m: &Manifest, s: &Sampling) -> Vec<CurvePoint> {
    let only_k_mu = s
        .params
        .iter()
        .all(|p| matches!(p.name, ParamName::K | ParamName::TOverR | ParamName::Mu));
    let has_k = s.param(ParamName::K).is_some() || s.param(ParamName::TOverR).is_some();
    let Some(mu) = s.param(ParamName::Mu).filter(|_| only_k_mu && has_k) else {
        return Vec::new();
    };
    let (lo, hi) = mu_range(&mu.distribution);
    let rows = s.rows();
    let points = m
        .grid
        .iter()
        .map(|a| a.values.len() as u64)
        .product::<u64>()
        * s.axis_points();
    let mut out = Vec::new();
    for (i, lc) in m.load_cases.iter().enumerate() {
        let first = i as u64 * points * rows;
        let base = plan::build_slice(m.clone(), first..first + 1);
        let Some(case) = base.cases.first() else {
            continue;
        };
        let mut scene = case.scene;
        if scene.find == Find::LoadFactor {
            // A fragility sample's λ_max falls to 0 where the arch fails under its own weight.
            scene.load = crate::model::Load::SelfWeight;
            scene.lambda = 0.0;
        }
        let mus: Vec<f64> = (0..CURVE_POINTS)
            .map(|j| lo + (hi - lo) * j as f64 / (CURVE_POINTS - 1) as f64)
            .collect();
        let found: Vec<(f64, Option<(f64, &'static str)>)> = mus
            .par_iter()
            .map(|&mu| {
                let t = crate::scene::Scene {
                    friction: Friction::new(mu).unwrap_or(Friction::INFINITE),
                    find: Find::Thickness,
                    ..scene
                };
                let sol = scene::solve_static(&t);
                let kc = match (sol.outcome, sol.k_crit, sol.mechanism) {
                    (Some(Outcome::Found), Some(k), Some(mech)) => Some((k, mech.as_str())),
                    _ => None,
                };
                (mu, kc)
            })
            .collect();
        let figure = samples_figure(&lc.name);
        for mech in ["rotational", "mixed", "sliding"] {
            let is = |i: usize| {
                found
                    .get(i)
                    .and_then(|f| f.1)
                    .is_some_and(|(_, m)| m == mech)
            };
            for (i, (mu, kc)) in found.iter().enumerate() {
                // A point of another mechanism next to this one's joins the two parts.
                let joins = i.checked_sub(1).is_some_and(is) || is(i + 1);
                let y = match kc {
                    Some((k, m)) if *m == mech || joins => *k,
                    _ => f64::NAN,
                };
                out.push(CurvePoint {
                    figure: figure.clone(),
                    series: collapse_series(mech),
                    x: *mu,
                    y,
                });
            }
        }
        if let Some(mu_min) = sliding_threshold(&scene, &found) {
            out.push(CurvePoint {
                figure: figure.clone(),
                series: MU_MIN_SERIES.into(),
                x: mu_min,
                y: f64::NAN,
            });
        }
    }
    out
}
