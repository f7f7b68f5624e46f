//! The collapse load factor λ_max of a load_factor study as a colour map over (μ, K), with
//! the regions of each collapse mechanism bounded by the located mechanism changes of
//! bifurcations.parquet. The chart's data is reduced here to the figure's resolution: a
//! raster of [`RASTER`] cells, the mechanism classified from the located changes as the
//! regime map classifies regimes and λ bilinear between the grid points of that mechanism
//! (a cell crossed by a located change draws each side from its own mechanism's λ, never
//! blended across the change), so a grid of a million cases draws from a few tens of
//! thousands of values.

use super::load_factor::{
    Cases, distinct, gap_sentence, group_stem, group_text, load_at_text, positions,
};
use super::regime_map::{ArchKey, bifurcations_of_arch};
use super::{Chart, FigureSpec, LoadCaseFigure};
use crate::figdata::stand_limit;
use crate::plan;
use crate::plot::lambda_map::{LambdaMap, LambdaStrip};
use crate::plot::regime_map::{Crossing, RegimeMap};
use crate::report::data::RunData;
use crate::store::LoadFactorCase;
use std::collections::HashMap;
use std::sync::Arc;

/// The fewest distinct values of finite μ and of K for which the map is drawn: with fewer,
/// the load-factor curves show every value.
pub const MIN_VALUES: usize = 4;

/// Raster cells of the map along μ and along K (about 2.5 design pixels each).
pub const RASTER: (usize, usize) = (240, 200);

/// At most this many grid points are ringed where a gap opens; a denser grid's gaps are
/// counted in the caption only.
const MAX_RINGS: usize = 2500;

/// Above this ratio of the largest to the smallest λ, the colour scale is logarithmic.
const LOG_RATIO: f64 = 30.0;

/// A logarithmic colour scale spans at most this ratio below the largest λ; smaller values
/// take its lowest colour.
const LOG_SPAN: f64 = 100.0;

/// The grid cell of `x` (its lower index) and the place in it, 0 to 1.
fn cell(v: &[f64], x: f64) -> (usize, f64) {
    let i = v.partition_point(|&g| g <= x).clamp(1, v.len() - 1) - 1;
    let f = ((x - v[i]) / (v[i + 1] - v[i])).clamp(0.0, 1.0);
    (i, f)
}

/// The mean of values with weights, over the finite values only (NaN when none is).
fn weighted(pairs: &[(f64, f64)]) -> f64 {
    let (sum, w) = pairs
        .iter()
        .filter(|(v, w)| v.is_finite() && *w > 0.0)
        .fold((0.0, 0.0), |(s, t), (v, w)| (s + v * w, t + w));
    if w > 0.0 { sum / w } else { f64::NAN }
}

/// The four grid points round (μ, K) as indices into the grid's values (K-major), with their
/// bilinear weights.
fn corners(g: &Grid, at: (f64, f64)) -> [(usize, f64); 4] {
    let ((i, s), (j, t)) = (cell(&g.mu, at.0), cell(&g.k, at.1));
    let p = |i: usize, j: usize| j * g.mu.len() + i;
    [
        (p(i, j), (1.0 - s) * (1.0 - t)),
        (p(i + 1, j), s * (1.0 - t)),
        (p(i, j + 1), (1.0 - s) * t),
        (p(i + 1, j + 1), s * t),
    ]
}

/// Where the arch starts to stand on the grid's edges (figdata's stand limit): on edges
/// along K, keyed by (μ index, lower K index), the K; on edges along μ, keyed by (lower μ
/// index, K index), the μ. The μ = ∞ column's edges have the μ index `mu.len()`.
#[derive(Debug, Default)]
struct StandLimit {
    along_k: HashMap<(usize, usize), f64>,
    along_mu: HashMap<(usize, usize), f64>,
}

