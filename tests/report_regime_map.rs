//! The regime map agrees with the located boundaries at any grid size: on coarse grids (the
//! coarse seed study and the README's μ ∈ {0.3, 0.35, 0.4, ∞}) the regime the figure draws
//! at points away from the boundaries is the regime an independent solve gives there, no
//! point drawn stable lies on the unstable side of the located collapse curve (nor the
//! other way round), and μ = ∞ is drawn as its own strip. A half-angle axis gets one map
//! per arch, each with its own bifurcations, and a table of them; a voussoir study with
//! several cases per count tabulates the values behind its errors.

use crate::common::{run_study, scratch};
use archstudy::model::{Arch, Discretisation, Friction, WeightModel};
use archstudy::output::RunLayout;
use archstudy::plot::regime_map::RegimeMap;
use archstudy::report::{charts, data};
use archstudy::scene::{self, Find, Scene};
use std::path::Path;

const README_STUDY: &str = "\
name: readme
grid:
  k: {from: 1.05, to: 1.5, steps: 181}
  mu: {values: [0.3, 0.35, 0.4, inf]}
load_cases:
  - {name: gravity, kind: self_weight}
find: state
";

/// The regime map the report draws for a run.
fn regime_map(run: &Path) -> RegimeMap {
    let data = data::load(&RunLayout::at(run)).expect("the run loads");
    charts::build(&data)
        .into_iter()
        .find_map(|f| match f.chart {
            charts::Chart::RegimeMap(m) => Some(m),
            _ => None,
        })
        .expect("a regime map")
}

/// The regime of the semicircle under self-weight at (μ, K), solved on its own.
fn solved(mu: f64, k: f64) -> String {
    let arch = Arch::new(k, 90.0, WeightModel::Annular, Discretisation::Continuum).expect("arch");
    let friction = Friction::new(mu).expect("friction");
    let s = scene::solve(&Scene::new(arch, friction, Find::State));
    s.regime().expect("a regime").as_str().to_string()
}

/// A reproducible sequence in [0, 1).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Every located boundary point of the map and its bifurcations, (μ, K).
fn located(m: &RegimeMap) -> Vec<(f64, f64)> {
    let mut v: Vec<(f64, f64)> = m
        .crossings_along_mu
        .iter()
        .map(|c| (c.at, c.fixed))
        .chain(m.crossings_along_k.iter().map(|c| (c.fixed, c.at)))
        .collect();
    v.extend(m.bifurcations.iter().map(|b| (b.mu, b.k)));
    v
}

/// Samples 200 points at least `gap` (in fractions of the axes) from every located boundary
/// point and checks the drawn regime against the solved one.
fn drawn_agrees_with_solve(m: &RegimeMap, gap: f64) {
    let (mu0, mu1) = (m.mu[0], m.mu[m.mu.len() - 1]);
    let (k0, k1) = (m.k[0], m.k[m.k.len() - 1]);
    let pts = located(m);
    let far = |mu: f64, k: f64| {
        pts.iter()
            .all(|&(pm, pk)| ((pm - mu) / (mu1 - mu0)).hypot((pk - k) / (k1 - k0)) >= gap)
    };
    let mut rng = Lcg(16);
    let mut checked = 0;
    while checked < 200 {
        let (mu, k) = (mu0 + (mu1 - mu0) * rng.next(), k0 + (k1 - k0) * rng.next());
        if !far(mu, k) {
            continue;
        }
        let drawn = m.regime_at(mu, k).map(str::to_string);
        assert_eq!(drawn, Some(solved(mu, k)), "at μ = {mu}, K = {k}");
        checked += 1;
    }
}

/// K_c(μ) by straight lines between the located points of the collapse curve off the
/// sliding segment, and the μ of the sliding segment: the stable side is K ≥ K_c(μ) and
/// μ ≥ μ_s (None on the curve).
fn stable_side(m: &RegimeMap) -> impl Fn(f64, f64) -> Option<bool> {
    let mut curve: Vec<(f64, f64)> = m
        .collapse
        .iter()
        .filter(|s| s.mechanism != "sliding")
        .flat_map(|s| s.points.iter().copied())
        .collect();
    curve.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mu_s = m
        .collapse
        .iter()
        .filter(|s| s.mechanism == "sliding")
        .flat_map(|s| s.points.iter().map(|p| p.0))
        .fold(f64::NEG_INFINITY, f64::max);
    move |mu: f64, k: f64| {
        let kc = match curve.iter().position(|p| p.0 >= mu) {
            Some(0) => curve[0].1,
            Some(i) => {
                let (a, b) = (curve[i - 1], curve[i]);
                a.1 + (b.1 - a.1) * (mu - a.0) / (b.0 - a.0)
            }
            None => curve[curve.len() - 1].1,
        };
        let tol = 1e-9;
        if mu < mu_s - tol || k < kc - tol {
            Some(false)
        } else if mu > mu_s + tol && k > kc + tol {
            Some(true)
        } else {
            None
        }
    }
}

