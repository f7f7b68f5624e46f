//! Figure 1: the regime map over (μ, K), its collapse curve by mechanism, the other regime
//! boundaries and the bifurcations.

use super::{Chart, FigureSpec, LoadCaseFigure, single_model};
use crate::plot::regime_map::{
    BifurcationMark, CollapseSegment, Crossing, InfiniteStrip, RegimeMap,
};
use crate::report::data::RunData;
use crate::report::format::short;
use crate::store::BoundaryRow;
use rayon::prelude::*;
use rustc_hash::{FxHashMap, FxHashSet};
use std::collections::BTreeMap;
use std::sync::Arc;

const REGIME_CAPTION: &str = "Regimes over the friction coefficient μ (horizontal) and the thickness ratio K = R/r (left axis; t/R_c on the right axis). Stable: an admissible state exists (Hʳ ∩ Hˢ ≠ ∅). Rotational: no line of thrust fits in the arch whatever the friction (Hʳ = ∅). Sliding: no thrust satisfies Coulomb's law at every joint (Hˢ = ∅; on a circular arch with radial joints whatever the thickness). Mixed: both domains exist but are disjoint. The thick line is the collapse curve through the located boundary points, coloured and labelled by the collapse mechanism (hinges only, hinges and sliding joints, sliding joints only); dots mark the bifurcations where two mechanisms coexist, with their values. Dashed lines are the other regime boundaries.";

const REGIONS_NOTE: &str = " Between grid points the regions are bounded by straight lines between the located boundary points.";

fn sorted_distinct(v: impl Iterator<Item = f64>) -> Vec<f64> {
    // A map's million rows hold a thousand distinct values: gather them before sorting
    // (the rows of an axis's value often follow one another: a repeat is not hashed).
    let mut distinct: FxHashSet<u64> = FxHashSet::default();
    let mut last = None;
    for x in v.filter(|x| x.is_finite()).map(f64::to_bits) {
        if last != Some(x) {
            distinct.insert(x);
            last = Some(x);
        }
    }
    let mut v: Vec<f64> = distinct.into_iter().map(f64::from_bits).collect();
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// The regime-map figure of a load case, when it is a state study over one model with at
/// least two values of μ and of K.
pub fn figure(data: &RunData, lc: &LoadCaseFigure) -> Option<FigureSpec> {
    let on = &lc.title_suffix;
    let map = regime_map(data, lc.name, on)?;
    let mut caption = REGIME_CAPTION.to_string();
    if map.infinite.is_some() {
        caption.push_str(" The strip at the right, apart from the μ axis, is μ = ∞.");
    }
    caption.push_str(REGIONS_NOTE);
    if !map.gap_collapse.is_empty() || moves_at_start_in_map(data, lc.name, &map) {
        let here = if map.gap_collapse.is_empty() {
            ""
        } else {
            " here, where it parts from the collapse curve, and"
        };
        caption.push_str(&format!(
            " Stable is the static verdict: part of the stable region lies in the \
             non-associative gap, where a mechanism obeying the flow rules can start (the \
             collapse, the first complete solution along K and along μ, drawn dashed{here} \
             on the critical curves)."
        ));
    }
    if !map.bifurcations.is_empty() {
        // The values stay readable where a narrow map shows only the points' numbers.
        let listed: Vec<String> = (map.bifurcations.iter())
            .map(|b| format!("{}, {}: {}", b.compact, b.lines[0], b.lines[1..].join(", ")))
            .collect();
        caption.push_str(&format!(" Bifurcations: {}.", listed.join("; ")));
    }
    Some(FigureSpec {
        stem: format!("regime-map{}", lc.stem_suffix),
        title: format!("Regime map{on}"),
        caption,
        chart: Chart::RegimeMap(map),
    })
}

fn regime_map(data: &RunData, lc: &str, on: &str) -> Option<RegimeMap> {
    if data.manifest.find_of(lc) != "state" || !single_model(data) {
        return None;
    }
    let title = match &data.manifest.title {
        Some(t) => format!("{t}{on}"),
        None => format!("Regimes over μ and K{on}"),
    };
    regime_map_of(data, lc, title, None)
}

/// The arch of the arch axes: half-angle, voussoir count, eccentricity and joint planes.
pub type ArchKey = crate::store::RowArch;

fn arch_matches(arch: Option<ArchKey>, a: Option<&crate::store::RowArch>) -> bool {
    match arch {
        None => true,
        Some(key) => a.is_some_and(|a| *a == key),
    }
}

/// Whether a row of bifurcations.parquet belongs to an arch (its columns as stored; a table
/// without the eccentricity or joints column holds the manifest's arch only).
fn group_matches(g: &crate::store::BifurcationGroup, a: ArchKey) -> bool {
    g.half_angle_deg.unwrap_or(90.0) == a.half_angle_deg
        && g.voussoirs.flatten() == a.voussoirs
        && (g.joints.is_none() || g.eccentricity == a.eccentricity)
        && g.joints.as_deref().is_none_or(|j| j == a.joints.as_str())
}

/// What the map reads of a state case: μ, K and the regime.
#[derive(Clone, Copy)]
struct MapCell<'a> {
    mu: Option<f64>,
    k: Option<f64>,
    regime: Option<&'a str>,
}

