//! A dense linear programme in a few free unknowns and many rows:
//! maximise c·x subject to A x ≤ b (x ∈ ℝᴰ, D ≤ 5 in practice, up to ~10⁵ rows).
//!
//! Method: the simplex method applied to the dual, min b·y s.t. Aᵀy = c, y ≥ 0, with an
//! explicit D × D basis (refactorised at every step, which costs nothing next to the O(mD)
//! pricing pass). A basis is a set of D rows B with multipliers y_B = A_B⁻ᵀ c ≥ 0; its vertex
//! x = A_B⁻¹ b_B. Each step brings in the row that x violates most (distance to its plane)
//! and drops a basic row by the ratio test on y, so c·x = b·y never increases.
//!
//! Phase 1 is a symbolic big-M: D artificial rows s_i x_i ≤ M (s_i = sign c_i, M → ∞) form
//! the starting basis with y_i = |c_i|. Every quantity is a pair (finite part, M-part)
//! compared lexicographically, so no numerical M is ever chosen. Artificial rows left in the
//! final basis with y_i > 0 mean the programme is unbounded; with y_i = 0 they only say that
//! some direction is free. Harris' two-pass ratio test keeps pivots large; Bland's rule takes
//! over after a run of degenerate steps, so the method terminates.
//!
//! Outcomes (optimal, infeasible, unbounded, iteration limit) are [`Status`] values; `Err`
//! means malformed input only (NaN, mismatched lengths).

/// Settings of the solver; all tolerances are relative.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Largest number of simplex steps (default 10 000 + 4·rows, set by [`Settings::for_rows`]).
    pub max_iter: usize,
    /// A row is violated when its distance a·x − b over |a| exceeds
    /// `tol_feas`·(1 + |x|∞) (default 1e-13).
    pub tol_feas: f64,
    /// Smallest normalised pivot |a_B| u_k / |a_r| accepted in the ratio test (default 1e-10).
    pub tol_pivot: f64,
    /// Tolerance on the multipliers y, relative to max |c| (default 1e-12).
    pub tol_dual: f64,
    /// Consecutive degenerate steps before switching to Bland's rule (default 12).
    pub degenerate_steps_before_bland: usize,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            max_iter: 10_000,
            tol_feas: 1e-13,
            tol_pivot: 1e-10,
            tol_dual: 1e-12,
            degenerate_steps_before_bland: 12,
        }
    }
}

impl Settings {
    /// The defaults with an iteration limit scaled to `rows`.
    pub fn for_rows(rows: usize) -> Self {
        Settings {
            max_iter: 10_000 + 4 * rows,
            ..Settings::default()
        }
    }
}

/// How a solve ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Status {
    /// x is optimal within the tolerances.
    Optimal,
    /// No x satisfies all rows (a violated row is a non-positive combination of basic rows).
    Infeasible,
    /// The objective is unbounded above along [`Solution::ray`].
    Unbounded,
    /// `max_iter` steps were taken without reaching an answer.
    IterationLimit,
    /// A basis turned out singular in floating point (not expected; reported, not hidden).
    NumericalFailure,
}

impl Status {
    /// `optimal`, `infeasible`, `unbounded`, `iteration_limit` or `numerical_failure`.
    pub fn as_str(self) -> &'static str {
        match self {
            Status::Optimal => "optimal",
            Status::Infeasible => "infeasible",
            Status::Unbounded => "unbounded",
            Status::IterationLimit => "iteration_limit",
            Status::NumericalFailure => "numerical_failure",
        }
    }
}

/// Malformed input (the only `Err` of [`maximise`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LpError {
    /// `a` and `b` have different lengths.
    #[error("the programme has {rows} rows but {rhs} right-hand sides")]
    DimensionMismatch {
        /// Rows of A.
        rows: usize,
        /// Entries of b.
        rhs: usize,
    },
    /// A coefficient is NaN or infinite, or a right-hand side is NaN.
    #[error("{what} {index} is not a finite number")]
    NotFinite {
        /// `objective`, `row` or `rhs`.
        what: &'static str,
        /// Index of the offending entry (row index for rows).
        index: usize,
    },
    /// Zero unknowns.
    #[error("the programme has no unknowns")]
    NoUnknowns,
}

/// The result of [`maximise`]; every number is finite.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Solution<const D: usize> {
    /// How the solve ended.
    pub status: Status,
    /// The optimal point when `status` is optimal, else the last iterate (finite).
    pub x: [f64; D],
    /// c·x.
    pub objective: f64,
    /// The basic rows (`None` for an artificial row: a free direction).
    pub basis: [Option<usize>; D],
    /// Multipliers y ≥ 0 of the basic rows (dual solution: c = Σ y_k a_k).
    pub duals: [f64; D],
    /// When unbounded: a direction d with A d ≤ 0 and c·d > 0; zero otherwise.
    pub ray: [f64; D],
    /// Largest a·x − b over all rows at `x` (≤ 0 up to tolerance when optimal).
    pub max_violation: f64,
    /// Simplex steps taken.
    pub iterations: usize,
}

