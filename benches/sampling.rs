//! Sampling studies (`cargo bench --bench sampling`): the samples of a plan (design points
//! mapped through the distributions), the engine over the samples of the self-weight
//! probability and of a horizontal-load fragility curve, and the exact probability by
//! quadrature. Whole runs of 10⁶ and 10⁵ samples, with their peak memory, are recorded in
//! docs/sampling.md (one run each is minutes, not a benchmark).

use archstudy::figdata::sampled::exact::{ExactSettings, probability};
use archstudy::{engine, manifest, plan};
use divan::counter::ItemsCount;
use divan::{Bencher, black_box};
use std::path::Path;

fn main() {
    divan::main();
}

const PROBABILITY: &str = "name: bench\nuncertain:\n  k: {distribution: truncated_normal, mean: 1.15, sd: 0.03, from: 1.0, to: 1.3}\n  mu: {distribution: uniform, from: 0.3, to: 0.5}\nfind: probability\n";

const FRAGILITY: &str = "name: bench\nload_cases:\n  - {name: seismic, kind: horizontal}\nuncertain:\n  k: {distribution: truncated_normal, mean: 1.3, sd: 0.05, from: 1.15, to: 1.5}\n  mu: {distribution: lognormal, median: 0.5, cov: 0.2}\nfind: fragility\n";

fn sampled(text: &str, n: u64, method: &str) -> manifest::Manifest {
    let text = format!("{text}samples: {{n: {n}, method: {method}, seed: 1}}\n");
    manifest::parse(&text, Path::new("bench.yaml")).expect("a valid manifest")
}

/// Building a slice of 2^16 samples (the design point, the quantiles, the scene) by method.
#[divan::bench(args = ["sobol", "lhs", "random"], sample_count = 10)]
fn plan_slice(bencher: Bencher, method: &str) {
    let m = sampled(PROBABILITY, 1 << 20, method);
    bencher.counter(ItemsCount::new(1usize << 16)).bench(|| {
        plan::build_slice(black_box(m.clone()), 1 << 19..(1 << 19) + (1 << 16))
            .cases
            .len()
    });
}

/// The engine over the samples of the self-weight probability (closed forms, separable).
#[divan::bench(args = [1 << 14, 1 << 16], sample_count = 5)]
fn probability_engine(bencher: Bencher, n: u64) {
    let plan = plan::build(sampled(PROBABILITY, n, "sobol")).expect("a plan");
    bencher
        .counter(ItemsCount::new(n as usize))
        .bench(|| engine::run(black_box(&plan), &archstudy::progress::Silent).len());
}

/// The engine over the samples of a horizontal-load fragility curve (a load factor each).
#[divan::bench(args = [1 << 12, 1 << 14], sample_count = 5)]
fn fragility_engine(bencher: Bencher, n: u64) {
    let plan = plan::build(sampled(FRAGILITY, n, "sobol")).expect("a plan");
    bencher
        .counter(ItemsCount::new(n as usize))
        .bench(|| engine::run(black_box(&plan), &archstudy::progress::Silent).len());
}

/// The exact probability of the self-weight study by quadrature to 1e-10.
#[divan::bench(sample_count = 3)]
fn exact_probability(bencher: Bencher) {
    let plan = plan::build_slice(sampled(PROBABILITY, 64, "sobol"), 0..1);
    let s = plan.manifest.sampling.clone().expect("a sampling study");
    let scene = plan.cases[0].scene;
    bencher.bench(|| probability(&s, black_box(&scene), &ExactSettings::DEFAULT).map(|e| e.value));
}