/// The few regime names of a map, one shared name each.
#[derive(Default)]
struct RegimeNames(Vec<Arc<str>>);

impl RegimeNames {
    fn of(&mut self, g: &str) -> Arc<str> {
        if let Some(n) = self.0.iter().find(|n| &***n == g) {
            return n.clone();
        }
        let n: Arc<str> = Arc::from(g);
        self.0.push(n.clone());
        n
    }
}

/// The regime of every grid point, K-major (None where no case gives one).
fn regimes_on_grid(cells: &[MapCell<'_>], mu: &[f64], k: &[f64]) -> Vec<Option<Arc<str>>> {
    let index = |v: &[f64]| -> FxHashMap<u64, usize> {
        v.iter()
            .enumerate()
            .map(|(i, x)| (x.to_bits(), i))
            .collect()
    };
    let (mi, ki) = (index(mu), index(k));
    let mut names = RegimeNames::default();
    let mut regimes = vec![None; mu.len() * k.len()];
    for c in cells {
        if let (Some(m), Some(kk)) = (c.mu, c.k)
            && let (Some(&i), Some(&j)) = (mi.get(&m.to_bits()), ki.get(&kk.to_bits()))
        {
            regimes[j * mu.len() + i] = c.regime.map(|g| names.of(g));
        }
    }
    regimes
}

/// The bifurcations of a load case, of one arch when `arch` is given.
pub fn bifurcations_of_arch<'a>(
    data: &'a RunData,
    lc: &str,
    arch: Option<ArchKey>,
) -> Vec<&'a crate::store::BifurcationRow> {
    data.bifurcations
        .iter()
        .flatten()
        .enumerate()
        .filter(|(i, b)| {
            b.load_case == lc
                && arch.is_none_or(|a| {
                    data.bifurcation_groups
                        .get(*i)
                        .is_some_and(|g| group_matches(g, a))
                })
        })
        .map(|(_, b)| b)
        .collect()
}

