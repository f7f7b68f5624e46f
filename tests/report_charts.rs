//! Charts and sections of the report that depend on what a study varies: a load_factor study
//! over K and μ gets λ as a colour map with its mechanism regions, and a report leaves out a
//! section with nothing in it.

use crate::common::study_run;
use archstudy::output::RunLayout;
use archstudy::report::{charts, data};
use archstudy::store;

/// A horizontal body force over K and μ (with μ = ∞): the collapse mechanism changes over
/// the grid, so its bifurcations outline mechanism regions; boundaries.parquet stays empty
/// (regime boundaries belong to state studies).
pub const HORIZONTAL_MAP: &str = "\
name: horizontal
grid:
  k: {from: 1.1, to: 1.6, steps: 11}
  mu: {values: [0.3, 0.35, 0.4, 0.5, 0.6, 0.8, 1.0, inf]}
load_cases:
  - {name: horizontal, kind: horizontal}
find: load_factor
";

/// A small state study over K and μ: boundaries are located.
const STATE_MAP: &str = "\
name: state
grid:
  k: {from: 1.05, to: 1.4, steps: 8}
  mu: {from: 0.2, to: 0.8, steps: 7}
load_cases:
  - {name: gravity, kind: self_weight}
find: state
";

#[test]
fn boundaries_section_only_where_boundaries_were_located() {
    let lf = study_run("sections-lf", "horizontal.yaml", HORIZONTAL_MAP);
    let layout = RunLayout::at(&lf);
    let rows = store::read_boundaries(&layout.boundaries()).expect("boundaries.parquet");
    assert!(rows.is_empty(), "{} boundary rows", rows.len());
    let md = std::fs::read_to_string(layout.report_md()).expect("report.md");
    let html = std::fs::read_to_string(layout.report_html()).expect("report.html");
    assert!(!md.contains("## Boundaries"), "empty section in report.md");
    assert!(
        !html.contains("id=\"boundaries\""),
        "empty section in report.html"
    );
    assert!(
        !html.contains("href=\"#boundaries\""),
        "contents link to no section"
    );

    let st = study_run("sections-state", "state.yaml", STATE_MAP);
    let layout = RunLayout::at(&st);
    let rows = store::read_boundaries(&layout.boundaries()).expect("boundaries.parquet");
    assert!(rows.len() >= 8, "{} boundary rows", rows.len());
    let md = std::fs::read_to_string(layout.report_md()).expect("report.md");
    let section = md
        .split("## Boundaries")
        .nth(1)
        .expect("a Boundaries section where boundaries were located");
    // Every located point is counted once in the section's table of groups.
    let counted: usize = section
        .split("\n\n")
        .nth(2)
        .expect("the groups table")
        .lines()
        .skip(2)
        .filter_map(|l| l.split('|').nth(5)?.trim().parse::<usize>().ok())
        .sum();
    assert_eq!(counted, rows.len(), "{section}");
}

/// The λ map the report draws for a run.
fn lambda_map(run: &std::path::Path) -> archstudy::plot::lambda_map::LambdaMap {
    let data = data::load(&RunLayout::at(run)).expect("the run loads");
    charts::build(&data)
        .into_iter()
        .find_map(|f| match f.chart {
            charts::Chart::LambdaMap(m) => Some(m),
            _ => None,
        })
        .expect("a λ map")
}

