//! Whole-range answers and windows of K: every critical outcome agrees with the state find on
//! both sides of it, and the windows of a thickness find are every interval of K on which the
//! arch stands (docs/mechanics.md §2, README "Interval answers").

use archstudy::analysis::Regime;
use archstudy::model::{
    Arch, ArchForm, Discretisation, Friction, JointOrientation, Load, Shape, WeightModel,
};
use archstudy::scene::{self, Find, Outcome, Scene, Solution};
use proptest::prelude::*;

/// How far either side of a reported limit the state find is asked (relative).
const SIDE: f64 = 1e-6;

fn form(pointed: Option<f64>, vertical: bool) -> ArchForm {
    ArchForm {
        shape: pointed.map_or(Shape::Circular, |eccentricity| Shape::Pointed {
            eccentricity,
        }),
        joints: if vertical {
            JointOrientation::Vertical
        } else {
            JointOrientation::Radial
        },
        keystone: false,
    }
}

fn scene_of(
    half_angle: f64,
    joints: Discretisation,
    form: ArchForm,
    mu: f64,
    load: Load,
    lambda: f64,
    find: Find,
) -> Scene {
    Scene {
        arch: Arch::new(1.3, half_angle, WeightModel::Annular, joints).expect("an arch"),
        friction: Friction::new(mu).expect("μ ≥ 0"),
        find,
        form,
        load,
        lambda,
    }
}

/// The state find of `scene` at K: `Some(true)` when it stands, `None` where the form does
/// not exist.
fn stands_at_k(scene: &Scene, k: f64) -> Option<bool> {
    let arch = scene.arch.with_k(k);
    let s = Scene {
        arch,
        find: Find::State,
        ..*scene
    };
    s.check().ok()?;
    let r = scene::solve(&s).regime?;
    Some(r == Regime::Stable)
}

fn stands_at_mu(scene: &Scene, mu: f64) -> bool {
    let s = Scene {
        friction: Friction::new(mu).expect("μ ≥ 0"),
        find: Find::State,
        ..*scene
    };
    scene::solve(&s).regime == Some(Regime::Stable)
}

fn stands_at_lambda(scene: &Scene, lambda: f64) -> bool {
    let s = Scene {
        lambda,
        find: Find::State,
        ..*scene
    };
    scene::solve(&s).regime == Some(Regime::Stable)
}

/// The first example: a vertical-joint pointed arch under a horizontal load, whose
/// thickness find answered `always_stands` while the state find at K = 1.01 … 1.3 says
/// `rotational`. The two hinges at −α (on the vertical joint and on the radial support joint
/// beyond it) are two joints, not one joint with hinges on both faces.
#[test]
fn a_vertical_joint_arch_under_a_horizontal_load_has_a_collapse_thickness() {
    let s = scene_of(
        88.641,
        Discretisation::Continuum,
        form(Some(0.4452), true),
        f64::INFINITY,
        Load::Horizontal,
        0.544009,
        Find::Thickness,
    );
    let sol = scene::solve(&s);
    assert_eq!(sol.outcome, Some(Outcome::Found), "{sol:?}");
    let k = sol.k_crit.expect("K_c");
    assert!((k - 1.3400013).abs() < 5e-7, "K_c = {k}");
    for thin in [1.01, 1.1, 1.2, 1.3] {
        assert_eq!(stands_at_k(&s, thin), Some(false), "K = {thin}");
    }
    assert_eq!(stands_at_k(&s, k * (1.0 - SIDE)), Some(false));
    assert_eq!(stands_at_k(&s, k * (1.0 + SIDE)), Some(true));
    assert_eq!(sol.k_windows.first().map(|w| w.0), Some(k));
}