impl StandLimit {
    /// The stored crossings of one load case on one arch.
    fn of(data: &RunData, lc: &str, g: &Grid, c: &LoadFactorCase) -> Self {
        let fig = stand_limit::stand_limit_figure(
            lc,
            c.half_angle_deg,
            c.eccentricity,
            c.joints,
            c.voussoirs,
        );
        let mut out = StandLimit::default();
        for p in data.curves.iter().filter(|p| p.figure == fig) {
            let (mu, k) = (p.x, p.y);
            if p.series == stand_limit::ALONG_K {
                let i = if mu.is_infinite() {
                    Some(g.mu.len())
                } else {
                    plan::axis_index(&g.mu, mu)
                };
                if let Some(i) = i {
                    out.along_k.insert((i, cell(&g.k, k).0), k);
                }
            } else if p.series == stand_limit::ALONG_MU
                && let Some(j) = plan::axis_index(&g.k, k)
            {
                out.along_mu.insert((cell(&g.mu, mu).0, j), mu);
            }
        }
        out
    }

    /// Whether (μ, K) in the grid cell (i, j) lies where the arch does not stand: `None` when
    /// the cell is not crossed by the limit on exactly two of its edges.
    fn never(&self, g: &Grid, (i, j): (usize, usize), at: (f64, f64)) -> Option<bool> {
        let (m0, m1, k0, k1) = (g.mu[i], g.mu[i + 1], g.k[j], g.k[j + 1]);
        let unit = |p: (f64, f64)| ((p.0 - m0) / (m1 - m0), (p.1 - k0) / (k1 - k0));
        let lam = |i: usize, j: usize| g.lambda[j * g.mu.len() + i];
        // Each crossed edge: its crossing and the end of it that does not stand.
        let mut cuts: Vec<((f64, f64), (f64, f64))> = Vec::new();
        for (ii, jj) in [(i, j), (i + 1, j)] {
            if let Some(&k) = self.along_k.get(&(ii, j)) {
                let never_at = if lam(ii, jj).is_finite() {
                    (g.mu[ii], k1)
                } else {
                    (g.mu[ii], k0)
                };
                cuts.push(((g.mu[ii], k), never_at));
            }
        }
        for jj in [j, j + 1] {
            if let Some(&mu) = self.along_mu.get(&(i, jj)) {
                let never_at = if lam(i, jj).is_finite() {
                    (m1, g.k[jj])
                } else {
                    (m0, g.k[jj])
                };
                cuts.push(((mu, g.k[jj]), never_at));
            }
        }
        let [(a, never_at), (b, _)] = cuts.as_slice() else {
            return None;
        };
        let (a, b, c, p) = (unit(*a), unit(*b), unit(*never_at), unit(at));
        let side = |q: (f64, f64)| (b.0 - a.0) * (q.1 - a.1) - (b.1 - a.1) * (q.0 - a.0);
        Some(side(p) * side(c) > 0.0)
    }

    /// The same on the μ = ∞ column, between its K values j and j + 1.
    fn never_infinite(&self, g: &Grid, col: &[f64], j: usize, k: f64) -> Option<bool> {
        let &limit = self.along_k.get(&(g.mu.len(), j))?;
        Some(if col[j].is_finite() {
            k > limit
        } else {
            k < limit
        })
    }
}

/// λ at (μ, K) of a point whose collapse mechanism is `mechanism` (from the located
/// regions): bilinear between the four grid points round it (over those with a finite λ)
/// when they all collapse by one mechanism, or when none of them collapses by the point's;
/// otherwise bilinear in the λ of the point's own mechanism (`branches`, see [`branch`]), so
/// that a mechanism's region is drawn up to the located change with its own values, never
/// with another mechanism's. NaN (no finite λ) where the arch does not stand (bounded by
/// the stand limit where a cell is crossed by it) and otherwise when the nearest grid point
/// has none, so that a grid line where the arch stands under every λ is drawn as such, not
/// blended from its neighbours.
fn lambda_at(
    g: &Grid,
    limit: &StandLimit,
    branches: &[(&str, Vec<f64>)],
    mechanism: Option<&str>,
    at: (f64, f64),
) -> f64 {
    let c = corners(g, at);
    let cell_of = (cell(&g.mu, at.0).0, cell(&g.k, at.1).0);
    match limit.never(g, cell_of, at) {
        Some(true) => return f64::NAN,
        Some(false) => {}
        None => match c.iter().max_by(|a, b| a.1.total_cmp(&b.1)) {
            Some(nearest) if g.lambda[nearest.0].is_finite() => {}
            _ => return f64::NAN,
        },
    }
    let raw = || weighted(&c.map(|(p, w)| (g.lambda[p], w)));
    let one_mechanism = c
        .iter()
        .all(|(p, _)| g.mechanism[*p] == g.mechanism[c[0].0]);
    let at_a_corner = c
        .iter()
        .any(|(p, _)| g.mechanism[*p].as_deref() == mechanism);
    let own = branches.iter().find(|b| Some(b.0) == mechanism);
    match own {
        Some((_, f)) if !one_mechanism && at_a_corner => {
            let v = weighted(&c.map(|(p, w)| (f[p], w)));
            if v.is_finite() { v } else { raw() }
        }
        _ => raw(),
    }
}