/// The regime map of a load case's state cases, of one arch of an arch axis when `arch` is
/// given (rows of results.parquet, boundaries.parquet and bifurcations.parquet of that
/// arch only), titled `title`.
pub fn regime_map_of(
    data: &RunData,
    lc: &str,
    title: String,
    arch: Option<ArchKey>,
) -> Option<RegimeMap> {
    // The rows are read once, in parallel, into what the map needs of them: each row of about
    // 400 bytes is a cache miss, and the later passes read cells of 48 bytes in order.
    let cells: Vec<MapCell<'_>> = (data.results.par_iter().enumerate())
        .filter(|(i, r)| {
            &*r.load_case == lc
                && &*r.find == "state"
                && arch_matches(arch, data.result_arches.get(*i))
        })
        .map(|(_, r)| MapCell {
            mu: r.mu,
            k: r.k,
            regime: r.regime.as_deref(),
        })
        .collect();
    let mu = sorted_distinct(cells.iter().filter_map(|c| c.mu));
    let k = sorted_distinct(cells.iter().filter_map(|c| c.k));
    if mu.len() < 2 || k.len() < 2 {
        return None;
    }
    let regimes = regimes_on_grid(&cells, &mu, &k);
    let all_bounds: Vec<&BoundaryRow> = data
        .boundaries
        .iter()
        .flatten()
        .enumerate()
        .filter(|(i, b)| b.load_case == lc && arch_matches(arch, data.boundary_arches.get(*i)))
        .map(|(_, b)| b)
        .collect();
    let infinite = infinite_strip(&cells, &k, &all_bounds);
    let bounds: Vec<&BoundaryRow> = all_bounds
        .into_iter()
        .filter(|b| b.mu.is_finite() && b.k.is_finite())
        .collect();
    let bifs = bifurcations_of_arch(data, lc, arch);
    let span = ((mu[0], mu[mu.len() - 1]), (k[0], k[k.len() - 1]));
    let collapse = collapse_segments(
        &bounds,
        &bifs.iter().map(|b| (b.mu, b.k)).collect::<Vec<_>>(),
        span,
    );
    let mut other = other_boundaries(&bounds);
    let bif_points: Vec<(f64, f64)> = bifs.iter().map(|b| (b.mu, b.k)).collect();
    extend_to_junctions(&mut other, &bif_points, (&mu, &k));
    let crossing = |b: &&BoundaryRow, fixed: f64, at: f64| Crossing {
        fixed,
        at,
        low: b.regime_low.clone(),
        high: b.regime_high.clone(),
    };
    let crossings_along_mu = bounds
        .iter()
        .filter(|b| b.axis == "mu")
        .map(|b| crossing(b, b.k, b.mu))
        .collect();
    let crossings_along_k = bounds
        .iter()
        .filter(|b| b.axis == "k")
        .map(|b| crossing(b, b.mu, b.k))
        .collect();
    let bifurcations = bifs
        .iter()
        .enumerate()
        .map(|(n, b)| BifurcationMark {
            mu: b.mu,
            k: b.k,
            lines: vec![
                crate::figdata::bifurcation_label(&b.mechanism_a, &b.mechanism_b),
                format!("μ = {}", short(b.mu)),
                format!("K = {}  (t/R_c = {})", short(b.k), short(b.t_over_r)),
            ],
            compact: (n + 1).to_string(),
        })
        .collect();
    Some(RegimeMap {
        title,
        mu,
        k,
        regimes,
        crossings_along_mu,
        crossings_along_k,
        collapse,
        other_boundaries: other,
        gap_collapse: gap_collapse(data, lc, arch),
        bifurcations,
        infinite,
    })
}

/// The first complete solution of a state study's thickness and friction paths where it parts
/// from the static critical curve (a non-associative gap), as lines over (μ, K); none on a
/// panel of one arch among several (the paths are searched for the study's own arch).
fn gap_collapse(data: &RunData, lc: &str, arch: Option<ArchKey>) -> Vec<Vec<(f64, f64)>> {
    use crate::figdata::{K_COLLAPSE_OF_MU, K_CRIT_OF_MU, MU_COLLAPSE_OF_K, MU_CRIT_OF_K};
    if arch.is_some() {
        return Vec::new();
    }
    let fig = crate::figdata::critical_figure(lc);
    let k_of_mu = parted(
        &data.curve(&fig, K_COLLAPSE_OF_MU),
        &data.curve(&fig, K_CRIT_OF_MU),
    );
    let mu_of_k: Vec<(f64, f64)> = parted(
        &data.curve(&fig, MU_COLLAPSE_OF_K),
        &data.curve(&fig, MU_CRIT_OF_K),
    )
    .into_iter()
    .map(|(k, mu)| (mu, k))
    .collect();
    [k_of_mu, mu_of_k]
        .into_iter()
        .filter(|l| {
            l.iter()
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .count()
                >= 2
        })
        .collect()
}