/// The second example: a pointed arch of 33 voussoirs with a point load stands on
/// [1.5621187, ≈1.5925], fails up to ≈2.6065 and stands again beyond.
#[test]
fn a_voussoir_arch_with_a_point_load_stands_in_two_windows() {
    let s = scene_of(
        58.297,
        Discretisation::Voussoirs(33),
        form(Some(0.3865), false),
        0.55525,
        Load::point(-44.611),
        3.356281,
        Find::Thickness,
    );
    let sol = scene::solve(&s);
    assert_eq!(sol.outcome, Some(Outcome::Found), "{sol:?}");
    let w = &sol.k_windows;
    assert_eq!(w.len(), 2, "{w:?}");
    assert!((w[0].0 - 1.5621187).abs() < 1e-7, "{w:?}");
    assert_eq!(Some(w[0].0), sol.k_crit);
    let to = w[0].1.expect("the first window closes");
    assert!((to - 1.5925).abs() < 1e-3, "{w:?}");
    assert!((w[1].0 - 2.6065).abs() < 1e-3, "{w:?}");
    assert_eq!(w[1].1, None, "stands to the end of the scan: {w:?}");
    assert!(sol.fails_again());
    // Every end is a sign change of the state find.
    for (k, inside) in [(w[0].0, 1.0), (to, -1.0), (w[1].0, 1.0)] {
        assert_eq!(stands_at_k(&s, k), Some(true), "at {k}");
        assert_eq!(stands_at_k(&s, k * (1.0 - inside * SIDE)), Some(false));
        assert_eq!(stands_at_k(&s, k * (1.0 + inside * SIDE)), Some(true));
    }
    // The summary says so.
    assert!(scene::summary(&sol).contains("fails again"));
}

/// The paper's arch has one window, open at the end of the scan, starting at its K_c.
#[test]
fn the_semicircle_stands_in_one_window_from_its_collapse_thickness() {
    let s = Scene::new(
        Arch::new(1.3, 90.0, WeightModel::Annular, Discretisation::Continuum).unwrap(),
        Friction::INFINITE,
        Find::Thickness,
    );
    let sol = scene::solve(&s);
    assert!((sol.k_crit.unwrap() - 1.113581813339).abs() < 1e-11);
    assert_eq!(sol.k_windows, vec![(sol.k_crit.unwrap(), None)]);
    assert_eq!(sol.k_windows_scanned_to, Some(3.0));
    assert!(!sol.fails_again());
}

/// A drawn scene of any arch, joint kind, load and find.
#[derive(Debug, Clone)]
struct Drawn {
    half_angle: f64,
    voussoirs: Option<u32>,
    pointed: Option<f64>,
    vertical: bool,
    mu: f64,
    load: u8,
    at: f64,
    lambda: f64,
    find: u8,
    k: f64,
}

impl Drawn {
    fn scene(&self) -> Option<Scene> {
        let joints = self
            .voussoirs
            .map_or(Discretisation::Continuum, Discretisation::Voussoirs);
        let load = match self.load {
            0 => Load::SelfWeight,
            1 => Load::Horizontal,
            _ => Load::point(self.at * self.half_angle),
        };
        let find = match self.find {
            0 => Find::Thickness,
            1 => Find::Friction,
            _ if load == Load::SelfWeight => Find::Thickness,
            _ => Find::LoadFactor,
        };
        let s = Scene {
            arch: Arch::new(self.k, self.half_angle, WeightModel::Annular, joints).ok()?,
            friction: Friction::new(self.mu)?,
            find,
            form: form(self.pointed, self.vertical),
            load,
            lambda: if load == Load::SelfWeight || find == Find::LoadFactor {
                0.0
            } else {
                self.lambda
            },
        };
        s.check().ok().map(|()| s)
    }
}

fn drawn() -> impl Strategy<Value = Drawn> {
    (
        (
            45.0..100.0f64,
            prop_oneof![Just(None), (3u32..30).prop_map(Some)],
        ),
        (
            prop_oneof![Just(None), (0.05..0.45f64).prop_map(Some)],
            any::<bool>(),
        ),
        prop_oneof![(0.2..1.2f64), Just(f64::INFINITY)],
        (0u8..3, -0.9..0.9f64, 0.0..0.6f64),
        (0u8..3, 1.05..1.6f64),
    )
        .prop_map(
            |((half_angle, voussoirs), (pointed, vertical), mu, (load, at, lambda), (find, k))| {
                Drawn {
                    half_angle,
                    voussoirs,
                    pointed,
                    vertical,
                    mu,
                    load,
                    at,
                    lambda,
                    find,
                    k,
                }
            },
        )
}

