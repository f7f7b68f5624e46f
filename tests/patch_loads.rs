//! Patch loads: a point load spread over a length of the extrados. An independent discrete
//! model (circular arch, radial joints, written from docs/loads-and-geometries.md alone: the
//! blocks' sector weights and centroids in closed form, each block's share of the patch from
//! the overlap of its extrados with the patch, equilibrium, no tension and Coulomb friction at
//! every joint, clarabel for the programme) against archstudy's voussoir route; the continuum
//! against fine voussoirs; the zero-width sliver of a concentrated load gone; the manifest
//! key, the command-line option and the stored column.

use crate::apex_oracle::csc;
use crate::common::{Draw, archstudy, manifest, scratch, solve_json, stderr};
use archstudy::model::{Arch, ArchForm, Discretisation, Friction, Load, WeightModel};
use archstudy::scene::{self, Find, Outcome, Scene, Solution};
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus,
};

/// A circular arch of `n` voussoirs (radial joints, annular weight) under a patch load.
#[derive(Clone, Copy, Debug)]
struct Discrete {
    k: f64,
    alpha_deg: f64,
    n: usize,
    mu: f64,
    at_x: f64,
    width: f64,
}

/// A load (fx, fy, moment about the arch's centre) applied to one block.
type Wrench = [f64; 3];

impl Discrete {
    fn joint(&self, j: usize) -> f64 {
        let a = self.alpha_deg.to_radians();
        -a + 2.0 * a * j as f64 / self.n as f64
    }

    /// The weight of block b (between joints b and b + 1): an annular sector.
    fn weight(&self, b: usize) -> Wrench {
        let (t0, t1) = (self.joint(b), self.joint(b + 1));
        let (dt, mid) = (t1 - t0, 0.5 * (t0 + t1));
        let area = 0.5 * (self.k * self.k - 1.0) * dt;
        let rho = 2.0 / 3.0 * (self.k.powi(3) - 1.0) / (self.k * self.k - 1.0) * (0.5 * dt).sin()
            / (0.5 * dt);
        [0.0, -area, -area * rho * mid.sin()]
    }

    /// Block b's part of a unit patch load: its extrados covers x from K sin θ_b to
    /// K sin θ_{b+1}; the patch covers [x0, x1] uniformly.
    fn patch(&self, b: usize) -> Wrench {
        let half_span = self.k * self.alpha_deg.to_radians().sin();
        let x0 = (2.0 * (self.at_x - 0.5 * self.width) - 1.0) * half_span;
        let x1 = (2.0 * (self.at_x + 0.5 * self.width) - 1.0) * half_span;
        let lo = (self.k * self.joint(b).sin()).max(x0);
        let hi = (self.k * self.joint(b + 1).sin()).min(x1);
        if hi <= lo {
            return [0.0; 3];
        }
        let f = (hi - lo) / (x1 - x0);
        [0.0, -f, -f * 0.5 * (lo + hi)]
    }

    /// λ_max (multiples of the total weight), `None` when the programme has no optimum
    /// (the arch never stands, or λ is unbounded).
    fn lambda_max(&self) -> Option<f64> {
        // Unknowns: the force (Fx, Fy) and moment M (about the centre) that the left
        // springing passes on, and λ. The force at joint j is affine in them: the sum of the
        // loads on the blocks before it.
        let w_total = (self.k * self.k - 1.0) * self.alpha_deg.to_radians();
        let nv = 4;
        let (mut trip, mut rhs) = (Vec::new(), Vec::new());
        let mut dead = [0.0; 3];
        let mut live = [0.0; 3];
        for j in 0..=self.n {
            if j > 0 {
                let (w, p) = (self.weight(j - 1), self.patch(j - 1));
                for c in 0..3 {
                    dead[c] += w[c];
                    live[c] += w_total * p[c];
                }
            }
            let t = self.joint(j);
            let (s, c) = t.sin_cos();
            // Joint j carries F = (Fx, Fy) + dead + λ live, M likewise. Its normal force is
            // N = F·(cos θ, −sin θ), its shear T = F·(sin θ, cos θ), and M = −ρN with ρ the
            // radius where the force crosses it: 1 ≤ ρ ≤ K, |T| ≤ μN.
            let n_of = [c, -s, 0.0];
            let t_of = [s, c, 0.0];
            let m_of = [0.0, 0.0, 1.0];
            let mut row = |coef: [f64; 3], sign: f64| {
                // g = coef·(F, M) ≤ 0 written as a·x + slack = b.
                let r = rhs.len();
                for (i, &v) in coef.iter().enumerate() {
                    trip.push((r, i, sign * v));
                }
                let lin: f64 = (0..3).map(|i| coef[i] * live[i]).sum();
                trip.push((r, 3, sign * lin));
                let cst: f64 = (0..3).map(|i| coef[i] * dead[i]).sum();
                rhs.push(-sign * cst);
            };
            let comb = |a: [f64; 3], x: f64, b: [f64; 3], y: f64| {
                [
                    a[0] * x + b[0] * y,
                    a[1] * x + b[1] * y,
                    a[2] * x + b[2] * y,
                ]
            };
            row(comb(m_of, 1.0, n_of, 1.0), 1.0); // M + N ≤ 0
            row(comb(m_of, -1.0, n_of, -self.k), 1.0); // −M − K N ≤ 0
            row(comb(t_of, 1.0, n_of, -self.mu), 1.0); // T − μN ≤ 0
            row(comb(t_of, -1.0, n_of, -self.mu), 1.0); // −T − μN ≤ 0
        }
        // λ ≥ 0 and a cap that tells an unbounded λ.
        let r = rhs.len();
        trip.push((r, 3, -1.0));
        rhs.push(0.0);
        trip.push((r + 1, 3, 1.0));
        rhs.push(1e6);
        let m = rhs.len();
        let a = csc(m, nv, &trip);
        let q = vec![0.0, 0.0, 0.0, -1.0];
        let settings = DefaultSettingsBuilder::default()
            .verbose(false)
            .tol_gap_abs(1e-11)
            .tol_gap_rel(1e-11)
            .tol_feas(1e-11)
            .build()
            .expect("settings");
        let pz = CscMatrix::<f64>::zeros((nv, nv));
        let cones = [NonnegativeConeT(m)];
        let mut solver = DefaultSolver::new(&pz, &q, &a, &rhs, &cones, settings).expect("solver");
        solver.solve();
        match solver.solution.status {
            SolverStatus::Solved | SolverStatus::AlmostSolved => {
                let l = solver.solution.x[3];
                (l < 1e5).then_some(l)
            }
            _ => None,
        }
    }

