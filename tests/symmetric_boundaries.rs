//! The boundaries and bifurcations of the example state maps of a pointed arch and of a
//! semicircle with vertical joints, checked against independent critical-value solves of the
//! general route (K_c(μ) and μ_c(K) at the located points).

use archstudy::analysis::MechanismKind::{Mixed, Rotational, Sliding};
use archstudy::analysis::forms::ArchModel;
use archstudy::analysis::general::{self, Settings};
use archstudy::boundaries::{self, Located};
use archstudy::model::{Arch, ArchForm, Friction};
use archstudy::progress::Silent;
use archstudy::scene::Scene;
use archstudy::{engine, manifest, plan};
use std::path::Path;

/// The plan and the located boundaries of an example study.
fn located(study: &str) -> (plan::Plan, Located) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(study);
    let m = manifest::load(&path).expect("a valid manifest");
    let plan = plan::build(m).expect("a plan");
    assert!(engine::is_symmetric_state_grid(&plan));
    let results = engine::run(&plan, &Silent);
    let found = boundaries::locate(&plan, &results);
    (plan, found)
}

/// The arch and form of a plan.
fn arch_of(plan: &plan::Plan) -> (Arch, ArchForm) {
    let s: &Scene = &plan.cases[0].scene;
    (s.arch, s.form)
}

/// K_c(μ) by the general route's thickness search.
fn k_crit(arch: Arch, form: ArchForm, mu: f64) -> f64 {
    let make =
        |k: f64| ArchModel::new(arch.with_k(k), form, archstudy::model::Load::SelfWeight).ok();
    let friction = Friction::new(mu).expect("μ ≥ 0");
    general::thickness_with(
        make,
        form.max_k(arch.half_angle),
        None,
        friction,
        &Settings::default(),
    )
    .found()
    .and_then(|s| s.k)
    .expect("a collapse thickness")
}

/// μ_c(K) by the general route's friction search.
fn mu_crit(arch: Arch, form: ArchForm, k: f64) -> f64 {
    let model = ArchModel::new(arch.with_k(k), form, archstudy::model::Load::SelfWeight)
        .expect("the form exists");
    general::friction(&model, &Settings::default())
        .found()
        .expect("a critical friction")
        .mu
}

fn close(a: f64, b: f64, tol: f64, what: &str) {
    assert!((a - b).abs() <= tol, "{what}: {a} against {b}");
}

/// Every located point on the collapse curve lies on K_c(μ) or μ_c(K) of the general route.
fn collapse_points_agree(plan: &plan::Plan, found: &Located, every: usize) {
    let (arch, form) = arch_of(plan);
    let on_curve: Vec<_> = found
        .boundaries
        .iter()
        .filter(|p| p.on_collapse_curve && p.mu.is_finite())
        .collect();
    assert!(on_curve.len() > 20, "{} collapse points", on_curve.len());
    for p in on_curve.iter().step_by(every) {
        match p.axis {
            boundaries::EdgeAxis::Mu => close(mu_crit(arch, form, p.k), p.mu, 1e-8, "μ_c(K)"),
            boundaries::EdgeAxis::K => close(k_crit(arch, form, p.mu), p.k, 1e-8, "K_c(μ)"),
        }
        assert!(p.mechanism.is_some());
    }
}

#[test]
fn pointed_arch_bifurcations_lie_on_both_critical_curves() {
    let (plan, found) = located("studies/pointed.yaml");
    let (arch, form) = arch_of(&plan);
    let b = &found.bifurcations;
    assert_eq!(b.len(), 2, "{b:?}");
    // Rotational/mixed: K where H^r empties (K_c at μ = ∞), μ_c there.
    let rm = &b[0];
    assert_eq!((rm.mechanism_a, rm.mechanism_b), (Mixed, Rotational));
    close(rm.k, k_crit(arch, form, f64::INFINITY), 2e-9, "K_c(∞)");
    close(
        rm.k,
        k_crit(arch, form, rm.mu * (1.0 + 1e-9)),
        2e-9,
        "K_c(μ_rm)",
    );
    close(rm.mu, mu_crit(arch, form, rm.k), 1e-9, "μ_c(K_rm)");
    close(rm.k, 1.073350784093, 1e-9, "K_rm");
    close(rm.mu, 0.3193503888, 1e-9, "μ_rm");
    // Mixed/sliding: below it the collapse is mixed (μ_c above μ_s), above it sliding.
    let ms = &b[1];
    assert_eq!((ms.mechanism_a, ms.mechanism_b), (Sliding, Mixed));
    close(ms.mu, mu_crit(arch, form, ms.k), 1e-8, "μ_c(K_ms)");
    close(
        ms.k,
        k_crit(arch, form, ms.mu * (1.0 + 1e-9)),
        1e-8,
        "K_c(μ_ms)",
    );
    let model = |k: f64| {
        ArchModel::new(arch.with_k(k), form, archstudy::model::Load::SelfWeight).expect("form")
    };
    let mu_s = |k: f64| {
        general::sliding_threshold(&model(k), &Settings::default())
            .found()
            .expect("a sliding threshold")
            .mu
    };
    close(ms.mu, mu_s(ms.k), 1e-8, "μ_s(K_ms)");
    // A mixed band below the bifurcation, none above it.
    assert!(mu_crit(arch, form, ms.k - 1e-3) > mu_s(ms.k - 1e-3) + 1e-6);
    close(
        mu_crit(arch, form, ms.k + 1e-3),
        mu_s(ms.k + 1e-3),
        1e-9,
        "no band",
    );
    collapse_points_agree(&plan, &found, 7);
}

#[test]
fn vertical_joint_bifurcation_lies_on_both_critical_curves() {
    let (plan, found) = located("studies/vertical-joints.yaml");
    let (arch, form) = arch_of(&plan);
    let b = &found.bifurcations;
    // The mixed band is still open at the thickest arch of the map: one bifurcation.
    assert_eq!(b.len(), 1, "{b:?}");
    let rm = &b[0];
    assert_eq!((rm.mechanism_a, rm.mechanism_b), (Mixed, Rotational));
    // K_c at μ = ∞ of docs/loads-and-geometries.md.
    close(rm.k, 1.115798390, 1e-9, "K_c(∞)");
    close(
        rm.k,
        k_crit(arch, form, rm.mu * (1.0 + 1e-9)),
        2e-9,
        "K_c(μ_rm)",
    );
    close(rm.mu, mu_crit(arch, form, rm.k), 1e-9, "μ_c(K_rm)");
    assert!(
        !found
            .boundaries
            .iter()
            .any(|p| p.mechanism == Some(Sliding))
    );
    collapse_points_agree(&plan, &found, 5);
}
