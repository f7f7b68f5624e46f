//! Tests of the general route against the reference values and the symmetric route.

use super::*;
use crate::analysis::MechanismKind;
use crate::analysis::circular::CircularArch;
use crate::analysis::statics::ArchGeometry;
use crate::analysis::statics::Resultant;
use crate::analysis::symmetric;
use crate::analysis::types::{Face, Sense};
use crate::model::{Arch, Friction};
use crate::model::{Discretisation, WeightModel};
use approx::{abs_diff_eq, assert_abs_diff_eq};
use std::f64::consts::FRAC_PI_2;

const K_C: f64 = 1.113581813339;
const MU_ROT: f64 = 0.395265252140;
const MU_MIN: f64 = 0.309215444330;
const K_BIF: f64 = 1.220507754643;

fn arch(k: f64, alpha_deg: f64, weight: WeightModel, joints: Discretisation) -> Arch {
    Arch::new(k, alpha_deg, weight, joints).unwrap()
}

fn semi(k: f64, joints: Discretisation) -> Arch {
    arch(k, 90.0, WeightModel::Annular, joints)
}

fn mu(m: f64) -> Friction {
    Friction::new(m).unwrap()
}

fn k_of(c: &Critical) -> f64 {
    c.found().and_then(|s| s.k).expect("a critical thickness")
}

fn mu_of(c: &Critical) -> f64 {
    c.found().map(|s| s.mu).expect("a critical friction")
}

fn sym_k(c: &symmetric::Critical) -> f64 {
    c.found().expect("symmetric K").k
}

fn sym_mu(c: &symmetric::Critical) -> f64 {
    c.found().expect("symmetric μ").mu
}

/// The five critical values of the paper for one arch by the general route:
/// K_c (μ = ∞), μ_c at K_c, μ_min, K at μ_min, K at μ = 0.35.
fn general_values(a: &Arch) -> [f64; 5] {
    let s = Settings::default();
    let kc = k_of(&thickness(a, Friction::INFINITE, &s));
    let mu_rot = mu_of(&friction(&CircularArch::new(a.with_k(kc)), &s));
    let mu_min = mu_of(&sliding_threshold(&CircularArch::new(*a), &s));
    let k_bif = k_of(&thickness(a, mu(mu_min), &s));
    let k_mixed = k_of(&thickness(a, mu(0.35), &s));
    [kc, mu_rot, mu_min, k_bif, k_mixed]
}

/// The same five values by the symmetric closed forms. The bifurcation friction is the
/// thrust of the K_c state (sliding at the springings, where H_max^s = μ W_half):
/// `symmetric::friction` at exactly K_c(N) is ill-conditioned for discrete arches (it
/// gives 0.41844 for N = 64 where H^s at μ = 0.3953 already contains H^r = {0.39524}).
fn symmetric_values(a: &Arch) -> [f64; 5] {
    let at_kc = symmetric::thickness(a, Friction::INFINITE);
    let kc = sym_k(&at_kc);
    let mu_rot = at_kc.found().expect("K_c state").thrust_over_half_weight;
    let mu_min = sym_mu(&symmetric::sliding_threshold(a));
    let k_bif = sym_k(&symmetric::thickness(a, mu(mu_min)));
    let k_mixed = sym_k(&symmetric::thickness(a, mu(0.35)));
    [kc, mu_rot, mu_min, k_bif, k_mixed]
}

fn assert_close(what: &str, got: [f64; 5], want: [f64; 5], tol: f64) {
    let names = ["K_c", "mu_rot", "mu_min", "K_bif", "K(0.35)"];
    for i in 0..5 {
        assert!(
            abs_diff_eq!(got[i], want[i], epsilon = tol),
            "{what}: {} = {} vs {} (diff {:e})",
            names[i],
            got[i],
            want[i],
            got[i] - want[i]
        );
    }
}

#[test]
fn continuum_reproduces_the_reference_values() {
    let a = semi(1.5, Discretisation::Continuum);
    let g = general_values(&a);
    let mut want = symmetric_values(&a);
    want[..4].copy_from_slice(&[K_C, MU_ROT, MU_MIN, K_BIF]);
    assert_close("continuum", g, want, 1e-9);
}