#[test]
fn lambda_map_draws_the_stored_load_factors_and_the_located_mechanism_changes() {
    let run = study_run("lambda-map", "horizontal.yaml", HORIZONTAL_MAP);
    let layout = RunLayout::at(&run);
    let map = lambda_map(&run);
    let cases = store::read_load_factor_cases(&layout.results()).expect("results.parquet");
    let bifs = store::read_bifurcations(&layout.bifurcations()).expect("bifurcations.parquet");
    // Reduced to the figure's resolution, not to the grid's.
    assert_eq!((map.nx, map.ny), charts::lambda_map::RASTER);
    assert_eq!(map.lambda.len(), map.nx * map.ny);
    let ((mu0, mu1), (k0, k1)) = map.window;
    for (v, e) in [(mu0, 0.3), (mu1, 1.0), (k0, 1.1), (k1, 1.6)] {
        assert!((v - e).abs() < 1e-12, "{:?}", map.window);
    }
    let finite: Vec<&store::LoadFactorCase> = cases.iter().filter(|c| c.mu.is_finite()).collect();
    let at = |mu: f64, k: f64| {
        finite
            .iter()
            .find(|c| (c.mu - mu).abs() < 1e-12 && (c.k - k).abs() < 1e-12)
            .expect("a case at a grid point")
    };
    let mus = [0.3, 0.35, 0.4, 0.5, 0.6, 0.8, 1.0];
    let ks: Vec<f64> = (0..11).map(|j| 1.1 + 0.05 * f64::from(j)).collect();
    // Every raster cell whose four grid points collapse by one mechanism takes their
    // bilinear mean λ, computed here from the rows. In a cell crossed by a change of
    // mechanism, a raster cell takes λ from the grid points of its own drawn mechanism only:
    // it lies within the stored λ of that mechanism's grid points within two grid lines of
    // the cell, never at a value blended with the other mechanism's.
    let (mut checked, mut crossed) = (0, 0);
    for j in 0..map.ny {
        for i in 0..map.nx {
            let mu = mu0 + (mu1 - mu0) * (i as f64 + 0.5) / map.nx as f64;
            let k = k0 + (k1 - k0) * (j as f64 + 0.5) / map.ny as f64;
            let a = mus.partition_point(|&m| m <= mu).clamp(1, mus.len() - 1) - 1;
            let b = ks
                .partition_point(|&g| g <= k + 1e-12)
                .clamp(1, ks.len() - 1)
                - 1;
            let corner = |ii: usize, jj: usize| at(mus[ii], ks[jj]).load_factor;
            let c = [
                corner(a, b),
                corner(a + 1, b),
                corner(a, b + 1),
                corner(a + 1, b + 1),
            ];
            let Some(c) = c.into_iter().collect::<Option<Vec<f64>>>() else {
                continue;
            };
            let kind = |ii: usize, jj: usize| at(mus[ii], ks[jj]).mechanism.clone();
            let drawn = map.lambda[j * map.nx + i];
            let one = [(a + 1, b), (a, b + 1), (a + 1, b + 1)]
                .iter()
                .all(|&(ii, jj)| kind(ii, jj) == kind(a, b));
            if !one {
                let own = map.mechanism[j * map.nx + i].map(|x| map.mechanisms[x as usize].clone());
                let corners = [(a, b), (a + 1, b), (a, b + 1), (a + 1, b + 1)];
                if own.is_none() || !corners.iter().any(|&(ii, jj)| kind(ii, jj) == own) {
                    continue;
                }
                let near: Vec<f64> = (a.saturating_sub(2)..=(a + 3).min(mus.len() - 1))
                    .flat_map(|ii| {
                        (b.saturating_sub(2)..=(b + 3).min(ks.len() - 1)).map(move |jj| (ii, jj))
                    })
                    .filter(|&(ii, jj)| kind(ii, jj) == own)
                    .filter_map(|(ii, jj)| corner(ii, jj))
                    .collect();
                let lo = near.iter().copied().fold(f64::INFINITY, f64::min);
                let hi = near.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                assert!(
                    drawn >= lo - 1e-12 && drawn <= hi + 1e-12,
                    "cell ({i}, {j}) at μ = {mu}, K = {k}, {own:?}: {drawn} outside [{lo}, {hi}]"
                );
                crossed += 1;
                continue;
            }
            let (s, t) = (
                (mu - mus[a]) / (mus[a + 1] - mus[a]),
                (k - ks[b]) / (ks[b + 1] - ks[b]),
            );
            let expected = c[0] * (1.0 - s) * (1.0 - t)
                + c[1] * s * (1.0 - t)
                + c[2] * (1.0 - s) * t
                + c[3] * s * t;
            assert!(
                (drawn - expected).abs() <= 1e-9 * expected.abs().max(1e-3),
                "cell ({i}, {j}) at μ = {mu}, K = {k}: {drawn} against {expected}"
            );
            checked += 1;
        }
    }
    // About a third of the map lies in cells of one mechanism, half in crossed cells.
    assert!(
        checked > map.nx * map.ny / 4 && crossed > map.nx * map.ny / 4,
        "{checked} cells of one mechanism, {crossed} crossed cells checked"
    );
    // The scale spans the stored values, 0.0295 to 0.859: a factor of 29, under the 30 at
    // which the scale turns logarithmic.
    let stored: Vec<f64> = cases.iter().filter_map(|c| c.load_factor).collect();
    let lo = stored.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = stored.iter().copied().fold(0.0, f64::max);
    assert_eq!(map.lambda_range, (lo, hi));
    assert!((hi / lo - 29.18).abs() < 0.01, "λ from {lo} to {hi}");
    assert!(!map.log, "λ from {lo} to {hi} on a logarithmic scale");
    // The mechanism drawn at a grid point is the stored case's, away from the located
    // changes (two raster cells).
    let (cx, cy) = ((mu1 - mu0) / map.nx as f64, (k1 - k0) / map.ny as f64);
    let mut compared = 0;
    for c in &finite {
        let near = bifs.iter().any(|b| {
            b.mu.is_finite() && ((b.mu - c.mu) / cx).abs() < 2.0 && ((b.k - c.k) / cy).abs() < 2.0
        });
        let Some(m) = c.mechanism.as_deref() else {
            continue;
        };
        if near {
            continue;
        }
        let i = (((c.mu - mu0) / cx) as usize).min(map.nx - 1);
        let j = (((c.k - k0) / cy) as usize).min(map.ny - 1);
        let drawn = map.mechanism[j * map.nx + i].map(|x| map.mechanisms[x as usize].as_str());
        assert_eq!(drawn, Some(m), "μ = {}, K = {}", c.mu, c.k);
        compared += 1;
    }
    assert!(compared >= 50, "{compared} of 77 grid points compared");
    // Every vertex of a drawn boundary is a located change, and every pair of mechanisms
    // with located changes at finite μ on two neighbouring grid lines is outlined.
    let located = |p: &(f64, f64)| bifs.iter().any(|b| b.mu == p.0 && b.k == p.1);
    assert!(!map.boundaries.is_empty());
    for line in &map.boundaries {
        assert!(line.iter().all(located), "{line:?}");
    }
    let on_lines: usize = map.boundaries.iter().map(Vec::len).sum();
    let at_finite = bifs.iter().filter(|b| b.mu.is_finite()).count();
    assert!(
        on_lines * 10 >= at_finite * 8,
        "{on_lines} of {at_finite} located changes drawn"
    );
    // μ = ∞ is its own strip, with the stored λ at its ends.
    let strip = map.infinite.as_ref().expect("a μ = ∞ strip");
    let inf = |k: f64| {
        cases
            .iter()
            .find(|c| c.mu.is_infinite() && (c.k - k).abs() < 1e-12)
            .expect("a case at μ = ∞")
            .load_factor
    };
    // K = 1.1 lies below K_c = 1.1136 of the semicircle: no state stands, no λ. The cells
    // below K_c are grey; the others up to K = 1.15 take the λ of 1.15.
    assert_eq!(inf(1.1), None);
    let (Some(l155), Some(l160), Some(l115)) = (inf(1.55), inf(1.6), inf(1.15)) else {
        panic!("λ at μ = ∞ for K = 1.15, 1.55 and 1.6");
    };
    let centre = |j: usize| 1.1 + 0.5 * (j as f64 + 0.5) / map.ny as f64;
    let mut grey = 0;
    for (j, l) in strip.lambda.iter().enumerate() {
        let k = centre(j);
        if k < crate::common::reference::K_C {
            assert!(l.is_nan(), "K = {k}: {l}");
            grey += 1;
        } else if k < 1.15 {
            assert!((l - l115).abs() < 1e-12, "K = {k}: {l}");
        }
    }
    assert!(grey > 0, "no grey cell below K_c");
    let half = 0.5 / map.ny as f64 * 0.5 / 0.05;
    let expect_last = l160 - (l160 - l155) * half;
    let last = strip.lambda[map.ny - 1];
    assert!(
        (last - expect_last).abs() < 1e-9,
        "{last} against {expect_last}"
    );
    // Every grid point of finite μ whose collapse comes before λ_max is ringed, and no other.
    let rows = store::read_results(&layout.results()).expect("results.parquet");
    let mut gapped: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.gap.as_deref() == Some("gap") && r.mu.is_some_and(f64::is_finite))
        .map(|r| (r.mu.unwrap(), r.k.unwrap()))
        .collect();
    let mut ringed = map.gaps.clone();
    gapped.sort_by(|a, b| a.partial_cmp(b).unwrap());
    ringed.sort_by(|a, b| a.partial_cmp(b).unwrap());
    assert_eq!(ringed, gapped);
    // K = 1.6, μ = 1: the collapse turns about two extrados hinges a sliver apart and slides
    // at the right springing just below the rotational limit.
    assert!(ringed.contains(&(1.0, 1.6)), "{ringed:?}");
    for r in rows.iter().filter(|r| r.gap.as_deref() == Some("gap")) {
        assert!(r.collapse_value.unwrap() < r.load_factor.unwrap());
    }
}