impl<const D: usize> Solution<D> {
    /// Indices of the rows with a·x − b ≥ −tol·|a| (rows active at x within a distance tol).
    pub fn active_rows(&self, a: &[[f64; D]], b: &[f64], tol: f64) -> Vec<usize> {
        a.iter()
            .zip(b)
            .enumerate()
            .filter(|(_, (row, bi))| {
                let n = norm(row);
                n > 0.0 && dot(row, &self.x) - **bi >= -tol * n
            })
            .map(|(i, _)| i)
            .collect()
    }
}

fn dot<const D: usize>(a: &[f64; D], x: &[f64; D]) -> f64 {
    let mut s = 0.0;
    for i in 0..D {
        s += a[i] * x[i];
    }
    s
}

fn norm<const D: usize>(a: &[f64; D]) -> f64 {
    dot(a, a).sqrt()
}

fn inf_norm<const D: usize>(x: &[f64; D]) -> f64 {
    x.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// LU factors with partial pivoting of a D × D matrix: P A = L U.
struct Lu<const D: usize> {
    lu: [[f64; D]; D],
    perm: [usize; D],
}

// Index loops read like the textbook triangular solves they implement.
#[allow(clippy::needless_range_loop)]
impl<const D: usize> Lu<D> {
    /// Factorises `m`; `None` when a pivot is negligible (singular to working precision).
    fn factor(mut m: [[f64; D]; D]) -> Option<Self> {
        let mut perm = [0; D];
        for (i, p) in perm.iter_mut().enumerate() {
            *p = i;
        }
        let scale = m
            .iter()
            .flat_map(|r| r.iter())
            .fold(0.0_f64, |s, v| s.max(v.abs()));
        if scale.is_nan() || scale <= 0.0 {
            return None;
        }
        for k in 0..D {
            let mut p = k;
            for i in k + 1..D {
                if m[i][k].abs() > m[p][k].abs() {
                    p = i;
                }
            }
            if m[p][k].is_nan() || m[p][k].abs() <= 1e-14 * scale {
                return None;
            }
            m.swap(k, p);
            perm.swap(k, p);
            for i in k + 1..D {
                let f = m[i][k] / m[k][k];
                m[i][k] = f;
                for j in k + 1..D {
                    m[i][j] -= f * m[k][j];
                }
            }
        }
        Some(Lu { lu: m, perm })
    }

    /// z with A z = r.
    fn solve(&self, r: &[f64; D]) -> [f64; D] {
        let mut z = [0.0; D];
        for i in 0..D {
            let mut s = r[self.perm[i]];
            for j in 0..i {
                s -= self.lu[i][j] * z[j];
            }
            z[i] = s;
        }
        for i in (0..D).rev() {
            let mut s = z[i];
            for j in i + 1..D {
                s -= self.lu[i][j] * z[j];
            }
            z[i] = s / self.lu[i][i];
        }
        z
    }

    /// z with Aᵀ z = r (Aᵀ = Uᵀ Lᵀ P).
    fn solve_t(&self, r: &[f64; D]) -> [f64; D] {
        let mut w = [0.0; D];
        for i in 0..D {
            let mut s = r[i];
            for j in 0..i {
                s -= self.lu[j][i] * w[j];
            }
            w[i] = s / self.lu[i][i];
        }
        for i in (0..D).rev() {
            let mut s = w[i];
            for j in i + 1..D {
                s -= self.lu[j][i] * w[j];
            }
            w[i] = s;
        }
        let mut z = [0.0; D];
        for i in 0..D {
            z[self.perm[i]] = w[i];
        }
        z
    }
}

/// The problem as the solver sees it: real rows 0..m, then the D artificial rows.
struct Tableau<'a, const D: usize> {
    a: &'a [[f64; D]],
    b: &'a [f64],
    /// 1/|a_r| for real rows (0 for ignored rows).
    inv_norm: Vec<f64>,
    /// Sign s_i of artificial row i: s_i x_i ≤ M.
    signs: [f64; D],
    m: usize,
    /// The real rows scaled to unit normal, a_r/|a_r|, for pricing (zero for ignored rows).
    unit: Vec<[f64; D]>,
    /// Their right-hand sides b_r/|a_r|; +∞ for ignored rows and for the rows of the current
    /// basis, so that pricing needs no test to pass over them.
    unit_b: Vec<f64>,
}

impl<const D: usize> Tableau<'_, D> {
    fn row(&self, k: usize) -> [f64; D] {
        if k < self.m {
            self.a[k]
        } else {
            let mut r = [0.0; D];
            r[k - self.m] = self.signs[k - self.m];
            r
        }
    }

    /// Right-hand side as (finite part, M-part).
    fn rhs(&self, k: usize) -> (f64, f64) {
        if k < self.m {
            (self.b[k], 0.0)
        } else {
            (0.0, 1.0)
        }
    }

    /// b_r/|a_r| of a real row (+∞ when it is ignored).
    fn unit_rhs(&self, k: usize) -> f64 {
        if self.inv_norm[k] > 0.0 {
            self.b[k] * self.inv_norm[k]
        } else {
            f64::INFINITY
        }
    }

    /// Marks a real row as basic (`true`) or not for pricing.
    fn set_basic(&mut self, k: usize, basic: bool) {
        if k < self.m {
            self.unit_b[k] = if basic {
                f64::INFINITY
            } else {
                self.unit_rhs(k)
            };
        }
    }

    fn row_norm(&self, k: usize) -> f64 {
        if k < self.m {
            if self.inv_norm[k] > 0.0 {
                1.0 / self.inv_norm[k]
            } else {
                0.0
            }
        } else {
            1.0
        }
    }
}