/// Vertical joints under horizontal loads, which the general draws undersample.
fn vertical_horizontal() -> impl Strategy<Value = Drawn> {
    (
        60.0..95.0f64,
        prop_oneof![Just(None), (0.05..0.45f64).prop_map(Some)],
        prop_oneof![(0.3..1.2f64), Just(f64::INFINITY)],
        0.05..0.8f64,
        0u8..3,
    )
        .prop_map(|(half_angle, pointed, mu, lambda, find)| Drawn {
            half_angle,
            voussoirs: None,
            pointed,
            vertical: true,
            mu,
            load: 1,
            at: 0.0,
            lambda,
            find,
            k: 1.3,
        })
}

/// What the state find says against a critical outcome, or `None` when they agree.
fn disagreement(scene: &Scene, s: &Solution) -> Option<String> {
    let outcome = s.outcome?;
    match (scene.find, outcome) {
        (Find::Thickness, Outcome::Found) => {
            if s.k_windows.first().map(|w| w.0) != s.k_crit {
                return Some(format!("K_c {:?} not the first window", s.k_crit));
            }
            for &(from, to) in &s.k_windows {
                let wide = to.is_none_or(|t| t - from > 4.0 * SIDE * t);
                if !wide {
                    continue;
                }
                let below = from * (1.0 - SIDE);
                if below > 1.0 + 1e-9 && stands_at_k(scene, below) == Some(true) {
                    return Some(format!("stands just below the window start {from}"));
                }
                if stands_at_k(scene, from * (1.0 + SIDE)) == Some(false) {
                    return Some(format!("fails just above the window start {from}"));
                }
                if let Some(t) = to {
                    if stands_at_k(scene, t * (1.0 - SIDE)) == Some(false) {
                        return Some(format!("fails just below the window end {t}"));
                    }
                    if stands_at_k(scene, t * (1.0 + SIDE)) == Some(true) {
                        return Some(format!("stands just above the window end {t}"));
                    }
                }
            }
            None
        }
        (Find::Thickness, Outcome::AlwaysStands | Outcome::NeverStands) => {
            let expect = outcome == Outcome::AlwaysStands;
            let to = s.k_windows_scanned_to.unwrap_or(3.0);
            [1.0 + 1e-6, 1.01, 1.1, 1.5, to]
                .into_iter()
                .filter(|&k| k <= to)
                .find(|&k| stands_at_k(scene, k).is_some_and(|st| st != expect))
                .map(|k| format!("{outcome} but the state at K = {k} disagrees"))
        }
        (Find::Friction, Outcome::Found) => {
            let m = s.mu_crit?;
            let (lo, hi) = (m * (1.0 - SIDE) - 1e-9, m * (1.0 + SIDE) + 1e-9);
            if lo > 0.0 && stands_at_mu(scene, lo) {
                return Some(format!("stands below μ_c = {m}"));
            }
            (!stands_at_mu(scene, hi)).then(|| format!("fails above μ_c = {m}"))
        }
        (Find::Friction, Outcome::AlwaysStands | Outcome::NeverStands) => {
            let expect = outcome == Outcome::AlwaysStands;
            [0.0, 0.3, f64::INFINITY]
                .into_iter()
                .find(|&m| stands_at_mu(scene, m) != expect)
                .map(|m| format!("{outcome} but the state at μ = {m} disagrees"))
        }
        (Find::LoadFactor, Outcome::Found) => {
            let l = s.load_factor?;
            let (lo, hi) = (l * (1.0 - SIDE) - 1e-9, l * (1.0 + SIDE) + 1e-9);
            if lo >= 0.0 && !stands_at_lambda(scene, lo) {
                return Some(format!("fails below λ_max = {l}"));
            }
            stands_at_lambda(scene, hi).then(|| format!("stands above λ_max = {l}"))
        }
        (Find::LoadFactor, Outcome::Unbounded | Outcome::NeverStands) => {
            let expect = outcome == Outcome::Unbounded;
            [0.0, 1.0, 100.0]
                .into_iter()
                .find(|&l| stands_at_lambda(scene, l) != expect)
                .map(|l| format!("{outcome} but the state at λ = {l} disagrees"))
        }
        _ => None,
    }
}

