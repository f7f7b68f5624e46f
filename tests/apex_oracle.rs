//! An independent discrete model of a pointed arch under a point load at its apex, written
//! from the definitions of docs/loads-and-geometries.md alone (no archstudy geometry, rows or
//! solver): the blocks' areas and centroids by Gauss–Legendre quadrature of Green's line
//! integrals on their boundaries, the equilibrium of every block with the force, shear and
//! moment of every joint as unknowns, and clarabel for the programmes.
//!
//! The critical friction μ_c is the root of the friction margin s(μ): the largest s such that
//! some admissible state (equilibrium, no tension at every joint) has |T| ≤ μN − s at every
//! joint. s is increasing and continuous, positive above μ_c and negative below.

use archstudy::model::{
    Arch, ArchForm, Discretisation, Friction, JointOrientation, Load, Shape, WeightModel,
};
use archstudy::scene::{self, Find, Outcome, Scene};
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus, ZeroConeT,
};

/// A point of the plane, over the intrados radius.
type P2 = [f64; 2];

/// The pointed arch: intrados radius 1, extrados K, right arc centred at (−d, 0) with
/// d = e·(1 + K)/2, half-angle α at the arc's centre from the vertical.
#[derive(Clone, Copy)]
struct Pointed {
    k: f64,
    alpha: f64,
    d: f64,
}

/// Where the apex load goes.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Apex {
    /// On the first block right of the crown joint, or on the keystone when there is no
    /// crown joint.
    Right,
    /// Shared between the two blocks at the crown joint in a proportion the programme
    /// chooses.
    Free,
    /// On a sliver between two crown joints, each with all its rows.
    Sliver,
}

/// One joint: its intrados and extrados ends.
#[derive(Clone, Copy)]
struct Joint {
    i: P2,
    e: P2,
}

impl Joint {
    /// Unit vector from intrados to extrados.
    fn t(&self) -> P2 {
        let (dx, dy) = (self.e[0] - self.i[0], self.e[1] - self.i[1]);
        let h = dx.hypot(dy);
        [dx / h, dy / h]
    }
    /// Unit normal from the part on the left into the part on the right.
    fn n(&self) -> P2 {
        let t = self.t();
        [t[1], -t[0]]
    }
    fn h(&self) -> f64 {
        (self.e[0] - self.i[0]).hypot(self.e[1] - self.i[1])
    }
    fn mid(&self) -> P2 {
        [0.5 * (self.i[0] + self.e[0]), 0.5 * (self.i[1] + self.e[1])]
    }
}

/// Five-point Gauss–Legendre nodes and weights on [−1, 1].
const GL: [(f64, f64); 5] = [
    (0.0, 0.568_888_888_888_888_9),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
];

/// (A, ∫x dA, ∫y dA) of a region from its boundary by Green's theorem: A = ∮x dy,
/// S_x = ∮x²/2 dy, S_y = −∮y²/2 dx, along a curve p(u), u from u0 to u1, with derivative
/// dp(u), by composite Gauss–Legendre.
fn green(p: impl Fn(f64) -> P2, dp: impl Fn(f64) -> P2, u0: f64, u1: f64) -> [f64; 3] {
    let m = ((u1 - u0).abs() / 0.01).ceil().max(1.0);
    let hstep = (u1 - u0) / m;
    let mut acc = [0.0; 3];
    for j in 0..m as usize {
        let c = u0 + (j as f64 + 0.5) * hstep;
        for (xi, w) in GL {
            let u = c + 0.5 * hstep * xi;
            let ([x, y], [dx, dy]) = (p(u), dp(u));
            let f = 0.5 * hstep * w;
            acc[0] += f * x * dy;
            acc[1] += f * 0.5 * x * x * dy;
            acc[2] -= f * 0.5 * y * y * dx;
        }
    }
    acc
}