/// Maximises c·x subject to a[r]·x ≤ b[r] for every row r, x free.
///
/// Rows with b = +∞ are ignored; a row with b = −∞, or with a = 0 and b < 0, makes the
/// programme infeasible. Invariants: the multipliers stay non-negative, c·x never increases
/// along the iterations, every returned number is finite.
pub fn maximise<const D: usize>(
    c: &[f64; D],
    a: &[[f64; D]],
    b: &[f64],
    settings: &Settings,
) -> Result<Solution<D>, LpError> {
    if D == 0 {
        return Err(LpError::NoUnknowns);
    }
    if a.len() != b.len() {
        return Err(LpError::DimensionMismatch {
            rows: a.len(),
            rhs: b.len(),
        });
    }
    if let Some(i) = c.iter().position(|v| !v.is_finite()) {
        return Err(LpError::NotFinite {
            what: "objective",
            index: i,
        });
    }
    if let Some(i) = a.iter().position(|r| r.iter().any(|v| !v.is_finite())) {
        return Err(LpError::NotFinite {
            what: "row",
            index: i,
        });
    }
    if let Some(i) = b.iter().position(|v| v.is_nan()) {
        return Err(LpError::NotFinite {
            what: "rhs",
            index: i,
        });
    }
    let m = a.len();
    let mut signs = [1.0; D];
    for (s, ci) in signs.iter_mut().zip(c) {
        if *ci < 0.0 {
            *s = -1.0;
        }
    }
    let mut out = Solution {
        status: Status::Optimal,
        x: [0.0; D],
        objective: 0.0,
        basis: [None; D],
        duals: [0.0; D],
        ray: [0.0; D],
        max_violation: 0.0,
        iterations: 0,
    };
    let mut inv_norm = vec![0.0; m];
    for (r, (row, &bi)) in a.iter().zip(b).enumerate() {
        let n = norm(row);
        if bi == f64::INFINITY {
            continue;
        }
        if bi == f64::NEG_INFINITY || (n == 0.0 && bi < 0.0) {
            out.status = Status::Infeasible;
            out.basis[0] = Some(r);
            out.max_violation = f64::MAX;
            return Ok(out);
        }
        if n > 0.0 {
            inv_norm[r] = 1.0 / n;
        }
    }
    // Separate simple passes: each vectorises, which one pass with three pushes a row does not.
    let unit = a
        .iter()
        .zip(&inv_norm)
        .map(|(row, &inv)| row.map(|v| v * inv))
        .collect();
    let mut t = Tableau {
        a,
        b,
        inv_norm,
        signs,
        m,
        unit,
        unit_b: Vec::new(),
    };
    t.unit_b = (0..m).map(|k| t.unit_rhs(k)).collect();
    Ok(simplex(c, &mut t, settings))
}

/// The state of one basis.
struct Vertex<const D: usize> {
    /// Finite and M-parts of the vertex.
    x0: [f64; D],
    x1: [f64; D],
    /// Multipliers.
    y: [f64; D],
    lu: Lu<D>,
}

fn vertex<const D: usize>(
    c: &[f64; D],
    t: &Tableau<'_, D>,
    basis: &[usize; D],
) -> Option<Vertex<D>> {
    let mut mat = [[0.0; D]; D];
    let mut r0 = [0.0; D];
    let mut r1 = [0.0; D];
    for (i, &k) in basis.iter().enumerate() {
        mat[i] = t.row(k);
        (r0[i], r1[i]) = t.rhs(k);
    }
    let lu = Lu::factor(mat)?;
    let mut x0 = lu.solve(&r0);
    // One step of iterative refinement on the finite part.
    let mut res = [0.0; D];
    for i in 0..D {
        res[i] = r0[i] - dot(&mat[i], &x0);
    }
    let dx = lu.solve(&res);
    for i in 0..D {
        x0[i] += dx[i];
    }
    let x1 = if basis.iter().any(|&k| k >= t.m) {
        lu.solve(&r1)
    } else {
        [0.0; D]
    };
    let y = lu.solve_t(c);
    if x0.iter().chain(&x1).chain(&y).any(|v| !v.is_finite()) {
        return None;
    }
    Some(Vertex { x0, x1, y, lu })
}