#[test]
fn discrete_arches_agree_with_the_symmetric_route() {
    for n in [16, 64] {
        let a = semi(1.5, Discretisation::Voussoirs(n));
        assert_close(
            &format!("N = {n}"),
            general_values(&a),
            symmetric_values(&a),
            1e-9,
        );
        // Away from K_c both friction searches are well conditioned.
        for k in [1.15, 1.3] {
            let g = mu_of(&friction(
                &CircularArch::new(a.with_k(k)),
                &Settings::default(),
            ));
            let w = sym_mu(&symmetric::friction(&a.with_k(k)));
            assert!(
                abs_diff_eq!(g, w, epsilon = 1e-9),
                "N = {n}, K = {k}: {g} vs {w}"
            );
        }
    }
}

#[test]
fn centreline_weight_agrees_with_the_symmetric_route() {
    for joints in [Discretisation::Continuum, Discretisation::Voussoirs(16)] {
        let a = arch(1.5, 90.0, WeightModel::Centreline, joints);
        assert_close(
            &format!("centreline {joints}"),
            general_values(&a),
            symmetric_values(&a),
            1e-9,
        );
    }
}

#[test]
fn segmental_and_horseshoe_arches_agree_with_the_symmetric_route() {
    // (α, a μ above μ_min, a K above K_c): μ_min is 0.0944 at 60°, 0.739 at 120°.
    for (alpha, m, k) in [(60.0, 0.5, 1.3), (120.0, 0.8, 1.6)] {
        let a = arch(1.5, alpha, WeightModel::Annular, Discretisation::Continuum);
        let s = Settings::default();
        let g = [
            k_of(&thickness(&a, Friction::INFINITE, &s)),
            mu_of(&sliding_threshold(&CircularArch::new(a), &s)),
            k_of(&thickness(&a, mu(m), &s)),
            mu_of(&friction(&CircularArch::new(a.with_k(k)), &s)),
        ];
        let w = [
            sym_k(&symmetric::thickness(&a, Friction::INFINITE)),
            sym_mu(&symmetric::sliding_threshold(&a)),
            sym_k(&symmetric::thickness(&a, mu(m))),
            sym_mu(&symmetric::friction(&a.with_k(k))),
        ];
        for i in 0..4 {
            assert!(
                abs_diff_eq!(g[i], w[i], epsilon = 1e-9),
                "α = {alpha}: value {i}: {} vs {} ({:e})",
                g[i],
                w[i],
                g[i] - w[i]
            );
        }
    }
}

#[test]
fn rotational_mechanism_at_k_c() {
    let c = thickness(
        &semi(1.5, Discretisation::Continuum),
        Friction::INFINITE,
        &Settings::default(),
    );
    let s = c.found().unwrap();
    let m = s.mechanism.as_ref().unwrap();
    assert_eq!(m.kind, MechanismKind::Rotational);
    let angles: Vec<(f64, Face)> = m.hinges.iter().map(|h| (h.angle_deg, h.face)).collect();
    assert_eq!(angles.len(), 5, "{angles:?}");
    let want = [
        (-90.0, Face::Extrados),
        (-54.48397403, Face::Intrados),
        (0.0, Face::Extrados),
        (54.48397403, Face::Intrados),
        (90.0, Face::Extrados),
    ];
    for ((a, f), (wa, wf)) in angles.iter().zip(want) {
        assert_eq!(*f, wf);
        assert!(abs_diff_eq!(*a, wa, epsilon = 1e-6), "{angles:?}");
    }
    // The limit state is symmetric: no shear at the crown, thrust = μ at the bifurcation.
    let crown = s.state.crown;
    assert_abs_diff_eq!(crown.shear_over_half_weight, 0.0, epsilon = 1e-12);
    assert_abs_diff_eq!(crown.thrust_over_half_weight, MU_ROT, epsilon = 1e-9);
}

#[test]
fn sliding_mechanism_at_mu_min() {
    let c = sliding_threshold(
        &CircularArch::new(semi(1.3, Discretisation::Continuum)),
        &Settings::default(),
    );
    let m = c.found().unwrap().mechanism.clone().unwrap();
    assert_eq!(m.kind, MechanismKind::Sliding);
    let j: Vec<(f64, Sense)> = m
        .sliding_joints
        .iter()
        .map(|j| (j.angle_deg, j.sense))
        .collect();
    assert_eq!(j.len(), 4, "{j:?}");
    assert!(abs_diff_eq!(j[2].0, 28.63619468, epsilon = 1e-6), "{j:?}");
    assert_eq!(j[2].1, Sense::Inward, "{j:?}");
    assert!(abs_diff_eq!(j[3].0, 90.0, epsilon = 1e-12), "{j:?}");
    assert_eq!(j[3].1, Sense::Outward, "{j:?}");
    assert_eq!((j[0].1, j[1].1), (Sense::Outward, Sense::Inward), "{j:?}");
}

