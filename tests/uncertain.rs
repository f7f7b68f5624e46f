//! Sampling studies: the sampled probability of collapse against the exact one, the exact
//! integral against an independent quadrature, a fragility median against the arch at the
//! median friction, Sobol indices against a brute-force variance decomposition, the same
//! samples for any thread count, and every bad input refused.

use crate::common::{StudyRun, archstudy, manifest, scratch, stderr};
use archstudy::analysis::symmetric;
use archstudy::model::{Arch, Discretisation, Friction, WeightModel, t_over_r_from_k};
use archstudy::runner::{RunOptions, run_study};
use archstudy::store::{EstimateRow, read_estimates};
use std::path::Path;

fn run(name: &str, text: &str, jobs: Option<usize>) -> (StudyRun, Vec<EstimateRow>) {
    let dir = scratch(name);
    let study = manifest(&dir, "s.yaml", text);
    let opts = RunOptions {
        jobs,
        ..RunOptions::new(&study, dir.join("out"))
    };
    let out = run_study(&opts).expect("the study runs").dir;
    let rows = read_estimates(&out.join("estimates.parquet")).unwrap();
    (StudyRun::new(dir, out), rows)
}

fn one<'a>(
    rows: &'a [EstimateRow],
    point: u64,
    quantity: &str,
    parameter: &str,
) -> &'a EstimateRow {
    rows.iter()
        .find(|r| r.point == point && r.quantity == quantity && r.parameter == parameter)
        .unwrap_or_else(|| panic!("no {quantity} {parameter} at point {point}"))
}

/// The sampled probability of 2^20 samples and the exact one agree within the sampled
/// estimate's interval, and the quadrature's own error is below 1e-10.
fn sampled_holds_exact(name: &str, arch: &str) {
    let text = format!(
        "name: {name}\n{arch}uncertain:\n  k: {{distribution: truncated_normal, mean: 1.12, sd: 0.03, from: 1.0, to: 1.3}}\n  mu: {{distribution: uniform, from: 0.3, to: 0.6}}\nsamples: {{n: 1048576, method: sobol, seed: 7}}\nfind: probability\n"
    );
    let (_, rows) = run(name, &text, None);
    let p = one(&rows, 0, "probability", "");
    let x = one(&rows, 0, "exact_probability", "");
    assert_eq!(one(&rows, 0, "samples", "").value, 1048576.0);
    assert!(x.value.is_finite(), "{}", x.note);
    assert!(x.hi.unwrap() - x.value <= 1e-10, "{x:?}");
    let (lo, hi) = (p.lo.unwrap(), p.hi.unwrap());
    assert!(
        lo <= x.value && x.value <= hi,
        "exact {} outside [{lo}, {hi}]",
        x.value
    );
    // Scrambled Sobol points do far better than their (binomial) interval says.
    assert!(
        (p.value - x.value).abs() < 2e-4,
        "{} vs {}",
        p.value,
        x.value
    );
    // The mechanisms share out the collapses.
    let parts: f64 = ["rotational", "mixed", "sliding", "none"]
        .iter()
        .map(|m| one(&rows, 0, "mechanism", m).value)
        .sum();
    assert!((parts - p.value).abs() < 1e-12);
}

#[test]
fn a_million_samples_of_the_semicircle_hold_the_exact_probability() {
    sampled_holds_exact("prob-semicircle", "");
}

#[test]
fn a_million_samples_of_a_pointed_arch_hold_the_exact_probability() {
    sampled_holds_exact(
        "prob-pointed",
        "arch: {shape: pointed, eccentricity: 0.2}\n",
    );
}

/// Φ(z) to an ulp or two, independent of the sampling module.
fn phi(z: f64) -> f64 {
    0.5 * libm::erfc(-z / std::f64::consts::SQRT_2)
}