/// On a 300 × 300 sample of the drawn map and along its grid lines, stable exactly on the stable side of the located
/// collapse curve.
fn stable_only_on_stable_side(m: &RegimeMap) {
    let side = stable_side(m);
    let (mu0, mu1) = (m.mu[0], m.mu[m.mu.len() - 1]);
    let (k0, k1) = (m.k[0], m.k[m.k.len() - 1]);
    let n = 300;
    let spread = |a: f64, b: f64, grid: &[f64]| {
        let mut v: Vec<f64> = (0..n)
            .map(|i| a + (b - a) * (i as f64 + 0.5) / n as f64)
            .collect();
        v.extend(grid);
        v
    };
    for &k in &spread(k0, k1, &m.k) {
        for &mu in &spread(mu0, mu1, &m.mu) {
            let Some(stable) = side(mu, k) else {
                continue;
            };
            assert_eq!(
                m.regime_at(mu, k) == Some("stable"),
                stable,
                "drawn {:?} at μ = {mu}, K = {k}",
                m.regime_at(mu, k)
            );
        }
    }
}

/// The μ = ∞ strip: rotational below the located K_c, stable above, as solved.
fn infinite_strip_is_drawn(m: &RegimeMap) {
    let strip = m.infinite.as_ref().expect("μ = ∞ is drawn as a strip");
    let kc = strip
        .collapse
        .iter()
        .find(|c| c.1 == "rotational")
        .expect("the rotational collapse at μ = ∞")
        .0;
    assert!((kc - 1.113581813339).abs() < 1e-8, "K_c at μ = ∞: {kc}");
    let (k0, k1) = (m.k[0], m.k[m.k.len() - 1]);
    for j in 0..50 {
        let k = k0 + (k1 - k0) * (j as f64 + 0.5) / 50.0;
        if (k - kc).abs() > 1e-6 {
            let expected = solved(f64::INFINITY, k);
            assert_eq!(
                m.regime_at(f64::INFINITY, k),
                Some(expected.as_str()),
                "K = {k}"
            );
        }
    }
}

#[test]
fn coarse_seed_regime_map_agrees_with_its_located_boundaries() {
    let dir = scratch("regime-map-coarse");
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("studies/coarse-seed.yaml"),
    )
    .expect("studies/coarse-seed.yaml");
    let run = run_study(&dir, "coarse-seed.yaml", &text);
    let m = regime_map(&run);
    assert_eq!(m.mu.len(), 11, "the finite μ axis");
    // The dashed boundaries reach where they meet: the corner (μ_min, K_c) of the none,
    // rotational, mixed and sliding regions and the rotational/mixed bifurcation, not the
    // last located point a grid cell short of them.
    let reaches = |mu: f64, k: f64| {
        m.other_boundaries
            .iter()
            .filter(|l| {
                l.iter()
                    .any(|p| (p.0 - mu).abs() < 1e-8 && (p.1 - k).abs() < 1e-8)
            })
            .count()
    };
    assert_eq!(
        reaches(0.309215444330, 1.113581813339),
        4,
        "{:?}",
        m.other_boundaries
    );
    assert!(reaches(0.395265252140, 1.113581813339) >= 1);
    drawn_agrees_with_solve(&m, 0.01);
    stable_only_on_stable_side(&m);
    infinite_strip_is_drawn(&m);
}

#[test]
fn readme_regime_map_agrees_with_its_located_boundaries() {
    let dir = scratch("regime-map-readme");
    let run = run_study(&dir, "readme.yaml", README_STUDY);
    let m = regime_map(&run);
    assert_eq!(m.mu, vec![0.3, 0.35, 0.4]);
    drawn_agrees_with_solve(&m, 0.01);
    stable_only_on_stable_side(&m);
    infinite_strip_is_drawn(&m);
}

const HALF_ANGLE_STUDY: &str = "\
name: segmental
grid:
  half_angle_deg: {values: [80, 90]}
  k: {from: 1.02, to: 1.4, steps: 9}
  mu: {from: 0.15, to: 0.8, steps: 8}
load_cases:
  - {name: gravity, kind: self_weight}
find: state
";