#[test]
fn lambda_map_only_where_k_and_mu_have_several_values() {
    let few = HORIZONTAL_MAP.replace(
        "mu: {values: [0.3, 0.35, 0.4, 0.5, 0.6, 0.8, 1.0, inf]}",
        "mu: {values: [0.4, 0.6, inf]}",
    );
    let run = study_run("lambda-map-few", "horizontal.yaml", &few);
    let data = data::load(&RunLayout::at(&run)).expect("the run loads");
    let figures = charts::build(&data);
    assert!(figures.iter().any(|f| f.stem == "load-factor"));
    assert!(!figures.iter().any(|f| f.stem.starts_with("lambda-map")));
}

const HALF_ANGLES: &str = "\
name: segmental
grid:
  half_angle_deg: {values: [70, 80, 90]}
  k: {from: 1.01, to: 1.4, steps: 14}
  mu: {from: 0.15, to: 0.8, steps: 14}
load_cases:
  - {name: gravity, kind: self_weight}
find: state
";

#[test]
fn regime_map_panels_name_their_arch_and_the_caption_lists_their_bifurcations() {
    let run = study_run("panels-alpha", "segmental.yaml", HALF_ANGLES);
    let data = data::load(&RunLayout::at(&run)).expect("the run loads");
    let figure = charts::build(&data)
        .into_iter()
        .find(|f| f.stem == "regime-maps")
        .expect("regime maps by half-angle");
    // The paper figure has no title, but each panel is named by its α.
    let svg = figure
        .render(archstudy::plot::Format::Paper(
            archstudy::manifest::FigureWidth::Double,
        ))
        .expect("drawn");
    let svg = String::from_utf8(svg).expect("SVG text");
    for alpha in ["α = 70°", "α = 80°", "α = 90°"] {
        assert_eq!(svg.matches(alpha).count(), 1, "{alpha} in the paper figure");
    }
    // Every bifurcation of bifurcations.parquet is listed under its own panel, with μ and K
    // to four decimals (numbered on the map where its values find no place).
    let bifs: Vec<(f64, f64, f64)> = data
        .bifurcations
        .iter()
        .flatten()
        .zip(&data.bifurcation_groups)
        .map(|(b, g)| (g.half_angle_deg.expect("α"), b.mu, b.k))
        .collect();
    assert!(bifs.len() >= 4, "{bifs:?}");
    let listed = figure
        .caption
        .split(" Bifurcations by panel: ")
        .nth(1)
        .expect("bifurcations in the caption");
    for (alpha, mu, k) in bifs {
        let panel = listed
            .split(". ")
            .find(|p| p.starts_with(&format!("α = {alpha}°:")))
            .unwrap_or_else(|| panic!("no panel α = {alpha}° in {listed}"));
        let (mu, k) = (format!("μ = {mu:.4}"), format!("K = {k:.4}"));
        assert!(
            panel.contains(&mu) && panel.contains(&k),
            "{mu}, {k} not in {panel}"
        );
    }
}