#[test]
fn the_exact_integral_equals_a_brute_force_quadrature_over_the_collapse_curve() {
    // K normal (a truncation 5 sd away changes nothing at 1e-7), μ uniform on [0.32, 0.5]
    // (above μ_min: the arch stands for every K ≥ K_c(μ), one kink at the rotational/mixed
    // bifurcation). P = (1/0.18) ∫ Φ((K_c(μ) − 1.15)/0.03) dμ, with K_c(μ) from the closed
    // forms of the symmetric problem (not the window scan the exact route reads).
    let text = "name: exact\nuncertain:\n  k: {distribution: truncated_normal, mean: 1.15, sd: 0.03, from: 1.0, to: 1.3}\n  mu: {distribution: uniform, from: 0.32, to: 0.5}\nsamples: {n: 64}\nfind: probability\n";
    let (_, rows) = run("exact-integral", text, None);
    let exact = one(&rows, 0, "exact_probability", "").value;
    let arch = Arch::new(1.2, 90.0, WeightModel::Annular, Discretisation::Continuum).unwrap();
    let n = 3600;
    let (a, b) = (0.32, 0.5);
    let h = (b - a) / n as f64;
    let trunc = phi((1.3 - 1.15) / 0.03) - phi((1.0 - 1.15) / 0.03);
    let g = |mu: f64| {
        let kc = symmetric::thickness(&arch, Friction::new(mu).unwrap())
            .found()
            .expect("K_c at μ above μ_min")
            .k;
        (phi((kc - 1.15) / 0.03) - phi((1.0 - 1.15) / 0.03)) / trunc
    };
    // Composite Simpson's rule.
    let mut sum = g(a) + g(b);
    for i in 1..n {
        sum += g(a + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    let brute = sum * h / 3.0 / (b - a);
    assert!(
        (exact - brute).abs() < 2e-7,
        "exact {exact}, brute force {brute}"
    );
    assert!(exact > 0.05 && exact < 0.95, "{exact}");
}

#[test]
fn sobol_points_converge_faster_than_random_ones() {
    let text = "name: conv\nuncertain:\n  k: {distribution: uniform, from: 1.08, to: 1.2}\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\nsamples: {n: 1024}\nfind: probability\n";
    let (_, rows) = run("convergence", text, None);
    let last = |m: &str| {
        rows.iter()
            .filter(|r| r.quantity == "convergence" && r.parameter == m)
            .max_by(|a, b| a.x.unwrap().total_cmp(&b.x.unwrap()))
            .map(|r| (r.x.unwrap(), r.value))
            .unwrap()
    };
    let (n_s, e_s) = last("sobol");
    let (n_r, e_r) = last("random");
    assert_eq!(n_s, n_r);
    assert!(n_s >= 16384.0);
    assert!(e_s * 3.0 < e_r, "Sobol {e_s}, random {e_r} at n = {n_s}");
    let slope = |m: &str| one(&rows, 0, "convergence_slope", m).value;
    assert!(slope("sobol") < -0.6, "{}", slope("sobol"));
    assert!(
        (-0.75..-0.3).contains(&slope("random")),
        "{}",
        slope("random")
    );
}

#[test]
fn the_median_of_a_fragility_curve_is_the_load_factor_at_the_median_friction() {
    // λ_max grows with μ (the Coulomb cones widen), so with μ alone uncertain the median of
    // λ_max is λ_max at the median μ.
    let text = "name: frag\ngrid:\n  k: {values: [1.3]}\nload_cases:\n  - {name: wind, kind: horizontal}\nuncertain:\n  mu: {distribution: uniform, from: 0.3, to: 0.7}\nsamples: {n: 2048, method: lhs, seed: 3}\nfind: fragility\n";
    let (out, rows) = run("fragility-median", text, None);
    let median = one(&rows, 0, "quantile", "0.5");
    let direct = crate::common::solve_json(&[
        "--k",
        "1.3",
        "--mu",
        "0.5",
        "--load",
        "horizontal",
        "--find",
        "load_factor",
    ]);
    let lambda = direct["load_factor"].as_f64().unwrap();
    assert!(
        median.lo.unwrap() <= lambda && lambda <= median.hi.unwrap(),
        "λ_max(μ = 0.5) = {lambda}, median {median:?}"
    );
    assert!(
        (median.value - lambda).abs() < 2e-3 * lambda,
        "{} vs {lambda}",
        median.value
    );
    // The fragility curve is a CDF: increasing, from about 0 to 1.
    let cdf: Vec<&EstimateRow> = rows
        .iter()
        .filter(|r| r.quantity == "fragility_cdf")
        .collect();
    assert!(
        cdf.windows(2)
            .all(|w| w[0].x <= w[1].x && w[0].value <= w[1].value)
    );
    assert!((cdf.last().unwrap().value - 1.0).abs() < 1e-12);
    assert!(out.join("plots/fragility.pdf").is_file());
}

#[test]
fn sobol_indices_of_the_margin_match_a_brute_force_variance_decomposition() {
    // Y = t(K)/t(K_c(μ)) − 1 with K and μ uniform and independent: the first-order index of K
    // is Var_K(E[Y | K]) / Var(Y), computed here on a midpoint grid from the closed forms.
    let text = "name: sens\nuncertain:\n  k: {distribution: uniform, from: 1.1, to: 1.25}\n  mu: {distribution: uniform, from: 0.32, to: 0.6}\nsamples: {n: 2048, seed: 11}\nfind: sensitivity\n";
    let (_, rows) = run("sensitivity", text, None);
    let arch = Arch::new(1.2, 90.0, WeightModel::Annular, Discretisation::Continuum).unwrap();
    let m = 300;
    let ks: Vec<f64> = (0..m)
        .map(|i| 1.1 + 0.15 * (i as f64 + 0.5) / m as f64)
        .collect();
    let tc: Vec<f64> = (0..m)
        .map(|j| {
            let mu = 0.32 + 0.28 * (j as f64 + 0.5) / m as f64;
            let kc = symmetric::thickness(&arch, Friction::new(mu).unwrap())
                .found()
                .unwrap()
                .k;
            t_over_r_from_k(kc)
        })
        .collect();
    let y = |i: usize, j: usize| t_over_r_from_k(ks[i]) / tc[j] - 1.0;
    let n = (m * m) as f64;
    let mean = (0..m)
        .flat_map(|i| (0..m).map(move |j| (i, j)))
        .map(|(i, j)| y(i, j))
        .sum::<f64>()
        / n;
    let var = (0..m)
        .flat_map(|i| (0..m).map(move |j| (i, j)))
        .map(|(i, j)| (y(i, j) - mean).powi(2))
        .sum::<f64>()
        / n;
    let cond = |of_k: bool| {
        (0..m)
            .map(|a| {
                let e = (0..m)
                    .map(|b| if of_k { y(a, b) } else { y(b, a) })
                    .sum::<f64>()
                    / m as f64;
                (e - mean).powi(2)
            })
            .sum::<f64>()
            / m as f64
            / var
    };
    for (param, s) in [("k", cond(true)), ("mu", cond(false))] {
        let f = one(&rows, 0, "first_order", param);
        let slack = 0.01;
        assert!(
            f.lo.unwrap() - slack <= s && s <= f.hi.unwrap() + slack,
            "{param}: brute force {s}, estimate {f:?}"
        );
        let t = one(&rows, 0, "total", param);
        assert!(t.value >= f.value - 0.05, "{t:?} {f:?}");
    }
    assert!((one(&rows, 0, "mean", "").value - mean).abs() < 0.01);
}

#[test]
fn a_distribution_parameter_given_as_an_axis_gives_each_point_its_own_distribution() {
    // Three scatters of μ over two thicknesses: the point (K = 1.2, sd = 0.05) is the same
    // study as a run with that one distribution, to the bit.
    let text = "name: scatters\ngrid:\n  k: {values: [1.15, 1.2]}\nuncertain:\n  mu: {distribution: truncated_normal, mean: 0.4, sd: {values: [0.02, 0.05, 0.1]}, from: 0.1, to: 0.8}\nsamples: {n: 512, seed: 3}\nfind: probability\n";
    let (_, rows) = run("scatters", text, None);
    let one_text = "name: one\ngrid:\n  k: {values: [1.2]}\nuncertain:\n  mu: {distribution: truncated_normal, mean: 0.4, sd: 0.05, from: 0.1, to: 0.8}\nsamples: {n: 512, seed: 3}\nfind: probability\n";
    let (_, one_rows) = run("scatters-one", one_text, None);
    // Points run K outer, sd inner: (1.2, 0.05) is point 4.
    let grid = |p: u64| {
        rows.iter()
            .filter(|r| r.point == p && r.quantity == "grid")
            .map(|r| (r.parameter.clone(), r.value))
            .collect::<Vec<_>>()
    };
    assert_eq!(
        grid(4),
        vec![("k".to_string(), 1.2), ("mu.sd".to_string(), 0.05)]
    );
    for q in ["probability", "exact_probability"] {
        let a = one(&rows, 4, q, "");
        let b = one(&one_rows, 0, q, "");
        assert_eq!(a.value.to_bits(), b.value.to_bits(), "{q}: {a:?} {b:?}");
    }
    // A wider scatter of μ fails more often at the thick arch (μ below μ_min).
    let p = |point| one(&rows, point, "exact_probability", "").value;
    assert!(p(3) < p(4) && p(4) < p(5), "{} {} {}", p(3), p(4), p(5));
    for point in 0..6 {
        let s = one(&rows, point, "probability", "");
        let x = p(point);
        assert!(
            s.lo.unwrap() <= x && x <= s.hi.unwrap(),
            "point {point}: {s:?} vs {x}"
        );
    }
}

#[test]
fn the_samples_are_the_same_for_any_thread_count() {
    let text = "name: jobs\nload_cases:\n  - {name: wind, kind: horizontal, lambda: 0.2}\nuncertain:\n  k: {distribution: beta, alpha: 2, beta: 3, from: 1.15, to: 1.45}\n  mu: {distribution: lognormal, mean: 0.5, sd: 0.1}\n  correlation: {between: [k, mu], value: 0.4}\nsamples: {n: 300, method: lhs, seed: 9}\nfind: probability\n";
    let (a, ra) = run("jobs-1", text, Some(1));
    let (b, rb) = run("jobs-2", text, Some(2));
    assert_eq!(format!("{ra:?}"), format!("{rb:?}"));
    let table = |d: &Path| {
        format!(
            "{:?}",
            archstudy::store::read_table(&d.join("samples.parquet")).unwrap()
        )
    };
    assert_eq!(table(&a), table(&b));
    // Latin hypercube: each of 300 strata of μ's distribution holds one sample.
    let df = archstudy::store::read_parquet(&a.join("samples.parquet")).unwrap();
    let k = archstudy::store::f64_column(&df, "k").unwrap();
    assert_eq!(k.len(), 300);
    assert!(k.iter().all(|v| v.is_some_and(|v| v > 1.15 && v < 1.45)));
}

/// Each bad manifest, and words its error must hold.
const BAD: &[(&str, &[&str])] = &[
    (
        "arch: {shape: pointed, eccentricity: 0.6, half_angle_deg: 90}\nuncertain:\n  k: {distribution: uniform, from: 1.05, to: {values: [1.3, 3.0]}}\n  mu: {distribution: uniform, from: 0.3, to: 0.6}\nfind: probability\n",
        &["key `uncertain.k`", "2.333"],
    ),
    (
        "uncertain:\n  k: {distribution: uniform, from: 1.1, to: 1.3}\n  mu: {distribution: truncated_normal, mean: 0.4, sd: {values: [0.05, -0.1]}, from: 0.1, to: 0.8}\nfind: probability\n",
        &["uncertain.mu.sd", "-0.1", "> 0"],
    ),
    (
        "uncertain:\n  k: {distribution: uniform, from: 1.1, to: {values: [1.3, 120]}}\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\nfind: probability\n",
        &["uncertain.k", "120", "(1, 100]"],
    ),
    (
        "uncertain:\n  k: {distribution: uniform, from: 1.1, to: 1.3}\n  mu: {distribution: uniform, from: 0.3, to: {from: 0.5, to: 0.9}}\nfind: probability\n",
        &["uncertain.mu.to", "{values: [...]}"],
    ),
    (
        "uncertain:\n  mu: {distribution: normal, mean: 0.4, sd: -0.1}\nfind: probability\ngrid:\n  k: {values: [1.2]}\n",
        &["uncertain.mu.sd", "-0.1", "> 0"],
    ),
    (
        "uncertain:\n  mu: {distribution: normal, mean: 0.4, sd: 0.1}\nfind: probability\ngrid:\n  k: {values: [1.2]}\n",
        &["uncertain.mu", "normal", "truncated_normal"],
    ),
    (
        "uncertain:\n  k: {distribution: truncated_normal, mean: 1.2, sd: 0.1, from: 0.5, to: 1.5}\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\nfind: probability\n",
        &["uncertain.k", "0.5", "(1, 100]"],
    ),
    (
        "uncertain:\n  k: {distribution: uniform, from: 1.1, to: 1.3}\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\n  correlation: {between: [k, mu], value: 1}\nfind: probability\n",
        &["uncertain.correlation.value", "(−1, 1)"],
    ),
    (
        "uncertain:\n  k: {distribution: uniform, from: 1.1, to: 1.3}\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\n  correlation: {between: [k, mu], value: -1.5}\nfind: probability\n",
        &["uncertain.correlation.value", "-1.5"],
    ),
    (
        "uncertain:\n  k: {distribution: uniform, from: 1.1, to: 1.3}\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\n  correlation: {between: [k, lambda], value: 0.5}\nfind: probability\n",
        &["uncertain.correlation.between", "lambda"],
    ),
    (
        "uncertain:\n  k: {distribution: uniform, from: 1.1, to: 1.3}\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\n  correlation: {between: [k, mu], value: 0.5}\nfind: sensitivity\n",
        &["uncertain.correlation", "independent"],
    ),
    (
        "uncertain:\n  k: {distribution: uniform, from: 1.3, to: 1.1}\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\nfind: probability\n",
        &["uncertain.k.to", "1.1", "greater than"],
    ),
    (
        "uncertain:\n  k: {distribution: weibull, from: 1.1, to: 1.3}\nfind: probability\n",
        &["uncertain.k.distribution", "weibull", "lognormal"],
    ),
    (
        "uncertain:\n  k: {distribution: uniform, from: 1.1, to: 1.3, sd: 2}\nfind: probability\n",
        &["uncertain.k.sd", "uniform"],
    ),
    (
        "grid:\n  mu: {values: [0.4]}\nuncertain:\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\n  k: {distribution: uniform, from: 1.1, to: 1.3}\nfind: probability\n",
        &["uncertain.mu", "grid axis"],
    ),
    (
        "uncertain:\n  voussoirs: {distribution: uniform, from: 4, to: 10}\n  k: {distribution: uniform, from: 1.1, to: 1.3}\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\nfind: probability\n",
        &["uncertain.voussoirs", "discrete"],
    ),
    (
        "uncertain:\n  k: {distribution: uniform, from: 1.1, to: 1.3}\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\nfind: fragility\n",
        &["load_cases.kind", "self_weight", "live load"],
    ),
    (
        "uncertain:\n  k: {distribution: uniform, from: 1.1, to: 1.3}\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\nsamples: {n: 1, method: sobol}\nfind: probability\n",
        &["samples.n", "[2,"],
    ),
    (
        "uncertain:\n  k: {distribution: uniform, from: 1.1, to: 1.3}\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\nsamples: {method: halton}\nfind: probability\n",
        &["samples.method", "halton", "lhs"],
    ),
    (
        "uncertain:\n  k: {distribution: uniform, from: 1.1, to: 1.3}\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\nsamples: {seed: -3}\nfind: probability\n",
        &["samples.seed", "-3"],
    ),
    (
        "uncertain:\n  k: {distribution: uniform, from: 1.1, to: 1.3}\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\nfind: state\n",
        &["uncertain", "probability"],
    ),
    (
        "find: probability\ngrid:\n  k: {values: [1.2]}\n  mu: {values: [0.4]}\n",
        &["uncertain", "needs"],
    ),
    (
        "uncertain:\n  k: {distribution: uniform, from: 1.1, to: 1.3}\nfind: probability\n",
        &["uncertain", "μ", "uncertain mu"],
    ),
    (
        "uncertain:\n  mu: {distribution: discrete, values: [0.3, 0.5], weights: [1, -1]}\n  k: {distribution: uniform, from: 1.1, to: 1.3}\nfind: probability\n",
        &["uncertain.mu.weights", "-1"],
    ),
    (
        "uncertain:\n  eccentricity: {distribution: uniform, from: 0.1, to: 0.3}\n  k: {distribution: uniform, from: 1.1, to: 1.3}\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\nfind: probability\n",
        &["uncertain.eccentricity", "pointed"],
    ),
    (
        "arch: {shape: pointed, eccentricity: 0.2}\nuncertain:\n  eccentricity: {distribution: uniform, from: 0.5, to: 1.2}\n  k: {distribution: uniform, from: 1.1, to: 1.3}\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\nfind: probability\n",
        &["uncertain.eccentricity", "[0, 0.9999]"],
    ),
    (
        "load_cases:\n  - {name: p, kind: point, at_deg: 30}\nuncertain:\n  at_deg: {distribution: uniform, from: -20, to: 20}\n  k: {distribution: uniform, from: 1.1, to: 1.3}\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\nfind: fragility\n",
        &["load_cases.at_deg", "own position"],
    ),
    (
        "load_cases:\n  - {name: p, kind: point}\nuncertain:\n  at_deg: {distribution: uniform, from: -20, to: 120}\n  k: {distribution: uniform, from: 1.1, to: 1.3}\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\nfind: fragility\n",
        &["uncertain.at_deg", "120"],
    ),
    (
        "load_cases:\n  - {name: w, kind: horizontal}\nuncertain:\n  lambda: {distribution: uniform, from: 0.1, to: 0.3}\n  k: {distribution: uniform, from: 1.1, to: 1.3}\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\nfind: fragility\n",
        &["uncertain.lambda", "λ_max itself"],
    ),
    (
        "load_cases:\n  - {name: w, kind: horizontal}\nuncertain:\n  k: {distribution: uniform, from: 1.1, to: 1.3}\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\nfind: probability\n",
        &["load_cases.lambda", "uncertain lambda", "fragility"],
    ),
];

#[test]
fn every_bad_sampling_input_is_refused_with_the_key_and_the_value() {
    let dir = scratch("bad-sampling");
    for (i, (body, words)) in BAD.iter().enumerate() {
        let study = manifest(
            &dir,
            &format!("bad{i}.yaml"),
            &format!("name: bad{i}\n{body}"),
        );
        let o = archstudy(&["check", study.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(2), "case {i} was accepted:\n{body}");
        let err = stderr(&o);
        for w in *words {
            assert!(err.contains(w), "case {i}: {w:?} not in {err}");
        }
    }
}

#[test]
fn a_lognormal_load_factor_and_a_discrete_friction_with_infinity_are_sampled() {
    // Supports unbounded above are allowed where the parameter is (λ, μ): the samples are
    // finite; a discrete μ may be inf. The probability is of not standing at the sampled λ.
    let text = "name: lam\nload_cases:\n  - {name: p, kind: point, at_deg: 30}\nuncertain:\n  lambda: {distribution: lognormal, median: 0.3, cov: 0.5}\n  k: {distribution: uniform, from: 1.15, to: 1.4}\n  mu: {distribution: discrete, values: [0.4, 0.6, inf]}\nsamples: {n: 200, method: lhs}\nfind: probability\n";
    let (out, rows) = run("lognormal-lambda", text, None);
    let p = one(&rows, 0, "probability", "");
    assert!(p.value > 0.0 && p.value < 1.0, "{p:?}");
    let df = archstudy::store::read_parquet(&out.join("samples.parquet")).unwrap();
    let lambda = archstudy::store::f64_column(&df, "lambda").unwrap();
    assert!(
        lambda
            .iter()
            .all(|v| v.is_some_and(|v| v.is_finite() && v > 0.0))
    );
    let mu = archstudy::store::f64_column(&df, "mu").unwrap();
    assert!(mu.contains(&Some(f64::INFINITY)));
}

#[test]
fn verify_re_derives_the_samples_and_the_estimates_and_catches_a_forged_probability() {
    let text = "name: forged\nuncertain:\n  k: {distribution: uniform, from: 1.08, to: 1.2}\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\nsamples: {n: 256, seed: 2}\nfind: probability\n";
    let (out, rows) = run("verify-sampled", text, None);
    let ok = archstudy(&["verify", out.to_str().unwrap()]);
    assert!(ok.status.success(), "{}", crate::common::stdout(&ok));
    let i = rows
        .iter()
        .position(|r| r.quantity == "probability")
        .unwrap();
    archstudy::store::rewrite_f64_value(&out.join("estimates.parquet"), "value", i, Some(0.01))
        .unwrap();
    let bad = archstudy(&["verify", out.to_str().unwrap()]);
    assert!(!bad.status.success());
    let text = crate::common::stdout(&bad);
    assert!(text.contains("estimates.parquet"), "{text}");
}