/// The λ of mechanism `m` at every grid point (K-major): the stored λ where the point
/// collapses by `m`; elsewhere carried on from such points along the grid lines, ring after
/// ring, each point taking the mean of its neighbours on its K and μ lines known from the
/// rings before. Every value is thus a mean of stored λ of mechanism `m` nearby, and never
/// another mechanism's. NaN everywhere when no grid point collapses by `m`.
fn branch(g: &Grid, m: &str) -> Vec<f64> {
    let (nm, n) = (g.mu.len(), g.lambda.len());
    let mut f: Vec<f64> = (0..n)
        .map(|p| match g.mechanism[p].as_deref() {
            Some(x) if x == m && g.lambda[p].is_finite() => g.lambda[p],
            _ => f64::NAN,
        })
        .collect();
    let neighbours = |p: usize| {
        let (i, j) = (p % nm, p / nm);
        [
            (i > 0).then(|| p - 1),
            (i + 1 < nm).then(|| p + 1),
            (j > 0).then(|| p - nm),
            (p + nm < n).then(|| p + nm),
        ]
        .into_iter()
        .flatten()
    };
    let mut queued = vec![false; n];
    let mut ring: Vec<usize> = Vec::new();
    for p in 0..n {
        if f[p].is_nan() && neighbours(p).any(|q| f[q].is_finite()) {
            queued[p] = true;
            ring.push(p);
        }
    }
    while !ring.is_empty() {
        let values: Vec<f64> = ring
            .iter()
            .map(|&p| {
                let known: Vec<(f64, f64)> = neighbours(p).map(|q| (f[q], 1.0)).collect();
                weighted(&known)
            })
            .collect();
        for (&p, v) in ring.iter().zip(values) {
            f[p] = v;
        }
        let mut next = Vec::new();
        for &p in &ring {
            for q in neighbours(p) {
                if !queued[q] && f[q].is_nan() {
                    queued[q] = true;
                    next.push(q);
                }
            }
        }
        ring = next;
    }
    f
}

/// λ and the collapse mechanism at the centre of every cell of an `nx` × `ny` raster over
/// the finite grid (K-major): the mechanism from the regions bounded by the located changes,
/// λ from that mechanism's own values ([`lambda_at`]).
fn raster<'a>(
    g: &Grid,
    limit: &StandLimit,
    classified: &'a RegimeMap,
    (nx, ny): (usize, usize),
) -> (Vec<f64>, Vec<Option<&'a str>>) {
    let mechanisms = classified.raster(nx, ny);
    let names = ["rotational", "mixed", "sliding"];
    let branches: Vec<(&str, Vec<f64>)> = names
        .into_iter()
        .filter(|m| g.mechanism.iter().any(|x| x.as_deref() == Some(m)))
        .map(|m| (m, branch(g, m)))
        .collect();
    let (mu0, mu1) = (g.mu[0], g.mu[g.mu.len() - 1]);
    let (k0, k1) = (g.k[0], g.k[g.k.len() - 1]);
    let centre = |i: usize, n: usize, a: f64, b: f64| a + (b - a) * (i as f64 + 0.5) / n as f64;
    let mut lambda = Vec::with_capacity(nx * ny);
    for j in 0..ny {
        for i in 0..nx {
            let at = (centre(i, nx, mu0, mu1), centre(j, ny, k0, k1));
            lambda.push(lambda_at(g, limit, &branches, mechanisms[j * nx + i], at));
        }
    }
    (lambda, mechanisms)
}