/// Whether the map holds stable arches that can move at the start of a thickness or friction
/// path (a sample of the figure data where the collapse is the search's start): at such a μ
/// the arches above K_c(μ), at such a K those above μ_c(K), are in the gap.
fn moves_at_start_in_map(data: &RunData, lc: &str, map: &RegimeMap) -> bool {
    use crate::figdata::{K_COLLAPSE_AT_START, K_CRIT_OF_MU, MU_COLLAPSE_AT_START, MU_CRIT_OF_K};
    let fig = crate::figdata::critical_figure(lc);
    let mu_top = if map.infinite.is_some() {
        f64::INFINITY
    } else {
        map.mu.last().copied().unwrap_or(f64::NEG_INFINITY)
    };
    let k_top = map.k.last().copied().unwrap_or(f64::NEG_INFINITY);
    let below = |start: &str, critical: &str, top: f64| {
        let critical = data.curve(&fig, critical);
        data.curve(&fig, start)
            .iter()
            .any(|&(x, _)| critical.iter().any(|c| c.0 == x && c.1 < top))
    };
    below(K_COLLAPSE_AT_START, K_CRIT_OF_MU, k_top)
        || below(MU_COLLAPSE_AT_START, MU_CRIT_OF_K, mu_top)
}

/// A collapse curve (x, y) where it parts from the static curve sampled at the same x by more
/// than 10⁻⁶·(1 + |y|), with the last sample on each side where they meet (so that the
/// dashed line leaves the static curve where the gap opens); NaN elsewhere. Samples without
/// a static value at their x count as parted.
fn parted(collapse: &[(f64, f64)], critical: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let apart: Vec<bool> = collapse
        .iter()
        .map(|&(x, y)| {
            critical
                .iter()
                .find(|c| c.0 == x)
                .is_none_or(|c| !c.1.is_finite() || (y - c.1).abs() > 1e-6 * (1.0 + y.abs()))
        })
        .collect();
    let near = |i: usize| {
        apart[i] || (i > 0 && apart[i - 1]) || apart.get(i + 1).copied().unwrap_or(false)
    };
    (collapse.iter().enumerate())
        .map(|(i, &(x, y))| if near(i) { (x, y) } else { (x, f64::NAN) })
        .collect()
}