#[test]
fn mechanism_panels_explain_their_orange_joint_dots() {
    let run = study_run("mechanism-dots", "state.yaml", STATE_MAP);
    let data = data::load(&RunLayout::at(&run)).expect("the run loads");
    let figures = charts::build(&data);
    let mut seen = 0;
    for f in &figures {
        let charts::Chart::Mechanisms(m) = &f.chart else {
            continue;
        };
        // One orange dot per sliding joint of the limit state in every panel, an arrow at
        // those that slip in the panel's mechanism: the caption says so.
        let slides: usize = m.panels.iter().map(|p| p.drawing.slides.len()).sum();
        let still = (m.panels.iter().flat_map(|p| &p.drawing.slides))
            .filter(|s| s.sense.is_none())
            .count();
        let svg = String::from_utf8(f.render(archstudy::plot::Format::Svg).expect("drawn"))
            .expect("SVG text");
        let orange = svg.matches("fill=\"#E67800\"").count();
        assert_eq!(orange, slides, "{}", f.stem);
        assert!(
            f.caption
                .contains("an orange dot at the middle of the joint"),
            "{}",
            f.caption
        );
        if still > 0 {
            assert!(
                f.caption.contains("a dot without an arrow"),
                "{}",
                f.caption
            );
        }
        seen += slides;
    }
    assert!(seen >= 2, "{seen} sliding joints drawn");
}