fn plus(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

impl Pointed {
    fn new(e: f64, k: f64, alpha_deg: f64) -> Self {
        Pointed {
            k,
            alpha: alpha_deg.to_radians(),
            d: e * (1.0 + k) / 2.0,
        }
    }

    /// ψ₁: the intrados apex.
    fn psi1(&self) -> f64 {
        self.d.asin()
    }

    /// The point of radius r at the signed angle u (u > 0 on the right arc, u < 0 on the
    /// mirrored left one), and its derivative in u.
    fn at(&self, r: f64, u: f64) -> (P2, P2) {
        let c = if u >= 0.0 { -self.d } else { self.d };
        ([c + r * u.sin(), r * u.cos()], [r * u.cos(), -r * u.sin()])
    }

    /// The apex of the circle of radius r (its crossing of x = 0) and the angle there.
    fn apex(&self, r: f64) -> (P2, f64) {
        let psi = (self.d / r).asin();
        ([0.0, r * psi.cos()], psi)
    }

    /// The joint at the signed angle u; u = 0 is the crown joint x = 0.
    fn joint(&self, u: f64) -> Joint {
        if u == 0.0 {
            Joint {
                i: self.apex(1.0).0,
                e: self.apex(self.k).0,
            }
        } else {
            Joint {
                i: self.at(1.0, u).0,
                e: self.at(self.k, u).0,
            }
        }
    }

    /// Green's integrals along the arc of radius r from signed angle u0 to u1, passing
    /// through the apex when they lie on either side of it (the arcs' parts with
    /// |u| < asin(d/r) are outside the arch).
    fn arc(&self, r: f64, u0: f64, u1: f64) -> [f64; 3] {
        let psi = self.apex(r).1;
        let along = |a: f64, b: f64| green(|u| self.at(r, u).0, |u| self.at(r, u).1, a, b);
        let (lo, hi) = (u0.min(u1), u0.max(u1));
        let mut pieces = Vec::new();
        if lo < -psi {
            pieces.push((lo, hi.min(-psi)));
        }
        if hi > psi {
            pieces.push((lo.max(psi), hi));
        }
        let mut acc = [0.0; 3];
        for (a, b) in pieces {
            let g = if u1 >= u0 { along(a, b) } else { along(b, a) };
            acc = plus(acc, g);
        }
        acc
    }

    /// (A, S_x, S_y) of the block between the joints at u0 < u1 (u = 0 the crown joint).
    fn block(&self, u0: f64, u1: f64) -> [f64; 3] {
        let (j0, j1) = (self.joint(u0), self.joint(u1));
        let seg = |p: P2, q: P2| {
            green(
                |s| [p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1])],
                |_| [q[0] - p[0], q[1] - p[1]],
                0.0,
                1.0,
            )
        };
        let mut m = self.arc(1.0, u0, u1);
        m = plus(m, seg(j1.i, j1.e));
        m = plus(m, self.arc(self.k, u1, u0));
        plus(m, seg(j0.e, j0.i))
    }

    /// The joints of N voussoirs per arch: ψ = ψ₁ + s(α − ψ₁), s = |−1 + 2j/N|, s = 0 the
    /// crown joint.
    fn joints(&self, n: u32) -> Vec<f64> {
        let p1 = self.psi1();
        (0..=n)
            .map(|j| {
                let s = -1.0 + 2.0 * f64::from(j) / f64::from(n);
                if s == 0.0 {
                    0.0
                } else {
                    (p1 + s.abs() * (self.alpha - p1)).copysign(s)
                }
            })
            .collect()
    }
}