/// The largest a·x − b over the rows and the first row that attains it ((−∞, usize::MAX) for
/// no rows). Four running maxima over interleaved rows keep the comparisons independent of
/// one another, so the loop is not bound by their latency; merging them by value, then by
/// index, gives the same row as one scan in order.
fn most_violated<const D: usize>(a: &[[f64; D]], b: &[f64], x: &[f64; D]) -> (f64, usize) {
    const LANES: usize = 4;
    let mut best = [(f64::NEG_INFINITY, usize::MAX); LANES];
    let n = a.len().min(b.len());
    let whole = n - n % LANES;
    for (i, (rows, bs)) in a[..whole]
        .chunks_exact(LANES)
        .zip(b[..whole].chunks_exact(LANES))
        .enumerate()
    {
        for l in 0..LANES {
            let v = dot(&rows[l], x) - bs[l];
            if v > best[l].0 {
                best[l] = (v, i * LANES + l);
            }
        }
    }
    for k in whole..n {
        let v = dot(&a[k], x) - b[k];
        let l = k % LANES;
        if v > best[l].0 {
            best[l] = (v, k);
        }
    }
    best.into_iter()
        .fold((f64::NEG_INFINITY, usize::MAX), |m, c| {
            if c.0 > m.0 || (c.0 == m.0 && c.1 < m.1) {
                c
            } else {
                m
            }
        })
}

/// The entering row chosen by pricing, or `None` when no row is violated.
struct Pricing {
    entering: Option<usize>,
    /// Largest finite-part violation a·x0 − b over rows (at M-part ≈ 0).
    max_violation: f64,
}

fn price<const D: usize>(
    t: &Tableau<'_, D>,
    v: &Vertex<D>,
    in_basis: &[bool],
    settings: &Settings,
    bland: bool,
) -> Pricing {
    let phase1 = v.x1.iter().any(|&z| z != 0.0);
    let tol0 = settings.tol_feas * (1.0 + inf_norm(&v.x0));
    let tol1 = settings.tol_feas * (1.0 + inf_norm(&v.x1));
    // Best (score, index) in the M-part and in the finite part.
    let mut best1: Option<(f64, usize)> = None;
    let mut best0: Option<(f64, usize)> = None;
    let mut max_violation = f64::NEG_INFINITY;
    if !phase1 {
        // Phase 2: the M-part of every real row is zero, so only its finite violation counts;
        // basic and ignored rows have b/|a| = +∞ and never win.
        let mut best = (f64::NEG_INFINITY, usize::MAX);
        if bland {
            for (k, (row, &bk)) in t.unit.iter().zip(&t.unit_b).enumerate() {
                let v0 = dot(row, &v.x0) - bk;
                if v0 > tol0 && best0.is_none() {
                    best0 = Some((v0, k));
                }
                best = if v0 > best.0 { (v0, k) } else { best };
            }
        } else {
            best = most_violated(&t.unit, &t.unit_b, &v.x0);
            if best.0 > tol0 {
                best0 = Some(best);
            }
        }
        max_violation = best.0;
    }
    if phase1 {
        // Real rows have no M-part in b: their M-violation is a·x1/|a|. Ignored rows (a = 0
        // here) and basic rows have b/|a| = +∞, so only a row whose M-violation is positive
        // needs the basis test.
        for (k, (row, &bk)) in t.unit.iter().zip(&t.unit_b).enumerate() {
            let v1 = dot(row, &v.x1);
            if v1 > tol1 {
                if !in_basis[k] && best1.is_none_or(|(s, _)| !bland && v1 > s) {
                    best1 = Some((v1, k));
                }
                continue;
            }
            if v1 < -tol1 {
                continue;
            }
            let v0 = dot(row, &v.x0) - bk;
            if v0 > max_violation {
                max_violation = v0;
            }
            if v0 > tol0 && best0.is_none_or(|(s, _)| !bland && v0 > s) {
                best0 = Some((v0, k));
            }
        }
    }
    let mut consider = |k: usize, row: &[f64; D], inv: f64, b0: f64, b1: f64| {
        let v1 = if phase1 {
            (dot(row, &v.x1) - b1) * inv
        } else {
            -b1 * inv
        };
        if v1 > tol1 {
            if best1.is_none_or(|(s, _)| !bland && v1 > s) {
                best1 = Some((v1, k));
            }
            return;
        }
        if v1 < -tol1 {
            return;
        }
        let v0 = (dot(row, &v.x0) - b0) * inv;
        if v0 > max_violation {
            max_violation = v0;
        }
        if v0 > tol0 && best0.is_none_or(|(s, _)| !bland && v0 > s) {
            best0 = Some((v0, k));
        }
    };
    for i in 0..D {
        let k = t.m + i;
        if in_basis[k] {
            continue;
        }
        consider(k, &t.row(k), 1.0, 0.0, 1.0);
    }
    // In Bland mode the lowest index wins; real rows come before artificial ones, and the
    // M-part dominates the finite part.
    let entering = match (best1, best0) {
        (Some((_, k)), _) => Some(k),
        (None, Some((_, k))) => Some(k),
        (None, None) => None,
    };
    Pricing {
        entering,
        max_violation: max_violation.max(0.0),
    }
}