#[test]
fn voussoir_study_overlays_the_collapse_curve_of_every_count() {
    use archstudy::model::{Arch, Discretisation, Friction, WeightModel};
    use archstudy::scene::{self, Find, Scene};
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("studies/voussoirs.yaml");
    let text = std::fs::read_to_string(path).expect("studies/voussoirs.yaml");
    let run = study_run("voussoir-curves", "voussoirs.yaml", &text);
    let data = data::load(&RunLayout::at(&run)).expect("the run loads");
    let figure = charts::build(&data)
        .into_iter()
        .find(|f| f.stem == "collapse-curves")
        .expect("the collapse curves by voussoir count");
    let charts::Chart::Lines(chart) = &figure.chart else {
        panic!("a line chart");
    };
    let lines = &chart.panels[0].lines;
    let labels: Vec<&str> = lines.iter().map(|l| l.label.as_str()).collect();
    assert_eq!(labels, ["N = 6", "N = 8", "N = 12", "N = 24", "continuum"]);
    // At μ = 0.8 every arch collapses by hinges alone: the curve is flat at K_c of its
    // count, which an independent solve at infinite friction gives.
    let mut ends = Vec::new();
    for (line, n) in lines
        .iter()
        .zip([Some(6), Some(8), Some(12), Some(24), None])
    {
        let disc = n.map_or(Discretisation::Continuum, Discretisation::Voussoirs);
        let arch = Arch::new(1.2, 90.0, WeightModel::Annular, disc).expect("arch");
        let kc = scene::solve(&Scene::new(arch, Friction::INFINITE, Find::Thickness))
            .k_crit
            .expect("K_c");
        let end = line
            .points
            .iter()
            .find(|p| p.x >= 0.8 - 1e-9)
            .expect("a collapse point at μ = 0.8");
        assert!(
            (end.y - kc).abs() < 1e-6,
            "{}: {} against K_c = {kc}",
            line.label,
            end.y
        );
        assert_eq!(end.mechanism, "rotational", "{}", line.label);
        ends.push(end.y);
    }
    // The joints of 6 voussoirs are among those of 12, those among those of 24, and those
    // among the continuum's sections: more places for a hinge, never a thinner arch.
    let tol = 1e-9;
    assert!(
        ends[0] <= ends[2] + tol && ends[2] <= ends[3] + tol && ends[3] <= ends[4] + tol,
        "{ends:?}"
    );
    assert!(ends[..4].iter().all(|&k| k < ends[4]), "{ends:?}");
}