/// The friction margin s(μ) of the arch with joints `us` (increasing, from −α to α) under
/// self-weight and P = λ·W_total at the extrados apex, or None when no admissible state
/// exists at all.
fn margin(arch: &Pointed, us: &[f64], lambda: f64, apex: Apex, mu: f64) -> Option<f64> {
    let mut us = us.to_vec();
    let crown = us.iter().position(|&u| u == 0.0);
    if apex == Apex::Sliver {
        let c = crown.expect("a crown joint");
        us.insert(c, 0.0);
    }
    let joints: Vec<Joint> = us.iter().map(|&u| arch.joint(u)).collect();
    let blocks: Vec<[f64; 3]> = us.windows(2).map(|w| arch.block(w[0], w[1])).collect();
    let w_total: f64 = arch.block(-arch.alpha, 0.0)[0] + arch.block(0.0, arch.alpha)[0];
    let p = lambda * w_total;
    // The block carrying P (the free split adds a second one).
    let loaded: Vec<usize> = match (crown, apex) {
        (None, _) => vec![us.iter().position(|&u| u > 0.0).expect("a keystone") - 1],
        (Some(c), Apex::Right | Apex::Sliver) => vec![c],
        (Some(c), Apex::Free) => vec![c - 1, c],
    };
    // Unknowns: (N, T, M) per joint, then s, then the part of P on the right block.
    let nj = joints.len();
    let (is, ip) = (3 * nj, 3 * nj + 1);
    let nv = 3 * nj + 2;
    let mut trip: Vec<(usize, usize, f64)> = Vec::new();
    let mut b: Vec<f64> = Vec::new();
    let mut row = 0;
    // Equilibrium of block k between joints k and k + 1 (three equality rows).
    for (k, blk) in blocks.iter().enumerate() {
        for (j, sign) in [(k, 1.0), (k + 1, -1.0)] {
            let jt = &joints[j];
            let (n_, t_, m_) = (jt.n(), jt.t(), jt.mid());
            for (var, dir) in [(3 * j, n_), (3 * j + 1, t_)] {
                trip.push((row, var, sign * dir[0]));
                trip.push((row + 1, var, sign * dir[1]));
                trip.push((row + 2, var, sign * (m_[0] * dir[1] - m_[1] * dir[0])));
            }
            trip.push((row + 2, 3 * j + 2, sign));
        }
        // Weight at the centroid: (0, −A), moment −S_x. P acts at the extrados apex, on
        // x = 0: no moment about the origin. With a free split the right block carries the
        // unknown part p and the left one P − p.
        let mut fy = -blk[0];
        let mz = -blk[1];
        match loaded.iter().position(|&l| l == k) {
            Some(0) if loaded.len() == 2 => {
                fy -= p;
                trip.push((row + 1, ip, 1.0));
            }
            Some(1) => trip.push((row + 1, ip, -1.0)),
            Some(_) => fy -= p,
            None => {}
        }
        // A x + s = b with s = 0: the joint terms equal minus the loads.
        b.extend([0.0, -fy, -mz]);
        row += 3;
    }
    let n_eq = row;
    // Inequalities A x ≤ b: no tension |M| ≤ N h/2, Coulomb |T| + s ≤ μN, s ≤ 10, 0 ≤ p ≤ P.
    for (j, jt) in joints.iter().enumerate() {
        let h2 = 0.5 * jt.h();
        for sm in [1.0, -1.0] {
            trip.push((row, 3 * j, -h2));
            trip.push((row, 3 * j + 2, sm));
            b.push(0.0);
            row += 1;
            trip.push((row, 3 * j, -mu));
            trip.push((row, 3 * j + 1, sm));
            trip.push((row, is, 1.0));
            b.push(0.0);
            row += 1;
        }
    }
    trip.push((row, is, 1.0));
    b.push(10.0);
    row += 1;
    trip.push((row, ip, 1.0));
    b.push(p);
    row += 1;
    trip.push((row, ip, -1.0));
    b.push(0.0);
    row += 1;
    let a = csc(row, nv, &trip);
    let mut q = vec![0.0; nv];
    q[is] = -1.0;
    let cones = [ZeroConeT(n_eq), NonnegativeConeT(row - n_eq)];
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .tol_gap_abs(1e-12)
        .tol_gap_rel(1e-12)
        .tol_feas(1e-12)
        .build()
        .expect("settings");
    let pz = CscMatrix::<f64>::zeros((nv, nv));
    let mut solver = DefaultSolver::new(&pz, &q, &a, &b, &cones, settings).expect("solver");
    solver.solve();
    match solver.solution.status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => Some(solver.solution.x[is]),
        _ => None,
    }
}

/// A compressed-column matrix from (row, column, value) triplets.
pub(crate) fn csc(m: usize, n: usize, trip: &[(usize, usize, f64)]) -> CscMatrix<f64> {
    let mut cols: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
    for &(r, c, v) in trip {
        cols[c].push((r, v));
    }
    let (mut colptr, mut rowval, mut nzval) = (vec![0], Vec::new(), Vec::new());
    for col in &mut cols {
        col.sort_by_key(|e| e.0);
        // Sum duplicates.
        let mut last: Option<usize> = None;
        for &(r, v) in col.iter() {
            if last == Some(r) {
                *nzval.last_mut().expect("an entry") += v;
            } else {
                rowval.push(r);
                nzval.push(v);
                last = Some(r);
            }
        }
        colptr.push(rowval.len());
    }
    CscMatrix::new(m, n, colptr, rowval, nzval)
}