/// The basic slot that leaves when row `r` enters (Harris two-pass, or Bland's rule).
/// `None`: no positive pivot, the programme is infeasible. Also returns the step length.
fn ratio_test<const D: usize>(
    t: &Tableau<'_, D>,
    v: &Vertex<D>,
    basis: &[usize; D],
    r: usize,
    settings: &Settings,
    ymax: f64,
    bland: bool,
) -> Option<(usize, f64)> {
    let ar = t.row(r);
    let u = v.lu.solve_t(&ar);
    let nr = t.row_norm(r);
    let tol_d = settings.tol_dual * ymax;
    let mut eligible = [false; D];
    let mut bound = f64::INFINITY;
    let mut any = false;
    for k in 0..D {
        let scaled = u[k] * t.row_norm(basis[k]) / nr;
        if scaled > settings.tol_pivot && u[k] > 0.0 {
            eligible[k] = true;
            any = true;
            bound = bound.min((v.y[k].max(0.0) + tol_d) / u[k]);
        }
    }
    if !any {
        return None;
    }
    let mut pick: Option<usize> = None;
    if bland {
        let mut min_ratio = f64::INFINITY;
        for k in 0..D {
            if eligible[k] {
                min_ratio = min_ratio.min(v.y[k].max(0.0) / u[k]);
            }
        }
        for k in 0..D {
            if eligible[k] {
                let ratio = v.y[k].max(0.0) / u[k];
                if ratio <= min_ratio + tol_d / u[k] && pick.is_none_or(|p| basis[k] < basis[p]) {
                    pick = Some(k);
                }
            }
        }
    } else {
        let mut best = 0.0;
        for k in 0..D {
            if eligible[k] {
                let ratio = v.y[k].max(0.0) / u[k];
                let scaled = u[k] * t.row_norm(basis[k]);
                if ratio <= bound && scaled > best {
                    best = scaled;
                    pick = Some(k);
                }
            }
        }
    }
    pick.map(|k| (k, v.y[k].max(0.0) / u[k]))
}

fn simplex<const D: usize>(
    c: &[f64; D],
    t: &mut Tableau<'_, D>,
    settings: &Settings,
) -> Solution<D> {
    let m = t.m;
    let mut basis = [0usize; D];
    for (i, k) in basis.iter_mut().enumerate() {
        *k = m + i;
    }
    let mut in_basis = vec![false; m + D];
    for &k in &basis {
        in_basis[k] = true;
    }
    let ymax = c.iter().fold(0.0_f64, |s, v| s.max(v.abs())).max(1e-300);
    let mut degenerate_run = 0;
    let mut last: Option<Vertex<D>> = None;
    let finish = |status: Status,
                  basis: &[usize; D],
                  v: Option<&Vertex<D>>,
                  iterations: usize,
                  max_violation: f64| {
        let mut s = Solution {
            status,
            x: [0.0; D],
            objective: 0.0,
            basis: [None; D],
            duals: [0.0; D],
            ray: [0.0; D],
            max_violation,
            iterations,
        };
        for (slot, &k) in s.basis.iter_mut().zip(basis) {
            *slot = (k < m).then_some(k);
        }
        if let Some(v) = v {
            s.x = v.x0;
            s.duals = v.y.map(|y| y.max(0.0));
            s.objective = dot(c, &v.x0);
        }
        s
    };
    for iter in 0..settings.max_iter {
        let Some(v) = vertex(c, t, &basis) else {
            return finish(Status::NumericalFailure, &basis, last.as_ref(), iter, 0.0);
        };
        let bland = degenerate_run >= settings.degenerate_steps_before_bland;
        let p = price(t, &v, &in_basis, settings, bland);
        let Some(r) = p.entering else {
            return optimal(c, t, &basis, &v, iter, p.max_violation, settings, ymax);
        };
        let Some((slot, step)) = ratio_test(t, &v, &basis, r, settings, ymax, bland) else {
            return finish(Status::Infeasible, &basis, Some(&v), iter, p.max_violation);
        };
        if step * ymax.recip() <= settings.tol_dual {
            degenerate_run += 1;
        } else {
            degenerate_run = 0;
        }
        in_basis[basis[slot]] = false;
        t.set_basic(basis[slot], false);
        basis[slot] = r;
        in_basis[r] = true;
        t.set_basic(r, true);
        last = Some(v);
    }
    finish(
        Status::IterationLimit,
        &basis,
        last.as_ref(),
        settings.max_iter,
        0.0,
    )
}