/// The λ maps of a load case, one per arch of the study.
pub fn figures(data: &RunData, lc: &LoadCaseFigure) -> Vec<FigureSpec> {
    if data.manifest.find_of(lc.name) != "load_factor" {
        return Vec::new();
    }
    let cases = Cases::of(data, lc.name);
    let groups = cases.groups();
    let several = groups.len() > 1;
    let mut out = Vec::new();
    for g in groups {
        let own = cases.of_group(g);
        let on = group_text(g, several);
        let at = load_at_text(&own, data.manifest.positions_by_x(lc.name));
        let title = format!("Collapse load factor over μ and K{on}{at}");
        let Some(map) = lambda_map(data, lc.name, &own, several.then_some(g), title) else {
            continue;
        };
        let mut caption = format!(
            "The collapse load factor λ_max of every case (results.parquet) as a colour over the friction coefficient μ and the thickness ratio K, bilinear between the grid points (grey where the arch does not stand under its own weight, bounded by the thickness and friction at which it starts to stand, found between the grid points either side (curves.parquet); and where the nearest grid point's λ is unbounded) and drawn at the figure's resolution; where a located change of the collapse mechanism crosses a grid cell, each side takes the λ of its own mechanism only, carried up to the change from the nearest grid points collapsing by it, so that λ is not blended across a change; {}.",
            if map.log {
                "a logarithmic colour scale over two decades below the largest λ (smaller values take its lowest colour)"
            } else {
                "a linear colour scale"
            }
        );
        caption.push_str(" Thin lines with a white edge join the located changes of the collapse mechanism on neighbouring grid lines (bifurcations.parquet); each region bounded by them is named by its collapse mechanism at λ_max (hinges only, hinges and sliding joints, sliding joints only).");
        if map.infinite.is_some() {
            caption.push_str(" The strip at the right, apart from the μ axis, is μ = ∞.");
        }
        let strip = map.infinite.iter().flat_map(|s| s.lambda.iter());
        if map.lambda.iter().chain(strip).any(|l| !l.is_finite()) {
            caption.push_str(
                " Grey: no finite λ (unbounded, or the arch does not stand under its own weight).",
            );
        }
        let marks = if own.len() > MAX_RINGS {
            "Not ringed (too many grid points to draw)"
        } else if map.infinite.is_some() {
            "Green rings, at grid points of finite μ"
        } else {
            "Green rings"
        };
        caption.push_str(&gap_sentence(&own, marks));
        out.push(FigureSpec {
            stem: format!("lambda-map{}{}", lc.stem_suffix, group_stem(g, several)),
            title: format!("{}{}", map.title, lc.title_suffix),
            caption,
            chart: Chart::LambdaMap(map),
        });
    }
    out
}

/// The grid of one arch: finite μ, K, and λ and the mechanism at every point (K-major), and
/// the μ = ∞ column when there is one.
struct Grid {
    mu: Vec<f64>,
    k: Vec<f64>,
    lambda: Vec<f64>,
    mechanism: Vec<Option<Arc<str>>>,
    infinite: Option<Vec<f64>>,
}

fn grid_of(own: &[&LoadFactorCase], by_x: bool) -> Option<Grid> {
    if positions(own, by_x).len() > 1 {
        return None;
    }
    let mu: Vec<f64> = distinct(own.iter().map(|c| c.mu).filter(|m| m.is_finite()));
    let k: Vec<f64> = distinct(own.iter().map(|c| c.k).filter(|k| k.is_finite()));
    if mu.len() < MIN_VALUES || k.len() < MIN_VALUES {
        return None;
    }
    let names: Vec<Arc<str>> = ["rotational", "mixed", "sliding"]
        .into_iter()
        .map(Arc::from)
        .collect();
    let intern = |m: &str| names.iter().find(|n| &***n == m).cloned();
    let mut g = Grid {
        lambda: vec![f64::NAN; mu.len() * k.len()],
        mechanism: vec![None; mu.len() * k.len()],
        infinite: None,
        mu,
        k,
    };
    for c in own {
        let Some(j) = plan::axis_index(&g.k, c.k) else {
            continue;
        };
        let lambda = c.load_factor.unwrap_or(f64::NAN);
        if c.mu.is_infinite() {
            g.infinite.get_or_insert_with(|| vec![f64::NAN; g.k.len()])[j] = lambda;
        } else if let Some(i) = plan::axis_index(&g.mu, c.mu) {
            g.lambda[j * g.mu.len() + i] = lambda;
            g.mechanism[j * g.mu.len() + i] = c.mechanism.as_deref().and_then(intern);
        }
    }
    Some(g)
}