#[test]
fn mixed_mechanism_between_the_bifurcations() {
    let c = thickness(
        &semi(1.5, Discretisation::Continuum),
        mu(0.35),
        &Settings::default(),
    );
    let m = c.found().unwrap().mechanism.clone().unwrap();
    assert_eq!(m.kind, MechanismKind::Mixed, "{m:?}");
    // Sliding at both springings, outward.
    assert_eq!(m.sliding_joints.len(), 2, "{m:?}");
    assert!(m.sliding_joints.iter().all(|j| j.sense == Sense::Outward));
}

#[test]
fn regimes_agree_with_the_symmetric_route() {
    let s = Settings::default();
    let points = [
        (1.3, 0.6),
        (1.2, f64::INFINITY),
        (1.05, 0.6),
        (1.1, f64::INFINITY),
        (1.15, 0.33),
        (1.12, 0.36),
        (1.3, 0.2),
        (1.5, 0.3),
        (1.05, 0.2),
        (1.1, 0.0),
    ];
    let mut seen = std::collections::HashSet::new();
    for joints in [
        Discretisation::Continuum,
        Discretisation::Voussoirs(16),
        Discretisation::Voussoirs(64),
    ] {
        for (k, m) in points {
            let a = semi(k, joints);
            let f = if m.is_infinite() {
                Friction::INFINITE
            } else {
                mu(m)
            };
            let want = symmetric::state(&a, f).regime;
            let got = regime(&CircularArch::new(a), f.angle(), &s);
            assert_eq!(got.regime, Some(want), "K = {k}, μ = {m}, {joints}");
            seen.insert(want);
        }
    }
    assert_eq!(seen.len(), 5, "{seen:?}");
}

#[test]
fn degenerate_points_give_finite_answers() {
    let s = Settings::default();
    for joints in [Discretisation::Continuum, Discretisation::Voussoirs(3)] {
        for k in [1.0 + 1e-9, 1.1, 3.0] {
            let g = CircularArch::new(semi(k, joints));
            for phi in [0.0, 0.3, FRAC_PI_2] {
                let r = regime(&g, phi, &s);
                assert!(r.regime.is_some(), "K = {k}, φ = {phi}, {joints}");
                for m in [&r.rotational, &r.sliding, &r.all] {
                    assert!(m.margin.is_finite() && m.margin <= s.margin_cap);
                    assert!(m.crown.thrust_over_half_weight.is_finite());
                }
            }
        }
    }
    // A single voussoir on two springings: the thinnest arch stands at μ = ∞.
    let one = semi(1.5, Discretisation::Voussoirs(1));
    let t = thickness(&one, Friction::INFINITE, &s);
    assert_eq!(
        t,
        Critical::AlwaysStands,
        "{:?}",
        symmetric::thickness(&one, Friction::INFINITE)
    );
}

/// The semicircular arch with a horizontal body force λ·g to the right (docs/mechanics.md §1).
struct Horizontal(CircularArch);

impl ArchGeometry for Horizontal {
    fn half_angle(&self) -> f64 {
        self.0.half_angle()
    }
    fn joint(&self, theta: f64) -> crate::analysis::statics::Joint {
        self.0.joint(theta)
    }
    fn dead_load(&self, theta: f64) -> Resultant {
        self.0.dead_load(theta)
    }
    fn live_load(&self, theta: f64) -> Resultant {
        // Per unit λ the force is the weight, acting at the weight radius ρ_s.
        let a = self.0.half_angle();
        Resultant {
            fx: theta / a,
            fy: 0.0,
            m: -self.0.weight_radius() * theta.sin() / a,
        }
    }
    fn discrete_joints(&self) -> Option<Vec<f64>> {
        self.0.discrete_joints()
    }
}