    fn archstudy(&self, n: Discretisation) -> Solution {
        let arch = Arch::new(self.k, self.alpha_deg, WeightModel::Annular, n).unwrap();
        scene::solve(&Scene {
            arch,
            friction: Friction::new(self.mu).unwrap(),
            find: Find::LoadFactor,
            form: ArchForm::default(),
            load: Load::PointX {
                at_x: self.at_x,
                width: self.width,
            },
            lambda: 0.0,
        })
    }
}

#[test]
fn voussoirs_under_a_patch_agree_with_an_independent_discrete_programme() {
    let mut draw = Draw(29);
    let (mut found, mut compared) = (0, 0);
    while compared < 100 {
        let width = draw.range(0.02, 0.4);
        let d = Discrete {
            k: draw.range(1.08, 1.5),
            alpha_deg: draw.range(30.0, 90.0),
            n: 2 + (draw.next() * 14.0) as usize,
            mu: draw.range(0.25, 1.2),
            at_x: draw.range(0.5 * width, 1.0 - 0.5 * width),
            width,
        };
        let ours = d.archstudy(Discretisation::Voussoirs(d.n as u32));
        let oracle = d.lambda_max();
        compared += 1;
        match (ours.outcome, oracle) {
            (Some(Outcome::Found), Some(l)) => {
                let got = ours.load_factor.unwrap();
                assert!(
                    (got - l).abs() <= 1e-6 * l.max(1.0),
                    "{d:?}: archstudy {got}, oracle {l}"
                );
                found += 1;
            }
            (Some(Outcome::Unbounded | Outcome::NeverStands), None) => {}
            (o, l) => panic!(
                "{d:?}: archstudy {o:?} {:?}, oracle {l:?}",
                ours.load_factor
            ),
        }
    }
    assert!(
        found >= 45,
        "only {found} of {compared} scenes had a finite λ_max"
    );
}

/// α = 60°, load at x/L = 0.25, μ = 0.3: concentrated, the load punches a sliver of zero
/// width and λ_max is the same at every K; spread over 5 % of the span, the block under the
/// patch slides on the joints at its ends.
const SLIVER: (f64, f64, f64) = (60.0, 0.25, 0.3);

fn sliver_scene(k: f64, width: f64, n: Discretisation) -> Solution {
    let (alpha, at_x, mu) = SLIVER;
    Discrete {
        k,
        alpha_deg: alpha,
        n: 1,
        mu,
        at_x,
        width,
    }
    .archstudy(n)
}