/// μ_c: the root of the margin, by the Illinois method from a bracket.
fn mu_crit(arch: &Pointed, us: &[f64], lambda: f64, apex: Apex) -> f64 {
    let f = |mu: f64| margin(arch, us, lambda, apex, mu).expect("an admissible state");
    let (mut a, mut b) = (0.0, 1.0);
    let (mut fa, mut fb) = (f(a), f(b));
    assert!(fa < 0.0 && fb > 0.0, "{fa} {fb}");
    let mut side = 0;
    for _ in 0..60 {
        let c = (a * fb - b * fa) / (fb - fa);
        let fc = f(c);
        if fc.abs() < 1e-13 || (b - a) < 1e-12 {
            return c;
        }
        if fc > 0.0 {
            b = c;
            fb = fc;
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        } else {
            a = c;
            fa = fc;
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
        }
    }
    0.5 * (a + b)
}

/// The scene of docs/loads-and-geometries.md, *A point load at the apex of a pointed arch*.
const E: f64 = 0.1213;
const K: f64 = 1.340132;
const ALPHA: f64 = 45.37;
const LAMBDA: f64 = 0.166277;

/// Two codes solving one discrete programme agree to the root tolerances of their friction
/// searches; discrete and continuum values with a joint at the continuum's critical joint
/// agree as well.
const SAME: f64 = 1e-9;

/// archstudy's answer for the scene: μ_c with the load on the right half, μ_c with the free
/// split, and the angles of the sliding joints of the limit state.
fn archstudy_mu(joints: Discretisation) -> (f64, Option<f64>, Vec<f64>) {
    let s = scene_of(joints);
    let sol = scene::solve(&s);
    assert_eq!(sol.outcome, Some(Outcome::Found), "{joints:?}");
    let sliding = sol.sliding_joints.iter().map(|j| j.angle_deg).collect();
    (sol.mu_crit.expect("μ_c"), sol.critical_apex_shared, sliding)
}

fn scene_of(joints: Discretisation) -> Scene {
    let arch = Arch::new(K, ALPHA, WeightModel::Annular, joints).expect("an arch");
    Scene {
        arch,
        friction: Friction::new(f64::INFINITY).expect("μ"),
        find: Find::Friction,
        form: ArchForm {
            shape: Shape::Pointed { eccentricity: E },
            keystone: false,
            joints: JointOrientation::Radial,
        },
        load: Load::point(0.0),
        lambda: LAMBDA,
    }
}

/// `joints` with the joints `extra` added, sorted.
fn with_joints(joints: &[f64], extra: &[f64]) -> Vec<f64> {
    let mut us = joints.to_vec();
    us.extend_from_slice(extra);
    us.sort_by(f64::total_cmp);
    us
}

/// The whole load on the right half (one crown joint, left of the load). The independent
/// model agrees with archstudy on 100 voussoirs; with the continuum's critical joint ψ*
/// (sliding inward at 18.52°) added to its joints it gives the continuum's μ_c. A discrete
/// arch has a subset of the continuum's joints, so its μ_c is never larger; the shortfall is
/// quadratic in the distance δ from its nearest joint to ψ* (the violation at ψ* is a smooth
/// maximum): halving δ divides it by 4, about 0.13·δ² (δ in radians). With N voussoirs per
/// arch δ ≤ (α − ψ₁)/N, so μ_c(N) is within 0.13·((α − ψ₁)/N)² of the continuum: 1.4e-8
/// at N = 2000.
#[test]
fn one_half_value_is_that_of_an_independent_model() {
    let arch = Pointed::new(E, K, ALPHA);
    let (continuum, _, sliding) = archstudy_mu(Discretisation::Continuum);
    approx::assert_abs_diff_eq!(continuum, 0.0773289, epsilon = 5e-8);
    let psi = sliding
        .iter()
        .copied()
        .find(|&a| a > 1.0 && a < ALPHA - 1.0)
        .expect("an interior sliding joint")
        .to_radians();
    let base = arch.joints(100);
    let discrete = mu_crit(&arch, &base, LAMBDA, Apex::Right);
    let (theirs, _, _) = archstudy_mu(Discretisation::Voussoirs(100));
    approx::assert_abs_diff_eq!(discrete, theirs, epsilon = SAME);
    let with_psi = mu_crit(&arch, &with_joints(&base, &[psi]), LAMBDA, Apex::Right);
    approx::assert_abs_diff_eq!(with_psi, continuum, epsilon = SAME);
    // The shortfall of a joint at ψ* + δ on 20 voussoirs (whose nearest joint is farther).
    let coarse = arch.joints(20);
    let shortfall = |delta: f64| {
        continuum
            - mu_crit(
                &arch,
                &with_joints(&coarse, &[psi + delta]),
                LAMBDA,
                Apex::Right,
            )
    };
    let (a, b, c) = (shortfall(4e-3), shortfall(2e-3), shortfall(1e-3));
    for (d, v) in [(4e-3, a), (2e-3, b), (1e-3, c)] {
        assert!(
            (0.10..0.16).contains(&(v / (d * d))),
            "δ = {d}: {v} ({})",
            v / (d * d)
        );
    }
    assert!(
        (3.6..4.4).contains(&(a / b)) && (3.6..4.4).contains(&(b / c)),
        "{a} {b} {c}"
    );
}