#[test]
fn a_friction_study_with_a_gap_draws_the_collapse_beside_the_critical_curve() {
    let manifest = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/studies/vertical-joints-drop.yaml"
    ))
    .unwrap();
    let run = study_run("gap-critical", "drop.yaml", &manifest);
    let data = data::load(&RunLayout::at(&run)).expect("the run loads");
    let figure = charts::build(&data)
        .into_iter()
        .find(|f| f.stem == "critical-curves")
        .expect("the critical curves");
    let charts::Chart::Critical(c) = &figure.chart else {
        panic!("not a critical chart");
    };
    let p = &c.panels[0];
    // At K = 1.3 the crown part drops from μ = 2.0553 down (W_c / 2 H_min, tests/gap.rs),
    // far above μ_c = 0.8828.
    let at = |curve: &[(f64, f64)]| {
        curve
            .iter()
            .find(|q| (q.0 - 1.3).abs() < 1e-9)
            .expect("K = 1.3")
            .1
    };
    assert!((at(&p.collapse) - 2.0553).abs() < 1e-4, "{:?}", p.collapse);
    assert!((at(&p.curve) - 0.8828).abs() < 1e-4, "{:?}", p.curve);
    assert!(p.collapse.iter().zip(&p.curve).all(|(c, s)| c.0 == s.0));
    assert!(
        figure.caption.contains("Dashed: the collapse"),
        "{}",
        figure.caption
    );
    // A study without a gap draws none.
    let run = study_run("gap-none", "state.yaml", STATE_MAP);
    let data = data::load(&RunLayout::at(&run)).expect("the run loads");
    for f in charts::build(&data) {
        if let charts::Chart::Critical(c) = &f.chart {
            assert!(c.panels.iter().all(|p| p.collapse.is_empty()));
            assert!(!f.caption.contains("Dashed: the collapse"));
        }
    }
}

#[test]
fn load_factor_lines_bar_the_gap_from_the_collapse_up_to_the_static_limit() {
    let manifest = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/studies/vertical-joints-horizontal.yaml"
    ))
    .unwrap();
    let run = study_run("gap-lines", "vj.yaml", &manifest);
    let data = data::load(&RunLayout::at(&run)).expect("the run loads");
    let figure = charts::build(&data)
        .into_iter()
        .find(|f| f.stem == "load-factor")
        .expect("the load-factor figure");
    let charts::Chart::Lines(c) = &figure.chart else {
        panic!("not a lines chart");
    };
    // Panel (b), λ against μ, one line per K (every case of finite μ): every barred point is
    // a stored case whose collapse comes before λ_max by its gap width.
    let rows = store::read_results(&RunLayout::at(&run).results()).unwrap();
    let mut barred = 0;
    for (line, k) in c.panels[1].lines.iter().zip([1.15, 1.3, 1.45]) {
        for q in line.points.iter().filter(|q| q.collapse.is_finite()) {
            let r = rows
                .iter()
                .find(|r| r.k == Some(k) && r.mu == Some(q.x))
                .expect("the case");
            assert_eq!(r.gap.as_deref(), Some("gap"));
            assert!((q.y - q.collapse - r.gap_width.unwrap()).abs() < 1e-12);
            assert!(q.collapse < q.y);
            barred += 1;
        }
    }
    let gaps = rows
        .iter()
        .filter(|r| r.gap.as_deref() == Some("gap"))
        .count();
    assert_eq!(barred, gaps);
    assert!(gaps >= 5, "{gaps}");
    assert!(
        figure
            .caption
            .contains(&format!("in {gaps} of the 15 cases")),
        "{}",
        figure.caption
    );
}