#[test]
fn half_angle_study_gets_one_regime_map_per_arch_and_its_collapse_curves() {
    let dir = scratch("regime-map-half-angle");
    let run = run_study(&dir, "segmental.yaml", HALF_ANGLE_STUDY);
    let data = data::load(&RunLayout::at(&run)).expect("the run loads");
    let figures = charts::build(&data);
    let maps = figures
        .iter()
        .find_map(|f| match &f.chart {
            charts::Chart::RegimeMapPanels(p) => Some(p.maps.clone()),
            _ => None,
        })
        .expect("regime maps by half-angle");
    let titles: Vec<&str> = maps.iter().map(|m| m.title.as_str()).collect();
    assert_eq!(titles, ["α = 80°", "α = 90°"]);
    // Each panel carries the bifurcations of its own arch only.
    let mut bifs: Vec<(f64, f64, f64)> = data
        .bifurcations
        .iter()
        .flatten()
        .zip(&data.bifurcation_groups)
        .map(|(b, g)| (g.half_angle_deg.expect("α"), b.mu, b.k))
        .collect();
    bifs.sort_by(|a, b| a.partial_cmp(b).expect("finite"));
    let mut drawn: Vec<(f64, f64, f64)> = maps
        .iter()
        .zip([80.0, 90.0])
        .flat_map(|(m, a)| m.bifurcations.iter().map(move |b| (a, b.mu, b.k)))
        .collect();
    drawn.sort_by(|a, b| a.partial_cmp(b).expect("finite"));
    assert_eq!(drawn, bifs);
    // The semicircle's panel has the reference bifurcations.
    let semi = &maps[1];
    assert!(
        semi.bifurcations
            .iter()
            .any(|b| (b.mu - 0.395265252140).abs() < 1e-6 && (b.k - 1.113581813339).abs() < 1e-6)
    );
    // The α = 80° map never draws a region against an independent solve of its own arch.
    let m80 = &maps[0];
    for (mu, k) in [(0.5, 1.3), (0.5, 1.03), (0.17, 1.3), (0.17, 1.03)] {
        let arch =
            Arch::new(k, 80.0, WeightModel::Annular, Discretisation::Continuum).expect("arch");
        let s = scene::solve(&Scene::new(
            arch,
            Friction::new(mu).expect("μ"),
            Find::State,
        ));
        let solved = s.regime().expect("regime").as_str().to_string();
        assert_eq!(
            m80.regime_at(mu, k),
            Some(solved.as_str()),
            "μ = {mu}, K = {k}"
        );
    }
    let stems: Vec<&str> = figures.iter().map(|f| f.stem.as_str()).collect();
    assert!(stems.contains(&"collapse-curves"), "{stems:?}");
    assert!(stems.contains(&"bifurcations-by-arch"), "{stems:?}");
    assert!(
        !stems.contains(&"regime-map"),
        "no single map of mixed arches"
    );
    // "What was computed" describes the half-angle as the axis it is.
    let md = std::fs::read_to_string(run.join("report.md")).expect("report.md");
    let computed = md
        .split("## Key results")
        .next()
        .expect("what was computed");
    assert!(
        computed.contains("half-embrace angle α (°): grid axis, 2 values: from 80 to 90"),
        "{computed}"
    );
    assert!(!computed.contains("α = 90°"), "{computed}");
    // The bifurcations by arch, tabulated.
    assert!(md.contains("### Bifurcations by arch"), "{md}");
    assert!(
        md.contains("| α = 90° | rotational / mixed | 0.3953 | 1.1136 | 0.1075 |"),
        "{md}"
    );
}

const ONE_COUNT_STUDY: &str = "\
name: one-count
grid:
  voussoirs: {values: [8, continuum]}
  mu: {values: [0.4, 0.6, 0.8]}
load_cases:
  - {name: gravity, kind: self_weight}
find: thickness
";

#[test]
fn voussoir_study_tabulates_the_values_behind_its_errors_and_skips_a_one_point_chart() {
    let dir = scratch("values-one-count");
    let run = run_study(&dir, "one-count.yaml", ONE_COUNT_STUDY);
    let data = data::load(&RunLayout::at(&run)).expect("the run loads");
    let stems: Vec<String> = charts::build(&data).into_iter().map(|f| f.stem).collect();
    assert!(!stems.iter().any(|s| s == "speed-accuracy"), "{stems:?}");
    let md = std::fs::read_to_string(run.join("report.md")).expect("report.md");
    assert!(md.contains("### K_c by voussoir count and case"), "{md}");
    // One row per μ for N = 8, each with the continuum K_c = 1.1135818133 at μ ≥ μ_rot.
    for mu in ["0.4000", "0.6000", "0.8000"] {
        assert!(
            md.contains(&format!(
                "| {mu} | 8 | 1.1062181517 | 1.1135818133 | -7.364e-3 |"
            )),
            "{md}"
        );
    }
}