/// The free split, and an odd count whose keystone lies over the apex: archstudy and the
/// independent model agree on 20 (free split) and 21 (keystone) voussoirs. Their continuum
/// limits are one value: the independent model with the critical joints ±ψ* added (sliding
/// inward at ±21.97°) gives archstudy's continuum free split both with a crown joint whose
/// shear may take any value between T and T − P and with a rigid keystone spanning the
/// wedges between ±ψ₁ (no crown joint at all). The free split's crown rows do not bind.
#[test]
fn free_split_and_keystone_limit_are_one_value() {
    use archstudy::analysis::forms::ArchModel;
    use archstudy::analysis::general;
    let arch = Pointed::new(E, K, ALPHA);
    let (_, shared, _) = archstudy_mu(Discretisation::Continuum);
    let shared = shared.expect("a free split");
    approx::assert_abs_diff_eq!(shared, 0.0380245, epsilon = 5e-8);
    // archstudy's own critical joints of the free split.
    let s = scene_of(Discretisation::Continuum);
    let model = ArchModel::new(s.arch, s.form, s.load)
        .expect("a valid form")
        .with_shared_apex();
    let settings = general::Settings {
        lambda: LAMBDA,
        ..general::Settings::default()
    };
    let limit = general::friction(&model, &settings);
    let state = limit.found().expect("a limit state");
    approx::assert_abs_diff_eq!(state.mu, shared, epsilon = 1e-12);
    let psi = state
        .mechanism
        .as_ref()
        .expect("a mechanism")
        .sliding_joints
        .iter()
        .map(|j| j.angle_deg)
        .find(|&a| a > 1.0 && a < ALPHA - 1.0)
        .expect("an interior sliding joint")
        .to_radians();
    let base = arch.joints(20);
    let free = mu_crit(&arch, &base, LAMBDA, Apex::Free);
    let (_, theirs, _) = archstudy_mu(Discretisation::Voussoirs(20));
    approx::assert_abs_diff_eq!(free, theirs.expect("a free split"), epsilon = SAME);
    let keystone = mu_crit(&arch, &arch.joints(21), LAMBDA, Apex::Right);
    let (theirs, none, _) = archstudy_mu(Discretisation::Voussoirs(21));
    approx::assert_abs_diff_eq!(keystone, theirs, epsilon = SAME);
    assert_eq!(none, None);
    let free_limit = mu_crit(&arch, &with_joints(&base, &[-psi, psi]), LAMBDA, Apex::Free);
    approx::assert_abs_diff_eq!(free_limit, shared, epsilon = SAME);
    let p1 = arch.psi1();
    let no_crown: Vec<f64> = base.iter().copied().filter(|&u| u != 0.0).collect();
    let wedges = with_joints(&no_crown, &[-psi, psi, -p1, p1]);
    let keystone_limit = mu_crit(&arch, &wedges, LAMBDA, Apex::Right);
    approx::assert_abs_diff_eq!(keystone_limit, shared, epsilon = SAME);
}