#[test]
fn the_lambda_map_bounds_its_grey_region_by_where_the_arch_starts_to_stand() {
    use crate::common::reference::{K_C, MU_MIN};
    use archstudy::figdata::stand_limit::{ALONG_K, ALONG_MU};
    let run = study_run("lambda-map-stand", "horizontal.yaml", HORIZONTAL_MAP);
    let layout = RunLayout::at(&run);
    let curves = store::read_curves(&layout.curves()).expect("curves.parquet");
    let along = |s: &str| -> Vec<(f64, f64)> {
        (curves.iter())
            .filter(|p| p.figure.starts_with("stand-limit-horizontal") && p.series == s)
            .map(|p| (p.x, p.y))
            .collect()
    };
    // Along K, at every μ from 0.4 up (and ∞) the semicircle starts to stand at K_c; along μ,
    // at every K from 1.25 up at μ_min, and at K = 1.2 at μ_c(1.2) of the friction find.
    let k_edges = along(ALONG_K);
    assert!(
        k_edges.iter().filter(|p| p.0 >= 0.4).count() == 6,
        "{k_edges:?}"
    );
    for p in k_edges.iter().filter(|p| p.0 >= 0.4) {
        assert!((p.1 - K_C).abs() < 1e-6, "{p:?}");
    }
    let mu_edges = along(ALONG_MU);
    for p in mu_edges.iter().filter(|p| p.1 >= 1.25) {
        assert!((p.0 - MU_MIN).abs() < 1e-6, "{p:?}");
    }
    let at_12 = mu_edges
        .iter()
        .find(|p| (p.1 - 1.2).abs() < 1e-12)
        .expect("K = 1.2");
    assert!((at_12.0 - 0.3232251).abs() < 1e-6, "{at_12:?}");
    // The map is grey on the near side of the limit and coloured on the far side, not at the
    // grid cell's edge: the raster cells just either side of K_c at μ = 0.7, and of μ_min at
    // K = 1.5.
    let map = lambda_map(&run);
    let ((mu0, mu1), (k0, k1)) = map.window;
    let pixel = |mu: f64, k: f64| {
        let i = ((mu - mu0) / (mu1 - mu0) * map.nx as f64) as usize;
        let j = ((k - k0) / (k1 - k0) * map.ny as f64) as usize;
        map.lambda[j * map.nx + i]
    };
    let (dk, dmu) = ((k1 - k0) / map.ny as f64, (mu1 - mu0) / map.nx as f64);
    assert!(pixel(0.7, K_C - 1.5 * dk).is_nan());
    assert!(pixel(0.7, K_C + 1.5 * dk).is_finite());
    assert!(pixel(MU_MIN - 1.5 * dmu, 1.5).is_nan());
    assert!(pixel(MU_MIN + 1.5 * dmu, 1.5).is_finite());
}