/// The μ = ∞ column of the grid, when it has one: its regimes at the grid K values, the
/// located changes along K there and its collapse points.
fn infinite_strip(
    cells: &[MapCell<'_>],
    k: &[f64],
    bounds: &[&BoundaryRow],
) -> Option<InfiniteStrip> {
    let at_inf: Vec<_> = cells
        .iter()
        .filter(|c| c.mu.is_some_and(f64::is_infinite))
        .collect();
    if at_inf.is_empty() {
        return None;
    }
    let mut names = RegimeNames::default();
    let mut regimes: Vec<Option<Arc<str>>> = vec![None; k.len()];
    for c in at_inf {
        if let Some(j) = c.k.and_then(|kk| k.iter().position(|&g| g == kk)) {
            regimes[j] = c.regime.map(|g| names.of(g));
        }
    }
    let inf = bounds
        .iter()
        .filter(|b| b.mu.is_infinite() && b.axis == "k");
    Some(InfiniteStrip {
        regimes,
        crossings: inf
            .clone()
            .map(|b| Crossing {
                fixed: b.mu,
                at: b.k,
                low: b.regime_low.clone(),
                high: b.regime_high.clone(),
            })
            .collect(),
        collapse: inf
            .filter(|b| b.on_collapse_curve)
            .map(|b| (b.k, b.mechanism.clone().unwrap_or_default()))
            .collect(),
    })
}

/// The collapse curve in order along it, split by mechanism. Points are ordered by
/// K/ΔK − μ/Δμ, which increases along a curve on which K grows as μ falls (the collapse
/// curve of a symmetric arch); bifurcations end one segment and start the next.
fn collapse_segments(
    bounds: &[&BoundaryRow],
    bifs: &[(f64, f64)],
    span: ((f64, f64), (f64, f64)),
) -> Vec<CollapseSegment> {
    let dm = (span.0.1 - span.0.0).max(1e-12);
    let dk = (span.1.1 - span.1.0).max(1e-12);
    let key = |mu: f64, k: f64| k / dk - mu / dm;
    let mut pts: Vec<(f64, f64, Option<String>)> = bounds
        .iter()
        .filter(|b| b.on_collapse_curve)
        .map(|b| (b.mu, b.k, Some(b.mechanism.clone().unwrap_or_default())))
        .collect();
    if pts.is_empty() {
        return Vec::new();
    }
    pts.extend(bifs.iter().map(|&(m, k)| (m, k, None)));
    pts.sort_by(|a, b| key(a.0, a.1).total_cmp(&key(b.0, b.1)));
    let mut segs: Vec<CollapseSegment> = Vec::new();
    let mut cur: Option<CollapseSegment> = None;
    let mut pending_bif: Option<(f64, f64)> = None;
    for (m, k, mech) in pts {
        match mech {
            None => {
                if let Some(mut c) = cur.take() {
                    c.points.push((m, k));
                    segs.push(c);
                }
                pending_bif = Some((m, k));
            }
            Some(name) => match cur.as_mut() {
                Some(c) if c.mechanism == name => c.points.push((m, k)),
                _ => {
                    let mut start = Vec::new();
                    if let Some(c) = cur.take() {
                        start.push(*c.points.last().unwrap_or(&(m, k)));
                        segs.push(c);
                    } else if let Some(b) = pending_bif {
                        start.push(b);
                    }
                    start.push((m, k));
                    pending_bif = None;
                    cur = Some(CollapseSegment {
                        mechanism: name,
                        points: start,
                    });
                }
            },
        }
    }
    if let Some(c) = cur {
        segs.push(c);
    }
    segs.retain(|s| s.points.len() >= 2);
    segs
}

/// The boundaries off the collapse curve, one polyline per (low, high, axis) group.
fn other_boundaries(bounds: &[&BoundaryRow]) -> Vec<Vec<(f64, f64)>> {
    let mut groups: BTreeMap<(String, String, String), Vec<(f64, f64)>> = BTreeMap::new();
    for b in bounds.iter().filter(|b| !b.on_collapse_curve) {
        groups
            .entry((b.regime_low.clone(), b.regime_high.clone(), b.axis.clone()))
            .or_default()
            .push((b.mu, b.k));
    }
    groups
        .into_iter()
        .map(|((_, _, axis), mut pts)| {
            if axis == "k" {
                pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            } else {
                pts.sort_by(|a, b| a.1.total_cmp(&b.1));
            }
            pts
        })
        .filter(|p| p.len() >= 2)
        .collect()
}

/// The largest spacing of a grid axis.
fn largest_step(v: &[f64]) -> f64 {
    v.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max)
}