/// The λ map of one arch's cases of a load case (all arches when `arch` is None), when it
/// has one load position and at least [`MIN_VALUES`] values of finite μ and of K.
pub fn lambda_map(
    data: &RunData,
    lc: &str,
    own: &[&LoadFactorCase],
    arch: Option<ArchKey>,
    title: String,
) -> Option<LambdaMap> {
    let g = grid_of(own, data.manifest.positions_by_x(lc))?;
    let finite = || {
        g.lambda
            .iter()
            .chain(g.infinite.iter().flatten())
            .copied()
            .filter(|l| l.is_finite())
    };
    let lo = finite().fold(f64::INFINITY, f64::min);
    let hi = finite().fold(f64::NEG_INFINITY, f64::max);
    if lo > hi {
        return None;
    }
    let hi = if hi > lo {
        hi
    } else {
        lo + 1e-9_f64.max(lo.abs() * 1e-6)
    };
    let bifs = bifurcations_of_arch(data, lc, arch);
    let changes: Vec<(f64, f64, &str, &str)> = bifs
        .iter()
        .map(|b| (b.mu, b.k, b.mechanism_a.as_str(), b.mechanism_b.as_str()))
        .collect();
    let (nx, ny) = RASTER;
    let (mu0, mu1) = (g.mu[0], g.mu[g.mu.len() - 1]);
    let (k0, k1) = (g.k[0], g.k[g.k.len() - 1]);
    let centre = |i: usize, n: usize, a: f64, b: f64| a + (b - a) * (i as f64 + 0.5) / n as f64;
    let classified = mechanism_map(&g, &changes);
    let limit = own
        .first()
        .map_or_else(StandLimit::default, |c| StandLimit::of(data, lc, &g, c));
    let (lambda, drawn) = raster(&g, &limit, &classified, (nx, ny));
    let mechanisms: Vec<String> = ["rotational", "mixed", "sliding"]
        .into_iter()
        .filter(|m| g.mechanism.iter().any(|x| x.as_deref() == Some(m)))
        .map(String::from)
        .collect();
    let mechanism = drawn
        .into_iter()
        .map(|m| {
            let m = m?;
            mechanisms.iter().position(|n| n == m).map(|p| p as u8)
        })
        .collect();
    let infinite = g.infinite.as_ref().map(|col| LambdaStrip {
        lambda: (0..ny)
            .map(|j| {
                let k = centre(j, ny, k0, k1);
                let (jj, t) = cell(&g.k, k);
                // As on the map: grey where the arch does not stand, and otherwise where the
                // nearest grid point has no finite λ.
                let nearest = if t < 0.5 { col[jj] } else { col[jj + 1] };
                let stands = match limit.never_infinite(&g, col, jj, k) {
                    Some(never) => !never,
                    None => nearest.is_finite(),
                };
                if stands {
                    weighted(&[(col[jj], 1.0 - t), (col[jj + 1], t)])
                } else {
                    f64::NAN
                }
            })
            .collect(),
        changes: changes
            .iter()
            .filter(|c| c.0.is_infinite())
            .map(|c| c.1)
            .collect(),
    });
    let log = lo > 0.0 && hi > LOG_RATIO * lo;
    // λ falls to 0 at the collapse curve: a few cells next to it would stretch a logarithmic
    // scale over decades that the rest of the map does not use.
    let lo = if log { lo.max(hi / LOG_SPAN) } else { lo };
    Some(LambdaMap {
        title,
        window: ((mu0, mu1), (k0, k1)),
        nx,
        ny,
        lambda,
        mechanism,
        mechanisms,
        boundaries: boundaries(&g, &changes),
        lambda_range: (lo, hi),
        log,
        infinite,
        gaps: rings(own),
    })
}

/// The grid points of finite μ ringed for a gap, (μ, K): none when the grid has more than
/// [`MAX_RINGS`] points.
fn rings(own: &[&LoadFactorCase]) -> Vec<(f64, f64)> {
    if own.len() > MAX_RINGS {
        return Vec::new();
    }
    (own.iter())
        .filter(|c| c.mu.is_finite() && c.collapse_below.is_some())
        .map(|c| (c.mu, c.k))
        .collect()
}

/// The two mechanisms of a change, the one at the lower end of its edge (`below`) first.
fn oriented<'a>(below: Option<&str>, a: &'a str, b: &'a str) -> (&'a str, &'a str) {
    if below == Some(b) { (b, a) } else { (a, b) }
}