/// μ_c with P on a sliver between two crown joints, each with all its rows (both sides of
/// the load are joints, as for a load inside the continuum of a circular arch). Only the
/// crown joints and the springings take part: the sliver punches down between the halves
/// (|T| and |T − P| within μN, so H ≥ λ/μ with T = P/2) while the halves slide outward on
/// their springings (H ≤ (1 + λ)·cot(α − φ), tan φ = μ), all over W_half. So μ_c is the
/// positive root of (1 + λ) sin α μ² + (1 + 2λ) cos α μ − λ sin α = 0, whatever the
/// eccentricity, thickness and voussoir count: 0.1147321, the 0.11473 reported for this scene
/// by a programme meant to put the whole load on one half that kept a joint on each side of it.
#[test]
fn load_on_a_sliver_between_two_crown_joints_gives_0_11473() {
    let (s, c) = ALPHA.to_radians().sin_cos();
    let (a, b, q) = ((1.0 + LAMBDA) * s, (1.0 + 2.0 * LAMBDA) * c, -LAMBDA * s);
    let closed = (-b + (b * b - 4.0 * a * q).sqrt()) / (2.0 * a);
    approx::assert_abs_diff_eq!(closed, 0.11473, epsilon = 5e-6);
    for (e, n) in [(E, 2), (E, 20), (0.3, 2)] {
        let arch = Pointed::new(e, K, ALPHA);
        let mu = mu_crit(&arch, &arch.joints(n), LAMBDA, Apex::Sliver);
        approx::assert_abs_diff_eq!(mu, closed, epsilon = SAME);
    }
    // archstudy's general route on the same model: its arch with a twin crown joint 0⁺
    // (the joint right of the load) that keeps every row.
    for joints in [Discretisation::Continuum, Discretisation::Voussoirs(20)] {
        let mu = archstudy_sliver(joints);
        approx::assert_abs_diff_eq!(mu, closed, epsilon = SAME);
        // The sliver asks more than the load on one half, which asks more than a free
        // split: every split of P lies between the last two.
        let (one_half, shared, _) = archstudy_mu(joints);
        assert!(shared.expect("a free split") < one_half && one_half < mu);
    }
}

/// archstudy's μ_c of the scene with a twin crown joint 0⁺ carrying every row.
fn archstudy_sliver(joints: Discretisation) -> f64 {
    use archstudy::analysis::forms::ArchModel;
    use archstudy::analysis::general;
    use archstudy::analysis::statics::{ArchGeometry, Joint, Resultant};
    struct Sliver(ArchModel);
    let twin = 0.0f64.next_up();
    impl ArchGeometry for Sliver {
        fn half_angle(&self) -> f64 {
            self.0.half_angle()
        }
        fn joint(&self, theta: f64) -> Joint {
            self.0.joint(theta)
        }
        fn dead_load(&self, theta: f64) -> Resultant {
            self.0.dead_load(theta)
        }
        fn live_load(&self, theta: f64) -> Resultant {
            self.0.live_load(theta)
        }
        fn discrete_joints(&self) -> Option<Vec<f64>> {
            let mut j = self.0.discrete_joints()?;
            j.push(0.0f64.next_up());
            j.sort_by(f64::total_cmp);
            Some(j)
        }
        fn families(&self) -> Vec<[f64; 2]> {
            self.0.families()
        }
        fn isolated_joints(&self) -> Vec<f64> {
            let mut j = self.0.isolated_joints();
            j.push(0.0f64.next_up());
            j
        }
        fn angle_deg(&self, theta: f64) -> f64 {
            self.0.angle_deg(theta)
        }
    }
    let s = scene_of(joints);
    let model = ArchModel::new(s.arch, s.form, s.load).expect("a valid form");
    // 0⁺ is the crown joint, with the load on its left: the right half's part from 0⁺ on.
    let (j0, j1) = (model.joint(0.0), model.joint(twin));
    assert_eq!((j0.intrados, j0.extrados), (j1.intrados, j1.extrados));
    assert_eq!(model.live_load(twin).fy, -2.0);
    assert_eq!(model.live_load(0.0).fy, 0.0);
    let settings = general::Settings {
        lambda: LAMBDA,
        ..general::Settings::default()
    };
    general::friction(&Sliver(model), &settings)
        .found()
        .expect("a limit state")
        .mu
}