/// Extends each end of the other boundaries, whose located points stop a grid cell short of
/// where they meet another boundary, to that meeting point: a bifurcation, or the crossing
/// with the straight line through another boundary, when it lies on the end's own line
/// within one grid cell beyond the end.
fn extend_to_junctions(
    lines: &mut [Vec<(f64, f64)>],
    bifs: &[(f64, f64)],
    (mu, k): (&[f64], &[f64]),
) {
    let (dm, dk) = (largest_step(mu).max(1e-12), largest_step(k).max(1e-12));
    // In cell units, so that μ and K weigh alike.
    let unit = |p: (f64, f64)| (p.0 / dm, p.1 / dk);
    let ends: Vec<((f64, f64), (f64, f64))> = lines
        .iter()
        .filter_map(|l| Some((unit(*l.first()?), unit(*l.last()?))))
        .collect();
    let mut candidates: Vec<(f64, f64)> = bifs.iter().map(|&p| unit(p)).collect();
    for (i, a) in ends.iter().enumerate() {
        for b in &ends[i + 1..] {
            candidates.extend(line_crossing(*a, *b));
        }
    }
    for line in lines.iter_mut() {
        if line.len() < 2 {
            continue;
        }
        for at_end in [false, true] {
            let n = line.len();
            let (end, inner) = if at_end {
                (unit(line[n - 1]), unit(line[n - 2]))
            } else {
                (unit(line[0]), unit(line[1]))
            };
            let len = (end.0 - inner.0).hypot(end.1 - inner.1).max(1e-12);
            let dir = ((end.0 - inner.0) / len, (end.1 - inner.1) / len);
            let best = candidates
                .iter()
                .filter_map(|&c| {
                    let (x, y) = (c.0 - end.0, c.1 - end.1);
                    let along = x * dir.0 + y * dir.1;
                    let off = (x * dir.1 - y * dir.0).abs();
                    (along > 1e-9 && along <= 1.5 && off <= 0.05).then_some((along, c))
                })
                .min_by(|a, b| a.0.total_cmp(&b.0));
            if let Some((_, c)) = best {
                let p = (c.0 * dm, c.1 * dk);
                if at_end {
                    line.push(p);
                } else {
                    line.insert(0, p);
                }
            }
        }
    }
}

/// Where the line through a.0 and a.1 crosses the line through b.0 and b.1 (None when
/// parallel).
fn line_crossing(a: ((f64, f64), (f64, f64)), b: ((f64, f64), (f64, f64))) -> Option<(f64, f64)> {
    let r = (a.1.0 - a.0.0, a.1.1 - a.0.1);
    let s = (b.1.0 - b.0.0, b.1.1 - b.0.1);
    let den = r.0 * s.1 - r.1 * s.0;
    if den.abs() < 1e-12 {
        return None;
    }
    let u = ((b.0.0 - a.0.0) * s.1 - (b.0.1 - a.0.1) * s.0) / den;
    Some((a.0.0 + u * r.0, a.0.1 + u * r.1))
}

#[cfg(test)]
mod tests {
    use super::parted;

    #[test]
    fn a_collapse_curve_is_kept_where_it_parts_from_the_static_curve_and_one_sample_beyond() {
        let critical = [
            (1.0, 1.0),
            (2.0, 1.0),
            (3.0, 1.0),
            (4.0, 1.0),
            (5.0, 1.0),
            (6.0, 1.0),
        ];
        // Equal at 1, 2, 5 and 6 (within 10⁻⁶), apart at 3 and 4.
        let collapse = [
            (1.0, 1.0),
            (2.0, 1.0),
            (3.0, 1.5),
            (4.0, 1.7),
            (5.0, 1.0 + 1e-9),
            (6.0, 1.0),
        ];
        let p = parted(&collapse, &critical);
        let kept: Vec<bool> = p.iter().map(|q| q.1.is_finite()).collect();
        assert_eq!(kept, [false, true, true, true, true, false]);
        assert_eq!(p[2], (3.0, 1.5));
        assert!(p.iter().zip(&collapse).all(|(a, b)| a.0 == b.0));
        // A collapse equal to the static curve everywhere draws nothing.
        assert!(parted(&critical, &critical).iter().all(|q| q.1.is_nan()));
    }
}