/// The answer at a basis that no row violates: optimal, or unbounded when an artificial
/// row carries a positive multiplier.
#[allow(clippy::too_many_arguments)]
fn optimal<const D: usize>(
    c: &[f64; D],
    t: &Tableau<'_, D>,
    basis: &[usize; D],
    v: &Vertex<D>,
    iterations: usize,
    max_violation: f64,
    settings: &Settings,
    ymax: f64,
) -> Solution<D> {
    let m = t.m;
    let mut s = Solution {
        status: Status::Optimal,
        x: v.x0,
        objective: 0.0,
        basis: [None; D],
        duals: v.y.map(|y| y.max(0.0)),
        ray: [0.0; D],
        max_violation,
        iterations,
    };
    for (slot, &k) in s.basis.iter_mut().zip(basis) {
        *slot = (k < m).then_some(k);
    }
    let unbounded = basis
        .iter()
        .zip(&v.y)
        .any(|(&k, &y)| k >= m && y > settings.tol_dual * ymax);
    if unbounded {
        s.status = Status::Unbounded;
        s.ray = v.x1;
        s.objective = dot(c, &v.x0);
        return s;
    }
    if v.x1.iter().any(|&z| z != 0.0) {
        // A free direction remains: move along it just far enough to satisfy the rows that
        // are satisfied only for large M (their M-part is negative).
        let tol1 = settings.tol_feas * (1.0 + inf_norm(&v.x1));
        let mut big_m: f64 = 0.0;
        for k in 0..m {
            let inv = t.inv_norm[k];
            if inv == 0.0 {
                continue;
            }
            let v1 = dot(&t.a[k], &v.x1) * inv;
            if v1 < -tol1 {
                let v0 = (dot(&t.a[k], &v.x0) - t.b[k]) * inv;
                if v0 > 0.0 {
                    big_m = big_m.max(v0 / -v1);
                }
            }
        }
        if big_m > 0.0 && big_m.is_finite() {
            for i in 0..D {
                s.x[i] += big_m * v.x1[i];
            }
            s.max_violation =
                t.a.iter()
                    .zip(t.b)
                    .zip(&t.inv_norm)
                    .filter(|(_, inv)| **inv > 0.0)
                    .map(|((row, bi), _)| dot(row, &s.x) - bi)
                    .fold(0.0, f64::max);
        }
    }
    s.objective = dot(c, &s.x);
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn solve<const D: usize>(c: [f64; D], a: &[[f64; D]], b: &[f64]) -> Solution<D> {
        maximise(&c, a, b, &Settings::default()).unwrap()
    }

    proptest::proptest! {
        #[test]
        fn most_violated_is_the_first_largest_of_one_scan(
            rows in proptest::collection::vec(
                (proptest::array::uniform3(-3i32..3), -2i32..2, proptest::bool::ANY),
                0..23,
            ),
            x in proptest::array::uniform3(-2i32..2),
        ) {
            // Small integers make ties common; masked rows (b = +∞) never win.
            let a: Vec<[f64; 3]> = rows.iter().map(|r| r.0.map(f64::from)).collect();
            let b: Vec<f64> = rows
                .iter()
                .map(|r| if r.2 { f64::INFINITY } else { f64::from(r.1) })
                .collect();
            let x = x.map(f64::from);
            let mut want = (f64::NEG_INFINITY, usize::MAX);
            for (k, (row, bk)) in a.iter().zip(&b).enumerate() {
                let v = dot(row, &x) - bk;
                if v > want.0 {
                    want = (v, k);
                }
            }
            proptest::prop_assert_eq!(most_violated(&a, &b, &x), want);
        }
    }

    #[test]
    fn square_corner() {
        // max x + y, x ≤ 1, y ≤ 2, x + y ≥ −5.
        let s = solve(
            [1.0, 1.0],
            &[[1.0, 0.0], [0.0, 1.0], [-1.0, -1.0]],
            &[1.0, 2.0, 5.0],
        );
        assert_eq!(s.status, Status::Optimal);
        assert!((s.x[0] - 1.0).abs() < 1e-15 && (s.x[1] - 2.0).abs() < 1e-15);
        assert!((s.objective - 3.0).abs() < 1e-15);
        let mut basis: Vec<_> = s.basis.iter().flatten().copied().collect();
        basis.sort();
        assert_eq!(basis, vec![0, 1]);
        assert!((s.duals[0] - 1.0).abs() < 1e-15 && (s.duals[1] - 1.0).abs() < 1e-15);
    }

    #[test]
    fn textbook_three_unknowns() {
        // max 3x + 2y + 4z  s.t.  x + y + 2z ≤ 4, 2x + 3z ≤ 5, 2x + y + 3z ≤ 7, x, y, z ≥ 0.
        // Optimum: x = 2.5, y = 1.5, z = 0, value 10.5.
        let a = [
            [1.0, 1.0, 2.0],
            [2.0, 0.0, 3.0],
            [2.0, 1.0, 3.0],
            [-1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, -1.0],
        ];
        let b = [4.0, 5.0, 7.0, 0.0, 0.0, 0.0];
        let s = solve([3.0, 2.0, 4.0], &a, &b);
        assert_eq!(s.status, Status::Optimal);
        assert!((s.objective - 10.5).abs() < 1e-13, "{s:?}");
        assert!((s.x[0] - 2.5).abs() < 1e-13 && (s.x[1] - 1.5).abs() < 1e-13);
        assert!(s.x[2].abs() < 1e-13);
    }

    #[test]
    fn infeasible_strip() {
        // x ≤ 1 and x ≥ 2.
        let s = solve([1.0, 0.0], &[[1.0, 0.0], [-1.0, 0.0]], &[1.0, -2.0]);
        assert_eq!(s.status, Status::Infeasible);
        assert!(s.x.iter().all(|v| v.is_finite()));
    }

    #[test]
    fn unbounded_with_a_ray() {
        // max x s.t. x − 2y ≤ 0, −y ≤ 0: unbounded along (2, 1).
        let s = solve([1.0, 0.0], &[[1.0, -2.0], [0.0, -1.0]], &[0.0, 0.0]);
        assert_eq!(s.status, Status::Unbounded);
        assert!(s.ray[0] > 0.0);
        assert!(s.ray[0] - 2.0 * s.ray[1] <= 1e-15 && -s.ray[1] <= 1e-15);
    }

    #[test]
    fn free_direction_is_not_unbounded() {
        // max x s.t. x ≤ 3 and a zero row: y and z appear nowhere and stay free.
        let s = solve(
            [1.0, 0.0, 0.0],
            &[[1.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
            &[3.0, 1.0],
        );
        assert_eq!(s.status, Status::Optimal);
        assert!((s.objective - 3.0).abs() < 1e-15);
        assert_eq!(s.basis.iter().flatten().count(), 1);
    }

    #[test]
    fn free_direction_needing_a_shift() {
        // max x s.t. x ≤ 1, x − y ≤ −5: y is free but must reach x + 5.
        let s = solve([1.0, 0.0], &[[1.0, 0.0], [1.0, -1.0]], &[1.0, -5.0]);
        assert_eq!(s.status, Status::Optimal);
        assert!((s.x[0] - 1.0).abs() < 1e-15);
        assert!(s.x[0] - s.x[1] <= -5.0 + 1e-12, "{s:?}");
        assert!(s.max_violation <= 1e-12);
    }

    #[test]
    fn zero_objective_is_a_feasibility_problem() {
        let s = solve(
            [0.0, 0.0],
            &[[1.0, 1.0], [-1.0, 0.0], [0.0, -1.0]],
            &[1.0, -0.2, -0.3],
        );
        assert_eq!(s.status, Status::Optimal);
        assert!(s.max_violation <= 1e-15);
        let s = solve(
            [0.0, 0.0],
            &[[1.0, 1.0], [-1.0, 0.0], [0.0, -1.0]],
            &[1.0, -0.6, -0.6],
        );
        assert_eq!(s.status, Status::Infeasible);
    }

    #[test]
    fn zero_rows_and_infinite_rhs() {
        let a = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [5.0, 5.0]];
        let s = solve([1.0, 1.0], &a, &[0.0, 1.0, 1.0, f64::INFINITY]);
        assert_eq!(s.status, Status::Optimal);
        assert!((s.objective - 2.0).abs() < 1e-15);
        let s = solve([1.0, 1.0], &a, &[-1e-300, 1.0, 1.0, 3.0]);
        assert_eq!(s.status, Status::Infeasible);
        let s = solve([1.0, 1.0], &a, &[0.0, 1.0, 1.0, f64::NEG_INFINITY]);
        assert_eq!(s.status, Status::Infeasible);
    }

    #[test]
    fn bad_input_is_an_error_not_a_panic() {
        let s = maximise(&[1.0], &[[f64::NAN]], &[1.0], &Settings::default());
        assert!(matches!(s, Err(LpError::NotFinite { what: "row", .. })));
        let s = maximise(&[1.0], &[[1.0]], &[f64::NAN], &Settings::default());
        assert!(matches!(s, Err(LpError::NotFinite { what: "rhs", .. })));
        let s = maximise(&[1.0], &[[1.0]], &[], &Settings::default());
        assert!(matches!(s, Err(LpError::DimensionMismatch { .. })));
        let s = maximise::<0>(&[], &[], &[], &Settings::default());
        assert!(matches!(s, Err(LpError::NoUnknowns)));
    }

    #[test]
    fn no_rows() {
        let s = solve([0.0, 0.0], &[], &[]);
        assert_eq!(s.status, Status::Optimal);
        let s = solve([0.0, -1.0], &[], &[]);
        assert_eq!(s.status, Status::Unbounded);
    }

    #[test]
    fn heavily_degenerate_polygon() {
        // max y over the regular 2000-gon inscribed in the unit circle, each edge repeated
        // three times and a thousand rows through the top vertex: the optimum is 1.
        let n = 2000;
        let mut a = Vec::new();
        let mut b = Vec::new();
        for i in 0..n {
            let t = 2.0 * std::f64::consts::PI * (i as f64 + 0.5) / n as f64;
            let h = (std::f64::consts::PI / n as f64).cos();
            for _ in 0..3 {
                a.push([t.cos(), t.sin()]);
                b.push(h);
            }
        }
        // Rows through (0, 1) after a rotation by π/2 … the top vertex is at angle π/2 only
        // for n ≡ 0 mod 4; add rows touching the optimum of the polygon instead.
        let s0 = solve([0.0, 1.0], &a, &b);
        assert_eq!(s0.status, Status::Optimal);
        for j in 0..1000 {
            let t = 0.2 + 0.6 * std::f64::consts::PI * j as f64 / 1000.0;
            let (st, ct) = t.sin_cos();
            a.push([ct, st]);
            b.push(ct * s0.x[0] + st * s0.x[1]);
        }
        let s = solve([0.0, 1.0], &a, &b);
        assert_eq!(s.status, Status::Optimal);
        assert!(
            (s.objective - s0.objective).abs() < 1e-13,
            "{s:?} vs {s0:?}"
        );
        assert!((s0.objective - 1.0).abs() < 1e-5);
    }

    #[test]
    fn parallel_and_duplicate_rows() {
        // max x + y + z over the unit cube given by duplicated and scaled faces.
        let mut a = Vec::new();
        let mut b = Vec::new();
        for s in [1.0, 2.0, 1e-3, 1e3] {
            for i in 0..3 {
                let mut r = [0.0; 3];
                r[i] = s;
                a.push(r);
                b.push(s);
                r[i] = -s;
                a.push(r);
                b.push(0.0);
            }
        }
        let s = solve([1.0, 1.0, 1.0], &a, &b);
        assert_eq!(s.status, Status::Optimal);
        assert!((s.objective - 3.0).abs() < 1e-14);
    }

    #[test]
    fn cycling_example_of_beale() {
        // Beale's classic cycling LP (as a maximisation with x ≥ 0):
        // max 0.75x4 − 20x5 + 0.5x6 − 6x7 s.t.
        // 0.25x4 − 8x5 − x6 + 9x7 ≤ 0, 0.5x4 − 12x5 − 0.5x6 + 3x7 ≤ 0, x6 ≤ 1. Value 1.25.
        let mut a = vec![
            [0.25, -8.0, -1.0, 9.0],
            [0.5, -12.0, -0.5, 3.0],
            [0.0, 0.0, 1.0, 0.0],
        ];
        let mut b = vec![0.0, 0.0, 1.0];
        for i in 0..4 {
            let mut r = [0.0; 4];
            r[i] = -1.0;
            a.push(r);
            b.push(0.0);
        }
        let s = solve([0.75, -20.0, 0.5, -6.0], &a, &b);
        assert_eq!(s.status, Status::Optimal);
        assert!((s.objective - 1.25).abs() < 1e-13, "{s:?}");
    }

    #[test]
    fn random_programmes_match_vertex_enumeration() {
        // Small random LPs in 2 unknowns inside a box: brute force over all row pairs.
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64) / ((1u64 << 53) as f64) * 2.0 - 1.0
        };
        for _ in 0..200 {
            let mut a = vec![[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0]];
            let mut b = vec![3.0, 3.0, 3.0, 3.0];
            for _ in 0..8 {
                a.push([rnd(), rnd()]);
                b.push(rnd());
            }
            let c = [rnd(), rnd()];
            let s = solve(c, &a, &b);
            let always_bland = Settings {
                degenerate_steps_before_bland: 0,
                ..Settings::default()
            };
            let s_bland = maximise(&c, &a, &b, &always_bland).unwrap();
            assert_eq!(s.status, s_bland.status);
            if s.status == Status::Optimal {
                assert!((s.objective - s_bland.objective).abs() < 1e-12);
            }
            let mut best = f64::NEG_INFINITY;
            for i in 0..a.len() {
                for j in i + 1..a.len() {
                    let det = a[i][0] * a[j][1] - a[i][1] * a[j][0];
                    if det.abs() < 1e-12 {
                        continue;
                    }
                    let x = [
                        (b[i] * a[j][1] - a[i][1] * b[j]) / det,
                        (a[i][0] * b[j] - b[i] * a[j][0]) / det,
                    ];
                    if a.iter().zip(&b).all(|(r, bi)| dot(r, &x) <= bi + 1e-12) {
                        best = best.max(dot(&c, &x));
                    }
                }
            }
            if best.is_finite() {
                assert_eq!(s.status, Status::Optimal);
                assert!(
                    (s.objective - best).abs() < 1e-10,
                    "{} vs {best}",
                    s.objective
                );
            } else {
                assert_eq!(s.status, Status::Infeasible);
            }
        }
    }

    #[test]
    fn random_four_unknown_programmes_match_clarabel() {
        use clarabel::algebra::CscMatrix;
        use clarabel::solver::{
            DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus,
        };
        let mut seed = 987654321u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64) / ((1u64 << 53) as f64) * 2.0 - 1.0
        };
        for _ in 0..40 {
            // A bounded polytope: random rows with positive right-hand sides around the origin
            // plus a loose box, and rows duplicated to make the optimum degenerate.
            let mut a = Vec::new();
            let mut b = Vec::new();
            for i in 0..4 {
                for s in [1.0, -1.0] {
                    let mut r = [0.0; 4];
                    r[i] = s;
                    a.push(r);
                    b.push(10.0);
                }
            }
            for _ in 0..60 {
                let r = [rnd(), rnd(), rnd(), rnd()];
                let bi = 0.1 + rnd().abs();
                a.push(r);
                b.push(bi);
                a.push(r.map(|v| 3.0 * v));
                b.push(3.0 * bi);
            }
            let c = [rnd(), rnd(), rnd(), rnd()];
            let ours = solve(c, &a, &b);
            assert_eq!(ours.status, Status::Optimal);
            assert!(ours.max_violation <= 1e-12);
            let p = CscMatrix::<f64>::zeros((4, 4));
            let q = c.map(|v| -v);
            let am = CscMatrix::from(a.iter());
            let cones = [NonnegativeConeT(b.len())];
            let settings = DefaultSettingsBuilder::default()
                .verbose(false)
                .build()
                .unwrap();
            let mut solver = DefaultSolver::new(&p, &q, &am, &b, &cones, settings).unwrap();
            solver.solve();
            assert_eq!(solver.solution.status, SolverStatus::Solved);
            let theirs = dot(&c, &[0, 1, 2, 3].map(|i| solver.solution.x[i]));
            assert!(
                (ours.objective - theirs).abs() < 1e-6 * (1.0 + theirs.abs()),
                "{} vs {theirs}",
                ours.objective
            );
        }
    }
}