/// The two mechanisms of a change in name order.
fn pair<'a>(a: &'a str, b: &'a str) -> (&'a str, &'a str) {
    if a <= b { (a, b) } else { (b, a) }
}

/// The mechanisms over the finite grid as a regime map (no curves, no labels), whose
/// classifier bounds each mechanism's region by the located changes.
fn mechanism_map(g: &Grid, changes: &[(f64, f64, &str, &str)]) -> RegimeMap {
    let at = |i: usize, j: usize| g.mechanism[j * g.mu.len() + i].as_deref();
    let mut along_mu = Vec::new();
    let mut along_k = Vec::new();
    for &(mu, k, a, b) in changes.iter().filter(|c| c.0.is_finite()) {
        if let Some(j) = plan::axis_index(&g.k, k) {
            let (low, high) = oriented(at(cell(&g.mu, mu).0, j), a, b);
            along_mu.push(Crossing {
                fixed: g.k[j],
                at: mu,
                low: low.into(),
                high: high.into(),
            });
        } else if let Some(i) = plan::axis_index(&g.mu, mu) {
            let (low, high) = oriented(at(i, cell(&g.k, k).0), a, b);
            along_k.push(Crossing {
                fixed: g.mu[i],
                at: k,
                low: low.into(),
                high: high.into(),
            });
        }
    }
    RegimeMap {
        title: String::new(),
        mu: g.mu.clone(),
        k: g.k.clone(),
        regimes: g.mechanism.clone(),
        crossings_along_mu: along_mu,
        crossings_along_k: along_k,
        collapse: Vec::new(),
        other_boundaries: Vec::new(),
        gap_collapse: Vec::new(),
        bifurcations: Vec::new(),
        infinite: None,
    }
}

/// A located change: on a K line (true) or a μ line, its pair of mechanisms, the index of
/// its grid line, its place along that line and the point (μ, K).
type Located<'a> = (bool, (&'a str, &'a str), usize, f64, (f64, f64));

/// A boundary being joined: its family and pair, the index of the grid line and the place
/// of its last point, and its points.
type Chain<'a> = ((bool, (&'a str, &'a str)), usize, f64, Vec<(f64, f64)>);

