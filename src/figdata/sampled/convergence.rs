//! What a sample size buys: the error of the sampled probability against the exact one as n
//! grows, for scrambled Sobol points and for random sampling, each over independent
//! replicates (the root-mean-square error of R estimates at each n), and for the run's own
//! samples. Every replicate's points are analysed once and the estimate read at each
//! power-of-two prefix (a prefix of 2^m Sobol points is itself a balanced net).

use super::reduce::Group;
use crate::analysis::types::Regime;
use crate::manifest::Sampling;
use crate::sampling::{Design, Method};
use crate::scene::{self, Find, Scene};
use crate::store::EstimateRow;
use rayon::prelude::*;

/// Settings of the convergence study.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConvergenceSettings {
    /// Independent replicates per method.
    pub replicates: u64,
    /// Scenes analysed in all, for a scene with the closed forms (circular arch under
    /// self-weight: microseconds each).
    pub budget_closed: u64,
    /// Scenes analysed in all, for a scene of the general route (tens of microseconds each
    /// and more).
    pub budget_general: u64,
    /// Smallest n shown.
    pub first: u64,
}

impl ConvergenceSettings {
    /// The defaults: 8 replicates, 2^19 and 2^15 scenes, from n = 16.
    pub const DEFAULT: Self = ConvergenceSettings {
        replicates: 8,
        budget_closed: 1 << 19,
        budget_general: 1 << 15,
        first: 16,
    };
}

/// The convergence rows of the first grid point of a load case, when its exact probability
/// is known (`rows` holds it); none otherwise.
pub fn rows(
    s: &Sampling,
    base: &Scene,
    lc: &str,
    g: &Group,
    rows: &[EstimateRow],
) -> Vec<EstimateRow> {
    let settings = ConvergenceSettings::DEFAULT;
    let Some(exact) = rows
        .iter()
        .find(|r| r.load_case == lc && r.point == g.point && r.quantity == "exact_probability")
        .map(|r| r.value)
        .filter(|v| v.is_finite())
    else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for &(n, fails) in g.prefix.iter().filter(|(n, _)| *n >= settings.first) {
        let est = fails as f64 / n as f64;
        out.push(
            EstimateRow::value(lc, g.point, "convergence", "this run", (est - exact).abs())
                .at(n as f64)
                .noted(s.method.as_str()),
        );
    }
    let state = Scene {
        find: Find::State,
        ..*base
    };
    let budget = if state.uses_closed_forms() {
        settings.budget_closed
    } else {
        settings.budget_general
    };
    let per_replicate = budget / (2 * settings.replicates);
    let top = (per_replicate.max(settings.first) as f64).log2().floor() as u32;
    let n_max = 1u64 << top;
    for (method, offset) in [(Method::Sobol, 1000), (Method::Random, 2000)] {
        let errors: Vec<Vec<f64>> = (0..settings.replicates)
            .into_par_iter()
            .map(|r| {
                let design = Design::new(method, s.seed + offset + r, n_max, s.params.len());
                let mut fails = 0u64;
                let mut errs = Vec::new();
                for row in 0..n_max {
                    if !stands(s, &design, row, &state) {
                        fails += 1;
                    }
                    let n = row + 1;
                    if n.is_power_of_two() && n >= settings.first {
                        errs.push(fails as f64 / n as f64 - exact);
                    }
                }
                errs
            })
            .collect();
        let levels = errors.first().map_or(0, Vec::len);
        let mut points = Vec::new();
        for i in 0..levels {
            let n = settings.first << i;
            let ms = errors.iter().map(|e| e[i] * e[i]).sum::<f64>() / errors.len() as f64;
            points.push((n as f64, ms.sqrt()));
            out.push(
                EstimateRow::value(lc, g.point, "convergence", method.as_str(), ms.sqrt())
                    .at(n as f64)
                    .noted(format!(
                        "root-mean-square error of {} independent replicates",
                        settings.replicates
                    )),
            );
        }
        if let Some(slope) = slope(&points) {
            out.push(EstimateRow::value(
                lc,
                g.point,
                "convergence_slope",
                method.as_str(),
                slope,
            ));
        }
    }
    out
}

/// Whether the arch of sample `row` stands (the scene's thickness and friction replaced by
/// the sample's).
fn stands(s: &Sampling, design: &Design, row: u64, base: &Scene) -> bool {
    let scene = crate::plan::with_sample(*base, s, &s.values(design, row));
    scene::solve_static(&scene).regime == Some(Regime::Stable)
}

/// The least-squares slope of log error against log n (the errors that are not zero).
fn slope(points: &[(f64, f64)]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|(_, e)| *e > 0.0)
        .map(|(n, e)| (n.ln(), e.ln()))
        .collect();
    if pts.len() < 3 {
        return None;
    }
    let m = pts.len() as f64;
    let (sx, sy) = pts.iter().fold((0.0, 0.0), |(a, b), (x, y)| (a + x, b + y));
    let (mx, my) = (sx / m, sy / m);
    let sxy: f64 = pts.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = pts.iter().map(|(x, _)| (x - mx) * (x - mx)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}
