//! Figures and reports: the Markdown golden file, key results against the stored values,
//! `archstudy report` on a copied run, and the figure files.

use crate::common::{assert_usage_error, run_study, scratch};
use archstudy::analysis::symmetric::{self, Critical, CriticalState};
use archstudy::model::{Arch, Friction, t_over_r_from_k};
use archstudy::output::RunLayout;
use archstudy::runner;
use archstudy::store::{self, TableBuilder};
use std::path::{Path, PathBuf};
use std::process::Command;

const SMALL_STUDY: &str = "\
name: small
title: Semicircular arch, coarse grid
description: An 11 x 11 grid over K and mu for the report tests.
arch:
  half_angle_deg: 90
  weight: annular
  voussoirs: continuum
grid:
  k: {from: 1.05, to: 1.5, steps: 11}
  mu: {from: 0.2, to: 0.8, steps: 11}
load_cases:
  - {name: gravity, kind: self_weight}
find: state
scenes:
  - {k: 1.35, mu: 0.4}
  - {k: 1.08, mu: 0.5}
";

/// Runs the small study into `dir`, with a fixed command line and one thread.
fn run_small(dir: &Path) -> PathBuf {
    run_study(dir, "small.yaml", SMALL_STUDY)
}

fn found(c: Critical) -> Option<CriticalState> {
    match c {
        Critical::Found(s) => Some(s),
        _ => None,
    }
}

#[derive(Default)]
struct Rows {
    load_case: Vec<String>,
    mu: Vec<f64>,
    k: Vec<f64>,
    low: Vec<String>,
    high: Vec<String>,
    axis: Vec<String>,
    on: Vec<bool>,
    mech: Vec<Option<String>>,
    thrust: Vec<Option<f64>>,
    moment: Vec<Option<f64>>,
    ha: Vec<Vec<f64>>,
    hf: Vec<Vec<String>>,
    sa: Vec<Vec<f64>>,
    ss: Vec<Vec<String>>,
}

impl Rows {
    fn push(
        &mut self,
        mu: f64,
        k: f64,
        low: &str,
        high: &str,
        axis: &str,
        s: Option<&CriticalState>,
    ) {
        self.load_case.push("gravity".into());
        self.mu.push(mu);
        self.k.push(k);
        self.low.push(low.into());
        self.high.push(high.into());
        self.axis.push(axis.into());
        self.on.push(s.is_some());
        self.mech
            .push(s.map(|s| s.mechanism.kind.as_str().to_string()));
        self.thrust.push(s.map(|s| s.thrust_over_half_weight));
        self.moment
            .push(s.map(|s| s.crown_moment).filter(|m| m.is_finite()));
        let m = s.map(|s| s.mechanism.clone());
        self.ha.push(
            m.iter()
                .flat_map(|m| m.hinges.iter().map(|h| h.angle_deg))
                .collect(),
        );
        self.hf.push(
            m.iter()
                .flat_map(|m| m.hinges.iter().map(|h| h.face.as_str().to_string()))
                .collect(),
        );
        self.sa.push(
            m.iter()
                .flat_map(|m| m.sliding_joints.iter().map(|h| h.angle_deg))
                .collect(),
        );
        self.ss.push(
            m.iter()
                .flat_map(|m| {
                    m.sliding_joints
                        .iter()
                        .map(|h| h.sense.as_str().to_string())
                })
                .collect(),
        );
    }
}

