//! Where the arch of a λ map starts to stand under its own weight. A load_factor case with no
//! λ_max either never stands (the arch fails under self-weight alone) or stands under every
//! λ; between a grid point that never stands and one with a λ_max lies the thickness (along
//! K) or friction (along μ) at which the arch starts to stand, found here by bisection on the
//! self-weight state of the same arch and stored in curves.parquet, so that the λ map bounds
//! its "no finite λ" region by the limit itself rather than by the grid cells.

use super::{ArchGroup, Collector};
use crate::manifest::{LoadCase, Manifest};
use crate::model::{Friction, JointOrientation, Load};
use crate::scene::{self, Find, Scene};
use crate::store::LoadFactorCase;
use std::collections::{BTreeMap, BTreeSet};

/// The series of the crossings on edges along K (x = μ, y = K).
pub const ALONG_K: &str = "stand_limit_k";

/// The series of the crossings on edges along μ (x = μ, y = K).
pub const ALONG_MU: &str = "stand_limit_mu";

/// The most grid points of one load case and arch for which the crossings are found: a
/// denser map draws its cells finer than its pixels, where the grid's own steps do not show.
pub const MAX_POINTS: usize = 65_536;

/// Bisection stops when the bracket is this fraction of its grid edge.
const BISECTION_TOL: f64 = 1e-7;

/// The curves.parquet figure of the crossings of a load case on one arch: its half-angle,
/// eccentricity (`None`: circular), joint planes and voussoirs (`None`: the continuum), each
/// written so that it reads back to the same value.
pub fn stand_limit_figure(
    load_case: &str,
    half_angle_deg: f64,
    eccentricity: Option<f64>,
    joints: JointOrientation,
    voussoirs: Option<u32>,
) -> String {
    let e = eccentricity.map_or("circular".to_string(), |e| format!("e{e}"));
    let n = voussoirs.map_or("continuum".to_string(), |n| format!("n{n}"));
    format!(
        "stand-limit-{load_case}-a{half_angle_deg}-{e}-{}-{n}",
        joints.as_str()
    )
}

/// One grid of a load case and arch: its μ values (infinite friction last) and K values, and
/// at each point whether it has a λ_max.
struct Lattice {
    mu: Vec<f64>,
    k: Vec<f64>,
    has: BTreeMap<(u64, u64), bool>,
}

impl Lattice {
    fn of(cases: &[&LoadFactorCase]) -> Option<Self> {
        let mu: BTreeSet<u64> = cases.iter().map(|c| c.mu.to_bits()).collect();
        let k: BTreeSet<u64> = cases.iter().map(|c| c.k.to_bits()).collect();
        if k.len() < 2 || cases.len() > MAX_POINTS {
            return None;
        }
        let sorted = |s: BTreeSet<u64>| {
            let mut v: Vec<f64> = s.into_iter().map(f64::from_bits).collect();
            v.sort_by(f64::total_cmp);
            v
        };
        Some(Lattice {
            mu: sorted(mu),
            k: sorted(k),
            has: cases
                .iter()
                .map(|c| ((c.mu.to_bits(), c.k.to_bits()), c.load_factor.is_some()))
                .collect(),
        })
    }

    fn has(&self, mu: f64, k: f64) -> Option<bool> {
        self.has.get(&(mu.to_bits(), k.to_bits())).copied()
    }
}

/// Whether the arch of `group` at (μ, K) admits a state under its own weight.
fn stands(manifest: &Manifest, group: &ArchGroup, mu: f64, k: f64) -> Option<bool> {
    let arch = group.arch(manifest, k).ok()?;
    let sol = scene::solve(&Scene {
        arch,
        friction: Friction::new(mu)?,
        find: Find::State,
        form: group.form,
        load: Load::SelfWeight,
        lambda: 0.0,
    });
    Some(sol.regime == Some(crate::analysis::Regime::Stable))
}

/// The point between `a` (never stands) and `b` (stands) where the arch starts to stand.
fn bisect(a: f64, b: f64, stands_at: impl Fn(f64) -> Option<bool>) -> Option<f64> {
    let (mut lo, mut hi) = (a, b);
    let tol = BISECTION_TOL * (b - a).abs();
    while (hi - lo).abs() > tol {
        let mid = 0.5 * (lo + hi);
        if stands_at(mid)? {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Some(0.5 * (lo + hi))
}

/// The crossings of one grid edge from `p` to `q` (grid points (μ, K)) where one has a λ_max
/// and the other has none and does not stand: `None` otherwise.
fn crossing(
    manifest: &Manifest,
    group: &ArchGroup,
    l: &Lattice,
    (p, q): ((f64, f64), (f64, f64)),
) -> Option<(f64, f64)> {
    let (hp, hq) = (l.has(p.0, p.1)?, l.has(q.0, q.1)?);
    if hp == hq {
        return None;
    }
    let (never, found) = if hp { (q, p) } else { (p, q) };
    if stands(manifest, group, never.0, never.1)? {
        // No λ_max although it stands: every λ is carried, no limit of standing here.
        return None;
    }
    if never.0 == found.0 {
        let k = bisect(never.1, found.1, |k| stands(manifest, group, never.0, k))?;
        Some((never.0, k))
    } else {
        let mu = bisect(never.0, found.0, |mu| stands(manifest, group, mu, never.1))?;
        Some((mu, never.1))
    }
}

/// Pushes the crossings of every load_factor load case and arch of the study.
pub(super) fn push(
    manifest: &Manifest,
    lc: &LoadCase,
    cases: &[&LoadFactorCase],
    out: &mut Collector,
) {
    if lc.find != Find::LoadFactor {
        return;
    }
    let mut groups: BTreeMap<String, (ArchGroup, Vec<&LoadFactorCase>)> = BTreeMap::new();
    for c in cases.iter().filter(|c| c.load_case == lc.name) {
        let fig = stand_limit_figure(
            &lc.name,
            c.half_angle_deg,
            c.eccentricity,
            c.joints,
            c.voussoirs,
        );
        groups
            .entry(fig)
            .or_insert_with(|| (ArchGroup::of_case(manifest, c), Vec::new()))
            .1
            .push(c);
    }
    for (fig, (group, own)) in groups {
        let Some(l) = Lattice::of(&own) else { continue };
        let edges_k =
            l.mu.iter()
                .flat_map(|&mu| l.k.windows(2).map(move |w| ((mu, w[0]), (mu, w[1]))));
        // Along μ between finite values only: μ = ∞ is a column of its own.
        let edges_mu = l.k.iter().flat_map(|&k| {
            (l.mu.windows(2))
                .filter(|w| w[1].is_finite())
                .map(move |w| ((w[0], k), (w[1], k)))
        });
        let along_k: Vec<(f64, f64)> = edges_k
            .filter_map(|e| crossing(manifest, &group, &l, e))
            .collect();
        let along_mu: Vec<(f64, f64)> = edges_mu
            .filter_map(|e| crossing(manifest, &group, &l, e))
            .collect();
        out.push(&fig, ALONG_K, &along_k);
        out.push(&fig, ALONG_MU, &along_mu);
    }
}
