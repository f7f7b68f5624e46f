//! The per-K-line path of symmetric self-weight state grids on pointed arches and vertical
//! joints gives every case the answer of the general route analysed case by case, at grid
//! points next to the sliding threshold and the critical friction of a line and at μ = ∞.

use archstudy::analysis::forms::ArchModel;
use archstudy::analysis::general::{self, Settings};
use archstudy::engine::{self, Status};
use archstudy::model::{
    Arch, ArchForm, Discretisation, JointOrientation, Load, Shape, WeightModel,
};
use archstudy::progress::Silent;
use archstudy::scene;
use archstudy::{manifest, plan};
use std::path::Path;

/// μ_s and μ_m of an arch at K (the sliding threshold and the critical friction).
fn thresholds(arch: Arch, form: ArchForm) -> (f64, f64) {
    let model = ArchModel::new(arch, form, Load::SelfWeight).expect("the form exists");
    let s = Settings::default();
    let mu_s = general::sliding_threshold(&model, &s)
        .found()
        .expect("a sliding threshold")
        .mu;
    let mu_m = general::friction(&model, &s)
        .found()
        .expect("a critical friction")
        .mu;
    (mu_s, mu_m)
}

/// Runs a state grid through the engine and checks each case against the general route.
fn both_routes_agree(
    arch_yaml: &str,
    form: ArchForm,
    (weight, joints): (WeightModel, Discretisation),
    k_near: f64,
) {
    let arch = Arch::new(k_near, 90.0, weight, joints).expect("an arch");
    let (mu_s, mu_m) = thresholds(arch, form);
    assert!(mu_s < mu_m, "μ_s {mu_s} μ_m {mu_m}");
    // Grid friction values on both sides of each threshold of the line K = k_near, a few
    // elsewhere and μ = ∞.
    let mut mus = vec![0.1, 0.3, 0.45, 0.7, 1.5, 3.0];
    for m in [mu_s, mu_m] {
        mus.extend([
            m * (1.0 - 1e-9),
            m * (1.0 + 1e-9),
            m * (1.0 - 1e-4),
            m * (1.0 + 1e-4),
        ]);
    }
    let mu_list: Vec<String> = mus.iter().map(|m| format!("{m:e}")).collect();
    let text = format!(
        "name: lines\narch:\n{arch_yaml}\ngrid:\n  k: {{values: [1.02, 1.06, 1.1, {k_near:e}, 1.16, 1.25, 1.4]}}\n  mu: {{values: [{}, inf]}}\nfind: state\n",
        mu_list.join(", ")
    );
    let m = manifest::parse(&text, Path::new("lines.yaml")).expect("a valid manifest");
    let plan = plan::build(m).expect("a plan");
    assert!(engine::is_symmetric_state_grid(&plan));
    let rows = engine::run(&plan, &Silent);
    assert_eq!(rows.len(), plan.cases.len());
    let mut seen = std::collections::HashSet::new();
    for (c, r) in plan.cases.iter().zip(&rows) {
        assert_eq!(r.status, Status::Ok);
        assert_eq!(r.case_id, c.id);
        let direct = scene::solve(&c.scene);
        let (k, mu) = (c.scene.arch.k, c.scene.friction.mu());
        assert_eq!(r.solution.regime, direct.regime, "K {k} μ {mu}");
        assert!(r.solution.regime.is_some());
        // Every column a state answer fills is the same (the solve time aside).
        let strip = |s: &scene::Solution| scene::Solution {
            solve_time_us: 0.0,
            ..s.clone()
        };
        assert_eq!(
            format!("{:?}", strip(&r.solution)),
            format!("{:?}", strip(&direct))
        );
        seen.insert(format!("{:?}", direct.regime));
    }
    // The grid crosses every regime of the map.
    for regime in ["Rotational", "Sliding", "Mixed", "Stable", "None"] {
        assert!(
            seen.iter().any(|s| s.contains(regime)),
            "{regime} missing: {seen:?}"
        );
    }
}

#[test]
fn pointed_arch_lines_match_the_general_route() {
    let form = ArchForm {
        shape: Shape::Pointed { eccentricity: 0.2 },
        joints: JointOrientation::Radial,
        keystone: false,
    };
    both_routes_agree(
        "  shape: pointed\n  eccentricity: 0.2",
        form,
        (WeightModel::Annular, Discretisation::Continuum),
        1.13,
    );
}

#[test]
fn vertical_joint_lines_match_the_general_route() {
    let form = ArchForm {
        shape: Shape::Circular,
        joints: JointOrientation::Vertical,
        keystone: false,
    };
    both_routes_agree(
        "  joints: vertical\n  weight: centreline",
        form,
        (WeightModel::Centreline, Discretisation::Continuum),
        1.13,
    );
}

#[test]
fn pointed_voussoir_lines_match_the_general_route() {
    let form = ArchForm {
        shape: Shape::Pointed { eccentricity: 0.2 },
        joints: JointOrientation::Vertical,
        keystone: false,
    };
    both_routes_agree(
        "  shape: pointed\n  eccentricity: 0.2\n  joints: vertical\n  voussoirs: 9",
        form,
        (WeightModel::Annular, Discretisation::Voussoirs(9)),
        1.13,
    );
}