/// The located changes at finite μ joined into polylines: on each family of grid lines (K
/// lines, μ lines) and for each pair of mechanisms, a change joins the line whose last
/// point lies on the previous grid line and nearest it, within two grid steps.
fn boundaries(g: &Grid, changes: &[(f64, f64, &str, &str)]) -> Vec<Vec<(f64, f64)>> {
    let step = |v: &[f64]| v.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
    let (dm, dk) = (step(&g.mu), step(&g.k));
    let mut pts: Vec<Located> = Vec::new();
    for &(mu, k, a, b) in changes.iter().filter(|c| c.0.is_finite()) {
        if let Some(j) = plan::axis_index(&g.k, k) {
            pts.push((true, pair(a, b), j, mu, (mu, k)));
        } else if let Some(i) = plan::axis_index(&g.mu, mu) {
            pts.push((false, pair(a, b), i, k, (mu, k)));
        }
    }
    pts.sort_by(|x, y| {
        (x.0, x.1, x.2)
            .cmp(&(y.0, y.1, y.2))
            .then(x.3.total_cmp(&y.3))
    });
    let mut lines: Vec<Chain> = Vec::new();
    for (family, p, idx, place, point) in pts {
        let reach = 2.0 * if family { dm } else { dk };
        let best = lines
            .iter_mut()
            .filter(|l| l.0 == (family, p) && l.1 + 1 == idx && (l.2 - place).abs() <= reach)
            .min_by(|a, b| (a.2 - place).abs().total_cmp(&(b.2 - place).abs()));
        match best {
            Some(l) => {
                l.1 = idx;
                l.2 = place;
                l.3.push(point);
            }
            None => lines.push(((family, p), idx, place, vec![point])),
        }
    }
    lines
        .into_iter()
        .map(|l| l.3)
        .filter(|l| l.len() >= 2)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Four K lines crossed by one located change from the mixed mechanism (μ ≤ 0.8, λ from
    /// 3.0 to 4.25) to the rotational one (μ ≥ 1.0, λ from 150 to 153) at μ = 0.95, nearer
    /// μ = 1.0 than the midline μ = 0.9: λ jumps by a factor of 40 there, as in the seismic
    /// study's quarter-span point load.
    fn jump() -> (Grid, Vec<(f64, f64, &'static str, &'static str)>) {
        let mu = vec![0.6, 0.8, 1.0, 1.2];
        let k = vec![1.3, 1.4, 1.5, 1.6];
        let mut lambda = Vec::new();
        let mut mechanism = Vec::new();
        for j in 0..k.len() {
            for (i, m) in mu.iter().enumerate() {
                let rotational = *m > 0.9;
                lambda.push(if rotational {
                    150.0 + j as f64
                } else {
                    3.0 + 0.5 * i as f64 + 0.25 * j as f64
                });
                mechanism.push(Some(Arc::from(if rotational {
                    "rotational"
                } else {
                    "mixed"
                })));
            }
        }
        let changes = k
            .iter()
            .map(|&k| (0.95, k, "mixed", "rotational"))
            .collect();
        let g = Grid {
            mu,
            k,
            lambda,
            mechanism,
            infinite: None,
        };
        (g, changes)
    }

    #[test]
    fn lambda_is_not_blended_across_a_located_change_of_mechanism() {
        let (g, changes) = jump();
        let classified = mechanism_map(&g, &changes);
        let (nx, ny) = (120, 60);
        let (lambda, mechanism) = raster(&g, &StandLimit::default(), &classified, (nx, ny));
        let (mut mixed_beyond_midline, mut checked) = (0, 0);
        for j in 0..ny {
            for i in 0..nx {
                let mu = 0.6 + 0.6 * (i as f64 + 0.5) / nx as f64;
                let k = 1.3 + 0.3 * (j as f64 + 0.5) / ny as f64;
                let (l, m) = (lambda[j * nx + i], mechanism[j * nx + i]);
                // The region of each mechanism ends at the located change, not at a midline.
                let want = if mu < 0.95 { "mixed" } else { "rotational" };
                assert_eq!(m, Some(want), "μ = {mu}, K = {k}");
                // Every pixel of the mixed side lies within the mixed grid points' λ (3.0 to
                // 4.25), every pixel of the rotational side within the rotational ones'
                // (150 to 153). Blended across the change, a pixel at μ = 0.93 took λ ≈ 100.
                let (lo, hi) = if want == "mixed" {
                    (3.0, 4.25)
                } else {
                    (150.0, 153.0)
                };
                assert!(
                    l >= lo - 1e-12 && l <= hi + 1e-12,
                    "μ = {mu}, K = {k}: λ = {l} outside [{lo}, {hi}]"
                );
                if want == "mixed" && mu > 0.9 {
                    mixed_beyond_midline += 1;
                }
                checked += 1;
            }
        }
        assert_eq!(checked, nx * ny);
        assert!(mixed_beyond_midline >= ny * 9, "{mixed_beyond_midline}");
        // Cells whose corners share one mechanism stay bilinear: μ = 0.7, K = 1.45 lies
        // halfway between λ 3.0 + 0.25 j and 3.5 + 0.25 j on K = 1.4 and 1.5 (j = 1, 2).
        let branches: Vec<(&str, Vec<f64>)> = ["rotational", "mixed"]
            .into_iter()
            .map(|m| (m, branch(&g, m)))
            .collect();
        let l = lambda_at(
            &g,
            &StandLimit::default(),
            &branches,
            Some("mixed"),
            (0.7, 1.45),
        );
        assert!((l - 3.625).abs() < 1e-12, "{l}");
        // Across the change, the mixed side of the cell (0.8, 1.0) × (1.4, 1.5) takes the
        // mixed λ of μ = 0.8 carried on at both its μ = 1.0 corners: 3.5 + 0.25 · 1.5.
        let l = lambda_at(
            &g,
            &StandLimit::default(),
            &branches,
            Some("mixed"),
            (0.93, 1.45),
        );
        assert!((l - 3.875).abs() < 1e-12, "{l}");
        let l = lambda_at(
            &g,
            &StandLimit::default(),
            &branches,
            Some("rotational"),
            (0.97, 1.45),
        );
        assert!((l - 151.5).abs() < 1e-12, "{l}");
    }
}