/// Writes boundaries.parquet and bifurcations.parquet for a K × μ grid of the semicircular
/// arch, with the schema of the boundaries stage, from the analysis (a stand-in for that
/// stage, so that these tests do not depend on it).
fn write_boundary_fixture(dir: &Path, ks: &[f64], mus: &[f64]) {
    let arch = Arch::semicircular(1.3).unwrap();
    let k_c = found(symmetric::thickness(&arch, Friction::INFINITE)).unwrap();
    let mu_min = found(symmetric::sliding_threshold(&arch)).unwrap().mu;
    let mu_rot = k_c.thrust_over_half_weight;
    let (k_lo, k_hi) = (ks[0], ks[ks.len() - 1]);
    let (mu_lo, mu_hi) = (mus[0], mus[mus.len() - 1]);
    let mut b = Rows::default();
    for &mu in mus {
        if mu >= mu_min {
            let s = found(symmetric::thickness(&arch, Friction::new(mu).unwrap())).unwrap();
            if s.k > k_lo && s.k < k_hi {
                let low = if s.mechanism.kind.as_str() == "rotational" {
                    "rotational"
                } else {
                    "mixed"
                };
                b.push(mu, s.k, low, "stable", "k", Some(&s));
            }
            if mu < mu_rot {
                b.push(mu, k_c.k, "rotational", "mixed", "k", None);
            }
        } else {
            b.push(mu, k_c.k, "none", "sliding", "k", None);
        }
    }
    let k_bif = found(symmetric::thickness(&arch, Friction::new(mu_min).unwrap())).unwrap();
    for &k in ks {
        if k >= k_c.k {
            let s = found(symmetric::friction(&arch.with_k(k))).unwrap();
            if s.mu > mu_lo && s.mu < mu_hi {
                let low = if k >= k_bif.k { "sliding" } else { "mixed" };
                b.push(s.mu, k, low, "stable", "mu", Some(&s));
            }
            if k < k_bif.k {
                b.push(mu_min, k, "sliding", "mixed", "mu", None);
            }
        } else {
            b.push(mu_min, k, "none", "rotational", "mu", None);
        }
    }
    let t: Vec<f64> = b.k.iter().map(|&k| t_over_r_from_k(k)).collect();
    let mut df = TableBuilder::new()
        .str("load_case", b.load_case)
        .f64("mu", b.mu)
        .f64("k", b.k)
        .f64("t_over_r", t)
        .str("regime_low", b.low)
        .str("regime_high", b.high)
        .str("axis", b.axis)
        .bool("on_collapse_curve", b.on)
        .opt_str("mechanism", b.mech)
        .opt_f64("thrust_over_half_weight", b.thrust)
        .opt_f64("crown_moment", b.moment)
        .list_f64("hinge_angles_deg", b.ha)
        .list_str("hinge_faces", b.hf)
        .list_f64("sliding_angles_deg", b.sa)
        .list_str("sliding_senses", b.ss)
        .finish()
        .unwrap();
    let layout = RunLayout::at(dir);
    store::write_parquet(&mut df, &layout.boundaries()).unwrap();
    // Bifurcations: K_c at μ = H/W_half there, and K at μ_min.
    let rot = found(symmetric::thickness(&arch, Friction::new(mu_rot).unwrap())).unwrap();
    let mut f = Rows::default();
    f.push(mu_rot, rot.k, "", "", "", Some(&rot));
    f.push(mu_min, k_bif.k, "", "", "", Some(&k_bif));
    let t: Vec<f64> = f.k.iter().map(|&k| t_over_r_from_k(k)).collect();
    let mut df = TableBuilder::new()
        .str("load_case", f.load_case)
        .f64("mu", f.mu)
        .f64("k", f.k)
        .f64("t_over_r", t)
        .str("mechanism_a", vec!["rotational", "mixed"])
        .str("mechanism_b", vec!["mixed", "sliding"])
        .f64(
            "thrust_over_half_weight",
            f.thrust.into_iter().map(|x| x.unwrap()).collect(),
        )
        .opt_f64("crown_moment", f.moment)
        .list_f64("hinge_angles_deg", f.ha)
        .list_str("hinge_faces", f.hf)
        .list_f64("sliding_angles_deg", f.sa)
        .list_str("sliding_senses", f.ss)
        .finish()
        .unwrap();
    store::write_parquet(&mut df, &layout.bifurcations()).unwrap();
}

fn grid_of(dir: &Path) -> (Vec<f64>, Vec<f64>) {
    let rows = store::read_results(&RunLayout::at(dir).results()).unwrap();
    let mut ks: Vec<f64> = rows.iter().filter_map(|r| r.k).collect();
    let mut mus: Vec<f64> = rows
        .iter()
        .filter_map(|r| r.mu)
        .filter(|m| m.is_finite())
        .collect();
    for v in [&mut ks, &mut mus] {
        v.sort_by(f64::total_cmp);
        v.dedup();
    }
    (ks, mus)
}

/// Adds the fixture boundary tables to a run and redoes its figure data and reports, as a
/// run with the boundaries stage would have.
fn with_boundaries(run: &Path) {
    let (ks, mus) = grid_of(run);
    write_boundary_fixture(run, &ks, &mus);
    let (plan, _) = runner::load_plan(&run.join("manifest.yaml")).unwrap();
    archstudy::figdata::run(&plan.manifest, &RunLayout::at(run)).unwrap();
    archstudy::report::render_run(run).unwrap();
}