/// A drawn scene's answer is confirmed and agrees with the state find on both sides of it.
fn agrees_with_the_state(d: &Drawn) -> Result<(), TestCaseError> {
    let Some(scene) = d.scene() else {
        return Ok(());
    };
    let s = scene::solve(&scene);
    prop_assert_ne!(s.outcome, Some(Outcome::Unconfirmed), "{:?}", d);
    let why = disagreement(&scene, &s);
    prop_assert!(why.is_none(), "{:?}: {:?} {:?}", why, d, s);
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn every_critical_outcome_agrees_with_the_state_on_both_sides(d in drawn()) {
        agrees_with_the_state(&d)?;
    }

    #[test]
    fn vertical_joints_under_horizontal_loads_agree_with_the_state(d in vertical_horizontal()) {
        agrees_with_the_state(&d)?;
    }
}

/// Voussoir arches with point loads: a brute-force scan at a quarter of the window scan's
/// step sees no interval of standing (or failing) wider than the step that the windows do not
/// show, and every window end is a sign change of the state find.
fn voussoirs_with_point_loads() -> impl Strategy<Value = Drawn> {
    (
        45.0..90.0f64,
        5u32..40,
        prop_oneof![Just(None), (0.05..0.45f64).prop_map(Some)],
        0.3..1.0f64,
        -0.95..0.95f64,
        0.3..4.0f64,
    )
        .prop_map(|(half_angle, n, pointed, mu, at, lambda)| Drawn {
            half_angle,
            voussoirs: Some(n),
            pointed,
            vertical: false,
            mu,
            load: 2,
            at,
            lambda,
            find: 0,
            k: 1.3,
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    #[test]
    fn no_window_wider_than_the_resolution_is_missed(d in voussoirs_with_point_loads()) {
        let Some(scene) = d.scene() else {
            return Ok(());
        };
        let s = scene::solve(&scene);
        let (Some(to), Some(res)) = (s.k_windows_scanned_to, s.k_windows_resolution) else {
            return Ok(());
        };
        let inside = |k: f64| {
            s.k_windows
                .iter()
                .any(|&(a, b)| a <= k && b.is_none_or(|b| k <= b))
        };
        // Brute force at a quarter step: each sample must be where the windows put it, but
        // within a step of a window end (where a narrower interval may hide).
        let step = res / 4.0;
        let n = ((to - 1.0) / step) as usize;
        let ends: Vec<f64> = s
            .k_windows
            .iter()
            .flat_map(|&(a, b)| [Some(a), b])
            .flatten()
            .collect();
        // A run of disagreeing samples is an interval the windows miss: at most four samples
        // (narrower than the resolution).
        let mut run = 0usize;
        for i in 1..n {
            let k = 1.0 + i as f64 * step;
            let Some(st) = stands_at_k(&scene, k) else { continue };
            if st != inside(k) && ends.iter().all(|e| (e - k).abs() > res) {
                run += 1;
                prop_assert!(
                    run <= 4,
                    "K = {k}: the state says {st}, the windows {:?}: {:?}",
                    s.k_windows,
                    d
                );
            } else {
                run = 0;
            }
        }
        for &e in &ends {
            prop_assert_eq!(stands_at_k(&scene, e), Some(true), "end {} {:?}", e, d);
        }
    }
}