#[test]
fn load_factor_vanishes_at_collapse_and_matches_the_margin() {
    let s = Settings::default();
    let kc = k_of(&thickness(
        &semi(1.5, Discretisation::Continuum),
        Friction::INFINITE,
        &s,
    ));
    // Just above K_c the arch carries only a vanishing horizontal load.
    let near_kc = load_factor(
        &Horizontal(CircularArch::new(semi(
            kc + 1e-9,
            Discretisation::Continuum,
        ))),
        FRAC_PI_2,
        &s,
    );
    assert_eq!(near_kc.outcome, Outcome::Solved);
    assert!(
        near_kc.lambda > 0.0 && near_kc.lambda < 1e-7,
        "λ = {}",
        near_kc.lambda
    );
    for joints in [Discretisation::Continuum, Discretisation::Voussoirs(64)] {
        let g = Horizontal(CircularArch::new(semi(1.3, joints)));
        let lf = load_factor(&g, 0.6f64.atan(), &s);
        assert_eq!(lf.outcome, Outcome::Solved, "{joints}");
        assert!(lf.lambda > 0.05 && lf.lambda < 1.0, "λ = {}", lf.lambda);
        assert!(lf.mechanism.is_some());
        // At λ_max the margin is zero; a little less λ leaves it positive.
        let at = |lambda: f64| {
            let s = Settings { lambda, ..s };
            margin(&g, 0.6f64.atan(), RowSet::All, &s).margin
        };
        assert!(
            abs_diff_eq!(at(lf.lambda), 0.0, epsilon = 1e-10),
            "{}",
            at(lf.lambda)
        );
        assert!(at(lf.lambda - 1e-3) > 0.0);
        assert!(at(lf.lambda + 1e-3) < 0.0);
    }
    // Without any live load λ is unbounded.
    let plain = load_factor(
        &CircularArch::new(semi(1.3, Discretisation::Voussoirs(8))),
        FRAC_PI_2,
        &s,
    );
    assert_eq!(plain.outcome, Outcome::Unbounded);
    assert_eq!(plain.lambda, f64::INFINITY);
}

#[test]
fn discrete_load_factor_tends_to_the_continuum() {
    let s = Settings::default();
    let phi = 0.6f64.atan();
    let cont = load_factor(
        &Horizontal(CircularArch::new(semi(1.3, Discretisation::Continuum))),
        phi,
        &s,
    );
    let fine = load_factor(
        &Horizontal(CircularArch::new(semi(
            1.3,
            Discretisation::Voussoirs(4096),
        ))),
        phi,
        &s,
    );
    // Fewer potential joints: the discrete arch carries at least as much.
    assert!(cont.lambda <= fine.lambda + 1e-12);
    assert!(
        fine.lambda - cont.lambda < 1e-5,
        "{} {}",
        cont.lambda,
        fine.lambda
    );
}

/// Solves maximise z₄ subject to a z ≤ b with clarabel (the oracle).
fn clarabel_max(rows: &LinearRows) -> f64 {
    use clarabel::algebra::CscMatrix;
    use clarabel::solver::{
        DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus,
    };
    let p = CscMatrix::<f64>::zeros((4, 4));
    let q = OBJECTIVE.map(|c| -c);
    let a = CscMatrix::from(rows.a.iter());
    let cones = [NonnegativeConeT(rows.b.len())];
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .tol_gap_abs(1e-11)
        .tol_gap_rel(1e-11)
        .tol_feas(1e-11)
        .build()
        .unwrap();
    let mut solver = DefaultSolver::new(&p, &q, &a, &rows.b, &cones, settings).unwrap();
    solver.solve();
    assert_eq!(solver.solution.status, SolverStatus::Solved);
    solver.solution.x[3]
}

#[test]
fn clarabel_agrees_on_the_n64_programmes() {
    let s = Settings::default();
    let g = Horizontal(CircularArch::new(semi(1.2, Discretisation::Voussoirs(64))));
    let thetas = g.discrete_joints().unwrap();
    for (set, phi) in [
        (RowSet::All, 0.35f64.atan()),
        (RowSet::All, FRAC_PI_2),
        (RowSet::Rotational, 1.0),
    ] {
        let rows = LinearRows::margin(&g, &thetas, phi, set, 0.0, s.margin_cap);
        let ours = lp::maximise(&OBJECTIVE, &rows.a, &rows.b, &s.lp).unwrap();
        assert_eq!(ours.status, lp::Status::Optimal);
        let oracle = clarabel_max(&rows);
        assert!(
            abs_diff_eq!(ours.x[3], oracle, epsilon = 1e-7),
            "{set:?}: {} vs {oracle}",
            ours.x[3]
        );
        // The general route uses the same programme.
        let m = margin(&g, phi, set, &s);
        assert_abs_diff_eq!(m.margin, ours.x[3], epsilon = 1e-14);
    }
    let rows = LinearRows::load_factor(&g, &thetas, 0.6f64.atan(), RowSet::All);
    let ours = lp::maximise(&OBJECTIVE, &rows.a, &rows.b, &s.lp).unwrap();
    assert_eq!(ours.status, lp::Status::Optimal);
    let oracle = clarabel_max(&rows);
    assert!(
        abs_diff_eq!(ours.x[3], oracle, epsilon = 1e-7),
        "λ: {} vs {oracle}",
        ours.x[3]
    );
}