#[test]
fn a_patch_replaces_the_sliver_by_the_block_under_it() {
    let point = sliver_scene(1.25, 0.0, Discretisation::Continuum);
    assert!((point.load_factor.unwrap() - 0.4893567758).abs() < 1e-9);
    let patch = sliver_scene(1.25, 0.05, Discretisation::Continuum);
    let l = patch.load_factor.unwrap();
    assert!((l - 0.5427678387).abs() < 1e-9, "{l}");
    // The sliding joints are the patch's ends: sin θ = (2 x/L − 1) sin α.
    let ends: Vec<f64> = [0.225f64, 0.275]
        .iter()
        .map(|x| {
            ((2.0 * x - 1.0) * 60f64.to_radians().sin())
                .asin()
                .to_degrees()
        })
        .collect();
    let sliding: Vec<f64> = patch.sliding_joints.iter().map(|j| j.angle_deg).collect();
    for e in &ends {
        assert!(
            sliding.iter().any(|s| (s - e).abs() < 1e-6),
            "{sliding:?} {ends:?}"
        );
    }
    assert_eq!(patch.mechanism_admissible, Some(true));
    // A narrower patch tends to the concentrated load.
    let narrow = sliver_scene(1.25, 1e-6, Discretisation::Continuum);
    assert!((narrow.load_factor.unwrap() - 0.4893567758).abs() < 1e-5);
    // Fine voussoirs approach the continuum from above (their joints miss the patch's ends).
    let mut last = f64::INFINITY;
    for n in [1000, 4000, 16000] {
        let v = sliver_scene(1.25, 0.05, Discretisation::Voussoirs(n))
            .load_factor
            .unwrap();
        assert!(v >= l - 1e-9 && v <= last + 1e-9, "{n}: {v} against {l}");
        last = v;
    }
    assert!((last - l) / l < 2e-4, "{last} against {l}");
}

#[test]
fn a_patch_on_the_continuum_agrees_with_fine_voussoirs_in_a_rotational_collapse() {
    let d = Discrete {
        k: 1.3,
        alpha_deg: 80.0,
        n: 4000,
        mu: 1.0,
        at_x: 0.3,
        width: 0.1,
    };
    let c = d.archstudy(Discretisation::Continuum);
    let v = d.archstudy(Discretisation::Voussoirs(4000));
    let (lc, lv) = (c.load_factor.unwrap(), v.load_factor.unwrap());
    assert_eq!(c.mechanism.map(|m| m.as_str()), Some("rotational"));
    assert!(lv >= lc - 1e-9 && (lv - lc) / lc < 1e-5, "{lc} {lv}");
}

#[test]
fn the_width_key_and_option_are_checked_and_stored() {
    let dir = scratch("patch-keys");
    let bad = |extra: &str, grid: &str| {
        let m = manifest(
            &dir,
            "bad.yaml",
            &format!(
                "name: p\narch: {{half_angle_deg: 60}}\ngrid:\n  k: {{values: [1.2]}}\n  mu: {{values: [0.4]}}\n{grid}load_cases:\n  - {{name: p, kind: point{extra}}}\nfind: load_factor\n"
            ),
        );
        let out = archstudy(&["run", m.to_str().unwrap(), "--out", dir.to_str().unwrap()]);
        assert!(!out.status.success());
        stderr(&out)
    };
    let e = bad(", at_x: 0.05, width: 0.2", "");
    assert!(
        e.contains("load_cases.width") && e.contains("past a"),
        "{e}"
    );
    let e = bad(", at_x: 0.5, width: 1.5", "");
    assert!(
        e.contains("load_cases.width") && e.contains("[0, 1]"),
        "{e}"
    );
    let e = bad(", width: 0.1", "  at_x: {values: [0.5, 0.97]}\n");
    assert!(e.contains("x/L = 0.97"), "{e}");
    let m = manifest(
        &dir,
        "h.yaml",
        "name: h\narch: {half_angle_deg: 60}\ngrid:\n  k: {values: [1.2]}\n  mu: {values: [0.4]}\nload_cases:\n  - {name: h, kind: horizontal, width: 0.1}\nfind: load_factor\n",
    );
    let out = archstudy(&["run", m.to_str().unwrap(), "--out", dir.to_str().unwrap()]);
    assert!(stderr(&out).contains("only a `point` load case can be spread"));
    let m = manifest(
        &dir,
        "w.yaml",
        "name: w\narch: {half_angle_deg: 100}\ngrid:\n  k: {values: [1.2]}\n  mu: {values: [0.4]}\nload_cases:\n  - {name: p, kind: point, at_deg: 10, width: 0.1}\nfind: load_factor\n",
    );
    let out = archstudy(&["run", m.to_str().unwrap(), "--out", dir.to_str().unwrap()]);
    assert!(stderr(&out).contains("at most 90°"), "{}", stderr(&out));

    let j = solve_json(&[
        "--find",
        "load-factor",
        "--k",
        "1.25",
        "--mu",
        "0.3",
        "--half-angle",
        "60",
        "--load",
        "point",
        "--at-x",
        "0.25",
        "--width",
        "0.05",
    ]);
    assert_eq!(j["load_width"], 0.05);
    assert!((j["load_factor"].as_f64().unwrap() - 0.5427678387).abs() < 1e-9);
    let out = archstudy(&["solve", "--load", "horizontal", "--width", "0.1"]);
    assert!(stderr(&out).contains("--width"), "{}", stderr(&out));
    let out = archstudy(&[
        "solve",
        "--find",
        "load-factor",
        "--load",
        "point",
        "--at-x",
        "0.02",
        "--width",
        "0.1",
        "--half-angle",
        "60",
    ]);
    assert!(!out.status.success());
    assert!(stderr(&out).contains("--width"), "{}", stderr(&out));
}