/// The report with what changes from run to run masked: dates, versions of the build and
/// every duration.
fn masked(md: &str) -> String {
    md.lines()
        .map(|l| {
            for label in [
                "| date |",
                "| manifest |",
                "| archstudy commit |",
                "| rustc |",
                "| archstudy version |",
            ] {
                if l.starts_with(label) {
                    return format!("{label} [masked] |");
                }
            }
            if l.contains(" µs") || l.contains(" ms") {
                let mut out = String::new();
                let mut in_num = false;
                for c in l.chars() {
                    if c.is_ascii_digit() || (in_num && c == '.') {
                        if !in_num {
                            out.push('#');
                        }
                        in_num = true;
                    } else {
                        in_num = false;
                        out.push(c);
                    }
                }
                return out;
            }
            l.to_string()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn markdown_report_of_a_small_study_matches_the_golden_file() {
    let d = scratch("golden");
    let run = run_small(&d);
    with_boundaries(&run);
    let md = std::fs::read_to_string(run.join("report.md")).unwrap();
    insta::assert_snapshot!("small_study_report_md", masked(&md));
    let _ = std::fs::remove_dir_all(&d);
}

/// Reads one stored cell named by a key-results source: `FILE row I COLUMN`.
fn stored_cell(run: &Path, source: &str) -> Vec<f64> {
    let parts: Vec<&str> = source.split_whitespace().collect();
    assert_eq!(parts.len(), 4, "source {source:?}");
    assert_eq!(parts[1], "row");
    let row: usize = parts[2].parse().unwrap();
    let df = store::read_parquet(&run.join(parts[0])).unwrap();
    let col = parts[3];
    if col.ends_with("_deg") {
        store::list_f64_column(&df, col).unwrap()[row].clone()
    } else {
        vec![store::f64_column(&df, col).unwrap()[row].unwrap()]
    }
}

fn numbers_in(text: &str) -> Vec<f64> {
    text.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-'))
        .filter(|s| s.chars().any(|c| c.is_ascii_digit()))
        .map(|s| s.parse::<f64>().unwrap())
        .collect()
}

#[test]
fn every_key_result_equals_the_stored_value() {
    let d = scratch("keys");
    let run = run_small(&d);
    with_boundaries(&run);
    let md = std::fs::read_to_string(run.join("report.md")).unwrap();
    let section = md
        .split("## Key results")
        .nth(1)
        .unwrap()
        .split("\n## ")
        .next()
        .unwrap();
    let rows: Vec<Vec<String>> = section
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| quantity"))
        .map(|l| {
            l.trim_matches('|')
                .split(" | ")
                .map(|c| c.trim().to_string())
                .collect()
        })
        .collect();
    assert!(rows.len() >= 8, "too few key results: {section}");
    for r in &rows {
        let source = r[4].trim_matches('`');
        let stored = stored_cell(&run, source);
        let shown = numbers_in(&r[1]);
        if source.ends_with("_deg") {
            // Angles shown once per ± pair, four decimals.
            for a in &shown {
                assert!(
                    stored.iter().any(|s| (s.abs() - a.abs()).abs() <= 0.5e-4),
                    "{} shows {a}, stored {stored:?}",
                    r[0]
                );
            }
            for s in &stored {
                assert!(
                    shown.iter().any(|a| (s.abs() - a.abs()).abs() <= 0.5e-4),
                    "{}: {s} not shown",
                    r[0]
                );
            }
        } else {
            assert_eq!(shown.len(), 1, "{r:?}");
            assert!(
                (shown[0] - stored[0]).abs() <= 0.5e-10 * (1.0 + stored[0].abs()),
                "{}: shown {} stored {}",
                r[0],
                shown[0],
                stored[0]
            );
            if r[2] != "—" {
                let paper: f64 = r[2].parse().unwrap();
                let d: f64 = r[3].parse().unwrap();
                assert!(
                    (d - (stored[0] - paper)).abs() <= 0.01 * d.abs().max(1e-12),
                    "{r:?}"
                );
            }
        }
    }
    // The paper's case: the four printed values appear.
    for printed in ["1.1136", "0.395", "0.309", "1.2205"] {
        assert!(
            rows.iter().any(|r| r[2] == printed),
            "paper value {printed} missing"
        );
    }
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn report_command_on_a_copied_run_gives_the_same_report() {
    let d = scratch("copy");
    let run = run_small(&d);
    let copy = d.join("copied");
    copy_dir(&run, &copy);
    for f in ["report.md", "report.html"] {
        std::fs::remove_file(copy.join(f)).unwrap();
    }
    std::fs::remove_dir_all(copy.join("plots")).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_archstudy"))
        .args(["report"])
        .arg(&copy)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for f in [
        "report.md",
        "report.html",
        "plots/regime-map.svg",
        "plots/state-scene-1.svg",
    ] {
        let a = std::fs::read(run.join(f)).unwrap();
        let b = std::fs::read(copy.join(f)).unwrap();
        assert!(a == b, "{f} differs after `archstudy report`");
    }
    let _ = std::fs::remove_dir_all(&d);
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        let p = e.path();
        if p.is_dir() {
            copy_dir(&p, &to.join(e.file_name()));
        } else {
            std::fs::copy(&p, to.join(e.file_name())).unwrap();
        }
    }
}

#[test]
fn report_command_on_a_missing_run_directory_is_a_usage_error() {
    let d = scratch("missing");
    let out = Command::new(env!("CARGO_BIN_EXE_archstudy"))
        .args(["report"])
        .arg(d.join("no-such-run"))
        .output()
        .unwrap();
    assert_usage_error(&out, &["is not a run directory", "no-such-run"]);
    // A directory without run.json is refused the same way.
    let out = Command::new(env!("CARGO_BIN_EXE_archstudy"))
        .args(["report"])
        .arg(&d)
        .output()
        .unwrap();
    assert_usage_error(&out, &["run.json"]);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn figures_are_written_as_svg_and_print_png() {
    let d = scratch("figures");
    let run = run_small(&d);
    with_boundaries(&run);
    let plots = run.join("plots");
    let mut stems: Vec<String> = std::fs::read_dir(&plots)
        .unwrap()
        .filter_map(|e| {
            let p = e.unwrap().path();
            (p.extension()? == "svg").then(|| p.file_stem().unwrap().to_string_lossy().into_owned())
        })
        .collect();
    stems.sort();
    for want in [
        "regime-map",
        "critical-curves",
        "domains-scene-1",
        "state-scene-1",
        "state-scene-2",
        "state-bifurcation-1",
        "state-bifurcation-2",
    ] {
        assert!(
            stems.iter().any(|s| s == want),
            "{want} missing from {stems:?}"
        );
    }
    let html = std::fs::read_to_string(run.join("report.html")).unwrap();
    for s in &stems {
        let svg = std::fs::read_to_string(plots.join(format!("{s}.svg"))).unwrap();
        assert!(
            svg.len() > 5_000 && svg.contains("<text"),
            "{s}.svg is trivial"
        );
        let png = std::fs::read(plots.join(format!("{s}.png"))).unwrap();
        let dec = png::Decoder::new(std::io::Cursor::new(png));
        let mut reader = dec.read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).unwrap();
        // Two columns (the default), 7.2 in at 300 dpi.
        assert_eq!(info.width, 2160, "{s}.png is {} px wide", info.width);
        let px = &buf[..info.buffer_size()];
        let mean = px.iter().map(|&v| f64::from(v)).sum::<f64>() / px.len() as f64;
        let var = px
            .iter()
            .map(|&v| (f64::from(v) - mean).powi(2))
            .sum::<f64>()
            / px.len() as f64;
        assert!(var > 100.0, "{s}.png is nearly blank (variance {var})");
    }
    assert_eq!(html.matches("<svg class=\"figure\"").count(), stems.len());
    assert!(
        !html.contains("<link") && !html.contains("<script src"),
        "the HTML fetches nothing"
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// Not a test: adds fixture boundary tables to an existing run directory and re-renders it
/// (`ARCHSTUDY_FIXTURE_RUN=output/seed cargo test --test integration -- --ignored fixture`).
#[test]
#[ignore]
fn fixture_boundaries_for_a_run_directory() {
    if let Ok(dir) = std::env::var("ARCHSTUDY_FIXTURE_RUN") {
        with_boundaries(Path::new(&dir));
    }
}

#[test]
fn mechanisms_section_lists_every_stored_mechanism_with_a_closed_work_equation() {
    let d = scratch("mechanisms");
    let run = run_small(&d);
    with_boundaries(&run);
    let rows = store::read_mechanisms(&RunLayout::at(&run).mechanisms()).unwrap();
    assert!(!rows.is_empty(), "no mechanisms stored");
    for rule in ["non_associative", "associative"] {
        assert!(rows.iter().any(|r| r.flow_rule == rule), "no {rule} row");
    }
    let md = std::fs::read_to_string(run.join("report.md")).unwrap();
    assert!(
        md.contains("## Collapse mechanisms"),
        "no mechanisms section"
    );
    let section = &md[md.find("## Collapse mechanisms").unwrap()..];
    let section = &section[..section.find("\n## ").unwrap()];
    let listed: Vec<&str> = section
        .lines()
        .filter(|l| l.contains("(pure sliding) |") || l.contains("(dilatancy tan φ) |"))
        .collect();
    assert_eq!(
        listed.len(),
        rows.len(),
        "one table row per stored mechanism"
    );
    assert!(
        listed.iter().all(|l| l.contains("| < 1e-9 |")),
        "{listed:?}"
    );
    for r in &rows {
        assert!(r.work_residual < 1e-9, "{r:?}");
        if r.flow_rule == "non_associative" {
            assert!(r.dilatancy.iter().all(|d| d.abs() < 1e-9), "{r:?}");
        } else {
            let tan_phi = r.mu;
            for (s, d) in r.slip.iter().zip(&r.dilatancy) {
                assert!((d - tan_phi * s.abs()).abs() < 1e-9, "{r:?}");
            }
        }
    }
    let html = std::fs::read_to_string(run.join("report.html")).unwrap();
    assert!(html.contains("id=\"mechanisms\""));
    assert!(run.join("plots/mechanisms-bifurcation-1.png").exists());
    let _ = std::fs::remove_dir_all(&d);
}

const CONVERGENCE_STUDY: &str = "\
name: conv
arch:
  half_angle_deg: 90
  weight: annular
grid:
  voussoirs:
    values: [4, 6, 10, 16, 24, 40, 64, 96, 160, continuum]
find: thresholds
";

#[test]
fn convergence_report_has_an_error_table_and_an_order_per_threshold() {
    let d = scratch("convergence-report");
    let run = run_study(&d, "conv.yaml", CONVERGENCE_STUDY);
    let refs = store::read_reference(&RunLayout::at(&run).reference()).unwrap();
    assert_eq!(
        refs.len(),
        9 * 4,
        "one reference per discrete case and quantity"
    );
    let md = std::fs::read_to_string(run.join("report.md")).unwrap();
    for column in [
        "k_c_rotational",
        "mu_rotational_mixed",
        "mu_min",
        "k_mixed_sliding",
    ] {
        let at = md
            .find(&format!("(`{column}`)"))
            .unwrap_or_else(|| panic!("no table for {column}"));
        let section = &md[at..];
        assert!(section.contains("| N | value | abs. error | solve time |"));
        assert!(section.contains("| continuum |"));
        let order = section
            .find("Observed order of convergence: ")
            .expect("no order of convergence");
        let value: f64 = section[order + 31..]
            .split_whitespace()
            .next()
            .unwrap()
            .parse()
            .unwrap();
        // Nested joint sets give plateaus, so only the statement is checked here; the fit
        // itself is tested against a power law in src/report/convergence.rs.
        assert!(value.is_finite(), "{column}: order {value}");
    }
    assert!(run.join("plots/speed-accuracy.png").exists());
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn key_results_name_the_arch_of_each_critical_value_and_of_the_widest_gap() {
    // A thickness find has no K of its own: the widest gap is placed by its arch and μ
    // (it once read "the widest at K found, μ = 1.2").
    let dir = scratch("key-results-widest-gap");
    let run = run_study(
        &dir,
        "gp.yaml",
        "name: gp\narch: {joints: vertical, voussoirs: 7}\ngrid:\n  half_angle_deg: {values: [60, 80]}\n  mu: {values: [0.8, 1.2]}\nfind: thickness\n",
    );
    let md = std::fs::read_to_string(run.join("report.md")).expect("report.md");
    assert!(
        md.contains("(a gap: 4 of 4); the widest at α = 60°, μ = 1.2: collapse"),
        "{md}"
    );
    assert!(!md.contains(" found,") && !md.contains("μ found"), "{md}");
    // The critical values of the two arches read apart.
    for alpha in [60, 80] {
        assert!(
            md.contains(&format!("| K_c at μ = 0.8 (α = {alpha}°) |")),
            "{md}"
        );
    }
}

#[test]
fn a_thrust_study_reports_the_range_of_admissible_thrusts() {
    let dir = scratch("key-results-thrust");
    let run = run_study(
        &dir,
        "th.yaml",
        "name: th\ngrid:\n  k: {values: [1.1, 1.2]}\n  mu: {values: [0.4, inf]}\nfind: thrust\n",
    );
    let md = std::fs::read_to_string(run.join("report.md")).expect("report.md");
    // At K = 1.2 the minimum thrust is μ_c(1.2) = 0.3232251; with μ = 0.4 the springing
    // slides at H = μ W_half.
    assert!(
        md.contains("| admissible crown thrust H/W_half at K = 1.2, μ = 0.4 (minimum to maximum) | 0.3232251130 to 0.4000000000 |"),
        "{md}"
    );
    assert!(
        md.contains("at K = 1.2, μ = ∞ (minimum to maximum) | 0.3232251130 to"),
        "{md}"
    );
    // K = 1.1 is below K_c = 1.1136: nothing stands at any μ.
    assert!(md.contains("a thrust case admits no crown thrust"), "{md}");
}
