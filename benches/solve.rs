//! Single-scene solves of the symmetric self-weight problem (`cargo bench --bench solve`).

use archstudy::analysis::symmetric;
use archstudy::model::{Arch, Discretisation, Friction, WeightModel};
use divan::black_box;

fn main() {
    divan::main();
}

fn arch(k: f64, n: Option<u32>) -> Arch {
    let joints = n.map_or(Discretisation::Continuum, Discretisation::Voussoirs);
    Arch::new(k, 90.0, WeightModel::Annular, joints).expect("valid arch")
}

/// Continuum collapse thickness K_c (μ = ∞), to 1e-15 in K.
#[divan::bench]
fn thickness_continuum() -> f64 {
    let s = symmetric::thickness(black_box(&arch(1.5, None)), Friction::INFINITE);
    s.found().map_or(f64::NAN, |s| s.k)
}

/// Continuum collapse thickness in the mixed range (μ = 0.35).
#[divan::bench]
fn thickness_continuum_mixed() -> f64 {
    let f = Friction::new(0.35).expect("μ ≥ 0");
    let s = symmetric::thickness(black_box(&arch(1.5, None)), f);
    s.found().map_or(f64::NAN, |s| s.k)
}

/// Continuum critical friction at K = 1.15.
#[divan::bench]
fn friction_continuum() -> f64 {
    let s = symmetric::friction(black_box(&arch(1.15, None)));
    s.found().map_or(f64::NAN, |s| s.mu)
}

/// Regime and both domains at (K, μ) = (1.35, 0.4).
#[divan::bench]
fn state_continuum() -> f64 {
    let f = Friction::new(0.4).expect("μ ≥ 0");
    let s = symmetric::state(black_box(&arch(1.35, None)), f);
    s.domains.rotational.interval.lo
}

/// Collapse thickness of N voussoirs.
#[divan::bench(args = [64, 512, 4096, 100_000])]
fn thickness_voussoirs(n: u32) -> f64 {
    let s = symmetric::thickness(black_box(&arch(1.5, Some(n))), Friction::INFINITE);
    s.found().map_or(f64::NAN, |s| s.k)
}

/// The whole thickness find of the semicircle at μ = ∞ as `archstudy solve` answers it: the
/// closed-form K_c (`thickness_continuum`) and the scan of K for windows, to compare with the
/// search alone.
#[divan::bench]
fn thickness_find_with_windows() -> Option<f64> {
    let s = archstudy::scene::Scene::new(
        black_box(arch(1.5, None)),
        Friction::INFINITE,
        archstudy::scene::Find::Thickness,
    );
    archstudy::scene::solve(&s).k_crit
}