#[test]
fn a_state_study_of_vertical_joints_draws_the_collapse_beside_its_critical_curves() {
    use archstudy::figdata::{MU_COLLAPSE_OF_K, MU_CRIT_OF_K, critical_figure};
    let run = study_run(
        "state-collapse",
        "vertical.yaml",
        "name: vertical\narch: {joints: vertical}\ngrid:\n  k: {from: 1.15, to: 1.5, steps: 8}\n  mu: {from: 1.0, to: 3.0, steps: 9}\nload_cases:\n  - {name: gravity, kind: self_weight}\nfind: state\n",
    );
    let layout = RunLayout::at(&run);
    let curves = store::read_curves(&layout.curves()).expect("curves.parquet");
    let fig = critical_figure("gravity");
    let series = |s: &str| -> Vec<(f64, f64)> {
        (curves.iter())
            .filter(|p| p.figure == fig && p.series == s)
            .map(|p| (p.x, p.y))
            .collect()
    };
    let (col, crit) = (series(MU_COLLAPSE_OF_K), series(MU_CRIT_OF_K));
    assert_eq!(col.len(), crit.len());
    // The collapse lies above μ_c at every sample where both exist, and at K = 1.5 where the
    // friction find puts it (the crown part drops, sliding inward on both springings).
    let mut above = 0;
    for (c, s) in col.iter().zip(&crit) {
        assert_eq!(c.0, s.0);
        if c.1.is_finite() && s.1.is_finite() {
            assert!(c.1 >= s.1 - 1e-9, "{c:?} {s:?}");
            above += usize::from(c.1 > s.1 + 1e-3);
        }
    }
    assert!(above > col.len() / 2, "{above} of {}", col.len());
    let last = col.last().expect("a sample at K = 1.5");
    assert!((last.0 - 1.5).abs() < 1e-12);
    let sol = archstudy::scene::solve(&archstudy::scene::Scene {
        arch: archstudy::model::Arch::new(
            1.5,
            90.0,
            archstudy::model::WeightModel::Annular,
            archstudy::model::Discretisation::Continuum,
        )
        .unwrap(),
        friction: archstudy::model::Friction::new(0.0).unwrap(),
        find: archstudy::scene::Find::Friction,
        form: archstudy::model::ArchForm {
            joints: archstudy::model::JointOrientation::Vertical,
            ..Default::default()
        },
        load: archstudy::model::Load::SelfWeight,
        lambda: 0.0,
    });
    assert_eq!(Some(last.1), sol.collapse_value);
    let md = std::fs::read_to_string(layout.report_md()).expect("report.md");
    assert!(md.contains("Dashed: the collapse, the first complete solution"));
    // The regime map draws the same collapse over (μ, K), where the gap opens in its stable
    // region, and says so.
    let regime = |run: &std::path::Path| {
        let data = data::load(&RunLayout::at(run)).expect("the run loads");
        charts::build(&data)
            .into_iter()
            .find(|f| f.stem == "regime-map")
            .expect("a regime map")
    };
    let f = regime(&run);
    let charts::Chart::RegimeMap(m) = &f.chart else {
        panic!("not a regime map");
    };
    // Drawn where it parts from μ_c(K): at more than half the samples.
    let drawn = m
        .gap_collapse
        .iter()
        .find(|l| l.iter().any(|p| p.1 == 1.5))
        .expect("the collapse along μ");
    let mut parted = 0;
    for ((c, s), d) in col.iter().zip(&crit).zip(drawn) {
        assert_eq!(d.1, c.0);
        if c.1 > s.1 + 1e-3 {
            assert_eq!(d.0, c.1);
            parted += 1;
        }
    }
    assert!(parted > col.len() / 2, "{drawn:?}");
    assert!(f.caption.contains("drawn dashed here"), "{}", f.caption);
    // The circular arch with radial joints has no gap: no collapse series at all, and none
    // on its regime map.
    let lf = study_run("state-collapse-seed", "state.yaml", STATE_MAP);
    let curves = store::read_curves(&RunLayout::at(&lf).curves()).expect("curves.parquet");
    assert!(!curves.iter().any(|p| p.series == MU_COLLAPSE_OF_K));
    let f = regime(&lf);
    let charts::Chart::RegimeMap(m) = &f.chart else {
        panic!("not a regime map");
    };
    assert!(m.gap_collapse.is_empty());
    assert!(!f.caption.contains("drawn dashed here"));
    // The pointed arch (e = 0.2) below μ = 0.26 has complete states at the top of its form
    // (K = 9) whose mechanisms the loads do no work on: nothing drives them, so they are no
    // collapse. Its collapse is its static curve everywhere (the static limit's own mechanism
    // obeys the flow rules), and the map shows no gap and says none.
    let pointed = study_run(
        "state-collapse-pointed",
        "pointed.yaml",
        "name: pointed\narch: {shape: pointed, eccentricity: 0.2}\ngrid:\n  k: {from: 1.03, to: 1.4, steps: 6}\n  mu: {values: [0.15, 0.2, 0.3, 0.5, 0.8]}\nload_cases:\n  - {name: gravity, kind: self_weight}\nfind: state\n",
    );
    let curves = store::read_curves(&RunLayout::at(&pointed).curves()).expect("curves.parquet");
    let at_start = |s: &str| curves.iter().filter(|p| p.series == s).count();
    assert_eq!(at_start(archstudy::figdata::K_COLLAPSE_AT_START), 0);
    assert_eq!(at_start(archstudy::figdata::K_COLLAPSE_OF_MU), 0);
    let f = regime(&pointed);
    let charts::Chart::RegimeMap(m) = &f.chart else {
        panic!("not a regime map");
    };
    assert!(m.gap_collapse.is_empty(), "{:?}", m.gap_collapse);
    assert!(
        !f.caption.contains("Stable is the static verdict"),
        "{}",
        f.caption
    );
}
